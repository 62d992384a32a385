"""The compiled rotation average of nps.noise.broadband.rotor against a straightforward evaluation of the same
formulas: element by element, sub-azimuth by sub-azimuth, with RP-1218's directivity in its angle form (eq. B1,
B2; Θ_e = arccos, Φ_e = atan2), Doppler factors and reception-time weights 1/D, and the source spectra
interpolated in dB on the same log-frequency grid. The reference is the algorithm of the rotor BPM before it was
compiled (numpy, one observer at a time); the two agree to rounding (≤ 1e-12 dB, measured ≤ 1e-13 dB)."""

import math

import numpy as np
import pytest

from nps.noise.broadband import bpm
from nps.noise.broadband.rotor import SPECTRUM_STEP_DECADES, SourceKinematics, rotating_sources_msp
from nps.noise.spectra import third_octave_bands

MEDIUM = bpm.Medium(340.0, 1.5e-5)
BANDS = third_octave_bands(np.arange(-10, 12))["center_hz"]
N_AZ, N_EL, OMEGA, N_BLADES, N_SUB = 12, 8, 180.0, 3, 16
HUB_VELOCITY = np.array([-40.0, 5.0, 2.0])  # the hub's velocity relative to the air, H


def _rotor():
    """One blade of a forward-flight rotor in H: flapping, reverse flow near the root on the retreating side,
    stalled and laminar sections, a blunt trailing edge; sections, kinematics, tip source and radiating mask."""
    edges = np.linspace(0.15, 1.2, N_EL + 1)
    psi, r = np.meshgrid(2 * np.pi * np.arange(N_AZ) / N_AZ, 0.5 * (edges[1:] + edges[:-1]), indexing="ij")
    beta = 0.04 + 0.03 * np.cos(psi)
    ut = OMEGA * r + 40.0 * np.sin(psi)
    up = 6.0 + 3.0 * np.cos(psi) * r
    alpha = np.radians(4.0 + 11.0 * np.sin(psi) ** 2 * (r < 0.6))  # up to 15°: stalled inboard on the sides
    cp, sp, cb, sb = np.cos(psi), np.sin(psi), np.cos(beta), np.sin(beta)
    e_r = np.stack([cb * cp, cb * sp, sb], axis=-1)
    e_t = np.stack([-sp, cp, 0 * psi], axis=-1)
    e_n = np.stack([-sb * cp, -sb * sp, cb], axis=-1)

    def kinematics(radius, ut_, up_, e_r_, e_t_, e_n_):
        w = np.hypot(ut_, up_)[..., None]
        return SourceKinematics(radius[..., None] * e_r_, e_r_, -(ut_[..., None] * e_t_ + up_[..., None] * e_n_) / w,
                                OMEGA * radius[..., None] * e_t_ + HUB_VELOCITY)

    speed = np.hypot(ut, up)
    tripped = np.arange(N_EL) % 2 == 0  # laminar (LBL-VS) on every other station
    sections = bpm.Sections(0.06, np.diff(edges), speed, alpha, 4e-4, np.radians(12.0), tripped)
    tip = slice(N_EL - 1, None)
    ut_tip = ut[:, tip] + OMEGA * (1.25 - r[:, tip])
    tip_kin = kinematics(np.full(ut_tip.shape, 1.25), ut_tip, up[:, tip], e_r[:, tip], e_t[:, tip], e_n[:, tip])
    tip_source = (np.hypot(ut_tip, up[:, tip]), 0.8 * alpha[:, tip])
    return sections, kinematics(r, ut, up, e_r, e_t, e_n), tip_kin, tip_source, ut > 0.0


OBSERVERS = np.array([[12.0, 0.0, -0.3], [3.0, -9.0, -6.0], [-8.0, 2.0, -10.0], [0.5, 0.2, -14.0], [-11.0, -4.0, 0.2]])


def _directivity_angles(rhat, kin: SourceKinematics, a, e, mach):
    """D̄_h, D̄_l of eq. (B1), (B2) in RP-1218's angle form at one source and direction r̂."""
    normal = np.cross(kin.flow_unit[a, e], kin.span_unit[a, e])
    theta = math.acos(min(max(float(rhat @ kin.flow_unit[a, e]), -1.0), 1.0))
    phi = math.atan2(abs(float(rhat @ normal)), float(rhat @ kin.span_unit[a, e]))
    cos_t, sin2_phi = math.cos(theta), math.sin(phi) ** 2
    high = 2.0 * math.sin(0.5 * theta) ** 2 * sin2_phi / ((1.0 + mach * cos_t) * (1.0 + 0.2 * mach * cos_t) ** 2)
    return high, math.sin(theta) ** 2 * sin2_phi / (1.0 + mach * cos_t) ** 4


def _reference_group(spectra, energy, log_grid, kin, mach, active, low_rows, observer, doppler):
    """Band MSP (n_g, n_band) of one blade's sources at one observer: the rotation average element by element
    (``spectra``: ln MSP on ``log_grid`` with Doppler, MSP at the band centres without; rows without ``energy``
    and inactive sources radiate nothing)."""
    n_az, n_src = mach.shape
    cell = 2 * np.pi / n_az
    total = np.zeros((spectra.shape[0], BANDS.size))
    d = np.ones((n_az, n_src))
    terms = np.zeros((n_az, n_src) + total.shape)
    for a in range(n_az):
        for e in range(n_src):
            high = low = 0.0
            for j in range(N_SUB):  # the source turned by +δ about z_H: the observer by −δ
                angle = -((j + 0.5) / N_SUB - 0.5) * cell
                turned = np.array([math.cos(angle) * observer[0] - math.sin(angle) * observer[1],
                                   math.sin(angle) * observer[0] + math.cos(angle) * observer[1], observer[2]])
                rvec = turned - kin.position_m[a, e]
                h, lo = _directivity_angles(rvec / np.linalg.norm(rvec), kin, a, e, mach[a, e])
                high, low = high + h / N_SUB, low + lo / N_SUB
            rvec = observer - kin.position_m[a, e]
            dist = np.linalg.norm(rvec)
            if doppler:
                rhat = rvec / dist
                d[a, e] = (1.0 - rhat @ HUB_VELOCITY / MEDIUM.speed_of_sound_mps) / (
                    1.0 - rhat @ kin.velocity_mps[a, e] / MEDIUM.speed_of_sound_mps)
            for g in range(spectra.shape[0]):
                if doppler:
                    source = np.exp(np.interp(np.log10(BANDS / d[a, e]), log_grid, spectra[g, a, e]))
                else:
                    source = spectra[g, a, e]
                factor = (low if low_rows[g, a, e] else high) / dist**2
                terms[a, e, g] = source * factor if active[a, e] and energy[g, a, e] else 0.0
    weight = (1.0 / d) / np.sum(1.0 / d, axis=0)
    return N_BLADES * np.sum(terms * weight[..., None, None], axis=(0, 1))


def _reference(doppler: bool) -> dict[str, np.ndarray]:
    sections, kin, tip_kin, (tip_speed, tip_alpha), active = _rotor()
    c0 = MEDIUM.speed_of_sound_mps
    if doppler:  # the grid of rotating_sources_msp: every f_c/D, one step beyond
        m_src = max(np.max(np.linalg.norm(k.velocity_mps, axis=-1)) for k in (kin, tip_kin)) / c0
        m_obs = np.linalg.norm(HUB_VELOCITY) / c0
        log_f0 = np.log10(BANDS.min() * (1 - m_src) / (1 + m_obs)) - SPECTRUM_STEP_DECADES
        log_f1 = np.log10(BANDS.max() * (1 + m_src) / (1 - m_obs)) + SPECTRUM_STEP_DECADES
        n_grid = int(np.ceil((log_f1 - log_f0) / SPECTRUM_STEP_DECADES)) + 1
        log_grid = log_f0 + SPECTRUM_STEP_DECADES * np.arange(n_grid)
    else:
        log_grid = np.log10(BANDS)
    unit = bpm.Directivity(1.0, 1.0, 1.0)
    section = bpm.section_msp(10.0**log_grid, sections, unit, MEDIUM)
    names = bpm.COMPONENTS[:-1]
    msp = np.stack([np.broadcast_to(section[n], (N_AZ, N_EL, log_grid.size)) for n in names])
    tip = bpm.tip_vortex_msp(10.0**log_grid, 0.06, tip_speed, tip_alpha, unit, MEDIUM)[None]
    low_rows = np.zeros(msp.shape[:3], dtype=bool)
    low_rows[names.index("separation")] = bpm.is_stalled(sections, MEDIUM)
    assert low_rows.any() and (~active).any() and all(np.any(msp[g] > 0) for g in range(len(names)))
    out = {name: np.zeros((len(OBSERVERS), BANDS.size)) for name in bpm.COMPONENTS}
    for names_, spectra, k, mach, on, low in (
            (names, msp, kin, np.asarray(sections.speed_mps) / c0, active, low_rows),
            (("tip",), tip, tip_kin, tip_speed / c0, np.ones(tip_speed.shape, bool), np.zeros(tip.shape[:3], bool))):
        ln = np.log(np.maximum(spectra, 1e-300)) if doppler else spectra
        for i, observer in enumerate(OBSERVERS):
            total = _reference_group(ln, np.any(spectra > 0.0, axis=-1), log_grid, k, mach, on, low, observer, doppler)
            for g, name in enumerate(names_):
                out[name][i] = total[g]
    return out


@pytest.mark.parametrize("doppler", [True, False])
def test_compiled_rotation_average_equals_the_element_by_element_evaluation(doppler):
    sections, kin, tip_kin, (tip_speed, tip_alpha), active = _rotor()
    fast = rotating_sources_msp(sections, kin, tip_kin, 0.06, tip_speed, tip_alpha, "flat", OBSERVERS, HUB_VELOCITY,
                                BANDS, N_BLADES, MEDIUM, active=active, doppler=doppler, n_sub=N_SUB)
    reference = _reference(doppler)
    for name in bpm.COMPONENTS:
        assert np.all(reference[name] > 0.0), name
        assert np.max(np.abs(10.0 * np.log10(fast[name] / reference[name]))) <= 1e-12, name


def test_directivity_factors_equal_the_angle_form():
    """D̄_h, D̄_l from (cos Θ_e, sin²Φ_e) equal eq. (B1), (B2) written with the angles (2 sin²(Θ_e/2),
    sin²Θ_e)."""
    rng = np.random.default_rng(3)
    theta, phi, mach = rng.uniform(0, np.pi, 200), rng.uniform(0, np.pi, 200), rng.uniform(0, 0.8, 200)
    cos_t = np.cos(theta)
    high, low = bpm.directivity_factors(cos_t, np.sin(phi) ** 2, mach)
    np.testing.assert_allclose(high, 2 * np.sin(theta / 2) ** 2 * np.sin(phi) ** 2
                               / ((1 + mach * cos_t) * (1 + 0.2 * mach * cos_t) ** 2), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(low, np.sin(theta) ** 2 * np.sin(phi) ** 2 / (1 + mach * cos_t) ** 4, rtol=1e-12,
                               atol=1e-15)


def test_mechanisms_no_section_has_are_zero_with_the_sections_shape():
    """section_msp skips LBL-VS on tripped blades and bluntness on sharp ones: the same zeros, shape S + (n_f,)."""
    sections = bpm.Sections(0.1, 0.05, np.linspace(40.0, 80.0, 6)[:, None] + np.zeros(4), np.radians(5.0), 0.0,
                            np.radians(14.0), True)
    radiation = bpm.directivity(2.0, np.pi / 2, np.pi / 2, 0.2)
    out = bpm.section_msp(BANDS, sections, radiation, MEDIUM)
    np.testing.assert_array_equal(out["lbl_vs"], bpm.lbl_vs_msp(BANDS, sections, radiation, MEDIUM))
    np.testing.assert_array_equal(out["bluntness"], bpm.bluntness_msp(BANDS, sections, radiation, MEDIUM))
    assert out["lbl_vs"].shape == out["bluntness"].shape == out["tbl_te_suction"].shape == (6, 4, BANDS.size)
