"""The numba cache of one version of the package sources lives in a directory of its own (nps.core.jit):
numba checks a cached kernel against its own file only, so a kernel cached before an edit of a function it
inlines from another file would load with the old arithmetic."""

import os
from pathlib import Path

import numba
from numba.core import config

from nps.core import jit


def test_kernel_cache_is_keyed_by_the_package_sources(monkeypatch):
    """The directory is named by the source hash, set in the environment (child processes keep it, not
    nesting a second hash), and survives numba's re-reading of its configuration when a NUMBA_ variable
    changes (as nps.stages.job's NUMBA_NUM_THREADS does)."""
    cache = Path(numba.config.CACHE_DIR)
    assert cache.name == jit.source_hash() and len(jit.source_hash()) == 16
    assert os.environ["NUMBA_CACHE_DIR"] == str(cache)
    monkeypatch.setenv("NUMBA_DEBUG_CACHE", "0")
    config.reload_config()
    assert Path(numba.config.CACHE_DIR) == cache
