"""Flight-path noise figures: :func:`path_plan_figure`, the SEL footprint in plan with the ground track coloured by
the loudest A-weighted source level toward the ground and the height profile coloured alike; :func:`path_history_figure`,
L_A(t) at the named microphones. Matplotlib (Agg)."""

from __future__ import annotations

import os
from typing import Mapping, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from nps.mission.footprint import CONTOUR_LEVELS_DB  # noqa: E402
from nps.noise.spectra import LEVEL_FLOOR_DB  # noqa: E402
from nps.plots import save_figure  # noqa: E402
from nps.plots.footprint import contour_map  # noqa: E402


def path_plan_figure(grid: pd.DataFrame, samples, source_below_db: np.ndarray,
                     microphones: Mapping[str, Sequence[float]], title: str, path: str | os.PathLike,
                     levels_db=CONTOUR_LEVELS_DB):
    """``grid``: path footprint grid (x_m, y_m, sel_db); ``samples``: the path samples (position_m, time_s);
    ``source_below_db`` (n,) the loudest source level below the horizon per sample (dB(A) at the hemisphere
    radius, nps.mission.path_noise.source_level_db)."""
    p = np.asarray(samples.position_m, float)
    fig, (ax, axz) = plt.subplots(2, 1, figsize=(9, 8), constrained_layout=True, gridspec_kw={"height_ratios": [3, 1]})
    contour_map(fig, ax, grid, "sel_db", levels_db, "Greys")
    track = ax.scatter(p[:, 0] / 1e3, p[:, 1] / 1e3, c=source_below_db, cmap="plasma", s=6, zorder=3)
    for name, xyz in microphones.items():
        ax.plot(xyz[0] / 1e3, xyz[1] / 1e3, "c^", ms=7, zorder=4)
        ax.annotate(name, (xyz[0] / 1e3, xyz[1] / 1e3), textcoords="offset points", xytext=(4, 4), fontsize=8, color="c")
    ax.set_xlabel("x (km)")
    ax.set_title(title)
    axz.scatter(np.asarray(samples.time_s), p[:, 2], c=source_below_db, cmap="plasma", s=6, norm=track.norm)
    fig.colorbar(track, ax=[axz], label="loudest level below the horizon\n(dB(A) at the hemisphere radius)")
    axz.set_xlabel("time (s)")
    axz.set_ylabel("height (m)")
    axz.set_ylim(0.0, 1.15 * p[:, 2].max())
    axz.grid(alpha=0.3)
    return save_figure(fig, path)


def path_history_figure(histories: pd.DataFrame, title: str, path: str | os.PathLike):
    """L_A(t) at each microphone of ``histories`` (microphone, time_s, la_db); records below the level floor
    (nothing received) are left out."""
    fig, ax = plt.subplots(figsize=(9, 4.5), constrained_layout=True)
    for name, rows in histories.groupby("microphone", sort=False):
        heard = rows["la_db"] > LEVEL_FLOOR_DB
        ax.plot(rows["time_s"][heard], rows["la_db"][heard], label=str(name))
    if histories.empty:
        ax.text(0.5, 0.5, "no microphones in the path's receivers", ha="center", va="center", transform=ax.transAxes)
    else:
        ax.legend(fontsize=8)
    ax.set_xlabel("reception time (s)")
    ax.set_ylabel("L_A (dB(A))")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    return save_figure(fig, path)
