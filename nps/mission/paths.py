"""Flight paths in 3-D: legs of straight and turning flight with speed, height and rotor-speed schedules,
sampled into a smooth time history (docs/reference/paths.md).

Mission frame E: x, y horizontal (y to the left of x), z height above flat ground, origin on the ground.
Heading ψ: direction of the horizontal velocity, measured from x_E toward y_E (counter-clockwise seen from
above); a positive heading change turns to port. Flight-path angle γ: of the velocity above the horizontal.

Each leg flies, from the state the previous leg ends in (so position, velocity, heading and rotor speed are
continuous):

* speed V(τ) = V_0 + a_x τ, a_x constant (from the end speed or given), τ the time since the leg start;
* flight-path angle γ(τ): from the entering γ_in toward the leg's γ_1 at the constant rate
  q = ± g Δn / V_0 (a pull-up or push-over with the normal load-factor increment Δn =
  ``flight_path_change_g``), then γ_1;
* heading: constant on a straight leg; on a turn of horizontal radius R, ψ = ψ_0 + σ s_h / R with
  s_h(τ) = ∫ V cos γ dτ the horizontal arc and σ = ±1 the turn side (+1 port);
* rotor-speed fraction linear in τ from the entering value to the leg's end value.

With C(τ) = ∫_0^τ V e^{iγ} dτ', s_h = Re C and the height change Im C; the horizontal position is the straight
line or the circle arc of length s_h. During the change (τ ≤ t_γ = |γ_1 − γ_in|/|q|)

    C(τ) = e^{iγ_in} [V_0 (e^{iqτ} − 1)/(iq) + a_x (τ e^{iqτ}/(iq) + (e^{iqτ} − 1)/q²)]

(e^{iqτ} − 1 = −2 sin²(qτ/2) + i sin qτ, free of cancellation), after it C(t_γ) + e^{iγ_1}(V(t_γ) τ' + a_x τ'²/2),
τ' = τ − t_γ. The velocity is V (cos γ cos ψ, cos γ sin ψ,
sin γ); the acceleration a = a_x V̂ + V γ̇ ∂V̂/∂γ + V ψ̇ ∂V̂/∂ψ with ψ̇ = σ V cos γ / R.

Load factor and bank, from the specific force f = a + g ẑ (what the rotors and the airframe's drag carry per
unit mass): n = |f − (f·V̂)V̂| / g (the part normal to the path, so a pull-up's V γ̇ counts and a_x does
not), bank φ = atan2(f·ŝ, f·n̂) with n̂ the upward normal to V̂ in its vertical plane and ŝ the horizontal
starboard direction: φ > 0 starboard down (the roll of docs/reference/conventions.md), a level coordinated
turn has tan φ = V²/(g R) and n = 1/cos φ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np
from scipy.optimize import brentq
from scipy.special import fresnel

from nps.rotor.trim import G0_M_S2

# bracket of the flight-path angle solved from a leg's height change (rad); the limits check the result
_GAMMA_BRACKET_RAD = math.radians(60.0)
# points per leg at which the limits are checked (plus the end of every flight-path change)
CHECK_POINTS_PER_LEG = 200
LEG_KINDS = ("straight", "turn")


class PathError(ValueError):
    """A path the aircraft cannot fly or that is ill-defined: ``field`` (e.g. ``legs[2].radius_m``) and
    ``expected`` (what was expected) make the one-line message."""

    def __init__(self, field: str, expected: str):
        super().__init__(f"{field}: {expected}")
        self.field, self.expected = field, expected


@dataclass(frozen=True)
class PathLimits:
    """What the aircraft may fly: bank (rad), normal load factor range, |a_x| (m/s²), climb and descent
    angles (rad, both positive)."""

    max_bank_rad: float
    min_load_factor: float
    max_load_factor: float
    max_longitudinal_acceleration_mps2: float
    max_climb_angle_rad: float
    max_descent_angle_rad: float


@dataclass(frozen=True)
class LegSpec:
    """One leg as written (SI, radians; None where not given): ``kind`` straight or turn; length by
    ``distance_m`` (along the path) or ``duration_s`` (straight), ``heading_change_rad`` with
    ``radius_m`` or ``bank_rad`` (turn); speed by ``end_speed_mps`` or ``acceleration_mps2``; height by
    ``height_change_m`` or ``flight_path_rad``; ``end_rotor_speed_fraction``."""

    kind: str
    distance_m: float | None = None
    duration_s: float | None = None
    heading_change_rad: float | None = None
    radius_m: float | None = None
    bank_rad: float | None = None
    end_speed_mps: float | None = None
    acceleration_mps2: float | None = None
    height_change_m: float | None = None
    flight_path_rad: float | None = None
    end_rotor_speed_fraction: float | None = None


@dataclass(frozen=True)
class PathSpec:
    """A path as written: start state in E and the legs."""

    name: str
    aircraft: str
    start_position_m: tuple[float, float, float]
    start_heading_rad: float
    start_speed_mps: float
    start_flight_path_rad: float
    start_rotor_speed_fraction: float
    flight_path_change_g: float
    limits: PathLimits
    legs: tuple[LegSpec, ...]
    roll_rate_rad_s: float = math.inf  # bank rate of a turn's roll-in and roll-out (inf: instantaneous)


def _rad(value):
    return None if value is None else math.radians(float(value))


def path_spec(document: Mapping) -> PathSpec:
    """The :class:`PathSpec` of a schema-valid path document (``nps/app/schemas/path.schema.yaml``, defaults
    filled): degrees to radians, nothing else interpreted."""
    start, limits = document["start"], document["limits"]
    legs = []
    for leg in document["legs"]:
        kind = "turn" if "turn" in leg else "straight"
        body = leg[kind]
        legs.append(LegSpec(kind, body.get("distance_m"), body.get("duration_s"), _rad(body.get("heading_change_deg")),
                            body.get("radius_m"), _rad(body.get("bank_deg")), leg.get("end_speed_mps"),
                            leg.get("acceleration_mps2"), leg.get("height_change_m"), _rad(leg.get("flight_path_deg")),
                            leg.get("end_rotor_speed_fraction")))
    x, y = start["position_m"]
    return PathSpec(
        document["name"], document["aircraft"], (float(x), float(y), float(start["height_m"])),
        math.radians(start["heading_deg"]), float(start["speed_mps"]), math.radians(start["flight_path_deg"]),
        float(start["rotor_speed_fraction"]), float(document["flight_path_change_g"]),
        PathLimits(math.radians(limits["max_bank_deg"]), float(limits["min_load_factor"]), float(limits["max_load_factor"]),
                   float(limits["max_longitudinal_acceleration_mps2"]), math.radians(limits["max_climb_angle_deg"]),
                   math.radians(limits["max_descent_angle_deg"])),
        tuple(legs), math.radians(document["roll_rate_deg_s"]))


@dataclass(frozen=True)
class Leg:
    """One solved leg: start time, duration (s), start position (m, E), speed V_0 and a_x, entering and
    final flight-path angles with the rate q (rad/s) and duration t_γ of the change, start heading, turn
    radius (inf on a straight leg) and side σ, rotor-speed fractions at start and end; a turn's horizontal arc
    (m) and the length L_r (m) of its roll-in and of its roll-out (0: instantaneous, :func:`_turn_track`)."""

    index: int
    kind: str
    t0_s: float
    duration_s: float
    position0_m: tuple[float, float, float]
    speed0_mps: float
    accel_mps2: float
    gamma0_rad: float
    gamma1_rad: float
    gamma_rate_rad_s: float
    gamma_time_s: float
    heading0_rad: float
    radius_m: float
    side: int
    fraction0: float
    fraction1: float
    arc_m: float = 0.0
    roll_length_m: float = 0.0


def _ramp(v0: float, a: float, gamma0: float, q: float, tau: np.ndarray) -> np.ndarray:
    """∫_0^τ (v0 + a s) e^{i(γ0 + q s)} ds (complex, closed form; q = 0: the straight-line integral)."""
    tau = np.asarray(tau, dtype=float)
    if q == 0.0:
        return (v0 * tau + 0.5 * a * tau * tau) * np.exp(1j * gamma0)
    theta = q * tau
    expm1 = -2.0 * np.sin(0.5 * theta) ** 2 + 1j * np.sin(theta)  # e^{iθ} − 1 without cancellation
    return np.exp(1j * gamma0) * (v0 * expm1 / (1j * q) + a * (tau * (1.0 + expm1) / (1j * q) + expm1 / (q * q)))


def _arc(leg: Leg, tau: np.ndarray) -> np.ndarray:
    """C(τ) = ∫_0^τ V e^{iγ} dτ' of a leg: Re the horizontal arc s_h, Im the height change (m)."""
    tau = np.asarray(tau, dtype=float)
    t_gamma = leg.gamma_time_s
    ramp = _ramp(leg.speed0_mps, leg.accel_mps2, leg.gamma0_rad, leg.gamma_rate_rad_s, np.minimum(tau, t_gamma))
    after = np.maximum(tau - t_gamma, 0.0)
    v_gamma = leg.speed0_mps + leg.accel_mps2 * t_gamma
    return ramp + (v_gamma * after + 0.5 * leg.accel_mps2 * after * after) * np.exp(1j * leg.gamma1_rad)


def _flight_path(leg: Leg, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """γ(τ) and γ̇(τ) of a leg (rad, rad/s)."""
    ramping = tau < leg.gamma_time_s
    gamma = np.where(ramping, leg.gamma0_rad + leg.gamma_rate_rad_s * np.minimum(tau, leg.gamma_time_s),
                     leg.gamma1_rad)
    return gamma, np.where(ramping, leg.gamma_rate_rad_s, 0.0)


def _clothoid(s: np.ndarray, k: float, side: int) -> np.ndarray:
    """∫_0^s e^{iσ k u²} du (complex; Fresnel integrals C, S of t = s √(2k/π))."""
    scale = math.sqrt(math.pi / (2.0 * k))
    sine, cosine = fresnel(np.asarray(s, float) / scale)
    return scale * (cosine + 1j * side * sine)


def _turn_track(leg: Leg, s_h: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Heading ψ (rad), horizontal displacement from the leg's start (complex x + i y, m, E) and curvature κ (1/m)
    at horizontal arc ``s_h`` of a turn that rolls in and out over L_r: κ rises linearly in arc from 0 to 1/R
    over the first L_r (a clothoid, ψ = ψ₀ + σ k s², k = 1/(2 R L_r)), stays 1/R, and falls back to 0 over the
    last L_r; the heading change of the whole arc R|Δψ| + L_r is Δψ. Closed form with Fresnel integrals."""
    radius, length, side, psi0 = leg.radius_m, leg.roll_length_m, leg.side, leg.heading0_rad
    k = 1.0 / (2.0 * radius * length)
    s1, s2 = length, leg.arc_m - length
    s = np.clip(np.asarray(s_h, float), 0.0, leg.arc_m)
    psi1 = psi0 + side * length / (2.0 * radius)
    psi2 = psi1 + side * (s2 - s1) / radius
    psi_end = psi2 + side * length / (2.0 * radius)
    p1 = np.exp(1j * psi0) * _clothoid(np.array(s1), k, side)
    p2 = p1 - 1j * side * radius * (np.exp(1j * psi2) - np.exp(1j * psi1))
    rolling_in, rolling_out = s < s1, s > s2
    u_in, u_out = np.minimum(s, s1), np.maximum(s - s2, 0.0)
    circle = np.clip(s, s1, s2) - s1
    heading = np.where(rolling_in, psi0 + side * k * u_in**2,
                       np.where(rolling_out, psi_end - side * k * (length - u_out)**2, psi1 + side * circle / radius))
    in_track = np.exp(1j * psi0) * _clothoid(u_in, k, side)
    circle_track = p1 - 1j * side * radius * (np.exp(1j * (psi1 + side * circle / radius)) - np.exp(1j * psi1))
    # roll-out: ψ = ψ_end − σ k (L_r − u)², its integral the conjugate clothoid between L_r − u and L_r
    out_track = p2 + np.exp(1j * psi_end) * np.conj(_clothoid(np.array(length), k, side) - _clothoid(length - u_out, k, side))
    track = np.where(rolling_in, in_track, np.where(rolling_out, out_track, circle_track))
    curvature = np.where(rolling_in, u_in, np.where(rolling_out, length - u_out, length)) / (radius * length)
    return heading, track, curvature


def leg_kinematics(leg: Leg, tau) -> dict[str, np.ndarray]:
    """Position, velocity, acceleration (m, m/s, m/s²; (n, 3) in E), speed, a_x, heading, γ and rotor-speed
    fraction of a leg at times τ since its start."""
    tau = np.atleast_1d(np.asarray(tau, dtype=float))
    arc = _arc(leg, tau)
    s_h, dz = arc.real, arc.imag
    speed = leg.speed0_mps + leg.accel_mps2 * tau
    gamma, gamma_rate = _flight_path(leg, tau)
    x0, y0, z0 = leg.position0_m
    psi0 = leg.heading0_rad
    if leg.kind == "turn" and leg.roll_length_m > 0.0:
        heading, track, curvature = _turn_track(leg, s_h)
        x, y = x0 + track.real, y0 + track.imag
        heading_rate = leg.side * speed * np.cos(gamma) * curvature
    elif leg.kind == "turn":
        heading = psi0 + leg.side * s_h / leg.radius_m
        x = x0 + leg.side * leg.radius_m * (np.sin(heading) - math.sin(psi0))
        y = y0 - leg.side * leg.radius_m * (np.cos(heading) - math.cos(psi0))
        heading_rate = leg.side * speed * np.cos(gamma) / leg.radius_m
    else:
        heading = np.full_like(tau, psi0)
        x, y = x0 + s_h * math.cos(psi0), y0 + s_h * math.sin(psi0)
        heading_rate = np.zeros_like(tau)
    cg, sg, cp, sp = np.cos(gamma), np.sin(gamma), np.cos(heading), np.sin(heading)
    unit = np.column_stack([cg * cp, cg * sp, sg])
    d_gamma = np.column_stack([-sg * cp, -sg * sp, cg])
    d_heading = np.column_stack([-sp, cp, np.zeros_like(sp)])
    accel = (leg.accel_mps2 * unit + (speed * gamma_rate)[:, None] * d_gamma
             + (speed * heading_rate * cg)[:, None] * d_heading)
    fraction = leg.fraction0 + (leg.fraction1 - leg.fraction0) * tau / leg.duration_s
    return {"position_m": np.column_stack([x, y, z0 + dz]), "velocity_mps": speed[:, None] * unit,
            "acceleration_mps2": accel, "speed_mps": speed, "longitudinal_acceleration_mps2": np.full_like(tau, leg.accel_mps2),
            "heading_rad": heading, "flight_path_rad": gamma, "rotor_speed_fraction": fraction}


def load_and_bank(velocity_unit: np.ndarray, heading_rad: np.ndarray, flight_path_rad: np.ndarray,
                  acceleration_mps2: np.ndarray) -> dict[str, np.ndarray]:
    """Specific force f = a + g ẑ split in the path axes (per g): tangential f_t (sin of the effective
    flight-path angle, :func:`nps.mission.path_states.effective_flight_path`), normal n_v (upward, in the
    vertical plane of V̂), lateral n_s (starboard); load factor n = hypot(n_v, n_s), bank atan2(n_s, n_v)."""
    f = acceleration_mps2 + np.array([0.0, 0.0, G0_M_S2])
    cg, sg = np.cos(flight_path_rad), np.sin(flight_path_rad)
    cp, sp = np.cos(heading_rad), np.sin(heading_rad)
    normal = np.column_stack([-sg * cp, -sg * sp, cg])
    starboard = np.column_stack([sp, -cp, np.zeros_like(cp)])
    n_v = np.einsum("ij,ij->i", f, normal) / G0_M_S2
    n_s = np.einsum("ij,ij->i", f, starboard) / G0_M_S2
    return {"tangential_g": np.einsum("ij,ij->i", f, velocity_unit) / G0_M_S2, "normal_g": n_v, "lateral_g": n_s,
            "load_factor": np.hypot(n_v, n_s), "bank_rad": np.arctan2(n_s, n_v)}


@dataclass(frozen=True)
class _Entry:
    """The state a leg starts from (the previous leg's end)."""

    time_s: float
    position_m: tuple[float, float, float]
    speed_mps: float
    flight_path_rad: float
    heading_rad: float
    fraction: float


def _leg_time(spec: LegSpec, speed0: float, where: str) -> tuple[float | None, float | None]:
    """(duration, a_x) of a straight leg, or (None, a_x or None) of a turn (its duration follows from the arc)."""
    a = spec.acceleration_mps2
    if spec.kind == "turn" or spec.duration_s is not None:
        duration = spec.duration_s
        if duration is not None and spec.end_speed_mps is not None:
            a = (spec.end_speed_mps - speed0) / duration
        return duration, (0.0 if a is None and spec.end_speed_mps is None else a)
    length = spec.distance_m
    if spec.end_speed_mps is not None:
        if speed0 + spec.end_speed_mps <= 0.0:
            raise PathError(f"{where}.end_speed_mps", "expected a positive speed at the start or at the end of the leg "
                                                      "(a leg with no speed covers no distance)")
        duration = 2.0 * length / (speed0 + spec.end_speed_mps)
        return duration, (spec.end_speed_mps - speed0) / duration
    a = 0.0 if a is None else a
    if a == 0.0 and speed0 <= 0.0:
        raise PathError(f"{where}.straight.distance_m", "a leg without speed covers no distance: expected duration_s "
                                                        "(hover), an acceleration_mps2 or an end_speed_mps")
    discriminant = speed0 * speed0 + 2.0 * a * length
    if discriminant < 0.0:
        raise PathError(f"{where}.acceleration_mps2", f"the speed reaches zero before the leg's distance_m {length} m "
                                                      f"(start speed {speed0:.4g} m/s, a_x {a} m/s²): expected a milder "
                                                      "deceleration or a shorter leg")
    return 2.0 * length / (speed0 + math.sqrt(discriminant)), a


def _turn_radius(spec: LegSpec, speed0: float, where: str) -> float:
    if spec.radius_m is not None:
        return float(spec.radius_m)
    if speed0 <= 0.0:
        raise PathError(f"{where}.turn.bank_deg", "a turn given by its bank needs speed at its start (R = V²/(g tan φ)); "
                                                  "expected radius_m or a leg that starts with speed")
    return speed0 * speed0 / (G0_M_S2 * math.tan(spec.bank_rad))


def _build(index: int, spec: LegSpec, entry: _Entry, gamma1: float, change_g: float, roll_rate: float, where: str) -> Leg:
    """The leg flying ``spec`` from ``entry`` with final flight-path angle ``gamma1`` (``roll_rate``: a turn's bank
    rate, rad/s)."""
    speed0, gamma0 = entry.speed_mps, entry.flight_path_rad
    change = gamma1 - gamma0
    if change != 0.0 and speed0 <= 0.0:
        raise PathError(f"{where}", "a change of flight-path angle needs speed at the leg start (the pull-up or push-over "
                                    "has the rate g Δn / V); expected a leg that keeps the entering angle")
    rate = math.copysign(G0_M_S2 * change_g / speed0, change) if change != 0.0 else 0.0
    t_gamma = abs(change / rate) if change != 0.0 else 0.0
    duration, a = _leg_time(spec, speed0, where)
    fraction1 = entry.fraction if spec.end_rotor_speed_fraction is None else float(spec.end_rotor_speed_fraction)
    radius, side, arc, roll = math.inf, 0, 0.0, 0.0
    if spec.kind == "turn":
        if spec.heading_change_rad == 0.0:
            raise PathError(f"{where}.turn.heading_change_deg", "expected a non-zero heading change (+ port, − starboard)")
        radius, side = _turn_radius(spec, speed0, where), (1 if spec.heading_change_rad > 0 else -1)
        roll = _roll_length(speed0, radius, roll_rate, radius * abs(spec.heading_change_rad), where)
        arc = radius * abs(spec.heading_change_rad) + roll
    leg = Leg(index, spec.kind, entry.time_s, 1.0 if duration is None else duration, entry.position_m, speed0,
              0.0 if a is None else a, gamma0, gamma1, rate, t_gamma, entry.heading_rad, radius, side, entry.fraction, fraction1,
              arc, roll)
    if duration is None:
        leg = _turn_duration(leg, spec, arc, where)
    return leg


def _roll_length(speed0: float, radius: float, roll_rate: float, circle_m: float, where: str) -> float:
    """Horizontal arc L_r = V₀ φ₀ / p (m) of a turn's roll-in (and roll-out) at the bank rate p (rad/s) to the
    coordinated bank φ₀ = atan(V₀²/(g R)) at the turn's start speed; 0 when p is infinite."""
    if math.isinf(roll_rate):
        return 0.0
    bank = math.atan(speed0 * speed0 / (G0_M_S2 * radius))
    roll = speed0 * bank / roll_rate
    if roll > circle_m:
        raise PathError(f"{where}.turn.heading_change_deg", (
            f"rolling in and out at roll_rate_deg_s {math.degrees(roll_rate):.3g}°/s to the bank {math.degrees(bank):.3g}° "
            f"takes {roll:.4g} m of arc each, more than the turn's R |Δψ| = {circle_m:.4g} m: expected a larger heading change "
            "or radius, or a faster roll rate"))
    return roll


def _with(leg: Leg, duration: float, spec: LegSpec) -> Leg:
    a = leg.accel_mps2 if spec.end_speed_mps is None else (spec.end_speed_mps - leg.speed0_mps) / duration
    return Leg(**{**leg.__dict__, "duration_s": duration, "accel_mps2": a})


def _turn_duration(leg: Leg, spec: LegSpec, arc_m: float, where: str) -> Leg:
    """The leg with the duration that covers the horizontal arc R |Δψ| of its turn."""
    def shortfall(duration):
        trial = _with(leg, duration, spec)
        return float(_arc(trial, np.array([duration]))[0].real) - arc_m

    top = arc_m / max(leg.speed0_mps, spec.end_speed_mps or 0.0, 1e-3)
    while shortfall(top) < 0.0:
        top *= 2.0
        if top > 1e6 or (spec.acceleration_mps2 is not None and leg.speed0_mps + spec.acceleration_mps2 * top < 0.0):
            raise PathError(f"{where}.acceleration_mps2", f"the speed reaches zero before the turn's arc of {arc_m:.4g} m "
                                                          "is flown: expected a milder deceleration or a shorter turn")
    return _with(leg, brentq(shortfall, 0.0, top, xtol=1e-12, rtol=1e-14), spec)


def _solve_leg(index: int, spec: LegSpec, entry: _Entry, change_g: float, roll_rate: float) -> Leg:
    """The leg, its final flight-path angle given, kept or solved from the height change (Brent's method)."""
    where = f"legs[{index}]"
    if spec.height_change_m is None:
        gamma1 = entry.flight_path_rad if spec.flight_path_rad is None else spec.flight_path_rad
        return _build(index, spec, entry, gamma1, change_g, roll_rate, where)

    def excess(gamma1):
        leg = _build(index, spec, entry, gamma1, change_g, roll_rate, where)
        return float(_arc(leg, np.array([leg.duration_s]))[0].imag) - spec.height_change_m

    low, high = -_GAMMA_BRACKET_RAD, _GAMMA_BRACKET_RAD
    if excess(low) > 0.0 or excess(high) < 0.0:
        raise PathError(f"{where}.height_change_m", (
            f"a height change of {spec.height_change_m} m cannot be flown in this leg with flight-path angles within "
            f"±{math.degrees(_GAMMA_BRACKET_RAD):g}° reached at the rate g flight_path_change_g / V = {change_g} g / "
            f"{entry.speed_mps:.4g} m/s: expected a longer leg, a smaller height change or a larger flight_path_change_g"))
    return _build(index, spec, entry, brentq(excess, low, high, xtol=1e-13, rtol=1e-15), change_g, roll_rate, where)


def solve_path(spec: PathSpec) -> tuple[Leg, ...]:
    """The legs of a path, each from the end state of the previous one (PathError naming the leg's field)."""
    entry = _Entry(0.0, spec.start_position_m, spec.start_speed_mps, spec.start_flight_path_rad, spec.start_heading_rad,
                   spec.start_rotor_speed_fraction)
    legs = []
    for index, leg_spec in enumerate(spec.legs):
        leg = _solve_leg(index, leg_spec, entry, spec.flight_path_change_g, spec.roll_rate_rad_s)
        if leg.gamma_time_s > leg.duration_s:
            raise PathError(f"legs[{index}]", (
                f"the flight-path change from {math.degrees(leg.gamma0_rad):.3g}° to {math.degrees(leg.gamma1_rad):.3g}° "
                f"takes {leg.gamma_time_s:.3g} s at flight_path_change_g {spec.flight_path_change_g} and the leg lasts "
                f"{leg.duration_s:.3g} s: expected a longer leg or a larger flight_path_change_g"))
        end = leg_kinematics(leg, [leg.duration_s])
        entry = _Entry(leg.t0_s + leg.duration_s, tuple(float(c) for c in end["position_m"][0]), float(end["speed_mps"][0]),
                       leg.gamma1_rad, float(end["heading_rad"][0]), leg.fraction1)
        if entry.speed_mps < 0.0:
            raise PathError(f"legs[{index}]", f"the speed would end at {entry.speed_mps:.4g} m/s: expected >= 0")
        legs.append(leg)
    return tuple(legs)


@dataclass(frozen=True)
class PathHistory:
    """A path sampled at times ``time_s`` (n,): position, velocity, acceleration (n, 3; m, m/s, m/s² in E),
    speed, a_x (m/s²), heading, flight-path angle γ, bank φ (rad), load factor n, the specific force's path
    components (per g: tangential, upward normal, starboard lateral), rotor-speed fraction and leg index."""

    time_s: np.ndarray
    position_m: np.ndarray
    velocity_mps: np.ndarray
    acceleration_mps2: np.ndarray
    speed_mps: np.ndarray
    longitudinal_acceleration_mps2: np.ndarray
    heading_rad: np.ndarray
    flight_path_rad: np.ndarray
    bank_rad: np.ndarray
    load_factor: np.ndarray
    tangential_g: np.ndarray
    normal_g: np.ndarray
    lateral_g: np.ndarray
    rotor_speed_fraction: np.ndarray
    leg: np.ndarray


def _history(legs: tuple[Leg, ...], times: np.ndarray) -> PathHistory:
    """Kinematics at ``times`` (s, within the path); a time on a join belongs to the later leg."""
    starts = np.array([leg.t0_s for leg in legs])
    owner = np.clip(np.searchsorted(starts, times, side="right") - 1, 0, len(legs) - 1)
    parts = {}
    for leg in legs:
        mask = owner == leg.index
        for key, value in leg_kinematics(leg, times[mask] - leg.t0_s).items():
            parts.setdefault(key, np.zeros((len(times),) + value.shape[1:]))[mask] = value
    unit = np.column_stack([np.cos(parts["flight_path_rad"]) * np.cos(parts["heading_rad"]),
                            np.cos(parts["flight_path_rad"]) * np.sin(parts["heading_rad"]), np.sin(parts["flight_path_rad"])])
    forces = load_and_bank(unit, parts["heading_rad"], parts["flight_path_rad"], parts["acceleration_mps2"])
    return PathHistory(time_s=times, leg=owner.astype(np.int32), **parts, **forces)


def path_end_s(legs: tuple[Leg, ...]) -> float:
    return legs[-1].t0_s + legs[-1].duration_s


def sample_path(legs: tuple[Leg, ...], dt_s: float) -> PathHistory:
    """The history at t_k = k Δt, k = 0 … ⌊T/Δt⌋ (T the path's duration; the end itself when it falls on the
    grid within 1e-9 Δt)."""
    count = int(math.floor(path_end_s(legs) / dt_s + 1e-9)) + 1
    return _history(legs, np.arange(count) * dt_s)


def _check_times(legs: tuple[Leg, ...]) -> np.ndarray:
    """Dense times of every leg (its start, end, the end of its flight-path change and CHECK_POINTS_PER_LEG
    between), the end of each leg taken just before the join."""
    times = []
    for leg in legs:
        tau = np.linspace(0.0, leg.duration_s, CHECK_POINTS_PER_LEG + 1)
        tau = np.concatenate([tau[:-1], [min(leg.gamma_time_s, leg.duration_s), leg.duration_s * (1.0 - 1e-12)]])
        times.append(leg.t0_s + np.sort(tau))
    return np.concatenate(times)


def _limit_field(leg: LegSpec, index: int, what: str) -> str:
    """The field a limit violation of a leg names: what sets the bank, the acceleration or the angle."""
    where = f"legs[{index}]"
    if what == "turn":
        if leg.kind != "turn":  # a straight leg's load factor comes from its flight-path change
            return "flight_path_change_g"
        return f"{where}.turn.radius_m" if leg.radius_m is not None else f"{where}.turn.bank_deg"
    if what == "speed":
        return f"{where}.end_speed_mps" if leg.end_speed_mps is not None else f"{where}.acceleration_mps2"
    return f"{where}.height_change_m" if leg.height_change_m is not None else f"{where}.flight_path_deg"


def check_limits(spec: PathSpec, legs: tuple[Leg, ...]) -> None:
    """Raise :class:`PathError` naming the first leg (and its field) that leaves the limits: bank, normal load
    factor, |a_x|, climb and descent angle, height above ground (z >= 0), speed >= 0."""
    limits = spec.limits
    history = _history(legs, _check_times(legs))
    checks = [
        ("turn", np.abs(history.bank_rad) > limits.max_bank_rad + 1e-12, lambda k: (
            f"bank {math.degrees(history.bank_rad[k]):.3g}° at {history.speed_mps[k]:.4g} m/s exceeds limits.max_bank_deg "
            f"{math.degrees(limits.max_bank_rad):.3g}°: expected a larger radius, a smaller bank or a lower speed")),
        ("turn", (history.load_factor > limits.max_load_factor + 1e-12) | (history.load_factor < limits.min_load_factor - 1e-12),
         lambda k: (f"load factor {history.load_factor[k]:.4g} outside limits [min_load_factor, max_load_factor] = "
                    f"[{limits.min_load_factor}, {limits.max_load_factor}]: expected a gentler turn or flight-path change")),
        ("speed", np.abs(history.longitudinal_acceleration_mps2) > limits.max_longitudinal_acceleration_mps2 + 1e-12,
         lambda k: (f"longitudinal acceleration {history.longitudinal_acceleration_mps2[k]:.4g} m/s² exceeds "
                    f"limits.max_longitudinal_acceleration_mps2 {limits.max_longitudinal_acceleration_mps2}: expected a "
                    "longer leg or a smaller speed change")),
        ("angle", (history.flight_path_rad > limits.max_climb_angle_rad + 1e-12)
         | (history.flight_path_rad < -limits.max_descent_angle_rad - 1e-12),
         lambda k: (f"flight-path angle {math.degrees(history.flight_path_rad[k]):.3g}° outside [-max_descent_angle_deg, "
                    f"max_climb_angle_deg] = [{-math.degrees(limits.max_descent_angle_rad):.3g}°, "
                    f"{math.degrees(limits.max_climb_angle_rad):.3g}°] of limits")),
        ("angle", history.position_m[:, 2] < -1e-9, lambda k: (
            f"the path goes below the ground (height {history.position_m[k, 2]:.4g} m at t = {history.time_s[k]:.4g} s): "
            "expected heights >= 0")),
    ]
    first = None
    for what, bad, message in checks:
        if bad.any():
            k = int(np.argmax(bad))
            if first is None or k < first[0]:
                first = (k, _limit_field(spec.legs[history.leg[k]], int(history.leg[k]), what), message(k))
    if first is not None:
        raise PathError(first[1], first[2])


def flight_path_history(spec: PathSpec, dt_s: float) -> tuple[tuple[Leg, ...], PathHistory]:
    """The solved legs of a path, checked against its limits, and its history at Δt = ``dt_s``."""
    legs = solve_path(spec)
    check_limits(spec, legs)
    return legs, sample_path(legs, dt_s)
