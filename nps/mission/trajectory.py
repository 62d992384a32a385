"""Flight paths: the mission's flight profile and the noise-certification reference procedures.

Mission frame E (nps.mission.propagation): x along the straight ground track, y to port, z height above
flat ground, origin on the ground below the first point of the path. A path is a sequence of
legs; each leg flies one mission segment's steady state (its hemisphere, horizontal speed V_h
and climb speed V_c) from a start point for a ground distance (m) or a duration (s). The path is
continuous: each leg starts where the previous one ended.

Mission profile (``profile`` of ``config/missions/*.yaml``, optional)::

    profile:
      - {segment: seg1, distance_m: 1500.0, start_altitude_m: 150.0}
      - {segment: seg2, duration_s: 60.0}
      - ...

``start_altitude_m`` is required on the first leg; on a later leg it is optional and, when given,
must equal the previous leg's end altitude within 1 m (a check, not a jump).

Certification reference procedures, 14 CFR Part 36 Appendix H (Stage 3) and ICAO Annex 16
Vol. I Chapter 8 (reference procedures of 8.6; measurement points of 8.3), in the reference
atmosphere (sea level, 25 °C, 70 % relative humidity, no wind):

* take-off: level flight at 20 m above ground at the best-rate-of-climb speed V_y up to 500 m
  before the flight-path reference point, then a climb at V_y with the best rate of climb;
* overflight: level flight 150 m above the reference point at the least of 0.9 V_H, 0.9 V_NE and
  0.45 V_H + 65 km/h (V_NE omitted when not given);
* approach: a stabilised 6.0° descent passing 120 m above the reference point at the greater of
  V_y and the lowest approved approach speed;
* microphones 1.2 m above ground at the reference point on the track and 150 m either side of
  it on the perpendicular line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from nps.core.atmosphere import isa

ALTITUDE_TOLERANCE_M = 1.0
MICROPHONE_HEIGHT_M = 1.2
SIDELINE_OFFSET_M = 150.0
REFERENCE_TEMPERATURE_K = 298.15
REFERENCE_HUMIDITY_PCT = 70.0
PROCEDURES = ("takeoff", "overflight", "approach")
TAKEOFF_HEIGHT_M = 20.0
TAKEOFF_LEVEL_BEFORE_M = 500.0
OVERFLIGHT_HEIGHT_M = 150.0
APPROACH_HEIGHT_M = 120.0
APPROACH_ANGLE_DEG = 6.0
KMH = 1.0 / 3.6


class FlightPathError(ValueError):
    """An invalid flight profile or procedure parameter (names the field and what was expected)."""


@dataclass(frozen=True)
class Leg:
    """One steady leg: ``segment`` id, horizontal and climb speed (m/s), duration (s)."""

    segment: str
    forward_speed_mps: float
    climb_speed_mps: float
    duration_s: float


@dataclass(frozen=True)
class FlightPath:
    """A continuous piecewise-linear path in E: ``legs`` flown in order from ``start_m`` (x, y, z)."""

    start_m: tuple[float, float, float]
    legs: tuple[Leg, ...]

    def __post_init__(self):
        if not self.legs:
            raise FlightPathError("flight path: needs at least one leg")
        z = self.start_m[2]
        for i, leg in enumerate(self.legs):
            if not (leg.duration_s > 0 and math.isfinite(leg.duration_s)):
                raise FlightPathError(f"legs[{i}] ({leg.segment}): expected a positive duration, got {leg.duration_s}")
            if not (leg.forward_speed_mps > 0):
                raise FlightPathError(f"legs[{i}] ({leg.segment}): expected a positive forward speed (hover is not a leg)")
            z += leg.climb_speed_mps * leg.duration_s
            if z < -1e-9:
                raise FlightPathError(f"legs[{i}] ({leg.segment}): the path goes below the ground (end altitude {z:.1f} m)")

    @property
    def knot_time_s(self) -> np.ndarray:
        return np.concatenate([[0.0], np.cumsum([leg.duration_s for leg in self.legs])])

    @property
    def knot_position_m(self) -> np.ndarray:
        steps = np.array([[leg.forward_speed_mps * leg.duration_s, 0.0, leg.climb_speed_mps * leg.duration_s]
                          for leg in self.legs])
        return np.asarray(self.start_m, float)[None, :] + np.vstack([np.zeros(3), np.cumsum(steps, axis=0)])

    @property
    def segments(self) -> list[str]:
        return [leg.segment for leg in self.legs]


def _number(item: Mapping, key: str, where: str, positive: bool = True) -> float:
    value = item[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or (positive and value <= 0):
        raise FlightPathError(f"{where}.{key}: expected a {'positive ' if positive else ''}number, got {value!r}")
    return float(value)


def mission_path(mission: Mapping, aircraft: str) -> FlightPath:
    """The ``profile`` of a validated mission for ``aircraft`` (speeds from its segments)."""
    profile = mission.get("profile")
    if not profile:
        raise FlightPathError(f"mission '{mission.get('name')}': no 'profile' (the optional flight profile) to fly")
    speeds = {s["id"]: s["aircraft"] for s in mission["segments"]}
    legs = []
    z = None
    for i, item in enumerate(profile):
        where = f"profile[{i}]"
        unknown = sorted(set(item) - {"segment", "distance_m", "duration_s", "start_altitude_m"})
        if unknown:
            raise FlightPathError(f"{where}: unknown key(s) {unknown}")
        seg = item.get("segment")
        if seg not in speeds:
            raise FlightPathError(f"{where}.segment: expected one of the mission's segments {sorted(speeds)}, got {seg!r}")
        if aircraft not in speeds[seg]:
            raise FlightPathError(f"{where}.segment: segment '{seg}' has no speeds for aircraft '{aircraft}'")
        v = speeds[seg][aircraft]
        vh, vc = float(v["forward_speed_mps"]), float(v["climb_speed_mps"])
        if ("distance_m" in item) == ("duration_s" in item):
            raise FlightPathError(f"{where}: give exactly one of 'distance_m' (ground distance) and 'duration_s'")
        duration = _number(item, "duration_s", where) if "duration_s" in item else _number(item, "distance_m", where) / max(vh, 1e-300)
        if "start_altitude_m" in item:
            start = _number(item, "start_altitude_m", where, positive=False)
            if start < 0:
                raise FlightPathError(f"{where}.start_altitude_m: expected >= 0 m, got {start}")
            if z is not None and abs(start - z) > ALTITUDE_TOLERANCE_M:
                raise FlightPathError(f"{where}.start_altitude_m: the previous leg ends at {z:.2f} m; expected that value "
                                      f"within {ALTITUDE_TOLERANCE_M} m (the path is continuous), got {start}")
            z = start if z is None else z
        elif z is None:
            raise FlightPathError(f"{where}.start_altitude_m: required on the first leg")
        if i == 0:
            z0 = z
        legs.append(Leg(seg, vh, vc, duration))
        z += vc * duration
    return FlightPath((0.0, 0.0, z0), tuple(legs))


@dataclass(frozen=True)
class Procedure:
    """A certification reference procedure: its path (reference point at x = 0), the
    microphones (3, 3) in E (centre, port, starboard) and the reference atmosphere."""

    name: str
    path: FlightPath
    microphones_m: np.ndarray
    speed_mps: float
    height_over_reference_m: float

    @property
    def atmosphere(self):
        return isa(0.0, REFERENCE_TEMPERATURE_K - isa(0.0).temperature_k, REFERENCE_HUMIDITY_PCT)


def microphones() -> np.ndarray:
    """Centre, port and starboard microphones (m, E), 1.2 m above ground, 150 m sidelines."""
    return np.array([[0.0, 0.0, MICROPHONE_HEIGHT_M], [0.0, SIDELINE_OFFSET_M, MICROPHONE_HEIGHT_M],
                     [0.0, -SIDELINE_OFFSET_M, MICROPHONE_HEIGHT_M]])


def overflight_speed_mps(vh_mps: float, vne_mps: float | None = None) -> float:
    """Reference overflight speed: least of 0.9 V_H, 0.9 V_NE and 0.45 V_H + 65 km/h."""
    candidates = [0.9 * vh_mps, 0.45 * vh_mps + 65.0 * KMH]
    if vne_mps is not None:
        candidates.append(0.9 * vne_mps)
    return min(candidates)


def certification_procedure(name: str, segment: str, params: Mapping, before_m: float = 2000.0,
                            after_m: float = 2000.0) -> Procedure:
    """The reference procedure ``name`` (PROCEDURES) flying ``segment``'s hemisphere.

    ``params`` (m/s): ``vy_mps`` (best-rate-of-climb airspeed), ``climb_angle_deg`` (take-off
    climb angle at V_y), ``vh_mps`` (maximum level speed at maximum continuous power),
    optional ``vne_mps`` and ``approach_min_speed_mps``. ``before_m``/``after_m``: ground
    distance flown before/after the reference point (the 10-dB-down window must fit).
    """
    if name not in PROCEDURES:
        raise FlightPathError(f"certification procedure: expected one of {PROCEDURES}, got {name!r}")
    for key in ("vy_mps", "vh_mps"):
        if key not in params:
            raise FlightPathError(f"certification.{key}: required")
        _number(params, key, "certification")
    for key in ("vne_mps", "approach_min_speed_mps"):
        if params.get(key) is not None:
            _number(params, key, "certification")
    if not (before_m > TAKEOFF_LEVEL_BEFORE_M and after_m > 0):
        raise FlightPathError(f"certification: before_m must exceed {TAKEOFF_LEVEL_BEFORE_M} m and after_m be positive")
    vy = float(params["vy_mps"])
    if name == "takeoff":
        gamma = math.radians(_number(params, "climb_angle_deg", "certification"))
        if not gamma < math.radians(45.0):
            raise FlightPathError("certification.climb_angle_deg: expected below 45 deg")
        vh, vc = vy * math.cos(gamma), vy * math.sin(gamma)
        level = Leg(segment, vy, 0.0, (before_m - TAKEOFF_LEVEL_BEFORE_M) / vy)
        climb = Leg(segment, vh, vc, (TAKEOFF_LEVEL_BEFORE_M + after_m) / vh)
        path = FlightPath((-before_m, 0.0, TAKEOFF_HEIGHT_M), (level, climb))
        return Procedure(name, path, microphones(), vy, TAKEOFF_HEIGHT_M + TAKEOFF_LEVEL_BEFORE_M * math.tan(gamma))
    if name == "overflight":
        v = overflight_speed_mps(float(params["vh_mps"]), params.get("vne_mps"))
        path = FlightPath((-before_m, 0.0, OVERFLIGHT_HEIGHT_M), (Leg(segment, v, 0.0, (before_m + after_m) / v),))
        return Procedure(name, path, microphones(), v, OVERFLIGHT_HEIGHT_M)
    v = max(vy, float(params.get("approach_min_speed_mps") or 0.0))
    gamma = math.radians(APPROACH_ANGLE_DEG)
    after = min(after_m, 0.95 * APPROACH_HEIGHT_M / math.tan(gamma))  # stop before the ground
    vh, vc = v * math.cos(gamma), -v * math.sin(gamma)
    path = FlightPath((-before_m, 0.0, APPROACH_HEIGHT_M + before_m * math.tan(gamma)),
                      (Leg(segment, vh, vc, (before_m + after) / vh),))
    return Procedure(name, path, microphones(), v, APPROACH_HEIGHT_M)


def reference_parameters(mission: Mapping, aircraft: str, segments: Mapping[str, str], vne_mps: float | None = None,
                         approach_min_speed_mps: float | None = None) -> dict:
    """Procedure parameters from a mission's steady segments: V_y and the climb angle from the
    take-off (best-rate-of-climb) segment, V_H from the fastest level segment."""
    speeds = {s["id"]: s["aircraft"][aircraft] for s in mission["segments"] if aircraft in s["aircraft"]}
    climb = speeds.get(segments.get("takeoff"))
    if climb is None:
        raise FlightPathError(f"certification.segments.takeoff: expected a mission segment with speeds for '{aircraft}'")
    if not climb["climb_speed_mps"] > 0:
        raise FlightPathError(f"certification.segments.takeoff: expected the best-rate-of-climb segment (climb speed > 0), "
                              f"'{segments['takeoff']}' has {climb['climb_speed_mps']} m/s")
    level = [v["forward_speed_mps"] for v in speeds.values() if v["climb_speed_mps"] == 0.0]
    if not level:
        raise FlightPathError(f"mission: no level segment for '{aircraft}' to take V_H from")
    return {
        "vy_mps": math.hypot(climb["forward_speed_mps"], climb["climb_speed_mps"]),
        "climb_angle_deg": math.degrees(math.atan2(climb["climb_speed_mps"], climb["forward_speed_mps"])),
        "vh_mps": max(level),
        "vne_mps": vne_mps,
        "approach_min_speed_mps": approach_min_speed_mps,
    }


def atmospheres_along(path: FlightPath, delta_t_k: float, relative_humidity_pct: float) -> tuple:
    """ISA + ΔT state at each leg's mean height (the segment's atmosphere for absorption)."""
    z = path.knot_position_m[:, 2]
    return tuple(isa(float(0.5 * (z[i] + z[i + 1])), delta_t_k, relative_humidity_pct) for i in range(len(path.legs)))


def leg_segments(path: FlightPath, order: Sequence[str]) -> np.ndarray:
    """Index into ``order`` of every leg's segment."""
    return np.array([list(order).index(s) for s in path.segments], dtype=np.int64)
