"""Unit tests of nps.wake.bvi: blade-frame resolution, filters, BVI disk table."""

import math

import numpy as np
import pytest

from nps.rotor import bet

from nps.wake import bvi

from nps.wake import prescribed as wake
from nps.rotor.geometry import OperatingPoint, RotorGeometry

GEO = RotorGeometry(
    name="test", n_blades=4, radius_m=2.0, chord_m=0.121, root_cutout_m=0.44, twist_rad=math.radians(-8.0),
    thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29,
)


def _trimmed(mu_x=0.15, mu_z=-0.0113, mu_y=0.0, sign=1, n_psi=120, n_r=20):
    geo = RotorGeometry(**{**GEO.__dict__, "rotation_sign": sign})
    op = OperatingPoint(omega_rad_s=109.12, mu_x=mu_x, mu_y=mu_y, mu_z=mu_z, density_kg_m3=1.2055,
                        speed_of_sound_mps=341.7, thrust_N=3300.0)
    trim = bet.trim_rotor(geo, op, bet.DiskGrid(n_psi, n_r))
    row = dict(n_blades=4, radius_m=2.0, omega_rad_s=109.12, rotation_sign=sign, mu_x=mu_x, mu_y=mu_y, mu_z=mu_z,
               density_kg_m3=1.2055, speed_of_sound_mps=341.7)
    return geo, trim, row


def test_blade_frame_increments():
    """ΔU_P = −v·n, ΔU_T = −v·e_t: a downward velocity raises U_P, a velocity along the blade's
    motion lowers U_T, an outward (radial) velocity changes neither when β = 0 (exact)."""
    psi = np.array([0.0, 0.7, 2.0])
    e_t = np.stack([-np.sin(psi), np.cos(psi), 0 * psi], -1)[:, None, :]
    e_r = np.stack([np.cos(psi), np.sin(psi), 0 * psi], -1)[:, None, :]
    down = np.broadcast_to(np.array([0.0, 0.0, -2.0]), (3, 1, 3))
    d_ut, d_up = bvi.blade_frame_increments(down + 3.0 * e_t + 5.0 * e_r, psi, np.zeros((3, 1)))
    assert np.allclose(d_up, 2.0) and np.allclose(d_ut, -3.0)
    beta = np.full((3, 1), 0.1)
    normal = np.stack([-np.sin(0.1) * np.cos(psi), -np.sin(0.1) * np.sin(psi), np.cos(0.1) + 0 * psi], -1)[:, None, :]
    _, d_up = bvi.blade_frame_increments(-4.0 * normal, psi, beta)
    assert np.allclose(d_up, 4.0)


def test_remove_low_harmonics_exact():
    psi = 2 * np.pi * np.arange(64) / 64
    field = (3 + 2 * np.cos(psi) - np.sin(psi) + 0.5 * np.cos(5 * psi))[:, None]
    assert np.allclose(bvi.remove_low_harmonics(field, 1), 0.5 * np.cos(5 * psi)[:, None], atol=1e-12)


def test_sears_function_values():
    """S(0) = 1; |S(k)| matches tabulated Sears magnitudes (Leishman, Principles, Fig. 8.29:
    0.84 at k = 0.1, 0.53 at 0.5, 0.39 at 1.0) within 0.01; |S| decreases with k."""
    k = np.array([0.0, 0.1, 0.5, 1.0, 2.0])
    s = np.abs(bvi.sears(k))
    assert s[0] == 1.0
    assert s[1:4] == pytest.approx([0.837, 0.526, 0.390], abs=0.01)
    assert np.all(np.diff(s) < 0)


def _amplitude(x, n):
    return 2 * abs(np.fft.rfft(x[:, 0])[n]) / x.shape[0]


def test_unsteady_response_keeps_low_and_attenuates_high_harmonics():
    """With U_T = Ωr (no forward speed) each harmonic n is scaled by |S(n c / 2r)| (rel. 1e-3,
    table interpolation): a 1/rev field at r = 1.7 m, c = 0.121 m (k = 0.036) keeps > 90 %,
    a 40/rev field (k = 1.42) about a third."""
    psi = 2 * np.pi * np.arange(360) / 360
    r, omega = 1.7, 109.12
    ut = np.full((360, 1), omega * r)
    low = bvi.unsteady_response(np.cos(psi)[:, None], ut, omega, 2.0, 0.121)
    assert _amplitude(low, 1) == pytest.approx(abs(bvi.sears(0.121 / 3.4)), rel=1e-3)
    assert _amplitude(low, 1) > 0.9
    high = bvi.unsteady_response(np.cos(40 * psi)[:, None], ut, omega, 2.0, 0.121)
    assert _amplitude(high, 40) == pytest.approx(abs(bvi.sears(40 * 0.121 / 3.4)), rel=1e-3)
    assert 0.25 < _amplitude(high, 40) < 0.4


def test_unsteady_response_uses_local_in_plane_speed():
    """Frozen coefficients: a pure 40/rev input at a station with U_T = Ωr (1 + 0.4 sin ψ)
    comes out as Re[S(k(ψ)) e^{−ik(ψ)/2} e^{i40ψ}], k(ψ) = 40 c Ω / (2 U_T(ψ)) (abs. 1e-3,
    exact Sears function), so the faster advancing section (ψ = 90°) is attenuated less than
    the retreating one (ψ = 270°): local amplitude 0.39 vs 0.26 for r = 1.7 m, c = 0.121 m."""
    psi = 2 * np.pi * np.arange(720) / 720
    r, omega, c = 1.7, 109.12, 0.121
    ut = (omega * r * (1 + 0.4 * np.sin(psi)))[:, None]
    out = bvi.unsteady_response(np.cos(40 * psi)[:, None], ut, omega, 2.0, c)[:, 0]
    k = 40 * c * omega / (2 * ut[:, 0])
    expected = np.real(bvi.sears(k) * np.exp(-0.5j * k) * np.exp(40j * psi))
    assert np.abs(out - expected).max() < 1e-3
    local = np.abs(bvi.sears(k))
    assert local[180] == pytest.approx(0.39, abs=0.01) and local[540] == pytest.approx(0.26, abs=0.01)


def test_compressible_gust_response_magnitude():
    """Compressibility scales the reduced frequency by 1/β² in the magnitude only: at M = 0.64
    (β² = 0.5904) and k = 0.5, |H| = |S(0.847)| = 0.42 against the incompressible |S(0.5)| =
    0.53 (Leishman's Sears values, within 0.01); the phase is the incompressible one; the
    quasi-steady limit k → 0 is unchanged (the BET carries the Prandtl–Glauert factor)."""
    beta_sq = 1 - 0.64**2
    h_inc = bvi.gust_transfer(np.array([0.0, 0.5]))
    h_com = bvi.gust_transfer(np.array([0.0, 0.5]), beta_sq)
    assert abs(h_com[0]) == pytest.approx(1.0, abs=1e-9)
    assert abs(h_inc[1]) == pytest.approx(0.526, abs=0.01)
    assert abs(h_com[1]) == pytest.approx(abs(bvi.sears(0.5 / beta_sq)), rel=1e-3)
    assert abs(h_com[1]) == pytest.approx(0.42, abs=0.01)
    assert np.angle(h_com[1]) == pytest.approx(np.angle(h_inc[1]), abs=1e-12)


def test_bvi_table_schema_and_no_retrim():
    """The BVI table has exactly the loads columns and rows, the trim's θ, β, geometry
    unchanged; with the 0/1-rev harmonics removed the thrust stays within 3 % of the trim,
    while adding the raw wake velocity (thesis) double-counts the inflow and loses > 5 %."""
    geo, trim, row = _trimmed()
    model = wake.WakeModel(steps_per_rev=120, revolutions=3)
    res = bvi.bvi_loads(trim.disk, row, geo, trim.totals.ct, model)
    assert list(res.disk.columns) == list(bvi.DISK_COLUMNS) == list(bet.DISK_COLUMNS)
    assert len(res.disk) == len(trim.disk)
    for col in ("psi_rad", "r_m", "dr_m", "chord_m", "theta_rad", "beta_rad", "beta_dot_rad_s"):
        assert np.array_equal(res.disk[col].to_numpy(), trim.disk[col].to_numpy())
    assert np.isfinite(res.disk.select_dtypes("number").to_numpy()).all()

    def thrust(d):
        return 4 * (d["fz_N_per_m"] * d["dr_m"]).sum() / 120

    t0 = thrust(trim.disk)
    assert thrust(res.disk) == pytest.approx(t0, rel=0.03)
    raw = bvi.bvi_loads(trim.disk, row, geo, trim.totals.ct, model, bvi.BVIModel(removed_harmonics=None, unsteady=False)).disk
    assert thrust(raw) < 0.95 * t0
    # recomputation goes through bet.section_forces with the new velocities
    f = bet.section_forces(res.disk.ut_mps, res.disk.up_mps, res.disk.theta_rad, res.disk.r_m, geo, 1.2055, 341.7)
    assert np.allclose(f.fz_N_per_m, res.disk.fz_N_per_m)


def test_hover_gives_no_impulsive_loading():
    """Hover: the BVI loads differ from the trimmed loads by < 1e-6 of the mean load (the
    axisymmetric wake lies below the disk and its mean is carried by the BET inflow)."""
    geo, trim, row = _trimmed(mu_x=0.0, mu_z=0.0, n_psi=72)
    res = bvi.bvi_loads(trim.disk, row, geo, trim.totals.ct, wake.WakeModel(steps_per_rev=72, revolutions=3))
    diff = np.abs(res.disk.fz_N_per_m.to_numpy() - trim.disk.fz_N_per_m.to_numpy())
    assert diff.max() < 1e-6 * np.abs(trim.disk.fz_N_per_m).mean()


def test_clockwise_rotor_loads_mirror_counterclockwise():
    """cw rotor with side wind +μ_y gives the same BVI disk (own azimuth) as ccw with −μ_y
    (rel. 1e-9)."""
    geo1, trim1, row1 = _trimmed(mu_y=-0.02, sign=1, n_psi=72, n_r=12)
    geo2, trim2, row2 = _trimmed(mu_y=0.02, sign=-1, n_psi=72, n_r=12)
    model = wake.WakeModel(steps_per_rev=72, revolutions=2)
    a = bvi.bvi_loads(trim1.disk, row1, geo1, trim1.totals.ct, model).disk
    b = bvi.bvi_loads(trim2.disk, row2, geo2, trim2.totals.ct, model).disk
    assert np.allclose(a.fz_N_per_m, b.fz_N_per_m, rtol=1e-9, atol=1e-9)


def test_bad_disk_tables_are_rejected():
    geo, trim, row = _trimmed(n_psi=24, n_r=6)
    with pytest.raises(ValueError, match="missing column"):
        bvi.disk_grid(trim.disk.drop(columns="circulation_m2_s"))
    with pytest.raises(ValueError, match="psi-major"):
        bvi.disk_grid(trim.disk.sort_values(["r_m", "psi_rad"]))
    with pytest.raises(ValueError, match="full grid"):
        bvi.disk_grid(trim.disk.iloc[:-1])
    with pytest.raises(ValueError, match="trim row"):
        bvi.wake_state(trim.disk, {"n_blades": 4}, 0.005)
