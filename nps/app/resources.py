"""Memory estimates per stage from the resolution: refuse what cannot fit, size ``mem_mb``.

Each estimate is the peak resident memory a stage adds above the interpreter with the NPS
modules imported (:data:`INTERPRETER_BYTES`), as a fixed part plus bytes per element of its
largest arrays. The coefficients are the largest ratios measured with ``ru_maxrss`` on the
demonstration helicopter's main rotor (segment 3; docs/reference/validity.md, "Memory"), so the
estimates are upper bounds of those measurements. Bytes are SI (1 MB = 10⁶ B).

Element counts:
- disk: n_psi × n_r stations (loads; disk fields of the wake/BVI and acoustics stages);
- wake table rows: 72 snapshot×blade pairs (5° snapshots over one blade passage, every blade)
  × (round(wake_revolutions × n_psi) + 1) nodes (the wake uses n_psi segments per revolution);
- signal samples: observers × samples_per_rev per rotor (two groups each); the HSI and metrics
  jobs read every rotor's signals at once (rotor samples = rotors × observers × samples_per_rev).

A job that treats the rotors of an aircraft in turn still holds the previous rotor's output table
while it computes the next: its estimate is the one-rotor peak plus that table (8 B per value).
"""

from __future__ import annotations

import math
import os
from typing import Mapping


INTERPRETER_BYTES = 250e6  # Python + numpy/pandas/pyarrow/numba + nps imported: 210-250 MB measured
LOADS_FIXED_BYTES = 12e6
LOADS_BYTES_PER_STATION = 650.0
WAKE_FIXED_BYTES = 60e6
WAKE_BYTES_PER_ROW = 520.0
WAKE_SNAPSHOT_BLADES = 72  # nps.cli.wake: 5° snapshots over 360°/B, B blades each
ACOUSTICS_FIXED_BYTES = 180e6  # includes a cold numba compilation (~100 MB)
ACOUSTICS_BYTES_PER_SAMPLE = 260.0
ACOUSTICS_BYTES_PER_STATION = 900.0
HSI_FIXED_BYTES = 110e6  # includes a cold numba compilation
HSI_BYTES_PER_SAMPLE = 160.0  # per rotor sample: every rotor's signals are read at once
METRICS_FIXED_BYTES = 60e6
METRICS_BYTES_PER_SAMPLE = 140.0  # per rotor sample of the radiated signals
METRICS_BYTES_PER_HSI_SAMPLE = 80.0  # per rotor sample of the HSI signals, when they enter
# column counts of nps.rotor.bet.DISK_COLUMNS and nps.wake.prescribed.WAKE_COLUMNS, written out so that Snakemake, which evaluates
# the memory requests, need not import the numba modules (tests/unit/test_resources.py checks them)
DISK_TABLE_COLUMNS = 16
WAKE_TABLE_COLUMNS = 14
DISK_TABLE_BYTES_PER_STATION = 8.0 * DISK_TABLE_COLUMNS  # a held loads/BVI disk table
WAKE_TABLE_BYTES_PER_ROW = 8.0 * WAKE_TABLE_COLUMNS  # a held wake table
MEM_MB_MARGIN = 1.25


class ResourceError(MemoryError):
    """A job's estimated memory exceeds what is available; the message holds the estimate."""


def _positive_int(name: str, value) -> int:
    if not (float(value) == int(value) and int(value) >= 1):
        raise ValueError(f"{name}: expected an integer >= 1, got {value!r}")
    return int(value)


def _held(n_rotors: int) -> int:
    """Output tables of earlier rotors still held while the next rotor is computed (0 or 1)."""
    return min(_positive_int("n_rotors", n_rotors), 2) - 1


def loads_bytes(n_psi: int, n_r: int, n_rotors: int = 1) -> float:
    """Peak memory (B) of a loads job trimming ``n_rotors`` rotors in turn on an n_psi × n_r disk."""
    stations = _positive_int("n_psi", n_psi) * _positive_int("n_r", n_r)
    return LOADS_FIXED_BYTES + (LOADS_BYTES_PER_STATION + DISK_TABLE_BYTES_PER_STATION * _held(n_rotors)) * stations


def wake_rows(n_psi: int, wake_revolutions: float) -> int:
    """Rows of one rotor's wake table: 72 × (round(wake_revolutions × n_psi) + 1)."""
    if not (math.isfinite(wake_revolutions) and wake_revolutions > 0.0):
        raise ValueError(f"wake_revolutions: expected a number > 0, got {wake_revolutions!r}")
    return WAKE_SNAPSHOT_BLADES * (int(round(wake_revolutions * _positive_int("n_psi", n_psi))) + 1)


def wake_bvi_bytes(n_psi: int, n_r: int, wake_revolutions: float, n_rotors: int = 1) -> float:
    """Peak memory (B) of a wake + BVI job treating ``n_rotors`` rotors in turn."""
    stations = _positive_int("n_psi", n_psi) * _positive_int("n_r", n_r)
    rows = wake_rows(n_psi, wake_revolutions)
    held = _held(n_rotors) * (DISK_TABLE_BYTES_PER_STATION * stations + WAKE_TABLE_BYTES_PER_ROW * rows)
    return WAKE_FIXED_BYTES + LOADS_BYTES_PER_STATION * stations + WAKE_BYTES_PER_ROW * rows + held


def acoustics_bytes(n_observers: int, samples_per_rev: int, n_psi: int, n_r: int, n_rotors: int = 1) -> float:
    """Peak memory (B) of the acoustics job of one observer set treating ``n_rotors`` rotors in turn
    (the held signal table is counted at the full per-sample coefficient)."""
    samples = _positive_int("observers", n_observers) * _positive_int("samples_per_rev", samples_per_rev)
    stations = _positive_int("n_psi", n_psi) * _positive_int("n_r", n_r)
    return (ACOUSTICS_FIXED_BYTES + ACOUSTICS_BYTES_PER_STATION * stations
            + ACOUSTICS_BYTES_PER_SAMPLE * samples * (1 + _held(n_rotors)))


def _rotor_samples(n_observers: int, samples_per_rev: int, n_rotors: int) -> int:
    return (_positive_int("observers", n_observers) * _positive_int("samples_per_rev", samples_per_rev)
            * _positive_int("n_rotors", n_rotors))


def hsi_bytes(n_observers: int, samples_per_rev: int, n_rotors: int = 1) -> float:
    """Peak memory (B) of the HSI job of one observer set (all rotors' signals read at once)."""
    return HSI_FIXED_BYTES + HSI_BYTES_PER_SAMPLE * _rotor_samples(n_observers, samples_per_rev, n_rotors)


def metrics_bytes(n_observers: int, samples_per_rev: int, n_rotors: int = 1, hsi: bool = False) -> float:
    """Peak memory (B) of the metrics job of one observer set and variant (without its figure)."""
    per_sample = METRICS_BYTES_PER_SAMPLE + (METRICS_BYTES_PER_HSI_SAMPLE if hsi else 0.0)
    return METRICS_FIXED_BYTES + per_sample * _rotor_samples(n_observers, samples_per_rev, n_rotors)


def estimate_bytes(stage: str, resolution: Mapping, n_observers: int = 1, n_rotors: int = 1, hsi: bool = False) -> float:
    """Estimate (B) of one job of ``stage`` (``loads``, ``wake``, ``acoustics``, ``hsi``, ``metrics``)
    from the campaign's ``resolution`` block (n_psi, n_r, wake_revolutions, samples_per_rev);
    ``hsi``: the metrics job also reads HSI signals."""
    n_psi, n_r = resolution["n_psi"], resolution["n_r"]
    if stage == "loads":
        return loads_bytes(n_psi, n_r, n_rotors)
    if stage == "wake":
        return wake_bvi_bytes(n_psi, n_r, float(resolution["wake_revolutions"]), n_rotors)
    if stage == "acoustics":
        return acoustics_bytes(n_observers, resolution["samples_per_rev"], n_psi, n_r, n_rotors)
    if stage == "hsi":
        return hsi_bytes(n_observers, resolution["samples_per_rev"], n_rotors)
    if stage == "metrics":
        return metrics_bytes(n_observers, resolution["samples_per_rev"], n_rotors, hsi)
    raise ValueError(f"estimate_bytes: stage '{stage}' has no estimate; expected loads, wake, acoustics, hsi or metrics")


OBSERVERS_BYTES_PER_OBSERVER = 400.0  # observer table: 9 float columns + directions, with pandas' copies (not measured)
CAMPAIGN_STAGES = ("loads", "wake", "acoustics", "hsi", "metrics")


def campaign_estimates(resolution: Mapping, observer_sets: Mapping[str, Mapping], n_rotors: int, hsi: bool = False
                       ) -> list[tuple[str, str, float]]:
    """(field, what, bytes) of every job a campaign plans, from its configuration alone: the loads and wake
    jobs of ``resolution``, and per observer set the observer table, acoustics, HSI (``hsi``) and metrics jobs
    of an aircraft with ``n_rotors`` rotors (the campaign's largest)."""
    out = [("resolution", f"loads on a {resolution['n_psi']} x {resolution['n_r']} disk",
            estimate_bytes("loads", resolution, n_rotors=n_rotors)),
           ("resolution", f"wake and BVI loads on a {resolution['n_psi']} x {resolution['n_r']} disk with "
                          f"{resolution['wake_revolutions']} wake revolutions",
            estimate_bytes("wake", resolution, n_rotors=n_rotors))]
    for name, spec in observer_sets.items():
        n = observer_count(spec)
        what = f"{n:,} observers x {resolution['samples_per_rev']} samples per revolution x {n_rotors} rotors"
        out.append((f"observer_sets.{name}", f"the observer table of {n:,} observers", OBSERVERS_BYTES_PER_OBSERVER * n))
        for stage in ("acoustics", "hsi", "metrics") if hsi else ("acoustics", "metrics"):
            out.append((f"observer_sets.{name}", f"{stage} of {what}", estimate_bytes(stage, resolution, n, n_rotors, hsi)))
    return out


def memory_problems(estimates, available: float | None = None) -> list[tuple[str, str]]:
    """[(field, problem)] of the first field (in the order of ``estimates``, :func:`campaign_estimates`: the
    resolution before the observer sets) with an estimate whose interpreter + bytes exceed the memory
    available (default :func:`available_bytes`), its largest, with the number of other such fields; [] when
    all fit."""
    have = available_bytes() if available is None else float(available)
    over = [e for e in estimates if INTERPRETER_BYTES + e[2] > have]
    if not over:
        return []
    field, what, need = max((e for e in over if e[0] == over[0][0]), key=lambda e: e[2])
    others = len({e[0] for e in over}) - 1
    more = f" ({others} other field(s) too)" if others else ""
    return [(field, f"{what} needs an estimated {(INTERPRETER_BYTES + need) / 1e6:,.0f} MB, {have / 1e6:,.0f} MB "
                    f"available: expected a job that fits in memory; lower the resolution or the observer count{more}")]


def observer_count(spec: Mapping) -> int:
    """Number of observers of an ``observer_sets.<name>`` entry of the campaign config."""
    kind = spec.get("kind")
    if kind in ("hemisphere", "sphere"):
        return int(spec["n_elevation"]) * int(spec["n_azimuth"])
    if kind == "points_ahead":
        return len(spec["elevations_deg"])
    if kind == "ground_grid":
        return int(spec["n_x"]) * int(spec["n_y"])
    if kind == "point":
        return 1
    raise ValueError(f"observer set: kind '{kind}' has no observer count")


def available_bytes() -> float:
    """Memory available to a new job (B): ``MemAvailable`` of /proc/meminfo, else physical memory."""
    try:
        with open("/proc/meminfo") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0
    except OSError:
        pass
    return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))


def check_memory(estimate_bytes: float, what: str, available: float | None = None) -> None:
    """Raise :class:`ResourceError` naming ``what``, the estimate and the available memory when
    interpreter + estimate exceed ``available`` (default :func:`available_bytes`)."""
    have = available_bytes() if available is None else float(available)
    need = INTERPRETER_BYTES + float(estimate_bytes)
    if need > have:
        raise ResourceError(f"{what}: needs an estimated {need / 1e6:,.0f} MB "
                            f"({INTERPRETER_BYTES / 1e6:.0f} MB interpreter + {estimate_bytes / 1e6:,.0f} MB arrays), "
                            f"{have / 1e6:,.0f} MB available; lower the resolution")


def mem_mb(estimate_bytes: float) -> int:
    """Snakemake ``resources: mem_mb`` for a job: (interpreter + estimate) × 1.25, in MB, rounded up."""
    return int(math.ceil((INTERPRETER_BYTES + float(estimate_bytes)) * MEM_MB_MARGIN / 1e6))


# ---- Cluster requests of every workflow job (profiles/slurm): threads, mem_mb and runtime ----
# mem_mb and runtime grow linearly with Snakemake's ``attempt`` (the profile's ``retries``
# resubmit a job killed for memory or time with 2x, then 3x its request).

MAX_THREADS = 4
OBSERVER_BLOCK = 16  # nps.noise.acoustics.OBSERVER_BLOCK (not imported: the DAG build must not load numba)
# figure stages that hold the same signals as a metrics job of their observer set
SIGNAL_FIGURES = ("hsi_figure", "bvi_hotspot", "rotor_maps")
# stage -> (minutes at the bundled resolution, work elements it scales with or None); >= 10x the
# longest job measured there on a loaded 2-core machine
RUNTIME_MIN = {
    "trim": (5, None), "loads": (5, "disk"), "observers": (5, None), "wake": (15, "wake"),
    "acoustics": (15, "signal"), "hsi": (15, "signal"), "metrics": (10, "signal"),
    "hsi_figure": (5, "signal"), "rotor_figures": (10, "disk"), "bvi_hotspot": (5, "signal"),
    "rotor_maps": (5, "signal"), "study_maps": (5, None), "summary": (5, None), "rig": (5, None), "carpet": (5, None),
}
BUNDLED_RESOLUTION = {"n_psi": 360, "n_r": 50, "wake_revolutions": 4, "samples_per_rev": 1024}
BUNDLED_OBSERVERS, BUNDLED_ROTORS = 360, 2


def _attempt(attempt: int) -> int:
    return _positive_int("attempt", attempt)


def _work_elements(kind: str, resolution: Mapping, n_observers: int, n_rotors: int) -> float:
    """disk: rotors·n_psi·n_r; wake: rotors·wake_revolutions·n_psi²; signal: rotors·observers·samples_per_rev."""
    if kind == "disk":
        return n_rotors * resolution["n_psi"] * resolution["n_r"]
    if kind == "wake":
        return n_rotors * float(resolution["wake_revolutions"]) * resolution["n_psi"] ** 2
    return n_rotors * n_observers * resolution["samples_per_rev"]


def job_mem_mb(stage: str, resolution: Mapping, n_observers: int = 1, n_rotors: int = 1, hsi: bool = False,
               attempt: int = 1) -> int:
    """``resources: mem_mb`` of one job of ``stage``: :func:`mem_mb` of its :func:`estimate_bytes`
    (figure stages holding signals: the metrics estimate; other stages: the interpreter alone),
    times the attempt."""
    if stage not in RUNTIME_MIN:
        raise ValueError(f"stage: expected one of {', '.join(RUNTIME_MIN)}, got {stage!r}")
    if stage in ("loads", "wake", "acoustics", "hsi", "metrics"):
        estimate = estimate_bytes(stage, resolution, n_observers, n_rotors, hsi)
    elif stage in SIGNAL_FIGURES:
        estimate = estimate_bytes("metrics", resolution, max(1, n_observers), n_rotors, hsi)
    else:
        estimate = 0.0
    return _attempt(attempt) * mem_mb(estimate)


def job_runtime_min(stage: str, resolution: Mapping, n_observers: int = 1, n_rotors: int = 1, attempt: int = 1) -> int:
    """``resources: runtime`` (minutes) of one job of ``stage``: :data:`RUNTIME_MIN` scaled by the
    job's work elements over the bundled resolution's (never below), times the attempt."""
    if stage not in RUNTIME_MIN:
        raise ValueError(f"stage: expected one of {', '.join(RUNTIME_MIN)}, got {stage!r}")
    minutes, kind = RUNTIME_MIN[stage]
    scale = 1.0
    if kind is not None:
        scale = max(1.0, _work_elements(kind, resolution, n_observers, n_rotors)
                    / _work_elements(kind, BUNDLED_RESOLUTION, BUNDLED_OBSERVERS, BUNDLED_ROTORS))
    return _attempt(attempt) * math.ceil(minutes * scale)


def job_threads(stage: str, n_observers: int = 1) -> int:
    """``threads`` of one job of ``stage``: the numba-parallel stages only, as many as their loops
    use — the wake (prange over azimuth rows and points) MAX_THREADS, the F1A radiation one per
    block of OBSERVER_BLOCK observers, HSI one per observer, up to MAX_THREADS; others 1."""
    if stage not in RUNTIME_MIN:
        raise ValueError(f"stage: expected one of {', '.join(RUNTIME_MIN)}, got {stage!r}")
    if stage == "wake":
        return MAX_THREADS
    if stage == "acoustics":
        return max(1, min(MAX_THREADS, math.ceil(n_observers / OBSERVER_BLOCK)))
    if stage == "hsi":
        return max(1, min(MAX_THREADS, n_observers))
    return 1
