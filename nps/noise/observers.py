"""Observer sets: single points, hemispheres/spheres, points ahead, planar ground grids.

Every set is a table with the columns of the acoustics CLI (``observer``, ``x_m``, ``y_m``,
``z_m``: position in the ground frame G at t = 0; ``vx_mps``, ``vy_mps``, ``vz_mps``: constant
velocity in G) plus descriptive columns (``azimuth_deg``, ``elevation_deg`` for directional
sets; ``grid_x_m``, ``grid_y_m`` for ground grids). Observers either stay in G (velocity 0) or
move with the aircraft (velocity = aircraft velocity V_G): then their position relative to
the aircraft is fixed, as in the thesis' hemisphere.

Directions follow the map convention of docs/reference/conventions.md: azimuth from straight behind
toward the main rotor's advancing side (starboard for the bundled aircraft), 180° ahead,
elevation from the horizontal, negative below; d = (−cos az cos el, −sin az cos el, sin el).
"""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.core.frames import observer_direction


class ObserverError(ValueError):
    """An observer-set specification is invalid."""


KINDS = ("point", "hemisphere", "sphere", "points_ahead", "ground_grid")
# stages whose artifact is an observer table: the campaign observer sets, a rig's microphones (nps.rig.case) and
# the observers of a PSU-WOPWOP case run by NPS
OBSERVER_STAGES = ("observers", "rig", "wopwop_run", "wopwop_read")


def _table(position_m: np.ndarray, velocity_mps, extra: Mapping[str, np.ndarray]) -> pd.DataFrame:
    position_m = np.asarray(position_m, dtype=float).reshape(-1, 3)
    velocity = np.broadcast_to(np.asarray(velocity_mps, dtype=float), position_m.shape)
    data = {"observer": np.arange(len(position_m), dtype=np.int32)}
    for i, axis in enumerate("xyz"):
        data[f"{axis}_m"] = position_m[:, i]
    for i, axis in enumerate("xyz"):
        data[f"v{axis}_mps"] = velocity[:, i].copy()
    data.update({k: np.asarray(v, dtype=float) for k, v in extra.items()})
    return pd.DataFrame(data)


def points(position_m: Sequence[Sequence[float]], velocity_mps=(0.0, 0.0, 0.0)) -> pd.DataFrame:
    """Observers at given G positions (m, at t = 0) with one common constant velocity (m/s)."""
    return _table(np.asarray(position_m, dtype=float), velocity_mps, {})


def directions(centre_m, radius_m: float, azimuth_deg, elevation_deg, velocity_mps=(0.0, 0.0, 0.0)) -> pd.DataFrame:
    """Observers at ``radius_m`` from ``centre_m`` (G, t = 0) in map directions (deg)."""
    if not radius_m > 0:
        raise ObserverError(f"observers: radius must be positive, got {radius_m}")
    az = np.asarray(azimuth_deg, dtype=float)
    el = np.asarray(elevation_deg, dtype=float)
    if np.any(np.abs(el) > 90.0):
        raise ObserverError("observers: elevations must lie in [-90, 90] deg")
    d = observer_direction(np.radians(az), np.radians(el))
    return _table(np.asarray(centre_m, float)[None, :] + radius_m * d, velocity_mps, {"azimuth_deg": az, "elevation_deg": el})


def hemisphere(centre_m, radius_m: float, n_elevation: int, n_azimuth: int, velocity_mps=(0.0, 0.0, 0.0),
               full_sphere: bool = False) -> pd.DataFrame:
    """Lower hemisphere (el from 0 to −90°) or sphere (+90 to −90°), elevation-major order.

    ``n_elevation`` elevations evenly spaced including both ends; ``n_azimuth`` azimuths
    az_j = j·360°/n_azimuth. 19 × 72 gives 5° steps.
    """
    if n_elevation < 2 or n_azimuth < 1:
        raise ObserverError(f"observers: need n_elevation >= 2 and n_azimuth >= 1, got {n_elevation}, {n_azimuth}")
    top = 90.0 if full_sphere else 0.0
    el = np.linspace(top, -90.0, n_elevation)
    az = np.arange(n_azimuth) * 360.0 / n_azimuth
    el_grid, az_grid = np.meshgrid(el, az, indexing="ij")
    return directions(centre_m, radius_m, az_grid.ravel(), el_grid.ravel(), velocity_mps)


def ground_grid(centre_m, height_below_m: float, x_range_m, y_range_m, n_x: int, n_y: int,
                velocity_mps=(0.0, 0.0, 0.0)) -> pd.DataFrame:
    """Horizontal grid ``height_below_m`` below ``centre_m``; x along the track, y to port (G)."""
    if not height_below_m > 0 or n_x < 1 or n_y < 1:
        raise ObserverError("observers: ground grid needs height_below_m > 0, n_x >= 1, n_y >= 1")
    gx = np.linspace(*x_range_m, n_x)
    gy = np.linspace(*y_range_m, n_y)
    xx, yy = np.meshgrid(gx, gy, indexing="ij")
    centre = np.asarray(centre_m, dtype=float)
    pos = np.stack([centre[0] + xx.ravel(), centre[1] + yy.ravel(), np.full(xx.size, centre[2] - height_below_m)], axis=-1)
    return _table(pos, velocity_mps, {"grid_x_m": xx.ravel(), "grid_y_m": yy.ravel()})


def observer_set(spec: Mapping, centre_m, reference_radius_m: float, aircraft_velocity_mps) -> pd.DataFrame:
    """Build a configured observer set (``observer_sets.<name>`` of config/config.yaml).

    ``centre_m``: centre in G at t = 0 of hemispheres and points ahead; a ground grid is centred
    ``height_below_m`` below the CG (the origin of G at t = 0, docs/reference/conventions.md); ``point``
    sets list ``positions_m``, offsets [x, y, z] (m, G axes) from ``centre_m``;
    radii in ``radius_R`` are multiples of ``reference_radius_m``; ``moving`` (default true)
    gives the observers the aircraft velocity.
    """
    kind = spec.get("kind")
    velocity = np.asarray(aircraft_velocity_mps, float) if spec.get("moving", True) else np.zeros(3)
    if kind == "point":
        offsets = np.asarray(spec["positions_m"], dtype=float)
        if offsets.ndim != 2 or offsets.shape[1] != 3 or not np.isfinite(offsets).all():
            raise ObserverError(f"observer set: positions_m: expected a list of [x, y, z] (m), got {spec['positions_m']!r}")
        return points(np.asarray(centre_m, dtype=float)[None, :] + offsets, velocity)
    if kind in ("hemisphere", "sphere"):
        return hemisphere(centre_m, spec["radius_R"] * reference_radius_m, int(spec["n_elevation"]), int(spec["n_azimuth"]),
                          velocity, full_sphere=kind == "sphere")
    if kind == "points_ahead":
        el = np.asarray(spec["elevations_deg"], dtype=float)
        return directions(centre_m, spec["radius_R"] * reference_radius_m, np.full(el.size, 180.0), el, velocity)
    if kind == "ground_grid":
        return ground_grid(np.zeros(3), spec["height_below_m"], spec["x_range_m"], spec["y_range_m"], int(spec["n_x"]),
                           int(spec["n_y"]), velocity)
    raise ObserverError(f"observer set: kind '{kind}', expected one of {KINDS}")


def rotor_roles(aircraft: Mapping) -> dict[str, str]:
    """Rotor name → role (``lift`` when not given) of an aircraft configuration."""
    return {r["name"]: r.get("role", "lift") for r in aircraft["rotors"]}


def lift_rotors(roles: Mapping[str, str]) -> list[str]:
    """Names of the rotors with role ``lift`` (all rotors when none is), in configuration order."""
    return [name for name, role in roles.items() if role == "lift"] or list(roles)


def observer_centre(trim: pd.DataFrame, rotors: Sequence[str], what: str = "trim") -> np.ndarray:
    """Mean hub position (m, G at t = 0) of the named rotors' rows of a trim table.

    The centre of hemispheres and points ahead: with the lift rotors, the main-rotor hub of a
    single-main-rotor helicopter, the point midway between the hubs of a tandem or coaxial and
    the centre of a multirotor's hub circle (the thesis' "aircraft centre").
    """
    missing = [r for r in rotors if r not in set(trim["rotor"])]
    if missing or not rotors:
        raise ObserverError(f"{what}: no row for rotor(s) {missing or list(rotors)}; rotors: {list(trim['rotor'])}")
    hubs = trim.set_index("rotor").loc[list(rotors), ["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)
    return hubs.mean(axis=0)


def with_directions(table: pd.DataFrame, centre_m) -> pd.DataFrame:
    """Add ``azimuth_deg`` and ``elevation_deg`` of each observer seen from ``centre_m`` when absent.

    Inverse of d = (−cos az cos el, −sin az cos el, sin el) (docs/reference/conventions.md); az in [0, 360),
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
