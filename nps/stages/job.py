"""Snakemake adapter: run one stage for a ``script:`` job, with its log and thread count.

Workflow scripts are two lines, ``from nps.stages.job import run_job; run_job(snakemake, "<stage>")``.
The job's named inputs, outputs and params (less the ``code`` hash that only triggers reruns; the
``job`` param, :func:`nps.app.plan.stage_params`, is unpacked) and its wildcards become the stage's
``inputs``, ``outputs`` and ``params``. numba's thread pool is sized
to the job's ``threads`` before anything imports numba. The stage's report goes to the job's
``log:`` file; an error is written there too and to stderr, and the job exits with status 1: an
expected error (a refused input, :func:`expected_errors`) as one line ``error: stage '<stage>': ...``,
any other error with its traceback (real module paths); ``NPS_DEBUG=1`` shows every traceback. The log's last line gives the job's start-up (process
start to the stage function imported) and work (the stage function) in seconds, and for a job that ran a numba
kernel the part of the work that imported numba (on the first kernel call, nps.core.jit), which
``benchmarks/campaign_times.py`` tabulates per rule.

A job imports only what its stage runs: the package faces import their modules on first use (nps.core.lazy),
numba is imported by the first kernel call, matplotlib by the figure code, the configuration code not at all
(the workflow validated the configuration once, and the params carry it).
"""

from __future__ import annotations

import os
import sys
import time
import traceback


def expected_errors() -> tuple[type[BaseException], ...]:
    """Errors of bad inputs (files, fields, values, validity, memory, trims that cannot converge): one line,
    no traceback (a workflow job unless env ``NPS_DEBUG=1``, a command unless ``--debug``); every other error
    keeps it. ConfigError, ValidityError, ObserverError, AcousticsError and ArtifactError are ValueErrors.
    Imported when called: numba's thread pool is sized before anything imports numba."""
    from nps.app.resources import ResourceError
    from nps.rotor.bet import TrimError
    from nps.rotor.trim import AircraftTrimError

    return ValueError, KeyError, OSError, ResourceError, TrimError, AircraftTrimError


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


def failure_text(stage: str, error: BaseException, trace: str, debug: bool = False) -> str:
    """What a failed job writes to its log and stderr: one line ``error: stage '<stage>': <message>`` for an
    expected error (:func:`expected_errors`), the message and ``trace`` (its traceback) for any other error
    or with ``debug`` (env ``NPS_DEBUG=1``)."""
    message = error.args[0] if isinstance(error, KeyError) and error.args else error
    if isinstance(error, expected_errors()) and not debug:
        return f"error: stage '{stage}': {message}\n"
    return f"stage '{stage}' failed: {message}\n\n{trace}"


def run_job(snakemake, stage: str) -> None:
    """Run ``stage`` (a key of :data:`nps.stages.STAGES`) for a Snakemake script job."""
    os.environ["NUMBA_NUM_THREADS"] = str(max(1, int(snakemake.threads)))
    os.environ["OPENBLAS_NUM_THREADS"] = "1"  # BLAS sums in one order: bit-reproducible spectra
    params = {key: value for key, value in snakemake.params.items() if key not in ("code", "job")}
    params.update(snakemake.params.get("job", {}))  # the planned params (nps.app.plan.stage_params)
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
            text = failure_text(stage, error, traceback.format_exc(), os.environ.get("NPS_DEBUG") == "1")
            log.write(text)
            sys.stderr.write(text)
            sys.exit(1)
        log.write(report if report.endswith("\n") else report + "\n")
        log.write(f"timing: start-up {start_up_s:.3f} s, work {work_s:.3f} s{numba_note()}\n")


def numba_note() -> str:
    """``, numba import S s`` when the job ran a kernel (numba imported on the first call, nps.core.jit); else ``""``."""
    jit = sys.modules.get("nps.core.jit")
    seconds = getattr(jit, "numba_import_s", 0.0) if jit is not None else 0.0
    return f", numba import {seconds:.3f} s" if seconds > 0.0 else ""
