"""``python -m nps trim``: aircraft trim for one aircraft and one mission segment."""

from __future__ import annotations

import argparse
import sys

from nps.atmosphere import isa
from nps.config import ConfigError, load_aircraft, load_mission
from nps.io import write_table
from nps.trim import AircraftTrimError, FlightCondition, trim_aircraft


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps trim", description=__doc__)
    parser.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    parser.add_argument("--mission", required=True, help="mission YAML (config/missions/NAME.yaml)")
    parser.add_argument("--segment", required=True, help="segment id, e.g. seg3")
    parser.add_argument("--altitude-m", type=float, default=0.0)
    parser.add_argument("--isa-delta-k", type=float, default=0.0)
    parser.add_argument("--out", required=True, help="output Parquet (one row per rotor)")
    args = parser.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        mission = load_mission(args.mission)
        segment = next((s for s in mission["segments"] if s["id"] == args.segment), None)
        if segment is None:
            raise ConfigError(f"{args.mission}: segments: no segment '{args.segment}'")
        if aircraft["name"] not in segment["aircraft"]:
            raise ConfigError(f"{args.mission}: segments.{args.segment}.aircraft: no speeds for '{aircraft['name']}'")
        speeds = segment["aircraft"][aircraft["name"]]
        flight = FlightCondition(speeds["forward_speed_mps"], speeds["climb_speed_mps"], isa(args.altitude_m, args.isa_delta_k))
        table = trim_aircraft(aircraft, flight, speeds.get("rotor_omega_scale"))
    except (ConfigError, AircraftTrimError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    write_table(table, args.out, stage="trim", metadata={"aircraft": aircraft["name"], "segment": args.segment})
    print(table[["rotor", "thrust_N", "torque_Nm", "mu_x", "mu_z", "ct", "tip_mach"]].to_string(index=False))
    return 0
