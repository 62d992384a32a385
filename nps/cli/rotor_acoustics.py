"""``python -m nps rotor_acoustics``: pressure signals of one rotor from its disk table (nps.acoustics).

Reads a disk table (``loads/{rotor}.parquet`` or ``bvi/{rotor}.parquet``), the aircraft trim
artifact and an observer table; writes the pressure signals of docs/conventions.md:
``observer``, ``group`` (``thickness``, ``loading``), ``time_s``, ``p_Pa`` on the aircraft's common
grid, one revolution of the reference (first) rotor with ``--samples-per-rev`` samples,
t_k = k·T_ref/N (t = 0: blade 0 of every rotor at ψ = 0). The rotor's sources are placed with
its trim row (hub, shaft, rotation, aircraft velocity), flapping and hinge offset; thickness by
the dual-compact lines (default) or the compact monopole.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Mapping

import numpy as np
import pandas as pd

from nps.acoustics import LOADING, THICKNESS, AcousticsError, Observers, TimeGrid, radiate_rotor, signals_table
from nps.config import ConfigError, aircraft_rotor, load_aircraft
from nps.io import ArtifactError, read_table, write_table
from nps.sources import DISK_COLUMNS, DUAL_COMPACT, ThicknessModel

TRIM_COLUMNS = ("rotor", "rotation_sign", "n_blades", "omega_rad_s", "hub_x_m", "hub_y_m", "hub_z_m", "vel_x_mps",
                "vel_y_mps", "vel_z_mps", "density_kg_m3", "speed_of_sound_mps") + tuple(
    f"r_gh_{i}{j}" for i in range(3) for j in range(3))
OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps")


def trim_row(trim: pd.DataFrame, rotor: str, what: str = "trim") -> pd.Series:
    """The single trim row of ``rotor``."""
    rows = trim[trim["rotor"] == rotor]
    if len(rows) != 1:
        raise ArtifactError(f"{what}: expected one row for rotor '{rotor}', found {len(rows)}; rotors: {list(trim['rotor'])}")
    return rows.iloc[0]


def common_grid(trim: pd.DataFrame, reference_rotor: str, samples_per_rev: int, what: str = "trim") -> TimeGrid:
    """One revolution of the reference rotor from t = 0 with ``samples_per_rev`` samples."""
    if samples_per_rev < 8:
        raise AcousticsError(f"samples_per_rev: expected at least 8, got {samples_per_rev}")
    omega = float(trim_row(trim, reference_rotor, what)["omega_rad_s"])
    if not omega > 0:
        raise ArtifactError(f"{what}: rotor '{reference_rotor}': omega_rad_s must be positive, got {omega}")
    return TimeGrid(0.0, 2.0 * np.pi / omega, int(samples_per_rev))


def rotor_signals(disk: pd.DataFrame, trim: pd.DataFrame, observers: pd.DataFrame, rotor: str, reference_rotor: str,
                  samples_per_rev: int, thickness: ThicknessModel, hinge_offset_m: float) -> pd.DataFrame:
    """Long signal table (observer, group, time_s, p_Pa) of one rotor at the observers."""
    row = trim_row(trim, rotor)
    grid = common_grid(trim, reference_rotor, samples_per_rev)
    obs = Observers(observers[["x_m", "y_m", "z_m"]].to_numpy(float), observers[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float))
    pressure = radiate_rotor(disk, row.to_dict(), obs, grid, thickness=thickness, hinge_offset_m=hinge_offset_m)
    return signals_table(observers["observer"].to_numpy(), (LOADING, THICKNESS), pressure, grid, total=False)


def run(disk_path: str | Path, trim_path: str | Path, observers_path: str | Path, rotor: str, reference_rotor: str,
        samples_per_rev: int, thickness: ThicknessModel, hinge_offset_m: float, out: str | Path,
        metadata: Mapping) -> pd.DataFrame:
    """Read the three artifacts, radiate, write the signal table; returns it."""
    disk = read_table(disk_path, required=DISK_COLUMNS)
    trim = read_table(trim_path, required=TRIM_COLUMNS)
    observers = read_table(observers_path, required=OBSERVER_COLUMNS)
    try:
        table = rotor_signals(disk, trim, observers, rotor, reference_rotor, samples_per_rev, thickness, hinge_offset_m)
    except AcousticsError as exc:
        raise AcousticsError(f"{disk_path} / {observers_path}: {exc}") from None
    meta = {**metadata, "rotor": rotor, "reference_rotor": reference_rotor, "samples_per_rev": int(samples_per_rev),
            "thickness": thickness.kind, "chord_fractions": list(thickness.chord_fractions),
            "hinge_offset_m": float(hinge_offset_m), "inputs": [str(disk_path), str(trim_path), str(observers_path)]}
    write_table(table, out, stage="acoustics", metadata=meta)
    return table


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps rotor_acoustics", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--disk", required=True, help="disk table (results/.../loads/ROTOR.parquet or bvi/ROTOR.parquet)")
    parser.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    parser.add_argument("--observers", required=True, help="observer table (results/.../observers/SET.parquet)")
    parser.add_argument("--aircraft", required=True, help="aircraft YAML: hinge offset, reference (first) rotor")
    parser.add_argument("--rotor", required=True, help="rotor name")
    parser.add_argument("--samples-per-rev", type=int, default=1024, help="samples per reference-rotor revolution")
    parser.add_argument("--thickness", default=DUAL_COMPACT, help="dual_compact (default) or compact_monopole")
    parser.add_argument("--chord-fractions", type=float, nargs=2, default=(0.13, 0.87), metavar=("FRONT", "REAR"),
                        help="dual-compact line positions from the leading edge (fractions of chord)")
    parser.add_argument("--out", required=True, help="signal table Parquet")
    args = parser.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        rotor = aircraft_rotor(aircraft, args.rotor, args.aircraft)
        model = ThicknessModel(args.thickness, tuple(args.chord_fractions))
        run(args.disk, args.trim, args.observers, args.rotor, aircraft["rotors"][0]["name"], args.samples_per_rev, model,
            float(rotor.get("hinge_offset_m", 0.0)), args.out, {"aircraft": aircraft["name"]})
    except (ConfigError, ArtifactError, AcousticsError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    return 0
