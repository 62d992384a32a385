"""Rotor-disk plots in the thesis orientation (chapter 4, Figs. 4.5–4.11).

Page layout: the aircraft flies toward the top of the page, ψ = 0 (aft, +x_H) at the bottom,
ψ = 180° at the top. A counterclockwise rotor (s = +1, seen from +z_H) has its advancing side
(ψ = 90°) on the right; a clockwise rotor (s = −1) is mirrored (advancing side on the left).
A station (ψ, r) is drawn at page coordinates (s r sin ψ, −r cos ψ), i.e. the hub frame seen
from +z_H with −x_H up. The rotation sense is marked by an arrow outside the disk.

:func:`disk_plot` is the generic building block (values on a ψ × r grid, optional contour
lines and an optional U_T = 0 reverse-flow outline); :func:`loads_figure` draws the loads
artifact's standard panels. Matplotlib with the Agg backend, perceptually uniform colormaps.
"""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from nps.plots import save_figure  # noqa: E402


def disk_grid(table: pd.DataFrame, column: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ψ (n_psi,), r (n_r,), values (n_psi, n_r)) of one column of a ψ-major disk table."""
    psi = np.unique(table["psi_rad"].to_numpy())
    r = np.unique(table["r_m"].to_numpy())
    values = table[column].to_numpy()
    if values.size != psi.size * r.size:
        raise ValueError(f"disk table: expected {psi.size}×{r.size} rows (ψ-major), got {values.size}")
    return psi, r, values.reshape(psi.size, r.size)


def _edges(centres: np.ndarray) -> np.ndarray:
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[centres[0] - (mid[0] - centres[0])], mid, [centres[-1] + (centres[-1] - mid[-1])]])


def _page_xy(psi: np.ndarray, r: np.ndarray, rotation_sign: int) -> tuple[np.ndarray, np.ndarray]:
    return rotation_sign * r * np.sin(psi), -r * np.cos(psi)


def disk_plot(
    psi_rad,
    r_m,
    values,
    *,
    rotation_sign: int = 1,
    ax=None,
    label: str = "",
    title: str = "",
    cmap: str = "viridis",
    contour_levels: int | None = 8,
    vmin: float | None = None,
    vmax: float | None = None,
    reverse_flow_ut=None,
):
    """Filled disk plot of ``values`` (n_psi, n_r) at azimuths ``psi_rad`` and radii ``r_m``.

    Cells span ψ_i ± Δψ/2 and the radial element edges. ``contour_levels``: number of
    contour lines (None for none). ``reverse_flow_ut``: U_T (n_psi, n_r); its zero contour
    (the reverse-flow boundary) is drawn dashed. ``rotation_sign`` +1 ccw, −1 cw.
    Returns (figure, axes, mappable).
    """
    psi = np.asarray(psi_rad, dtype=float)
    r = np.asarray(r_m, dtype=float)
    v = np.asarray(values, dtype=float)
    if v.shape != (psi.size, r.size):
        raise ValueError(f"disk_plot: values shape {v.shape} does not match (n_psi, n_r) = ({psi.size}, {r.size})")
    if rotation_sign not in (1, -1):
        raise ValueError(f"disk_plot: rotation_sign: expected +1 or -1, got {rotation_sign!r}")
    if ax is None:
        fig, ax = plt.subplots(figsize=(5.2, 4.6))
    else:
        fig = ax.figure
    dpsi = 2.0 * np.pi / psi.size
    psi_e, r_e = np.meshgrid(np.concatenate([psi - 0.5 * dpsi, [psi[-1] + 0.5 * dpsi]]), _edges(r), indexing="ij")
    x_e, y_e = _page_xy(psi_e, r_e, rotation_sign)
    mesh = ax.pcolormesh(x_e, y_e, v, cmap=cmap, vmin=vmin, vmax=vmax, shading="flat", rasterized=True)
    # periodic centre grid for contours
    psi_c, r_c = np.meshgrid(np.concatenate([psi, [psi[0] + 2.0 * np.pi]]), r, indexing="ij")
    x_c, y_c = _page_xy(psi_c, r_c, rotation_sign)
    if contour_levels and np.ptp(v) > 0.0:
        ax.contour(x_c, y_c, np.vstack([v, v[:1]]), levels=contour_levels, colors="k", linewidths=0.5, alpha=0.6)
    if reverse_flow_ut is not None:
        ut = np.asarray(reverse_flow_ut, dtype=float)
        if (ut < 0.0).any() and (ut > 0.0).any():
            ax.contour(x_c, y_c, np.vstack([ut, ut[:1]]), levels=[0.0], colors="w", linewidths=1.2, linestyles="--")
    cbar = fig.colorbar(mesh, ax=ax, shrink=0.85)
    cbar.set_label(label)
    _decorate(ax, r_e.max(), rotation_sign)
    ax.set_title(title, fontsize=10)
    return fig, ax, mesh


def _decorate(ax, radius: float, rotation_sign: int) -> None:
    """Axes in metres, flight arrow, ψ labels and the rotation arrow."""
    lim = 1.3 * radius
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xlabel("starboard-side distance in the rotor frame (m)" if rotation_sign == 1 else "distance, mirrored rotor (m)")
    ax.set_ylabel("forward distance (m)")
    ax.annotate("", xy=(0.0, 1.27 * radius), xytext=(0.0, 1.07 * radius),
                arrowprops=dict(arrowstyle="-|>", color="0.2", lw=1.2))
    ax.text(-0.05 * radius, 1.17 * radius, "flight", fontsize=7, color="0.2", va="center", ha="right")
    for psi_deg in (0, 90, 180, 270):
        x, y = _page_xy(np.radians(psi_deg), 1.1 * radius, rotation_sign)
        if psi_deg == 180:
            x += 0.18 * radius
        ax.text(x, y, f"ψ={psi_deg}°", ha="center", va="center", fontsize=7)
    # rotation arrow: arc from ψ = 20° to 60° just outside the disk, in the rotation sense
    arc = np.radians(np.linspace(20.0, 60.0, 30))
    x, y = _page_xy(arc, 1.2 * radius, rotation_sign)
    ax.plot(x[:-1], y[:-1], color="0.2", lw=1.2)
    ax.annotate("", xy=(x[-1], y[-1]), xytext=(x[-3], y[-3]), arrowprops=dict(arrowstyle="-|>", color="0.2", lw=1.2))
    side = "advancing side →" if rotation_sign == 1 else "← advancing side"
    ax.text(0.0, -1.27 * radius, side, ha="center", va="center", fontsize=7)


LOADS_PANELS = (
    ("fz_N_per_m", "Z loading F_z (N/m)", 1.0),
    ("roll_contribution", "roll moment contribution s·r·sinψ·F_z (N·m/m)", 1.0),
    ("pitch_contribution", "pitch moment contribution −r·cosψ·F_z (N·m/m)", 1.0),
    ("inflow_ratio", "inflow ratio λ (−)", 1.0),
    ("up_mps", "U_P (m/s)", 1.0),
    ("ut_mps", "U_T (m/s)", 1.0),
    ("alpha_eff_rad", "angle of attack α (deg)", 180.0 / np.pi),
    ("mach", "section Mach number (−)", 1.0),
)


def loads_figure(table: pd.DataFrame, path: str | os.PathLike, *, rotation_sign: int, title: str = "") -> None:
    """Eight-panel disk figure of a loads (or BVI) disk table, written to ``path`` (PNG).

    Panels: F_z, roll and pitch moment contributions of F_z about the hub (hub-frame signs of
    docs/reference/conventions.md), λ, U_P, U_T, α and Mach; the dashed white line is U_T = 0.
    """
    data = table.copy()
    data["roll_contribution"] = rotation_sign * data["r_m"] * np.sin(data["psi_rad"]) * data["fz_N_per_m"]
    data["pitch_contribution"] = -data["r_m"] * np.cos(data["psi_rad"]) * data["fz_N_per_m"]
    _, _, ut = disk_grid(data, "ut_mps")
    fig, axes = plt.subplots(2, 4, figsize=(20, 9.5))
    for ax, (column, label, scale) in zip(axes.ravel(), LOADS_PANELS):
        psi, r, v = disk_grid(data, column)
        cmap = "cividis" if column in ("roll_contribution", "pitch_contribution") else "viridis"
        # colour range from the forward-flow stations: reverse-flow angles (±90°) would swamp it
        vmin, vmax = np.percentile(v[ut > 0.0] * scale, [0.5, 99.5]) if column == "alpha_eff_rad" else (None, None)
        disk_plot(psi, r, v * scale, rotation_sign=rotation_sign, ax=ax, label=label, cmap=cmap, vmin=vmin, vmax=vmax,
                  reverse_flow_ut=ut)
    fig.suptitle(title)
    # fixed margins: tight_layout measures all 16 axes and costs ~1 s per figure
    fig.subplots_adjust(left=0.035, right=0.975, bottom=0.06, top=0.93, wspace=0.42, hspace=0.25)
    save_figure(fig, path)
