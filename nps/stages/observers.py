"""Stage ``observers``: one configured observer set of an aircraft in one segment (nps.noise.observers).

inputs: ``trim`` (hub positions in G at t = 0, aircraft velocity). outputs: ``observers``, the
observer table of docs/reference/conventions.md: ``observer``, ``x_m``, ``y_m``, ``z_m`` (G, t = 0),
``vx_mps``, ``vy_mps``, ``vz_mps``, ``azimuth_deg``, ``elevation_deg`` (map convention, seen from the
set's centre) plus the set's own descriptive columns. params: ``spec`` (``observer_sets.<name>``),
``rotor_roles`` (rotor name → role: the centre is the mean hub of the lift rotors),
``reference_radius_m`` (radii in ``radius_R`` are multiples of it: the first rotor's radius),
``rotors`` (rotor name → validated rotor configuration, in aircraft order: blade paths of the
near-field check), ``aircraft``, ``segment``, ``obsset``; optional ``allow_outside_validity``.

Validity (nps.app.validity.observer_findings): every observer at least 5 chords from every blade path
and one radius from every hub over one revolution of the first rotor.
"""

from __future__ import annotations

import math

from nps.app import validity
from nps.app.io import check_provenance, read_table, write_table
from nps.noise.observers import lift_rotors, observer_centre, observer_set, with_directions
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row


def run(inputs: dict, outputs: dict, params: dict) -> str:
    spec, roles, radius = params["spec"], params["rotor_roles"], float(params["reference_radius_m"])
    centre_rotors = lift_rotors(roles)
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, "aircraft": params["aircraft"], "segment": params["segment"]})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    centre = observer_centre(trim, centre_rotors, str(inputs["trim"]))
    velocity = trim[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)[0]
    table = with_directions(observer_set(spec, centre, radius, velocity), centre)
    rotors = list(params["rotors"].values())
    revolution_s = 2.0 * math.pi / float(trim_row(trim, rotors[0]["name"], str(inputs["trim"]))["omega_rad_s"])
    warnings = validity.recorded(validity.observer_findings(table, {"rotors": rotors}, trim, revolution_s), params,
                                 str(outputs["observers"]))
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "centre_m": centre.tolist(), "centre_rotors": list(centre_rotors), "reference_radius_m": radius,
            "spec": dict(spec), "inputs": [str(inputs["trim"])], **warnings}
    write_table(table, outputs["observers"], stage="observers", metadata=meta)
    return (f"{len(table)} observers, centre {centre.tolist()}: mean hub of the lift rotors {centre_rotors}"
            + validity.report(warnings))
