"""Noise certification: EPNL at the three microphones of the Chapter 8 procedures, limits, margins.

Each reference procedure (nps.mission.trajectory) is flown with the aircraft's source hemisphere and
propagated (nps.mission.propagation) to the centre and the two 150 m sideline microphones in the
reference atmosphere. The half-second records are the band levels at reception times
t_k = t_0 + 0.5 k s (the steady levels at the record instants); per microphone PNLT_k, PNLTM,
the 10-dB-down window and EPNL = 10 log10((Δt/10 s) Σ 10^(PNLT_k/10)) come from
:func:`nps.noise.metrics.time_history_metrics` (14 CFR 36 A36.4.3 tone correction, A36.4.5 duration
correction; the A36.4.4 band-sharing adjustment is not applied). The procedure's EPNL is the
arithmetic mean of the three microphones' EPNLs (Chapter 8 evaluation of the three points).

Limits (Stage 3; ICAO Annex 16 Vol. I Chapter 8, 8.4.2, adopted as Stage 3 in 14 CFR Part 36
Appendix H): at a maximum take-off mass M ≥ 80 000 kg 106 (take-off), 104 (overflight) and
109 EPNdB (approach), decreasing linearly with log M at 3 EPNdB per halving of the mass down to
86, 84 and 89 EPNdB (reached at M = 788 kg), constant below:
L(M) = max(L_floor, L_80t + 3 log2(M / 80 000 kg)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from nps.noise.metrics import PNL_BANDS, pnlt, time_history_metrics
from nps.mission.propagation import Ground, Hemisphere, Trajectory, propagate
from nps.mission.trajectory import PROCEDURES, Procedure

RECORD_S = 0.5
LIMIT_MASS_KG = 80_000.0
LIMITS_DB = {"takeoff": (106.0, 86.0), "overflight": (104.0, 84.0), "approach": (109.0, 89.0)}
MICROPHONE_NAMES = ("centre", "port", "starboard")


def noise_limit_epndb(procedure: str, max_mass_kg: float) -> float:
    """Chapter 8 (8.4.2) / Stage 3 limit (EPNdB) of ``procedure`` for the maximum mass (kg)."""
    if procedure not in LIMITS_DB:
        raise ValueError(f"procedure must be one of {PROCEDURES}, got {procedure!r}")
    if not (np.isfinite(max_mass_kg) and max_mass_kg > 0):
        raise ValueError(f"max_mass_kg must be positive, got {max_mass_kg}")
    top, floor = LIMITS_DB[procedure]
    return float(min(top, max(floor, top + 3.0 * np.log2(max_mass_kg / LIMIT_MASS_KG))))


@dataclass(frozen=True)
class ProcedureResult:
    """One procedure: per-microphone table (EPNL, PNLTM, duration, SEL, L_Amax, truncated),
    the PNLT and L_A histories (3, n_t) at ``time_s``, the procedure EPNL, limit and margin."""

    name: str
    microphones: pd.DataFrame
    time_s: np.ndarray
    pnlt_db: np.ndarray
    la_db: np.ndarray
    epnl_db: float
    limit_db: float

    @property
    def margin_db(self) -> float:
        return self.limit_db - self.epnl_db


def reception_times(trajectory: Trajectory, receivers: np.ndarray, c_mps: float, record_s: float = RECORD_S) -> np.ndarray:
    """Half-second reception grid covering every ray from the path to ``receivers``."""
    start = float(trajectory.time_s[0])
    reach = np.linalg.norm(receivers[:, None, :] - np.asarray(trajectory.position_m)[None, :, :], axis=-1).max()
    n = int(np.ceil((float(trajectory.time_s[-1]) - start + reach / c_mps) / record_s)) + 1
    return start + record_s * np.arange(n)


def microphone_histories(bands_db: np.ndarray, band_numbers: np.ndarray, record_s: float = RECORD_S):
    """(metrics per microphone, PNLT histories (n_mic, n_t)) of band histories (n_mic, n_t, n_b)."""
    columns = np.searchsorted(band_numbers, PNL_BANDS)
    rows, histories = [], []
    for levels in bands_db:
        m = time_history_metrics(levels, band_numbers, record_s)
        rows.append({"epnl_db": m.epnl_db, "pnltm_db": m.pnltm_db, "epnl_duration_s": m.epnl_duration_s,
                     "sel_10db_down_db": m.sel_db, "lamax_db": m.lamax_db, "truncated": m.truncated})
        histories.append(pnlt(levels[:, columns]))
    return pd.DataFrame(rows), np.array(histories)


def certify(procedure: Procedure, hemisphere: Hemisphere, max_mass_kg: float, ground: Ground = Ground(),
            absorption: bool = True) -> ProcedureResult:
    """Fly ``procedure`` with ``hemisphere`` and evaluate EPNL at its three microphones (in the
    reference atmosphere; ``absorption=False`` drops the air absorption)."""
    atm = procedure.atmosphere
    path = procedure.path
    trajectory = Trajectory(path.knot_time_s, path.knot_position_m, np.zeros(len(path.legs), dtype=np.int64),
                            (atm if absorption else None,) * len(path.legs))
    times = reception_times(trajectory, procedure.microphones_m, atm.speed_of_sound_mps)
    hist = propagate([hemisphere], trajectory, procedure.microphones_m, times, atm.speed_of_sound_mps, ground,
                     store_bands=True)
    table, pnlt_hist = microphone_histories(hist.bands_db, hist.band_numbers)
    table.insert(0, "microphone", list(MICROPHONE_NAMES))
    table.insert(1, "y_m", procedure.microphones_m[:, 1])
    return ProcedureResult(procedure.name, table, times, pnlt_hist, hist.la_db, float(table["epnl_db"].mean()),
                           noise_limit_epndb(procedure.name, max_mass_kg))


def histories_table(results) -> pd.DataFrame:
    """Procedure × microphone × record: time_s, pnlt_db, la_db of every procedure result."""
    return pd.concat([pd.DataFrame({
        "procedure": r.name,
        "microphone": np.repeat(list(MICROPHONE_NAMES), r.time_s.size),
        "time_s": np.tile(r.time_s, len(MICROPHONE_NAMES)),
        "pnlt_db": r.pnlt_db.ravel(),
        "la_db": r.la_db.ravel(),
    }) for r in results], ignore_index=True)


def summary_table(aircraft: str, max_mass_kg: float, results) -> pd.DataFrame:
    """One row per procedure: EPNL (mean of three microphones), limit, margin, speed, height."""
    return pd.DataFrame({
        "aircraft": aircraft,
        "procedure": [r.name for r in results],
        "max_mass_kg": float(max_mass_kg),
        "epnl_db": [r.epnl_db for r in results],
        "epnl_centre_db": [float(r.microphones["epnl_db"].iloc[0]) for r in results],
        "epnl_port_db": [float(r.microphones["epnl_db"].iloc[1]) for r in results],
        "epnl_starboard_db": [float(r.microphones["epnl_db"].iloc[2]) for r in results],
        "limit_db": [r.limit_db for r in results],
        "margin_db": [r.margin_db for r in results],
    })
