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
kernel the part of the work that imported numba (on the first kernel call, nps.core.jit), then CPU time and
resident-memory peak, which ``benchmarks/campaign_times.py`` tabulates per rule.

In a local ``snakemake`` run the Snakefile starts a job server (nps.stages.jobserver) that imported NPS, numba
and matplotlib once; each job's script sends its plain :func:`job_spec` there (:func:`submit`) and a forked child
runs it with the job's stdout/stderr, environment and directory, so the job skips ~0.5 s of imports and ~0.5 s
of numba start-up. Without a server (env ``NPS_JOB_SERVER=off``, a cluster node, a command) the job runs in its
own process; both paths run :func:`run_spec` and write the same artifacts, bit for bit. The timing line also
gives the job's CPU time and resident-memory peak, a forked child's own (Snakemake's benchmark files measure the
script process that waited for it; the child's peak counts the pages it shares with the server).

A job in its own process imports only what its stage runs: the package faces import their modules on first use (nps.core.lazy),
numba is imported by the first kernel call, matplotlib by the figure code, the configuration code not at all
(the workflow validated the configuration once, and the params carry it).
"""

from __future__ import annotations

import os
import pickle
import socket
import struct
import sys
import time
import traceback

SERVER_ENV = "NPS_JOB_SERVER"
"""Environment variable naming the job server's socket (``off``: jobs run in their own processes)."""
REQUEST_HEADER = struct.Struct("!Q")
"""Job server protocol: the length of the pickled request, sent with the job's stdout and stderr descriptors."""
EXIT_STATUS = struct.Struct("!i")
"""Job server protocol: the child's exit status, the server's reply."""


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


def job_spec(snakemake, stage: str) -> dict:
    """What a Snakemake script job runs, as plain values: ``stage``, ``threads``, ``inputs``, ``outputs``,
    ``params`` (the rule's params less ``code``, the planned ``job`` params unpacked, the wildcards) and ``log``
    (the job's log path)."""
    params = {key: value for key, value in snakemake.params.items() if key not in ("code", "job")}
    params.update(snakemake.params.get("job", {}))  # the planned params (nps.app.plan.stage_params)
    wildcards = dict(snakemake.wildcards.items())
    clash = sorted(set(params) & set(wildcards))
    if clash:
        raise ValueError(f"rule {snakemake.rule}: params {clash} have the names of wildcards")
    params.update(wildcards)
    return {"stage": stage, "threads": max(1, int(snakemake.threads)), "inputs": dict(snakemake.input.items()),
            "outputs": dict(snakemake.output.items()), "params": params, "log": str(snakemake.log[0])}


def run_spec(spec: dict, age_s=process_age_s) -> int:
    """Run the job ``spec`` (:func:`job_spec`) in this process: its report, or its error, to its log (and an error
    to stderr); returns the exit status, 0 or 1. ``age_s()``: seconds since the job started (its log's start-up
    is the age when the stage function is imported)."""
    os.environ["NUMBA_NUM_THREADS"] = str(spec["threads"])
    os.environ["OPENBLAS_NUM_THREADS"] = "1"  # BLAS sums in one order: bit-reproducible spectra
    stage = spec["stage"]
    with open(spec["log"], "w") as log:
        try:
            from nps.stages import stage_function

            run = stage_function(stage)
            start_up_s = age_s()
            started = time.perf_counter()
            report = run(spec["inputs"], spec["outputs"], spec["params"])
            work_s = time.perf_counter() - started
        except Exception as error:  # every failure is logged where Snakemake points the user
            text = failure_text(stage, error, traceback.format_exc(), os.environ.get("NPS_DEBUG") == "1")
            log.write(text)
            sys.stderr.write(text)
            return 1
        log.write(report if report.endswith("\n") else report + "\n")
        log.write(f"timing: start-up {start_up_s:.3f} s, work {work_s:.3f} s{numba_note()}{usage_note()}\n")
    return 0


def run_job(snakemake, stage: str) -> None:
    """Run ``stage`` (a key of :data:`nps.stages.STAGES`) for a Snakemake script job: forked by the run's job server
    where there is one (nps.stages.jobserver), else in this process; exits with status 1 when the stage failed."""
    spec = job_spec(snakemake, stage)
    status = submit(spec)
    if status is None:
        status = run_spec(spec)
    if status:
        sys.exit(status)


def submit(spec: dict) -> int | None:
    """Run the job ``spec`` in a child of the job server named by ``NPS_JOB_SERVER`` (nps.stages.jobserver); its
    exit status, or None when there is no server to run it (then the caller runs it). Standard output and error
    are the caller's."""
    path = os.environ.get(SERVER_ENV, "")
    if not path or path == "off":
        return None
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        connection.connect(path)
    except OSError:
        connection.close()
        return None
    request = pickle.dumps({"spec": spec, "env": dict(os.environ), "cwd": os.getcwd(), "age_s": process_age_s()})
    with connection:
        sys.stdout.flush()
        sys.stderr.flush()
        socket.send_fds(connection, [REQUEST_HEADER.pack(len(request))], [1, 2])
        connection.sendall(request)
        reply = receive(connection, EXIT_STATUS.size)
    if len(reply) != EXIT_STATUS.size:  # the server went away while the job ran
        sys.stderr.write(f"error: stage '{spec['stage']}': the NPS job server ({path}) stopped during the job\n")
        return 1
    return EXIT_STATUS.unpack(reply)[0]


def receive(connection: socket.socket, size: int) -> bytes:
    """Up to ``size`` bytes from ``connection``: fewer only when the other side closed it."""
    data = b""
    while len(data) < size:
        chunk = connection.recv(size - len(data))
        if not chunk:
            break
        data += chunk
    return data


def usage_note() -> str:
    """``, cpu S s, max rss M MB``: this process's CPU time (user + system) and resident-memory peak (``VmHWM`` of
    /proc/self/status: getrusage's peak would carry Snakemake's own across the exec of a job process; a forked
    child's counts the pages it shares with the job server)."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_SELF)
    peak_kb = usage.ru_maxrss
    try:
        with open("/proc/self/status") as handle:
            peak_kb = next(int(line.split()[1]) for line in handle if line.startswith("VmHWM:"))
    except (OSError, StopIteration, ValueError, IndexError):
        pass
    return f", cpu {usage.ru_utime + usage.ru_stime:.3f} s, max rss {peak_kb / 1024:.0f} MB"


def numba_note() -> str:
    """``, numba import S s`` when the job ran a kernel (numba imported on the first call, nps.core.jit); else ``""``."""
    jit = sys.modules.get("nps.core.jit")
    seconds = getattr(jit, "numba_import_s", 0.0) if jit is not None else 0.0
    return f", numba import {seconds:.3f} s" if seconds > 0.0 else ""
