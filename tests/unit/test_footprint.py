"""Mission footprints (nps.mission.footprint): the line-source analytic check, exposure, contour areas."""

import numpy as np
import pytest

from nps.mission.footprint import FootprintError, GroundGrid, contour_areas, exposure_metrics, mission_footprint, touches_edge
from nps.mission.propagation import Ground, Hemisphere, Trajectory, propagate
from nps.noise.spectra import LEVEL_FLOOR_DB
from nps.mission.trajectory import FlightPath, Leg

EL = np.linspace(-90.0, 0.0, 19)
AZ = np.arange(72) * 5.0
BANDS = np.arange(-20, 11)
C = 340.0


def omnidirectional(level_db, velocity, radius=50.0):
    """Co-moving hemisphere of a steady omnidirectional source of ``level_db`` at emission distance
    ``radius``: an observer in direction d hears the ray emitted in n = M + s d (|n| = 1) from
    r_e = radius/s, so L_h(d) = level + 20 log10 s (1 kHz band only)."""
    m = np.asarray(velocity, float) / C
    el, az = np.meshgrid(np.radians(EL), np.radians(AZ), indexing="ij")
    d = np.stack([-np.cos(az) * np.cos(el), -np.sin(az) * np.cos(el), np.sin(el)], axis=-1)
    md = d @ m
    s = -md + np.sqrt(md**2 + 1.0 - m @ m)
    levels = np.full(EL.shape + AZ.shape + BANDS.shape, LEVEL_FLOOR_DB)
    levels[..., BANDS == 0] = (level_db + 20.0 * np.log10(s))[..., None]
    return Hemisphere(EL, AZ, BANDS, levels, radius, np.asarray(velocity, float), C)


def test_line_source_sel_and_lamax():
    """Acceptance (a): a steady omnidirectional source of 90 dB at 50 m (1 kHz band) in level
    flight at h = 150 m, V = 40 m/s, no absorption or ground: under the track SEL equals the
    closed-form finite line source 10 log10(P/(h V)·2 atan(X/h)) (P = p² r² of the source,
    ±X the path ends) within 0.2 dB, with Doppler shifts of up to half a band on; L_Amax equals
    the spherical-spreading level at distance h, 90 − 20 log10(150/50), within 0.02 dB."""
    h, v, duration = 150.0, 40.0, 200.0
    x_end = v * duration / 2
    traj = Trajectory(np.array([0.0, duration]), np.array([[-x_end, 0.0, h], [x_end, 0.0, h]]), np.array([0]), (None,))
    times = np.arange(0.0, duration + 30.0, 0.5)
    hist = propagate([omnidirectional(90.0, (v, 0.0, 0.0))], traj, np.array([[0.0, 0.0, 0.0]]), times, C, Ground("none"))
    m = exposure_metrics(hist.la_db, hist.segment, 1)
    closed = 10.0 * np.log10(10.0 ** 9.0 * 50.0**2 / (h * v) * 2.0 * np.arctan(x_end / h))
    assert m["sel_db"][0] == pytest.approx(closed, abs=0.2)
    assert m["lamax_db"][0] == pytest.approx(90.0 - 20.0 * np.log10(h / 50.0), abs=0.02)
    assert m["segment_sel_db"][0, 0] == m["sel_db"][0]


def test_exposure_per_segment_sums_to_mission():
    la = np.array([[70.0, 80.0, 75.0, LEVEL_FLOOR_DB], [60.0, 60.0, 60.0, 60.0]])
    seg = np.array([[0, 0, 1, -1], [1, 1, 1, 1]])
    m = exposure_metrics(la, seg, 2)
    e = 10 ** (m["segment_sel_db"] / 10).clip(0)
    assert 10 * np.log10(10 ** (m["segment_sel_db"][0, 0] / 10) + 10 ** (m["segment_sel_db"][0, 1] / 10)) == pytest.approx(m["sel_db"][0])
    assert m["segment_lamax_db"][0].tolist() == [80.0, 75.0]
    assert m["segment_sel_db"][1, 0] == LEVEL_FLOOR_DB and e.shape == (2, 2)
    assert m["sel_db"][1] == pytest.approx(60.0 + 10 * np.log10(4 * 0.5))


def test_contour_areas_and_grid():
    grid = GroundGrid((0.0, 100.0), (-50.0, 50.0), 10.0)
    assert grid.points().shape == (11 * 11, 3)
    values = np.where(np.abs(grid.points()[:, 1]) <= 20.0, 72.0, 50.0)
    assert contour_areas(values, 100.0).tolist() == [5 * 11 * 100.0] * 3 + [0.0, 0.0]
    assert touches_edge(values.reshape(11, 11)).tolist() == [True, True, True, False, False]
    peak = np.full((11, 11), 50.0)
    peak[5, 5] = 90.0
    assert not touches_edge(peak).any()
    with pytest.raises(FootprintError, match="spacing_m"):
        GroundGrid((0.0, 1.0), (0.0, 1.0), 0.0)


def test_mission_footprint_two_segments():
    """Two legs (level, then climb) with two hemispheres 10 dB apart: the per-leg SELs add up to
    the mission SEL, the footprint is left-right symmetric, the microphone under the level leg
    hears its maximum from leg 0, and a missing hemisphere is a clear error."""
    path = FlightPath((0.0, 0.0, 150.0), (Leg("seg2", 40.0, 0.0, 50.0), Leg("seg1", 40.0, 4.0, 50.0)))
    hemis = {"seg2": omnidirectional(90.0, (40.0, 0.0, 0.0)), "seg1": omnidirectional(80.0, (40.0, 0.0, 4.0))}
    grid = GroundGrid((-500.0, 4500.0), (-1000.0, 1000.0), 250.0)
    fp = mission_footprint(path, hemis, grid, {"m1": (1000.0, 0.0, 1.2)}, C)
    g = fp.grid
    total = 10 * np.log10(10 ** (g["leg0_sel_db"] / 10) + 10 ** (g["leg1_sel_db"] / 10))
    assert np.abs(total - g["sel_db"]).max() < 1e-9
    mirror = g.set_index(["x_m", "y_m"])["sel_db"]
    assert np.abs(mirror.to_numpy() - mirror.reindex(list(zip(g["x_m"], -g["y_m"]))).to_numpy()).max() < 1e-9
    mic = fp.microphones.iloc[0]
    assert mic["lamax_db"] > 70.0 and np.isfinite(mic["epnl_db"])
    assert mic["leg0_epnl_db"] > mic["leg1_epnl_db"] and mic["leg0_epnl_db"] <= mic["epnl_db"] + 1e-9
    h = fp.histories
    assert h["leg"].iloc[int(h["la_db"].argmax())] == 0 and set(h["leg"]) == {-1, 0, 1}
    assert set(fp.areas["metric"]) == {"sel_db", "lamax_db"}
    with pytest.raises(FootprintError, match="seg1"):
        mission_footprint(path, {"seg2": hemis["seg2"]}, grid, {}, C)
