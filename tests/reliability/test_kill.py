"""Kill test of issue 14: a tiny campaign killed with SIGKILL during a Parquet write, then rerun with
``--rerun-incomplete``, leaves no orphan temporary file and reproduces the uninterrupted artifacts
byte for byte (the committed manifest of tests/workflow/test_campaign.py's tiny campaign).

The kill is placed exactly: a ``sitecustomize`` module on the jobs' PYTHONPATH wraps
``pyarrow.parquet.write_table`` and, once the temporary file of the first metrics table is written
(before ``nps.app.io.write_table`` renames it), kills the whole Snakemake process group with SIGKILL.
About 25 s on an idle 2-core machine (helicopter only); a second Snakemake campaign, so marked slow (the
default run keeps one, tests/workflow/test_campaign.py's tiny campaign).
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

REPO = Path(__file__).resolve().parents[2]
from campaigns import TINY, tiny_manifest
from nps.app.digests import compare, digests, read_manifest

TARGET = "hemisphere_base.parquet"  # metrics table: written late, after most artifacts
SITECUSTOMIZE = f'''
import os
import signal

import pyarrow.parquet as pq

_write = pq.write_table


def write_table(table, where, *args, **kwargs):
    _write(table, where, *args, **kwargs)
    name = os.path.basename(str(where))
    if name.startswith(".{TARGET}.") and name.endswith(".tmp"):
        os.killpg(os.getpgid(0), signal.SIGKILL)


pq.write_table = write_table
'''


def _snakemake(workdir: Path, *args: str, env: dict | None = None) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=1800, start_new_session=True)


@pytest.mark.slow
def test_sigkill_during_a_parquet_write_then_rerun_incomplete(tmp_path):
    work = tmp_path / "campaign"
    shutil.copytree(REPO / "config", work / "config")
    tiny = {**TINY, "campaign": {**TINY["campaign"], "aircraft": ["helicopter"]}}
    (work / "config/config.yaml").write_text(yaml.safe_dump(tiny, sort_keys=False))
    hook = tmp_path / "hook"
    hook.mkdir()
    (hook / "sitecustomize.py").write_text(SITECUSTOMIZE)
    killed = _snakemake(work, "-j2", "all", env={**os.environ, "PYTHONPATH": str(hook)})
    assert killed.returncode == -signal.SIGKILL, killed.stderr[-3000:]
    orphans = sorted((work / "results").rglob(f".{TARGET}.*.tmp"))
    assert orphans, "the kill did not happen during the metrics write"

    assert _snakemake(work, "--unlock").returncode == 0
    rerun = _snakemake(work, "-j2", "all", "--rerun-incomplete")
    assert rerun.returncode == 0, rerun.stderr[-3000:]
    assert not list((work / "results").rglob("*.tmp"))
    manifest = {n: d for n, d in read_manifest(tiny_manifest()).items()
                if n.startswith("helicopter/")}
    assert not compare(digests(work / "results"), manifest)
