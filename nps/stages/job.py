"""Snakemake adapter: run one stage for a ``script:`` job, with its log and thread count.

Workflow scripts are two lines, ``from nps.stages.job import run_job; run_job(snakemake, "<stage>")``.
The job's named inputs, outputs and params (less the ``code`` hash that only triggers reruns) and
its wildcards become the stage's ``inputs``, ``outputs`` and ``params``. numba's thread pool is sized
to the job's ``threads`` before anything imports numba. The stage's report goes to the job's
``log:`` file; an error is written there too (message and traceback with the real module paths)
and to stderr, and the job exits with status 1.
"""

from __future__ import annotations

import os
import sys
import traceback


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

            report = stage_function(stage)(dict(snakemake.input.items()), dict(snakemake.output.items()), params)
        except Exception as error:  # every failure is logged where Snakemake points the user
            text = f"stage '{stage}' failed: {error}\n\n{traceback.format_exc()}"
            log.write(text)
            sys.stderr.write(text)
            sys.exit(1)
        log.write(report if report.endswith("\n") else report + "\n")
