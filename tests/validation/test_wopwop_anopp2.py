"""``nps wopwop run`` on the 44 ANOPP2 compact F1A cases written as PSU-WOPWOP cases.

Reference: NASA ANOPP2's output in tests/data/anopp2_compact_f1a (OpenMDAO/AcousticAnalogies.jl @ 8638416), the
cases of tests/validation/test_acoustics_anopp2.py: B = 2 CROTOR propeller, 200–2200 rpm, hub translating at 5 m/s
along the rotation axis, observer 30.48 m away in the rotor plane or 45° below, at rest or moving with the hub.

Each case as a PSU-WOPWOP case (:mod:`wopwop_cases`): an outer container translating at VH = (0, 0, 5) m/s
(KnownFunction), the rotor container turning at Omega about z (KnownFunction), two blade containers (turned by 0
and π) sharing one constant geometry file and one constant loading file, dTau = T/256. The blade frame has the span
along +y and the direction of motion along −x (blade 0 at [−r sin φ, r cos φ] with φ = Ωt, as ANOPP2). Three
compact zones (structured, iMax = 1, one node per blade element, node normals (0, 0, dr)):

* the lifting line at the element, loading vectors (Tp, 0, Np) = the force on the blade per unit span (patch
  frame), reported as loading;
* the two dual-compact thickness lines of nps.noise.sources at chord offsets d (toward the leading edge), carrying
  the force on the fluid ±ρ0 (A/D)(v·e_c) v per unit span, D = 0.74 c, v = (−Ω r, −Ω d, V) their velocity relative
  to the air in the blade frame (constant: the motion is steady), e_c = −x; written as the force on the blade,
  format 1.1 with loadingOutput = 1 so that their noise is reported as thickness. Two layouts, as in
  test_acoustics_anopp2.py: "dual" (NPS's: lines at 13 % and 87 % chord, the element at 25 %) and "dual_centred"
  (the pair centred on the element, where ANOPP2's monopole sits).

Every zone id is negative (compact zones radiate no thickness of their own). The stationary observers take the
runner's direct path, the observers moving with the hub its periodic path.

Criteria, those of test_acoustics_anopp2.py and docs/validation/anopp2_compact_f1a.md, over the ANOPP2 window (its
512 observer times are the case's observer grid): loading max |error| < 1 % of the ANOPP2 peak-to-peak (4.5 % for
the windmilling 200 rpm −45° cases); thickness (against ANOPP2's compact monopole) "dual" pointwise < 9 % and
peak-to-peak within 3 %, "dual_centred" pointwise < 1 % (2.5 % at 200 rpm). Measured over the 44 cases: loading
≤ 0.16 %, 200 rpm −45° 3.71 % stationary and 4.39 % moving; "dual" 4.69–8.11 % pointwise, peak-to-peak ratio
0.9936–1.0255; "dual_centred" ≤ 0.98 %, 200 rpm 2.44 % — NPS's own numbers (docs/validation/anopp2_compact_f1a.md:
loading ≤ 0.2 %, 3.7 % / 4.4 %; 4.7–8.1 %; ≤ 0.98 %, 2.4 %): the runner matches NPS's long-table path
(``nps.noise.sources.radiate``) on the same lines to ≤ 3.3e-6 of the peak-to-peak (float32 files).
"""

import numpy as np
import pytest

import wopwop_cases as wc
from test_acoustics_anopp2 import B, C0, CASES, R_OBS, RHO0, V_HUB, _run as long_table_run

STEPS_PER_REV = 256
PAIR_CENTRE = {"dual": 0.25 - 0.5, "dual_centred": 0.0}  # the pair's centre from the element, chords toward the LE
HALF_SEPARATION, SEPARATION = 0.37, 0.74                 # chord fractions 0.13 / 0.87
LINE_OUTPUT = [2, 1, 1]                                  # lifting line: loading; thickness lines: thickness
FAST_CENTRED = [(1, False, False), (6, False, False), (11, False, False), (1, True, False), (2, True, False)]


def reference(data_dir, nn: int, below: bool, moving: bool) -> np.ndarray:
    """ANOPP2's (observer time s, thickness Pa, loading Pa) rows of one case."""
    name = f"anopp2_{'const_vel_' if moving else ''}omega{nn:02d}{'_theta-45' if below else ''}.csv"
    return np.loadtxt(data_dir / "anopp2_compact_f1a" / name, delimiter=",", comments="#")


def blade_lines(data_dir, nn: int, layout: str):
    """(zones, loads (force on the blade per unit span, blade frame), Omega rad/s) of one blade (module doc)."""
    r, dr, chord, _, area, normal, tangential = np.loadtxt(
        data_dir / f"anopp2_compact_f1a/ccblade_loads_omega{nn:02d}.csv", delimiter=",", comments="#").T
    omega = 200 * nn * 2 * np.pi / 60

    def nodes(offset):  # chord offset toward the leading edge (−x in the blade frame)
        return np.stack([-offset, r, np.zeros_like(r)], axis=-1)

    zones = [wc.compact_line("lifting_line", nodes(0.0 * r), dr)]
    loads = [np.stack([tangential, np.zeros_like(r), normal], axis=-1)]
    for name, sign in (("thickness_front", 1.0), ("thickness_rear", -1.0)):
        offset = (PAIR_CENTRE[layout] + sign * HALF_SEPARATION) * chord
        velocity = np.stack([-omega * r, -omega * offset, np.full_like(r, V_HUB)], axis=-1)
        strength = sign * RHO0 * area / (SEPARATION * chord) * (omega * r)  # ρ0 (A/D)(v·e_c), v·e_c = Ω r
        zones.append(wc.compact_line(name, nodes(offset), dr))
        loads.append(-strength[:, None] * velocity)
    return zones, loads, omega


def run_anopp2_case(directory, data_dir, nn: int, below: bool, moving: bool, layout: str):
    """(runner pressure (thickness, loading) (2, nt) Pa, ANOPP2 rows) of one case on ANOPP2's observer times."""
    ref = reference(data_dir, nn, below, moving)
    zones, loads, omega = blade_lines(data_dir, nn, layout)
    theta = np.radians(-45.0 if below else 0.0)
    t = ref[:, 0]
    observers = [wc.observer_groups("observer", [R_OBS * np.cos(theta), 0.0, R_OBS * np.sin(theta)], t[0], t[-1],
                                    t.size, (0.0, 0.0, V_HUB) if moving else None)]
    sources = wc.rotor_groups(omega, B, 2 * np.pi / omega / STEPS_PER_REV, "blade.dat", "loads.dat", (0.0, 0.0, V_HUB))
    case = wc.write_case(directory, observers, sources, C0, RHO0,
                         {"blade.dat": wc.geometry_file(zones), "loads.dat": wc.loading_file(zones, loads, LINE_OUTPUT)})
    (result,) = wc.run(case)
    assert np.allclose(result.observers.grid.times_s, t, rtol=0.0, atol=1e-9 * t[-1])
    assert {m.split()[0] for m in result.modes.values()} == {"periodic" if moving else "direct"}
    return result.pressure_pa["rotor"][0], ref


def errors(p: np.ndarray, ref: np.ndarray) -> dict[str, float]:
    """Max |runner − ANOPP2| / ANOPP2 peak-to-peak per group, and the thickness peak-to-peak ratio."""
    out = {g: np.abs(p[k] - ref[:, k + 1]).max() / np.ptp(ref[:, k + 1]) for k, g in enumerate(("thickness", "loading"))}
    out["p2p_ratio"] = np.ptp(p[0]) / np.ptp(ref[:, 1])
    return out


def label(nn, below, moving, layout) -> str:
    return f"{200 * nn} rpm {'-45' if below else '0'} deg {'moving' if moving else 'fixed'} {layout}"


@pytest.mark.parametrize("nn,below,moving", CASES)
def test_anopp2_case_as_wopwop(tmp_path, data_dir, nn, below, moving):
    """Loading within 1 % of peak-to-peak (4.5 % at 200 rpm −45°); thickness with NPS's own line layout within 9 %
    pointwise (the c/(4U) time shift of lines centred a quarter chord behind the monopole) and 3 % in
    peak-to-peak. Catches a wrong loading sign or frame (patch frame, force on the blade), span length (|n| = dr),
    blade turn or rotation sense, a loadingOutput = 1 zone reported as loading, a wrong translation of the outer
    container, moving observer or source-time span."""
    p, ref = run_anopp2_case(tmp_path, data_dir, nn, below, moving, "dual")
    err = errors(p, ref)
    print(f"{label(nn, below, moving, 'dual')}: thickness {err['thickness']:.4f}, p2p ratio {err['p2p_ratio']:.4f}, "
          f"loading {err['loading']:.5f}")
    assert err["loading"] < (0.045 if (nn == 1 and below) else 0.01)
    assert err["thickness"] < 0.09 and abs(err["p2p_ratio"] - 1) < 0.03


def check_centred(tmp_path, data_dir, cases):
    """The pair centred on the element on ``cases``: thickness within 1 % of peak-to-peak pointwise (2.5 % at
    200 rpm, where the flight speed is 0.2 of the tip speed), 3 % in peak-to-peak."""
    worst = 0.0
    for nn, below, moving in cases:
        p, ref = run_anopp2_case(tmp_path / label(nn, below, moving, "c").replace(" ", "_"), data_dir, nn, below,
                                 moving, "dual_centred")
        err = errors(p, ref)
        print(f"{label(nn, below, moving, 'dual_centred')}: thickness {err['thickness']:.4f}, "
              f"p2p ratio {err['p2p_ratio']:.4f}")
        worst = max(worst, err["thickness"])
        assert err["thickness"] < (0.025 if nn == 1 else 0.01) and abs(err["p2p_ratio"] - 1) < 0.03
    print(f"dual_centred, worst of {len(cases)} cases: {worst:.4f}")


def test_anopp2_centred_pair_as_wopwop(tmp_path, data_dir):
    """Fast subset: 200, 1200, 2200 rpm in plane, 200 and 400 rpm −45° (the largest gaps: 2.44 %, 0.98 %), fixed
    observer. The 1 % criterion is sharper than the 9 % of NPS's layout: it catches a force-law or line-velocity
    error of a few per cent (v without the hub's axial speed: 3.0 % at 200 rpm −45°, 1.5 % at 400 rpm −45°, tried;
    D taken as the chord: 26 %)."""
    check_centred(tmp_path, data_dir, FAST_CENTRED)


@pytest.mark.slow
def test_anopp2_centred_pair_as_wopwop_all_cases(tmp_path, data_dir):
    """All 44 cases (≈ 15 s), criteria of :func:`check_centred`."""
    check_centred(tmp_path, data_dir, CASES)


@pytest.mark.parametrize("layout", sorted(PAIR_CENTRE))
@pytest.mark.parametrize("nn,below,moving", [(1, True, False), (11, False, False), (6, True, True), (11, False, True)])
def test_runner_matches_nps_long_table(tmp_path, data_dir, nn, below, moving, layout):
    """The same lines through NPS's long-table path (``nps.noise.sources.radiate`` on the numpy source table of
    test_acoustics_anopp2.py, analytic velocities, 6th-order differences): thickness and loading within 1e-5 of the
    ANOPP2 peak-to-peak (measured ≤ 3.3e-6: the float32 files). Catches what the ANOPP2 tolerances hide: a time
    shift, a lost or doubled term of a few 0.1 %, a wrong source-time span on the direct path."""
    p, ref = run_anopp2_case(tmp_path, data_dir, nn, below, moving, layout)
    _, nps, _ = long_table_run(data_dir, nn, below, moving, layout)
    gap = [np.abs(p[k] - nps[g]).max() / np.ptp(ref[:, k + 1]) for k, g in enumerate(("thickness", "loading"))]
    print(f"{label(nn, below, moving, layout)}: |runner - long table| / p2p thickness {gap[0]:.2e}, loading {gap[1]:.2e}")
    assert max(gap) < 1e-5
