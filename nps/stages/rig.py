"""Stage ``rig``: set-up of one rig (nps.rig.case), the step that stands for the aircraft trim and the
observer set of the study.

inputs: ``config`` (the rig's YAML, ``config/rigs/NAME.yaml``). outputs: ``trim`` (trim artifact, one
row per rotor: each rotor solved under its own control mode at its own condition, hub and axis in G) and
``observers`` (the microphones in G, moving with the hub, with their test-frame positions ``x_T_m``,
``y_T_m``, ``z_T_m`` and ``group``). params: optional ``allow_outside_validity`` (default: the rig's own).

Before writing anything (one gate for the workflow, ``python -m nps rig`` and ``python -m nps rotor``;
nps.app.validity): the atmosphere, hover tip Mach and Lock number, and for a rotor speed that is not
trimmed the advance ratio and advancing tip Mach, before the rotor solve; after it the trim checks,
flap angle and controls, and every microphone against the blade path and hub — per rotor, a rotors[]
entry's messages naming it (``rotors[1] 'tail'``); the memory of the
rig's loads and acoustics jobs (nps.app.resources).
"""

from __future__ import annotations

import pandas as pd

from nps.app import validity
from nps.app.config import load_rig
from nps.app.io import write_table
from nps.app.resources import check_memory, estimate_bytes
from nps.noise.observers import ObserverError
from nps.rig.case import microphone_table, rig_operating_point, rig_solution, rig_trim
from nps.rotor.bet import DiskGrid


def check_rig_memory(rig: dict, where: str) -> None:
    """Refuse a rig whose loads or acoustics job cannot fit in memory (its resolution, its microphones)."""
    resolution, n_mics = rig["resolution"], len(rig["microphones_T"])
    check_memory(estimate_bytes("loads", resolution), f"{where}: resolution: loads on a {resolution['n_psi']} x "
                 f"{resolution['n_r']} disk (n_psi x n_r)")
    check_memory(estimate_bytes("acoustics", resolution, n_mics),
                 f"{where}: {n_mics} microphones x {resolution['samples_per_rev']} samples per revolution")


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rig = load_rig(inputs["config"])
    resolution, condition = rig["resolution"], rig["condition"]
    rotors, conditions = rig["rotor_configs"], rig["rotor_conditions"]
    allowed = params["allow_outside_validity"] if "allow_outside_validity" in params else rig["allow_outside_validity"]
    switch = {"allow_outside_validity": bool(allowed)}
    where = f"{inputs['config']}: rig '{rig['name']}'"
    # the one-rotor form's messages as before; each rotors[] entry named by its index and name
    places = [where] if "rotors" not in rig else [f"{where}: rotors[{i}] '{r['name']}'" for i, r in enumerate(rotors)]
    before = [validity.rig_condition_findings(r, rig_operating_point(r, c), r["control"]) for r, c in zip(rotors, conditions)]
    for found, place in zip(before, places):
        validity.recorded(found, switch, place)  # refuses before the rotor solves unless allowed
    check_rig_memory(rig, str(inputs["config"]))
    try:
        mics = microphone_table(rig["microphones_T"], rig["microphone_groups"], condition["tunnel_speed_mps"])
    except ObserverError as exc:
        raise ObserverError(f"{inputs['config']}: microphones: {exc}") from None
    grid = DiskGrid(int(resolution["n_psi"]), int(resolution["n_r"]))
    warnings, rows = [], []
    for rotor, rotor_condition, found, place in zip(rotors, conditions, before, places):
        solution = rig_solution(rotor, rotor_condition, grid)
        row = rig_trim(rotor, rotor_condition, None, solution)
        after = validity.rig_findings(rotor, row, solution.result.summary(), mics)
        warnings += validity.recorded(found + after, switch, place).get("validity_warnings", [])
        rows.append(row)
    trim = rows[0] if len(rows) == 1 else pd.concat(rows, ignore_index=True)
    several = {"rotors": [dict(c, rotor=r["name"]) for r, c in zip(rotors, conditions)]} if "rotors" in rig else {}
    meta = {"rig": rig["name"], "condition": dict(condition), **several, "inputs": [str(inputs["config"])],
            **({"validity_warnings": warnings} if warnings else {})}
    write_table(trim, outputs["trim"], stage="rig", metadata=meta)
    write_table(mics, outputs["observers"], stage="rig", metadata=meta)
    lines = [f"rotor {row['rotor']}, control {rotor['control']}, omega {row['omega_rad_s']:.6g} rad/s, thrust "
             f"{row['thrust_N']:.6g} N, torque {row['torque_Nm']:.6g} N m, power {row['power_W']:.6g} W"
             for rotor, (_, row) in zip(rotors, trim.iterrows())]
    return (f"rig {rig['name']}: " + "; ".join(lines) + f", {len(mics)} microphones"
            + validity.report({"validity_warnings": warnings}))
