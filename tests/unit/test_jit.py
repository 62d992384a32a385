"""The numba cache of one version of the package sources lives in a directory of its own (nps.core.jit):
numba checks a cached kernel against its own file only, so a kernel cached before an edit of a function it
inlines from another file would load with the old arithmetic."""

import os
from pathlib import Path

import numba

from nps.core import jit


def test_kernel_cache_is_keyed_by_the_package_sources():
    cache = Path(numba.config.CACHE_DIR)
    assert cache.name == jit.source_hash() and len(jit.source_hash()) == 16
    base = os.environ.get("NUMBA_CACHE_DIR")
    expected = Path(base) if base else Path(jit.__file__).resolve().parents[1] / "__pycache__" / "numba"
    assert cache.parent == expected.resolve() or cache.parent == expected
