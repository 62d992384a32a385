"""Numba options of every NPS kernel, in one place.

Every compiled kernel is declared with :func:`kernel`: on-disk caching (``cache=True``, the cache
lives in ``NUMBA_CACHE_DIR``/<:func:`source_hash`>), NumPy's error model (a division by zero gives inf/NaN instead of
raising inside a compiled loop; the callers check finiteness) and no fast-math, so results are
bit-reproducible. ``parallel=True`` marks kernels whose outer loop is a ``numba.prange`` over
independent items (observers, points, stations); ``inline=True`` marks small device functions
inlined into their callers.

numba validates a cached kernel by its own file's time stamp only, not by the files of the functions
it inlines or calls: a kernel in ``nps/wake/free.py`` cached before an edit of ``nps/wake/vortex.py`` would
load with the old arithmetic. The cache of one version of the sources therefore lives in a directory of
its own, named by the hash of every ``nps`` source file (``NUMBA_CACHE_DIR`` set: under it; unset:
``nps/__pycache__/numba``); an edit anywhere in the package compiles afresh.
"""

from __future__ import annotations

import hashlib
import os
from functools import lru_cache
from pathlib import Path

import numba

prange = numba.prange
_PACKAGE_DIR = Path(__file__).resolve().parents[1]  # the nps package


@lru_cache(maxsize=1)
def source_hash() -> str:
    """SHA-256 (first 16 hex digits) of the ``nps`` package sources, in path order."""
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE_DIR.rglob("*.py")):
        digest.update(path.relative_to(_PACKAGE_DIR).as_posix().encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def _cache_dir() -> str:
    """``NUMBA_CACHE_DIR`` (unset: ``nps/__pycache__/numba``) joined with :func:`source_hash`, once: a child
    process inheriting the joined directory keeps it."""
    base = os.environ.get("NUMBA_CACHE_DIR") or str(_PACKAGE_DIR / "__pycache__" / "numba")
    return base if os.path.basename(os.path.normpath(base)) == source_hash() else os.path.join(base, source_hash())


# in the environment as well: numba re-reads its configuration from the environment whenever a NUMBA_ variable
# changes (nps.stages.job sets NUMBA_NUM_THREADS), which would drop a directory set in numba.config alone
os.environ["NUMBA_CACHE_DIR"] = numba.config.CACHE_DIR = _cache_dir()


def kernel(function=None, *, parallel: bool = False, inline: bool = False):
    """``numba.njit`` with the project's options; usable as ``@kernel`` or ``@kernel(parallel=True)``."""
    options = dict(cache=True, error_model="numpy", parallel=parallel, inline="always" if inline else "never")
    if function is None:
        return lambda f: numba.njit(**options)(f)
    return numba.njit(**options)(function)


def host_cpu_name() -> str:
    """The CPU model LLVM compiles numba's kernels for on this machine (e.g. ``znver5``, ``skylake-avx512``):
    kernels compiled for different models may round differently in the last bit."""
    import llvmlite.binding as llvm

    return numba.config.CPU_NAME or str(llvm.get_host_cpu_name())
