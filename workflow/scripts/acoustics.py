"""Snakemake script: pressure signals of one rotor at one observer set (nps.cli.rotor_acoustics)."""

from contextlib import redirect_stderr

import numba

from nps.cli.rotor_acoustics import run
from nps.sources import ThicknessModel

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    model = ThicknessModel(p.thickness, tuple(float(f) for f in p.chord_fractions))
    table = run(snakemake.input.disk, snakemake.input.trim, snakemake.input.observers, w.rotor, p.reference_rotor,
                int(p.samples_per_rev), model, float(p.hinge_offset_m), snakemake.output[0],
                {"aircraft": w.aircraft, "segment": w.segment, "obsset": w.obsset, "variant": w.variant})
    print(table.groupby("group")["p_Pa"].agg(["min", "max", "std"]).to_string(), file=log)
