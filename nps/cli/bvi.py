"""``python -m nps bvi``: BVI loads of one rotor (wake-induced velocity added, no re-trim).

Reads the loads disk table, its summary and the aircraft trim; writes the BVI disk table
(same schema as the loads table) and optionally the disk figure (induced ΔU_P, trimmed and
BVI F_z with contour lines).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from nps import bvi, wake
from nps.cli.wake import model_arguments, model_from_args
from nps.config import ConfigError, aircraft_rotor, load_aircraft
from nps.io import ArtifactError, read_table, write_table
from nps.rotor import RotorGeometry


def run(rotor_config: dict, loads_path, summary_path, trim_path, model: wake.WakeModel, out, *,
        bvi_model: bvi.BVIModel = bvi.BVIModel(), figure=None, title: str = "", metadata: dict | None = None) -> bvi.BVIResult:
    """Compute and write the BVI disk table of one rotor."""
    geometry = RotorGeometry.from_config(rotor_config)
    disk = read_table(loads_path, required=bvi.DISK_COLUMNS)
    summary = read_table(summary_path, required=("quantity", "value", "unit"))
    trim = read_table(trim_path, required=bvi.TRIM_COLUMNS)
    row = bvi.select_trim_row(trim, geometry.name, str(trim_path))
    ct = bvi.summary_value(summary, "ct", str(summary_path))
    result = bvi.bvi_loads(disk, row, geometry, ct, model, bvi_model)
    meta = {**(metadata or {}), "rotor": geometry.name, "wake_model": model.__dict__, "bvi_model": bvi_model.__dict__,
            "inputs": [str(loads_path), str(summary_path), str(trim_path)]}
    write_table(result.disk, out, stage="bvi", metadata=meta)
    if figure is not None:
        from nps.plots.wake import bvi_figure_from_tables

        Path(figure).parent.mkdir(parents=True, exist_ok=True)
        bvi_figure_from_tables(disk, result.disk, figure, rotation_sign=geometry.rotation_sign, title=title or geometry.name)
    return result


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps bvi", description=__doc__)
    parser.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    parser.add_argument("--rotor", required=True, help="rotor name in the aircraft file")
    parser.add_argument("--loads", required=True, help="loads disk table (results/.../loads/ROTOR.parquet)")
    parser.add_argument("--summary", help="loads summary (default: <loads stem>_summary.parquet)")
    parser.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    parser.add_argument("--out", required=True, help="BVI disk table Parquet (results/.../bvi/ROTOR.parquet)")
    parser.add_argument("--figure", help="PNG of the induced-velocity and loading disk maps")
    parser.add_argument("--quasi-steady", action="store_true", help="no Sears response (thesis lifting line)")
    model_arguments(parser)
    args = parser.parse_args(argv)
    summary = args.summary or str(Path(args.loads).with_name(f"{Path(args.loads).stem}_summary.parquet"))
    try:
        aircraft = load_aircraft(args.aircraft)
        rotor = aircraft_rotor(aircraft, args.rotor, args.aircraft)
        result = run(rotor, args.loads, summary, args.trim, model_from_args(args), args.out,
                     bvi_model=bvi.BVIModel(unsteady=not args.quasi_steady), figure=args.figure,
                     title=f"{aircraft['name']} {args.rotor}", metadata={"aircraft": aircraft["name"]})
    except (ConfigError, ArtifactError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    print(f"BVI loads of '{args.rotor}': peak |dU_P| = {abs(result.d_up_mps).max():.3g} m/s -> {args.out}")
    return 0
