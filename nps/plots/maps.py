"""Observer-hemisphere maps in the thesis convention (docs/reference/conventions.md).

Azimuth on the horizontal axis with straight ahead (180°) at the centre, the main rotor's
advancing side (90°) on the right half and straight behind (0°/360°) at both edges;
elevation on the vertical axis from the rotor plane (0°, top) to straight down (−90°,
bottom). Levels in dB re 20 µPa. Every map says the orientation on its axis (:data:`AZIMUTH_NOTE`), labels
its contour lines and names a direction once: the straight-down point (el −90°), which every azimuth of
the hemisphere grid repeats, is one observer direction (:func:`distinct_directions`, :func:`direction_name`).
"""

from __future__ import annotations

from typing import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.plots import save_figure


AZIMUTH_NOTE = "az 0° behind, 90° advancing side, 180° ahead, 270° retreating side"
# the words under the ticks of the map's horizontal axis (observer azimuth)
AZIMUTH_WORDS = {0.0: "behind", 90.0: "advancing", 180.0: "ahead", 270.0: "retreating"}
POLE_TOLERANCE_DEG = 1e-6


def is_pole(elevation_deg) -> np.ndarray:
    """True where the elevation is ±90° (straight below or above: one point whatever the azimuth)."""
    return np.abs(np.abs(np.asarray(elevation_deg, dtype=float)) - 90.0) <= POLE_TOLERANCE_DEG


def direction_name(azimuth_deg: float, elevation_deg: float) -> str:
    """A direction in the map convention (docs/reference/conventions.md, "Observer azimuth"), e.g.
    "az 135° (ahead, advancing side), el −30°"; the poles are "straight below" / "straight above" without
    an azimuth."""
    if is_pole(elevation_deg):
        return "straight below" if elevation_deg < 0.0 else "straight above"
    az = float(azimuth_deg) % 360.0
    fore = "behind" if az < 90.0 or az > 270.0 else ("ahead" if 90.0 < az < 270.0 else "")
    side = "advancing side" if 0.0 < az < 180.0 else ("retreating side" if az > 180.0 else "")
    where = ", ".join(w for w in (fore, side) if w)
    return f"az {az:.0f}° ({where}), el {float(elevation_deg):.0f}°".replace("-", "−")


def distinct_directions(table, order_by: str | None = None, ascending: bool = False):
    """Rows of an observer table (``azimuth_deg``, ``elevation_deg``, ``observer``) with the pole collapsed:
    of the observers at el ±90° (the same point for every azimuth) only the first is kept, after sorting by
    ``order_by`` (then by observer id) when given. A "loudest observers" list taken from the result names
    the straight-down point once."""
    rows = table.sort_values([order_by, "observer"] if order_by else ["observer"],
                             ascending=[ascending, True] if order_by else [True], kind="mergesort")
    elevation = rows["elevation_deg"].to_numpy(dtype=float)
    pole = is_pole(elevation)
    repeated = np.zeros(len(rows), dtype=bool)
    for sign in (-1.0, 1.0):
        at_pole = np.flatnonzero(pole & (np.sign(elevation) == sign))
        repeated[at_pole[1:]] = True
    return rows[~repeated]


def map_axis_deg(azimuth_deg) -> np.ndarray:
    """Horizontal map coordinate: (360° − azimuth) so that 180° (ahead) is at the centre and
    the advancing side (90°) falls on the right, 270° on the left; 0° maps to 360° (right edge)
    and behind also appears at the left edge through the periodic copy added by the plot."""
    return (360.0 - np.asarray(azimuth_deg, dtype=float)) % 360.0


def _grid(azimuth_deg, elevation_deg, level_db):
    """Regular (elevation × azimuth) grid with a periodic column so both edges show 'behind'."""
    az = np.asarray(azimuth_deg, dtype=float)
    el = np.asarray(elevation_deg, dtype=float)
    x_unique = np.unique(map_axis_deg(az))
    el_unique = np.unique(el)
    grid = np.full((el_unique.size, x_unique.size), np.nan)
    grid[np.searchsorted(el_unique, el), np.searchsorted(x_unique, map_axis_deg(az))] = level_db
    if x_unique[0] > 0.0 or x_unique[-1] < 360.0:
        x_unique = np.concatenate([x_unique, [x_unique[0] + 360.0]])
        grid = np.concatenate([grid, grid[:, :1]], axis=1)
    # the straight-down observer, when present, is one point: spread it along the bottom row
    bottom = el_unique == -90.0
    if bottom.any():
        row = grid[bottom][0]
        grid[bottom] = np.nanmean(row) if np.isnan(row).any() else row
    return x_unique, el_unique, grid


def hemisphere_map(ax, azimuth_deg, elevation_deg, level_db, *, vmin=None, vmax=None, title="",
                   colour_label="OASPL (dB re 20 µPa)", marker: Sequence[float] | None = None, cmap="viridis"):
    """Draw one map on ``ax``; ``marker`` = (azimuth_deg, elevation_deg) of a hotspot."""
    x, el, grid = _grid(azimuth_deg, elevation_deg, level_db)
    mesh = ax.pcolormesh(x, el, grid, shading="gouraud", cmap=cmap, vmin=vmin, vmax=vmax)
    levels = np.arange(np.floor(np.nanmin(grid)), np.ceil(np.nanmax(grid)) + 1.0, 2.0)
    if levels.size > 1:
        lines = ax.contour(x, el, grid, levels=levels, colors="k", linewidths=0.4, alpha=0.6)
        ax.clabel(lines, levels=lines.levels[::2], fmt="%.0f", fontsize=6, inline=True)
    if marker is not None:
        # the straight-down point is the whole bottom row of the map: its marker goes under "ahead"
        x_marker = 180.0 if is_pole(marker[1]) else map_axis_deg(marker[0])
        ax.plot(x_marker, marker[1], marker="*", color="red", markersize=14, markeredgecolor="white",
                label=f"max: {direction_name(marker[0], marker[1])}", clip_on=False)
        ax.legend(loc="lower right", fontsize=7)
    ax.set_xlim(0.0, 360.0)
    ax.set_ylim(-90.0, 0.0)
    ticks = np.arange(0.0, 361.0, 45.0)
    azimuths = (360.0 - ticks) % 360.0
    ax.set_xticks(ticks, [f"{a:.0f}\n{AZIMUTH_WORDS[a]}" if a in AZIMUTH_WORDS else f"{a:.0f}" for a in azimuths],
                  fontsize=7)
    ax.set_xlabel(f"observer azimuth (deg; {AZIMUTH_NOTE})", fontsize=8)
    ax.set_ylabel("elevation (deg; −90 straight below)")
    ax.set_title(title, fontsize=9)
    colourbar = plt.colorbar(mesh, ax=ax)
    colourbar.set_label(colour_label)
    return mesh


def map_panels(panels, path, *, suptitle="", colour_label="OASPL (dB re 20 µPa)", shared_scale=True, ncols=2):
    """Figure of several maps. ``panels``: list of dicts with azimuth_deg, elevation_deg,
    level_db, title and optional marker. A shared colour scale when ``shared_scale``."""
    levels = np.concatenate([np.asarray(p["level_db"], dtype=float) for p in panels])
    vmin, vmax = (float(np.min(levels)), float(np.max(levels))) if shared_scale else (None, None)
    nrows = int(np.ceil(len(panels) / ncols))
    fig, axes = plt.subplots(nrows, min(ncols, len(panels)), figsize=(6.2 * min(ncols, len(panels)), 3.6 * nrows), squeeze=False)
    for ax, panel in zip(axes.flat, panels):
        hemisphere_map(ax, panel["azimuth_deg"], panel["elevation_deg"], panel["level_db"], vmin=vmin, vmax=vmax,
                       title=panel["title"], colour_label=colour_label, marker=panel.get("marker"))
    for ax in list(axes.flat)[len(panels):]:
        ax.set_visible(False)
    fig.suptitle(suptitle)
    fig.tight_layout()
    save_figure(fig, path)
