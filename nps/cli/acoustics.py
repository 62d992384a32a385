"""``python -m nps acoustics``: compact F1A pressure signals of tabulated sources at observers.

Sources (Parquet or CSV, long format, one row per node × source time): node, [group], time_s
(uniform, the same for all nodes), x_m, y_m, z_m (ground frame), fx_N, fy_N, fz_N (force on the
fluid), optional volume_m3 (compact thickness monopole), optional vx_mps, vy_mps, vz_mps.
Observers: observer, x_m, y_m, z_m (position at t = 0), vx_mps, vy_mps, vz_mps.
Output: observer, group (each group and "total"), time_s (t_k = T0 + k·D/N), p_Pa.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pandas as pd

from nps.acoustics import C0_MPS, RHO0_KG_M3, AcousticsError, radiate
from nps.io import ArtifactError, read_table, write_table


def _read(path: str) -> pd.DataFrame:
    if Path(path).suffix.lower() == ".csv":
        if not Path(path).exists():
            raise ArtifactError(f"{path}: file not found")
        return pd.read_csv(path)
    return read_table(path)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps acoustics", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sources", required=True, help="source table (.parquet or .csv)")
    parser.add_argument("--observers", required=True, help="observer table (.parquet or .csv)")
    parser.add_argument("--t-start", type=float, required=True, help="first observer time T0 (s)")
    parser.add_argument("--duration", type=float, required=True, help="window length D (s)")
    parser.add_argument("--samples", type=int, required=True, help="number of observer samples N")
    parser.add_argument("--c0", type=float, default=C0_MPS, help=f"speed of sound (m/s), default {C0_MPS}")
    parser.add_argument("--rho0", type=float, default=RHO0_KG_M3, help=f"density (kg/m^3), default {RHO0_KG_M3}")
    parser.add_argument("--out", required=True, help="output Parquet")
    args = parser.parse_args(argv)
    try:
        if not (args.c0 > 0 and args.rho0 > 0 and args.duration > 0 and args.samples > 0):
            raise AcousticsError("--c0, --rho0, --duration and --samples must be positive")
        sources = _read(args.sources)
        observers = _read(args.observers)
        try:
            table = radiate(sources, observers, args.t_start, args.duration, args.samples, args.c0, args.rho0)
        except AcousticsError as exc:
            raise AcousticsError(f"{args.sources} / {args.observers}: {exc}") from None
    except (AcousticsError, ArtifactError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    write_table(table, args.out, stage="acoustics",
                metadata={"sources": str(args.sources), "observers": str(args.observers), "c0_mps": args.c0, "rho0_kg_m3": args.rho0})
    return 0
