"""Wall time of a finished campaign, per stage, from the Snakemake benchmark files.

Reads ``results/benchmarks/<rule>/**/*.tsv`` (one file per job, column ``s`` = wall seconds of the
job, ``cpu_time``, ``max_rss`` in MB) and prints per rule: jobs, summed job wall time, mean and
largest job, largest resident memory. The campaign's elapsed time is about the summed job time
divided by the number of parallel jobs (``-j``) plus Snakemake's own scheduling.

    python benchmarks/campaign_times.py [results/benchmarks]
"""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd


def stage_table(benchmark_dir: Path) -> pd.DataFrame:
    rows = []
    for path in sorted(benchmark_dir.rglob("*.tsv")):
        last = pd.read_csv(path, sep="\t").iloc[-1]
        rows.append({"rule": path.relative_to(benchmark_dir).parts[0], "s": float(last["s"]),
                     "cpu_s": float(last["cpu_time"]), "max_rss_mb": float(last["max_rss"])})
    if not rows:
        raise SystemExit(f"{benchmark_dir}: no benchmark files (run the campaign first)")
    jobs = pd.DataFrame(rows)
    table = jobs.groupby("rule").agg(jobs=("s", "size"), total_s=("s", "sum"), mean_s=("s", "mean"),
                                     max_s=("s", "max"), cpu_s=("cpu_s", "sum"), max_rss_mb=("max_rss_mb", "max"))
    return table.sort_values("total_s", ascending=False)


def main(argv: list[str]) -> int:
    directory = Path(argv[0] if argv else "results/benchmarks")
    table = stage_table(directory)
    pd.set_option("display.width", 120)
    print(table.round(2).to_string())
    print(f"\n{int(table['jobs'].sum())} jobs, summed job wall time {table['total_s'].sum():.0f} s "
          f"({table['total_s'].sum() / 2 / 60:.1f} min on 2 parallel slots)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
