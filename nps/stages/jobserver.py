"""Job server of a local workflow run: every job forked from one process that imported NPS once.

A workflow job is a fresh Python process that spends 0.5 s importing NumPy, pandas and pyarrow before its stage
starts, and a job that runs a compiled kernel another 0.5–0.8 s importing numba and preparing its code generator
(docs/performance.md). In a local run (``snakemake -j2 all``) the Snakefile's ``onstart`` starts this server
(:func:`start`): it imports those libraries, the stage modules, numba (prepared, no kernel run) and matplotlib
once, then listens on a Unix socket named by the environment variable ``NPS_JOB_SERVER``, which the job processes
inherit. A job (:func:`nps.stages.job.run_job`) sends its plan (:func:`nps.stages.job.job_spec`), environment,
working directory and its standard output and error (file descriptors) to the server (:func:`nps.stages.job.submit`); the server
forks a child that takes them over and runs the stage as the job would (:func:`nps.stages.job.run_spec`: same
code, same inputs, same artifacts, the same log), and the job exits with the child's status. Without a server
(none started, the variable unset or ``off``, a cluster node, a server gone) a job runs in its own process as
before.

The server is single-threaded and runs no kernel and no I/O on tables, so that forking it is safe: no thread
pool of numba, OpenBLAS or pyarrow is started before a fork. It stays in Snakemake's process group, so that a
signal to the group (Ctrl-C, a kill of the run) reaches the jobs' children as it reaches jobs in their own
processes; the server itself ignores Ctrl-C. A job killed by Snakemake closes its connection and
the server kills its child (no artifact is written after Snakemake gave up the job; writes are atomic,
nps.app.io). The server exits when told to (:func:`stop`, Snakemake's ``onsuccess``/``onerror``) or when the
Snakemake process that started it is gone, and removes its socket's directory (private to the user, in the
temporary directory); a SIGKILL of the whole run leaves that directory and its socket behind.

Snakemake's ``benchmark:`` files measure the job process, i.e. the wall time of the job (the child's work
included) but not the child's CPU time and memory; the last line of the job's log gives them (``cpu``,
``max rss``; for a forked child its own CPU time and its resident peak, the server's shared pages included).
"""

from __future__ import annotations

import os
import pickle
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from nps.stages.job import EXIT_STATUS, REQUEST_HEADER, SERVER_ENV, receive, run_spec

READY_TIMEOUT_S = 60.0
"""Longest wait of :func:`start` for the server to listen (its imports take about 1.5 s)."""


def preload() -> None:
    """Import what the jobs use: NumPy, pandas, pyarrow's Parquet, every stage module, numba with its code
    generator prepared (no kernel run: no thread started) and matplotlib's Agg backend."""
    os.environ["OPENBLAS_NUM_THREADS"] = "1"  # before NumPy: no BLAS threads in a process that forks
    os.environ.setdefault("MPLBACKEND", "Agg")
    import numpy  # noqa: F401
    import pandas  # noqa: F401
    import pyarrow.parquet  # noqa: F401

    from nps.stages import STAGES, stage_function

    for stage in STAGES:
        stage_function(stage)
    from nps.core.jit import prepare_numba

    prepare_numba()
    import matplotlib.pyplot  # noqa: F401


def _child(request: dict, fds: list[int], received_s: float) -> int:
    """In the forked child: take over the job's output streams, environment and directory, run the job."""
    import nps.core.jit as jit

    os.dup2(fds[0], 1)
    os.dup2(fds[1], 2)
    for fd in fds:
        os.close(fd)
    numba_cache = os.environ.get("NUMBA_CACHE_DIR")
    os.environ.clear()
    os.environ.update(request["env"])
    if numba_cache:  # the directory the server's numba was set up with (nps.core.jit)
        os.environ["NUMBA_CACHE_DIR"] = numba_cache
    os.chdir(request["cwd"])
    jit.numba_import_s = 0.0  # the job imported no numba
    spec = request["spec"]
    os.environ["NUMBA_NUM_THREADS"] = str(spec["threads"])
    if "numba" in sys.modules:
        sys.modules["numba"].config.reload_config()  # the job's thread count; no thread runs yet
    return run_spec(spec, age_s=lambda: request["age_s"] + time.perf_counter() - received_s)


def serve(path: str, owner_pid: int) -> None:
    """Listen on the Unix socket ``path`` and fork a child per request until SIGTERM or until ``owner_pid`` is
    gone; a child whose job's connection closes before it ends is killed."""
    preload()
    wake_read, wake_write = os.pipe()
    os.set_blocking(wake_write, False)
    signal.set_wakeup_fd(wake_write)
    signal.signal(signal.SIGCHLD, lambda *_: None)
    stopping = []
    signal.signal(signal.SIGTERM, lambda *_: stopping.append(True))
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C reaches the jobs' children (same process group), not it
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path + ".tmp")
    listener.listen(64)
    os.rename(path + ".tmp", path)  # the socket appears when it accepts
    running: dict[int, socket.socket] = {}
    while not stopping and _alive(owner_pid):
        for status, connection in _reaped(running):
            try:
                connection.sendall(EXIT_STATUS.pack(status))
            except OSError:
                pass
            connection.close()
        readable, _, _ = select.select([listener, wake_read, *running.values()], [], [], 1.0)
        if wake_read in readable:
            os.read(wake_read, 4096)
        for connection in [c for c in readable if c not in (listener, wake_read)]:
            if not _open(connection):  # the job is gone: so is its child
                pid = next(p for p, c in running.items() if c is connection)
                os.kill(pid, signal.SIGKILL)
        if listener in readable:
            connection, _ = listener.accept()
            pid = _fork_job(connection, listener, running)
            if pid is not None:
                running[pid] = connection
    for pid in running:
        os.kill(pid, signal.SIGKILL)
    listener.close()
    shutil.rmtree(os.path.dirname(path), ignore_errors=True)


def _open(connection: socket.socket) -> bool:
    """Whether the job at the other end of ``connection`` still waits (it sends nothing after its request)."""
    try:
        return bool(connection.recv(1, socket.MSG_PEEK))
    except OSError:
        return False


def _reaped(running: dict) -> list[tuple[int, socket.socket]]:
    """(exit status, connection) of every child that ended."""
    done = []
    while running:
        pid, status = os.waitpid(-1, os.WNOHANG)
        if pid == 0:
            break
        connection = running.pop(pid, None)
        if connection is not None:
            done.append((os.waitstatus_to_exitcode(status) if os.WIFEXITED(status) else 1, connection))
    return done


def _fork_job(connection: socket.socket, listener: socket.socket, running: dict) -> int | None:
    """Read a request from ``connection`` and fork its child; None (connection closed) when it is incomplete."""
    connection.settimeout(10.0)
    request, fds = None, []
    try:
        header, fds, _, _ = socket.recv_fds(connection, REQUEST_HEADER.size, 2)
        if len(header) == REQUEST_HEADER.size:
            request = pickle.loads(receive(connection, REQUEST_HEADER.unpack(header)[0]))
    except (OSError, pickle.UnpicklingError, EOFError):  # not a request of nps.stages.job.submit
        request = None
    if request is None or len(fds) != 2:
        for fd in fds:
            os.close(fd)
        connection.close()
        return None
    received_s = time.perf_counter()
    pid = os.fork()
    if pid == 0:  # the child: never returns into the server loop
        status = 1
        try:
            signal.set_wakeup_fd(-1)
            for number in (signal.SIGCHLD, signal.SIGTERM):
                signal.signal(number, signal.SIG_DFL)
            signal.signal(signal.SIGINT, signal.default_int_handler)  # a job's Ctrl-C as in its own process
            listener.close()
            for other in running.values():
                other.close()
            connection.close()
            status = _child(request, fds, received_s)
        except BaseException:  # noqa: BLE001 - whatever happens, the child ends here with its status
            import traceback

            traceback.print_exc()
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(status)
    for fd in fds:
        os.close(fd)
    return pid


def _alive(pid: int) -> bool:
    """Whether process ``pid`` exists (signal 0; a process of another user counts)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        pass
    return True


def start(owner_pid: int, log_path: str | os.PathLike) -> subprocess.Popen | None:
    """Start a server for the Snakemake process ``owner_pid`` (its log: ``log_path``) and set ``NPS_JOB_SERVER`` in
    this process's environment for the jobs; None (jobs run in their own processes) when the variable is ``off``,
    outside Linux or when the server does not come up within READY_TIMEOUT_S."""
    if os.environ.get(SERVER_ENV) == "off" or not sys.platform.startswith("linux"):
        return None
    path = os.path.join(tempfile.mkdtemp(prefix="nps-jobs-"), "socket")
    Path(log_path).parent.mkdir(parents=True, exist_ok=True)
    package_root = str(Path(__file__).resolve().parents[2])  # jobs find nps by Snakemake's search path: so does the server
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [package_root, os.environ.get("PYTHONPATH")])))
    with open(log_path, "w") as log:
        server = subprocess.Popen([sys.executable, "-m", "nps.stages.jobserver", path, str(owner_pid)], env=env,
                                  stdin=subprocess.DEVNULL, stdout=log, stderr=log)
    deadline = time.monotonic() + READY_TIMEOUT_S
    while not os.path.exists(path):
        if server.poll() is not None or time.monotonic() > deadline:
            server.kill()
            shutil.rmtree(os.path.dirname(path), ignore_errors=True)
            sys.stderr.write(f"NPS job server did not start (its log: {log_path}); every job runs in its own process\n")
            return None
        time.sleep(0.02)
    os.environ[SERVER_ENV] = path
    return server


def stop(server: subprocess.Popen | None) -> None:
    """Stop a server of :func:`start` (its jobs have ended) and remove its socket."""
    if server is None:
        return
    path = os.environ.pop(SERVER_ENV, None)
    server.terminate()
    try:
        server.wait(timeout=10.0)
    except subprocess.TimeoutExpired:
        server.kill()
    if path:
        shutil.rmtree(os.path.dirname(path), ignore_errors=True)


if __name__ == "__main__":
    serve(sys.argv[1], int(sys.argv[2]))
