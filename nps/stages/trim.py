"""Stage ``trim``: aircraft trim of one aircraft in one mission segment (nps.rotor.trim).

inputs: none. outputs: ``trim`` (trim.parquet, one row per rotor, :data:`nps.rotor.trim.TRIM_COLUMNS`).
params: ``aircraft_config`` (validated aircraft configuration), ``speeds`` (the mission segment's entry for
this aircraft: forward_speed_mps, climb_speed_mps, optional rotor_omega_scale; a flight-path state's entry,
:func:`nps.mission.path_states.state_speeds`, adds acceleration_mps2), ``atmosphere``
(altitude_m, isa_delta_K, relative_humidity_pct), ``segment`` (segment id), ``n_psi``, ``n_r``
(disk resolution of the blade-element loads that solve the speeds of ``rpm``-controlled rotors,
:func:`nps.rotor.control.trim_rotor_speeds`); optional ``allow_outside_validity`` (campaign switch,
default false).

Validity (nps.app.validity): hover tip Mach and Lock number before the trim, advance ratio, advancing
tip Mach, blade loading, mean lift and vortex-ring state after it.
"""

from __future__ import annotations

import pandas as pd

from nps.app import validity
from nps.core.atmosphere import AtmosphereState, isa
from nps.rotor.bet import DiskGrid
from nps.rotor.control import trim_rotor_speeds
from nps.app.io import write_table
from nps.rotor.trim import FlightCondition


def trimmed(aircraft: dict, speeds: dict, atmosphere: AtmosphereState, params: dict, where: str) -> tuple[pd.DataFrame, list]:
    """The trim table of ``aircraft`` flying ``speeds`` (a segment's or a path state's entry; no acceleration:
    steady) and its validity findings; refuses (ValidityError naming ``where``) before the trim when the rotors
    lie outside the envelope and ``params`` do not allow it."""
    before = validity.aircraft_findings(aircraft, atmosphere.speed_of_sound_mps, speeds.get("rotor_omega_scale"))
    validity.recorded(before, params, where)  # refuses before the trim unless allowed
    acceleration = tuple(speeds["acceleration_mps2"]) if "acceleration_mps2" in speeds else (0.0, 0.0, 0.0)
    flight = FlightCondition(speeds["forward_speed_mps"], speeds["climb_speed_mps"], atmosphere, acceleration)
    grid = DiskGrid(int(params["n_psi"]), int(params["n_r"]))
    table = trim_rotor_speeds(aircraft, flight, speeds.get("rotor_omega_scale"), grid)
    return table, before + validity.trim_findings(aircraft, table)


def run(inputs: dict, outputs: dict, params: dict) -> str:
    aircraft, speeds, atm = params["aircraft_config"], params["speeds"], params["atmosphere"]
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
    where = str(outputs["trim"])
    table, findings = trimmed(aircraft, speeds, atmosphere, params, where)
    warnings = validity.recorded(findings, params, where)
    write_table(table, outputs["trim"], stage="trim",
                metadata={"aircraft": aircraft["name"], "segment": params["segment"], "speeds": dict(speeds), **warnings})
    return table.to_string() + validity.report(warnings)
