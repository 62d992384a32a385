"""Stage ``bvi_hotspot``: pressure history and spectrum at the BVISPL hotspot with and without BVI, and pressure histories

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

import numpy as np

from nps.app.io import read_signals, read_table
from nps.app.study import hotspot


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """Pressure history and spectrum at the BVISPL hotspot with and without BVI, and pressure histories
    (BVI loads) at several directions of the hemisphere.

    inputs: ``metrics`` (hemisphere, variant bvi), ``trim``, ``base`` and ``bvi`` (acoustics directories),
    ``observers``. outputs: ``hotspot``, ``histories`` (PNG). params: ``rotors``, ``harmonics``,
    ``segment_name`` (the mission's name of the segment), ``radius_R``, ``radius_m`` (the hemisphere's radius),
    ``aircraft``, ``segment``.
    """
    from nps.plots import hemisphere_title, segment_title
    from nps.plots.acoustics import pressure_histories
    from nps.plots.study import bvi_hotspot_figure, summed_signal

    spot = hotspot(read_table(inputs["metrics"]), "bvispl_db")
    reference = read_table(inputs["trim"]).iloc[0]
    bpf_hz = float(reference["n_blades"]) * float(reference["omega_rad_s"]) / (2.0 * np.pi)
    rotors = list(params["rotors"])
    signals_bvi = read_signals(inputs["bvi"], rotors)
    base = summed_signal(read_signals(inputs["base"], rotors), spot["observer"])
    bvi = summed_signal(signals_bvi, spot["observer"])
    hemisphere = hemisphere_title(params["radius_R"], params["radius_m"])
    bvi_hotspot_figure(params["aircraft"], params["segment"], spot, base, bvi, bpf_hz, tuple(params["harmonics"]),
                       outputs["hotspot"], segment_name=params["segment_name"], hemisphere=hemisphere)
    observers = read_table(inputs["observers"], required=("observer", "azimuth_deg", "elevation_deg"))
    pressure_histories(signals_bvi, observers, outputs["histories"],
                       title=f"{params['aircraft']} {segment_title(params['segment'], params['segment_name'])}, "
                             f"{hemisphere}, loads with BVI")
    return str(spot)
