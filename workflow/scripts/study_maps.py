"""Snakemake script: hemisphere maps of one level kind over several segments for one aircraft."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.study import study_maps

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    tables = {segment: read_table(path) for segment, path in snakemake.input.items()}
    study_maps(snakemake.wildcards.kind, snakemake.wildcards.aircraft, tables, snakemake.output[0])
