"""``python -m nps loads``: trimmed blade loads of one rotor for one aircraft trim row.

Writes the disk table to ``--out`` and, next to it, ``<stem>_summary.parquet`` (quantity,
value, unit) and ``<stem>_history.parquet`` (trim iterations); ``--figure`` adds the disk plots.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from nps.bet import DiskGrid, TrimError, trim_rotor
from nps.config import ConfigError, aircraft_rotor, load_aircraft
from nps.io import ArtifactError, read_table, write_table
from nps.rotor import OperatingPoint, RotorGeometry

TRIM_COLUMNS = ("rotor", "omega_rad_s", "mu_x", "mu_y", "mu_z", "density_kg_m3", "speed_of_sound_mps",
                "thrust_N", "roll_moment_Nm", "pitch_moment_Nm")


def sibling(path: str | Path, suffix: str) -> Path:
    """``loads/main.parquet`` → ``loads/main_<suffix>.parquet``."""
    path = Path(path)
    return path.with_name(f"{path.stem}_{suffix}{path.suffix}")


def run(rotor_config: dict, trim_path: str | Path, n_psi: int, n_r: int, out: str | Path, metadata: dict,
        summary_out: str | Path | None = None, history_out: str | Path | None = None) -> dict:
    """Trim one rotor from its configuration and the aircraft trim artifact; write the three tables
    (summary and history default to the ``_summary``/``_history`` siblings of ``out``)."""
    geometry = RotorGeometry.from_config(rotor_config)
    trim = read_table(trim_path, required=TRIM_COLUMNS)
    rows = trim[trim["rotor"] == geometry.name]
    if len(rows) != 1:
        raise ArtifactError(f"{trim_path}: expected one row for rotor '{geometry.name}', found {len(rows)}")
    op = OperatingPoint.from_trim_row(rows.iloc[0])
    result = trim_rotor(geometry, op, DiskGrid(n_psi, n_r))
    meta = {**metadata, "rotor": geometry.name, "n_psi": n_psi, "n_r": n_r, "inputs": [str(trim_path)]}
    write_table(result.disk, out, stage="loads", metadata=meta)
    write_table(result.summary(), summary_out or sibling(out, "summary"), stage="loads", metadata=meta)
    write_table(result.history, history_out or sibling(out, "history"), stage="loads", metadata=meta)
    return {"result": result, "geometry": geometry}


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps loads", description=__doc__)
    parser.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    parser.add_argument("--rotor", required=True, help="rotor name in the aircraft file")
    parser.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    parser.add_argument("--n-psi", type=int, default=360, help="azimuth stations (default 360)")
    parser.add_argument("--n-r", type=int, default=50, help="radial stations (default 50)")
    parser.add_argument("--out", required=True, help="disk table Parquet (results/.../loads/NAME.parquet)")
    parser.add_argument("--figure", help="optional PNG of the disk plots")
    args = parser.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        rotor = aircraft_rotor(aircraft, args.rotor, args.aircraft)
        done = run(rotor, args.trim, args.n_psi, args.n_r, args.out, {"aircraft": aircraft["name"]})
    except (ConfigError, ArtifactError, TrimError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    result = done["result"]
    if args.figure:
        from nps.plots.disk import loads_figure

        loads_figure(result.disk, args.figure, rotation_sign=done["geometry"].rotation_sign,
                     title=f"{aircraft['name']} {args.rotor}")
    print(result.summary().to_string(index=False))
    return 0
