"""Snakemake script: pressure history and spectrum at the BVISPL hotspot, with and without BVI."""

from contextlib import redirect_stderr

import numpy as np

from nps.io import read_table
from nps.plots.study import bvi_hotspot_figure, summed_signal
from nps.study import hotspot

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    spot = hotspot(read_table(snakemake.input.metrics), "bvispl_db")
    reference = read_table(snakemake.input.trim).iloc[0]
    bpf_hz = float(reference["n_blades"]) * float(reference["omega_rad_s"]) / (2.0 * np.pi)
    base = summed_signal({path: read_table(path) for path in snakemake.input.base}, spot["observer"])
    bvi = summed_signal({path: read_table(path) for path in snakemake.input.bvi}, spot["observer"])
    w = snakemake.wildcards
    bvi_hotspot_figure(w.aircraft, w.segment, spot, base, bvi, bpf_hz, tuple(snakemake.params.harmonics), snakemake.output[0])
    print(spot, file=log)
