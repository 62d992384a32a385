"""Level carpet on a microphone plane of a rig (test frame T: x_T downstream, y_T toward the
advancing side of a counterclockwise rotor; docs/reference/rigs.md), viewed from above."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.plots import save_figure


def carpet_figure(planes, level: str, label: str, title: str, path) -> None:
    """Filled contours of column ``level`` over (y_T, x_T) of each plane table (one panel each);
    the free stream runs up the page (x_T up), the advancing side is on the right (y_T)."""
    fig, axes = plt.subplots(1, len(planes), figsize=(4.6 * len(planes) + 0.8, 5.2), squeeze=False)
    for ax, part in zip(axes[0], planes):
        x, y = np.unique(part["x_T_m"]), np.unique(part["y_T_m"])
        grid = np.full((x.size, y.size), np.nan)
        grid[np.searchsorted(x, part["x_T_m"]), np.searchsorted(y, part["y_T_m"])] = part[level]
        filled = ax.contourf(y, x, grid, levels=16, cmap="viridis")
        ax.contour(y, x, grid, levels=filled.levels, colors="k", linewidths=0.3)
        ax.plot(part["y_T_m"], part["x_T_m"], "k.", ms=1.5)
        ax.plot([0.0], [0.0], "r+", ms=10)
        ax.set_xlabel("y_T (m), advancing side →")
        ax.set_ylabel("x_T (m), downstream ↑")
        ax.set_aspect("equal")
        ax.set_title(f"z_T = {part['z_T_m'].iloc[0]:.3g} m")
        fig.colorbar(filled, ax=ax, label=label)
    fig.suptitle(title)
    fig.tight_layout()
    save_figure(fig, path)
