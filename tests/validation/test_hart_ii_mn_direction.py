"""HART-II MN: why the BL → MN change of the BVISPL carpet maximum has the wrong sign
(docs/validation/hart_ii_mn_direction.md). Flow and airload evidence only, never the noise data.

1. The blade-motion input: the rig applies the published 3/rev HHC (θ3 = 0.8° at ψ3 = 300°, MN; 180°,
   MV) plus the measured elastic torsion, and the measured torsion and flap respond to that input as a
   damped linear system would (same lag for MN and MV); the predicted 3/rev M²C_n change from BL is
   within 25 % and 20° of the measured one. No sign, phase or double-counting error.
2. The advancing-side BVI events at r/R = 0.87 (Beddoes wake, Betz structure, measured motion): the
   late MN event (measured ψ 68.2°) is timed right, but the measured MN has no event at ψ 45°–62°
   (max −dM²C_n/dψ 0.0006 /deg against BL's 0.0055) where NPS predicts its strongest one (0.0096 /deg);
   those events set NPS's MN maximum microphone (x_T 0, y_T 1.81 m).
3. The PIV vortex heights where the blade meets them on the advancing side (cut ψ = 20°, met at
   ψ 55°–85°, r/R ≥ 0.78): the measured MN lowers them by ≈ 12 cm from BL, NPS by ≈ 2 cm.

Items 2 and 3 are strict expected failures: they pass once the wake's vortex heights respond to the
HHC as measured. Runtime ≈ 35 s (three trims and BVI loads, Numba compilation included).
"""

from pathlib import Path

import numpy as np
import pytest

import hart_ii_case as h
from nps.app.config import load_rig
from nps.rig.case import rig_solution
from nps.rotor import bet
from nps.rotor.geometry import RotorGeometry
from nps.wake import bvi
from nps.wake import prescribed as wake

RIGS = Path(__file__).resolve().parents[2] / "config" / "rigs"
NAMES = ("BL", "MN", "MV")
GRID = bet.DiskGrid(360, 50)
MODEL = wake.WakeModel(steps_per_rev=360)


def _harmonic(psi_rad, values, n):
    """Complex amplitude c + i s of c cos nψ + s sin nψ in ``values`` (periodic samples)."""
    return 2.0 * np.mean(np.asarray(values) * np.exp(1j * n * np.asarray(psi_rad)))


def _phase_deg(z) -> float:
    return float(np.degrees(np.angle(z)))


def _wrap(deg) -> float:
    return float((deg + 180.0) % 360.0 - 180.0)


def _hhc(case: h.Case) -> complex:
    """θ3 cos(3ψ − ψ3) as c + i s (deg)."""
    return case.theta3_deg * np.exp(1j * np.radians(case.psi3_deg))


def _elastic3(case: h.Case) -> complex:
    """Measured 3/rev elastic tip torsion as c + i s (deg)."""
    _, c, s = next(t for t in case.elastic_twist if t[0] == 3)
    return complex(np.degrees(c), np.degrees(s))


@pytest.fixture(scope="module")
def runs():
    """Per condition: ψ (deg), M²C_n at r/R = 0.87 with BVI, the trim disk, the wake state (Beddoes)."""
    out = {}
    for name in NAMES:
        geometry, op, row = h.case_setup(h.CASES[name])
        trim = bet.trim_rotor(geometry, op, GRID)
        res = bvi.bvi_loads(trim.disk, row, geometry, trim.totals.ct, MODEL, bvi.BVIModel())
        grid = bvi.disk_grid(res.disk)
        j = int(np.argmin(np.abs(grid.r_m / h.RADIUS_M - h.R_OVER_R)))
        fz = res.disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
        out[name] = dict(psi=np.degrees(grid.psi_rad), cn=h.cn_m2(fz, op.density_kg_m3, op.speed_of_sound_mps),
                         disk=trim.disk, state=bvi.wake_state(trim.disk, row, trim.totals.ct), omega=op.omega_rad_s)
    return out


@pytest.mark.parametrize("rig_name, case", [("hart_ii_mn_measured", "MN"), ("hart_ii_mv_measured", "MV")])
def test_rig_applies_the_published_hhc_plus_the_measured_torsion(rig_name, case):
    """The 3/rev pitch the rig's trimmed blade carries at r/R ≈ 0.87 is θ3∠ψ3 + (r/R)·(measured 3/rev tip
    torsion) within 0.01° (MN 1.43° at 350.5°, MV 1.60° at 234.4°); with the torsion taken out the rest is
    the published 0.8° within 0.01° at ψ3 within 0.5°. Nothing else adds a 3/rev pitch (no double counting)."""
    rig = load_rig(RIGS / f"{rig_name}.yaml")
    rotor, condition = rig["rotor_configs"][0], rig["rotor_conditions"][0]
    disk = rig_solution(rotor, condition, GRID).result.disk
    psi, r = np.unique(disk["psi_rad"]), np.unique(disk["r_m"])
    j = int(np.argmin(np.abs(r / RotorGeometry.from_config(rotor).radius_m - h.R_OVER_R)))
    theta_deg = np.degrees(disk["theta_rad"].to_numpy().reshape(psi.size, r.size)[:, j])
    applied = _harmonic(psi, theta_deg, 3)
    rbar = r[j] / h.RADIUS_M
    expected = _hhc(h.CASES[case]) + rbar * _elastic3(h.CASES[case])
    assert abs(applied - expected) < 0.01, (applied, expected)
    hhc_part = applied - rbar * _elastic3(h.CASES[case])
    assert abs(abs(hhc_part) - h.CASES[case].theta3_deg) < 0.01
    assert abs(_wrap(_phase_deg(hhc_part) - h.CASES[case].psi3_deg)) < 0.5


def test_measured_torsion_responds_to_the_hhc_convention_used():
    """The measured 3/rev elastic tip torsion over the HHC input, θ_el/θ_HHC, is one transfer function for
    MN and MV only with θ_HHC = θ3 cos(3ψ − ψ3): lag 84.4° / 84.3°, gain 1.60 / 1.88 (a damped torsion
    mode near 3/rev lags by 0°–180°). A mirrored azimuth, cos(3ψ + ψ3), or cos(3(ψ − ψ3)) make the two
    lags differ by more than 100°."""
    mn, mv = h.CASES["MN"], h.CASES["MV"]
    lag = {c.name: _phase_deg(_elastic3(c) / _hhc(c)) for c in (mn, mv)}
    assert abs(_wrap(lag["MN"] - lag["MV"])) < 2.0, lag
    assert 0.0 < lag["MN"] < 180.0 and 1.0 < abs(_elastic3(mn) / _hhc(mn)) < 2.5
    for input_of in (lambda c: np.conj(_hhc(c)),  # cos(3ψ + ψ3)
                     lambda c: c.theta3_deg * np.exp(3j * np.radians(c.psi3_deg))):  # cos(3(ψ − ψ3))
        other = [_phase_deg(_elastic3(c) / input_of(c)) for c in (mn, mv)]
        assert abs(_wrap(other[0] - other[1])) > 100.0, other


def test_measured_flap_lags_the_total_pitch_as_a_damped_flap_mode():
    """The measured 3/rev tip flap lags the total 3/rev tip pitch (HHC + torsion) by 153° (MN) and 166° (MV);
    an equivalent hinged blade (ν² = 1 + 3e/(2(R − e)), e = 0.29 m, γ = 8) forced at 3/rev lags by 159°.
    A flipped flap or pitch sign would give −27° / −14°."""
    e, radius, gamma = h.GEOMETRY.hinge_offset_m, h.RADIUS_M, h.GEOMETRY.lock_number
    nu_sq = 1.0 + 1.5 * e / (radius - e)
    model_lag = _phase_deg(complex(nu_sq - 9.0, 3.0 * gamma / 8.0))
    for name in ("MN", "MV"):
        case = h.CASES[name]
        _, c, s = next(t for t in h.tip_flap_harmonics(case) if t[0] == 3)
        flap = complex(np.degrees(c), np.degrees(s))
        lag = _phase_deg(flap / (_hhc(case) + _elastic3(case)))
        assert 140.0 < lag < 175.0 and abs(lag - model_lag) < 10.0, (name, lag, model_lag)


def test_predicted_3_per_rev_loading_change_matches_the_measured(runs):
    """BL → MN and BL → MV change of the 3/rev M²C_n at r/R = 0.87: NPS ×1.16 / ×1.09 of the measured,
    −12.7° / −12.1° in phase; asserted within 25 % and 20°."""
    base_m = _harmonic(np.radians(h.measured_cn("BL")[0]), h.measured_cn("BL")[1], 3)
    base_p = _harmonic(np.radians(runs["BL"]["psi"]), runs["BL"]["cn"], 3)
    for name in ("MN", "MV"):
        psi_m, cn_m = h.measured_cn(name)
        measured = _harmonic(np.radians(psi_m), cn_m, 3) - base_m
        predicted = _harmonic(np.radians(runs[name]["psi"]), runs[name]["cn"], 3) - base_p
        assert 0.8 < abs(predicted) / abs(measured) < 1.25, (name, abs(predicted), abs(measured))
        assert abs(_wrap(_phase_deg(predicted / measured))) < 20.0, name


def _steepest_drop(psi_deg, values, lo, hi):
    """(−dM²C_n/dψ per deg, ψ deg) of the steepest fall of the ≥ 10/rev content in [lo, hi)."""
    slope = np.gradient(h.high_pass(values), psi_deg)
    inside = (psi_deg >= lo) & (psi_deg < hi)
    k = int(np.argmin(slope[inside]))
    return float(-slope[inside][k]), float(psi_deg[inside][k])


def test_late_advancing_mn_event_is_timed_right(runs):
    """Measured MN: the strongest advancing-side event at ψ 68.2° (−dM²C_n/dψ 0.0142 /deg); NPS's strongest
    in 62°–80° within 3° of it (68.0°, 0.0094 /deg)."""
    measured = _steepest_drop(*h.measured_cn("MN"), 62.0, 80.0)
    predicted = _steepest_drop(runs["MN"]["psi"], runs["MN"]["cn"], 62.0, 80.0)
    assert _steepest_drop(*h.measured_cn("MN"), 30.0, 80.0) == measured
    assert abs(predicted[1] - measured[1]) < 3.0, (predicted, measured)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="NPS strengthens the MN events at psi 45-62 deg (0.0096 /deg against BL's 0.0036) "
                          "where the measured MN has none (0.0006 against 0.0055; hart_ii_mn_direction.md)")
def test_mid_advancing_events_vanish_in_mn(runs):
    """Measured: the steepest fall in ψ 45°–62° drops from 0.0055 /deg (BL) to 0.0006 /deg (MN), below a
    quarter; NPS must show the same."""
    measured = {n: _steepest_drop(*h.measured_cn(n), 45.0, 62.0)[0] for n in ("BL", "MN")}
    assert measured["MN"] < 0.25 * measured["BL"], measured
    predicted = {n: _steepest_drop(runs[n]["psi"], runs[n]["cn"], 45.0, 62.0)[0] for n in ("BL", "MN")}
    assert predicted["MN"] < 0.25 * predicted["BL"], predicted


def _met_heights(runs, name):
    """Advancing PIV vortices of the ψ = 20° cut met by a blade at ψ 55°–85°, r/R ≥ 0.78: rows (y, x, measured
    z − blade z, NPS z − blade z) in m; the meeting point found with the vortex carried aft at the free stream."""
    run = runs[name]
    beta = run["disk"]["beta_rad"].to_numpy().reshape(GRID.n_psi, -1)[:, 0]
    speed = h.SPEED * np.cos(np.radians(h.CASES[name].shaft_deg))
    rows = []
    for side, psi0, y, x, z, _, z_pred, _ in h.piv_miss_distances(run["state"], MODEL, name):
        if side != "advancing" or psi0 != 20.0:
            continue
        psi_b, x_m = np.degrees(np.arctan2(y, x)) % 360.0, x
        for _ in range(5):  # the next blade (within 90°) reaches the vortex while it convects aft
            x_m = x + speed * np.radians((psi_b - psi0) % 90.0) / run["omega"]
            psi_b = np.degrees(np.arctan2(y, x_m)) % 360.0
        r = np.hypot(x_m, y)
        if 55.0 <= psi_b <= 85.0 and 0.78 * h.RADIUS_M <= r <= h.RADIUS_M:
            z_blade = r * np.sin(np.interp(psi_b, np.arange(GRID.n_psi) * 360.0 / GRID.n_psi, beta, period=360.0))
            rows.append((y, x, z - z_blade, z_pred - z_blade))
    return np.array(rows)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="the advancing-side vortices the MN blade meets at psi 55-85 deg drop by ~12 cm "
                          "from BL (PIV), by ~2 cm in NPS (hart_ii_mn_direction.md)")
def test_mn_lowers_the_advancing_vortices_as_measured(runs):
    """Vortex height over the blade where it is met (PIV cut ψ = 20°, pairs of BL and MN vortices in the same
    cut within 0.1 m in y and 0.25 m in x; 3 pairs): measured mean change −0.114 m (asserted < −0.08 m); NPS must
    give at least half of it (it gives −0.019 m). Heights over the blade: measured BL 0.135, MN 0.020, MV 0.200 m;
    NPS 0.047, 0.027, 0.062 m."""
    bl, mn = _met_heights(runs, "BL"), _met_heights(runs, "MN")
    pairs = [(m[2] - b[2], m[3] - b[3]) for b in bl for m in mn if abs(m[0] - b[0]) < 0.1 and abs(m[1] - b[1]) < 0.25]
    assert len(pairs) >= 3, pairs
    measured, predicted = np.mean(pairs, axis=0)
    assert measured < -0.08, measured
    assert predicted < 0.5 * measured, (measured, predicted)
