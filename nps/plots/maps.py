"""Observer-hemisphere maps in the thesis convention (docs/reference/conventions.md).

Azimuth on the horizontal axis with straight ahead (180°) at the centre, the main rotor's
advancing side (90°) on the right half and straight behind (0°/360°) at both edges;
elevation on the vertical axis from the rotor plane (0°, top) to straight down (−90°,
bottom). Levels in dB re 20 µPa.
"""

from __future__ import annotations

from typing import Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.plots import save_figure


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
        ax.contour(x, el, grid, levels=levels, colors="k", linewidths=0.4, alpha=0.5)
    if marker is not None:
        ax.plot(map_axis_deg(marker[0]), marker[1], marker="*", color="red", markersize=14,
                markeredgecolor="white", label=f"max at az {marker[0]:.0f}°, el {marker[1]:.0f}°")
        ax.legend(loc="lower right", fontsize=7)
    ax.set_xlim(0.0, 360.0)
    ax.set_ylim(-90.0, 0.0)
    ticks = np.arange(0.0, 361.0, 45.0)
    ax.set_xticks(ticks, [f"{(360 - t) % 360:.0f}" for t in ticks])
    ax.set_xlabel("observer azimuth (deg; 180 ahead, 90 advancing side)")
    ax.set_ylabel("elevation (deg)")
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
