"""Unit tests of nps.plots.acoustics: summing rotors per group, observer picks, the figure file."""

import numpy as np
import pytest

from nps.noise.acoustics import TimeGrid
from nps.noise.signals import signals_table
from nps.noise.observers import hemisphere
from nps.plots.acoustics import group_signals, nearest_observer, pick_observers, pressure_histories

GRID = TimeGrid(0.0, 0.2, 32)


def rotor_table(ids, scale):
    """Thickness sin, loading cos (times ``scale`` and the observer id) on GRID."""
    t = GRID.times_s
    p = np.stack([np.stack([np.sin(2 * np.pi * t / 0.2), np.cos(2 * np.pi * t / 0.2)]) * scale * (o + 1) for o in ids])
    return signals_table(ids, ("thickness", "loading"), p, GRID)


def test_group_signals_sums_rotors_per_group_and_ignores_total():
    ids = np.arange(3)
    got_ids, time, groups = group_signals([rotor_table(ids, 1.0), rotor_table(ids, 2.0)])
    assert np.array_equal(got_ids, ids) and np.allclose(time, GRID.times_s)
    assert np.allclose(groups["thickness"][2], 9.0 * np.sin(2 * np.pi * GRID.times_s / 0.2))
    assert np.allclose(groups["total"], groups["thickness"] + groups["loading"])
    with pytest.raises(ValueError, match="do not share"):
        group_signals([rotor_table(ids, 1.0), rotor_table(np.arange(2), 1.0)])


def test_observer_picks_follow_the_map_convention():
    """19 × 72 hemisphere: nearest to (180°, −30°) is exactly that observer; the loudest is found."""
    obs = hemisphere([0.0, 0.0, 0.0], 10.0, 19, 72)
    ahead = nearest_observer(obs, 180.0, -30.0)
    row = obs[obs["observer"] == ahead].iloc[0]
    assert (row["azimuth_deg"], row["elevation_deg"]) == (180.0, -30.0)
    total = np.zeros((len(obs), 8))
    total[777, ::2] = 1.0
    picks = pick_observers(obs, obs["observer"].to_numpy(), total)
    assert list(picks.values())[0] == 777 and len(set(picks.values())) == len(picks)


def test_pressure_histories_writes_a_figure(tmp_path):
    obs = hemisphere([0.0, 0.0, 0.0], 10.0, 3, 4)
    ids = obs["observer"].to_numpy()
    path = pressure_histories({"main": rotor_table(ids, 1.0), "tail": rotor_table(ids, 0.5)}, obs, tmp_path / "p.png",
                              title="test")
    assert path.stat().st_size > 10_000
