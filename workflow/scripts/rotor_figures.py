"""Snakemake script: disk, wake and BVI figures of the drawn rotors of one aircraft x segment."""

from contextlib import redirect_stderr
from pathlib import Path

from nps.io import read_table, rotor_path
from nps.plots.disk import loads_figure
from nps.plots.wake import bvi_figure_from_tables, wake_figure_from_tables

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    w = snakemake.wildcards
    out = Path(snakemake.output[0])
    out.mkdir(parents=True, exist_ok=True)
    for rotor, spec in snakemake.params.rotors.items():
        name = f"{w.aircraft} {w.segment} rotor '{rotor}'"
        disk = read_table(snakemake.input[f"loads_{rotor}"])
        loads_figure(disk, out / f"disk_{rotor}.png", rotation_sign=int(spec["rotation_sign"]),
                     title=f"{name} (flying toward the top)")
        if snakemake.params.wake:
            wake_figure_from_tables(read_table(rotor_path(snakemake.input.wake, rotor)), disk, out / f"wake_{rotor}.png",
                                    radius_m=float(spec["radius_m"]), title=f"{name}: tip vortices, blade 0 at ψ = 0")
            bvi_figure_from_tables(disk, read_table(rotor_path(snakemake.input.bvi, rotor)), out / f"bvi_{rotor}.png",
                                   rotation_sign=int(spec["rotation_sign"]), title=f"{name} (flying toward the top)")
        print(f"rotor {rotor}: figures written", file=log)
