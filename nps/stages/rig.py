"""Stage ``rig``: set-up of one rig (nps.rig.case), the step that stands for the aircraft trim and the
observer set of the study.

inputs: ``config`` (the rig's YAML, ``config/rigs/NAME.yaml``). outputs: ``trim`` (trim artifact, one
row: the rotor solved under its control mode at the rig's condition) and ``observers`` (the microphones
in G, moving with the hub, with their test-frame positions ``x_T_m``, ``y_T_m``, ``z_T_m`` and
``group``). params: optional ``allow_outside_validity`` (default: the rig's own).

Before writing anything (one gate for the workflow, ``python -m nps rig`` and ``python -m nps rotor``;
nps.app.validity): the atmosphere, hover tip Mach and Lock number, and for a rotor speed that is not
trimmed the advance ratio and advancing tip Mach, before the rotor solve; after it the trim checks,
flap angle and controls, and every microphone against the blade path and hub; the memory of the
rig's loads and acoustics jobs (nps.app.resources).
"""

from __future__ import annotations

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
    resolution, condition, rotor = rig["resolution"], rig["condition"], rig["rotor_config"]
    allowed = params["allow_outside_validity"] if "allow_outside_validity" in params else rig["allow_outside_validity"]
    switch = {"allow_outside_validity": bool(allowed)}
    where = f"{inputs['config']}: rig '{rig['name']}'"
    before = validity.rig_condition_findings(rotor, rig_operating_point(rotor, condition), rotor["control"])
    validity.recorded(before, switch, where)  # refuses before the rotor solve unless allowed
    check_rig_memory(rig, str(inputs["config"]))
    try:
        mics = microphone_table(rig["microphones_T"], rig["microphone_groups"], condition["tunnel_speed_mps"])
    except ObserverError as exc:
        raise ObserverError(f"{inputs['config']}: microphones: {exc}") from None
    solution = rig_solution(rotor, condition, DiskGrid(int(resolution["n_psi"]), int(resolution["n_r"])))
    trim = rig_trim(rotor, condition, None, solution)
    found = validity.rig_findings(rotor, trim, solution.result.summary(), mics)
    warnings = validity.recorded(before + found, switch, where)
    meta = {"rig": rig["name"], "condition": dict(condition), "inputs": [str(inputs["config"])], **warnings}
    write_table(trim, outputs["trim"], stage="rig", metadata=meta)
    write_table(mics, outputs["observers"], stage="rig", metadata=meta)
    row = trim.iloc[0]
    return (f"rig {rig['name']}: rotor {row['rotor']}, control {rig['rotor_config']['control']}, "
            f"omega {row['omega_rad_s']:.6g} rad/s, thrust {row['thrust_N']:.6g} N, torque {row['torque_Nm']:.6g} N m, "
            f"power {row['power_W']:.6g} W, {len(mics)} microphones" + validity.report(warnings))
