"""Snakemake script: per aircraft, one summary row per segment (levels, hotspots, trim, wall times)."""

from contextlib import redirect_stderr
from pathlib import Path

import pandas as pd

from nps.io import read_table, write_table
from nps.study import segment_summary, stage_wall_times

with open(snakemake.log[0], "w") as log, redirect_stderr(log):
    p = snakemake.params
    aircraft = snakemake.wildcards.aircraft
    root = Path(snakemake.input.trims[0]).parents[1]
    rows = []
    for segment in p.segments:
        base = root / segment
        trim = read_table(base / "trim.parquet")
        loads = {r: read_table(base / "loads" / f"{r}_summary.parquet") for r in p.rotors}
        metrics = {v: read_table(base / "metrics" / f"hemisphere_{v}.parquet") for v in p.variants[segment]}
        rows.append(segment_summary(aircraft, segment, trim, loads, metrics, stage_wall_times(p.benchmarks, aircraft, segment)))
    table = pd.DataFrame(rows)
    # wall times differ run to run: in the CSV (report) only, so the Parquet stays bit-reproducible
    wall = [c for c in table.columns if c.startswith("wall_")]
    write_table(table.drop(columns=wall), snakemake.output.table, stage="summary", metadata={"aircraft": aircraft})
    table.to_csv(snakemake.output.csv, index=False, float_format="%.6g")
    print(table.to_string(), file=log)
