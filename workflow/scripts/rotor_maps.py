"""Snakemake script: OASPL maps of one rotor alone (e.g. the tail rotor)."""

from contextlib import redirect_stderr

from nps.io import read_signals, read_table
from nps.plots.study import rotor_maps, rotor_oaspl

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    rotor = snakemake.wildcards.rotor
    levels = {s: rotor_oaspl(read_signals(path, [rotor])[rotor])
              for s, path in zip(snakemake.params.segments, snakemake.input.signals)}
    observers = read_table(snakemake.input.observers)
    rotor_maps(snakemake.wildcards.aircraft, rotor, levels, observers, snakemake.output[0])
