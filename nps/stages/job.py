"""Snakemake adapter: run one stage for a ``script:`` job, with its log and thread count.

Workflow scripts are two lines, ``from nps.stages.job import run_job; run_job(snakemake, "<stage>")``.
The job's named inputs, outputs and params (less the ``code`` hash that only triggers reruns) and
its wildcards become the stage's ``inputs``, ``outputs`` and ``params``. numba's thread pool is sized
to the job's ``threads`` before anything imports numba. The stage's report goes to the job's
``log:`` file; an error is written there too (message and traceback with the real module paths)
and to stderr, and the job exits with status 1. The log's last line gives the job's start-up (process
start to the stage function imported) and work (the stage function) in seconds, which
``benchmarks/campaign_times.py`` tabulates per rule.
"""

from __future__ import annotations

import os
import sys
import time
import traceback


def process_age_s() -> float:
    """Seconds since this process started (Linux /proc; 0 where unavailable)."""
    try:
        with open("/proc/self/stat") as handle:
            start_ticks = float(handle.read().rpartition(")")[2].split()[19])
        with open("/proc/uptime") as handle:
            uptime_s = float(handle.read().split()[0])
    except (OSError, IndexError, ValueError):
        return 0.0
    return max(0.0, uptime_s - start_ticks / os.sysconf("SC_CLK_TCK"))


def run_job(snakemake, stage: str) -> None:
    """Run ``stage`` (a key of :data:`nps.stages.STAGES`) for a Snakemake script job."""
    os.environ["NUMBA_NUM_THREADS"] = str(max(1, int(snakemake.threads)))
    params = {key: value for key, value in snakemake.params.items() if key != "code"}
    wildcards = dict(snakemake.wildcards.items())
    clash = sorted(set(params) & set(wildcards))
    if clash:
        raise ValueError(f"rule {snakemake.rule}: params {clash} have the names of wildcards")
    params.update(wildcards)
    with open(snakemake.log[0], "w") as log:
        try:
            from nps.stages import stage_function

            run = stage_function(stage)
            start_up_s = process_age_s()
            started = time.perf_counter()
            report = run(dict(snakemake.input.items()), dict(snakemake.output.items()), params)
            work_s = time.perf_counter() - started
        except Exception as error:  # every failure is logged where Snakemake points the user
            text = f"stage '{stage}' failed: {error}\n\n{traceback.format_exc()}"
            log.write(text)
            sys.stderr.write(text)
            sys.exit(1)
        log.write(report if report.endswith("\n") else report + "\n")
        log.write(f"timing: start-up {start_up_s:.3f} s, work {work_s:.3f} s\n")
