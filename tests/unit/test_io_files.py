"""Artifact files (nps.app.io.write_table): umask permissions, temporary files removed on failure and
after a killed write, bytes of a redone write identical to an uninterrupted one."""

import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import nps.app.io
from nps.app.io import remove_stale_temporaries, write_table

REPO = Path(__file__).resolve().parents[2]
LARGE_ROWS = 2_000_000


def large_table() -> pd.DataFrame:
    """Incompressible ~48 MB table: its zstd write takes long enough to be killed halfway."""
    rng = np.random.default_rng(14)
    return pd.DataFrame({name: rng.standard_normal(LARGE_ROWS) for name in ("x_m", "y_m", "p_Pa")})


def temporaries(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir() if p.name.endswith(".tmp"))


@pytest.mark.parametrize("umask", [0o022, 0o002, 0o077])
def test_artifact_gets_the_umask_permissions(tmp_path, umask):
    old = os.umask(umask)
    try:
        path = write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "x.parquet", stage="test")
    finally:
        os.umask(old)
    assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask


def test_failure_mid_write_removes_the_temporary_and_keeps_the_old_artifact(tmp_path, monkeypatch):
    path = write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "x.parquet", stage="test")
    before = path.read_bytes()
    real_write = nps.app.io.pq.write_table

    def write_then_fail(table, where, **kwargs):
        real_write(table, where, **kwargs)
        assert temporaries(tmp_path)  # the temporary exists while writing
        raise KeyboardInterrupt

    monkeypatch.setattr(nps.app.io.pq, "write_table", write_then_fail)
    with pytest.raises(KeyboardInterrupt):
        write_table(pd.DataFrame({"a": [2.0]}), path, stage="test")
    assert temporaries(tmp_path) == [] and path.read_bytes() == before


def test_stale_temporaries_of_the_same_output_only_are_removed(tmp_path):
    stale = [".x.parquet.ab12cd34.tmp", ".x.parquet.q_w3e4r5.tmp"]  # this writer's and mkstemp's names
    others = [".x.parquet.y.ab12cd34.tmp", ".y.parquet.ab12cd34.tmp", ".x.parquet.toolongtoken.tmp", "x.parquet.tmp"]
    for name in stale + others:
        (tmp_path / name).write_bytes(b"partial")
    assert remove_stale_temporaries(tmp_path / "missing_dir" / "x.parquet") == []
    write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "x.parquet", stage="test")
    assert temporaries(tmp_path) == sorted(others)


WRITER = """
import sys
from test_io_files import large_table  # this file, on the child's PYTHONPATH
from nps.app.io import write_table
write_table(large_table(), sys.argv[1], stage="test", metadata={"case": "kill"})
"""


def test_killed_write_leaves_an_orphan_that_the_redone_write_removes(tmp_path):
    out = tmp_path / "killed" / "big.parquet"
    out.parent.mkdir()
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parent)}
    writer = subprocess.Popen([sys.executable, "-c", WRITER, str(out)], env=env)
    deadline = time.monotonic() + 120.0
    try:
        while True:  # kill once Parquet bytes are flowing into the temporary file
            partial = [p for p in out.parent.iterdir() if p.name.endswith(".tmp") and p.stat().st_size > 0]
            if partial or writer.poll() is not None or time.monotonic() > deadline:
                break
            time.sleep(0.002)
        os.kill(writer.pid, signal.SIGKILL)
    finally:
        writer.wait()
    assert writer.returncode == -signal.SIGKILL, "the writer finished before it could be killed"
    assert not out.exists() and len(temporaries(out.parent)) == 1  # the orphan a SIGKILL leaves

    table = large_table()
    write_table(table, out, stage="test", metadata={"case": "kill"})
    reference = write_table(table, tmp_path / "uninterrupted" / "big.parquet", stage="test", metadata={"case": "kill"})
    assert temporaries(out.parent) == []
    assert out.read_bytes() == reference.read_bytes()
