"""Snakemake script: hemisphere maps of every level family over its segments for one aircraft."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.study import study_maps

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    tables = {segment: read_table(path) for segment, path in snakemake.input.items()}
    for kind, segments in snakemake.params.segments.items():
        study_maps(kind, snakemake.wildcards.aircraft, {s: tables[s] for s in segments}, snakemake.output[kind])
        print(f"{kind}: segments {segments}", file=log)
