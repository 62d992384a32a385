"""Stage ``wake``: tip-vortex wake and BVI loads of every rotor of one aircraft in one segment.

``wake.model: beddoes`` (default): per rotor, the Beddoes prescribed wake from its trimmed loads
(nps.wake.prescribed), and the BVI loads, i.e. the wake's induced velocity added to the trimmed loads without
re-trim (nps.wake.bvi). ``wake.model: free``: the free-vortex wakes of all rotors relaxed together
(nps.wake.free) and each rotor's loads with every rotor's wake, re-trimmed where the other rotors'
wakes change its mean inflow (nps.wake.interaction; options in the optional ``wake.free`` block), plus
the per-aircraft interaction summary ``interaction.parquet`` in the wake directory. Either way a
legacy-VTK series of each rotor's wake for ParaView.

inputs: ``trim`` (trim.parquet), ``loads`` (directory of the loads stage). outputs: ``wake``
(directory: ``{rotor}.parquet`` wake geometry, :data:`nps.wake.prescribed.WAKE_COLUMNS`, one row per vortex
node per snapshot over one blade passage, ``{rotor}_vtk/``, with the free wake ``interaction.parquet``), ``bvi`` (directory:
``{rotor}.parquet``, BVI disk table with the loads' columns; over a common period (``wake.free.common_period``) m
revolutions of blade 0, ψ_i = 2πi/N for i < mN, with ``revolutions`` and ``blade_shift_steps`` in its metadata,
:meth:`nps.wake.free.FreeWakeSolution.period_record`). params: ``rotors`` (rotor name →
validated rotor configuration), ``wake`` (the config ``wake`` section, defaults filled: model, A, B, C, D,
core_radius_chords, core_growth, vortex_structure, step_deg (snapshot spacing), unsteady (Sears response),
free), ``revolutions`` (wake age kept), ``steps_per_rev`` (vortex segments per revolution),
``aircraft``, ``segment``; optional ``allow_outside_validity`` (campaign switch, default false).

Before computing: provenance of the trim and loads artifacts (aircraft, segment, rotor), memory
(nps.app.resources) and, per rotor, the wake length (nps.app.validity.wake_findings), the loads summary's C_T and
the wake's flow state from the disk table: every rotor before the first rotor's tables are written.
"""

from __future__ import annotations

from pathlib import Path

from nps.wake import bvi

from nps.wake import free as freewake

from nps.wake import interaction

from nps.app import validity

from nps.app import vtk

from nps.wake import prescribed as wake
from nps.app.io import check_provenance, read_table, rotor_path, write_table
from nps.app.resources import check_memory, estimate_bytes
from nps.rig import RIG_AIRCRAFT
from nps.rotor.geometry import RotorGeometry, RotorMotion
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row

SUMMARY_COLUMNS = ("quantity", "value", "unit")


def _vtk_series(directory: Path, rotor: str, state: wake.WakeState, table, psi, motion: RotorMotion, root_m: float) -> None:
    """Legacy-VTK series of the wake snapshots with the blade lines (ParaView: ``<rotor>.vtk.series``)."""
    frames = []
    for step, psi_b in enumerate(psi):
        blades_h = wake.blade_lines_hub(state, psi_b, root_m, n_points=8)
        blades_g = wake.hub_to_ground(blades_h, psi_b / state.omega_rad_s, motion.hub_position_m, motion.velocity_mps, motion.r_gh)
        frames.append((psi_b / state.omega_rad_s,
                       vtk.wake_step_polydata(table[table["step"] == step], blades_g, f"NPS wake {rotor} step {step}")))
    vtk.write_series(directory, rotor, frames)


def run(inputs: dict, outputs: dict, params: dict) -> str:
    model = wake.WakeModel.from_config(params["wake"], params["revolutions"], int(params["steps_per_rev"]))
    bvi_model = bvi.BVIModel(unsteady=bool(params["wake"]["unsteady"]))
    step_deg = float(params["wake"]["step_deg"])
    same = {"aircraft": params["aircraft"], "segment": params["segment"]}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    wake_dir, bvi_dir = Path(outputs["wake"]), Path(outputs["bvi"])
    names = list(params["rotors"])
    paths = {name: (rotor_path(inputs["loads"], name), rotor_path(inputs["loads"], name, "_summary")) for name in names}
    warnings = {}
    for name in names:  # every input and the wake length checked before the first rotor is computed
        for path in paths[name]:
            check_provenance(path, {"stage": "loads", "rotor": name, **same})
        warnings[name] = validity.recorded(validity.wake_findings(model, trim_row(trim, name, str(inputs["trim"]))),
                                           params, str(rotor_path(wake_dir, name)))
    disks = {name: read_table(paths[name][0], required=bvi.DISK_COLUMNS, nonempty=True) for name in names}
    summaries = {name: read_table(paths[name][1], required=SUMMARY_COLUMNS) for name in names}
    for name in names:  # every rotor's disk grid (named by its file) and C_T before the first rotor is computed
        bvi.disk_grid(disks[name], str(paths[name][0]))
    cts = {name: bvi.summary_value(summaries[name], "ct", str(paths[name][1])) for name in names}
    states = {name: bvi.wake_state(disks[name], trim_row(trim, name, str(inputs["trim"])), cts[name]) for name in names}
    check_memory(estimate_bytes("wake", {"n_psi": model.steps_per_rev, "n_r": disks[names[0]]["r_m"].nunique(),
                                          "wake_revolutions": model.revolutions}, n_rotors=len(names)),
                 f"{wake_dir}: wake of {model.revolutions:g} revolutions x {model.steps_per_rev} steps")
    free = params["wake"]["model"] == "free"
    if free:
        # a rig's rotors keep their own control in the re-trim (nps.wake.interaction); an aircraft's: None
        controls = ({n: r["control"] for n, r in params["rotors"].items()} if params["aircraft"] == RIG_AIRCRAFT
                    else None)
        coupled = interaction.aircraft_bvi_loads(trim, params["rotors"], disks, summaries, model,
                                                 freewake.FreeWakeModel.from_config(params["wake"]["free"]), bvi_model,
                                                 controls=controls)
    report = []
    for name, rotor in params["rotors"].items():
        disk, inputs_of = disks[name], [str(paths[name][0]), str(paths[name][1]), str(inputs["trim"])]
        ct, state = cts[name], states[name]
        row = trim_row(trim, name, str(inputs["trim"]))
        meta = {"aircraft": params["aircraft"], "segment": params["segment"], "rotor": name, "wake_model": model.record(),
                **warnings[name]}
        # wake geometry snapshots over one blade passage (the wake is periodic in 2π/B)
        motion = RotorMotion.from_trim_row(row)
        psi = wake.snapshot_azimuths(state.n_blades, step_deg)
        snapshot = (lambda p, n=name: freewake.wake_snapshot(coupled.solution, n, p)) if free else None
        table = wake.wake_table(state, model, psi, motion, snapshot=snapshot)
        write_table(table, rotor_path(wake_dir, name), stage="wake", metadata={**meta, "step_deg": step_deg, "inputs": inputs_of})
        _vtk_series(wake_dir / f"{name}_vtk", name, state, table, psi, motion, float(disk["r_m"].min() - 0.5 * disk["dr_m"].iloc[0]))
        # BVI loads: the wake's induced velocity on the blades
        result = coupled.results[name] if free else bvi.bvi_loads(disk, row, RotorGeometry.from_config(rotor), ct, model, bvi_model)
        period = (coupled.solution.period_record(coupled.solution.index(name), disk["psi_rad"].nunique())
                  if free else {})
        write_table(result.disk, rotor_path(bvi_dir, name), stage="bvi",
                    metadata={**meta, **period, "bvi_model": bvi_model.__dict__, "inputs": inputs_of})
        report.append(f"rotor {name}: {len(table)} wake nodes; peak |dU_P| = {abs(result.d_up_mps).max():.4g} m/s, "
                      f"peak |dU_T| = {abs(result.d_ut_mps).max():.4g} m/s" + validity.report(warnings[name]))
    if free:
        timing = coupled.solution.timing
        periods = [p.describe() for p in timing.periods] if timing is not None else []
        write_table(coupled.summary, wake_dir / "interaction.parquet", stage="wake",
                    metadata={"aircraft": params["aircraft"], "segment": params["segment"], "free_wake": params["wake"]["free"],
                              **({"common_periods": periods} if periods else {})})
        report += periods + [coupled.summary.to_string(index=False)]
    return "\n".join(report)
