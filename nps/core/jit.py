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

numba is imported on the first call of a kernel, not when a module declaring one is imported (numba costs
about 0.35 s of a job's start-up; most jobs run no kernel): :func:`kernel` returns a :class:`LazyKernel`, and
:data:`prange` is a stand-in for ``numba.prange``. The first use of a kernel (:func:`numba_module`) imports
numba with the cache directory above, makes every kernel declared so far a ``numba.njit`` dispatcher with the
same options, and puts the dispatchers (and ``numba.prange``) in place of the stand-ins in every loaded ``nps``
module, so that kernels calling kernels compile as if declared with ``numba.njit``; kernels declared after
that are dispatchers at once. What numba compiles and caches is unchanged.
"""

from __future__ import annotations

import functools
import hashlib
import os
import sys
import time
from functools import lru_cache
from pathlib import Path

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


class _Prange:
    """Stands for ``numba.prange`` until numba is imported (then replaced by it); a ``range`` when called."""

    def __call__(self, *args):
        return range(*args)

    def __repr__(self) -> str:
        return "nps.core.jit.prange (numba.prange once numba is imported)"


prange = _Prange()
_numba = None  # the numba module, once numba_module() imported it
numba_import_s = 0.0  # seconds numba_module() took to import numba (0 until then): a job's log reports it
_pending: list[LazyKernel] = []  # kernels declared before numba was imported


class LazyKernel:
    """A kernel declared before numba is imported: ``numba.njit(**options)(function)`` made on first use.

    Calling it (or reading an attribute of the dispatcher, ``signatures``, ``stats``, ``py_func``) imports numba
    (:func:`numba_module`), which puts the dispatcher in its place in every loaded ``nps`` module."""

    def __init__(self, function, options: dict):
        functools.update_wrapper(self, function)
        self.py_func, self.options, self.compiled = function, options, None

    def dispatcher(self):
        """The ``numba.njit`` dispatcher of this kernel (numba imported on the first call)."""
        if self.compiled is None:
            numba = numba_module()
            if self.compiled is None:  # declared outside kernel()
                self.compiled = numba.njit(**self.options)(self.py_func)
        return self.compiled

    def __call__(self, *args, **kwargs):
        return self.dispatcher()(*args, **kwargs)

    def __getattr__(self, name: str):
        if name.startswith("__") or name in ("options", "compiled"):
            raise AttributeError(name)
        return getattr(self.dispatcher(), name)

    def __repr__(self) -> str:
        return f"<nps kernel {self.__qualname__} (numba not imported yet)>"


def _replace_stand_ins(numba) -> None:
    """Every :class:`LazyKernel` and the :data:`prange` stand-in held by a loaded ``nps`` module replaced by its
    dispatcher and ``numba.prange``: numba compiles a kernel against its module's globals."""
    for name, module in list(sys.modules.items()):
        if module is None or not (name == "nps" or name.startswith("nps.")):
            continue
        names = vars(module)
        for key, value in list(names.items()):
            if isinstance(value, LazyKernel):
                names[key] = value.dispatcher()
            elif isinstance(value, _Prange):
                names[key] = numba.prange


def numba_module():
    """numba, imported on the first call with the project's cache directory (:func:`_cache_dir`); the kernels
    declared so far become dispatchers, in place of their stand-ins in every loaded ``nps`` module."""
    global _numba, numba_import_s
    if _numba is None:
        started = time.perf_counter()
        # in the environment as well: numba re-reads its configuration from the environment whenever a NUMBA_
        # variable changes (nps.stages.job sets NUMBA_NUM_THREADS), which would drop a directory set in
        # numba.config alone
        os.environ["NUMBA_CACHE_DIR"] = _cache_dir()
        import numba

        numba.config.CACHE_DIR = os.environ["NUMBA_CACHE_DIR"]
        for pending in _pending:
            pending.compiled = numba.njit(**pending.options)(pending.py_func)
        _pending.clear()
        _numba = numba
        _replace_stand_ins(numba)
        numba_import_s = time.perf_counter() - started
    return _numba


def prepare_numba() -> None:
    """Import numba (:func:`numba_module`) and prepare its code generator as before the first cached kernel is
    loaded, without running a kernel (no thread pool started): what a process that forks jobs does once
    (nps.stages.jobserver)."""
    numba_module()
    from numba.core.registry import cpu_target

    cpu_target.target_context.refresh()


def kernel(function=None, *, parallel: bool = False, inline: bool = False):
    """``numba.njit`` with the project's options; usable as ``@kernel`` or ``@kernel(parallel=True)``. Before
    numba is imported, a :class:`LazyKernel` that imports it on first use."""
    options = dict(cache=True, error_model="numpy", parallel=parallel, inline="always" if inline else "never")
    if function is None:
        return lambda f: kernel(f, parallel=parallel, inline=inline)
    if _numba is not None:
        return _numba.njit(**options)(function)
    lazy = LazyKernel(function, options)
    _pending.append(lazy)
    return lazy


def kernel_array(values, dtype=float):
    """``values`` as a C-contiguous, writeable array of ``dtype``: the one array type a kernel's callers pass.

    numba compiles a kernel once per argument type, and a read-only array (a pandas column, a broadcast view) or a
    Fortran-ordered one is a type of its own: each variant of an argument is another compilation of the whole
    kernel (12–19 s for the F1A kernel), in every job that meets it on an empty cache. A copy is made only where
    ``values`` is not already such an array; the values are unchanged."""
    import numpy as np

    array = np.ascontiguousarray(values, dtype=dtype)
    return array if array.flags.writeable else array.copy()


def host_cpu_name() -> str:
    """The CPU model LLVM compiles numba's kernels for on this machine (e.g. ``znver5``, ``skylake-avx512``):
    kernels compiled for different models may round differently in the last bit."""
    import llvmlite.binding as llvm

    return numba_module().config.CPU_NAME or str(llvm.get_host_cpu_name())
