"""Snakemake script: pressure history and spectrum at the BVISPL hotspot with and without BVI, and
pressure time histories (BVI loads) at several directions of the hemisphere."""

from contextlib import redirect_stderr

import numpy as np

from nps.io import read_signals, read_table
from nps.plots.acoustics import pressure_histories
from nps.plots.study import bvi_hotspot_figure, summed_signal
from nps.study import hotspot

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    spot = hotspot(read_table(snakemake.input.metrics), "bvispl_db")
    reference = read_table(snakemake.input.trim).iloc[0]
    bpf_hz = float(reference["n_blades"]) * float(reference["omega_rad_s"]) / (2.0 * np.pi)
    rotors = snakemake.params.rotors
    signals_bvi = read_signals(snakemake.input.bvi, rotors)
    base = summed_signal(read_signals(snakemake.input.base, rotors), spot["observer"])
    bvi = summed_signal(signals_bvi, spot["observer"])
    bvi_hotspot_figure(w.aircraft, w.segment, spot, base, bvi, bpf_hz, tuple(snakemake.params.harmonics),
                       snakemake.output.hotspot)
    observers = read_table(snakemake.input.observers, required=("observer", "azimuth_deg", "elevation_deg"))
    pressure_histories(signals_bvi, observers, snakemake.output.histories,
                       title=f"{w.aircraft} {w.segment}, hemisphere observers, loads with BVI")
    print(spot, file=log)
