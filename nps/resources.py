"""Cluster requests of the workflow's jobs: threads, memory (MB) and run time (min).

A job's memory is a start-up baseline plus bytes per element of the arrays it holds, the elements
being counted from the configured resolution (:class:`JobSize`):

- disk elements ``n_rotors·n_psi·n_r`` (blade-load tables; per-rotor loads jobs have n_rotors 1),
- wake elements ``n_rotors·wake_revolutions·n_psi²`` (one wake snapshot per blade azimuth),
- signal elements ``n_rotors·n_observers·samples_per_rev`` (pressure-signal tables).

Constants: peak resident memory (Snakemake benchmark ``max_rss``) of the helicopter seg3 + seg5
jobs measured at two resolutions, the bundled one (n_psi 360, n_r 50, 4 wake revolutions,
1024 samples per revolution, 360 hemisphere observers) and a coarse one (72, 16, 2, 256, 32
observers), warm numba cache; the baseline is the coarse job's memory (e.g. acoustics 279 MB, HSI
280 MB, metrics 198 MB) and the per-element bytes the slope between the two (acoustics ~100 B
and HSI ~160 B per signal element, i.e. a few copies of 2 float64 columns per sample). The
request is 1.5 times the estimate, at least 500 MB, times the attempt: a job killed for memory
or time is resubmitted (profile ``retries``) with twice, then three times the request.

Run time: ``RUNTIME_MIN`` (minutes at the bundled resolution, ≥ 10 times the longest job measured
there on a loaded 2-core machine) scaled by the ratio of the job's work elements to the
bundled resolution's, times the attempt.

Threads: numba-parallel kernels only. The wake (prange over azimuth rows and points) asks
``MAX_THREADS``; the F1A radiation runs in parallel over blocks of ``acoustics.OBSERVER_BLOCK``
observers and HSI over observers, so they ask one thread per block / observer up to
``MAX_THREADS``; every other stage is serial (1). Snakemake lowers a request above ``--cores``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

MAX_THREADS = 4
OBSERVER_BLOCK = 16  # nps.acoustics.OBSERVER_BLOCK (not imported: the workflow must not load numba)
MIN_MEMORY_MB = 500
HEADROOM = 1.5


@dataclass(frozen=True)
class JobSize:
    """What a job's arrays scale with: the ``resolution`` section of the config, the rotors the job
    handles and the observers of its observer set (0 where it has none)."""

    n_psi: int
    n_r: int
    wake_revolutions: int
    samples_per_rev: int
    n_rotors: int = 1
    n_observers: int = 0

    def __post_init__(self):
        for name in ("n_psi", "n_r", "wake_revolutions", "samples_per_rev", "n_rotors"):
            if int(getattr(self, name)) < 1:
                raise ValueError(f"JobSize.{name}: expected an integer >= 1, got {getattr(self, name)!r}")
        if int(self.n_observers) < 0:
            raise ValueError(f"JobSize.n_observers: expected an integer >= 0, got {self.n_observers!r}")

    def elements(self) -> dict[str, int]:
        """Element counts of the disk, wake and signal arrays."""
        return {
            "disk": self.n_rotors * self.n_psi * self.n_r,
            "wake": self.n_rotors * self.wake_revolutions * self.n_psi**2,
            "signal": self.n_rotors * self.n_observers * self.samples_per_rev,
        }


# stage -> (baseline MB, bytes per element of each kind)
MEMORY = {
    "trim": (130, {}),
    "loads": (140, {"disk": 600}),
    "observers": (140, {}),
    "wake": (280, {"wake": 35, "disk": 600}),
    "acoustics": (280, {"signal": 110, "disk": 700}),
    "hsi": (270, {"signal": 160}),
    "metrics": (200, {"signal": 150}),
    "hsi_figure": (240, {"signal": 160}),
    "rotor_figures": (200, {"disk": 1800}),
    "bvi_hotspot": (200, {"signal": 170}),
    "rotor_maps": (180, {"signal": 100}),
    "study_maps": (180, {}),
    "summary": (140, {}),
}

# stage -> (minutes at the bundled resolution, element kind its work scales with or None)
RUNTIME_MIN = {
    "trim": (5, None),
    "loads": (5, "disk"),
    "observers": (5, None),
    "wake": (15, "wake"),
    "acoustics": (15, "signal"),
    "hsi": (15, "signal"),
    "metrics": (10, "signal"),
    "hsi_figure": (5, "signal"),
    "rotor_figures": (10, "disk"),
    "bvi_hotspot": (5, "signal"),
    "rotor_maps": (5, "signal"),
    "study_maps": (5, None),
    "summary": (5, None),
}

# elements at the bundled resolution (helicopter, two rotors, 360 hemisphere observers)
BUNDLED = JobSize(n_psi=360, n_r=50, wake_revolutions=4, samples_per_rev=1024, n_rotors=2, n_observers=360)


def observer_count(spec: Mapping) -> int:
    """Number of observers of an ``observer_sets.<name>`` config entry."""
    kind = spec.get("kind")
    if kind in ("hemisphere", "sphere"):
        return int(spec["n_elevation"]) * int(spec["n_azimuth"])
    if kind == "points_ahead":
        return len(spec["elevations_deg"])
    if kind == "ground_grid":
        return int(spec["n_x"]) * int(spec["n_y"])
    raise ValueError(f"observer set kind: expected hemisphere, sphere, points_ahead or ground_grid, got {kind!r}")


def _stage(table: dict, stage: str):
    if stage not in table:
        raise ValueError(f"stage: expected one of {sorted(table)}, got {stage!r}")
    return table[stage]


def _attempt(attempt: int) -> int:
    if int(attempt) < 1:
        raise ValueError(f"attempt: expected an integer >= 1, got {attempt!r}")
    return int(attempt)


def memory_mb(stage: str, size: JobSize, attempt: int = 1) -> int:
    """Memory request (MB) of one job of ``stage``; grows linearly with the attempt."""
    base_mb, bytes_per = _stage(MEMORY, stage)
    elements = size.elements()
    estimate_mb = base_mb + sum(b * elements[kind] for kind, b in bytes_per.items()) / 1e6
    return _attempt(attempt) * max(MIN_MEMORY_MB, 100 * math.ceil(HEADROOM * estimate_mb / 100))


def runtime_min(stage: str, size: JobSize, attempt: int = 1) -> int:
    """Run-time limit (minutes) of one job of ``stage``; grows linearly with the attempt."""
    minutes, kind = _stage(RUNTIME_MIN, stage)
    scale = 1.0 if kind is None else max(1.0, size.elements()[kind] / BUNDLED.elements()[kind])
    return _attempt(attempt) * math.ceil(minutes * scale)


def threads(stage: str, size: JobSize) -> int:
    """Threads of one job of ``stage``: numba-parallel stages only, as many as their loops can use."""
    _stage(MEMORY, stage)
    if stage == "wake":
        return MAX_THREADS
    if stage == "acoustics":
        return max(1, min(MAX_THREADS, math.ceil(size.n_observers / OBSERVER_BLOCK)))
    if stage == "hsi":
        return max(1, min(MAX_THREADS, size.n_observers))
    return 1
