"""Unit tests of the ISO 9613-1 absorption additions to nps.core.atmosphere (and isa() unchanged)."""

import numpy as np
import pytest

from nps.noise import spectra
from nps.core.atmosphere import (
    absorb_band_levels,
    absorb_msp,
    absorb_periodic_signal,
    absorption_db_per_m,
    isa,
)


def test_isa_sea_level_unchanged():
    s = isa(0.0)
    assert s.temperature_k == 288.15 and s.pressure_pa == 101_325.0
    assert s.density_kg_m3 == pytest.approx(1.225, abs=1e-3)


def test_absorption_limits():
    """Classical limit: at 20 °C, RH 0 and very high frequency, molecular relaxation vanishes and
    α → 8.686·1.84e−11·f² (dB/m) within 1 %; α grows with frequency; α(0) = 0."""
    f = 1.0e7
    classical = 8.686 * 1.84e-11 * f**2
    assert absorption_db_per_m(f, 293.15, 0.0, 101_325.0) == pytest.approx(classical, rel=0.01)
    alpha = absorption_db_per_m(np.array([0.0, 100.0, 1e3, 1e4]), 288.15, 70.0, 101_325.0)
    assert alpha[0] == 0.0 and np.all(np.diff(alpha) > 0)


def test_absorption_bad_input():
    with pytest.raises(ValueError, match="relative_humidity_pct"):
        absorption_db_per_m(1000.0, 288.15, 120.0, 101_325.0)
    with pytest.raises(ValueError, match="temperature_k"):
        absorption_db_per_m(1000.0, -1.0, 50.0, 101_325.0)
    with pytest.raises(ValueError, match="distance_m"):
        absorb_band_levels([80.0], [1000.0], -5.0, isa(0.0))


def test_absorption_applications_agree():
    """Eq. 3.4 applied three ways agrees: a 2 kHz tone absorbed over 300 m in the time domain has
    the line MSP absorb_msp predicts (1e-12 relative), its level drops by α(2 kHz)·300 m (1e-9 dB),
    and absorb_band_levels subtracts the same α·r; an observer at 0 m is unchanged."""
    state = isa(0.0)
    n, dt = 1000, 1.0 / 20000.0
    t = np.arange(n) * dt
    p = np.stack([np.cos(2 * np.pi * 2000.0 * t), np.cos(2 * np.pi * 2000.0 * t)])
    out = absorb_periodic_signal(p, dt, np.array([300.0, 0.0]), state)
    f, msp = spectra.narrowband_msp(p, dt)
    _, msp_out = spectra.narrowband_msp(out, dt)
    assert np.allclose(msp_out[0], absorb_msp(f, msp[0], 300.0, state), rtol=1e-12, atol=1e-20)
    assert np.allclose(out[1], p[1], atol=1e-12)
    loss = spectra.level_db(msp[0].sum()) - spectra.level_db(msp_out[0].sum())
    alpha = absorption_db_per_m(2000.0, state.temperature_k, state.relative_humidity_pct, state.pressure_pa)
    assert loss == pytest.approx(alpha * 300.0, abs=1e-9)
    assert absorb_band_levels([[80.0]], [2000.0], [[300.0]], state)[0, 0] == pytest.approx(80.0 - alpha * 300.0)
