"""Study figures (thesis chapter 7 families) assembled from metrics and signal artifacts."""

from __future__ import annotations

from typing import Mapping

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.noise.signals import signal_arrays
from nps.plots import hemisphere_title, save_figure, segment_title
import pandas as pd

from nps.plots.maps import direction_name, map_panels
from nps.noise.spectra import level_db, narrowband_msp
from nps.app.study import hotspot

MAP_KINDS = {
    "oaspl": ("oaspl_db", "OASPL (dB re 20 µPa)", "OASPL"),
    "dba": ("oaspl_dba", "OASPL, A-weighted (dBA)", "A-weighted OASPL"),
    "bvispl": ("bvispl_db", "BVISPL (dB re 20 µPa)", "BVISPL"),
    "hsi_oaspl": ("oaspl_db", "OASPL with HSI (dB re 20 µPa)", "OASPL with HSI"),
}


def study_maps(kind: str, aircraft: str, metrics_by_segment: Mapping[str, pd.DataFrame], path, *,
               segment_names: Mapping[str, str] | None = None, radius_R: float | None = None,
               radius_m: float | None = None) -> None:
    """Hemisphere maps of one level for several segments on a shared colour scale.

    ``metrics_by_segment``: segment → hemisphere metrics table (the variant with BVI where it
    was computed); ``segment_names``: segment → mission name (titles); ``radius_R``, ``radius_m``: the
    hemisphere's radius (title). Every panel names its maximum and where it is; BVISPL maps star the hotspot.
    """
    column, colour_label, name = MAP_KINDS[kind]
    names = dict(segment_names or {})
    panels = []
    for segment, table in metrics_by_segment.items():
        spot = hotspot(table, column)
        panels.append({
            "azimuth_deg": table["azimuth_deg"].to_numpy(),
            "elevation_deg": table["elevation_deg"].to_numpy(),
            "level_db": table[column].to_numpy(),
            "title": f"{aircraft} {segment_title(segment, names.get(segment))}: {name}\n"
                     f"max {spot['value']:.1f} dB, {direction_name(spot['azimuth_deg'], spot['elevation_deg'])}",
            "marker": (spot["azimuth_deg"], spot["elevation_deg"]) if kind == "bvispl" else None,
        })
    map_panels(panels, path, suptitle=f"{aircraft}: {name} on the {hemisphere_title(radius_R, radius_m)} "
                                      "(moving with the aircraft)", colour_label=colour_label)


def rotor_oaspl(signals: pd.DataFrame) -> pd.DataFrame:
    """OASPL (dB re 20 µPa) per observer of one rotor's signal table (sum of its source groups)."""
    ids, _, groups = signal_arrays(signals[signals["group"] != "total"])
    p = sum(groups.values())
    p = p - p.mean(axis=1, keepdims=True)
    return pd.DataFrame({"observer": ids, "oaspl_db": level_db(np.mean(p * p, axis=1))})


def rotor_maps(aircraft: str, rotor: str, levels_by_segment: Mapping[str, pd.DataFrame], observers: pd.DataFrame, path,
               *, segment_names: Mapping[str, str] | None = None, radius_R: float | None = None,
               radius_m: float | None = None) -> None:
    """OASPL maps of a single rotor (e.g. the tail rotor) for several segments (titles as :func:`study_maps`)."""
    names = dict(segment_names or {})
    panels = []
    for segment, levels in levels_by_segment.items():
        table = levels.merge(observers[["observer", "azimuth_deg", "elevation_deg"]], on="observer")
        spot = hotspot(table, "oaspl_db")
        panels.append({
            "azimuth_deg": table["azimuth_deg"].to_numpy(),
            "elevation_deg": table["elevation_deg"].to_numpy(),
            "level_db": table["oaspl_db"].to_numpy(),
            "title": f"{aircraft} {segment_title(segment, names.get(segment))}: rotor '{rotor}' alone\n"
                     f"max {spot['value']:.1f} dB, {direction_name(spot['azimuth_deg'], spot['elevation_deg'])}",
        })
    map_panels(panels, path, suptitle=f"{aircraft}: OASPL of rotor '{rotor}' alone (thickness + loading) on the "
                                      f"{hemisphere_title(radius_R, radius_m)}")


def summed_signal(signals_by_rotor: Mapping[str, pd.DataFrame], observer: int) -> tuple[np.ndarray, np.ndarray]:
    """(time_s, p_Pa) at one observer summed over rotors and source groups."""
    total = None
    for table in signals_by_rotor.values():
        rows = table[(table["observer"] == observer) & (table["group"] != "total")]
        series = rows.groupby("time_s", sort=True)["p_Pa"].sum()
        total = series if total is None else total + series
    return total.index.to_numpy(), total.to_numpy()


def bvi_hotspot_figure(aircraft: str, segment: str, spot: Mapping[str, float], base: tuple, bvi: tuple,
                       bpf_hz: float, harmonics: tuple[int, int], path, *, segment_name: str | None = None,
                       hemisphere: str = "hemisphere") -> None:
    """Pressure history and spectrum at the BVISPL hotspot with and without BVI loads; ``hemisphere``: how the
    title names the observer set (:func:`nps.plots.hemisphere_title`)."""
    fig, (ax_t, ax_f) = plt.subplots(1, 2, figsize=(12, 4))
    for (time_s, p_pa), label, style in ((base, "without BVI", "-"), (bvi, "with BVI", "-")):
        ax_t.plot(1e3 * (time_s - time_s[0]), p_pa, style, lw=0.9, label=label)
        frequency, msp = narrowband_msp(p_pa, time_s[1] - time_s[0])
        level = level_db(msp)
        keep = frequency > 0
        ax_f.plot(frequency[keep] / bpf_hz, level[keep], lw=0.9, label=label)
    ax_f.axvspan(harmonics[0] - 0.5, harmonics[1] + 0.5, color="0.85", zorder=0, label="BVISPL band")
    ax_t.set_xlabel("time (ms)")
    ax_t.set_ylabel("acoustic pressure (Pa)")
    ax_t.legend()
    ax_f.set_xscale("log")
    ax_f.set_xlabel("frequency / main-rotor BPF (−)")
    ax_f.set_ylabel("SPL of harmonic (dB re 20 µPa)")
    ax_f.set_ylim(bottom=max(0.0, ax_f.get_ylim()[0]))
    ax_f.legend()
    fig.suptitle(f"{aircraft} {segment_title(segment, segment_name)}: BVISPL hotspot\non the {hemisphere}, "
                 f"{direction_name(spot['azimuth_deg'], spot['elevation_deg'])} (observer {spot['observer']}), "
                 "one revolution", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path)
