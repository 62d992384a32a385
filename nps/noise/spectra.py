"""Spectral analysis of acoustic pressure: narrowband, 1/3-octave bands, filters, harmonic bands.

Pressures in Pa, times in s, frequencies in Hz, mean-square pressures (MSP) in Pa², levels in
dB re 20 µPa.

Narrowband (:func:`narrowband_msp`): the one-sided mean-square-pressure line spectrum of a
record of N samples. Without a window (``window="none"``) the DFT coefficients X_k = Σ p_n
e^{−2πikn/N} / N give MSP_0 = |X_0|², MSP_k = 2|X_k|² (0 < k < N/2) and MSP_{N/2} = |X_{N/2}|²
(N even), so Σ MSP_k = mean(p²) exactly (Parseval) and a tone that completes an integer number of
cycles in the record lands in one bin with MSP = a²/2. This is the right choice for the periodic
one-revolution signals of NPS (the record is exactly one period: every bin is a rotor harmonic).
With a window w_n (Hann, Hamming, Blackman: for records that are not periodic) the power-
preserving normalisation |FFT(p·w)|² / (N Σw²) (times 2 for 0 < k < N/2) is used: the band sums
keep the signal's mean-square pressure, while a tone's energy spreads over the window's main
lobe (Σ over the lobe = a²/2).

1/3-octave bands (:func:`third_octave_bands`): base-10 exact bands of IEC 61260-1:2014 / ANSI
S1.11-2004, band number n (n = 0 at 1 kHz): mid-band f_m = 1000·10^(n/10) Hz, edges
f_m·10^(±1/20) Hz. A narrowband line belongs to band n when f_lower ≤ f < f_upper.

Filters: for periodic records an ideal (brick-wall) FFT filter is exact; for other records a
zero-phase Butterworth filter (scipy ``sosfiltfilt``) is used.
"""

from __future__ import annotations

import numpy as np

P_REF_PA = 20e-6
LEVEL_FLOOR_DB = -100.0
"""Levels of bands with no energy are reported at this floor (dB re 20 µPa) instead of −∞."""

WINDOWS = ("none", "hann", "hamming", "blackman")

# Nominal mid-band frequencies (IEC 61260-1 Annex E), band numbers -20 (10 Hz) ... 13 (20 kHz).
_NOMINAL_HZ = (
    10, 12.5, 16, 20, 25, 31.5, 40, 50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800,
    1000, 1250, 1600, 2000, 2500, 3150, 4000, 5000, 6300, 8000, 10000, 12500, 16000, 20000,
)
BAND_NUMBER_MIN = -20
BAND_NUMBER_MAX = 13


def level_db(msp_pa2) -> np.ndarray:
    """Sound pressure level 10·log10(MSP/p_ref²) in dB re 20 µPa, floored at LEVEL_FLOOR_DB."""
    msp = np.asarray(msp_pa2, dtype=float)
    if np.any(msp < 0.0) or not np.all(np.isfinite(msp)):
        raise ValueError("mean-square pressure must be finite and non-negative")
    floor = P_REF_PA**2 * 10.0 ** (LEVEL_FLOOR_DB / 10.0)
    return 10.0 * np.log10(np.maximum(msp, floor) / P_REF_PA**2)


def msp_from_level(level_db_) -> np.ndarray:
    """Mean-square pressure (Pa²) of a level in dB re 20 µPa; levels at the floor give 0."""
    level = np.asarray(level_db_, dtype=float)
    return np.where(level <= LEVEL_FLOOR_DB, 0.0, P_REF_PA**2 * 10.0 ** (level / 10.0))


def sum_levels_db(levels_db, axis=None) -> np.ndarray:
    """Energy sum of levels (dB) along ``axis``."""
    return level_db(np.sum(msp_from_level(levels_db), axis=axis))


def _check_record(p_pa: np.ndarray, dt_s: float) -> np.ndarray:
    p = np.asarray(p_pa, dtype=float)
    if p.shape[-1] < 2:
        raise ValueError(f"pressure record needs at least 2 samples along its last axis, got shape {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError("pressure record contains non-finite values")
    if not (np.isfinite(dt_s) and dt_s > 0.0):
        raise ValueError(f"sample interval dt_s must be positive, got {dt_s}")
    return p


def _window(name: str, n: int) -> np.ndarray:
    if name not in WINDOWS:
        raise ValueError(f"window must be one of {WINDOWS}, got {name!r}")
    if name == "none":
        return np.ones(n)
    from scipy.signal import get_window  # scipy.signal costs ~1 s to import: only when windowing

    return get_window(name, n, fftbins=True)


def narrowband_msp(p_pa, dt_s: float, window: str = "none") -> tuple[np.ndarray, np.ndarray]:
    """One-sided MSP line spectrum of ``p_pa`` (last axis = time, sample interval ``dt_s``).

    Returns (frequency_hz, msp_Pa2) with frequency_hz = k/(N dt), k = 0…⌊N/2⌋ and msp of shape
    p.shape[:-1] + (⌊N/2⌋+1,). Normalisation in the module docstring; Σ msp = mean(p²) exactly
    for ``window="none"``.
    """
    p = _check_record(p_pa, dt_s)
    n = p.shape[-1]
    w = _window(window, n)
    spectrum = np.fft.rfft(p * w, axis=-1)
    msp = np.abs(spectrum) ** 2 / (n * np.sum(w**2))
    msp[..., 1 : (n + 1) // 2] *= 2.0
    return np.fft.rfftfreq(n, dt_s), msp


def third_octave_bands(band_numbers) -> dict[str, np.ndarray]:
    """Exact base-10 1/3-octave bands for integer ``band_numbers`` (0 = 1 kHz).

    Returns arrays ``band`` (int), ``center_hz`` (exact mid-band 1000·10^(n/10)), ``lower_hz``,
    ``upper_hz`` (f_m·10^(∓1/20)) and ``nominal_hz`` (IEC nominal label; NaN outside 10 Hz–20 kHz).
    """
    n = np.atleast_1d(np.asarray(band_numbers))
    if not np.issubdtype(n.dtype, np.integer):
        raise ValueError(f"band numbers must be integers, got dtype {n.dtype}")
    center = 1000.0 * 10.0 ** (n / 10.0)
    inside = (n >= BAND_NUMBER_MIN) & (n <= BAND_NUMBER_MAX)
    nominal = np.full(n.shape, np.nan)
    nominal[inside] = np.asarray(_NOMINAL_HZ, dtype=float)[n[inside] - BAND_NUMBER_MIN]
    return {
        "band": n.astype(np.int64),
        "center_hz": center,
        "lower_hz": center * 10.0 ** (-1.0 / 20.0),
        "upper_hz": center * 10.0 ** (1.0 / 20.0),
        "nominal_hz": nominal,
    }


def band_number_of(frequency_hz) -> np.ndarray:
    """1/3-octave band number containing each frequency (f_lower ≤ f < f_upper), f > 0."""
    f = np.asarray(frequency_hz, dtype=float)
    if np.any(f <= 0.0):
        raise ValueError("band_number_of needs positive frequencies")
    return np.floor(10.0 * np.log10(f / 1000.0) + 0.5).astype(np.int64)


def band_msp(frequency_hz, msp_pa2, band_numbers) -> np.ndarray:
    """Sum narrowband lines into 1/3-octave bands: MSP (Pa²) per band, last axis = bands.

    Lines at 0 Hz (the mean) belong to no band. ``msp_pa2`` has the frequency on its last axis.
    """
    f = np.asarray(frequency_hz, dtype=float)
    msp = np.asarray(msp_pa2, dtype=float)
    bands = np.atleast_1d(np.asarray(band_numbers, dtype=np.int64))
    if msp.shape[-1] != f.size:
        raise ValueError(f"msp last axis ({msp.shape[-1]}) must match frequency_hz ({f.size})")
    positive = f > 0.0
    line_band = np.full(f.size, np.iinfo(np.int64).min)
    line_band[positive] = band_number_of(f[positive])
    # one-hot assignment matrix (lines x bands); bands are few, lines at most a few thousand
    assign = (line_band[:, None] == bands[None, :]).astype(float)
    return msp @ assign


def band_levels_from_signal(p_pa, dt_s: float, band_numbers, window: str = "none") -> np.ndarray:
    """1/3-octave band levels (dB) of a pressure record (last axis = time)."""
    f, msp = narrowband_msp(p_pa, dt_s, window)
    return level_db(band_msp(f, msp, band_numbers))


def harmonic_band_msp(frequency_hz, msp_pa2, fundamental_hz: float, first: int, last: int) -> np.ndarray:
    """MSP (Pa²) of the harmonics ``first``…``last`` of ``fundamental_hz``.

    The band runs from (first − ½)·f0 to (last + ½)·f0 (half a harmonic spacing beyond the
    outer harmonics), so for a periodic signal it holds exactly harmonics first…last and, for a
    spectrum of finer resolution, everything between them. BVISPL uses f0 = main-rotor BPF and
    harmonics 7…40.
    """
    if not (np.isfinite(fundamental_hz) and fundamental_hz > 0.0):
        raise ValueError(f"fundamental_hz must be positive, got {fundamental_hz}")
    if not (1 <= first <= last):
        raise ValueError(f"harmonic band needs 1 <= first <= last, got {first}..{last}")
    f = np.asarray(frequency_hz, dtype=float)
    inside = (f >= (first - 0.5) * fundamental_hz) & (f < (last + 0.5) * fundamental_hz)
    return np.sum(np.asarray(msp_pa2, dtype=float)[..., inside], axis=-1)


def filter_signal(
    p_pa,
    dt_s: float,
    highpass_hz: float | None = None,
    lowpass_hz: float | None = None,
    periodic: bool = True,
    order: int = 4,
) -> np.ndarray:
    """High-, low- or band-pass filter a pressure record (last axis = time).

    ``periodic=True``: ideal FFT filter, keeping lines with highpass_hz ≤ f ≤ lowpass_hz (exact
    for a record that is one period). ``periodic=False``: zero-phase Butterworth of ``order``
    (applied forward and backward, so the magnitude response is squared: −6 dB at the cut-off).
    """
    p = _check_record(p_pa, dt_s)
    nyquist = 0.5 / dt_s
    for name, value in (("highpass_hz", highpass_hz), ("lowpass_hz", lowpass_hz)):
        if value is not None and not (0.0 < value < nyquist):
            raise ValueError(f"{name} must lie in (0, {nyquist:g}) Hz (Nyquist), got {value}")
    if highpass_hz is not None and lowpass_hz is not None and highpass_hz >= lowpass_hz:
        raise ValueError(f"highpass_hz ({highpass_hz}) must be below lowpass_hz ({lowpass_hz})")
    if highpass_hz is None and lowpass_hz is None:
        return p.copy()
    if periodic:
        f = np.fft.rfftfreq(p.shape[-1], dt_s)
        keep = np.ones(f.size, dtype=bool)
        if highpass_hz is not None:
            keep &= f >= highpass_hz
        if lowpass_hz is not None:
            keep &= f <= lowpass_hz
        return np.fft.irfft(np.fft.rfft(p, axis=-1) * keep, n=p.shape[-1], axis=-1)
    from scipy import signal as _signal  # ~1 s import: only for non-periodic filtering

    if highpass_hz is not None and lowpass_hz is not None:
        sos = _signal.butter(order, [highpass_hz, lowpass_hz], btype="bandpass", fs=1.0 / dt_s, output="sos")
    elif highpass_hz is not None:
        sos = _signal.butter(order, highpass_hz, btype="highpass", fs=1.0 / dt_s, output="sos")
    else:
        sos = _signal.butter(order, lowpass_hz, btype="lowpass", fs=1.0 / dt_s, output="sos")
    return _signal.sosfiltfilt(sos, p, axis=-1)


def band_level_records(p_pa, dt_s: float, band_numbers, record_s: float = 0.5, window: str = "hann"):
    """1/3-octave band levels of consecutive records of ``record_s`` seconds of a long signal.

    For certification metrics (14 CFR 36 A2: half-second records). Returns (record centre times
    in s from the first sample, levels (n_records, n_bands) in dB). A trailing partial record is
    dropped. ``window`` as in :func:`narrowband_msp` (Hann by default: a flyover record is not
    periodic; its power-preserving normalisation keeps band energies).
    """
    p = _check_record(p_pa, dt_s)
    if p.ndim != 1:
        raise ValueError(f"band_level_records takes one signal (1-D), got shape {p.shape}")
    n_per = int(round(record_s / dt_s))
    if n_per < 2 or abs(n_per * dt_s - record_s) > 1e-9 * record_s + 1e-12:
        raise ValueError(f"record_s ({record_s}) must be a whole number (>= 2) of samples of {dt_s} s")
    n_records = p.size // n_per
    if n_records < 1:
        raise ValueError(f"signal of {p.size * dt_s:g} s is shorter than one {record_s} s record")
    records = p[: n_records * n_per].reshape(n_records, n_per)
    times = (np.arange(n_records) + 0.5) * record_s
    return times, band_levels_from_signal(records, dt_s, band_numbers, window)
