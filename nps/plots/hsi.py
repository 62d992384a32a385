"""Figures of the HSI stage: thesis Fig. 6.3 kind (original, amplified, sheared, shock-fitted)
and time histories of several observers before and after HSI processing."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Mapping

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from nps.plots import save_figure  # noqa: E402

if TYPE_CHECKING:
    from nps.noise.hsi import HsiIntermediate

STEP_TITLES = ("original", "amplified (eq. 6.1)", "sheared (eq. 6.3-6.6)", "shock-fitted (equal area)")


def plot_intermediate_grid(cases: Mapping[str, tuple], path) -> Path:
    """One row per case ``label -> (time_s, p_pa, p_amplified_pa, time_sheared_s, fit: ShockFit)``,
    one column per step; time in ms from the first sample, pressure in Pa."""
    cmap = plt.get_cmap("viridis")
    fig, axes = plt.subplots(len(cases), 4, figsize=(13, 2.4 * len(cases) + 0.6), sharex="row", sharey="row", squeeze=False)
    for row, (label, (t, p, p_amp, t_sh, fit)) in zip(axes, cases.items()):
        t0 = t[0]
        curves = ((t, p), (t, p_amp), (t_sh, p_amp), (fit.time_s, fit.p_pa))
        for k, (ax, (x, y)) in enumerate(zip(row, curves)):
            ax.plot(1e3 * (x - t0), y, color=cmap(0.15 + 0.23 * k), lw=1.0)
            if k == 3 and fit.shock_time_s.size:
                ax.plot(1e3 * (fit.shock_time_s - t0), fit.p_after_pa, "v", color=cmap(0.9), ms=4, label="shock")
                ax.legend(loc="lower right", fontsize=7)
            ax.grid(alpha=0.3)
        row[0].set_ylabel(f"{label}\np [Pa]")
    for ax, title in zip(axes[0], STEP_TITLES):
        ax.set_title(title, fontsize=9)
    for ax in axes[-1]:
        ax.set_xlabel("time [ms]")
    fig.tight_layout()
    return save_figure(fig, path)


def plot_intermediate(inter: HsiIntermediate, path) -> Path:
    """Thesis Fig. 6.3 kind for one observer from :func:`nps.noise.hsi.process`."""
    label = f"obs {inter.observer}, M_r = {inter.mach_r:.3f}"
    return plot_intermediate_grid(
        {label: (inter.time_s, inter.p_original_pa, inter.p_amplified_pa, inter.time_sheared_s, inter.fitted)}, path
    )


def plot_observer_histories(histories: Mapping[str, tuple[np.ndarray, np.ndarray, np.ndarray]], path,
                            title: str = "") -> Path:
    """Stacked time histories ``label -> (time_s, p_original_pa, p_hsi_pa)``, e.g. the five HSI observers
    10 R ahead at 0° … −52° elevation; time in ms from the first sample, pressure in Pa."""
    cmap = plt.get_cmap("cividis")
    fig, axes = plt.subplots(len(histories), 1, figsize=(8, 1.8 * len(histories) + 0.6), sharex=True, squeeze=False)
    for ax, (label, (t, p0, p1)) in zip(axes[:, 0], histories.items()):
        ax.plot(1e3 * (t - t[0]), p0, color=cmap(0.2), lw=0.9, label="without HSI")
        ax.plot(1e3 * (t - t[0]), p1, color=cmap(0.85), lw=1.1, label="with HSI")
        ax.set_ylabel(f"{label}\np [Pa]", fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="lower right", fontsize=7)
    axes[-1, 0].set_xlabel("time [ms]")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    return save_figure(fig, path)
