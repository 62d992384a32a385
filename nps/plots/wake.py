"""Figures of the wake and BVI stage (matplotlib, Agg; perceptually uniform colormaps).

- :func:`wake_views`: tip-vortex geometry with the blades, top and side view (thesis Fig. 5.6),
  hub frame H, flight toward the left (x_H aft to the right).
- :func:`bvi_disk_figure`: induced velocity and BVI loading disk maps with contour lines
  (thesis Figs. 5.7–5.8), drawn with ``nps.plots.disk.disk_plot`` (flight toward the top).
- :func:`hart_ii_loading`, :func:`hart_ii_vortices`: HART-II comparisons.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

from nps.plots.disk import disk_plot  # noqa: E402


def wake_views(nodes_h_m: np.ndarray, blades_h_m: np.ndarray, radius_m: float, title: str = "",
               ages_rev: np.ndarray | None = None):
    """Top (x_H–y_H) and side (x_H–z_H) views on one length scale, lengths in rotor radii.

    ``nodes_h_m`` (B, N, 3) vortex nodes in H; ``blades_h_m`` (B, 2, 3) root and tip of each
    blade in H; ``ages_rev`` (B, N) the nodes' wake age in revolutions (colour; without it the node
    index over the last). The panels share the x axis and their heights follow the drawn extents, so
    neither view is a sliver and no white band separates them; the colour bar runs under both.
    """
    nodes = np.asarray(nodes_h_m) / radius_m
    blades = np.asarray(blades_h_m) / radius_m
    n_age = nodes.shape[1]
    ages = (np.tile(np.arange(n_age) / max(n_age - 1, 1), (nodes.shape[0], 1)) if ages_rev is None
            else np.asarray(ages_rev, dtype=float))
    points = np.concatenate([nodes.reshape(-1, 3), blades.reshape(-1, 3)])
    low, high = points.min(axis=0) - 0.1, points.max(axis=0) + 0.1
    extent = np.maximum(high - low, 0.4)
    width_in = 8.0
    heights = [width_in * extent[1] / extent[0], width_in * extent[2] / extent[0]]
    fig, (top, side) = plt.subplots(2, 1, figsize=(width_in + 1.2, sum(heights) + 2.4), sharex=True,
                                    height_ratios=heights, layout="constrained")
    norm = plt.Normalize(0.0, float(ages.max()) or 1.0)
    for ax, j, ylabel in ((top, 1, "y_H / R (starboard)"), (side, 2, "z_H / R (up, thrust)")):
        for k in range(nodes.shape[0]):
            segs = np.stack([nodes[k, :-1][:, [0, j]], nodes[k, 1:][:, [0, j]]], axis=1)
            lc = LineCollection(segs, cmap="viridis", norm=norm, linewidths=0.9)
            lc.set_array(0.5 * (ages[k, :-1] + ages[k, 1:]))
            ax.add_collection(lc)
            ax.plot(blades[k, :, 0], blades[k, :, j], color="k", lw=3)
        ax.set_xlim(low[0], high[0])
        ax.set_ylim(low[j], low[j] + extent[j])
        ax.set_aspect("equal")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    top.set_title("top view, looking down the shaft", fontsize=9)
    side.set_title("side view from port", fontsize=9)
    side.set_xlabel("x_H / R (aft; flight toward the left)")
    fig.suptitle(title or "Tip-vortex wake")
    fig.colorbar(lc, ax=[top, side], location="bottom", shrink=0.6, aspect=40,
                 label="wake age (rotor revolutions)" if ages_rev is not None else "wake age / maximum age")
    return fig


def bvi_disk_figure(psi_rad, r_m, d_up_mps, fz_base, fz_bvi, *, rotation_sign: int = 1, contour_step_N_per_m=None, title=""):
    """Three disk maps (``nps.plots.disk.disk_plot``, flight toward the top): wake-induced ΔU_P
    (m/s), trimmed and BVI F_z (N/m); the BVI panel has contour lines every
    ``contour_step_N_per_m`` (default: 32 levels over the range, as thesis Fig. 5.8)."""
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.2), layout="constrained")
    lim = float(np.abs(d_up_mps).max()) or 1.0
    disk_plot(psi_rad, r_m, d_up_mps, rotation_sign=rotation_sign, ax=axes[0], label="ΔU_P (m/s, + down)",
              title="wake-induced ΔU_P", cmap="cividis", vmin=-lim, vmax=lim, contour_levels=None)
    lo, hi = float(min(fz_base.min(), fz_bvi.min())), float(max(fz_base.max(), fz_bvi.max()))
    step = contour_step_N_per_m or (hi - lo) / 32
    levels = np.arange(np.floor(lo / step), np.ceil(hi / step) + 1) * step
    disk_plot(psi_rad, r_m, fz_base, rotation_sign=rotation_sign, ax=axes[1], label="F_z (N/m)",
              title="trimmed loading", vmin=lo, vmax=hi, contour_levels=None)
    disk_plot(psi_rad, r_m, fz_bvi, rotation_sign=rotation_sign, ax=axes[2], label="F_z (N/m)",
              title=f"with BVI (contours every {step:.3g} N/m)", vmin=lo, vmax=hi, contour_levels=None)
    psi_c, r_c = np.meshgrid(np.append(psi_rad, psi_rad[0] + 2 * np.pi), r_m, indexing="ij")
    axes[2].contour(rotation_sign * r_c * np.sin(psi_c), -r_c * np.cos(psi_c), np.vstack([fz_bvi, fz_bvi[:1]]),
                    levels=levels, colors="k", linewidths=0.35)
    fig.suptitle(title)
    return fig


def hart_ii_loading(psi_meas_deg, cn_meas, psi_model_deg, cn_base, cn_bvi, cn_high_pass=None, title=""):
    """M²C_n vs ψ: measured, trimmed and BVI model; optional second panel of high-passed signals
    ``cn_high_pass`` = (measured, model)."""
    rows = 2 if cn_high_pass is not None else 1
    fig, axes = plt.subplots(rows, 1, figsize=(10, 3.6 * rows), squeeze=False, layout="constrained")
    colors = plt.get_cmap("viridis")([0.0, 0.45, 0.8])
    ax = axes[0, 0]
    ax.plot(psi_meas_deg, cn_meas, color=colors[0], label="HART-II measured (BL)")
    ax.plot(psi_model_deg, cn_base, color=colors[2], label="NPS trimmed BET")
    ax.plot(psi_model_deg, cn_bvi, color=colors[1], label="NPS with BVI")
    ax.set_ylabel("M²C_n at r/R = 0.87")
    ax.set_title(title)
    if cn_high_pass is not None:
        axes[1, 0].plot(psi_meas_deg, cn_high_pass[0], color=colors[0], label="measured, ≥ 10/rev")
        axes[1, 0].plot(psi_model_deg, cn_high_pass[1], color=colors[1], label="NPS BVI, ≥ 10/rev")
        axes[1, 0].set_ylabel("M²C_n, harmonics ≥ 10")
    for a in axes[:, 0]:
        for lo, hi in ((30, 80), (280, 330)):
            a.axvspan(lo, hi, color="0.9", zorder=0)
        a.set_xlim(0, 360)
        a.set_xticks(np.arange(0, 361, 30))
        a.set_xlabel("blade azimuth ψ (deg)")
        a.grid(alpha=0.3)
        a.legend(loc="lower right", fontsize=8)
    return fig


def hart_ii_vortices(records, title=""):
    """PIV vs predicted tip-vortex positions in the cut planes y = const (x–z, m).

    ``records``: tuples (side, ψ deg, y, x_meas, z_meas, x_pred, z_pred, miss)."""
    cuts = sorted({(r[0], r[1]) for r in records})
    fig, axes = plt.subplots(len(cuts), 1, figsize=(9, 2.3 * len(cuts)), squeeze=False, layout="constrained")
    cmap = plt.get_cmap("viridis")
    for ax, cut in zip(axes[:, 0], cuts):
        rows = [r for r in records if (r[0], r[1]) == cut]
        ys = sorted({round(r[2], 1) for r in rows})
        for r in rows:
            c = cmap(ys.index(round(r[2], 1)) / max(len(ys) - 1, 1))
            ax.plot(r[3], r[4], "o", color=c)
            ax.plot(r[5], r[6], "x", color=c)
            ax.plot([r[3], r[5]], [r[4], r[6]], color=c, lw=0.6)
        ax.set_title(f"{cut[0]} side, ψ = {cut[1]:.0f}°: o PIV, x NPS (colour: cut y)", fontsize=9)
        ax.set_xlabel("x_H (m, aft)")
        ax.set_ylabel("z_H (m)")
        ax.grid(alpha=0.3)
    fig.suptitle(title)
    return fig


def wake_figure_from_tables(wake_table, loads_disk, path, *, radius_m: float, title: str = "") -> None:
    """Top/side views of snapshot 0 of a wake artifact, blades from root cutout to the vortex
    release points (node 0), and save to ``path``."""
    first = wake_table[wake_table["step"] == 0].sort_values(["blade", "node"])
    n_blades = int(first["blade"].nunique())
    nodes = first[["x_h_m", "y_h_m", "z_h_m"]].to_numpy().reshape(n_blades, -1, 3)
    root = float(loads_disk["r_m"].min() - 0.5 * loads_disk["dr_m"].iloc[0])
    tips = nodes[:, 0, :]
    blades = np.stack([tips * root / radius_m, tips], axis=1)
    ages = first["age_rad"].to_numpy().reshape(n_blades, -1) / (2.0 * np.pi) if "age_rad" in first else None
    fig = wake_views(nodes, blades, radius_m, title=title, ages_rev=ages)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def bvi_figure_from_tables(loads_disk, bvi_disk, path, *, rotation_sign: int, title: str = "") -> None:
    """:func:`bvi_disk_figure` of a loads table and its BVI table (ΔU_P = difference of U_P); of a BVI table over
    several turns of a common period, its first turn."""
    psi = np.unique(loads_disk["psi_rad"].to_numpy())
    r = np.unique(loads_disk["r_m"].to_numpy())
    shape = (psi.size, r.size)
    bvi_disk = bvi_disk.iloc[: psi.size * r.size]
    d_up = (bvi_disk["up_mps"].to_numpy() - loads_disk["up_mps"].to_numpy()).reshape(shape)
    fig = bvi_disk_figure(psi, r, d_up, loads_disk["fz_N_per_m"].to_numpy().reshape(shape),
                          bvi_disk["fz_N_per_m"].to_numpy().reshape(shape), rotation_sign=rotation_sign, title=title)
    fig.savefig(path, dpi=110)
    plt.close(fig)
