"""Noise along a sampled flight path (nps.mission.path_noise): steady straight legs flown as samples give the mission
footprint of the same legs, and the hemisphere frames put each state's path axes on the sample's."""

import numpy as np
import pytest

from nps.mission.footprint import FootprintError, GroundGrid, mission_footprint
from nps.mission.path_noise import PathSamples, hemisphere_frames, path_axes, path_footprint
from nps.mission.trajectory import FlightPath, Leg

from test_footprint import C, omnidirectional
from test_path_propagation import directional


def samples_of(path: FlightPath, dt_s: float) -> PathSamples:
    """``path`` sampled every ``dt_s`` (its knots included), one state per leg, heading 0, the legs' γ."""
    t = np.unique(np.concatenate([np.arange(0.0, path.knot_time_s[-1], dt_s), path.knot_time_s]))
    position = np.stack([np.interp(t, path.knot_time_s, path.knot_position_m[:, i]) for i in range(3)], axis=-1)
    leg = np.clip(np.searchsorted(path.knot_time_s, t, side="right") - 1, 0, len(path.legs) - 1)
    gamma = np.array([np.arctan2(l.climb_speed_mps, l.forward_speed_mps) for l in path.legs])
    return PathSamples(t, position, np.zeros(t.size), gamma[leg], gamma[leg], leg, leg, leg, np.zeros(t.size))


def test_steady_legs_as_samples_reproduce_the_mission_footprint():
    """Acceptance (issue 37): a path of straight steady legs reproduces the mission footprint of the same legs,
    SEL and L_Amax within 0.1 dB at every receiver, also the microphones' EPNL and per-leg metrics. Without air
    absorption the two are the same computation (1e-6 dB: the chords only subdivide the legs); with it each chord
    absorbs at its own mean height instead of its leg's (0.02 dB on the climbing leg here)."""
    path = FlightPath((0.0, 0.0, 150.0), (Leg("seg2", 40.0, 0.0, 50.0), Leg("seg1", 40.0, 4.0, 50.0)))
    hemis = {"seg2": directional(5, (40.0, 0.0, 0.0)), "seg1": directional(6, (40.0, 0.0, 4.0))}
    grid = GroundGrid((-500.0, 4500.0), (-1000.0, 1000.0), 250.0)
    mics = {"m1": (1000.0, 0.0, 1.2), "m2": (3000.0, 300.0, 1.2)}
    samples = samples_of(path, 0.5)
    for absorption, tolerance in ((False, 1e-6), (True, 0.1)):
        reference = mission_footprint(path, hemis, grid, mics, C, absorption=absorption)
        flown = path_footprint(samples, ["seg2", "seg1"], [hemis["seg2"], hemis["seg1"]], grid, mics, C,
                               absorption=absorption)
        for column in ("sel_db", "lamax_db", "leg0_sel_db", "leg1_sel_db"):
            assert np.abs(flown.grid[column] - reference.grid[column]).max() < tolerance
        for column in ("epnl_db", "sel_db", "leg0_epnl_db", "leg1_sel_db"):
            assert np.abs(flown.microphones[column] - reference.microphones[column]).max() < tolerance
    assert flown.segments == ["seg2", "seg1"]


def test_frames_put_the_canonical_path_axes_on_the_sample():
    """C Aᵀ maps the sample's flight direction, upward normal and starboard (E) onto the canonical ones at its γ_e:
    a level sample at heading 120° decelerating at γ_e = −6° sees its velocity along (cos γ_e, 0, sin γ_e) of the
    hemisphere, and so the specific force f = (g sin γ_e, g cos γ_e, 0) in path axes along the canonical z; 1e-12."""
    chi, gamma_e = np.radians(120.0), np.radians(-6.0)
    samples = PathSamples(np.array([0.0, 1.0]), np.array([[0.0, 0.0, 100.0], [-10.0, 17.3, 100.0]]),
                          np.full(2, chi), np.zeros(2), np.full(2, gamma_e), np.zeros(2, int), np.zeros(2, int),
                          np.ones(2, int), np.zeros(2))
    frames = hemisphere_frames(samples)
    actual = path_axes(chi, 0.0)
    np.testing.assert_allclose(frames[0] @ actual[:, 0], [np.cos(gamma_e), 0.0, np.sin(gamma_e)], atol=1e-12)
    np.testing.assert_allclose(frames[0] @ actual[:, 1], [-np.sin(gamma_e), 0.0, np.cos(gamma_e)], atol=1e-12)
    np.testing.assert_allclose(frames[0] @ actual[:, 2], [0.0, -1.0, 0.0], atol=1e-12)
    specific_force = actual @ np.array([np.sin(gamma_e), np.cos(gamma_e), 0.0])  # E, per g
    np.testing.assert_allclose(frames[0] @ specific_force, [0.0, 0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(actual[:, 2], [np.sin(chi), -np.cos(chi), 0.0], atol=1e-12)  # starboard


def test_bad_samples_are_refused():
    with pytest.raises(FootprintError, match="heading_rad"):
        PathSamples(np.array([0.0, 1.0]), np.zeros((2, 3)), np.array([0.0, np.nan]), np.zeros(2), np.zeros(2),
                    np.zeros(2), np.zeros(2), np.zeros(2), np.zeros(2))
    samples = PathSamples(np.array([0.0, 1.0]), np.array([[0.0, 0.0, 10.0], [1.0, 0.0, 10.0]]), np.zeros(2),
                          np.zeros(2), np.zeros(2), np.zeros(2, int), np.array([0, 2]), np.zeros(2, int), np.zeros(2))
    with pytest.raises(FootprintError, match="state must index the 1 states"):
        path_footprint(samples, ["a"], [omnidirectional(90.0, (1.0, 0.0, 0.0))],
                       GroundGrid((0.0, 10.0), (0.0, 10.0), 10.0), {}, C)
