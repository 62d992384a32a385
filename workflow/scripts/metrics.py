"""Snakemake script: metrics and 1/3-octave bands of one aircraft x segment x observer set x variant."""

from contextlib import redirect_stderr

from nps.atmosphere import isa
from nps.io import read_signals, read_table, write_table
from nps.metrics import metrics_tables
from nps.plots.spectra import loudest_observer_figure

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    signals = read_signals(snakemake.input.signals, p.rotors)
    hsi = read_signals(snakemake.input.hsi, p.rotors) if p.hsi else None
    trim = read_table(snakemake.input.trim)
    observers = read_table(snakemake.input.observers)
    atm = p.atmosphere
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"]) if p.absorption else None
    harmonics = tuple(int(h) for h in p.harmonics)
    table, bands, levels = metrics_tables(signals, observers, trim, p.solidity, atmosphere, hsi, p.broadband, harmonics)
    meta = {"aircraft": w.aircraft, "segment": w.segment, "obsset": w.obsset, "variant": w.variant,
            "bvispl_harmonics": list(harmonics), "absorption": p.absorption, "broadband": p.broadband, "hsi": p.hsi}
    write_table(table, snakemake.output.metrics, stage="metrics", metadata=meta)
    write_table(bands, snakemake.output.bands, stage="metrics", metadata=meta)
    loudest_observer_figure(table, bands, levels, trim, harmonics,
                            f"{w.aircraft} {w.segment} {w.obsset} ({w.variant})", snakemake.output.figure)
    print(table.describe().to_string(), file=log)
