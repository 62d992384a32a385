"""Pegg's data-range check (nps.noise.broadband.pegg.pegg_outside_range)."""

import numpy as np
import pytest

from nps.noise.broadband.pegg import pegg_outside_range


def test_helicopter_main_rotor_is_inside_and_drone_rotor_is_outside():
    # bundled helicopter main rotor: R = 7.62 m, ΩR = 213.4 m/s, T ≈ weight 5140 kg · g
    assert pegg_outside_range(7.62, 213.4, 5140.1 * 9.80665) == []
    # the drone propeller: R = 0.12 m, tip speed ~ 80 m/s, T ~ 5 N
    messages = pegg_outside_range(0.12, 80.0, 5.0)
    assert [m.split("=")[0] for m in messages] == ["radius_m", "tip_speed_mps", "thrust_N"]
    # a tail rotor is outside the main-rotor data by its size and thrust only
    assert [m.split("=")[0] for m in pegg_outside_range(1.55, 200.0, 4000.0)] == ["radius_m", "thrust_N"]


def test_non_finite_input_is_an_error():
    with pytest.raises(ValueError, match="thrust_N"):
        pegg_outside_range(7.0, 200.0, np.nan)
