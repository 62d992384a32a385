"""Snakemake script: observer time histories with and without HSI (rotors summed)."""

from contextlib import redirect_stderr

from nps.hsi import combine_rotors
from nps.io import read_signals, read_table
from nps.plots.hsi import plot_observer_histories

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    rotors = snakemake.params.rotors
    raw = combine_rotors(list(read_signals(snakemake.input.signals, rotors).values()))
    hsi = combine_rotors(list(read_signals(snakemake.input.hsi, rotors).values()))
    observers = read_table(snakemake.input.observers, required=("observer", "elevation_deg")).sort_values("observer")
    histories = {}
    for o, el in zip(observers["observer"], observers["elevation_deg"]):
        a, b = raw[raw["observer"] == o], hsi[hsi["observer"] == o]
        histories[f"el {el:.0f}°"] = (a["time_s"].to_numpy(), a["p_Pa"].to_numpy(), b["p_Pa"].to_numpy())
    w = snakemake.wildcards
    plot_observer_histories(histories, snakemake.output[0],
                            title=f"{w.aircraft} {w.segment}: observers 10 R ahead ({w.variant} loads), rotors summed")
