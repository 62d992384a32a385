"""Snakemake script: Beddoes tip-vortex wake of one aircraft x segment x rotor (nps.wake)."""

from contextlib import redirect_stderr

from nps.cli.wake import run
from nps.wake import WakeModel

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    model = WakeModel.from_config(p.wake, p.revolutions, int(p.steps_per_rev))
    done = run(snakemake.input.disk, snakemake.input.summary, snakemake.input.trim, w.rotor, model,
               snakemake.output.wake, vtk_dir=snakemake.output.vtk,
               metadata={"aircraft": w.aircraft, "segment": w.segment})
    print(f"{len(done['table'])} wake nodes, model {model}", file=log)
