"""Numba options of every NPS kernel, in one place.

Every compiled kernel is declared with :func:`kernel`: on-disk caching (``cache=True``, the cache
lives in ``NUMBA_CACHE_DIR``), NumPy's error model (a division by zero gives inf/NaN instead of
raising inside a compiled loop; the callers check finiteness) and no fast-math, so results are
bit-reproducible. ``parallel=True`` marks kernels whose outer loop is a ``numba.prange`` over
independent items (observers, points, stations); ``inline=True`` marks small device functions
inlined into their callers.
"""

from __future__ import annotations

import numba

prange = numba.prange


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
