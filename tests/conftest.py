"""Shared test fixtures: repository paths and the bundled configuration."""

import os
from pathlib import Path

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

REPO = Path(__file__).resolve().parents[1]
# one numba cache for the test process and the workflow jobs it starts (the Snakefile's default): on a fresh
# machine every kernel is compiled once, not once here and once more in the jobs
os.environ.setdefault("NUMBA_CACHE_DIR", str(REPO / ".numba_cache"))
DATA = Path(__file__).resolve().parent / "data"


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO


@pytest.fixture(scope="session")
def data_dir() -> Path:
    return DATA
