"""Snakemake script: pressure signals of every rotor of the aircraft at one observer set (nps.cli.rotor_acoustics)."""

from contextlib import redirect_stderr

import numba

from nps.cli.rotor_acoustics import run
from nps.io import rotor_path
from nps.sources import ThicknessModel

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    model = ThicknessModel(p.thickness, tuple(float(f) for f in p.chord_fractions))
    for rotor in p.rotors:
        disk = rotor_path(snakemake.input.bvi_dir, rotor) if w.variant == "bvi" else snakemake.input[f"disk_{rotor}"]
        table = run(disk, snakemake.input.trim, snakemake.input.observers, rotor, p.rotors[0],
                    int(p.samples_per_rev), model, float(p.hinge_offsets_m[rotor]), rotor_path(snakemake.output[0], rotor),
                    {"aircraft": w.aircraft, "segment": w.segment, "obsset": w.obsset, "variant": w.variant})
        print(f"rotor {rotor}:", table.groupby("group", observed=True)["p_Pa"].agg(["min", "max", "std"]).to_string(), file=log)
