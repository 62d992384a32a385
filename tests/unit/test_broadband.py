"""Unit tests of nps.noise.broadband.pegg (Pegg model plumbing: geometry, lift term, scaling, errors)."""

import numpy as np
import pytest

from nps.noise.broadband import pegg as broadband


def test_observer_geometry():
    """Hub at (1, 2, 3), axis +z: observer 10 m below → r = 10, cos θ = −1; 10 m to the side →
    cos θ = 0; the axis need not be normalised."""
    r, c = broadband.observer_geometry([1, 2, 3], [0, 0, 2.0], [[1, 2, -7], [11, 2, 3]])
    assert r == pytest.approx([10, 10])
    assert c == pytest.approx([-1, 0])
    with pytest.raises(ValueError, match="coincides"):
        broadband.observer_geometry([0, 0, 0], [0, 0, 1], [[0, 0, 0]])


def test_lift_term_branches():
    """f(0.4) = 0 dB; f(0.48) = 0.79 dB on the low branch, 0.8 dB on the high branch just above."""
    assert broadband.lift_term_db(0.4) == pytest.approx(0.0)
    assert broadband.lift_term_db(0.48) == pytest.approx(10 * np.log10(1.2))
    assert broadband.lift_term_db(0.4800001) == pytest.approx(0.8, abs=1e-5)
    assert broadband.mean_lift_coefficient(0.005, 0.1) == pytest.approx(0.3)


def test_scaling_laws():
    """Level ∝ 60 log V_T (same peak band), 20 log(1/r) spherical spreading, 10 log A_b; peak
    frequency falls 72.2 Hz per doubling of thrust (240 log10 2)."""
    bands = np.arange(-12, 4)
    a = broadband.PeggRotor(5.0e4, 200.0, 10.0, 0.3)
    base = broadband.band_levels_db(a, bands, [100.0, 200.0], [0.5, 0.5], 340.0)
    assert np.allclose(base[0] - base[1], 20 * np.log10(2.0))
    b = broadband.PeggRotor(5.0e4, 200.0, 20.0, 0.3)
    assert np.allclose(broadband.band_levels_db(b, bands, [100.0], [0.5], 340.0)[0] - base[0], 10 * np.log10(2))
    c = broadband.PeggRotor(5.0e4, 201.0, 10.0, 0.3)  # fp moves by 2.4 Hz: same band here
    assert broadband.band_number_of(broadband.peak_frequency_hz(5.0e4, 201.0)) == broadband.band_number_of(
        broadband.peak_frequency_hz(5.0e4, 200.0))
    assert np.allclose(broadband.band_levels_db(c, bands, [100.0], [0.5], 340.0)[0] - base[0], 60 * np.log10(201 / 200))
    assert broadband.peak_frequency_hz(1.0e4, 200.0) - broadband.peak_frequency_hz(2.0e4, 200.0) == pytest.approx(240 * np.log10(2))


def test_bad_inputs():
    with pytest.raises(ValueError, match="thrust_N"):
        broadband.PeggRotor(-1.0, 200.0, 10.0, 0.3)
    with pytest.raises(ValueError, match="not positive"):
        broadband.peak_frequency_hz(1e9, 10.0)
    rotor = broadband.PeggRotor(5.0e4, 200.0, 10.0, 0.3)
    with pytest.raises(ValueError, match="distance_m"):
        broadband.band_levels_db(rotor, [0], [0.0], [0.0], 340.0)
    with pytest.raises(ValueError, match="cos_theta"):
        broadband.band_levels_db(rotor, [0], [10.0], [1.5], 340.0)
