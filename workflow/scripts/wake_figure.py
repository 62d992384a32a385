"""Snakemake script: top and side views of one rotor's tip-vortex wake (thesis Fig. 5.6 kind)."""

from contextlib import redirect_stderr

from nps.io import read_table
from nps.plots.wake import wake_figure_from_tables
from nps.wake import WAKE_COLUMNS

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    wake_figure_from_tables(read_table(snakemake.input.wake, required=WAKE_COLUMNS),
                            read_table(snakemake.input.disk, required=("r_m", "dr_m")), snakemake.output[0],
                            radius_m=float(snakemake.params.radius_m),
                            title=f"{w.aircraft} {w.segment} rotor '{w.rotor}': tip vortices, blade 0 at ψ = 0")
