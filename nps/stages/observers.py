"""Stage ``observers``: one configured observer set of an aircraft in one segment (nps.observers).

inputs: ``trim`` (hub positions in G at t = 0, aircraft velocity). outputs: ``observers``, the
observer table of docs/conventions.md: ``observer``, ``x_m``, ``y_m``, ``z_m`` (G, t = 0),
``vx_mps``, ``vy_mps``, ``vz_mps``, ``azimuth_deg``, ``elevation_deg`` (map convention, seen from the
set's centre) plus the set's own descriptive columns. params: ``spec`` (``observer_sets.<name>``),
``rotor_roles`` (rotor name → role: the centre is the mean hub of the lift rotors),
``reference_radius_m`` (radii in ``radius_R`` are multiples of it: the first rotor's radius),
``aircraft``, ``segment``, ``obsset``.
"""

from __future__ import annotations

from nps.io import read_table, write_table
from nps.observers import lift_rotors, observer_centre, observer_set, with_directions
from nps.trim import TRIM_COLUMNS


def run(inputs: dict, outputs: dict, params: dict) -> str:
    spec, roles, radius = params["spec"], params["rotor_roles"], float(params["reference_radius_m"])
    centre_rotors = lift_rotors(roles)
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS)
    centre = observer_centre(trim, centre_rotors, str(inputs["trim"]))
    velocity = trim[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)[0]
    table = with_directions(observer_set(spec, centre, radius, velocity), centre)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "centre_m": centre.tolist(), "centre_rotors": list(centre_rotors), "reference_radius_m": radius,
            "spec": dict(spec), "inputs": [str(inputs["trim"])]}
    write_table(table, outputs["observers"], stage="observers", metadata=meta)
    return f"{len(table)} observers, centre {centre.tolist()}: mean hub of the lift rotors {centre_rotors}"
