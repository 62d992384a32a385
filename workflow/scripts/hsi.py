"""Snakemake script: HSI processing of one rotor's signals for one observer set -> hsi/ artifacts."""

from contextlib import redirect_stderr

import numba

from nps.hsi import OBSERVER_COLUMNS, SIGNAL_COLUMNS, process
from nps.io import read_table, write_table

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    w = snakemake.wildcards
    trim = read_table(snakemake.input.trim, required=("rotor",))
    row = trim[trim["rotor"] == w.rotor]
    if len(row) != 1:
        raise ValueError(f"{snakemake.input.trim}: expected one row for rotor '{w.rotor}', found {len(row)}")
    result = process(
        read_table(snakemake.input.signals, required=SIGNAL_COLUMNS),
        read_table(snakemake.input.observers, required=OBSERVER_COLUMNS),
        row.iloc[0].to_dict(),
    )
    meta = {"rotor": w.rotor, "obsset": w.obsset, "variant": w.variant, "inputs": list(snakemake.input)}
    write_table(result.signals, snakemake.output.signals, stage="hsi", metadata=meta)
    write_table(result.diagnostics, snakemake.output.diagnostics, stage="hsi", metadata=meta)
    print(result.diagnostics.to_string(max_rows=40), file=log)
