"""Snakemake script: disk plots (thesis Figs. 4.6-4.11 kinds) of one rotor's loads."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.disk import loads_figure

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    disk = read_table(snakemake.input.disk, required=("psi_rad", "r_m", "fz_N_per_m", "ut_mps"))
    loads_figure(disk, snakemake.output[0], rotation_sign=int(snakemake.params.rotation_sign),
                 title=f"{w.aircraft} {w.segment} rotor '{w.rotor}' (flying toward the top)")
