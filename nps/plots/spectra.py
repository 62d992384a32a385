"""Spectrum figures: narrowband tonal lines with 1/3-octave band levels, tonal and broadband.

:func:`spectrum_figure` draws, for one observer, (top) the narrowband tonal total as line
levels (dB re 20 µPa per FFT line) with the total 1/3-octave band levels as steps and the
BVISPL harmonic band shaded, and (bottom) the 1/3-octave levels per source (thickness, loading,
HSI, broadband, total) from the metrics stage's bands table. Matplotlib, Agg backend; the sources in
the colour-blind-safe Okabe–Ito colours with distinct line styles (:data:`SOURCE_STYLES`), the total in
black, so that every curve stands apart from its neighbours in colour and in print.
"""

from __future__ import annotations

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from nps.noise.spectra import LEVEL_FLOOR_DB, level_db  # noqa: E402
from nps.plots.maps import direction_name  # noqa: E402

_SOURCES = ("thickness", "loading", "hsi", "broadband", "total")
# source -> (colour, line style, width): Okabe & Ito (2008) colour-blind-safe palette, total in black
SOURCE_STYLES = {
    "thickness": ("#0072B2", "-", 1.6),
    "loading": ("#D55E00", "-", 1.6),
    "hsi": ("#CC79A7", "--", 1.6),
    "broadband": ("#009E73", "-.", 1.6),
    "total": ("#000000", "-", 2.4),
}


def _steps(ax, bands: pd.DataFrame, label: str, color, lw: float = 1.5, linestyle: str = "-") -> None:
    b = bands.sort_values("band")
    centre = b["center_hz"].to_numpy()
    edges = np.concatenate([centre * 10.0 ** (-1.0 / 20.0), centre[-1:] * 10.0 ** (1.0 / 20.0)])
    ax.stairs(b["level_db"].to_numpy(), edges, label=label, color=color, lw=lw, linestyle=linestyle, baseline=None)


def spectrum_figure(
    frequency_hz,
    tonal_msp_pa2,
    bands: pd.DataFrame,
    bpf_hz: float,
    harmonics: tuple[int, int],
    title: str,
    path: str | os.PathLike | None = None,
    dynamic_range_db: float = 80.0,
):
    """Spectrum figure of one observer; returns the Figure (saved to ``path`` when given).

    ``frequency_hz``, ``tonal_msp_pa2``: narrowband lines of the tonal total (Pa²);
    ``bands``: rows of the bands table for this observer (source, band, center_hz, level_db).
    """
    missing = [c for c in ("source", "band", "center_hz", "level_db") if c not in bands.columns]
    if missing:
        raise ValueError(f"bands table: missing column(s) {missing}")
    f = np.asarray(frequency_hz, dtype=float)[1:]
    lines = level_db(np.asarray(tonal_msp_pa2, dtype=float)[1:])
    top = max(float(lines.max()), float(bands["level_db"].max())) + 5.0
    bottom = top - dynamic_range_db
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 7), sharex=True, constrained_layout=True)
    shown = lines > bottom
    ax1.vlines(f[shown], bottom, lines[shown], color=SOURCE_STYLES["thickness"][0], lw=0.8, label="tonal lines")
    total = bands[bands["source"] == "total"]
    _steps(ax1, total, "1/3-octave total", SOURCE_STYLES["total"][0], lw=2.0)
    ax1.axvspan((harmonics[0] - 0.5) * bpf_hz, (harmonics[1] + 0.5) * bpf_hz, color="0.85", zorder=0,
                label=f"BVISPL band (BPF harmonics {harmonics[0]}–{harmonics[1]})")
    ax1.set_ylabel("SPL (dB re 20 µPa)")
    ax1.set_title(title)
    for source in _SOURCES:
        part = bands[bands["source"] == source]
        if len(part) and (part["level_db"] > LEVEL_FLOOR_DB).any():
            colour, style, width = SOURCE_STYLES[source]
            _steps(ax2, part, source, colour, lw=width, linestyle=style)
    ax2.set_ylabel("1/3-octave band SPL (dB re 20 µPa)")
    ax2.set_xlabel("frequency (Hz)")
    for ax in (ax1, ax2):
        ax.set_xscale("log")
        ax.set_ylim(bottom, top)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    ax2.set_xlim(8.9, 22_400.0)
    if path is not None:
        fig.savefig(path, dpi=120)
    return fig


def loudest_observer_figure(metrics: pd.DataFrame, bands: pd.DataFrame, levels, trim: pd.DataFrame,
                            harmonics: tuple[int, int], title: str, path: str | os.PathLike):
    """:func:`spectrum_figure` of the observer with the highest total OASPL.

    ``metrics``, ``bands``, ``levels``: the three results of :func:`nps.noise.metrics.metrics_tables`
    (observers in the same order); ``trim``: trim table, first row = reference (main) rotor.
    """
    loudest = int(np.argmax(metrics["oaspl_db"].to_numpy()))
    observer = int(metrics["observer"].iloc[loudest])
    where = (f", {direction_name(metrics['azimuth_deg'].iloc[loudest], metrics['elevation_deg'].iloc[loudest])}"
             if {"azimuth_deg", "elevation_deg"} <= set(metrics.columns) else "")
    ref = trim.iloc[0]
    bpf_hz = float(ref["n_blades"]) * float(ref["omega_rad_s"]) / (2.0 * np.pi)
    return spectrum_figure(levels.frequency_hz, levels.tonal_msp[loudest], bands[bands["observer"] == observer],
                           bpf_hz, harmonics, f"{title}: observer {observer} (loudest{where})", path)
