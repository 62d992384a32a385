"""Frames: the conventions of docs/reference/conventions.md on cases with known answers."""

import numpy as np

from nps.core import frames


def test_main_rotor_hub_frame_axes():
    """Untilted ccw main rotor: x_H aft, y_H starboard (advancing side), z_H up."""
    r_bh = frames.hub_to_body([0.0, 0.0, 1.0])
    assert np.allclose(r_bh[:, 0], [-1, 0, 0]) and np.allclose(r_bh[:, 1], [0, -1, 0]) and np.allclose(r_bh[:, 2], [0, 0, 1])
    blade_at_90 = r_bh @ frames.blade_span_unit_hub(np.pi / 2, +1)
    assert np.allclose(blade_at_90, [0, -1, 0])  # advancing blade over the starboard side
    assert np.allclose(r_bh @ frames.blade_span_unit_hub(np.pi / 2, -1), [0, 1, 0])  # cw: port


def test_nose_up_pitch_and_starboard_down_roll():
    assert np.allclose(frames.body_to_ground(np.radians(10), 0.0) @ [1, 0, 0], [np.cos(np.radians(10)), 0, np.sin(np.radians(10))])
    assert frames.body_to_ground(0.0, np.radians(5))[2, 1] > 0  # port side (y_B) rises: starboard down


def test_observer_map_directions():
    assert np.allclose(frames.observer_direction(0.0, 0.0), [-1, 0, 0])          # behind
    assert np.allclose(frames.observer_direction(np.pi / 2, 0.0), [0, -1, 0])    # starboard
    assert np.allclose(frames.observer_direction(np.pi, 0.0), [1, 0, 0])         # ahead
    assert np.allclose(frames.observer_direction(0.3, -np.pi / 2), [0, 0, -1])   # straight down


def test_rotations_are_proper():
    for r in (frames.body_to_ground(0.3, -0.2), frames.hub_to_body([0.1, -0.9, 0.3])):
        assert np.allclose(r @ r.T, np.eye(3)) and np.isclose(np.linalg.det(r), 1.0)
