"""Pressure-signal tables: the long format every signal artifact uses, and its array form.

A signal table has one row per observer × source group × sample: ``observer`` (int32), ``group``
(categorical: ``thickness``, ``loading``, ``total``, ``hsi`` …), ``time_s`` (reception time on a
uniform grid shared by all observers and groups) and ``p_Pa`` (acoustic pressure, Pa).
Canonical order: observer, then group, then time (docs/reference/conventions.md "Pressure signals").
This module converts between that table and arrays ``(n_obs, n_groups, n_samples)``; it does no
file I/O (``nps.app.io`` reads and writes artifacts) and knows nothing about rotors.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

SIGNAL_COLUMNS = ("observer", "group", "time_s", "p_Pa")
TOTAL = "total"  # group holding the sum of the other groups
SIGNAL_STAGES = ("acoustics", "wopwop_run", "wopwop_read")
"""Stages that write pressure-signal tables: NPS's acoustics stage, a PSU-WOPWOP case run by NPS, PSU-WOPWOP's own outputs
read by NPS (nps.stages.wopwop_read)."""
TONE_SUMS = ("coherent", "incoherent")
"""How the rotors of an aircraft add (aircraft schema ``tone_sum``, docs/reference/tones.md): ``coherent``
sums their pressures (phases locked), ``incoherent`` their mean-square spectra (phases not locked)."""


def check_tone_sum(tone_sum: str) -> None:
    """Refuse a ``tone_sum`` other than those of :data:`TONE_SUMS`."""
    if tone_sum not in TONE_SUMS:
        raise ValueError(f"tone_sum: expected one of {list(TONE_SUMS)}, got {tone_sum!r}")


def signals_table(ids: np.ndarray, groups, pressure: np.ndarray, grid, total: bool = True) -> pd.DataFrame:
    """Long table ``observer, group, time_s, p_Pa`` from pressures (Pa) of shape (n_obs, n_groups, n_samples).

    ``grid``: the observer time grid (anything with ``times_s``, e.g. :class:`nps.noise.acoustics.TimeGrid`);
    ``total`` appends the group ``total``, the sum over the groups.
    """
    groups = list(groups)
    if total:
        pressure = np.concatenate([pressure, pressure.sum(axis=1, keepdims=True)], axis=1)
        groups = groups + [TOTAL]
    n_obs, n_grp, n_t = pressure.shape
    return pd.DataFrame({
        "observer": np.repeat(np.asarray(ids, dtype=np.int32), n_grp * n_t),
        "group": pd.Categorical.from_codes(np.tile(np.repeat(np.arange(n_grp), n_t), n_obs), categories=groups),
        "time_s": np.tile(grid.times_s, n_obs * n_grp),
        "p_Pa": pressure.reshape(-1),
    })


def check_observers(table: pd.DataFrame, observer_ids, what: str, observers_what: str) -> None:
    """Refuse a signal table whose observers are not exactly those of the observer table (ids
    ``observer_ids`` read from ``observers_what``): a missing observer would vanish from the results."""
    have, want = np.unique(table["observer"].to_numpy()), np.unique(np.asarray(observer_ids))
    missing, extra = np.setdiff1d(want, have), np.setdiff1d(have, want)
    if missing.size or extra.size:
        parts = [f"observer(s) {missing[:5].tolist()}{' ...' if missing.size > 5 else ''} of {observers_what} missing"] * bool(missing.size)
        parts += [f"observer(s) {extra[:5].tolist()}{' ...' if extra.size > 5 else ''} not in {observers_what}"] * bool(extra.size)
        raise ValueError(f"{what}: {'; '.join(parts)} ({have.size} observers, expected {want.size})")


def signal_arrays(table: pd.DataFrame, groups=None, what: str = "pressure signals"
                  ) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Signal artifact → (observer ids (sorted, int32), time_s (N,), group → p_Pa (n_obs, N)).

    The inverse of :func:`signals_table`.
    Every observer needs every group on one shared uniform time grid. ``groups``: the groups
    allowed (default any). Tables in the canonical order of ``signals_table`` (observer,
    then group, then time) are reshaped without sorting; others are sorted first.
    """
    missing = [c for c in SIGNAL_COLUMNS if c not in table.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}; expected {list(SIGNAL_COLUMNS)}")
    if len(table) == 0:
        raise ValueError(f"{what}: no rows")
    time_all = table["time_s"].to_numpy(dtype=float)
    p_all = table["p_Pa"].to_numpy(dtype=float)
    if not (np.isfinite(time_all).all() and np.isfinite(p_all).all()):
        raise ValueError(f"{what}: time_s and p_Pa must be finite")
    obs_values, obs_code = np.unique(table["observer"].to_numpy(), return_inverse=True)
    grp_code, grp_values = pd.factorize(table["group"], sort=True)
    grp_values = [str(g) for g in grp_values]
    unknown = sorted(set(grp_values) - set(groups)) if groups is not None else []
    if unknown:
        raise ValueError(f"{what}: column 'group' has {unknown}; expected {list(groups)}")
    n_obs, n_grp = obs_values.size, len(grp_values)
    key = obs_code.astype(np.int64) * n_grp + grp_code
    counts = np.bincount(key, minlength=n_obs * n_grp)
    if counts.min() == 0 or counts.min() != counts.max():
        raise ValueError(f"{what}: every observer needs every group with the same number of samples")
    n = int(counts[0])
    canonical = bool(np.all(key[1:] >= key[:-1])) and bool(np.all(np.diff(time_all.reshape(-1, n), axis=1) > 0))
    if not canonical:
        order = np.lexsort((time_all, key))
        time_all, p_all = time_all[order], p_all[order]
    times = time_all.reshape(n_obs * n_grp, n)
    step = np.diff(times[0])
    if n < 2 or not np.allclose(step, step[0], rtol=1e-9, atol=0.0):
        raise ValueError(f"{what}: time_s must be a uniform grid of at least 2 samples")
    if not np.allclose(times, times[0], rtol=0.0, atol=1e-9 * (times[0, -1] - times[0, 0])):
        raise ValueError(f"{what}: observers and groups do not share one time grid")
    p = p_all.reshape(n_obs, n_grp, n)
    return obs_values.astype(np.int32), times[0].copy(), {g: p[:, k, :] for k, g in enumerate(grp_values)}
