"""Footprint and certification figures.

:func:`footprint_figure`: a ground metric (SEL or L_Amax, dB) over the grid as filled contours
with the 60/65/70/75/80 dB lines, the ground track and, below, the altitude profile with the
legs' segments. :func:`pnlt_figure`: PNLT(t) at the three certification microphones of each
procedure with each microphone's 10-dB-down window shaded. :func:`certification_figure`: the
EPNLs, limits and margins per aircraft and procedure as a table. Matplotlib (Agg).
"""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from nps.mission.footprint import CONTOUR_LEVELS_DB  # noqa: E402
from nps.plots import save_figure  # noqa: E402


def contour_map(fig, ax, grid: pd.DataFrame, metric: str, levels_db, cmap: str) -> None:
    """A ground metric (``metric`` column of ``grid``: x_m, y_m, dB) on ``ax`` in km: filled 5-dB contours from
    20 dB below the lowest of ``levels_db``, black lines at ``levels_db``, equal axes and the colour bar."""
    for col in ("x_m", "y_m", metric):
        if col not in grid.columns:
            raise ValueError(f"footprint grid: missing column '{col}'")
    x = np.unique(grid["x_m"].to_numpy())
    y = np.unique(grid["y_m"].to_numpy())
    values = grid.sort_values(["x_m", "y_m"])[metric].to_numpy().reshape(x.size, y.size)
    top = float(np.ceil(values.max() / 5.0) * 5.0)
    fill = ax.contourf(x / 1e3, y / 1e3, values.T, levels=np.arange(min(levels_db) - 20.0, top + 5.0, 5.0),
                       cmap=cmap, extend="min")
    lines = ax.contour(x / 1e3, y / 1e3, values.T, levels=list(levels_db), colors="k", linewidths=0.8)
    ax.clabel(lines, fmt="%.0f", fontsize=8)
    ax.set_ylabel("y (km, port +)")
    ax.set_aspect("equal", adjustable="box")
    fig.colorbar(fill, ax=ax, label=f"{'SEL' if metric.startswith('sel') else 'L_Amax'} (dB(A))")


def footprint_figure(grid: pd.DataFrame, knots_m: np.ndarray, segments, metric: str, title: str,
                     path: str | os.PathLike, levels_db=CONTOUR_LEVELS_DB, segment_names=None):
    """``grid``: footprint grid table (x_m, y_m, ``metric``); ``knots_m`` (n_leg + 1, 3) path knots
    (E frame); ``segments``: segment id of each leg; ``segment_names``: optional segment id → mission name,
    written under each leg's id in the altitude profile."""
    knots = np.asarray(knots_m, float)
    fig, (ax, axz) = plt.subplots(2, 1, figsize=(9, 7.5), sharex=True, constrained_layout=True,
                                  gridspec_kw={"height_ratios": [3, 1]})
    contour_map(fig, ax, grid, metric, levels_db, "viridis")
    ax.plot(knots[:, 0] / 1e3, knots[:, 1] / 1e3, "w-", lw=1.5, label="ground track")
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title)
    axz.plot(knots[:, 0] / 1e3, knots[:, 2], "k-")
    names = dict(segment_names or {})
    for k, seg in enumerate(segments):
        axz.annotate(f"{seg}\n{names[seg]}" if seg in names else seg, ((knots[k, 0] + knots[k + 1, 0]) / 2e3, (knots[k, 2] + knots[k + 1, 2]) / 2),
                     ha="center", va="bottom", fontsize=8)
    axz.set_xlabel("x along the track (km)")
    axz.set_ylabel("height (m)")
    axz.set_ylim(0.0, 1.2 * knots[:, 2].max())
    axz.grid(alpha=0.3)
    return save_figure(fig, path)


def pnlt_figure(histories: pd.DataFrame, title: str, path: str | os.PathLike):
    """``histories``: procedure, microphone, time_s, pnlt_db (certification histories table)."""
    for col in ("procedure", "microphone", "time_s", "pnlt_db"):
        if col not in histories.columns:
            raise ValueError(f"certification histories: missing column '{col}'")
    procedures = list(dict.fromkeys(histories["procedure"]))
    fig, axes = plt.subplots(len(procedures), 1, figsize=(8, 2.8 * len(procedures)), constrained_layout=True,
                             squeeze=False)
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.8, 3))
    for ax, proc in zip(axes[:, 0], procedures):
        rows = histories[histories["procedure"] == proc]
        peak = rows["pnlt_db"].max()
        for colour, (mic, h) in zip(colours, rows.groupby("microphone", sort=False)):
            t = h["time_s"].to_numpy()
            p = h["pnlt_db"].to_numpy()
            above = np.flatnonzero(p >= p.max() - 10.0)
            ax.plot(t, p, color=colour, label=f"{mic}: PNLTM {p.max():.1f} TPNdB")
            ax.axvspan(t[above[0]] - 0.25, t[above[-1]] + 0.25, color=colour, alpha=0.15)
        ax.set_ylim(peak - 30.0, peak + 3.0)
        ax.set_ylabel("PNLT (TPNdB)")
        ax.set_title(f"{proc} (shaded: 10-dB-down window per microphone)", fontsize=10)
        ax.legend(fontsize=8, loc="upper right")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("reception time (s)")
    fig.suptitle(title)
    return save_figure(fig, path)


def certification_figure(summary: pd.DataFrame, title: str, path: str | os.PathLike):
    """``summary``: certification summary rows (aircraft, procedure, epnl_db, limit_db, margin_db, …)."""
    for col in ("aircraft", "procedure", "epnl_db", "limit_db", "margin_db"):
        if col not in summary.columns:
            raise ValueError(f"certification summary: missing column '{col}'")
    cols = ["aircraft", "procedure", "epnl_centre_db", "epnl_port_db", "epnl_starboard_db", "epnl_db", "limit_db",
            "margin_db"]
    cols = [c for c in cols if c in summary.columns]
    text = [[row[c] if isinstance(row[c], str) else f"{row[c]:.1f}" for c in cols] for _, row in summary.iterrows()]
    fig, ax = plt.subplots(figsize=(10, 0.45 * len(text) + 1.2), constrained_layout=True)
    ax.axis("off")
    title = f"{title} (EPNdB; microphone EPNLs, their mean, the Chapter 8 limit and the margin)"
    labels = {"epnl_centre_db": "centre", "epnl_port_db": "port", "epnl_starboard_db": "starboard",
              "epnl_db": "EPNL (mean)", "limit_db": "limit", "margin_db": "margin"}
    table = ax.table(cellText=text, colLabels=[labels.get(c, c) for c in cols],
                     loc="center", cellLoc="center")
    table.auto_set_font_size(False)
    table.set_fontsize(8)
    for i, (_, row) in enumerate(summary.iterrows(), start=1):
        table[i, cols.index("margin_db")].set_facecolor("#c7e9c0" if row["margin_db"] >= 0 else "#fcbba1")
    ax.set_title(title)
    return save_figure(fig, path)
