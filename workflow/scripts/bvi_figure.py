"""Snakemake script: induced velocity and BVI loading disk maps (thesis Figs. 5.7-5.8 kind)."""

from contextlib import redirect_stderr

from nps.bvi import DISK_COLUMNS
from nps.io import read_table
from nps.plots.wake import bvi_figure_from_tables

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    bvi_figure_from_tables(read_table(snakemake.input.disk, required=DISK_COLUMNS),
                           read_table(snakemake.input.bvi, required=DISK_COLUMNS), snakemake.output[0],
                           rotation_sign=int(snakemake.params.rotation_sign),
                           title=f"{w.aircraft} {w.segment} rotor '{w.rotor}' (flying toward the top)")
