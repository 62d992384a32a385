"""Snakemake script: pressure time histories at several observers, rotors summed (nps.plots.acoustics)."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.acoustics import pressure_histories

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    signals = {r: read_table(snakemake.input[f"signal_{r}"]) for r in snakemake.params.rotors}
    observers = read_table(snakemake.input.observers, required=("observer", "azimuth_deg", "elevation_deg"))
    pressure_histories(signals, observers, snakemake.output[0],
                       title=f"{w.aircraft} {w.segment}, {w.obsset} observers, {w.variant} loads")
