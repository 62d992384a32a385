"""Snakemake script: BVI loads of one aircraft x segment x rotor (nps.bvi)."""

from contextlib import redirect_stderr

import numba

from nps.cli.bvi import run
from nps.wake import WakeModel

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    p = snakemake.params
    w = snakemake.wildcards
    model = WakeModel.from_config(p.wake, p.revolutions, int(p.steps_per_rev))
    result = run(p.rotor, snakemake.input.disk, snakemake.input.summary, snakemake.input.trim, model,
                 snakemake.output[0], metadata={"aircraft": w.aircraft, "segment": w.segment})
    print(f"peak |dU_P| = {abs(result.d_up_mps).max():.4g} m/s, peak |dU_T| = {abs(result.d_ut_mps).max():.4g} m/s",
          file=log)
