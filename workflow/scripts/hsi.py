"""Snakemake script: HSI processing of every rotor's signals for one observer set -> hsi/ artifacts."""

from contextlib import redirect_stderr

import numba

from nps.hsi import OBSERVER_COLUMNS, process
from nps.io import read_signals, read_table, rotor_path, write_table

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    numba.set_num_threads(max(1, min(snakemake.threads, numba.config.NUMBA_NUM_THREADS)))
    w = snakemake.wildcards
    rotors = snakemake.params.rotors
    trim = read_table(snakemake.input.trim, required=("rotor",))
    observers = read_table(snakemake.input.observers, required=OBSERVER_COLUMNS)
    signals = read_signals(snakemake.input.signals, rotors)
    for rotor in rotors:
        row = trim[trim["rotor"] == rotor]
        if len(row) != 1:
            raise ValueError(f"{snakemake.input.trim}: expected one row for rotor '{rotor}', found {len(row)}")
        result = process(signals[rotor], observers, row.iloc[0].to_dict())
        meta = {"rotor": rotor, "obsset": w.obsset, "variant": w.variant, "inputs": list(snakemake.input)}
        write_table(result.signals, rotor_path(snakemake.output[0], rotor), stage="hsi", metadata=meta)
        write_table(result.diagnostics, rotor_path(snakemake.output[0], rotor, "_diagnostics"), stage="hsi", metadata=meta)
        print(f"rotor {rotor}:\n{result.diagnostics.describe().to_string()}", file=log)
