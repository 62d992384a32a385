"""``python -m nps observers``: one configured observer set of an aircraft in one segment.

Reads the aircraft trim artifact (hub positions in G at t = 0, aircraft velocity) and writes the
observer table of docs/conventions.md: ``observer``, ``x_m``, ``y_m``, ``z_m`` (G, t = 0),
``vx_mps``, ``vy_mps``, ``vz_mps``, ``azimuth_deg``, ``elevation_deg`` (map convention, seen from
the set's centre) plus the set's own descriptive columns (e.g. ``grid_x_m`` of a ground grid).

Centre of hemispheres and points ahead: the mean hub position of the aircraft's lift rotors,
i.e. the main-rotor hub of a single-main-rotor helicopter (the antitorque rotor is not a lift
rotor), the point midway between the hubs of a tandem or coaxial and the centre of a
multirotor's hub circle (the thesis' "aircraft centre"). Radii in ``radius_R`` are multiples of
the reference radius, the radius of the aircraft's first rotor.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.config import ConfigError, load_aircraft, read_yaml
from nps.io import ArtifactError, read_table, write_table
from nps.observers import ObserverError, observer_set

TRIM_COLUMNS = ("rotor", "hub_x_m", "hub_y_m", "hub_z_m", "vel_x_mps", "vel_y_mps", "vel_z_mps")


def rotor_roles(aircraft: Mapping) -> dict[str, str]:
    """Rotor name → role (``lift`` when not given) of an aircraft configuration."""
    return {r["name"]: r.get("role", "lift") for r in aircraft["rotors"]}


def lift_rotors(roles: Mapping[str, str]) -> list[str]:
    """Names of the rotors with role ``lift`` (all rotors when none is), in configuration order."""
    return [name for name, role in roles.items() if role == "lift"] or list(roles)


def observer_centre(trim: pd.DataFrame, rotors: Sequence[str], what: str = "trim") -> np.ndarray:
    """Mean hub position (m, G at t = 0) of the named rotors' trim rows."""
    missing = [r for r in rotors if r not in set(trim["rotor"])]
    if missing or not rotors:
        raise ArtifactError(f"{what}: no row for rotor(s) {missing or list(rotors)}; rotors: {list(trim['rotor'])}")
    hubs = trim.set_index("rotor").loc[list(rotors), ["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)
    return hubs.mean(axis=0)


def with_directions(table: pd.DataFrame, centre_m) -> pd.DataFrame:
    """Add ``azimuth_deg`` and ``elevation_deg`` of each observer seen from ``centre_m`` when absent.

    Inverse of d = (−cos az cos el, −sin az cos el, sin el) (docs/conventions.md); az in [0, 360),
    0 for an observer straight above or below.
    """
    if {"azimuth_deg", "elevation_deg"} <= set(table.columns):
        return table
    rel = table[["x_m", "y_m", "z_m"]].to_numpy(float) - np.asarray(centre_m, float)[None, :]
    dist = np.linalg.norm(rel, axis=1)
    if not (dist > 0).all():
        raise ObserverError(f"observers: observer {int(np.argmin(dist))} sits at the set's centre; its direction is undefined")
    out = table.copy()
    out["elevation_deg"] = np.degrees(np.arcsin(np.clip(rel[:, 2] / dist, -1.0, 1.0)))
    out["azimuth_deg"] = np.degrees(np.arctan2(-rel[:, 1], -rel[:, 0])) % 360.0
    return out


def run(spec: Mapping, trim_path: str | Path, roles: Mapping[str, str], reference_radius_m: float,
        out: str | Path, metadata: Mapping) -> pd.DataFrame:
    """Build one observer set (``observer_sets.<name>`` of the campaign config) and write it;
    ``roles``: rotor name → role, the set's centre is the mean hub of the lift rotors."""
    centre_rotors = lift_rotors(roles)
    trim = read_table(trim_path, required=TRIM_COLUMNS)
    centre = observer_centre(trim, centre_rotors, str(trim_path))
    velocity = trim[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)[0]
    table = with_directions(observer_set(spec, centre, float(reference_radius_m), velocity), centre)
    meta = {**metadata, "centre_m": centre.tolist(), "centre_rotors": list(centre_rotors),
            "reference_radius_m": float(reference_radius_m), "spec": dict(spec), "inputs": [str(trim_path)]}
    write_table(table, out, stage="observers", metadata=meta)
    return table


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps observers", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--config", required=True, help="campaign config (config/config.yaml) holding observer_sets")
    parser.add_argument("--set", required=True, help="observer set name in observer_sets")
    parser.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    parser.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    parser.add_argument("--out", required=True, help="observer table Parquet (results/.../observers/SET.parquet)")
    args = parser.parse_args(argv)
    try:
        sets = read_yaml(args.config).get("observer_sets", {})
        if args.set not in sets:
            raise ConfigError(f"{args.config}: observer_sets: no set named '{args.set}'; sets: {list(sets)}")
        aircraft = load_aircraft(args.aircraft)
        table = run(sets[args.set], args.trim, rotor_roles(aircraft), aircraft["rotors"][0]["radius_m"], args.out,
                    {"aircraft": aircraft["name"], "obsset": args.set})
    except (ConfigError, ArtifactError, ObserverError, KeyError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    print(f"{len(table)} observers written to {args.out}")
    return 0
