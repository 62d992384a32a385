"""Unit tests of nps.noise.observers: map convention, counts, radii, ground grid, motion."""

import numpy as np
import pytest
import yaml

from nps.noise.observers import ObserverError, ground_grid, hemisphere, observer_set


def test_hemisphere_map_convention():
    """19 × 72 observers at 10 m: az 180° straight ahead (+x_G), 90° starboard (−y_G), el −90° straight down."""
    obs = hemisphere([1.0, 2.0, 3.0], 10.0, 19, 72, [5.0, 0.0, 0.0])
    assert len(obs) == 1368
    rel = obs[["x_m", "y_m", "z_m"]].to_numpy() - [1.0, 2.0, 3.0]
    assert np.allclose(np.linalg.norm(rel, axis=1), 10.0)
    pick = lambda az, el: rel[(obs.azimuth_deg == az) & (obs.elevation_deg == el)][0]
    assert np.allclose(pick(180.0, 0.0), [10.0, 0.0, 0.0])
    assert np.allclose(pick(90.0, 0.0), [0.0, -10.0, 0.0])
    assert np.allclose(pick(0.0, 0.0), [-10.0, 0.0, 0.0])
    assert np.allclose(pick(45.0, -90.0), [0.0, 0.0, -10.0])
    assert (obs.vx_mps == 5.0).all() and obs.observer.tolist() == list(range(1368))


def test_ground_grid_and_config_sets():
    grid = ground_grid([0.0, 0.0, 0.0], 150.0, [-300.0, 300.0], [-300.0, 300.0], 13, 13)
    assert len(grid) == 169 and np.allclose(grid.z_m, -150.0) and grid.x_m.min() == -300.0
    spec = {"kind": "points_ahead", "radius_R": 10.0, "elevations_deg": [0.0, -13.0], "moving": False}
    pts = observer_set(spec, [0.0, 0.0, 1.8], 7.62, [40.0, 0.0, 0.0])
    assert np.allclose(pts[["x_m", "y_m", "z_m"]].iloc[0], [76.2, 0.0, 1.8]) and (pts.vx_mps == 0).all()
    hemi = observer_set({"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 3, "n_azimuth": 4}, [0, 0, 0], 2.0, [40.0, 0.0, 0.0])
    assert len(hemi) == 12 and (hemi.vx_mps == 40.0).all()


def test_point_set_places_observers_at_offsets_from_the_centre():
    """Campaign kind ``point``: positions_m are offsets (G axes) from the set's centre, moving with the aircraft."""
    table = observer_set({"kind": "point", "positions_m": [[0.0, 0.0, -150.0], [10.0, -5.0, 0.0]]},
                         np.array([1.0, 2.0, 3.0]), 5.0, [40.0, 0.0, 0.0])
    assert table[["x_m", "y_m", "z_m"]].to_numpy().tolist() == [[1.0, 2.0, -147.0], [11.0, -3.0, 3.0]]
    assert np.all(table["vx_mps"] == 40.0)
    with pytest.raises(ObserverError, match="positions_m: expected a list of"):
        observer_set({"kind": "point", "positions_m": [[0.0, 1.0]]}, np.zeros(3), 5.0, [0.0, 0.0, 0.0])


def test_campaign_schema_accepts_point_and_sphere_sets():
    from pathlib import Path

    from nps.app.config import validate

    config = yaml.safe_load((Path(__file__).resolve().parents[2] / "config/config.yaml").read_text())
    config["observer_sets"]["mics"] = {"kind": "point", "positions_m": [[0.0, 0.0, -100.0]]}
    config["observer_sets"]["ball"] = {"kind": "sphere", "radius_R": 10.0, "n_elevation": 5, "n_azimuth": 8}
    validate(config, "config", "config/config.yaml")
