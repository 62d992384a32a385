"""Terrain under the receivers (nps.mission.terrain, propagation's ground plane at the local elevation, the path
files' ``receivers.terrain``): bilinear elevations are exact on a plane; flying over a plateau is flying over flat
ground with everything lowered by the plateau's height; a receiver on a hill under a hovering source hears the
closed-form spreading; a terrain that misses a receiver, or a path below the terrain, is refused in one line."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from nps.app.config import ConfigError, load_path
from nps.mission.footprint import GroundGrid, trajectory_footprint
from nps.mission.propagation import Ground, PropagationError, Trajectory, propagate
from nps.mission.terrain import Terrain, TerrainError
from nps.noise.spectra import LEVEL_FLOOR_DB

from test_footprint import C, omnidirectional
from test_path_propagation import directional

REPO = Path(__file__).resolve().parents[2]


def test_bilinear_elevation_is_exact_on_a_plane():
    x, y = np.array([-100.0, 0.0, 250.0, 400.0]), np.array([-50.0, 80.0, 300.0])
    plane = lambda px, py: 20.0 + 0.05 * px + 0.02 * py  # noqa: E731
    terrain = Terrain(x, y, plane(*np.meshgrid(x, y)))
    rng = np.random.default_rng(0)
    px, py = rng.uniform(-100.0, 400.0, 200), rng.uniform(-50.0, 300.0, 200)
    np.testing.assert_allclose(terrain.elevation_m(px, py), plane(px, py), rtol=0, atol=1e-12)
    with pytest.raises(TerrainError, match="outside the terrain grid"):
        terrain.elevation_m(np.array([401.0]), np.array([0.0]))
    with pytest.raises(TerrainError, match="height_m: expected 3 rows"):
        Terrain(x, y, np.zeros((4, 3)))
    with pytest.raises(TerrainError, match="elevations >= 0"):
        Terrain(x, y, -np.ones((3, 4)))


def test_plateau_is_flat_ground_lowered_by_its_height():
    """Path, receivers and ground raised by 40 m give the flat-ground levels (hard ground: the image source is
    mirrored in the plateau) within 1e-9 dB; ignoring the plateau's elevation (image in z = 0) changes them."""
    t = np.array([0.0, 40.0])
    path = np.array([[0.0, 0.0, 150.0], [1600.0, 0.0, 30.0]])
    rng = np.random.default_rng(5)
    rec = np.stack([rng.uniform(-500, 2000, 30), rng.uniform(-800, 800, 30), np.full(30, 1.2)], axis=-1)
    times = np.arange(0.0, 50.0, 0.5)
    hemi = [directional(4)]
    lift = np.array([0.0, 0.0, 40.0])
    flat = propagate(hemi, Trajectory(t, path, np.array([0]), (None,)), rec, times, C, Ground("hard"))
    plateau = propagate(hemi, Trajectory(t, path + lift, np.array([0]), (None,)), rec + lift, times, C, Ground("hard"),
                        ground_elevation_m=np.full(30, 40.0))
    heard = flat.la_db > LEVEL_FLOOR_DB
    assert heard.sum() > 1000
    np.testing.assert_allclose(plateau.la_db, flat.la_db, atol=1e-9)
    datum = propagate(hemi, Trajectory(t, path + lift, np.array([0]), (None,)), rec + lift, times, C, Ground("hard"))
    assert np.abs(datum.la_db - flat.la_db)[heard].max() > 1.0
    with pytest.raises(PropagationError, match="at most its z"):
        propagate(hemi, Trajectory(t, path, np.array([0]), (None,)), rec, times, C, ground_elevation_m=np.full(30, 2.0))


def test_receiver_on_a_hill_under_a_hovering_source_hears_the_spreading():
    """A hovering omnidirectional source (90 dB at 50 m, 1 kHz) 150 m above the datum, no ground: a receiver 1.2 m
    above a 30 m hill right below it is 20 log10(148.8 / 118.8) dB louder than one on flat ground (1e-9 dB)."""
    hover = Trajectory(np.array([0.0, 60.0]), np.array([[0.0, 0.0, 150.0], [0.0, 0.0, 150.0]]), np.array([0]), (None,))
    hemi = [omnidirectional(90.0, (0.0, 0.0, 0.0))]
    x = np.array([-200.0, 0.0, 200.0])
    hill = Terrain(x, x, np.array([[0.0, 0.0, 0.0], [0.0, 30.0, 0.0], [0.0, 0.0, 0.0]]))
    footprint = trajectory_footprint(hover, hemi, np.array([0]), ["hover"], GroundGrid((-200.0, 200.0), (-200.0, 200.0), 200.0),
                                     {"top": (0.0, 0.0, 1.2)}, C, Ground("none"), terrain=hill)
    flat = trajectory_footprint(hover, hemi, np.array([0]), ["hover"], GroundGrid((-200.0, 200.0), (-200.0, 200.0), 200.0),
                                {"top": (0.0, 0.0, 1.2)}, C, Ground("none"))
    top = footprint.grid.set_index(["x_m", "y_m"]).loc[(0.0, 0.0)]
    assert top["z_m"] == pytest.approx(31.2, abs=1e-12)
    expected = 20.0 * np.log10(148.8 / 118.8)
    assert top["lamax_db"] - flat.grid.set_index(["x_m", "y_m"]).loc[(0.0, 0.0), "lamax_db"] == pytest.approx(expected, abs=1e-9)
    assert footprint.microphones["lamax_db"].iloc[0] - flat.microphones["lamax_db"].iloc[0] == pytest.approx(expected, abs=1e-9)
    corner = footprint.grid.set_index(["x_m", "y_m"]).loc[(200.0, 200.0)]
    assert corner["lamax_db"] == flat.grid.set_index(["x_m", "y_m"]).loc[(200.0, 200.0), "lamax_db"]  # no hill there


def _path_with_terrain(tmp_path, terrain, microphones=None):
    document = yaml.safe_load((REPO / "config/paths/helicopter_approach_6deg.yaml").read_text())
    document["receivers"]["terrain"] = terrain
    if microphones is not None:
        document["receivers"]["microphones"] = microphones
    path = tmp_path / "helicopter_approach_6deg.yaml"
    path.write_text(yaml.safe_dump(document))
    return path


COVER = {"x_m": [-3500.0, 1000.0], "y_m": [-2000.0, 2500.0], "height_m": [[0.0, 10.0], [5.0, 15.0]]}


def test_terrain_is_read_and_checked(tmp_path):
    assert load_path(_path_with_terrain(tmp_path, COVER), 0.5)["receivers"]["terrain"] == COVER
    cases = [
        ({**COVER, "x_m": [-3000.0, 1000.0]}, None,
         "receivers.terrain: expected a grid covering the receiver grid x -3500..1000 m, y -2000..2500 m"),
        ({**COVER, "height_m": [[0.0, 10.0, 3.0], [5.0, 15.0, 3.0]]}, None, "receivers.terrain.height_m: expected 2 rows"),
        ({**COVER, "x_m": [1000.0, -3500.0]}, None, "receivers.terrain: x_m and y_m: expected strictly increasing"),
        (COVER, {"far": [5000.0, 0.0, 1.2]}, "receivers.microphones.far: expected a position on the terrain grid"),
        ({**COVER, "height_m": [[0.0, 200.0], [0.0, 200.0]]}, None, "the path passes"),
    ]
    for terrain, microphones, expected in cases:
        path = _path_with_terrain(tmp_path, terrain, microphones)
        with pytest.raises(ConfigError) as error:
            load_path(path, 0.5)
        assert str(error.value).startswith(str(path)) and expected in str(error.value), str(error.value)
