"""Snakemake script: OASPL maps of one rotor alone (e.g. the tail rotor)."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.study import rotor_maps, rotor_oaspl

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    levels = {s: rotor_oaspl(read_table(path)) for s, path in zip(snakemake.params.segments, snakemake.input.signals)}
    observers = read_table(snakemake.input.observers)
    rotor_maps(snakemake.wildcards.aircraft, snakemake.wildcards.rotor, levels, observers, snakemake.output[0])
