"""The numba cache of one version of the package sources lives in a directory of its own (nps.core.jit):
numba checks a cached kernel against its own file only, so a kernel cached before an edit of a function it
inlines from another file would load with the old arithmetic. numba itself is imported on the first call of a
kernel, not with the modules that declare kernels."""

import dataclasses
import os
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np
from numba.core import config

from nps.core import jit

REPO = Path(__file__).resolve().parents[2]


def test_kernel_cache_is_keyed_by_the_package_sources(monkeypatch):
    """The directory is named by the source hash, set in the environment (child processes keep it, not
    nesting a second hash), and survives numba's re-reading of its configuration when a NUMBA_ variable
    changes (as nps.stages.job's NUMBA_NUM_THREADS does)."""
    assert jit.numba_module() is numba
    cache = Path(numba.config.CACHE_DIR)
    assert cache.name == jit.source_hash() and len(jit.source_hash()) == 16
    assert os.environ["NUMBA_CACHE_DIR"] == str(cache)
    monkeypatch.setenv("NUMBA_DEBUG_CACHE", "0")
    config.reload_config()
    assert Path(numba.config.CACHE_DIR) == cache


def _fresh(code: str) -> str:
    """stdout of ``code`` run by a fresh interpreter on this repository's package."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, (str(REPO), os.environ.get("PYTHONPATH")))))
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env,
                          cwd=REPO).stdout


def test_numba_is_imported_by_the_first_kernel_call_only():
    """Importing modules that declare kernels (kernels calling kernels across modules, prange) does not import
    numba; the first call does, with the cache directory of the sources, and then every loaded module holds the
    dispatchers and numba.prange in place of the stand-ins; a kernel declared afterwards is a dispatcher."""
    out = _fresh(
        "import os, sys\n"
        "import nps.wake.free as free, nps.wake.vortex as vortex\n"
        "from nps.core import jit\n"
        "print('numba' in sys.modules, vortex.prange is jit.prange and isinstance(vortex.segment_velocity, jit.LazyKernel))\n"
        "jit.host_cpu_name()\n"
        "import numba\n"
        "from numba.core.registry import CPUDispatcher\n"
        "kernels = [v for m in (free, vortex) for v in vars(m).values() if isinstance(v, (jit.LazyKernel, CPUDispatcher))]\n"
        "print(all(isinstance(k, CPUDispatcher) for k in kernels), len(kernels) > 3)\n"
        "print(free.prange is numba.prange, vortex.prange is numba.prange, jit.prange is numba.prange)\n"
        "print(os.path.basename(numba.config.CACHE_DIR) == jit.source_hash())\n"
        "import nps.noise.hsi_kernels as later\n"
        "print(isinstance(later.radiation_mach_kernel, CPUDispatcher))\n")
    assert out.split() == ["False", "True"] + ["True"] * 7, out


def test_a_lazy_kernel_computes_what_numba_njit_computes():
    """A kernel declared before numba is imported gives numba.njit's result, bit for bit, with the project's
    options (error model numpy: 1/0 is inf), and reads as its dispatcher (signatures) after the first call."""

    def ratio(a, b):
        out = np.empty_like(a)
        for i in jit.prange(a.shape[0]):
            out[i] = np.sin(a[i]) / b[i]
        return out

    lazy = jit.LazyKernel(ratio, dict(cache=False, error_model="numpy", parallel=False, inline="never"))
    a, b = np.linspace(0.0, 3.0, 7), np.array([1.0, 3.0, 0.0, 7.0, 0.1, 1e-300, 2.0])
    got = lazy(a, b)
    expected = numba.njit(error_model="numpy")(ratio.__wrapped__ if hasattr(ratio, "__wrapped__") else ratio)(a, b)
    assert np.array_equal(got, expected) and np.isinf(got[2])
    assert lazy.signatures and lazy.py_func is ratio and lazy.__name__ == "ratio"


def test_kernel_array_is_a_writeable_c_contiguous_copy_only_where_needed():
    """A read-only or Fortran-ordered array comes back as a writeable C-contiguous copy with the same values;
    an array that already is one comes back as itself."""
    good = np.arange(6.0).reshape(2, 3)
    assert jit.kernel_array(good) is good
    readonly = good.copy()
    readonly.flags.writeable = False
    fortran = np.asfortranarray(good)
    for odd in (readonly, fortran, np.broadcast_to(good[0], (2, 3)), [0, 1, 2]):
        array = jit.kernel_array(odd)
        assert array.flags.c_contiguous and array.flags.writeable
        np.testing.assert_array_equal(array, np.asarray(odd, dtype=float))
    assert jit.kernel_array(good, dtype=np.int64).dtype == np.int64


def test_read_only_and_fortran_inputs_compile_no_second_signature():
    """Pandas columns are read-only and transposed arrays Fortran-ordered: each would be a numba type of its own and
    a whole recompilation of the kernel (issue 36). The callers pass every array through kernel_array, so a
    kernel keeps the one signature of its C-contiguous writeable inputs."""
    from nps.noise.acoustics import Observers, _coverage, covered_interval
    from nps.wake.bvi import _transfer_array, gust_transfer
    from tests.unit.test_acoustics_reference import _observers, _sources

    sources = _sources(16, None)
    position, velocity = _observers()
    covered_interval(sources, Observers(position, velocity))
    gust_transfer(np.linspace(0.0, 5.0, 8), np.full(8, 0.5))
    coverage, transfer = len(_coverage.signatures), len(_transfer_array.signatures)
    frozen = np.array(sources.time_s)
    frozen.flags.writeable = False
    odd = Observers(np.asfortranarray(position), np.asfortranarray(velocity))
    covered_interval(dataclasses.replace(sources, time_s=frozen), odd)
    gust_transfer(np.asfortranarray(np.linspace(0.0, 5.0, 8).reshape(2, 4)), 0.5)
    assert (len(_coverage.signatures), len(_transfer_array.signatures)) == (coverage, transfer)
