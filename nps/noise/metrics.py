"""Noise metrics: OASPL, A-weighting, BVISPL, PNL, PNLT, EPNL, SEL, L_Amax.

Levels in dB re 20 µPa, frequencies in Hz, times in s, mean-square pressures (MSP) in Pa².

- A-weighting: IEC 61672-1:2013 eq. (E.1)-(E.6), the analytic curve with pole frequencies
  f1 = 20.598997, f2 = 107.65265, f3 = 737.86223, f4 = 12194.217 Hz, normalised to exactly 0 dB
  at 1 kHz (the standard rounds this constant to A1000 = −2.000 dB; the exact value
  −1.99966 dB is used, as ANOPP2 does).
- PNL: 14 CFR Part 36 Appendix A, A36.4.2: noy values from the Table A36-3 constants,
  N = 0.85·n_max + 0.15·Σn, PNL = 40 + (10/log10 2)·log10 N (PNdB), for the 24 1/3-octave bands
  50 Hz–10 kHz (band numbers −13…10).
- PNLT: A36.4.3 tone correction, steps 1-10 with Table A36-2 (F < 1.5 dB gives no correction).
  The band-sharing adjustment of PNLTM (A36.4.4) is not applied.
- EPNL: A36.4.5, half-second records: EPNL = 10·log10((Δt/T)·Σ 10^(PNLT_k/10)) with T = 10 s,
  summed over the records from the first to the last one with PNLT ≥ PNLTM − 10 dB.
- SEL: 10·log10(Σ 10^(L_A,k/10)·Δt / 1 s) over the records from the first to the last with
  L_A ≥ L_Amax − 10 dB (the 10-dB-down exposure used for helicopter certification, 14 CFR 36
  Appendix J); L_Amax = max_k L_A,k.

The metrics stage (:func:`observer_set_metrics`, :func:`metrics_tables`) works on the periodic
one-revolution signals of docs/reference/conventions.md: their spectra are taken *without a window*
(every FFT line is an exact rotor harmonic, Parseval holds exactly, no leakage between the BVISPL
harmonics and the others); windows are for non-periodic records such as the half-second records
of a flyover (:func:`nps.noise.spectra.band_level_records`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.noise.broadband import pegg as broadband
from nps.core.atmosphere import AtmosphereState, absorb_band_levels, apply_line_gain, periodic_absorption_gain
from nps.noise.signals import check_tone_sum, signal_arrays
from nps.noise.spectra import (
    LEVEL_FLOOR_DB,
    band_msp,
    harmonic_band_msp,
    level_db,
    msp_from_level,
    narrowband_msp,
    third_octave_bands,
)

# IEC 61672-1 A-weighting pole frequencies (Hz)
_F1, _F2, _F3, _F4 = 20.598997, 107.65265, 737.86223, 12194.217


def _a_weighting_raw_db(f: np.ndarray) -> np.ndarray:
    f2 = f * f
    gain = _F4**2 * f2 * f2 / ((f2 + _F1**2) * np.sqrt(f2 + _F2**2) * np.sqrt(f2 + _F3**2) * (f2 + _F4**2))
    return 20.0 * np.log10(gain)


_A1000_DB = float(_a_weighting_raw_db(np.array(1000.0)))


def a_weighting_db(frequency_hz) -> np.ndarray:
    """IEC 61672-1 A-weighting (dB) at ``frequency_hz`` (> 0), exactly 0 dB at 1 kHz."""
    f = np.asarray(frequency_hz, dtype=float)
    if np.any(~np.isfinite(f)) or np.any(f <= 0.0):
        raise ValueError("a_weighting_db needs finite positive frequencies (Hz)")
    return _a_weighting_raw_db(f) - _A1000_DB


def a_weighted_msp(frequency_hz, msp_pa2) -> np.ndarray:
    """A-weighted total MSP (Pa²) of a line spectrum (frequency on the last axis; 0 Hz dropped)."""
    f = np.asarray(frequency_hz, dtype=float)
    msp = np.asarray(msp_pa2, dtype=float)
    positive = f > 0.0
    weight = 10.0 ** (a_weighting_db(f[positive]) / 10.0)
    return msp[..., positive] @ weight


def oaspl_db(msp_pa2, axis=-1) -> np.ndarray:
    """Overall SPL (dB) of a line or band MSP spectrum summed along ``axis``."""
    return level_db(np.sum(np.asarray(msp_pa2, dtype=float), axis=axis))


# ---------------------------------------------------------------- 14 CFR 36 PNL / PNLT / EPNL
PNL_BANDS = np.arange(-13, 11)
"""Band numbers of the 24 PNL bands, 50 Hz (−13) to 10 kHz (10)."""

PNL_NOMINAL_HZ = np.array(
    [50, 63, 80, 100, 125, 160, 200, 250, 315, 400, 500, 630, 800, 1000, 1250, 1600, 2000, 2500,
     3150, 4000, 5000, 6300, 8000, 10000], dtype=float,
)

# Table A36-3 (14 CFR 36 Appendix A): SPL(a), SPL(b), SPL(c), SPL(d), SPL(e), M(b), M(c), M(d), M(e)
_INF = np.inf
_NOY_TABLE = np.array([
    [91.0, 64, 52, 49, 55, 0.043478, 0.030103, 0.07952, 0.058098],
    [85.9, 60, 51, 44, 51, 0.04057, 0.030103, 0.06816, 0.058098],
    [87.3, 56, 49, 39, 46, 0.036831, 0.030103, 0.06816, 0.052288],
    [79.0, 53, 47, 34, 42, 0.036831, 0.030103, 0.05964, 0.047534],
    [79.8, 51, 46, 30, 39, 0.035336, 0.030103, 0.053013, 0.043573],
    [76.0, 48, 45, 27, 36, 0.033333, 0.030103, 0.053013, 0.043573],
    [74.0, 46, 43, 24, 33, 0.033333, 0.030103, 0.053013, 0.040221],
    [74.9, 44, 42, 21, 30, 0.032051, 0.030103, 0.053013, 0.037349],
    [94.6, 42, 41, 18, 27, 0.030675, 0.030103, 0.053013, 0.034859],
    [_INF, 40, 40, 16, 25, 0.030103, 0.0, 0.053013, 0.034859],
    [_INF, 40, 40, 16, 25, 0.030103, 0.0, 0.053013, 0.034859],
    [_INF, 40, 40, 16, 25, 0.030103, 0.0, 0.053013, 0.034859],
    [_INF, 40, 40, 16, 25, 0.030103, 0.0, 0.053013, 0.034859],
    [_INF, 40, 40, 16, 25, 0.030103, 0.0, 0.053013, 0.034859],
    [_INF, 38, 38, 15, 23, 0.030103, 0.0, 0.05964, 0.034859],
    [_INF, 34, 34, 12, 21, 0.02996, 0.0, 0.053013, 0.040221],
    [_INF, 32, 32, 9, 18, 0.02996, 0.0, 0.053013, 0.037349],
    [_INF, 30, 30, 5, 15, 0.02996, 0.0, 0.047712, 0.034859],
    [_INF, 29, 29, 4, 14, 0.02996, 0.0, 0.047712, 0.034859],
    [_INF, 29, 29, 5, 14, 0.02996, 0.0, 0.053013, 0.034859],
    [_INF, 30, 30, 6, 15, 0.02996, 0.0, 0.053013, 0.034859],
    [_INF, 31, 31, 10, 17, 0.02996, 0.0, 0.06816, 0.037349],
    [44.3, 34, 34, 17, 23, 0.042285, 0.02996, 0.07952, 0.037349],
    [50.7, 37, 37, 21, 29, 0.042285, 0.02996, 0.05964, 0.043573],
])


def _check_pnl_bands(band_levels_db) -> np.ndarray:
    spl = np.asarray(band_levels_db, dtype=float)
    if spl.ndim < 1 or spl.shape[-1] != 24:
        raise ValueError(
            f"PNL needs the 24 1/3-octave band levels 50 Hz-10 kHz on the last axis, got shape {spl.shape}"
        )
    if not np.all(np.isfinite(spl)):
        raise ValueError("PNL band levels must be finite (use the level floor for empty bands)")
    return spl


def noy(band_levels_db) -> np.ndarray:
    """Perceived noisiness n (noy) of each of the 24 bands (A36.4.2.1(a), Table A36-3)."""
    spl = _check_pnl_bands(band_levels_db)
    a, b, c, d, e, mb, mc, md, me = (_NOY_TABLE[:, j] for j in range(9))
    with np.errstate(over="ignore"):
        return np.select(
            [spl >= a, spl >= b, spl >= e, spl >= d],
            [10.0 ** (mc * (spl - c)), 10.0 ** (mb * (spl - b)), 0.3 * 10.0 ** (me * (spl - e)),
             0.1 * 10.0 ** (md * (spl - d))],
            default=0.0,
        )


def pnl(band_levels_db) -> np.ndarray:
    """Perceived noise level (PNdB) from the 24 band levels 50 Hz–10 kHz (last axis)."""
    n = noy(band_levels_db)
    total = 0.85 * n.max(axis=-1) + 0.15 * n.sum(axis=-1)
    # N = 0 (all bands below SPL(d)) has no defined PNL: report the level floor
    with np.errstate(divide="ignore"):
        out = 40.0 + 10.0 / np.log10(2.0) * np.log10(total)
    return np.where(total > 0.0, out, LEVEL_FLOOR_DB)


@dataclass(frozen=True)
class ToneCorrection:
    """Intermediate and final quantities of the A36.4.3 tone-correction procedure (24 bands)."""

    slope: np.ndarray          # S (step 1), NaN where undefined (bands 1-3)
    adjusted_spl: np.ndarray   # SPL' (step 4)
    adjusted_slope: np.ndarray  # S' (step 5), bands 3..25 (23 values)
    average_slope: np.ndarray  # S̄ (step 6), bands 3..23 (21 values)
    final_spl: np.ndarray      # SPL'' (step 7), NaN in bands 1-2
    excess: np.ndarray         # F (step 8), 0 where < 1.5 dB
    correction: np.ndarray     # C (step 9)

    @property
    def c_max_db(self) -> float:
        return float(self.correction.max())


def _tone_correction_rows(spl: np.ndarray) -> ToneCorrection:
    """A36.4.3 steps 1-9 for spectra ``spl`` (n, 24) at once; every field has a leading n axis
    (S' (n, 23), S̄ (n, 21), the others (n, 24))."""
    n = spl.shape[0]
    i3 = 2  # 0-based index of band 3 (80 Hz)
    s = np.full((n, 24), np.nan)
    s[:, i3 + 1 :] = np.diff(spl[:, i3:], axis=1)  # step 1: S(i) = SPL(i) - SPL(i-1), i = 4..24
    circled_s = np.zeros((n, 24), dtype=bool)  # step 2: |S(i) - S(i-1)| > 5
    circled_s[:, i3 + 2 :] = np.abs(np.diff(s[:, i3 + 1 :], axis=1)) > 5.0
    # step 3: circle SPL(i) where S(i) is positive and rising, SPL(i-1) where S turns non-positive
    s_prev = np.roll(s, 1, axis=1)
    circled_spl = circled_s & (s > 0.0) & (s > s_prev)
    circled_spl[:, :-1] |= (circled_s & (s <= 0.0) & (s_prev > 0.0))[:, 1:]
    adjusted = spl.copy()  # step 4
    neighbours = np.full((n, 24), np.nan)
    neighbours[:, 1:23] = 0.5 * (spl[:, :22] + spl[:, 2:])
    neighbours[:, 23] = spl[:, 22] + s[:, 22]
    adjusted[circled_spl] = neighbours[circled_spl]
    sp = np.empty((n, 23))  # step 5: S'(3..25)
    sp[:, 1:22] = np.diff(adjusted[:, i3:], axis=1)
    sp[:, 0] = sp[:, 1]
    sp[:, 22] = sp[:, 21]
    sbar = (sp[:, 0:21] + sp[:, 1:22] + sp[:, 2:23]) / 3.0  # step 6: S̄(3..23)
    final = np.full((n, 24), np.nan)  # step 7
    final[:, i3] = spl[:, i3]
    final[:, i3 + 1 :] = spl[:, i3 : i3 + 1] + np.cumsum(sbar, axis=1)
    f = np.zeros((n, 24))  # step 8
    f[:, i3:] = spl[:, i3:] - final[:, i3:]
    f[f < 1.5] = 0.0
    low_or_high = (PNL_NOMINAL_HZ < 500.0) | (PNL_NOMINAL_HZ > 5000.0)  # step 9, Table A36-2
    c = np.where(
        low_or_high,
        np.select([f >= 20.0, f >= 3.0, f >= 1.5], [10.0 / 3.0, f / 6.0, f / 3.0 - 0.5], 0.0),
        np.select([f >= 20.0, f >= 3.0, f >= 1.5], [20.0 / 3.0, f / 3.0, 2.0 * f / 3.0 - 1.0], 0.0),
    )
    return ToneCorrection(s, adjusted, sp, sbar, final, f, c)


def tone_correction(band_levels_db) -> ToneCorrection:
    """14 CFR 36 A36.4.3 steps 1-9 for one spectrum of the 24 bands 50 Hz–10 kHz."""
    spl = _check_pnl_bands(band_levels_db)
    if spl.ndim != 1:
        raise ValueError(f"tone_correction takes one spectrum (24 values), got shape {spl.shape}")
    rows = _tone_correction_rows(spl[None, :])
    return ToneCorrection(*(getattr(rows, name)[0] for name in ToneCorrection.__dataclass_fields__))


def pnlt(band_levels_db) -> np.ndarray:
    """Tone-corrected PNL (TPNdB) = PNL + C_max; band levels on the last axis (24 bands)."""
    spl = _check_pnl_bands(band_levels_db)
    c_max = _tone_correction_rows(spl.reshape(-1, 24)).correction.max(axis=1).reshape(spl.shape[:-1])
    return pnl(spl) + c_max


@dataclass(frozen=True)
class TimeHistoryMetrics:
    """Certification metrics of a sequence of half-second records (levels in dB, times in s)."""

    pnltm_db: float
    epnl_db: float
    epnl_duration_s: float
    sel_db: float
    lamax_db: float
    truncated: bool  # True when a 10-dB-down point lies outside the record sequence


def _ten_db_down(levels: np.ndarray) -> tuple[int, int, bool]:
    above = np.flatnonzero(levels >= levels.max() - 10.0)
    first, last = int(above[0]), int(above[-1])
    return first, last, first == 0 or last == levels.size - 1


def time_history_metrics(band_levels_db, band_numbers, record_s: float = 0.5) -> TimeHistoryMetrics:
    """PNLTM, EPNL, SEL and L_Amax of a record sequence.

    ``band_levels_db`` (n_records, n_bands): 1/3-octave levels of consecutive ``record_s``-second
    records, for the integer ``band_numbers`` (must include −13…10; others count in L_A only).
    """
    levels = np.asarray(band_levels_db, dtype=float)
    bands = np.asarray(band_numbers, dtype=np.int64)
    if levels.ndim != 2 or levels.shape[1] != bands.size or levels.shape[0] < 1:
        raise ValueError(f"band_levels_db must be (n_records, {bands.size}), got {levels.shape}")
    index = {int(b): j for j, b in enumerate(bands)}
    missing = [int(b) for b in PNL_BANDS if int(b) not in index]
    if missing:
        raise ValueError(f"time_history_metrics needs 1/3-octave bands -13..10 (50 Hz-10 kHz); missing {missing}")
    pnlt_k = pnlt(levels[:, [index[int(b)] for b in PNL_BANDS]])
    first, last, trunc_p = _ten_db_down(pnlt_k)
    epnl = 10.0 * np.log10(record_s / 10.0 * np.sum(10.0 ** (pnlt_k[first : last + 1] / 10.0)))
    centres = 1000.0 * 10.0 ** (bands / 10.0)
    la_k = level_db(msp_from_level(levels + a_weighting_db(centres)).sum(axis=1))
    a_first, a_last, trunc_a = _ten_db_down(la_k)
    sel = 10.0 * np.log10(record_s * np.sum(10.0 ** (la_k[a_first : a_last + 1] / 10.0)))
    return TimeHistoryMetrics(
        pnltm_db=float(pnlt_k.max()),
        epnl_db=float(epnl),
        epnl_duration_s=(last - first + 1) * record_s,
        sel_db=float(sel),
        lamax_db=float(la_k.max()),
        truncated=bool(trunc_p or trunc_a),
    )


# ------------------------------------------------------------ metrics of one observer set
STUDY_BANDS = np.arange(-20, 14)
"""1/3-octave bands of the metrics artifacts: 10 Hz (−20) to 20 kHz (13)."""

TONAL_SOURCES = ("thickness", "loading", "hsi")


@dataclass(frozen=True)
class ObserverSetLevels:
    """Per-observer levels of one observer set (dB re 20 µPa).

    ``oaspl_db`` maps source (thickness, loading, hsi, broadband, total) to OASPL per observer;
    ``bands_db`` maps the same sources to 1/3-octave levels (n_observers, n_bands) for
    ``band_numbers``.
    """

    band_numbers: np.ndarray
    frequency_hz: np.ndarray  # narrowband lines of the tonal total
    tonal_msp: np.ndarray  # (n_observers, n_lines) Pa², tonal total (after absorption if applied)
    oaspl_db: dict[str, np.ndarray]
    bands_db: dict[str, np.ndarray]
    oaspl_dba: np.ndarray
    bvispl_db: np.ndarray
    pnl_db: np.ndarray
    pnlt_db: np.ndarray


def _tonal_spectra(parts: Sequence[Mapping[str, np.ndarray]], dt_s: float) -> tuple[dict, np.ndarray, np.ndarray]:
    """Narrowband MSP spectra (source → (frequency, MSP)), lines and tonal-total MSP of mutually incoherent
    ``parts`` (each source group → p (Pa)): each part's spectra (its total the ``hsi`` signal when present,
    else thickness + loading), added as mean-square pressures. One part: the spectra of its signals."""
    source_spectra, total_msp = {}, None
    for part in parts:
        unknown = sorted(set(part) - set(TONAL_SOURCES))
        if unknown or not {"thickness", "loading"} <= set(part):
            raise ValueError(f"signals_pa needs 'thickness' and 'loading' (optional 'hsi'); got {sorted(part)}")
        spectra = {name: narrowband_msp(p, dt_s) for name, p in part.items()}
        freq, msp = spectra["hsi"] if "hsi" in part else narrowband_msp(part["thickness"] + part["loading"], dt_s)
        total_msp = msp if total_msp is None else total_msp + msp
        for name, (f, m) in spectra.items():
            source_spectra[name] = (f, m) if name not in source_spectra else (f, source_spectra[name][1] + m)
    if len(parts) > 1 and len({frozenset(part) for part in parts}) > 1:
        raise ValueError(f"incoherent parts must hold the same source groups; got {[sorted(part) for part in parts]}")
    return source_spectra, freq, total_msp


def observer_set_metrics(
    signals_pa: Mapping[str, np.ndarray] | Sequence[Mapping[str, np.ndarray]],
    dt_s: float,
    bpf_hz: float,
    broadband_db: np.ndarray | None = None,
    harmonics: tuple[int, int] = (7, 40),
    band_numbers=STUDY_BANDS,
) -> ObserverSetLevels:
    """Levels of one observer set from its summed (over rotors) periodic pressure signals.

    ``signals_pa``: source name (``thickness``, ``loading``, optionally ``hsi``) → p (Pa),
    shape (n_observers, N), one period sampled every ``dt_s`` s, already absorbed if wanted; or a
    sequence of such mappings whose phases are not locked (one per rotor, tone sum ``incoherent``):
    their mean-square spectra add (:func:`_tonal_spectra`). The tonal total is the ``hsi`` signal when present (HSI processing replaces each rotor's
    thickness + loading sum), else thickness + loading. ``broadband_db``: broadband 1/3-octave
    levels (n_observers, n_bands) for ``band_numbers`` (energy-summed over rotors), added to the
    total by energy band by band. OASPL_A weights the tonal lines at their exact frequencies
    and the broadband bands at their mid-band frequencies. BVISPL: harmonics ``harmonics`` of
    ``bpf_hz`` (main-rotor BPF) of the tonal total. PNL/PNLT: of the total band levels.
    Tonal energy above the Nyquist frequency of the signals is not represented.
    """
    parts = [signals_pa] if isinstance(signals_pa, Mapping) else list(signals_pa)
    if not parts:
        raise ValueError("signals_pa: no signals")
    bands = np.asarray(band_numbers, dtype=np.int64)
    if np.any(np.diff(bands) != 1) or bands[0] > PNL_BANDS[0] or bands[-1] < PNL_BANDS[-1]:
        raise ValueError("band_numbers must be consecutive and include the PNL bands -13..10 (50 Hz-10 kHz)")
    centres = third_octave_bands(bands)["center_hz"]
    source_spectra, freq, total_msp = _tonal_spectra(parts, dt_s)
    # the 0 Hz line (the mean pressure) is not sound: excluded from every level
    oaspl = {name: level_db(msp[..., 1:].sum(axis=-1)) for name, (_, msp) in source_spectra.items()}
    bands_db = {name: level_db(band_msp(f, msp, bands)) for name, (f, msp) in source_spectra.items()}
    total_band_msp = band_msp(freq, total_msp, bands)
    total_ms = total_msp[..., 1:].sum(axis=-1)
    a_ms = a_weighted_msp(freq, total_msp)
    if broadband_db is not None:
        bb = np.asarray(broadband_db, dtype=float)
        if bb.shape != total_band_msp.shape:
            raise ValueError(f"broadband_db must have shape {total_band_msp.shape}, got {bb.shape}")
        bb_msp = msp_from_level(bb)
        bands_db["broadband"] = bb
        oaspl["broadband"] = level_db(bb_msp.sum(axis=-1))
        total_band_msp = total_band_msp + bb_msp
        total_ms = total_ms + bb_msp.sum(axis=-1)
        a_ms = a_ms + bb_msp @ 10.0 ** (a_weighting_db(centres) / 10.0)
    oaspl["total"] = level_db(total_ms)
    bands_db["total"] = level_db(total_band_msp)
    pnl_bands = bands_db["total"][..., np.searchsorted(bands, PNL_BANDS)]
    bvispl = level_db(harmonic_band_msp(freq, total_msp, bpf_hz, *harmonics))
    return ObserverSetLevels(
        bands, freq, total_msp, oaspl, bands_db, level_db(a_ms), bvispl, pnl(pnl_bands), pnlt(pnl_bands)
    )


OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "elevation_deg", "azimuth_deg")
"""Columns the metrics stage needs from the observers artifact."""


def metrics_tables(
    signals: Mapping[str, pd.DataFrame],
    observers: pd.DataFrame,
    trim: pd.DataFrame,
    solidity: Mapping[str, float],
    atmosphere: AtmosphereState | None,
    hsi_signals: Mapping[str, pd.DataFrame] | None = None,
    broadband_on: bool = True,
    harmonics: tuple[int, int] = (7, 40),
    broadband_msp: Mapping[str, np.ndarray] | None = None,
    tone_sum: str = "coherent",
) -> tuple[pd.DataFrame, pd.DataFrame, ObserverSetLevels]:
    """Metrics and band tables of one aircraft × segment × observer set × variant.

    ``signals``/``hsi_signals``: rotor name → pressure-signal table (docs/reference/conventions.md; a
    ``total`` group, the sum of the others, is ignored);
    ``observers``: observers artifact; ``trim``: trim artifact (first row = reference rotor,
    whose BPF defines BVISPL); ``solidity``: rotor → σ (blade area A_b = σ π R², C̄_L = 6 C_T/σ);
    ``atmosphere``: absorption over each rotor's hub-observer distance, or None for none.
    ``broadband_msp``: rotor → broadband 1/3-octave band MSP (Pa², (n_observers, STUDY_BANDS), observers
    in ascending id order) computed elsewhere (BPM), used instead of Pegg's when ``broadband_on``; the
    rotors it does not hold get Pegg's (``models.broadband: auto``: BPM for some rotors, Pegg for the others).
    ``tone_sum`` (:data:`nps.noise.signals.TONE_SUMS`): ``coherent`` sums the rotors' pressures, ``incoherent`` their
    mean-square spectra (rotors whose phases are not locked; broadband is an energy sum either way).
    Returns (metrics: one row per observer, bands: observer × source × band, the levels
    object with the narrowband tonal spectra, observers in ascending id order).
    """
    obs = _sorted_observers(observers)
    _check_rotor_sets(trim, signals, hsi_signals)
    ids = obs["observer"].to_numpy()
    positions = obs[["x_m", "y_m", "z_m"]].to_numpy(dtype=float)
    rows = [row for _, row in trim.iterrows()]
    geometry = [_hub_observer_geometry(row, positions) for row in rows]
    check_tone_sum(tone_sum)
    parts, dt = _rotor_tonal_signals(rows, geometry, signals, hsi_signals, ids, atmosphere)
    summed = parts if tone_sum == "incoherent" else coherent_sum(parts)
    broadband_db = _broadband_band_levels(rows, geometry, solidity, atmosphere, broadband_msp) if broadband_on else None
    ref = trim.iloc[0]
    bpf_hz = float(ref["n_blades"]) * float(ref["omega_rad_s"]) / (2.0 * np.pi)
    result = observer_set_metrics(summed, dt, bpf_hz, broadband_db, harmonics, STUDY_BANDS)
    return _metrics_table(obs, result), _bands_table(ids, result), result


def _sorted_observers(observers: pd.DataFrame) -> pd.DataFrame:
    """The observers artifact in ascending observer id; error naming a missing column."""
    for col in OBSERVER_COLUMNS:
        if col not in observers.columns:
            raise ValueError(f"observers: missing column '{col}'")
    return observers.sort_values("observer", kind="mergesort").reset_index(drop=True)


def _check_rotor_sets(trim: pd.DataFrame, signals: Mapping, hsi_signals: Mapping | None) -> None:
    rotors = list(trim["rotor"])
    if set(signals) != set(rotors):
        raise ValueError(f"pressure signals are for rotors {sorted(signals)}, trim has {sorted(rotors)}")
    if hsi_signals is not None and set(hsi_signals) != set(rotors):
        raise ValueError(f"HSI signals are for rotors {sorted(hsi_signals)}, trim has {sorted(rotors)}")


def _hub_observer_geometry(row: pd.Series, positions: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(distance (m), cos θ from the thrust axis) of each observer (n, 3) from one rotor's hub."""
    hub = row[["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(dtype=float)
    axis = row[["r_gh_02", "r_gh_12", "r_gh_22"]].to_numpy(dtype=float)
    return broadband.observer_geometry(hub, axis, positions)


def coherent_sum(parts: Sequence[Mapping[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Source group → p (Pa) summed over ``parts`` (the rotors, in order): the coherent tone sum."""
    summed: dict[str, np.ndarray] = {}
    for part in parts:
        for group, p in part.items():
            summed[group] = summed.get(group, 0.0) + p
    return summed


def _rotor_tonal_signals(rows, geometry, signals, hsi_signals, ids: np.ndarray,
                         atmosphere: AtmosphereState | None) -> tuple[list[dict[str, np.ndarray]], float]:
    """Per rotor (trim order), source group → p (Pa) (n_observers, N), each rotor's signals absorbed over
    its own hub-observer distances; and the sample interval (s)."""
    parts: list[dict[str, np.ndarray]] = []
    time_ref = None
    for row, (dist, _) in zip(rows, geometry):
        name = row["rotor"]
        part: dict[str, np.ndarray] = {}
        tables = [(signals[name], f"pressure signals of rotor '{name}'")]
        if hsi_signals is not None:
            tables.append((hsi_signals[name], f"HSI signals of rotor '{name}'"))
        gains: dict[tuple[int, float], np.ndarray] = {}  # absorption per (N, dt) of this rotor
        for table, what in tables:
            obs_ids, time, groups = signal_arrays(table, what=what)
            if obs_ids.shape != ids.shape or np.any(obs_ids != ids):
                raise ValueError(f"{what}: observers differ from the observers artifact")
            if time_ref is None:
                time_ref = time
            elif time.shape != time_ref.shape or not np.allclose(time, time_ref):
                raise ValueError(f"{what}: time grid differs from the other rotors'")
            dt = float(time[1] - time[0])
            for group, p in groups.items():
                if group == "total":  # a producer's redundant sum of the groups
                    continue
                if group not in TONAL_SOURCES:
                    raise ValueError(f"{what}: unknown group '{group}'")
                if atmosphere is not None:
                    key = (p.shape[-1], dt)
                    if key not in gains:
                        gains[key] = periodic_absorption_gain(p.shape[-1], dt, dist, atmosphere)
                    p = apply_line_gain(p, gains[key])
                part[group] = part.get(group, 0.0) + p
        parts.append(part)
    return parts, float(time_ref[1] - time_ref[0])


def _broadband_band_levels(rows, geometry, solidity: Mapping[str, float], atmosphere: AtmosphereState | None,
                           given_msp: Mapping[str, np.ndarray] | None) -> np.ndarray:
    """Broadband 1/3-octave levels (dB) (n_observers, STUDY_BANDS), energy-summed over the rotors
    (trim order), each absorbed at the mid-band frequencies over its hub distance: a rotor's
    ``given_msp`` (Pa², e.g. BPM) when it holds the rotor, else Pegg's model."""
    centres = third_octave_bands(STUDY_BANDS)["center_hz"]
    bb_msp = np.zeros((geometry[0][0].size, STUDY_BANDS.size))
    for row, (dist, cos_t) in zip(rows, geometry):
        name = row["rotor"]
        if given_msp is not None and name in given_msp:
            given = np.asarray(given_msp[name], dtype=float)
            if given.shape != bb_msp.shape:
                raise ValueError(f"broadband_msp of rotor '{name}': expected shape {bb_msp.shape}, got {given.shape}")
            levels = level_db(given)
        else:
            sigma = float(solidity[name])
            radius = float(row["radius_m"])
            rotor = broadband.PeggRotor(
                thrust_N=float(row["thrust_N"]),
                tip_speed_mps=float(row["omega_rad_s"]) * radius,
                blade_area_m2=sigma * np.pi * radius**2,
                mean_lift_coefficient=broadband.mean_lift_coefficient(float(row["ct"]), sigma),
            )
            levels = broadband.band_levels_db(rotor, STUDY_BANDS, dist, cos_t, float(row["speed_of_sound_mps"]))
        if atmosphere is not None:
            levels = absorb_band_levels(levels, centres, dist[:, None], atmosphere)
        bb_msp += msp_from_level(levels)
    return level_db(bb_msp)


def _metrics_table(obs: pd.DataFrame, result: ObserverSetLevels) -> pd.DataFrame:
    """One row per observer: direction, total levels and OASPL per source present."""
    metrics = pd.DataFrame({
        "observer": obs["observer"].to_numpy().astype(np.int32),
        "elevation_deg": obs["elevation_deg"].to_numpy(dtype=float),
        "azimuth_deg": obs["azimuth_deg"].to_numpy(dtype=float),
        "oaspl_db": result.oaspl_db["total"],
        "oaspl_dba": result.oaspl_dba,
        "bvispl_db": result.bvispl_db,
        "pnl_db": result.pnl_db,
        "pnlt_db": result.pnlt_db,
    })
    for source in ("thickness", "loading", "hsi", "broadband"):
        if source in result.oaspl_db:
            metrics[f"oaspl_{source}_db"] = result.oaspl_db[source]
    return metrics


def _bands_table(ids: np.ndarray, result: ObserverSetLevels) -> pd.DataFrame:
    """Long table observer × source × band of the 1/3-octave levels (dB)."""
    n_obs, n_bands = ids.size, result.band_numbers.size
    centres = third_octave_bands(result.band_numbers)["center_hz"]
    frames = [
        pd.DataFrame({
            "observer": np.repeat(ids.astype(np.int32), n_bands),
            "source": source,
            "band": np.tile(result.band_numbers.astype(np.int32), n_obs),
            "center_hz": np.tile(centres, n_obs),
            "level_db": levels.reshape(-1),
        })
        for source, levels in result.bands_db.items()
    ]
    return pd.concat(frames, ignore_index=True)


def rotor_solidities(aircraft: Mapping) -> dict[str, float]:
    """Rotor name → solidity σ = B c/(π R) from a validated aircraft configuration."""
    # imported here: nps.rotor.geometry loads numba (airfoil kernels), which metrics jobs do not need
    from nps.rotor.geometry import RotorGeometry

    return {str(r["name"]): RotorGeometry.from_config(r).solidity for r in aircraft["rotors"]}
