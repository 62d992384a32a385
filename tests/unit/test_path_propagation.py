"""Propagation along turning, decelerating paths (nps.mission.propagation: heading per segment, hemispheres blended
between states): a turned path equals the same path along x with the receivers turned, a blend is the weighted dB
level, and a decelerating point source is heard with the closed-form spreading and Doppler shift."""

import numpy as np
import pytest
from scipy.optimize import brentq

from nps.mission.propagation import Ground, Hemisphere, PropagationError, Trajectory, propagate, turn_about_z
from nps.noise.spectra import LEVEL_FLOOR_DB

from test_footprint import AZ, BANDS, C, EL, omnidirectional


def directional(seed: int, velocity=(40.0, 0.0, -3.0)) -> Hemisphere:
    """A hemisphere with levels varying with direction and band (no symmetry a rotation could hide behind)."""
    h = omnidirectional(90.0, velocity)
    rng = np.random.default_rng(seed)
    levels = 70.0 + 10.0 * rng.random(h.levels_db.shape)
    return Hemisphere(EL, AZ, BANDS, levels, h.radius_m, h.velocity_mps, C)


def test_turned_path_equals_the_path_along_x_with_receivers_turned():
    """Heading χ: flying along (cos χ, sin χ) with the hemisphere turned to heading χ (frames R_z(−χ)) is flying
    along +x with every receiver turned by −χ about the start point (same spreading, Doppler, ground): 1e-9 dB."""
    chi = np.radians(57.0)
    rot = np.array([[np.cos(chi), -np.sin(chi), 0.0], [np.sin(chi), np.cos(chi), 0.0], [0.0, 0.0, 1.0]])
    t = np.array([0.0, 40.0])
    along_x = np.array([[0.0, 0.0, 150.0], [1600.0, 0.0, 30.0]])
    rng = np.random.default_rng(3)
    rec_x = np.stack([rng.uniform(-500, 2000, 40), rng.uniform(-800, 800, 40), np.full(40, 1.2)], axis=-1)
    times = np.arange(0.0, 50.0, 0.5)
    hemi = [directional(1)]
    straight = propagate(hemi, Trajectory(t, along_x, np.array([0]), (None,)), rec_x, times, C, Ground("hard"))
    frames = turn_about_z(chi)[None]
    turned = propagate(hemi, Trajectory(t, along_x @ rot.T, np.array([0]), (None,), hemisphere_frames=frames),
                       rec_x @ rot.T, times, C, Ground("hard"))
    heard = straight.la_db > LEVEL_FLOOR_DB
    assert heard.sum() > 1000
    np.testing.assert_allclose(turned.la_db, straight.la_db, atol=1e-9)
    # a heading that does not follow the track turns the directivity: the levels change
    wrong = propagate(hemi, Trajectory(t, along_x @ rot.T, np.array([0]), (None,)), rec_x @ rot.T, times, C,
                      Ground("hard"))
    assert np.abs(wrong.la_db - straight.la_db)[heard].max() > 1.0


def test_blend_of_two_states_is_the_weighted_level():
    """Segment blending (1 − w) L_a + w L_b: states 8 dB apart everywhere, w = 0.25, give L_a + 2 dB (same motion,
    so the same direction, spreading and Doppler): 1e-9 dB; w = 0 is state a bit for bit."""
    a = directional(2)
    b = Hemisphere(EL, AZ, BANDS, a.levels_db + 8.0, a.radius_m, a.velocity_mps, C)
    t = np.array([0.0, 30.0])
    p = np.array([[-600.0, 0.0, 120.0], [600.0, 0.0, 30.0]])
    rec = np.array([[0.0, 0.0, 1.2], [200.0, 300.0, 1.2], [-300.0, -150.0, 10.0]])
    times = np.arange(0.0, 40.0, 0.5)
    base = propagate([a, b], Trajectory(t, p, np.array([0]), (None,)), rec, times, C, Ground("none"), store_bands=True)
    blend = propagate([a, b], Trajectory(t, p, np.array([0]), (None,), next_hemisphere_index=np.array([1]),
                                         hemisphere_weight=np.array([0.25])), rec, times, C, Ground("none"),
                      store_bands=True)
    zero = propagate([a, b], Trajectory(t, p, np.array([0]), (None,), next_hemisphere_index=np.array([1]),
                                        hemisphere_weight=np.array([0.0])), rec, times, C, Ground("none"))
    heard = base.la_db > LEVEL_FLOOR_DB
    np.testing.assert_allclose(blend.la_db[heard], base.la_db[heard] + 2.0, atol=1e-9)
    assert np.array_equal(zero.la_db, base.la_db)


def test_decelerating_source_matches_the_closed_form():
    """A point source of 90 dB at 50 m (1 kHz band) decelerating from 60 to 20 m/s (a = −1 m/s²) in level flight
    150 m up, flown as 0.25-s chords blended between hemispheres at 60, 40, 20 m/s by speed: the received band
    energy equals 90 − 20 log10(r_e/50) and the Doppler shift −10 log10(1 − M(τ)·n) band numbers, both at the
    exact emission time τ of the accelerated motion (|x − X(τ)| = c (t − τ), X = x0 + v0 τ + a τ²/2), within
    0.01 dB and 0.005 band (the chords' velocity differs from the instantaneous one by up to a Δt/2)."""
    v0, acc, h, span = 60.0, -1.0, 150.0, 40.0
    knots = np.arange(0.0, span + 1e-9, 0.25)
    pos = np.stack([v0 * knots + 0.5 * acc * knots**2 - 1200.0, np.zeros_like(knots), np.full_like(knots, h)], -1)
    speeds = (60.0, 40.0, 20.0)
    hemis = [omnidirectional(90.0, (v, 0.0, 0.0)) for v in speeds]
    mid_speed = v0 + acc * 0.5 * (knots[1:] + knots[:-1])
    first = np.where(mid_speed > 40.0, 0, 1)
    weight = np.where(mid_speed > 40.0, (60.0 - mid_speed) / 20.0, (40.0 - mid_speed) / 20.0)
    traj = Trajectory(knots, pos, first, (None,) * first.size, next_hemisphere_index=first + 1,
                      hemisphere_weight=weight)
    receivers = np.array([[0.0, 0.0, 0.0], [-400.0, 250.0, 0.0], [300.0, -100.0, 0.0]])
    times = np.arange(2.0, 40.0, 1.0)
    hist = propagate(hemis, traj, receivers, times, C, Ground("none"), store_bands=True)
    energy = (10.0 ** (hist.bands_db / 10.0) * (hist.bands_db > LEVEL_FLOOR_DB)).sum(axis=-1)
    b0 = int(np.flatnonzero(BANDS == 0)[0])
    checked = 0
    for i, x in enumerate(receivers):
        for j, t in enumerate(times):
            def lag(tau):
                return np.linalg.norm(x - (pos[0] + np.array([v0 * tau + 0.5 * acc * tau**2, 0.0, 0.0]))) - C * (t - tau)
            if lag(0.0) > 0.0:  # heard before the path starts
                continue
            tau = brentq(lag, 0.0, t)
            if tau > span - 0.25:
                continue
            r = x - (pos[0] + np.array([v0 * tau + 0.5 * acc * tau**2, 0.0, 0.0]))
            re = np.linalg.norm(r)
            mach = (v0 + acc * tau) * r[0] / re / C
            assert 10.0 * np.log10(energy[i, j]) == pytest.approx(90.0 - 20.0 * np.log10(re / 50.0), abs=0.01)
            e0, e1 = 10.0 ** (hist.bands_db[i, j, b0] / 10.0), 10.0 ** (hist.bands_db[i, j, b0 + 1] / 10.0)
            e_lo = 10.0 ** (hist.bands_db[i, j, b0 - 1] / 10.0)
            delta = -10.0 * np.log10(1.0 - mach)
            shift = e1 / (e0 + e1) if delta >= 0.0 else -e_lo / (e0 + e_lo)
            assert shift == pytest.approx(delta, abs=0.005)
            checked += 1
    assert checked > 60


def test_bad_state_fields_are_refused():
    t, p = np.array([0.0, 1.0]), np.array([[0.0, 0.0, 10.0], [1.0, 0.0, 10.0]])
    with pytest.raises(PropagationError, match="go together"):
        Trajectory(t, p, np.array([0]), (None,), hemisphere_weight=np.array([0.5]))
    with pytest.raises(PropagationError, match="within \\[0, 1\\]"):
        Trajectory(t, p, np.array([0]), (None,), next_hemisphere_index=np.array([0]), hemisphere_weight=np.array([1.5]))
    with pytest.raises(PropagationError, match="hemisphere_frames"):
        Trajectory(t, p, np.array([0]), (None,), hemisphere_frames=np.full((1, 3, 3), 0.5))
    with pytest.raises(PropagationError, match="next_hemisphere_index must lie"):
        propagate([omnidirectional(90.0, (1.0, 0.0, 0.0))],
                  Trajectory(t, p, np.array([0]), (None,), next_hemisphere_index=np.array([3]),
                             hemisphere_weight=np.array([0.5])), np.zeros((1, 3)), np.array([0.5]), C)
