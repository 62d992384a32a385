"""Stage ``radiate`` (not in the study workflow): compact-F1A pressure signals of tabulated sources.

inputs: ``sources`` (Parquet or CSV, long format, one row per node × source time: node, [group],
time_s (uniform, the same for all nodes), x_m, y_m, z_m (ground frame), fx_N, fy_N, fz_N (force on
the fluid), optional volume_m3 (compact thickness monopole), optional vx_mps, vy_mps, vz_mps),
``observers`` (Parquet or CSV: observer, x_m, y_m, z_m at t = 0, vx_mps, vy_mps, vz_mps).
outputs: ``signals`` (observer, group (each group and "total"), time_s, p_Pa). params: ``t_start_s``,
``duration_s``, ``n_samples`` (observer grid t_k = T0 + k·D/N), ``c0_mps``, ``rho0_kg_m3``.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from nps.noise.acoustics import AcousticsError
from nps.app.io import ArtifactError, read_table, write_table
from nps.noise.sources import radiate


def read_any(path: str | Path) -> pd.DataFrame:
    """A table from Parquet (an NPS artifact) or CSV."""
    if Path(path).suffix.lower() == ".csv":
        if not Path(path).exists():
            raise ArtifactError(f"{path}: file not found")
        return pd.read_csv(path)
    return read_table(path)


def run(inputs: dict, outputs: dict, params: dict) -> str:
    c0, rho0 = float(params["c0_mps"]), float(params["rho0_kg_m3"])
    duration, samples = float(params["duration_s"]), int(params["n_samples"])
    if not (c0 > 0 and rho0 > 0 and duration > 0 and samples > 0):
        raise AcousticsError("c0_mps, rho0_kg_m3, duration_s and n_samples must be positive")
    sources, observers = read_any(inputs["sources"]), read_any(inputs["observers"])
    try:
        table = radiate(sources, observers, float(params["t_start_s"]), duration, samples, c0, rho0)
    except AcousticsError as exc:
        raise AcousticsError(f"{inputs['sources']} / {inputs['observers']}: {exc}") from None
    write_table(table, outputs["signals"], stage="radiate",
                metadata={"sources": str(inputs["sources"]), "observers": str(inputs["observers"]), "c0_mps": c0, "rho0_kg_m3": rho0})
    return f"{table['observer'].nunique()} observers x {samples} samples -> {outputs['signals']}"
