"""Unit tests of nps.rotor.bet: section kernel properties, disk-table contract, signs, errors."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.rotor.bet import (
    DISK_COLUMNS,
    Controls,
    DiskGrid,
    TrimError,
    radial_stations,
    rotor_loads,
    section_forces,
    trim_rotor,
)
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.geometry import OperatingPoint, RotorGeometry

R = 7.62
GEOM = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.15 * R,
                     twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0, hinge_offset_m=0.381)
WEIGHT_N = 5140.1 * 9.80665


def op(mu_x=0.0, mu_z=0.0, **kw):
    return OperatingPoint(omega_rad_s=28.0, mu_x=mu_x, mu_y=kw.pop("mu_y", 0.0), mu_z=mu_z, density_kg_m3=1.225,
                          speed_of_sound_mps=340.3, thrust_N=kw.pop("thrust_N", WEIGHT_N), **kw)


@pytest.fixture(scope="module")
def forward():
    return trim_rotor(GEOM, op(0.24, 0.03), DiskGrid(72, 20))


def test_radial_stations_are_element_midpoints():
    r, dr = radial_stations(GEOM, 10)
    assert np.allclose(dr, 0.85 * R / 10) and math.isclose(r[0], 0.15 * R + dr[0] / 2)
    assert math.isclose(r[-1] + dr[-1] / 2, R) and math.isclose(dr.sum(), 0.85 * R)


def test_disk_table_columns_and_psi_major_order(forward):
    disk = forward.disk
    assert tuple(disk.columns) == DISK_COLUMNS and len(disk) == 72 * 20
    assert np.all(disk["psi_rad"].to_numpy()[:20] == 0.0)
    assert np.allclose(disk["psi_rad"].to_numpy()[20], 2 * np.pi / 72)
    assert np.isfinite(disk.to_numpy(dtype=float)).all()


def test_section_forces_reproduce_disk_table_exactly(forward):
    """The BVI contract: section_forces on the table's U_T, U_P, θ, r gives its F_z, F_x bit for bit."""
    d = forward.disk
    f = section_forces(d["ut_mps"], d["up_mps"], d["theta_rad"], d["r_m"], GEOM, 1.225, 340.3)
    assert np.array_equal(f.fz_N_per_m, d["fz_N_per_m"].to_numpy())
    assert np.array_equal(f.fx_N_per_m, d["fx_N_per_m"].to_numpy())
    assert np.array_equal(f.circulation_m2_s, d["circulation_m2_s"].to_numpy())


def test_thrust_equals_sum_of_sectional_forces(forward):
    """T = (B/N_ψ) Σ F_z dr over the table (each blade sees every azimuth once): to 1e-12."""
    d = forward.disk
    total = GEOM.n_blades / 72 * float(np.sum(d["fz_N_per_m"] * d["dr_m"]))
    assert abs(total - forward.totals.thrust_N) <= 1e-12 * abs(total)
    torque = GEOM.n_blades / 72 * float(np.sum(d["fx_N_per_m"] * d["dr_m"] * d["r_m"]))
    assert abs(torque - forward.totals.torque_Nm) <= 1e-12 * abs(torque)


finite = st.floats(-400.0, 400.0, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(finite, finite, st.floats(-1.5, 1.5), st.floats(0.0, 1.2 * R), st.floats(50.0, 400.0))
def test_section_forces_finite_everywhere(ut, up, theta, r, sound):
    """Reverse flow, stall, M > 1, U_T = 0, r beyond the tip: never a NaN or an inf."""
    f = section_forces(ut, up, theta, r, GEOM, 1.225, sound)
    for value in (f.fz_N_per_m, f.fx_N_per_m, f.alpha_eff_rad, f.mach, f.circulation_m2_s):
        assert np.isfinite(value).all()
    assert abs(f.alpha_eff_rad) <= np.pi / 2 + 1e-12
    assert abs(f.circulation_m2_s) <= 0.5 * GEOM.chord_m * GEOM.airfoil.cl_max * math.hypot(ut, up) + 1e-12


@settings(max_examples=100, deadline=None)
@given(st.floats(1.0, 300.0), st.booleans(), st.floats(-50.0, 50.0), st.floats(-0.5, 0.5), st.floats(1.2, R))
def test_symmetric_section_is_odd_in_pitch_and_inflow(speed, reverse, up, theta, r):
    """Symmetric polar (α0 = cd1 = 0): (U_P, θ) → (−U_P, −θ) flips F_z and keeps F_x.

    (Away from U_T = 0, where α = ±π/2 is the branch cut of the mod-π angle.)"""
    ut = -speed if reverse else speed
    a = section_forces(ut, up, theta, r, GEOM, 1.225, 340.0)
    b = section_forces(ut, -up, -theta, r, GEOM, 1.225, 340.0)
    assert np.isclose(a.fz_N_per_m, -b.fz_N_per_m, rtol=1e-12, atol=1e-9)
    assert np.isclose(a.fx_N_per_m, b.fx_N_per_m, rtol=1e-12, atol=1e-9)


def test_small_angle_limit_is_thesis_eq_4_1():
    """Without drag and tip loss, F_z → ½ρca(θU_T² − U_P U_T) (eq. 4.1) as angles → 0 (rel 1e-4)."""
    foil = LinearAirfoil(cd0=0.0, cd2=0.0, cl_max=10.0)
    g = RotorGeometry(**{**GEOM.__dict__, "airfoil": foil})
    ut, up, theta = 150.0, 0.3, 0.01
    f = section_forces(ut, up, theta, 5.0, g, 1.225, 1e9, tip_loss=False)
    eq41 = 0.5 * 1.225 * g.chord_m * 5.73 * (theta * ut**2 - up * ut)
    assert math.isclose(f.fz_N_per_m, eq41, rel_tol=1e-4)


def test_reverse_flow_section_pushes_down():
    """Wind from the trailing edge on a nose-up section: force down, drag along the motion."""
    f = section_forces(-20.0, 0.0, 0.1, 2.0, GEOM, 1.225, 340.0)
    assert f.fz_N_per_m < 0.0 and f.fx_N_per_m < 0.0 and math.isclose(f.alpha_eff_rad, 0.1)


def test_compressibility_bounded_and_stall_limited():
    low = section_forces(100.0, 0.0, 0.05, 5.0, GEOM, 1.225, 1e9, tip_loss=False)
    sonic = section_forces(340.0, 0.0, 0.05, 5.0, GEOM, 1.225, 340.0, tip_loss=False)
    cl_low = low.fz_N_per_m / (0.5 * 1.225 * 0.58 * 100.0**2)
    cl_sonic = sonic.fz_N_per_m / (0.5 * 1.225 * 0.58 * 340.0**2)
    assert math.isclose(cl_sonic / cl_low, 1.0 / math.sqrt(1.0 - 0.95**2), rel_tol=1e-12)
    stalled = section_forces(100.0, 0.0, 0.6, 5.0, GEOM, 1.225, 1e9, tip_loss=False)
    assert math.isclose(stalled.circulation_m2_s, 0.5 * 0.58 * 1.4 * 100.0, rel_tol=1e-12)


def test_tip_loss_takes_lift_to_zero_at_the_tip():
    """Prandtl F: 1 inboard, < 0.3 within 0.1 % R of the tip (B = 4, φ ≈ 0.025), 0 at the tip."""
    r = np.array([0.5 * R, 0.9 * R, 0.999 * R, R])
    with_loss = section_forces(200.0 * r / R, 5.0, 0.1, r, GEOM, 1.225, 1e9).circulation_m2_s
    without = section_forces(200.0 * r / R, 5.0, 0.1, r, GEOM, 1.225, 1e9, tip_loss=False).circulation_m2_s
    factor = with_loss / without
    assert math.isclose(factor[0], 1.0, rel_tol=1e-9) and factor[2] < 0.3 and factor[3] == 0.0
    assert np.all(np.diff(factor) < 0.0)


def test_hub_moment_signs_follow_conventions():
    """Hover, e > 0: θ1c > 0 flaps the advancing side up 90° later (β1s > 0) → M_x > 0 for ccw,
    mirrored for cw; θ1s > 0 flaps the front up (β1c < 0) → nose-up M_y > 0. The aerodynamic
    moment of the disk loads about the hub has the same sign as the transmitted hub moment."""
    grid = DiskGrid(36, 20)
    for s in (1, -1):
        g = RotorGeometry(**{**GEOM.__dict__, "rotation_sign": s})
        lat = rotor_loads(g, op(), grid, Controls(0.12, math.radians(1.0), 0.0))
        assert lat.flapping.beta1s_rad > 0 and s * lat.totals.roll_moment_Nm > 0 and s * lat.totals.aero_roll_moment_Nm > 0
        assert abs(lat.totals.pitch_moment_Nm) < 0.15 * abs(lat.totals.roll_moment_Nm)
        lon = rotor_loads(g, op(), grid, Controls(0.12, 0.0, math.radians(1.0)))
        assert lon.flapping.beta1c_rad < 0 and lon.totals.pitch_moment_Nm > 0 and lon.totals.aero_pitch_moment_Nm > 0


def test_trim_meets_nonzero_moment_targets_for_both_rotation_senses():
    grid = DiskGrid(36, 20)
    for s in (1, -1):
        g = RotorGeometry(**{**GEOM.__dict__, "rotation_sign": s})
        target = op(0.2, 0.02, roll_moment_Nm=4000.0, pitch_moment_Nm=-3000.0)
        t = trim_rotor(g, target, grid)
        assert abs(t.totals.roll_moment_Nm - 4000.0) <= 1e-3 * WEIGHT_N * R
        assert abs(t.totals.pitch_moment_Nm + 3000.0) <= 1e-3 * WEIGHT_N * R
        assert abs(t.totals.thrust_N / WEIGHT_N - 1.0) <= 1e-3


def test_bad_inputs_raise_before_computation():
    with pytest.raises(ValueError, match="n_psi"):
        DiskGrid(4, 10)
    with pytest.raises(ValueError, match="density_kg_m3"):
        trim_rotor(GEOM, OperatingPoint(28.0, 0.1, 0.0, 0.0, float("nan"), 340.0, 1e4), DiskGrid(36, 10))
    with pytest.raises(ValueError, match="root_cutout_m"):
        trim_rotor(RotorGeometry(**{**GEOM.__dict__, "root_cutout_m": 8.0}), op(), DiskGrid(36, 10))
    teetering = RotorGeometry(**{**GEOM.__dict__, "hinge_offset_m": 0.0})
    with pytest.raises(ValueError, match="roll_moment_Nm"):
        trim_rotor(teetering, op(roll_moment_Nm=100.0), DiskGrid(36, 10))


def test_unreachable_thrust_raises_trim_error_with_residuals():
    with pytest.raises(TrimError, match="thrust_N: residual"):
        trim_rotor(GEOM, op(0.1, 0.0, thrust_N=20 * WEIGHT_N), DiskGrid(36, 10), max_outer=3)


def test_cli_writes_disk_summary_and_history(tmp_path, repo_root):
    """``python -m nps loads`` on a one-row trim artifact: three artifacts, contract columns."""
    import pandas as pd

    from nps.__main__ import main
    from nps.app.io import read_table, write_table
    from tests.trim_tables import complete_trim

    trim = complete_trim(pd.DataFrame({"rotor": ["main"], "omega_rad_s": [28.0], "mu_x": [0.2], "mu_y": [0.0], "mu_z": [0.02],
                         "density_kg_m3": [1.225], "speed_of_sound_mps": [340.3], "thrust_N": [WEIGHT_N],
                         "roll_moment_Nm": [0.0], "pitch_moment_Nm": [0.0]}))
    write_table(trim, tmp_path / "trim.parquet", stage="trim")
    out = tmp_path / "loads" / "main.parquet"
    argv = ["loads", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"), "--rotor", "main",
            "--trim", str(tmp_path / "trim.parquet"), "--n-psi", "36", "--n-r", "10", "--out-dir", str(out.parent)]
    assert main(argv) == 0
    assert tuple(read_table(out).columns) == DISK_COLUMNS
    summary = read_table(tmp_path / "loads" / "main_summary.parquet", required=("quantity", "value", "unit"))
    for q in ("theta0_rad", "beta1s_rad", "lambda0", "kx", "thrust_N", "power_W", "ct", "trim_iterations", "mean_cl"):
        assert q in set(summary["quantity"])
    assert len(read_table(tmp_path / "loads" / "main_history.parquet")) >= 2
    assert main(argv[:4] + ["nope"] + argv[5:]) == 2
