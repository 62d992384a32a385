"""Snakemake script: one observer set of one aircraft x segment (nps.cli.observers)."""

from contextlib import redirect_stderr

from nps.cli.observers import run

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    table = run(p.spec, snakemake.input.trim, p.rotor_roles, p.reference_radius_m, snakemake.output[0],
                {"aircraft": w.aircraft, "segment": w.segment, "obsset": w.obsset})
    print(f"{len(table)} observers, centre: mean hub of the lift rotors of {dict(p.rotor_roles)}", file=log)
