"""Rotor control modes: what is trimmed, and by which control, for one rotor.

- ``collective`` (default, :func:`default_mode`): collective and cyclic pitch trimmed to the thrust and
  hub-moment targets at the given rotor speed (:func:`nps.rotor.bet.trim_rotor`, thesis Fig. 4.3). With
  ``flapping: false`` (rigid blades, no cyclic: a propeller) only the collective is trimmed,
  to the thrust, and the hub moments are whatever the loads give (reported, not trimmed).
- ``collective_only``: the collective alone trimmed to the thrust, cyclic zero, the flapping free
  (a teetering rotor's teeter with its δ3 coupling) and the hub moments the answer: a tail rotor as
  flown, which has no cyclic. The default of an antitorque rotor with a teetering hub.
- ``rpm``: fixed blade pitch θ0 (``pitch_deg`` at 75 % radius), no cyclic; the rotor speed Ω
  is trimmed so that the thrust meets the target. The free stream is held: the advance
  ratios scale as μ = V/(ΩR), so μ Ω stays that of the operating point.
- ``fixed``: given θ0 and Ω, nothing trimmed; the thrust, torque and power are the answer
  (:func:`nps.rotor.bet.rotor_loads`). The operating point's thrust target is not used.

``flapping`` (default true) applies to every mode: false holds β ≡ 0.

The one-control trims (Ω → T, θ0 → T) are secant iterations on the thrust residual to
|T − T*| ≤ tol_rel |T*|, the inflow (and flapping) re-solved at every evaluation. Ω starts
at the operating point's speed and its T ∝ Ω² correction Ω √(T*/T); θ0 at 0.10 and 0.11 rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable, Mapping

import numpy as np
import pandas as pd

from nps.core.solvers import ConvergenceError, secant
from nps.rotor.bet import MAX_CONTROL_RAD, Controls, DiskGrid, RotorTrim, TrimError, rotor_loads, trim_rotor
from nps.rotor.geometry import TEETERING, OperatingPoint, RotorGeometry

MODES = ("collective", "collective_only", "rpm", "fixed")
TRIMMED_PITCH = ("collective", "collective_only")  # the modes whose pitch the trim sets (no pitch_deg)
_MAX_ITERATIONS = 30  # load evaluations of a one-control secant trim (nps.core.solvers.secant)
_THETA_START_RAD = 0.1


def default_mode(rotor: Mapping) -> str:
    """The control of a ``rotors[]`` entry that names none: ``collective_only`` for an antitorque rotor with a
    teetering hub (a tail rotor has no cyclic: its teeter is free, δ3 acting), else ``collective``."""
    teetering_tail = rotor.get("role") == "antitorque" and rotor.get("hub") == TEETERING
    return "collective_only" if teetering_tail else "collective"


@dataclass(frozen=True)
class RotorControl:
    """Control mode of one rotor; ``pitch_rad`` θ0 at 75 % radius for ``rpm`` and ``fixed``."""

    mode: str = "collective"
    pitch_rad: float | None = None
    flapping: bool = True

    def __post_init__(self):
        if self.mode not in MODES:
            raise ValueError(f"control: expected one of {MODES}, got {self.mode!r}")
        if self.mode in TRIMMED_PITCH and self.pitch_rad is not None:
            raise ValueError(f"control pitch_deg: expected none with control '{self.mode}' (the trim sets the pitch)")
        if self.mode not in TRIMMED_PITCH and not (self.pitch_rad is not None and math.isfinite(self.pitch_rad)):
            raise ValueError(f"control pitch_deg: required (a finite number) with control '{self.mode}'")

    @classmethod
    def from_config(cls, rotor: Mapping) -> "RotorControl":
        """From a validated ``rotors[]`` entry: ``control`` (:func:`default_mode` without one), ``pitch_deg``,
        ``flapping``."""
        pitch = rotor.get("pitch_deg")
        return cls(str(rotor.get("control", default_mode(rotor))), None if pitch is None else math.radians(float(pitch)),
                   bool(rotor.get("flapping", True)))


@dataclass(frozen=True)
class RotorSolution:
    """Loads of one rotor under its control mode, and the operating point they belong to
    (for ``rpm`` the trimmed rotor speed and the advance ratios at it)."""

    result: RotorTrim
    operating_point: OperatingPoint
    control: RotorControl

    def summary(self) -> pd.DataFrame:
        """The rotor loads summary (:meth:`RotorTrim.summary`) plus the rotor speed."""
        extra = pd.DataFrame({"quantity": ["omega_rad_s"], "value": np.array([self.operating_point.omega_rad_s]),
                              "unit": ["rad/s"]})
        return pd.concat([self.result.summary(), extra], ignore_index=True)


def at_rotor_speed(op: OperatingPoint, omega_rad_s: float) -> OperatingPoint:
    """``op`` at another rotor speed with the same free stream: μ_i Ω held."""
    scale = op.omega_rad_s / omega_rad_s
    return replace(op, omega_rad_s=omega_rad_s, mu_x=op.mu_x * scale, mu_y=op.mu_y * scale, mu_z=op.mu_z * scale)


def _secant(evaluate: Callable[[float], RotorTrim], u0: float, first: RotorTrim, u1: float, target: float,
            tol: float, what: str, name: str) -> tuple[float, RotorTrim]:
    """Control u with |thrust − target| ≤ tol (N) by the secant method from (u0, ``first``) and u1."""
    try:
        root = secant(evaluate, u0, first, u1, target=target, tol=tol, max_iter=_MAX_ITERATIONS, what=f"{what} trim",
                      value=lambda result: result.totals.thrust_N)
    except ConvergenceError as failure:
        raise TrimError(f"rotor '{name}': {what} trim did not reach the thrust target {target:.6g} N within {tol:.3g} "
                        f"N in {_MAX_ITERATIONS} iterations (last {what} {failure.x:.6g}, thrust {failure.value:.6g} N)"
                        ) from failure
    return root.x, root.payload


# usual ranges of the inputs a failed rotor solution names (likely_inputs): outside, a unit error is likely
TIP_SPEED_RANGE_MPS = (30.0, 330.0)  # ΩR: small rigs to transonic tips; ΩR/(2π) × 60 rpm typed as rad/s exceeds it
CHORD_RADIUS_RANGE = (0.01, 0.25)  # c/R of helicopter, tail, propeller and rig blades; a chord in mm exceeds it
DENSITY_RANGE_KG_M3 = (0.05, 10.0)  # air at altitude to heavy-gas tunnels (nps.app.validity.check_atmosphere)


def likely_inputs(geometry: RotorGeometry, op: OperatingPoint) -> str:
    """The inputs a failed rotor solution most likely comes from, for its message (which names the rotor
    already): rotor speed (with the tip speed), chord, radius and density, each marked where it lies outside
    its usual range (a speed in rpm, a chord in mm), and the settings to change."""
    tip_speed, chord_ratio = op.omega_rad_s * geometry.radius_m, geometry.chord_m / geometry.radius_m
    notes = []
    if not TIP_SPEED_RANGE_MPS[0] <= tip_speed <= TIP_SPEED_RANGE_MPS[1]:
        notes.append(f"tip speed omega_rad_s x radius_m = {tip_speed:.4g} m/s is outside the usual "
                     f"{TIP_SPEED_RANGE_MPS[0]:g}-{TIP_SPEED_RANGE_MPS[1]:g} m/s (omega in rpm? "
                     f"{op.omega_rad_s:.4g} rpm would be {op.omega_rad_s * math.pi / 30.0:.4g} rad/s)")
    if not CHORD_RADIUS_RANGE[0] <= chord_ratio <= CHORD_RADIUS_RANGE[1]:
        notes.append(f"chord {geometry.chord_m:.4g} m is {chord_ratio:.3g} R, outside the usual "
                     f"{CHORD_RADIUS_RANGE[0]:g}-{CHORD_RADIUS_RANGE[1]:g} R (chord in mm?)")
    if not DENSITY_RANGE_KG_M3[0] <= op.density_kg_m3 <= DENSITY_RANGE_KG_M3[1]:
        notes.append(f"density {op.density_kg_m3:.4g} kg/m³ is outside {DENSITY_RANGE_KG_M3[0]:g}-"
                     f"{DENSITY_RANGE_KG_M3[1]:g} kg/m³ (g/m³?)")
    found = "; ".join(notes) if notes else "each within its usual range: check the thrust target and the pitch"
    return (f"its inputs: omega_rad_s {op.omega_rad_s:.6g} rad/s, chord {geometry.chord_m:.4g} m, "
            f"radius {geometry.radius_m:.4g} m, density {op.density_kg_m3:.4g} kg/m³, thrust target {op.thrust_N:.6g} N: "
            f"{found}; settings to change: the rotor's omega_rad_s, chord_m, radius_m, pitch_deg or control, the "
            f"condition's atmosphere or thrust_N")


def solve_rotor(geometry: RotorGeometry, op: OperatingPoint, grid: DiskGrid, control: RotorControl, *,
                tol_rel: float = 1e-3, tip_loss: bool = True) -> RotorSolution:
    """Blade loads of one rotor under ``control`` (module docstring) at the operating point ``op``.

    ``op.thrust_N`` is the target of ``collective`` and ``rpm``; ``op.omega_rad_s`` the rotor
    speed of ``collective`` and ``fixed`` and the start value of ``rpm``. A solution that does not
    converge raises :class:`nps.rotor.bet.TrimError` naming the likely inputs (:func:`likely_inputs`).
    """
    if not 0.0 < tol_rel < 0.1:
        raise ValueError(f"solve_rotor: tol_rel: expected 0 < tol_rel < 0.1, got {tol_rel!r}")
    try:
        return _solve(geometry, op, grid, control, tol_rel, tip_loss)
    except TrimError as error:
        raise TrimError(f"{error}; {likely_inputs(geometry, op)}") from error


def _bounded_collective(geometry: RotorGeometry, op: OperatingPoint, loads: Callable[[float], RotorTrim]
                        ) -> Callable[[float], RotorTrim]:
    """``loads`` of θ0 refusing a collective outside the trim's search bound |θ0| < MAX_CONTROL_RAD."""
    def bounded(theta0: float) -> RotorTrim:
        if not abs(theta0) < MAX_CONTROL_RAD:
            raise TrimError(f"rotor '{geometry.name}': collective trim left the control bound |theta0| < "
                            f"{MAX_CONTROL_RAD:g} rad (theta0 {theta0:.4g} rad = {math.degrees(theta0):.4g} deg) before "
                            f"reaching the thrust target {op.thrust_N:.6g} N: the rotor cannot give it at "
                            f"{op.omega_rad_s:.6g} rad/s")
        return loads(theta0)
    return bounded


def _solve(geometry: RotorGeometry, op: OperatingPoint, grid: DiskGrid, control: RotorControl, tol_rel: float,
           tip_loss: bool) -> RotorSolution:
    """:func:`solve_rotor` without the input hints."""
    if control.mode == "collective" and control.flapping:
        return RotorSolution(trim_rotor(geometry, op, grid, tol_rel=tol_rel, tip_loss=tip_loss), op, control)

    def loads(theta0: float, point: OperatingPoint) -> RotorTrim:
        return rotor_loads(geometry, point, grid, Controls(theta0), tip_loss=tip_loss, flapping=control.flapping)

    if control.mode == "fixed":
        return RotorSolution(loads(control.pitch_rad, op), op, control)
    target, tol = op.thrust_N, tol_rel * abs(op.thrust_N)
    if target <= 0.0:
        raise ValueError(f"rotor '{geometry.name}': operating point thrust_N: expected a positive thrust target for "
                         f"control '{control.mode}', got {target!r}")
    if control.mode == "rpm":
        first = loads(control.pitch_rad, op)
        thrust0 = first.totals.thrust_N
        if not thrust0 > 0.0:
            raise TrimError(f"rotor '{geometry.name}': pitch {math.degrees(control.pitch_rad):.3g} deg gives no positive "
                            f"thrust ({thrust0:.4g} N) at {op.omega_rad_s:.4g} rad/s; rpm control cannot reach the target")
        omega, result = _secant(lambda w: loads(control.pitch_rad, at_rotor_speed(op, w)), op.omega_rad_s, first,
                                op.omega_rad_s * math.sqrt(target / thrust0), target, tol, "rotor speed", geometry.name)
        return RotorSolution(result, at_rotor_speed(op, omega), control)
    # collective without flapping, or collective_only: θ0 alone, from 0.1 rad and a 0.01 rad step
    _, result = _secant(_bounded_collective(geometry, op, lambda t: loads(t, op)), _THETA_START_RAD,
                        loads(_THETA_START_RAD, op), _THETA_START_RAD + 0.01, target, tol, "collective", geometry.name)
    return RotorSolution(result, op, control)


def trim_rotor_speeds(aircraft: Mapping, flight, omega_scale: Mapping[str, float] | None, grid: DiskGrid,
                      tol_rel: float = 1e-3, max_iterations: int = 20) -> pd.DataFrame:
    """Aircraft trim (:func:`nps.rotor.trim.trim_aircraft`) with the speeds of the ``rpm``-controlled
    rotors solved by the blade-element loads: the rotor-speed re-trim of the trim stage.

    The aircraft balance gives every rotor's thrust at the current speeds; each ``rpm`` rotor's
    Ω is then solved to that thrust at its fixed pitch (:func:`solve_rotor`, tolerance
    ``tol_rel``/4) and the aircraft re-trimmed at the new speeds (they change the momentum
    torques, hence the thrust shares). Stops when no speed moves by more than ``tol_rel``/8
    relative: the loads at the table's Ω then meet its thrust to ``tol_rel`` (thrust ∝ Ω²).
    Without ``rpm`` rotors this is :func:`nps.rotor.trim.trim_aircraft` itself (same table).
    """
    from nps.rotor.trim import trim_aircraft, trim_row

    controlled = {r["name"]: r for r in aircraft["rotors"] if r.get("control", "collective") == "rpm"}
    speeds: dict[str, float] = {}
    for _ in range(max_iterations):
        table = trim_aircraft(aircraft, flight, omega_scale, speeds)
        if not controlled:
            return table
        solved = {}
        for name, rotor in controlled.items():
            row = trim_row(table, name)
            solution = solve_rotor(RotorGeometry.from_config(rotor), OperatingPoint.from_trim_row(row), grid,
                                   RotorControl.from_config(rotor), tol_rel=tol_rel / 4,
                                   tip_loss=bool(rotor.get("tip_loss", True)))
            solved[name] = solution.operating_point.omega_rad_s
        moved = max(abs(solved[n] - speeds.get(n, trim_row(table, n)["omega_rad_s"])) / solved[n] for n in solved)
        speeds = solved
        if moved <= tol_rel / 8:
            return trim_aircraft(aircraft, flight, omega_scale, speeds)
    raise TrimError(f"aircraft '{aircraft['name']}': rotor speeds of the rpm-controlled rotors {sorted(controlled)} did "
                    f"not settle in {max_iterations} aircraft re-trims (last change {moved:.3g} relative)")


def loads_at_trim(geometry: RotorGeometry, op: OperatingPoint, grid: DiskGrid, control: RotorControl,
                  tol_rel: float = 1e-3, tip_loss: bool = True) -> RotorSolution:
    """The loads stage's solution at one trim-table operating point ``op``.

    ``collective`` and ``fixed``: :func:`solve_rotor`. ``rpm``: the table's Ω is already the
    solved speed (:func:`trim_rotor_speeds`, or the rig set-up), so the loads are taken
    at it with the fixed pitch — every later stage reads the same Ω from the table — and must
    meet the table's thrust to ``tol_rel``; a table not trimmed for rpm control fails here.
    """
    if control.mode != "rpm":
        return solve_rotor(geometry, op, grid, control, tol_rel=tol_rel, tip_loss=tip_loss)
    solution = solve_rotor(geometry, op, grid, replace(control, mode="fixed"), tol_rel=tol_rel, tip_loss=tip_loss)
    thrust = solution.result.totals.thrust_N
    if not abs(thrust - op.thrust_N) <= tol_rel * abs(op.thrust_N):
        raise TrimError(f"rotor '{geometry.name}': rpm control: the trim table's rotor speed {op.omega_rad_s:.6g} rad/s "
                        f"gives {thrust:.6g} N, not its thrust {op.thrust_N:.6g} N within {tol_rel:.3g}; the trim "
                        f"table was not trimmed for rpm control (trim stage, nps.rotor.control.trim_rotor_speeds)")
    return RotorSolution(solution.result, op, control)
