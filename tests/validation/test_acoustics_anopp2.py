"""Compact F1A against NASA ANOPP2 (code-to-code), all 44 cases.

Reference: tests/data/anopp2_compact_f1a (OpenMDAO/AcousticAnalogies.jl @ 8638416, ANOPP2 output).
Case: B = 2 CROTOR propeller, 200–2200 rpm, hub translating at 5 m/s along the rotation axis,
observer 30.48 m away in the rotor plane or 45° below, stationary or translating with the hub.
Sources go through the public long-table API (``nps.noise.acoustics.radiate``, the CLI's function) with
analytic velocities; accelerations, jerks and force rates come from its 6th-order differences.
Criterion (the source project's): max |error| over the ANOPP2 window (≈ four blade passages) below
1 % of the ANOPP2 peak-to-peak, for the loading (dipole) and the compact-monopole thickness. The
windmilling 200 rpm, −45° cases need 4.5 % for the loading (the source project's own allowance;
an independent re-implementation reaches 3.7 % / 4.4 % there too). The dual-compact thickness
(two lines at 13 %/87 % chord, ±ρ0 (A/D)(v·e_c) v dr, A = the element area, D = 0.74 c) is
compared with ANOPP2's compact monopole on all 44 cases.
"""

import numpy as np
import pandas as pd
import pytest

from nps.noise.sources import radiate

STEPS_PER_REV = 256
REVOLUTIONS = 3
B, V_HUB, C0, RHO0, R_OBS = 2, 5.0, 340.0, 1.226, 30.48


def _sources(data_dir, nn, thickness):
    r, dr, chord, _, area, np_, tp = np.loadtxt(data_dir / f"anopp2_compact_f1a/ccblade_loads_omega{nn:02d}.csv", delimiter=",", comments="#").T
    omega = 200 * nn * 2 * np.pi / 60
    # start an eighth of a revolution early so the dual-compact lines ahead of the loading line cover the window
    tau = (np.arange(REVOLUTIONS * STEPS_PER_REV) - STEPS_PER_REV // 8) * 2 * np.pi / omega / STEPS_PER_REV
    frames, node = [], 0
    for k in range(B):
        phi = 2 * np.pi * k / B + omega * tau
        for e in range(r.size):
            # dual compact, lines along the in-plane motion direction e_c = (−cos φ, −sin φ, 0). "dual": lines at 13 %/87 % chord with the element (ANOPP2's monopole) at the quarter chord, as
            # nps.noise.sources places them; "dual_centred": the same pair centred on the element
            lines = [(0.0, 1.0, "loading")]
            if thickness.startswith("dual"):
                centre = 0.0 if thickness == "dual_centred" else (0.25 - 0.5) * chord[e]
                lines += [(centre + 0.37 * chord[e], 1.0, "thickness"), (centre - 0.37 * chord[e], -1.0, "thickness")]
            for offset, sign, group in lines:
                x = -r[e] * np.sin(phi) - offset * np.cos(phi)
                y = r[e] * np.cos(phi) - offset * np.sin(phi)
                vel = (-omega * y, omega * x, np.full_like(tau, V_HUB))
                frame = {
                    "node": node, "group": group, "time_s": tau, "x_m": x, "y_m": y, "z_m": V_HUB * tau,
                    "vx_mps": vel[0], "vy_mps": vel[1], "vz_mps": vel[2],
                }
                if group == "loading":
                    frame.update(fx_N=-tp[e] * np.cos(phi) * dr[e], fy_N=-tp[e] * np.sin(phi) * dr[e], fz_N=np.full_like(tau, -np_[e] * dr[e]))
                    if thickness == "monopole":
                        frame["volume_m3"] = np.full_like(tau, area[e] * dr[e])
                    else:
                        frame["volume_m3"] = np.zeros_like(tau)
                else:
                    # force on the fluid ±ρ0 (A/D)(v·e_c) v dr (nps.noise.sources, docs/reference/acoustics.md)
                    strength = sign * RHO0 * area[e] / ((0.87 - 0.13) * chord[e]) * dr[e] * (-vel[0] * np.cos(phi) - vel[1] * np.sin(phi))
                    frame.update(fx_N=strength * vel[0], fy_N=strength * vel[1], fz_N=strength * vel[2], volume_m3=np.zeros_like(tau))
                frames.append(pd.DataFrame(frame))
                node += 1
    return pd.concat(frames, ignore_index=True)


def _run(data_dir, nn, below, moving, thickness):
    name = f"anopp2_{'const_vel_' if moving else ''}omega{nn:02d}{'_theta-45' if below else ''}.csv"
    ref = np.loadtxt(data_dir / "anopp2_compact_f1a" / name, delimiter=",", comments="#")
    theta = np.radians(-45.0 if below else 0.0)
    observers = pd.DataFrame({"observer": [0], "x_m": [R_OBS * np.cos(theta)], "y_m": [0.0], "z_m": [R_OBS * np.sin(theta)],
                              "vx_mps": [0.0], "vy_mps": [0.0], "vz_mps": [V_HUB if moving else 0.0]})
    t = ref[:, 0]
    out = radiate(_sources(data_dir, nn, thickness), observers, t[0], (t[1] - t[0]) * t.size, t.size, c0_mps=C0, rho0_kg_m3=RHO0)
    assert np.allclose(out[out.group == "total"].time_s.to_numpy(), t, rtol=0, atol=1e-12)
    p = {g: out[out.group == g].p_Pa.to_numpy() for g in ("thickness", "loading")}
    err = {g: np.abs(p[g] - ref[:, col]).max() / np.ptp(ref[:, col]) for g, col in (("thickness", 1), ("loading", 2))}
    return err, p, ref


CASES = [(nn, below, moving) for moving in (False, True) for below in (False, True) for nn in range(1, 12)]


@pytest.mark.parametrize("nn,below,moving", CASES)
def test_anopp2_compact_monopole_and_loading(data_dir, nn, below, moving):
    """Thickness (compact monopole) and loading within 1 % of peak-to-peak (4.5 % loading at 200 rpm, −45°)."""
    err, _, _ = _run(data_dir, nn, below, moving, "monopole")
    assert err["thickness"] < 0.01
    assert err["loading"] < (0.045 if (nn == 1 and below) else 0.01)


def _check_dual_compact(data_dir, cases):
    """Dual compact vs ANOPP2's compact monopole on ``cases``.

    The dual-compact force law has the compact monopole as its compact limit (exact for a section
    in steady rotation; docs/reference/acoustics.md). Two layouts:
    * pair centred on the element (where ANOPP2's monopole sits): max |difference| < 1 % of the
      ANOPP2 peak-to-peak, 2.5 % at 200 rpm (there the axial flight speed is 0.2 of the tip speed and
      the O(V/U) term of a pair separated across the helical path shows). Measured ≤ 0.98 %, 2.4 %.
    * as nps.noise.sources places it (13 %/87 % chord, element at 25 %): the box centre lies a quarter
      chord behind the monopole, a pure time shift of ≈ c/(4U); peak-to-peak within 3 % (measured
      0.997–1.026) and max |difference| < 9 % of peak-to-peak (measured 4.7–8.1 %, the shift).
    The loading is unaffected. The thesis' ±ρ0c²·t·dr lines were 1168× (200 rpm) … 4.5× (2200 rpm) the
    monopole's peak-to-peak here.
    """
    worst = {"dual": 0.0, "dual_centred": 0.0}
    for nn, below, moving in cases:
        for layout, tolerance in (("dual_centred", 0.025 if nn == 1 else 0.01), ("dual", 0.09)):
            err, p, ref = _run(data_dir, nn, below, moving, layout)
            gap = np.abs(p["thickness"] - ref[:, 1]).max() / np.ptp(ref[:, 1])
            ratio = np.ptp(p["thickness"]) / np.ptp(ref[:, 1])
            print(f"{layout} {200 * nn} rpm {'-45' if below else '0'} deg {'moving' if moving else 'fixed'}: "
                  f"max |dual - ANOPP2 monopole| / p2p = {gap:.4f}, p2p ratio {ratio:.4f}")
            worst[layout] = max(worst[layout], gap)
            assert gap < tolerance
            assert abs(ratio - 1) < 0.03
    print(f"dual compact vs ANOPP2 monopole, worst of {len(cases)} cases: {worst}")


@pytest.mark.slow
def test_anopp2_dual_compact_thickness_vs_monopole_all_cases(data_dir):
    """All 44 cases (≈ 30 s), criteria of :func:`_check_dual_compact`."""
    _check_dual_compact(data_dir, CASES)


def test_anopp2_dual_compact_thickness_vs_monopole(data_dir):
    """Fast subset: 200, 1200, 2200 rpm in plane and 200 rpm −45° (the extremes of the gaps), fixed observer."""
    _check_dual_compact(data_dir, [(1, False, False), (6, False, False), (11, False, False), (1, True, False)])
