"""Snakemake script: trimmed blade loads of one aircraft x segment x rotor (nps.bet)."""

from contextlib import redirect_stderr

from nps.cli.loads import run

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    w = snakemake.wildcards
    done = run(
        p.rotor,
        snakemake.input.trim,
        int(p.n_psi),
        int(p.n_r),
        snakemake.output.disk,
        {"aircraft": w.aircraft, "segment": w.segment},
        summary_out=snakemake.output.summary,
        history_out=snakemake.output.history,
    )
    print(done["result"].summary().to_string(index=False), file=log)
    print(done["result"].history.to_string(index=False), file=log)
