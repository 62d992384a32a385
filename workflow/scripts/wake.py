"""Snakemake script: wake geometry (+ VTK) and BVI loads of every rotor of one aircraft x segment."""

from contextlib import redirect_stderr
from pathlib import Path

import numba

from nps.cli import bvi, wake
from nps.io import rotor_path
from nps.wake import WakeModel

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    p = snakemake.params
    w = snakemake.wildcards
    model = WakeModel.from_config(p.wake, p.revolutions, int(p.steps_per_rev))
    wake_dir, bvi_dir = Path(snakemake.output.wake), Path(snakemake.output.bvi)
    meta = {"aircraft": w.aircraft, "segment": w.segment}
    for rotor, rotor_config in p.rotors.items():
        disk, summary = snakemake.input[f"disk_{rotor}"], snakemake.input[f"summary_{rotor}"]
        done = wake.run(disk, summary, snakemake.input.trim, rotor, model, rotor_path(wake_dir, rotor),
                        vtk_dir=wake_dir / f"{rotor}_vtk", metadata=meta)
        result = bvi.run(rotor_config, disk, summary, snakemake.input.trim, model, rotor_path(bvi_dir, rotor),
                         metadata=meta)
        print(f"rotor {rotor}: {len(done['table'])} wake nodes; peak |dU_P| = {abs(result.d_up_mps).max():.4g} m/s, "
              f"peak |dU_T| = {abs(result.d_ut_mps).max():.4g} m/s", file=log)
