"""``python -m nps wake``: Beddoes tip-vortex wake of one rotor from its trimmed loads.

Reads the loads disk table, its summary and the aircraft trim; writes the wake-geometry
artifact (one row per vortex node per snapshot, ``nps.wake.WAKE_COLUMNS``) for snapshots over
one blade passage (the wake is periodic in 2π/B), optionally the legacy-VTK series of the
same snapshots (ParaView: open ``<rotor>.vtk.series``) and the top/side-view figure.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from nps import bvi, vtk, wake
from nps.io import ArtifactError, read_table, write_table
from nps.rotor import RotorMotion


def snapshot_azimuths(n_blades: int, step_deg: float) -> np.ndarray:
    """Blade-0 azimuths (rad) covering one blade passage [0, 2π/B) every ``step_deg``."""
    if not step_deg > 0.0:
        raise ValueError(f"snapshot step: expected > 0 deg, got {step_deg}")
    return np.radians(np.arange(0.0, 360.0 / n_blades - 1e-9, step_deg))


def run(loads_path, summary_path, trim_path, rotor: str, model: wake.WakeModel, out, *, step_deg: float = 5.0,
        vtk_dir=None, figure=None, title: str = "", metadata: dict | None = None) -> dict:
    """Compute and write the wake of ``rotor``; returns the state and the table."""
    disk = read_table(loads_path, required=bvi.DISK_COLUMNS)
    summary = read_table(summary_path, required=("quantity", "value", "unit"))
    trim = read_table(trim_path, required=bvi.TRIM_COLUMNS)
    row = bvi.select_trim_row(trim, rotor, str(trim_path))
    state = bvi.wake_state(disk, row, bvi.summary_value(summary, "ct", str(summary_path)))
    motion = RotorMotion.from_trim_row(row)
    psi = snapshot_azimuths(state.n_blades, step_deg)
    table = wake.wake_table(state, model, psi, motion)
    meta = {**(metadata or {}), "rotor": rotor, "wake_model": model.__dict__, "step_deg": step_deg,
            "inputs": [str(loads_path), str(summary_path), str(trim_path)]}
    write_table(table, out, stage="wake", metadata=meta)
    root = float(disk["r_m"].min() - 0.5 * disk["dr_m"].iloc[0])
    if vtk_dir is not None:
        frames = []
        for step, psi_b in enumerate(psi):
            blades_h = wake.blade_lines_hub(state, psi_b, root, n_points=8)
            blades_g = wake.hub_to_ground(blades_h, psi_b / state.omega_rad_s, motion.hub_position_m,
                                          motion.velocity_mps, motion.r_gh)
            frames.append((psi_b / state.omega_rad_s,
                           vtk.wake_step_polydata(table[table["step"] == step], blades_g, f"NPS wake {rotor} step {step}")))
        vtk.write_series(vtk_dir, rotor, frames)
    if figure is not None:
        from nps.plots.wake import wake_figure_from_tables

        Path(figure).parent.mkdir(parents=True, exist_ok=True)
        wake_figure_from_tables(table, disk, figure, radius_m=state.radius_m,
                                title=f"{title or rotor}: tip vortices, blade 0 at ψ = 0")
    return {"state": state, "table": table}


def model_arguments(parser: argparse.ArgumentParser) -> None:
    """Wake-model options shared by ``wake`` and ``bvi``."""
    d = wake.WakeModel()
    parser.add_argument("--A", type=float, default=d.a_skew, help="Beddoes skew coefficient A")
    parser.add_argument("--B", type=float, default=d.b_lateral, help="Beddoes lateral coefficient B")
    parser.add_argument("--C", type=float, default=d.c_mean, help="Beddoes mean-inflow coefficient C")
    parser.add_argument("--D", type=float, default=d.d_contraction, help="Landgrebe contraction D")
    parser.add_argument("--revolutions", type=float, default=d.revolutions, help="wake age kept (revolutions)")
    parser.add_argument("--steps-per-rev", type=int, default=d.steps_per_rev, help="vortex segments per revolution")
    parser.add_argument("--core-radius-chords", type=float, default=d.core_radius_chords, help="r_c / c")
    parser.add_argument("--core-growth", action="store_true", help="Squire core growth with wake age")


def model_from_args(args) -> wake.WakeModel:
    return wake.WakeModel(a_skew=args.A, b_lateral=args.B, c_mean=args.C, d_contraction=args.D,
                          revolutions=args.revolutions, steps_per_rev=args.steps_per_rev,
                          core_radius_chords=args.core_radius_chords, core_growth=args.core_growth)


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps wake", description=__doc__)
    parser.add_argument("--loads", required=True, help="loads disk table (results/.../loads/ROTOR.parquet)")
    parser.add_argument("--summary", help="loads summary (default: <loads stem>_summary.parquet)")
    parser.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    parser.add_argument("--rotor", required=True, help="rotor name")
    parser.add_argument("--out", required=True, help="wake geometry Parquet (results/.../wake/ROTOR.parquet)")
    parser.add_argument("--step-deg", type=float, default=5.0, help="snapshot spacing over one blade passage")
    parser.add_argument("--vtk-dir", help="write a legacy-VTK series here")
    parser.add_argument("--figure", help="PNG of the top and side views")
    model_arguments(parser)
    args = parser.parse_args(argv)
    summary = args.summary or str(Path(args.loads).with_name(f"{Path(args.loads).stem}_summary.parquet"))
    try:
        done = run(args.loads, summary, args.trim, args.rotor, model_from_args(args), args.out,
                   step_deg=args.step_deg, vtk_dir=args.vtk_dir, figure=args.figure)
    except (ArtifactError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    table = done["table"]
    print(f"wake of '{args.rotor}': {table['step'].nunique()} snapshots, {len(table)} nodes -> {args.out}")
    return 0
