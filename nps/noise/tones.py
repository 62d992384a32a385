"""Rotor tones: level and phase of each blade-passage harmonic, and narrowband line spectra.

A rotor whose blades all see the same periodic disk table radiates, to an observer moving with the
aircraft, a signal of period 1/BPF (BPF = B Ω/2π): its tones are the harmonics m·BPF, m = 1, 2, ….
Each tone is reported as

    p_m(t) = a_m cos(2π f_m t + φ_m),  f_m = m·BPF,
    SPL_m = 20 log10((a_m/√2) / 20 µPa),  φ_m in (−π, π],

t measured from t = 0 of docs/reference/conventions.md (blade 0 of every rotor at ψ = 0, CG at the ground
origin), whatever the first sample time of the record. Equivalently p(t) = Σ_m Re(C_m e^{+i 2π f_m t})
with the complex amplitude C_m = a_m e^{iφ_m} (Pa, peak).

Extraction from a uniformly sampled record p_n = p(t0 + n·Δt), n = 0…N−1:

* when the record spans a whole number K of fundamental periods (N Δt f_1 = K within 1e-9 relative;
  the reference rotor on the aircraft's common grid, or a rotor turning an integer multiple faster),
  the tones are exact DFT lines: C_m = (2/N) X_{mK} e^{−i 2π f_m t0}, X_k = Σ_n p_n e^{−i 2π k n/N};
* otherwise (a tail rotor turning 116/28 times faster than the main rotor: its harmonics fall
  between the lines of the reference grid) the Fourier series of period 1/f_1 with every harmonic
  below the Nyquist frequency (m f_1 ≤ (N/2 − 1)/(N Δt)) is fitted to the samples by linear least
  squares; for a band-limited periodic signal this is exact, and the harmonics, separated by K > 1
  DFT bins, are well conditioned. Records shorter than one period are refused.

Tones above the Nyquist frequency of the record are not represented.
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import pandas as pd

from nps.noise.signals import TOTAL, check_tone_sum, signal_arrays
from nps.noise.spectra import level_db, narrowband_msp

TONE_COLUMNS = ("observer", "source", "harmonic", "frequency_hz", "spl_db", "phase_rad")
SPECTRUM_COLUMNS = ("observer", "source", "frequency_hz", "msp_Pa2", "spl_db")
COMMENSURATE_RTOL = 1e-9


def highest_harmonic(n_samples: int, dt_s: float, fundamental_hz: float) -> int:
    """Highest harmonic m of ``fundamental_hz`` resolved by the record: m·f_1 ≤ (N/2 − 1)/(N Δt)."""
    return int(np.floor((n_samples / 2 - 1) / (n_samples * dt_s * fundamental_hz) * (1 + COMMENSURATE_RTOL)))


def harmonic_amplitudes(p_pa, t0_s: float, dt_s: float, fundamental_hz: float, n_harmonics: int) -> np.ndarray:
    """Complex amplitudes C_m (Pa, peak), m = 1…``n_harmonics``, of a periodic signal (module docstring).

    ``p_pa``: samples on the last axis, at t0_s + n·dt_s (s); ``fundamental_hz`` f_1 (the BPF for a
    rotor's tones). Returns shape p.shape[:-1] + (n_harmonics,); p(t) ≈ mean + Σ Re(C_m e^{i 2π m f_1 t}).
    """
    p = np.asarray(p_pa, dtype=float)
    n = p.shape[-1] if p.ndim else 0
    if n < 8 or not np.all(np.isfinite(p)):
        raise ValueError(f"harmonic_amplitudes: p_pa needs at least 8 finite samples on its last axis, got shape {p.shape}")
    if not (np.isfinite(dt_s) and dt_s > 0.0 and np.isfinite(fundamental_hz) and fundamental_hz > 0.0 and np.isfinite(t0_s)):
        raise ValueError(f"harmonic_amplitudes: dt_s and fundamental_hz must be positive and finite, got {dt_s}, {fundamental_hz}")
    cycles = n * dt_s * fundamental_hz
    if cycles < 1.0 - COMMENSURATE_RTOL:
        raise ValueError(f"harmonic_amplitudes: the record spans {cycles:.3g} periods of {fundamental_hz:g} Hz; at least one is needed")
    top = highest_harmonic(n, dt_s, fundamental_hz)
    if not 1 <= n_harmonics <= top:
        raise ValueError(f"harmonic_amplitudes: n_harmonics must be 1…{top} (below the Nyquist frequency), got {n_harmonics}")
    m = np.arange(1, n_harmonics + 1)
    k = round(cycles)
    if abs(cycles - k) <= COMMENSURATE_RTOL * cycles:
        lines = np.fft.rfft(p, axis=-1)[..., m * k]
        return 2.0 / n * lines * np.exp(-2j * np.pi * m * fundamental_hz * t0_s)
    phase = 2.0 * np.pi * fundamental_hz * (t0_s + dt_s * np.arange(n))[:, None] * np.arange(1, top + 1)[None, :]
    design = np.concatenate([np.ones((n, 1)), np.cos(phase), np.sin(phase)], axis=1)
    coef = np.linalg.lstsq(design, p.reshape(-1, n).T, rcond=None)[0]
    amplitudes = (coef[1 : 1 + n_harmonics] - 1j * coef[1 + top : 1 + top + n_harmonics]).T
    return amplitudes.reshape(p.shape[:-1] + (n_harmonics,))


def tone_levels(amplitudes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(SPL (dB re 20 µPa) of each tone's rms a/√2, phase φ (rad, (−π, π])) of complex amplitudes C_m."""
    amplitudes = np.asarray(amplitudes)
    return level_db(np.abs(amplitudes) ** 2 / 2.0), np.angle(amplitudes)


def blade_passage_hz(trim_row) -> float:
    """BPF (Hz) = B Ω / 2π of a trim row."""
    return float(trim_row["n_blades"]) * float(trim_row["omega_rad_s"]) / (2.0 * np.pi)


def _rotor_pressures(signals: Mapping[str, pd.DataFrame], rotors) -> tuple[np.ndarray, np.ndarray, dict, dict, dict]:
    """Observer ids, time grid, rotor → p (n_obs, N) summed over groups, group → p summed over rotors,
    rotor → (group → p)."""
    ids_ref = time_ref = None
    per_rotor, per_group, parts = {}, {}, {}
    for name in rotors:
        what = f"pressure signals of rotor '{name}'"
        ids, time, groups = signal_arrays(signals[name], what=what)
        if ids_ref is None:
            ids_ref, time_ref = ids, time
        elif ids.shape != ids_ref.shape or np.any(ids != ids_ref):
            raise ValueError(f"{what}: observers differ from rotor '{rotors[0]}'")
        elif time.shape != time_ref.shape or not np.allclose(time, time_ref):
            raise ValueError(f"{what}: time grid differs from rotor '{rotors[0]}'")
        groups = {g: p for g, p in groups.items() if g != TOTAL}  # a producer's redundant sum of the groups
        per_rotor[name], parts[name] = sum(groups.values()), groups
        for g, p in groups.items():
            per_group[g] = per_group.get(g, 0.0) + p
    return ids_ref, time_ref, per_rotor, per_group, parts


def tone_table(signals: Mapping[str, pd.DataFrame], trim: pd.DataFrame, n_harmonics: int,
               tone_sum: str = "coherent") -> pd.DataFrame:
    """Tone table of an aircraft at one observer set: one row per observer × source × harmonic.

    ``signals``: rotor name → signal table (docs/reference/conventions.md; all rotors on one grid);
    ``trim``: trim artifact, rows in aircraft order, the first is the reference rotor.
    ``source`` is a rotor name (that rotor's signal, all groups: harmonics m of its own BPF) or
    ``total`` (harmonics m of the reference rotor's BPF: the sum of the complex amplitudes of every
    rotor's tone at exactly that frequency; a rotor whose harmonics fall between them, such as a tail
    rotor at a non-integer speed ratio, has its tones in its own rows only); with ``tone_sum``
    ``incoherent`` (rotors whose phases are not locked) the total's mean-square pressure is the sum of
    theirs, |C|² = Σ|C_j|², and its phase_rad is 0 (an energy sum has no phase). m = 1…``n_harmonics``,
    fewer where the record's Nyquist frequency cuts them off. Columns :data:`TONE_COLUMNS`; free field
    (no air absorption), the acoustics signals as radiated (no HSI processing).
    """
    if n_harmonics < 1:
        raise ValueError(f"n_harmonics: expected an integer >= 1, got {n_harmonics}")
    check_tone_sum(tone_sum)
    rotors = list(trim["rotor"])
    if set(signals) != set(rotors):
        raise ValueError(f"pressure signals are for rotors {sorted(signals)}, trim has {sorted(rotors)}")
    ids, time, per_rotor, _, _ = _rotor_pressures(signals, rotors)
    dt, t0 = float(time[1] - time[0]), float(time[0])
    bpfs = [blade_passage_hz(row) for _, row in trim.iterrows()]
    amplitudes = {}  # every harmonic the record resolves, per rotor
    for name, bpf in zip(rotors, bpfs):
        top = highest_harmonic(time.size, dt, bpf)
        if top < 1:
            raise ValueError(f"rotor '{name}': BPF {bpf:g} Hz is above the Nyquist frequency of the signals")
        amplitudes[name] = harmonic_amplitudes(per_rotor[name], t0, dt, bpf, top)
    # total: at m·BPF_ref, the sum of the rotors whose harmonic n·BPF_j falls exactly there
    m_ref = np.arange(1, min(int(n_harmonics), amplitudes[rotors[0]].shape[-1]) + 1)
    total = np.zeros((ids.size, m_ref.size), dtype=complex)
    for name, bpf in zip(rotors, bpfs):
        n = m_ref * bpfs[0] / bpf
        k = np.rint(n).astype(np.int64)
        hit = (np.abs(n - k) <= COMMENSURATE_RTOL * n) & (k >= 1) & (k <= amplitudes[name].shape[-1])
        if tone_sum == "incoherent":
            total[:, hit] += np.abs(amplitudes[name][:, k[hit] - 1]) ** 2
        else:
            total[:, hit] += amplitudes[name][:, k[hit] - 1]
    if tone_sum == "incoherent":
        total = np.sqrt(total.real) + 0j
    sources = [(name, amplitudes[name][:, :n_harmonics], bpf) for name, bpf in zip(rotors, bpfs)]
    sources.append((TOTAL, total, bpfs[0]))
    frames = []
    for source, c, bpf in sources:
        m = c.shape[-1]
        spl, phase = tone_levels(c)
        frames.append(pd.DataFrame({
            "observer": np.repeat(ids, m).astype(np.int32),
            "source": source,
            "harmonic": np.tile(np.arange(1, m + 1, dtype=np.int32), ids.size),
            "frequency_hz": np.tile(bpf * np.arange(1, m + 1), ids.size),
            "spl_db": spl.reshape(-1),
            "phase_rad": phase.reshape(-1),
        }))
    return pd.concat(frames, ignore_index=True)


def _fluctuation_power(p: np.ndarray) -> np.ndarray:
    return np.mean((p - p.mean(axis=-1, keepdims=True)) ** 2, axis=-1)


TIE_DB = 1e-6  # levels this close rank as equal (loudest_observers)


def loudest_observers(signals: Mapping[str, pd.DataFrame], rotors, count: int, tone_sum: str = "coherent") -> np.ndarray:
    """Ids of the ``count`` observers with the highest mean-square total pressure; ``tone_sum``
    ``incoherent``: the sum of the rotors' mean-square pressures. Levels are ranked rounded to multiples
    of ``TIE_DB``, so that mirror observers of a symmetric set (equal but for rounding) tie, and a tie takes
    the lower id first: the choice does not follow the last bits of the arithmetic."""
    check_tone_sum(tone_sum)
    ids, _, per_rotor, _, _ = _rotor_pressures(signals, list(rotors))
    if tone_sum == "incoherent":
        power = sum(_fluctuation_power(p) for p in per_rotor.values())
    else:
        power = _fluctuation_power(sum(per_rotor.values()))
    with np.errstate(divide="ignore"):
        level = np.round(10.0 * np.log10(power) / TIE_DB)
    order = np.lexsort((ids, -level))
    return np.sort(ids[order[: max(0, int(count))]])


def narrowband_table(signals: Mapping[str, pd.DataFrame], rotors, observers, tone_sum: str = "coherent") -> pd.DataFrame:
    """Narrowband line spectra at ``observers`` (ids): one row per observer × source × line.

    ``source``: each source group (``thickness``, ``loading``, …) summed over the rotors, and
    ``total``; lines k/(N Δt), k = 1…⌊N/2⌋ of the record (one reference-rotor revolution: every line
    a harmonic of the reference shaft frequency), unwindowed: Σ msp = mean-square pressure
    (:func:`nps.noise.spectra.narrowband_msp`). ``msp_Pa2`` and ``spl_db`` (dB re 20 µPa) per line; free
    field, no broadband (its 1/3-octave bands are in the metrics' band table). ``tone_sum``
    ``incoherent``: every source's spectrum is the sum of the rotors' mean-square spectra.
    """
    check_tone_sum(tone_sum)
    ids, time, _, per_group, parts = _rotor_pressures(signals, list(rotors))
    wanted = np.asarray(observers, dtype=np.int64)
    missing = sorted(set(wanted.tolist()) - set(ids.tolist()))
    if missing:
        raise ValueError(f"observers {missing} are not in the pressure signals (observers {ids.min()}…{ids.max()})")
    rows = np.searchsorted(ids, np.sort(wanted))
    dt = float(time[1] - time[0])
    if tone_sum == "incoherent":
        coherent_sets = [{**groups, TOTAL: sum(groups.values())} for groups in parts.values()]
    else:
        coherent_sets = [{**per_group, TOTAL: sum(per_group.values())}]
    frames = []
    for source in coherent_sets[0]:
        spectra = [narrowband_msp(sets[source][rows], dt) for sets in coherent_sets]
        freq, msp = spectra[0][0], sum(m for _, m in spectra)
        freq, msp = freq[1:], msp[:, 1:]  # the 0 Hz line (mean pressure) is not sound
        frames.append(pd.DataFrame({
            "observer": np.repeat(ids[rows], freq.size).astype(np.int32),
            "source": source,
            "frequency_hz": np.tile(freq, rows.size),
            "msp_Pa2": msp.reshape(-1),
            "spl_db": level_db(msp).reshape(-1),
        }))
    table = pd.concat(frames, ignore_index=True)
    return table.sort_values(["observer"], kind="mergesort").reset_index(drop=True)
