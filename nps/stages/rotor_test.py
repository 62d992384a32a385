"""Stage ``rotor_test``: set-up of one isolated-rotor test case (nps.rig.case).

inputs: ``config`` (the test's YAML, ``config/tests/NAME.yaml``). outputs: ``trim`` (trim artifact,
one row: the rotor solved under its control mode at the test condition) and ``observers`` (the
microphones in G, moving with the hub, with their test-frame positions ``x_T_m``, ``y_T_m``,
``z_T_m`` and ``group``). params: none (the wildcard ``test`` names the case).
"""

from __future__ import annotations

from nps.rotor.bet import DiskGrid
from nps.app.config import load_rotor_test
from nps.app.io import write_table
from nps.rig.case import microphone_table, rotor_test_trim


def run(inputs: dict, outputs: dict, params: dict) -> str:
    test = load_rotor_test(inputs["config"])
    resolution, condition = test["resolution"], test["condition"]
    trim = rotor_test_trim(test["rotor_config"], condition, DiskGrid(int(resolution["n_psi"]), int(resolution["n_r"])))
    mics = microphone_table(test["microphones_T"], test["microphone_groups"], condition["tunnel_speed_mps"])
    meta = {"test": test["name"], "condition": dict(condition), "inputs": [str(inputs["config"])]}
    write_table(trim, outputs["trim"], stage="rotor_test", metadata=meta)
    write_table(mics, outputs["observers"], stage="rotor_test", metadata=meta)
    row = trim.iloc[0]
    return (f"test {test['name']}: rotor {row['rotor']}, control {test['rotor_config'].get('control', 'collective')}, "
            f"omega {row['omega_rad_s']:.6g} rad/s, thrust {row['thrust_N']:.6g} N, torque {row['torque_Nm']:.6g} N m, "
            f"power {row['power_W']:.6g} W, {len(mics)} microphones")
