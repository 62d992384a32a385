"""Figures of the acoustics stage: pressure time histories of several observers, per source group
(thickness, loading, summed over the aircraft's rotors) and total.

Observers are picked by direction in the map convention of docs/reference/conventions.md (azimuth from
straight behind toward the main rotor's advancing side, 180° ahead; elevation negative below)
plus the loudest observer of the set. Hemisphere maps of any level are drawn by
:func:`nps.plots.maps.hemisphere_map` (thesis convention: ahead at the centre, advancing side on
the right, behind at both edges, elevation 0° at the top to −90° at the bottom).
"""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from nps.plots import save_figure  # noqa: E402
from nps.plots.maps import direction_name  # noqa: E402
import pandas as pd  # noqa: E402

from nps.core.frames import observer_direction  # noqa: E402
from nps.noise.signals import signal_arrays  # noqa: E402

# label -> (azimuth_deg, elevation_deg) of the observers shown besides the loudest one
DIRECTIONS = {
    "ahead, 30° below": (180.0, -30.0),
    "advancing side, 30° below": (90.0, -30.0),
    "retreating side, 30° below": (270.0, -30.0),
    "behind, 30° below": (0.0, -30.0),
    "straight below": (0.0, -90.0),
}
GROUPS = ("thickness", "loading")


def group_signals(tables: Sequence[pd.DataFrame]) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Sum signal tables (observer, group, time_s, p_Pa) of several rotors on their common grid.

    Returns (observer ids, time_s (n,), group → p_Pa (n_obs, n)) for ``thickness``, ``loading``
    and ``total`` (their sum); a ``total`` group present in a table is ignored.
    """
    ids = time = None
    summed = {}
    for table in tables:
        obs, t, groups = signal_arrays(table[table["group"].isin(GROUPS)], GROUPS)
        if ids is None:
            ids, time = obs, t
        elif not (np.array_equal(obs, ids) and np.allclose(t, time, rtol=0.0, atol=1e-9 * max(1.0, abs(time[-1])))):
            raise ValueError("pressure signals: the rotors' tables do not share observers and time grid")
        for group, p in groups.items():
            summed[group] = summed.get(group, 0.0) + p
    summed["total"] = sum(summed.values())
    return ids, time, summed


def nearest_observer(observers: pd.DataFrame, azimuth_deg: float, elevation_deg: float) -> int:
    """Id of the observer whose direction (``azimuth_deg``, ``elevation_deg`` columns) is closest."""
    target = observer_direction(np.radians(azimuth_deg), np.radians(elevation_deg))
    dirs = observer_direction(np.radians(observers["azimuth_deg"].to_numpy(float)),
                              np.radians(observers["elevation_deg"].to_numpy(float)))
    return int(observers["observer"].to_numpy()[np.argmax(np.asarray(dirs).reshape(-1, 3) @ target)])


def _unit_direction(observers: pd.DataFrame, observer: int) -> np.ndarray:
    row = observers[observers["observer"] == observer].iloc[0]
    return np.asarray(observer_direction(np.radians(float(row["azimuth_deg"])), np.radians(float(row["elevation_deg"])))).ravel()


def pick_observers(observers: pd.DataFrame, ids: np.ndarray, total_pa: np.ndarray) -> dict[str, int]:
    """label → observer id: the loudest (largest rms of the total) and those nearest to DIRECTIONS, each
    direction once: an observer at the direction of one already picked (the straight-down point, which every
    azimuth of a hemisphere grid repeats) is left out."""
    rms = np.sqrt(np.mean((total_pa - total_pa.mean(axis=1, keepdims=True)) ** 2, axis=1))
    loud = int(ids[np.argmax(rms)])
    row = observers[observers["observer"] == loud].iloc[0]
    picks = {f"loudest ({direction_name(row['azimuth_deg'], row['elevation_deg'])})": loud}
    seen = [_unit_direction(observers, loud)]
    for label, (az, el) in DIRECTIONS.items():
        obs = nearest_observer(observers, az, el)
        direction = _unit_direction(observers, obs)
        if all(np.dot(direction, other) < 1.0 - 1e-9 for other in seen):
            picks[label] = obs
            seen.append(direction)
    return picks


def pressure_histories(signals_by_rotor: Mapping[str, pd.DataFrame], observers: pd.DataFrame, path, *,
                       picks: Mapping[str, int] | None = None, title: str = "") -> Path:
    """Stacked time histories (one panel per observer) of thickness, loading and total pressure (Pa),
    summed over the rotors of ``signals_by_rotor``, against time in ms (one reference revolution).

    ``picks``: label → observer id; by default :func:`pick_observers` (loudest and DIRECTIONS).
    """
    ids, time, groups = group_signals(list(signals_by_rotor.values()))
    picks = pick_observers(observers, ids, groups["total"]) if picks is None else dict(picks)
    index = {int(o): k for k, o in enumerate(ids)}
    cmap = plt.get_cmap("viridis")
    colours = {"thickness": cmap(0.75), "loading": cmap(0.4), "total": cmap(0.0)}
    fig, axes = plt.subplots(len(picks), 1, figsize=(8.0, 1.9 * len(picks) + 0.9), sharex=True, squeeze=False)
    for ax, (label, obs) in zip(axes[:, 0], picks.items()):
        for group in ("thickness", "loading", "total"):
            ax.plot(1e3 * time, groups[group][index[obs]], color=colours[group], lw=1.6 if group == "total" else 1.0,
                    label=group)
        ax.set_ylabel("p [Pa]")
        ax.set_title(f"observer {obs}: {label}", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="upper right", fontsize=7, ncol=3)
    axes[-1, 0].set_xlabel("time [ms]")
    fig.suptitle(title + (f" ({', '.join(signals_by_rotor)})" if title else ""), fontsize=10)
    fig.tight_layout()
    return save_figure(fig, path)
