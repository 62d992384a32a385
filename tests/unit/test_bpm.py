"""Unit tests of nps.noise.broadband.bpm (RP-1218 scaling laws) and nps.noise.broadband.rotor (rotation average, Doppler)."""

import numpy as np
import pandas as pd
import pytest

from nps.noise.broadband import bpm
from nps.core.atmosphere import isa
from nps.noise.broadband.rotor import (BladeEdge, SourceKinematics, _radiation, disk_outside_bpm_range,
                                 medium_from_atmosphere, rotor_broadband_msp)
from nps.rotor.geometry import OperatingPoint, RotorGeometry

MEDIUM = bpm.Medium(340.0, 1.5e-5)
F_HZ = 1000.0 * 10.0 ** (np.arange(-10, 14) / 10.0)
MIC = bpm.directivity(1.22, np.pi / 2, np.pi / 2, 0.2)


def _sections(**kw):
    base = dict(chord_m=0.1, span_m=0.5, speed_mps=60.0, alpha_rad=np.radians(4.0), te_thickness_m=1e-3,
                te_angle_rad=np.radians(14.0), tripped=False)
    base.update(kw)
    return bpm.Sections(**base)


def test_directivity_normal_to_chord_at_rest_is_one():
    assert bpm.directivity_high(np.pi / 2, np.pi / 2, 0.0) == pytest.approx(1.0)
    assert bpm.directivity_low(np.pi / 2, np.pi / 2, 0.0) == pytest.approx(1.0)
    # trailing-edge cardioid: nothing straight downstream, twice the level ahead (B1)
    assert bpm.directivity_high(0.0, np.pi / 2, 0.0) == pytest.approx(0.0)
    assert bpm.directivity_high(np.pi, np.pi / 2, 0.0) == pytest.approx(2.0)
    # convective amplification toward the leading edge (Θ_e = 180°): 1/((1 − M)(1 − 0.2 M)²)
    m = 0.3
    assert bpm.directivity_high(np.pi, np.pi / 2, m) == pytest.approx(2.0 / ((1 - m) * (1 - 0.2 * m) ** 2))
    assert bpm.directivity_low(np.pi / 2 + 0.3, np.pi / 2, m) == pytest.approx(
        np.sin(np.pi / 2 + 0.3) ** 2 / (1 + m * np.cos(np.pi / 2 + 0.3)) ** 4)


def test_span_and_distance_scaling_is_exact():
    """Every section mechanism scales with L / r_e² (eq. 25-28, 53, 70)."""
    one = bpm.section_msp(F_HZ, _sections(), MIC, MEDIUM)
    two = bpm.section_msp(F_HZ, _sections(span_m=1.0), bpm.directivity(2.44, np.pi / 2, np.pi / 2, 0.2), MEDIUM)
    for name in one:
        np.testing.assert_allclose(two[name], one[name] / 2.0, rtol=1e-12)


def test_tbl_te_peak_level_scales_as_mach5_delta_star_k1():
    """Eq. (26) at α* = 0 and the spectral peak (St_s = St_1, A = 0), Θ_e = Φ_e = 90° (D̄_h = 1):
    SPL = 10 log10(δ*_s M⁵ L / r_e²) + K_1 − 3, so doubling U adds 50 log10 2 + Δ(10 log10 δ*) + ΔK_1."""
    levels, expected = [], []
    for u in (40.0, 80.0):
        re = u * 0.1 / MEDIUM.kinematic_viscosity_m2_s
        dstar = bpm.trailing_edge_thicknesses(0.1, re, 0.0, True)["delta_star_s_m"]
        mach = u / MEDIUM.speed_of_sound_mps
        f_peak = np.array([bpm.st1(mach) * u / dstar])
        msp = bpm.tbl_te_msp(f_peak, _sections(alpha_rad=0.0, tripped=True, speed_mps=u), MIC, MEDIUM)
        levels.append(10 * np.log10(msp["tbl_te_suction"][0] / bpm.P_REF_PA**2))
        expected.append(10 * np.log10(dstar * mach**5 * 0.5 / 1.22**2) + bpm.k1(re) - 3.0)
    np.testing.assert_allclose(levels, expected, atol=1e-4)  # A(1) = √67.552 − 8.219 = 2.4e-6 dB


def test_a_and_b_curves_peak_at_zero_and_reach_minus_20_db_at_a0():
    for re in (5e4, 3e5, 1e6):
        assert bpm.a_curve(1.0, re) == pytest.approx(0.0, abs=1e-5)  # rounded constants: √67.552 − 8.219, √16.888 − 4.109
        assert bpm.b_curve(1.0, re) == pytest.approx(0.0, abs=1e-3)
    a0 = -9.57e-13 * (3e5 - 8.57e5) ** 2 + 1.13
    assert bpm.a_curve(10.0**a0, 3e5) == pytest.approx(-20.0, abs=1e-9)


def test_mechanisms_switch_off_where_rp1218_says():
    sec = _sections(tripped=True, te_thickness_m=0.0)
    out = bpm.section_msp(F_HZ, sec, MIC, MEDIUM)
    assert np.all(out["lbl_vs"] == 0.0)  # LBL-VS needs a laminar boundary layer
    assert np.all(out["bluntness"] == 0.0)  # sharp trailing edge
    assert np.all(out["separation"] > 0.0)
    zero_alpha = bpm.section_msp(F_HZ, _sections(alpha_rad=0.0), MIC, MEDIUM)
    assert np.all(zero_alpha["separation"] == 0.0)  # K2 − K1 = −1000 dB below γ0 − γ
    np.testing.assert_allclose(zero_alpha["tbl_te_pressure"], zero_alpha["tbl_te_suction"], rtol=1e-12)


def test_negative_angle_equals_positive_angle():
    pos = bpm.section_msp(F_HZ, _sections(alpha_rad=np.radians(5.0)), MIC, MEDIUM)
    neg = bpm.section_msp(F_HZ, _sections(alpha_rad=np.radians(-5.0)), MIC, MEDIUM)
    for name in pos:
        np.testing.assert_array_equal(pos[name], neg[name])


def test_vectorised_over_elements_and_bands():
    chords = np.array([0.05, 0.1, 0.2])
    many = bpm.section_msp(F_HZ, _sections(chord_m=chords), MIC, MEDIUM)
    for i, c in enumerate(chords):
        single = bpm.section_msp(F_HZ, _sections(chord_m=c), MIC, MEDIUM)
        for name in many:
            np.testing.assert_array_equal(many[name][i], single[name])
    assert all(np.all(np.isfinite(v)) for v in many.values())


@pytest.mark.parametrize("field, value", [("chord_m", 0.0), ("speed_mps", -1.0), ("alpha_rad", np.nan),
                                          ("te_thickness_m", -1e-3), ("span_m", np.inf)])
def test_bad_section_input_names_the_field(field, value):
    with pytest.raises(ValueError, match=field):
        _sections(**{field: value})


def test_valid_range_flags_elements_outside_the_data():
    out = bpm.valid_range(np.array([50.0, 50.0, 150.0, 50.0]), np.array([0.1, 0.005, 0.1, 0.1]),
                          np.radians([5.0, 5.0, 5.0, 30.0]), MEDIUM)
    np.testing.assert_array_equal(out["any"], [False, True, True, True])
    np.testing.assert_array_equal(out["reynolds"], [False, True, False, False])
    np.testing.assert_array_equal(out["mach"], [False, False, True, False])
    np.testing.assert_array_equal(out["alpha"], [False, False, False, True])


def test_tip_lift_slope_ratio_table():
    assert bpm.tip_lift_slope_ratio(4.0) == pytest.approx(0.71)
    assert bpm.tip_lift_slope_ratio(5.0) == pytest.approx(0.75)
    assert bpm.tip_lift_slope_ratio(1.0) == pytest.approx(0.54)
    assert bpm.tip_lift_slope_ratio(100.0) == pytest.approx(0.95)


def test_medium_from_isa_sea_level():
    medium = medium_from_atmosphere(isa(0.0))
    assert medium.kinematic_viscosity_m2_s == pytest.approx(1.461e-5, rel=2e-3)  # ISA table value
    assert medium.speed_of_sound_mps == pytest.approx(340.294, rel=1e-5)


def test_doppler_factor_and_directivity_of_a_moving_source():
    kin = SourceKinematics(np.zeros((1, 1, 3)), np.array([[[0.0, 1.0, 0.0]]]), np.array([[[-1.0, 0.0, 0.0]]]),
                           np.array([[[68.0, 0.0, 0.0]]]))
    mach = np.array([[0.2]])
    _, d = _radiation(kin, mach, np.array([10.0, 0.0, 0.0]), np.zeros(3), 340.0, True, 1e-9, 1)
    assert d[0, 0] == pytest.approx(1.0 / (1.0 - 0.2))
    radiation, d = _radiation(kin, mach, np.array([0.0, 0.0, 10.0]), np.zeros(3), 340.0, True, 1e-9, 1)
    assert d[0, 0] == pytest.approx(1.0)  # normal to the motion: Θ_e = Φ_e = 90°, D̄_h = D̄_l = 1
    assert radiation.high[0, 0] == pytest.approx(1.0) and radiation.low[0, 0] == pytest.approx(1.0)
    # the cell average of D̄_h over ±δ about z equals the mean of the point values
    avg, _ = _radiation(kin, mach, np.array([-3.0, 0.0, 10.0]), np.zeros(3), 340.0, False, 0.4, 2)
    points = [_radiation(kin, mach, np.array([-3.0 * np.cos(a), 3.0 * np.sin(a), 10.0]), np.zeros(3), 340.0, False,
                         1e-9, 1)[0].high[0, 0] for a in (-0.1, 0.1)]
    assert avg.high[0, 0] == pytest.approx(np.mean(points), rel=1e-9)


def _hover_rotor(n_psi=36, n_r=10, rotation_sign=1, n_blades=2):
    radius, omega = 1.0, 200.0
    edges = np.linspace(0.2, radius, n_r + 1)
    r, dr = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    disk = pd.DataFrame({
        "psi_rad": np.repeat(2 * np.pi * np.arange(n_psi) / n_psi, n_r), "r_m": np.tile(r, n_psi),
        "dr_m": np.tile(dr, n_psi), "chord_m": 0.08, "beta_rad": 0.0, "ut_mps": np.tile(omega * r, n_psi),
        "up_mps": 8.0, "alpha_eff_rad": np.radians(6.0),
    })
    geometry = RotorGeometry(name="r", n_blades=n_blades, radius_m=radius, chord_m=0.08, root_cutout_m=0.2,
                             twist_rad=0.0, thickness_ratio=0.12, lock_number=5.0, rotation_sign=rotation_sign)
    operating = OperatingPoint(omega_rad_s=omega, mu_x=0.0, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225,
                               speed_of_sound_mps=340.0, thrust_N=1.0)
    return disk, geometry, operating


BANDS = np.arange(-6, 12)
EDGE = BladeEdge(te_thickness_m=5e-4, tripped=False)


def test_hover_rotor_is_axisymmetric_and_mirror_symmetric():
    disk, geometry, operating = _hover_rotor()
    step = 2 * np.pi / 36
    obs = 20.0 * np.array([[np.cos(0.3), 0.0, -np.sin(0.3)],
                           [np.cos(0.3) * np.cos(step), np.cos(0.3) * np.sin(step), -np.sin(0.3)]])
    out = rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, EDGE)
    np.testing.assert_allclose(out["total"][0], out["total"][1], rtol=1e-10)
    disk_m, geometry_m, _ = _hover_rotor(rotation_sign=-1)
    mirrored = rotor_broadband_msp(disk_m, geometry_m, operating, obs * [1, -1, 1], MEDIUM, BANDS, EDGE)
    np.testing.assert_allclose(mirrored["total"], out["total"], rtol=1e-10)


def test_blade_count_and_on_axis_doppler():
    """B blades radiate B times one blade's energy (exact without Doppler); on the axis (M_r = 0)
    Doppler changes nothing but the dB interpolation of the source spectra (≤ 0.02 dB)."""
    axis = np.array([[0.0, 0.0, -15.0]])
    disk, geometry, operating = _hover_rotor(n_blades=2)
    two = rotor_broadband_msp(disk, geometry, operating, axis, MEDIUM, BANDS, EDGE, doppler=False)
    disk, geometry4, _ = _hover_rotor(n_blades=4)
    four = rotor_broadband_msp(disk, geometry4, operating, axis, MEDIUM, BANDS, EDGE, doppler=False)
    np.testing.assert_allclose(four["total"], 2.0 * two["total"], rtol=1e-12)
    with_doppler = rotor_broadband_msp(disk, geometry, operating, axis, MEDIUM, BANDS, EDGE)
    assert np.max(np.abs(10 * np.log10(with_doppler["total"] / two["total"]))) < 0.02


def test_doppler_interpolation_matches_direct_evaluation():
    """The rotation average with source spectra interpolated in dB on a 1/80-decade grid equals the
    direct evaluation of every mechanism at f_c/D to 0.02 dB (forward flight, oblique observer)."""
    disk, geometry, _ = _hover_rotor(n_psi=12)
    operating = OperatingPoint(omega_rad_s=200.0, mu_x=0.25, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225,
                               speed_of_sound_mps=340.0, thrust_N=1.0)
    disk = disk.assign(ut_mps=disk["ut_mps"] + 50.0 * np.sin(disk["psi_rad"]))
    observer = np.array([20.0, 5.0, -8.0])
    out = rotor_broadband_msp(disk, geometry, operating, observer[None], MEDIUM, BANDS, EDGE, n_azimuth=12)
    # direct: the same geometry, spectra evaluated at f_c / D (no interpolation)
    from nps.noise.spectra import third_octave_bands  # noqa: PLC0415
    psi, r = disk["psi_rad"].to_numpy().reshape(12, -1), disk["r_m"].to_numpy().reshape(12, -1)
    ut, up = disk["ut_mps"].to_numpy().reshape(12, -1), 8.0
    e_r = np.stack([np.cos(psi), np.sin(psi), 0 * psi], -1)
    e_t = np.stack([-np.sin(psi), np.cos(psi), 0 * psi], -1)
    e_n = np.array([0.0, 0.0, 1.0])
    w = np.hypot(ut, up)
    hub = np.array([-50.0, 0.0, 0.0])  # −μ_x Ω R along x_H
    kin = SourceKinematics(r[..., None] * e_r, e_r, -(ut[..., None] * e_t + up * e_n) / w[..., None],
                           200.0 * r[..., None] * e_t + hub)
    radiation, d = _radiation(kin, w / 340.0, observer, hub, 340.0, True, 2 * np.pi / 12, 16)
    sections = bpm.Sections(0.08, disk["dr_m"].to_numpy().reshape(12, -1), w, np.radians(6.0), 5e-4,
                            np.radians(14.0), False)
    direct = bpm.section_msp(third_octave_bands(BANDS)["center_hz"] / d[..., None], sections, radiation, MEDIUM)
    weight = (1.0 / d) / np.sum(1.0 / d, axis=0)  # reception-time average over azimuth: weights 1/D
    for name, msp in direct.items():
        expected = 2 * np.sum(np.where((ut > 0.0)[..., None], msp, 0.0) * weight[..., None], axis=(0, 1))
        assert np.max(np.abs(10 * np.log10(out[name][0] / expected))) < 0.02, name


def test_in_plane_doppler_shifts_a_rising_spectrum_down():
    """Ahead of the advancing blade the cardioid and the Doppler upshift coincide: a band on the rising
    side of the spectrum is fed from lower source frequencies, so its level drops with Doppler."""
    disk, geometry, operating = _hover_rotor()
    obs = np.array([[30.0, 0.0, -3.0]])
    on = rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, BladeEdge(tripped=True))
    off = rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, BladeEdge(tripped=True), doppler=False)
    assert on["tbl_te_suction"][0, 0] < off["tbl_te_suction"][0, 0]
    assert on["tbl_te_suction"][0, -1] > off["tbl_te_suction"][0, -1]


def test_reverse_flow_elements_radiate_nothing():
    disk, geometry, operating = _hover_rotor()
    obs = np.array([[10.0, 0.0, -5.0]])
    base = rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, EDGE)
    inner = disk["r_m"] < 0.3
    reversed_disk = disk.assign(ut_mps=np.where(inner, -disk["ut_mps"], disk["ut_mps"]))
    out = rotor_broadband_msp(reversed_disk, geometry, operating, obs, MEDIUM, BANDS, EDGE)
    assert np.all(out["tbl_te_suction"] < base["tbl_te_suction"])
    np.testing.assert_array_equal(out["tip"], base["tip"])


def test_rotor_input_errors():
    disk, geometry, operating = _hover_rotor()
    obs = np.array([[10.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="alpha_eff_rad"):
        rotor_broadband_msp(disk.drop(columns="alpha_eff_rad"), geometry, operating, obs, MEDIUM, BANDS)
    with pytest.raises(ValueError, match="n_azimuth"):
        rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, n_azimuth=7)
    with pytest.raises(ValueError, match="tripped"):
        rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, BladeEdge(tripped=(True, False)))
    with pytest.raises(ValueError, match="ψ-major"):
        rotor_broadband_msp(disk.sort_values("r_m", kind="stable"), geometry, operating, obs, MEDIUM, BANDS)
    with pytest.raises(ValueError, match="tip_shape"):
        BladeEdge(tip_shape="swept")


def test_disk_range_check_flags_rows():
    disk, _, _ = _hover_rotor()
    outside = disk_outside_bpm_range(disk, MEDIUM)
    speed = np.hypot(disk["ut_mps"], disk["up_mps"])
    np.testing.assert_array_equal(outside, (speed / 340.0 > bpm.DATA_MACH_RANGE[1]).to_numpy())


def test_rotation_average_converges_near_the_rotor_plane():
    """Forward flight (μ = 0.2), observers 0° and 2° above the disk plane: 36 azimuths (with the
    directivity cell average) agree with 360 to 0.5 dB in every band (directivity only: no Doppler). Point sampling of D̄_h alone
    missed a few-degree-wide peak at Θ_e → 180° and differed by up to 7.5 dB (docs/reference/bpm.md)."""
    n_psi, n_r, radius, omega, mu = 360, 10, 7.62, 28.0, 0.2
    edges = np.linspace(1.0, radius, n_r + 1)
    r = np.tile(0.5 * (edges[1:] + edges[:-1]), n_psi)
    psi = np.repeat(2 * np.pi * np.arange(n_psi) / n_psi, n_r)
    disk = pd.DataFrame({"psi_rad": psi, "r_m": r, "dr_m": np.tile(np.diff(edges), n_psi), "chord_m": 0.53,
                         "beta_rad": 0.03, "ut_mps": omega * r + mu * omega * radius * np.sin(psi), "up_mps": 5.0,
                         "alpha_eff_rad": np.radians(5.0)})
    geometry = RotorGeometry(name="m", n_blades=4, radius_m=radius, chord_m=0.53, root_cutout_m=1.0, twist_rad=0.0,
                             thickness_ratio=0.1, lock_number=8.0)
    operating = OperatingPoint(omega_rad_s=omega, mu_x=mu, mu_y=0.0, mu_z=0.0, density_kg_m3=1.2,
                               speed_of_sound_mps=340.0, thrust_N=5e4)
    el, az = np.radians([0.0, 2.0]), np.radians([67.0, 127.0])
    obs = 150.0 * np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)
    coarse, fine = (rotor_broadband_msp(disk, geometry, operating, obs, MEDIUM, BANDS, EDGE, n_azimuth=n,
                                        doppler=False)["total"] for n in (36, 360))
    assert np.max(np.abs(10 * np.log10(coarse / fine))) < 0.5
