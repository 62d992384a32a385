"""The job server of local workflow runs (nps.stages.jobserver, issue 36): a job forked from the server writes the
same artifact and log as the job in its own process, reports a refused input as that job does, survives a malformed
request, runs in its own process when there is no server, and the server ends with the Snakemake process that started it."""

import os
import socket
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

from nps.stages import jobserver
from nps.stages.job import REQUEST_HEADER, SERVER_ENV, job_spec, run_spec, submit

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="the job server is for Linux")


class _Named(dict):
    """Snakemake's named lists: ``items()``, ``get`` and positional access."""

    def __getitem__(self, key):
        return list(self.values())[key] if isinstance(key, int) else dict.__getitem__(self, key)


def _trim_job(tmp_path: Path, repo_root: Path, name: str) -> SimpleNamespace:
    from nps.app.config import load_aircraft, load_mission

    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    speeds = next(s for s in load_mission(repo_root / "config/missions/demo.yaml")["segments"] if s["id"] == "seg2")
    params = {"aircraft_config": aircraft, "speeds": speeds["aircraft"]["helicopter"],
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}, "n_psi": 36,
              "n_r": 10}
    return SimpleNamespace(rule="trim", threads=1, input=_Named(), output=_Named(trim=str(tmp_path / f"{name}.parquet")),
                           params=_Named(job=params, code="x"), wildcards=_Named(segment="seg2"),
                           log=_Named(log=str(tmp_path / f"{name}.log")))


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """A job server owned by this test process (NPS_JOB_SERVER set while the module's tests run), started from a
    working directory outside the repository, as Snakemake's ``-d DIR`` does."""
    saved = os.environ.get(SERVER_ENV)
    os.environ.pop(SERVER_ENV, None)
    workdir, cwd = tmp_path_factory.mktemp("server"), os.getcwd()
    os.chdir(workdir)
    try:
        process = jobserver.start(os.getpid(), workdir / "server.log")
    finally:
        os.chdir(cwd)
    assert process is not None, (workdir / "server.log").read_text()
    yield process
    jobserver.stop(process)
    if saved is not None:
        os.environ[SERVER_ENV] = saved


def _report(log: Path) -> list[str]:
    """The log without its timing line (times differ from run to run)."""
    return [line for line in log.read_text().splitlines() if not line.startswith("timing: ")]


def test_a_forked_job_writes_what_the_job_writes_in_its_own_process(server, tmp_path, repo_root):
    forked, own = _trim_job(tmp_path, repo_root, "forked"), _trim_job(tmp_path, repo_root, "own")
    assert submit(job_spec(forked, "trim")) == 0
    assert run_spec(job_spec(own, "trim")) == 0
    assert (tmp_path / "forked.parquet").read_bytes() == (tmp_path / "own.parquet").read_bytes()
    assert _report(tmp_path / "forked.log") == _report(tmp_path / "own.log")
    timing = (tmp_path / "forked.log").read_text().splitlines()[-1]
    assert timing.startswith("timing: start-up ") and ", cpu " in timing and "numba" not in timing, timing


def test_a_refused_input_is_one_line_on_the_jobs_stderr(server, tmp_path, repo_root, capfd, monkeypatch):
    monkeypatch.delenv("NPS_DEBUG", raising=False)
    job = _trim_job(tmp_path, repo_root, "bad")
    job.params["job"] = {**job.params["job"], "n_psi": -1}
    assert submit(job_spec(job, "trim")) == 1
    err = capfd.readouterr().err  # the child wrote to this process's file descriptor 2
    lines = [line for line in (tmp_path / "bad.log").read_text().splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: stage 'trim': "), lines
    assert lines[0] in err and "Traceback" not in err
    assert not (tmp_path / "bad.parquet").exists()


def test_a_malformed_request_leaves_the_server_serving(server, tmp_path, repo_root):
    """A request that is not a pickled job (a stray client, a truncated write) is dropped; the next job runs."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as stray:
        stray.connect(os.environ[SERVER_ENV])
        garbage = b"not a pickle"
        socket.send_fds(stray, [REQUEST_HEADER.pack(len(garbage))], [1, 2])
        stray.sendall(garbage)
        stray.settimeout(10.0)
        assert stray.recv(16) == b""  # closed by the server, no child forked
    assert server.poll() is None
    assert submit(job_spec(_trim_job(tmp_path, repo_root, "after"), "trim")) == 0


def test_without_a_server_a_job_runs_in_its_own_process(tmp_path, repo_root, monkeypatch):
    spec = job_spec(_trim_job(tmp_path, repo_root, "alone"), "trim")
    monkeypatch.delenv(SERVER_ENV, raising=False)
    assert submit(spec) is None
    monkeypatch.setenv(SERVER_ENV, "off")
    assert submit(spec) is None
    monkeypatch.setenv(SERVER_ENV, str(tmp_path / "no-such-socket"))
    assert submit(spec) is None
    assert not (tmp_path / "alone.log").exists()


def test_the_server_ends_with_its_snakemake_process(tmp_path, monkeypatch):
    monkeypatch.delenv(SERVER_ENV, raising=False)
    owner = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    server = jobserver.start(owner.pid, tmp_path / "server.log")
    try:
        path = os.environ[SERVER_ENV]
        assert os.path.exists(path)
        owner.kill()
        owner.wait()
        server.wait(timeout=10.0)  # the server polls its owner once a second
        assert not os.path.exists(os.path.dirname(path))
    finally:
        jobserver.stop(server)
