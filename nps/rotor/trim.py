"""Aircraft trim: steady and quasi-static force and moment balance (the role NDARC had in the thesis).

Frames and signs: docs/reference/conventions.md. For an aircraft flying with velocity
V_G = (V_h, 0, V_c) and acceleration a_G (zero in steady flight; quasi-static flight along a path,
nps.mission.paths: the balance of the instant, rates of the attitude neglected) the unknowns are the
body pitch θ, the body roll φ and the thrust T_i of every rotor; each rotor's thrust acts along its
shaft axis a_i (tip-path plane perpendicular to the shaft, i.e. zero hub-moment targets). The
balance, in the ground frame G:

    Σ T_i R_GB a_i  −  W ẑ  −  ½ ρ |V|² f V̂  = m a_G                     (forces)
    Σ p_i × (T_i a_i)  −  Σ s_i Q_i a_i  = 0   (selected components, body frame, about the CG)

p_i is the hub position relative to the CG, s_i the rotation sign and Q_i the rotor torque
(the shaft drives the rotor with +s_i Q_i a_i, so the rotor reacts on the airframe with
−s_i Q_i a_i). Which moment components close the system depends on the layout:

- single main rotor + antitorque rotor: yaw (the antitorque thrust balances main-rotor torque);
- two lift rotors separated along x by more than one radius (tandem): pitch (thrust split
  from the CG position);
- two coaxial lift rotors: yaw (equal and opposite torque);
- three or more lift rotors (multirotor): roll, pitch and yaw; the remaining freedom is closed
  by the minimum-norm Newton step from equal thrust shares. The fixed rotors give propulsion
  by tilting the whole body.

Roll and pitch moments of single-rotor and coaxial layouts are left to the hub moments (not
balanced by thrust). Rotor torque from momentum theory plus profile power:

    λ = μ_z + λ_i,  λ_i = C_T / (2 sqrt(μ² + λ²))         (Glauert, iterated)
    P = T Ω R (κ λ_i + μ_z) + ρ A (ΩR)³ σ c_d0 (1 + 4.65 μ²) / 8,   Q = P / Ω

with κ = 1.15 (induced-power factor) and μ² = μ_x² + μ_y².
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from nps.core import frames
from nps.core.atmosphere import AtmosphereState
from nps.core.solvers import ConvergenceError, newton, newton_fd
from nps.rotor.geometry import RotorGeometry

G0_M_S2 = 9.80665
INDUCED_POWER_FACTOR = 1.15
# aircraft balance (nps.core.solvers.newton_fd): converged when every residual is below TRIM_TOLERANCE, the
# residuals being forces / W and moments / (W R_max) (dimensionless); at most TRIM_MAX_ITERATIONS Newton updates;
# forward-difference steps TRIM_FD_STEP rad (pitch, roll) and TRIM_FD_STEP W (thrusts); the minimum-norm step
# (more rotors than balance equations) drops singular values below TRIM_PINV_RCOND σ_max
TRIM_TOLERANCE = 1e-12
TRIM_MAX_ITERATIONS = 50
TRIM_FD_STEP = 1e-7
TRIM_PINV_RCOND = 1e-12
# Glauert inflow (nps.core.solvers.newton): converged when the Newton step |Δλ_i| < GLAUERT_TOLERANCE (λ_i is
# dimensionless, a fraction of ΩR); each step may halve λ_i at most
GLAUERT_TOLERANCE = 1e-14
GLAUERT_MAX_ITERATIONS = 100


# The trim artifact (``trim.parquet``): one row per rotor, these columns (docs/reference/conventions.md).
TRIM_COLUMNS = (
    "rotor", "role", "rotation_sign", "n_blades", "radius_m", "omega_rad_s", "thrust_N", "roll_moment_Nm",
    "pitch_moment_Nm", "torque_Nm", "power_W", "mu_x", "mu_y", "mu_z", "lambda_i", "ct", "tip_mach",
    "hub_x_m", "hub_y_m", "hub_z_m", "vel_x_mps", "vel_y_mps", "vel_z_mps",
    *(f"r_gh_{i}{j}" for i in range(3) for j in range(3)),
    "density_kg_m3", "speed_of_sound_mps", "pitch_rad", "roll_rad", "flight_path_rad", "trim_iterations",
)

# stages whose artifact is a trim table: the aircraft trim, the set-up of a rig (nps.rig.case) and a PSU-WOPWOP
# case run by NPS (its rotors, nps.wopwop.rotors)
TRIM_STAGES = ("trim", "rig", "wopwop_run", "wopwop_read")


def trim_row(trim: pd.DataFrame, rotor: str, what: str = "trim.parquet") -> dict:
    """The row of ``rotor`` in a trim table, as a dict (the one accessor every stage uses).

    Raises ValueError naming ``what`` when the rotor has not exactly one row. (Stages read trim
    artifacts with ``read_table(path, required=TRIM_COLUMNS)``, which names missing columns.)
    """
    rows = trim[trim["rotor"] == rotor]
    if len(rows) != 1:
        raise ValueError(f"{what}: expected one row for rotor '{rotor}', found {len(rows)}; rotors: {list(trim['rotor'])}")
    return rows.iloc[0].to_dict()


class AircraftTrimError(RuntimeError):
    """The aircraft force and moment balance did not converge."""


@dataclass(frozen=True)
class FlightCondition:
    """Flight at one instant: horizontal speed, climb speed (negative in descent), atmosphere, and the
    acceleration (m/s², ground frame G: x along the horizontal velocity, y port, z up; zero in steady
    flight). A coordinated turn to starboard at speed V on radius R has a_G = (0, −V²/R, 0): the trimmed
    roll is its bank, tan φ = V²/(g R) for a rotor thrust along z_B without drag."""

    forward_speed_mps: float
    climb_speed_mps: float
    atmosphere: AtmosphereState
    acceleration_mps2: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @property
    def velocity_g(self) -> np.ndarray:
        return np.array([self.forward_speed_mps, 0.0, self.climb_speed_mps])

    @property
    def flight_path_rad(self) -> float:
        return float(np.arctan2(self.climb_speed_mps, self.forward_speed_mps))


def glauert_inflow(ct: float, mu: float, mu_z: float) -> float:
    """Induced inflow ratio λ_i from λ_i = C_T / (2 sqrt(μ² + (μ_z + λ_i)²)) (Newton).

    Starts from the larger of the hover and high-speed limits; valid outside the vortex-ring
    state (the bundled missions stay outside it).
    """
    if ct <= 0.0:
        return 0.0

    def value_and_slope(lam_i):
        lam = mu_z + lam_i
        root = np.sqrt(mu * mu + lam * lam)
        return lam_i - ct / (2.0 * root), 1.0 + ct * lam / (2.0 * root**3)

    start = max(np.sqrt(ct / 2.0), ct / (2.0 * max(mu, 1e-6)))
    try:
        return float(newton(value_and_slope, start, tol=GLAUERT_TOLERANCE, max_iter=GLAUERT_MAX_ITERATIONS,
                            what="Glauert inflow", min_ratio=0.5))
    except ConvergenceError as failure:
        raise AircraftTrimError(f"Glauert inflow did not converge (C_T={ct:.4g}, mu={mu:.4g}, mu_z={mu_z:.4g})") from failure


def _layout_moments(aircraft: dict) -> list[int]:
    """Body moment components (0 roll, 1 pitch, 2 yaw) that close the balance for a layout."""
    lift = [r for r in aircraft["rotors"] if r["role"] == "lift"]
    if any(r["role"] == "antitorque" for r in aircraft["rotors"]):
        return [2]
    if len(lift) == 1:
        return []
    if len(lift) == 2:
        dx = abs(lift[0]["hub_position_m"][0] - lift[1]["hub_position_m"][0])
        return [1] if dx > min(r["radius_m"] for r in lift) else [2]
    return [0, 1, 2]


@dataclass
class _RotorState:
    rotor: dict
    omega_rad_s: float
    axis_b: np.ndarray
    r_bh: np.ndarray
    geometry: RotorGeometry

    @property
    def radius_m(self) -> float:
        return float(self.rotor["radius_m"])

    @property
    def sign(self) -> int:
        return 1 if self.rotor["rotation"] == "ccw" else -1


def _rotor_aero(state: _RotorState, thrust_n: float, r_gb: np.ndarray, flight: FlightCondition) -> dict:
    """Advance ratios, inflow, torque and power of one rotor at a given thrust and attitude."""
    rotor = state.rotor
    rho = flight.atmosphere.density_kg_m3
    radius = state.radius_m
    tip_speed = state.omega_rad_s * radius
    r_gh = r_gb @ state.r_bh
    v_h = -(r_gh.T @ flight.velocity_g)
    mu_x, mu_y = v_h[0] / tip_speed, v_h[1] / tip_speed
    mu_z = -v_h[2] / tip_speed
    area = np.pi * radius**2
    ct = thrust_n / (rho * area * tip_speed**2)
    mu = float(np.hypot(mu_x, mu_y))
    lam_i = glauert_inflow(ct, mu, mu_z)
    solidity = state.geometry.solidity
    cd0 = state.geometry.airfoil.cd0
    power = thrust_n * tip_speed * (INDUCED_POWER_FACTOR * lam_i + mu_z)
    power += rho * area * tip_speed**3 * solidity * cd0 * (1.0 + 4.65 * mu * mu) / 8.0
    return {
        "r_gh": r_gh,
        "mu_x": mu_x,
        "mu_y": mu_y,
        "mu_z": mu_z,
        "lambda_i": lam_i,
        "ct": ct,
        "power_W": power,
        "torque_Nm": power / state.omega_rad_s,
    }


def _residual(x, states, moments, aircraft, flight, weight_n, length_m) -> np.ndarray:
    pitch, roll = x[0], x[1]
    thrusts = x[2:]
    r_gb = frames.body_to_ground(pitch, roll)
    velocity = flight.velocity_g
    speed = float(np.linalg.norm(velocity))
    drag = 0.5 * flight.atmosphere.density_kg_m3 * speed**2 * aircraft["fuselage_drag_area_m2"]
    force = np.array([0.0, 0.0, -weight_n]) - (drag * velocity / speed if speed > 0 else 0.0)
    # m a_G: in steady flight a_G = 0 and x − 0.0 ≡ x, the steady balance bit for bit
    force = force - aircraft["gross_weight_kg"] * np.asarray(flight.acceleration_mps2, dtype=float)
    moment_b = np.zeros(3)
    for state, thrust in zip(states, thrusts):
        force = force + thrust * (r_gb @ state.axis_b)
        aero = _rotor_aero(state, thrust, r_gb, flight)
        position = np.asarray(state.rotor["hub_position_m"], dtype=float)
        moment_b += np.cross(position, thrust * state.axis_b) - state.sign * aero["torque_Nm"] * state.axis_b
    return np.concatenate([force / weight_n, moment_b[moments] / (weight_n * length_m)])


def _rotor_states(aircraft: dict, omega_scale: dict[str, float], rotor_speeds: dict[str, float]) -> list[_RotorState]:
    """Every rotor's speed (``rotor_speeds``, else the configured speed × ``omega_scale``), unit thrust axis
    a_i (body frame) and hub rotation R_BH."""
    states = []
    for rotor in aircraft["rotors"]:
        axis_b = np.asarray(rotor["thrust_axis_body"], dtype=float)
        axis_b = axis_b / np.linalg.norm(axis_b)
        omega = rotor_speeds.get(rotor["name"], rotor["omega_rad_s"] * omega_scale.get(rotor["name"], 1.0))
        states.append(_RotorState(rotor, omega, axis_b, frames.hub_to_body(axis_b), RotorGeometry.from_config(rotor)))
    return states


def _balance(aircraft: dict, flight: FlightCondition, states: list[_RotorState]) -> tuple[np.ndarray, int]:
    """(θ, φ, T_1 … T_n) of the balance and the Newton updates it took, from level attitude with the weight
    shared equally by the lift rotors (2 % of it on each other rotor)."""
    weight = aircraft["gross_weight_kg"] * G0_M_S2
    length = max(s.radius_m for s in states)
    moments = _layout_moments(aircraft)
    n_lift = sum(s.rotor["role"] == "lift" for s in states)
    x = np.concatenate([[0.0, 0.0], [weight / n_lift if s.rotor["role"] == "lift" else 0.02 * weight for s in states]])
    scale = np.concatenate([[1.0, 1.0], np.full(len(states), weight)])
    args = (states, moments, aircraft, flight, weight, length)
    try:
        solution = newton_fd(lambda v: (_residual(v, *args), None), x, steps=TRIM_FD_STEP * scale, tol=TRIM_TOLERANCE,
                             max_iter=TRIM_MAX_ITERATIONS, what="aircraft balance", rcond=TRIM_PINV_RCOND)
    except ConvergenceError as failure:
        raise AircraftTrimError(
            f"aircraft '{aircraft['name']}' did not trim at V_h={flight.forward_speed_mps} m/s, "
            f"V_c={flight.climb_speed_mps} m/s{_acceleration_text(flight)}: residuals {failure.value} (forces/W, moments/(W R)); inputs to check: "
            f"gross_weight_kg, fuselage_drag_area_m2, the rotors' hub_position_m and thrust_axis_body (force and "
            f"moment balance), and the segment's speeds"
        ) from failure
    return solution.x, solution.iterations


def _acceleration_text(flight: FlightCondition) -> str:
    """``, a=(x, y, z) m/s²`` of an accelerated flight for a message, "" in steady flight."""
    if not any(flight.acceleration_mps2):
        return ""
    return ", a=(" + ", ".join(f"{c:.4g}" for c in flight.acceleration_mps2) + ") m/s²"


def _check_thrusts(aircraft: dict, states: list[_RotorState], thrusts: np.ndarray) -> None:
    """Raise :class:`AircraftTrimError` naming the first rotor whose balancing thrust is not positive."""
    negative = [(s.rotor, float(t)) for s, t in zip(states, thrusts) if t <= 0.0]
    if negative:
        rotor, thrust = negative[0]
        balance = ("the lift rotors' torque: check its thrust_axis_body against the lift rotors' rotation (or a descent "
                   "steep enough to drive the lift rotors, autorotation, which NPS does not model)"
                   if rotor["role"] == "antitorque" else "weight, drag and moments: check its thrust_axis_body and "
                   "hub_position_m against the other rotors', gross_weight_kg, fuselage_drag_area_m2 and the segment's speeds")
        raise AircraftTrimError(
            f"aircraft '{aircraft['name']}': rotor '{rotor['name']}' ({rotor['role']}) would need a thrust of {thrust:.4g} N "
            f"along its thrust_axis_body {rotor['thrust_axis_body']} to balance {balance}")


def _trim_table_row(state: _RotorState, thrust: float, pitch: float, roll: float, flight: FlightCondition,
                    iterations: int) -> dict:
    """One rotor's row of the trim table (TRIM_COLUMNS) at the balanced attitude and thrust."""
    r_gb = frames.body_to_ground(pitch, roll)
    aero = _rotor_aero(state, thrust, r_gb, flight)
    hub = r_gb @ np.asarray(state.rotor["hub_position_m"], dtype=float)
    row = {
        "rotor": state.rotor["name"],
        "role": state.rotor["role"],
        "rotation_sign": np.int8(state.sign),
        "n_blades": np.int32(state.rotor["n_blades"]),
        "radius_m": state.radius_m,
        "omega_rad_s": state.omega_rad_s,
        "thrust_N": thrust,
        "roll_moment_Nm": 0.0,
        "pitch_moment_Nm": 0.0,
        "torque_Nm": aero["torque_Nm"],
        "power_W": aero["power_W"],
        "mu_x": aero["mu_x"],
        "mu_y": aero["mu_y"],
        "mu_z": aero["mu_z"],
        "lambda_i": aero["lambda_i"],
        "ct": aero["ct"],
        "tip_mach": state.omega_rad_s * state.radius_m / flight.atmosphere.speed_of_sound_mps,
        "hub_x_m": hub[0],
        "hub_y_m": hub[1],
        "hub_z_m": hub[2],
        "vel_x_mps": flight.velocity_g[0],
        "vel_y_mps": flight.velocity_g[1],
        "vel_z_mps": flight.velocity_g[2],
    }
    for i in range(3):
        for j in range(3):
            row[f"r_gh_{i}{j}"] = aero["r_gh"][i, j]
    row.update(
        density_kg_m3=flight.atmosphere.density_kg_m3,
        speed_of_sound_mps=flight.atmosphere.speed_of_sound_mps,
        pitch_rad=pitch,
        roll_rad=roll,
        flight_path_rad=flight.flight_path_rad,
        trim_iterations=np.int32(iterations),
    )
    return row


def trim_aircraft(aircraft: dict, flight: FlightCondition, omega_scale: dict[str, float] | None = None,
                  rotor_speeds: dict[str, float] | None = None) -> pd.DataFrame:
    """Trim one aircraft in steady flight; one row per rotor (columns: docs/reference/conventions.md).

    ``aircraft`` is a validated aircraft configuration; ``omega_scale`` optional per-rotor
    speed factors; ``rotor_speeds`` optional rotor speeds (rad/s) that replace the scaled
    configured ones (the rpm-control re-trim, :func:`nps.rotor.control.trim_rotor_speeds`). Raises
    :class:`AircraftTrimError` if the balance does not converge (tolerances: TRIM_* constants).
    """
    states = _rotor_states(aircraft, omega_scale or {}, rotor_speeds or {})
    x, iterations = _balance(aircraft, flight, states)
    _check_thrusts(aircraft, states, x[2:])
    pitch, roll = float(x[0]), float(x[1])
    return pd.DataFrame([_trim_table_row(state, float(thrust), pitch, roll, flight, iterations)
                         for state, thrust in zip(states, x[2:])])


def disk_flow_angle_deg(trim_row) -> float:
    """Angle of the free stream to the rotor plane, positive when it enters from below.

    atan2(−μ_z, sqrt(μ_x² + μ_y²)): a level rotor in a 6° descent gives +6°.
    """
    return float(np.degrees(np.arctan2(-trim_row["mu_z"], np.hypot(trim_row["mu_x"], trim_row["mu_y"]))))
