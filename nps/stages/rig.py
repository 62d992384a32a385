"""Stage ``rig``: set-up of one rig (nps.rig.case), the step that stands for the aircraft trim and the
observer set of the study.

inputs: ``config`` (the rig's YAML, ``config/rigs/NAME.yaml``). outputs: ``trim`` (trim artifact, one
row: the rotor solved under its control mode at the rig's condition) and ``observers`` (the microphones
in G, moving with the hub, with their test-frame positions ``x_T_m``, ``y_T_m``, ``z_T_m`` and
``group``). params: none (the file names the rig).
"""

from __future__ import annotations

from nps.rotor.bet import DiskGrid
from nps.app.config import load_rig
from nps.app.io import write_table
from nps.rig.case import microphone_table, rig_trim


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rig = load_rig(inputs["config"])
    resolution, condition = rig["resolution"], rig["condition"]
    trim = rig_trim(rig["rotor_config"], condition, DiskGrid(int(resolution["n_psi"]), int(resolution["n_r"])))
    mics = microphone_table(rig["microphones_T"], rig["microphone_groups"], condition["tunnel_speed_mps"])
    meta = {"rig": rig["name"], "condition": dict(condition), "inputs": [str(inputs["config"])]}
    write_table(trim, outputs["trim"], stage="rig", metadata=meta)
    write_table(mics, outputs["observers"], stage="rig", metadata=meta)
    row = trim.iloc[0]
    return (f"rig {rig['name']}: rotor {row['rotor']}, control {rig['rotor_config']['control']}, "
            f"omega {row['omega_rad_s']:.6g} rad/s, thrust {row['thrust_N']:.6g} N, torque {row['torque_Nm']:.6g} N m, "
            f"power {row['power_W']:.6g} W, {len(mics)} microphones")
