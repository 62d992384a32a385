"""Unit tests of nps.noise.spectra: scaling, Parseval, band edges, filters, harmonic bands."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.noise import spectra


def _tone(amplitude, freq_hz, n, dt, phase=0.3):
    t = np.arange(n) * dt
    return amplitude * np.cos(2 * np.pi * freq_hz * t + phase)


@settings(max_examples=40, deadline=None)
@given(st.integers(8, 600), st.integers(0, 2**31 - 1))
def test_parseval_unwindowed(n, seed):
    """Σ MSP lines = mean(p²) to 1e-12 relative; OASPL from signal and spectrum within 0.01 dB."""
    p = np.random.default_rng(seed).normal(0.0, 3.0, n)
    f, msp = spectra.narrowband_msp(p, 1e-3)
    assert f.size == n // 2 + 1
    assert np.isclose(msp.sum(), np.mean(p**2), rtol=1e-12)
    assert abs(spectra.level_db(msp.sum()) - spectra.level_db(np.mean(p**2))) < 0.01


def test_windowed_scaling_preserves_power():
    """Hann (power-normalised): total MSP of white noise within 3 % of mean(p²); a bin-centred
    tone's main lobe (3 lines) sums to a²/2 within 1e-12."""
    rng = np.random.default_rng(1)
    n, dt = 4096, 1e-4
    p = rng.normal(0.0, 1.0, n)
    _, msp = spectra.narrowband_msp(p, dt, window="hann")
    assert msp.sum() == pytest.approx(np.mean(p**2), rel=0.03)
    f, msp = spectra.narrowband_msp(_tone(2.0, 100 / (n * dt), n, dt), dt, window="hann")
    assert msp[99:102].sum() == pytest.approx(2.0, rel=1e-12)


def test_pure_tone_line_and_band():
    """A 2 Pa tone of 1 kHz (integer cycles) gives one line of MSP 2 Pa² (97.0 dB) in band 0
    (891.3–1122.0 Hz) and nothing (floor) in the neighbours."""
    n, dt = 2000, 1.0 / 20000.0
    p = _tone(2.0, 1000.0, n, dt)
    f, msp = spectra.narrowband_msp(p, dt)
    k = int(np.argmax(msp))
    assert f[k] == pytest.approx(1000.0)
    assert msp[k] == pytest.approx(2.0, rel=1e-12)
    levels = spectra.band_levels_from_signal(p, dt, [-1, 0, 1])
    assert levels[1] == pytest.approx(10 * np.log10(2.0 / 4e-10), abs=1e-9)
    assert levels[0] < -90 and levels[2] < -90


def test_band_edges_base10():
    """IEC 61260 base-10: f_m = 1000·10^(n/10), edges f_m·10^(±0.05); contiguous; 1 kHz edges
    891.25/1122.02 Hz; nominal labels for 10 Hz–20 kHz."""
    b = spectra.third_octave_bands(np.arange(-20, 14))
    assert np.allclose(b["upper_hz"][:-1], b["lower_hz"][1:], rtol=1e-14)
    zero = 20
    assert b["center_hz"][zero] == 1000.0
    assert b["lower_hz"][zero] == pytest.approx(891.2509, abs=1e-4)
    assert b["upper_hz"][zero] == pytest.approx(1122.0185, abs=1e-4)
    assert b["nominal_hz"][0] == 10 and b["nominal_hz"][-1] == 20000
    assert np.all(np.abs(b["center_hz"] / b["nominal_hz"] - 1) < 0.03)
    assert spectra.band_number_of([891.26, 1122.01, 1122.02, 315.0]).tolist() == [0, 0, 1, -5]


def test_band_msp_conserves_energy():
    """All lines within the band range end up in exactly one band (Σ bands = Σ lines > 0 Hz)."""
    rng = np.random.default_rng(2)
    p = rng.normal(size=512)  # lines every 15.6 Hz: the first lies above the 8.9 Hz lower edge
    f, msp = spectra.narrowband_msp(p, 1.0 / 8000.0)
    bands = spectra.band_msp(f, msp, np.arange(-20, 7))  # 10 Hz .. 5012 Hz upper edge covers 4 kHz Nyquist
    assert bands.sum() == pytest.approx(msp[1:].sum(), rel=1e-12)


def test_harmonic_band_edges():
    """Harmonic band 7..40 of f0 holds exactly harmonics 7..40: 6th and 41st excluded, edges at
    6.5 f0 and 40.5 f0."""
    f0 = 10.0
    f = np.arange(0, 500) * 1.0
    msp = np.zeros(f.size)
    msp[[60, 70, 400, 410]] = 1.0
    assert spectra.harmonic_band_msp(f, msp, f0, 7, 40) == pytest.approx(2.0)
    msp[:] = 0.0
    msp[[64, 65, 404, 405]] = 1.0  # 6.4 f0, 6.5 f0 (in), 40.4 f0 (in), 40.5 f0 (out)
    assert spectra.harmonic_band_msp(f, msp, f0, 7, 40) == pytest.approx(2.0)
    with pytest.raises(ValueError, match="first <= last"):
        spectra.harmonic_band_msp(f, msp, f0, 8, 7)


def test_filters_periodic_and_butterworth():
    """Brick-wall: a 50 Hz + 500 Hz mix high-passed at 200 Hz keeps the 500 Hz tone exactly
    (1e-12); Butterworth (zero-phase, order 4) removes > 99.9 % of the 50 Hz energy mid-record."""
    n, dt = 4000, 1e-4
    low, high = _tone(1.0, 50.0, n, dt), _tone(0.5, 500.0, n, dt, 1.1)
    out = spectra.filter_signal(low + high, dt, highpass_hz=200.0)
    assert np.max(np.abs(out - high)) < 1e-12
    out = spectra.filter_signal(low + high, dt, lowpass_hz=200.0)
    assert np.max(np.abs(out - low)) < 1e-12
    out = spectra.filter_signal(low + high, dt, highpass_hz=200.0, periodic=False)
    mid = slice(1000, 3000)
    assert np.mean((out - high)[mid] ** 2) < 1e-3 * np.mean(low[mid] ** 2)
    with pytest.raises(ValueError, match="Nyquist"):
        spectra.filter_signal(low, dt, lowpass_hz=6000.0)


def test_band_level_records():
    """Half-second records of a 1 kHz tone stepping 2 → 4 Pa: band-0 levels 97.0 and 103.0 dB."""
    dt = 1.0 / 16000.0
    p = np.concatenate([_tone(2.0, 1000.0, 8000, dt), _tone(4.0, 1000.0, 8000, dt)])
    t, lv = spectra.band_level_records(p, dt, [0], record_s=0.5, window="hann")
    assert t.tolist() == [0.25, 0.75]
    assert lv[:, 0] == pytest.approx([10 * np.log10(2 / 4e-10), 10 * np.log10(8 / 4e-10)], abs=1e-9)


def test_bad_input_messages():
    with pytest.raises(ValueError, match="window must be one of"):
        spectra.narrowband_msp(np.ones(8), 1.0, window="kaiser")
    with pytest.raises(ValueError, match="non-finite"):
        spectra.narrowband_msp(np.array([1.0, np.nan, 0.0]), 1.0)
    with pytest.raises(ValueError, match="dt_s"):
        spectra.narrowband_msp(np.ones(8), 0.0)
    assert spectra.level_db(0.0) == spectra.LEVEL_FLOOR_DB
