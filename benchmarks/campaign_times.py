"""Wall time of a finished campaign, per stage, from the Snakemake benchmark files and job logs.

Reads ``results/benchmarks/<rule>/**/*.tsv`` (one file per job, column ``s`` = wall seconds of the
job, ``cpu_time``, ``max_rss`` in MB) and the last line of each job log ``results/logs/<rule>/**/*.log``
(``timing: start-up S s, work W s[, numba import N s]``, written by nps.stages.job) and prints per rule: jobs,
summed job wall time, mean and largest job, mean start-up (process start to the stage function imported),
mean work (the stage function) and mean numba import within the work (jobs that ran a kernel; numba is
imported by the first kernel call), largest resident memory. The campaign's elapsed time is about
the summed job time divided by the number of parallel jobs (``-j``) plus Snakemake's own scheduling.

    python benchmarks/campaign_times.py [results]
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pandas as pd


TIMING = re.compile(r"timing: start-up (?P<start_up_s>[\d.]+) s, work (?P<work_s>[\d.]+) s"
                    r"(?:, numba import (?P<numba_s>[\d.]+) s)?(?:, cpu (?P<cpu_s>[\d.]+) s, max rss (?P<rss_mb>\d+) MB)?")


def log_timings(log_dir: Path) -> pd.DataFrame:
    """Per job (rule, start_up_s, work_s, numba_s, log_cpu_s, log_rss_mb) from the ``timing:`` line of its log
    (numba_s: 0 for a job that imported no numba; log_cpu_s, log_rss_mb: NaN in a log written before they were
    reported)."""
    rows = []
    for path in sorted(log_dir.rglob("*.log")):
        lines = path.read_text().splitlines()
        match = TIMING.match(lines[-1]) if lines else None
        if match:
            values = match.groupdict()
            rows.append({"rule": path.relative_to(log_dir).parts[0], "start_up_s": float(values["start_up_s"]),
                         "work_s": float(values["work_s"]), "numba_s": float(values["numba_s"] or 0.0),
                         "log_cpu_s": float(values["cpu_s"] or "nan"), "log_rss_mb": float(values["rss_mb"] or "nan")})
    return pd.DataFrame(rows, columns=["rule", "start_up_s", "work_s", "numba_s", "log_cpu_s", "log_rss_mb"])


def stage_table(results: Path) -> pd.DataFrame:
    benchmark_dir = results / "benchmarks"
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
    timings = log_timings(results / "logs").groupby("rule").agg(
        start_up_s=("start_up_s", "mean"), work_s=("work_s", "mean"), numba_s=("numba_s", "mean"),
        log_cpu_s=("log_cpu_s", "sum"), log_rss_mb=("log_rss_mb", "max"))
    return table.join(timings).sort_values("total_s", ascending=False)


def main(argv: list[str]) -> int:
    table = stage_table(Path(argv[0] if argv else "results"))
    pd.set_option("display.width", 120)
    print(table.round(2).to_string())
    print(f"\n{int(table['jobs'].sum())} jobs, summed job wall time {table['total_s'].sum():.0f} s "
          f"({table['total_s'].sum() / 2 / 60:.1f} min on 2 parallel slots)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
