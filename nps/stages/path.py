"""Stage ``path``: a flight path's time history and the quasi-static trim states that cover it
(nps.mission.paths, nps.mission.path_states; docs/reference/paths.md).

inputs: none. outputs: ``history`` (path_history.parquet, one row per time step, :data:`HISTORY_COLUMNS`),
``states`` (path_states.parquet, one row per state × rotor: :data:`STATE_COLUMNS` and the trim table's columns,
:data:`nps.rotor.trim.TRIM_COLUMNS`). params: ``aircraft_config`` (validated aircraft), ``path_config`` (validated
path, nps.app.config.load_path), ``paths`` (dt_s, state_tolerances), ``atmosphere`` (altitude_m, isa_delta_K,
relative_humidity_pct: the states are trimmed in the campaign atmosphere, as mission segments are), ``n_psi``,
``n_r`` (loads that solve rpm-controlled rotor speeds), optional ``allow_outside_validity``.

Each state is a mission segment's speeds entry plus its acceleration (:func:`nps.mission.path_states.state_speeds`),
trimmed by the trim stage's own function (:func:`nps.stages.trim.trimmed`): the trim stage given that entry writes
the state's rows, so the noise chain can run per (aircraft, state) as it runs per (aircraft, segment).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from nps.app import validity
from nps.app.io import write_table
from nps.core.atmosphere import isa
from nps.mission.path_states import (COORDINATES, StateTolerances, choose_states, state_coordinates, state_flight, state_key,
                                     state_speeds)
from nps.mission.paths import flight_path_history, path_spec
from nps.stages.trim import trimmed

HISTORY_COLUMNS = (
    "time_s", "leg", "x_m", "y_m", "z_m", "vel_x_mps", "vel_y_mps", "vel_z_mps", "acc_x_mps2", "acc_y_mps2", "acc_z_mps2",
    "speed_mps", "longitudinal_acceleration_mps2", "heading_rad", "flight_path_rad", "bank_rad", "load_factor",
    "effective_flight_path_rad", "rotor_speed_fraction", *COORDINATES, "state", "neighbour", "neighbour_weight",
)
STATE_COLUMNS = ("state", "state_index", *COORDINATES, "load_factor", "bank_rad", "forward_speed_mps", "climb_speed_mps",
                 "state_acc_x_mps2", "state_acc_y_mps2", "state_acc_z_mps2")


def history_table(history, coordinates: np.ndarray, states, keys: list[str]) -> pd.DataFrame:
    """The time history with its state coordinates and bracketing states (keys, neighbour weight)."""
    table = {"time_s": history.time_s, "leg": history.leg}
    for axis, column in enumerate("xyz"):
        table[f"{column}_m"] = history.position_m[:, axis]
    for axis, column in enumerate("xyz"):
        table[f"vel_{column}_mps"] = history.velocity_mps[:, axis]
    for axis, column in enumerate("xyz"):
        table[f"acc_{column}_mps2"] = history.acceleration_mps2[:, axis]
    for name in ("speed_mps", "longitudinal_acceleration_mps2", "heading_rad", "flight_path_rad", "bank_rad", "load_factor"):
        table[name] = getattr(history, name)
    table["effective_flight_path_rad"] = np.radians(coordinates[:, 1])
    table["rotor_speed_fraction"] = history.rotor_speed_fraction
    table.update({name: coordinates[:, i] for i, name in enumerate(COORDINATES)})
    table.update(state=np.array(keys)[states.state], neighbour=np.array(keys)[states.neighbour], neighbour_weight=states.weight)
    return pd.DataFrame(table)


def run(inputs: dict, outputs: dict, params: dict) -> str:
    aircraft, settings, atm = params["aircraft_config"], params["paths"], params["atmosphere"]
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
    reference = aircraft["rotors"][0]
    tip_speed = reference["omega_rad_s"] * reference["radius_m"]
    legs, history = flight_path_history(path_spec(params["path_config"]), float(settings["dt_s"]))
    coordinates = state_coordinates(history, tip_speed)
    states = choose_states(coordinates, StateTolerances(**settings["state_tolerances"]))
    where, keys, tables, findings = str(outputs["states"]), [], [], []
    for index, values in enumerate(states.values):
        flight, fraction = state_flight(values, tip_speed, atmosphere)
        keys.append(state_key(flight, fraction))
        if keys[-1] in keys[:-1]:  # the same trim input (at μ = 0 neither γ_e nor a_x enters): one state
            continue
        trim, found = trimmed(aircraft, state_speeds(flight, fraction, [r["name"] for r in aircraft["rotors"]]), atmosphere,
                              params, where)
        findings += found
        n_v = np.cos(np.radians(values[1])) + values[2]
        fields = {"state": keys[-1], "state_index": np.int32(index), **dict(zip(COORDINATES, values)),
                  "load_factor": float(np.hypot(n_v, values[3])), "bank_rad": float(np.arctan2(values[3], n_v)),
                  "forward_speed_mps": flight.forward_speed_mps, "climb_speed_mps": flight.climb_speed_mps,
                  **{f"state_acc_{c}_mps2": a for c, a in zip("xyz", flight.acceleration_mps2)}}
        tables.append(trim.assign(**fields)[[*STATE_COLUMNS, *trim.columns]])
    warnings = validity.recorded(findings, params, where)
    meta = {"aircraft": aircraft["name"], "path": params["path_config"]["name"], "paths": dict(settings), **warnings}
    write_table(history_table(history, coordinates, states, keys), outputs["history"], stage="path", metadata=meta)
    write_table(pd.concat(tables, ignore_index=True), outputs["states"], stage="path", metadata=meta)
    return (f"path '{params['path_config']['name']}' ({aircraft['name']}): {len(legs)} legs, "
            f"{history.time_s[-1]:.1f} s, {len(history.time_s)} samples, {len(tables)} trim states"
            + validity.report(warnings))
