"""Hemisphere propagation (nps.mission.propagation): spreading, absorption, Doppler, ground, symmetry."""

import numpy as np
import pytest
from scipy.special import wofz

from nps.core.atmosphere import absorption_db_per_m, isa
from nps.mission.propagation import (
    Ground,
    Hemisphere,
    PropagationError,
    Trajectory,
    normalised_impedance,
    propagate,
    spherical_reflection_coefficient,
)
from nps.noise.spectra import third_octave_bands

BANDS = np.arange(-20, 11)
EL = np.linspace(-90.0, 0.0, 10)
AZ = np.arange(36) * 10.0
C = 340.0
ATM = isa(0.0)


def _hemisphere(levels=80.0, velocity=(0.0, 0.0, 0.0), radius=50.0):
    lv = np.broadcast_to(np.asarray(levels, float), (EL.size, AZ.size, BANDS.size)).copy()
    return Hemisphere(EL, AZ, BANDS, lv, radius, np.asarray(velocity, float), C)


def _level_flight(height, speed, duration=200.0, start=-100.0):
    t = np.array([0.0, duration])
    p = np.array([[start * speed, 0.0, height], [(start + duration) * speed, 0.0, height]])
    return Trajectory(t, p, np.array([0]), (ATM,))


def _alpha():
    centres = third_octave_bands(BANDS)["center_hz"]
    return absorption_db_per_m(centres, ATM.temperature_k, ATM.relative_humidity_pct, ATM.pressure_pa)


def test_hover_spreading_and_absorption():
    """Acceptance (b): hover at h; every receiver's band level = hemisphere level − 20 log10(d/r_h)
    − α d, to 0.05 dB (no ground), for a directional hemisphere read at the receiver's direction."""
    el_grid, az_grid = np.meshgrid(EL, AZ, indexing="ij")
    levels = 80.0 + 0.1 * el_grid[..., None] + 3.0 * np.cos(np.radians(az_grid))[..., None] + 0.0 * BANDS
    hemi = Hemisphere(EL, AZ, BANDS, levels, 50.0, np.zeros(3), C)
    h = 120.0
    traj = Trajectory(np.array([0.0, 60.0]), np.array([[0.0, 0.0, h], [0.0, 0.0, h]]), np.array([0]), (ATM,))
    # receivers in grid directions: azimuth 30 deg, elevation -40 deg and straight below
    rec = []
    for az, el in ((30.0, -40.0), (200.0, -60.0), (0.0, -90.0)):
        d = np.array([-np.cos(np.radians(az)) * np.cos(np.radians(el)), -np.sin(np.radians(az)) * np.cos(np.radians(el)),
                      np.sin(np.radians(el))])
        rec.append(np.array([0.0, 0.0, h]) + d * h / -d[2])
    rec = np.array(rec)
    out = propagate([hemi], traj, rec, np.array([30.0]), C, Ground("none"), store_bands=True)
    dist = np.linalg.norm(rec - [0.0, 0.0, h], axis=1)
    expected_dir = np.array([80.0 - 4.0 + 3.0 * np.cos(np.radians(30.0)), 80.0 - 6.0 + 3.0 * np.cos(np.radians(200.0)), 80.0 - 9.0 + 3.0])
    expected = expected_dir[:, None] - 20.0 * np.log10(dist[:, None] / 50.0) - _alpha() * dist[:, None]
    assert np.abs(out.bands_db[:, 0, :] - expected).max() < 0.05


def test_hard_ground_six_and_three_db():
    """Acceptance (d): on a hard ground a receiver at z = 0 gets +6.02 dB in every band (coherent,
    Δr = 0); a receiver 0.1 m up gets +6 dB in the lowest bands (kΔr ≪ 1), one 1.2 m up +3 dB (within 0.1)
    in the high bands (incoherent limit 1 + a², a ≈ 1); ``coherent=False`` gives +3 dB everywhere."""
    hemi = _hemisphere()
    traj = _level_flight(150.0, 0.0)
    rec = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, 1.2], [0.0, 0.0, 0.1]])
    t = np.array([100.0])
    free = propagate([hemi], traj, rec, t, C, Ground("none"), store_bands=True).bands_db[:, 0]
    hard = propagate([hemi], traj, rec, t, C, Ground("hard"), store_bands=True).bands_db[:, 0]
    gain = hard - free
    assert np.abs(gain[0] - 20.0 * np.log10(2.0)).max() < 1e-9
    a = 148.8 / 151.2
    assert np.abs(gain[2, :4] - 10.0 * np.log10((1.0 + 149.9 / 150.1) ** 2)).max() < 0.01  # kΔr < 0.07
    assert np.abs(gain[1, -3:] - 10.0 * np.log10(1.0 + a * a)).max() < 0.1
    inc = propagate([hemi], traj, rec[:2], t, C, Ground("hard", coherent=False), store_bands=True).bands_db[:, 0] - free[:2]
    assert np.abs(inc - 10.0 * np.log10(1.0 + np.array([1.0, a * a]))[:, None]).max() < 1e-9


def test_symmetric_hemisphere_symmetric_footprint():
    """Acceptance (c): a hemisphere symmetric about the vertical plane of the track (L(az) =
    L(360 − az)) gives mirror-symmetric levels at receivers y and −y, in flight with climb."""
    el_grid, az_grid = np.meshgrid(EL, AZ, indexing="ij")
    levels = 75.0 + 5.0 * np.cos(np.radians(az_grid))[..., None] + 0.05 * el_grid[..., None] - 0.2 * BANDS
    hemi = Hemisphere(EL, AZ, BANDS, levels, 50.0, np.array([40.0, 0.0, 3.0]), C)
    t = np.array([0.0, 40.0])
    traj = Trajectory(t, np.array([[0.0, 0.0, 100.0], [1600.0, 0.0, 220.0]]), np.array([0]), (ATM,))
    x = np.linspace(-300.0, 1900.0, 12)
    y = np.linspace(60.0, 600.0, 7)
    xx, yy = np.meshgrid(x, y, indexing="ij")
    port = np.stack([xx.ravel(), yy.ravel(), np.full(xx.size, 1.2)], axis=1)
    starboard = port * [1.0, -1.0, 1.0]
    times = np.arange(0.0, 50.0, 0.5)
    a = propagate([hemi], traj, port, times, C, Ground("hard")).la_db
    b = propagate([hemi], traj, starboard, times, C, Ground("hard")).la_db
    assert np.abs(a - b).max() < 1e-9
    assert np.ptp(a.max(axis=1)) > 10.0  # the footprint is not trivially flat


def test_doppler_shift_and_emission_time():
    """An approaching source (M = 0.2) shifts a 1 kHz band by −10 log10(1 − M) = 0.969 bands:
    3.1 % of the energy stays in the 1 kHz band, 96.9 % goes to 1.25 kHz; the total energy equals
    the hemisphere's at the emission distance less the absorption at the received frequency;
    the ray heard at t left at τ = t − r_e/c."""
    v = 0.2 * C
    levels = np.full((EL.size, AZ.size, BANDS.size), -100.0)
    levels[..., BANDS == 0] = 90.0
    hemi = Hemisphere(EL, AZ, BANDS, levels, 50.0, np.array([v, 0.0, 0.0]), C)
    traj = Trajectory(np.array([0.0, 20.0]), np.array([[0.0, 0.0, 100.0], [20.0 * v, 0.0, 100.0]]), np.array([0]), (ATM,))
    rec = np.array([[3000.0, 0.0, 100.0]])
    t = np.array([10.0])
    out = propagate([hemi], traj, rec, t, C, Ground("none"), store_bands=True)
    tau = (t[0] - 3000.0 / C) / (1.0 - 0.2)  # x_s(τ) = vτ, 3000 − vτ = c (t − τ)
    r_e = 3000.0 - v * tau
    msp = np.where(out.bands_db[0, 0] > -100.0, 10.0 ** (out.bands_db[0, 0] / 10.0), 0.0)
    delta = -10.0 * np.log10(0.8)
    centres = third_octave_bands(np.array([0, 1]))["center_hz"]
    a0, a1 = absorption_db_per_m(centres, ATM.temperature_k, ATM.relative_humidity_pct, ATM.pressure_pa)
    msp_free = msp * 10.0 ** ((a0 + delta * (a1 - a0)) * r_e / 10.0)  # α at the received band number δ
    total = 90.0 - 20.0 * np.log10(r_e * (1.0 - 0.2) / 50.0)  # |n − M_h| = 1 − M on the axis ahead
    assert 10.0 * np.log10(msp_free.sum()) == pytest.approx(total, abs=1e-6)
    assert msp_free[BANDS == 1][0] / msp_free.sum() == pytest.approx(delta, abs=1e-9)
    assert msp_free[BANDS == 0][0] / msp_free.sum() == pytest.approx(1.0 - delta, abs=1e-9)


def test_impedance_ground():
    """Delany-Bazley and Miki impedances at f/σ = 5 (1 kHz, 200 kPa s/m²); the spherical-wave Q
    equals scipy's Faddeeva-based value, tends to 1 on a very stiff ground and to the plane-wave
    R_p far from grazing at large k r_2."""
    z_db = normalised_impedance("delany_bazley", 1000.0, 200.0)
    assert z_db == pytest.approx(1.0 + 9.08 * 5.0**-0.75 + 11.9j * 5.0**-0.73)
    z_m = normalised_impedance("miki", 1000.0, 200.0)
    assert z_m == pytest.approx(1.0 + (5.50 + 8.43j) * 5.0**-0.632)
    sin_psi = np.array([0.01, 0.1, 0.5, 0.9])
    kr = np.array([50.0, 500.0, 5000.0, 50000.0])
    q = spherical_reflection_coefficient(sin_psi, kr, z_db)
    beta = 1.0 / z_db
    rp = (sin_psi - beta) / (sin_psi + beta)
    w = np.sqrt(0.5j * kr) * (sin_psi + beta)
    ref = rp + (1.0 - rp) * (1.0 + 1j * np.sqrt(np.pi) * w * wofz(w))
    assert np.abs(q - ref).max() < 1e-3
    assert abs(spherical_reflection_coefficient(0.3, 1000.0, 1e8) - 1.0) < 1e-6
    assert abs(spherical_reflection_coefficient(0.9, 1e7, z_db) - rp[3]) < 1e-3


def test_bad_input():
    with pytest.raises(PropagationError, match="ground.model"):
        Ground("grass")
    with pytest.raises(PropagationError, match="below the ground"):
        Trajectory(np.array([0.0, 1.0]), np.array([[0.0, 0.0, 10.0], [1.0, 0.0, -1.0]]), np.array([0]), (ATM,))
    with pytest.raises(PropagationError, match="receivers"):
        propagate([_hemisphere()], _level_flight(100.0, 10.0), np.array([[0.0, 0.0, -2.0]]), np.array([0.0]), C)
    with pytest.raises(PropagationError, match="levels_db"):
        Hemisphere(EL, AZ, BANDS, np.full((EL.size, AZ.size, BANDS.size), np.nan), 50.0, np.zeros(3), C)
