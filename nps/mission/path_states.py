"""Trim states that cover a flight path: a small set of quasi-static states, each time's bracketing states and
interpolation weights (docs/reference/paths.md, "States").

Quasi-static equivalence. Every force on the aircraft but gravity (rotor thrusts along body axes, fuselage drag
along −V̂) balances m f, f = a + g ẑ the specific force (nps.rotor.trim). The rotors' state (advance ratios,
inflow, thrust, torque) depends only on the speed V, the rotor speed and the components of f in the path axes
(V̂, the upward normal n̂, the starboard ŝ): f_t = f·V̂, f_n = f·n̂, f_s = f·ŝ; the aircraft's attitude against
gravity does not enter. A steady flight at the flight-path angle γ_e has f_t = g sin γ_e, so a flight with
f_t = g sin γ + a_x is rotor-equivalent to the steady flight at the effective flight-path angle

    sin γ_e = sin γ + a_x / g                                                    (1)

(the longitudinal force balance along the path; to first order γ_e ≈ γ + asin(a_x/g), the quasi-static
acoustic-mapping relation of Schmitz, Gopalan & Sim 2002), with the normal load n_v = f_n/g in place of cos γ_e
and the lateral n_s = f_s/g. A state is therefore the point

    (μ, γ_e, Δn_v = n_v − cos γ_e, n_s, Ω/Ω_0)

with μ = V/(Ω R) of the reference (first) rotor at the rotor-speed fraction Ω/Ω_0; steady flight has Δn_v = n_s = 0.
States are points of a lattice with the tolerances as spacing (so equal states of two paths or procedures get
equal keys); the trim input of a state is its canonical flight: speed V at γ_e, a_x = 0, the normal and lateral
acceleration Δn_v g n̂ + n_s g ŝ, every rotor at the fraction Ω/Ω_0.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass

import numpy as np

from nps.core.atmosphere import AtmosphereState
from nps.mission.paths import PathHistory
from nps.rotor.trim import G0_M_S2, FlightCondition

# a sample within this many lattice units of its state's point takes that state alone (rounding of the scaling)
WEIGHT_FLOOR = 1e-9
COORDINATES = ("advance_ratio", "effective_flight_path_deg", "normal_load_increment", "lateral_load_factor",
               "rotor_speed_fraction")


@dataclass(frozen=True)
class StateTolerances:
    """Lattice spacing of the state coordinates (:data:`COORDINATES`): μ, γ_e (deg), Δn_v, n_s, Ω/Ω_0."""

    advance_ratio: float
    flight_path_deg: float
    load_factor: float
    rotor_speed_fraction: float

    @property
    def spacing(self) -> np.ndarray:
        return np.array([self.advance_ratio, self.flight_path_deg, self.load_factor, self.load_factor,
                         self.rotor_speed_fraction])


def effective_flight_path(tangential_g: np.ndarray) -> np.ndarray:
    """γ_e (rad) of eq. (1) from f_t/g = sin γ + a_x/g (clipped to ±1: |f_t| > g is no steady flight)."""
    return np.arcsin(np.clip(tangential_g, -1.0, 1.0))


def state_coordinates(history: PathHistory, tip_speed_mps: float) -> np.ndarray:
    """(n, 5) state coordinates (:data:`COORDINATES`) of every sample; ``tip_speed_mps`` Ω_0 R of the
    reference rotor at the nominal rotor speed."""
    gamma_e = effective_flight_path(history.tangential_g)
    fraction = history.rotor_speed_fraction
    return np.column_stack([history.speed_mps / (fraction * tip_speed_mps), np.degrees(gamma_e),
                            history.normal_g - np.cos(gamma_e), history.lateral_g, fraction])


@dataclass(frozen=True)
class PathStates:
    """States of a path: ``lattice`` (m, 5) integer indices and ``values`` (m, 5) coordinates of the states in
    order of first visit; per sample the state it rounds to (``state``), its bracketing neighbour
    (``neighbour``, equal to ``state`` when none) and the neighbour's weight ``weight`` in [0, 1]."""

    lattice: np.ndarray
    values: np.ndarray
    state: np.ndarray
    neighbour: np.ndarray
    weight: np.ndarray


def choose_states(coordinates: np.ndarray, tolerances: StateTolerances) -> PathStates:
    """States covering the samples: each sample rounds to the nearest lattice point (spacing: the tolerances);
    equal points are one state. The runs of equal states along the path bracket each sample with the state
    of the previous or next run: the weight w = clip((u − A)·(B − A)/|B − A|², 0, 1) in lattice units
    (u the sample, A its state, B the neighbour that gives the larger w), so that (1 − w) A + w B follows
    the path between the lattice points (w below WEIGHT_FLOOR: 0)."""
    scaled = coordinates / tolerances.spacing
    lattice = np.rint(scaled).astype(np.int64)
    keys, first, state = np.unique(lattice, axis=0, return_index=True, return_inverse=True)
    order = np.argsort(first)  # states numbered in order of first visit
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    state = rank[state.reshape(-1)]
    run_start = np.flatnonzero(np.concatenate([[True], state[1:] != state[:-1]]))
    run_of = np.cumsum(np.concatenate([[False], state[1:] != state[:-1]]))
    run_state = state[run_start]
    points = keys[order].astype(float)
    neighbour, weight = state.copy(), np.zeros(len(state))
    for offset in (-1, 1):
        other_run = np.clip(run_of + offset, 0, len(run_start) - 1)
        other = run_state[other_run]
        step = points[other] - points[state]
        length2 = np.einsum("ij,ij->i", step, step)
        along = np.einsum("ij,ij->i", scaled - points[state], step) / np.where(length2 > 0, length2, 1.0)
        candidate = np.where((length2 > 0) & (along > WEIGHT_FLOOR), np.clip(along, 0.0, 1.0), 0.0)
        better = candidate > weight
        neighbour, weight = np.where(better, other, neighbour), np.where(better, candidate, weight)
    return PathStates(keys[order], keys[order] * tolerances.spacing, state, neighbour, weight)


def _clean(value: float) -> float:
    """``value`` with a negative zero made positive (canonical text of the key, bit-identical steady input)."""
    return value + 0.0


def state_flight(values: np.ndarray, tip_speed_mps: float, atmosphere: AtmosphereState) -> tuple[FlightCondition, float]:
    """The canonical flight of a state (module docstring) and its rotor-speed fraction: speed
    V = μ (Ω/Ω_0) Ω_0 R along γ_e, acceleration Δn_v g n̂ + n_s g ŝ in the trim's ground frame G
    (n̂ = (−sin γ_e, 0, cos γ_e), ŝ = (0, −1, 0))."""
    mu, gamma_e_deg, dn_v, n_s, fraction = (float(v) for v in values)
    gamma_e = math.radians(gamma_e_deg)
    speed = mu * fraction * tip_speed_mps
    acceleration = (_clean(-math.sin(gamma_e) * dn_v * G0_M_S2), _clean(-n_s * G0_M_S2),
                    _clean(math.cos(gamma_e) * dn_v * G0_M_S2))
    return FlightCondition(speed * math.cos(gamma_e), _clean(speed * math.sin(gamma_e)), atmosphere, acceleration), fraction


def state_speeds(flight: FlightCondition, fraction: float, rotors: list[str]) -> dict:
    """A state as a mission segment's speeds entry for the trim (nps.stages.trim): forward and climb speed,
    ``rotor_omega_scale`` (the fraction for every rotor in ``rotors``) and ``acceleration_mps2`` (G)."""
    return {"forward_speed_mps": flight.forward_speed_mps, "climb_speed_mps": flight.climb_speed_mps,
            "rotor_omega_scale": {name: fraction for name in rotors}, "acceleration_mps2": list(flight.acceleration_mps2)}


def state_key(flight: FlightCondition, fraction: float) -> str:
    """Deterministic key of a state's trim input: ``s`` + 12 hex digits of the SHA-1 of its canonical JSON
    (speeds, acceleration and rotor-speed fraction rounded to 1e-9; the atmosphere is the campaign's)."""
    fields = {"forward_speed_mps": flight.forward_speed_mps, "climb_speed_mps": flight.climb_speed_mps,
              "acceleration_mps2": list(flight.acceleration_mps2), "rotor_speed_fraction": fraction}
    text = json.dumps(_round(fields), sort_keys=True, separators=(",", ":"), allow_nan=False)
    return "s" + hashlib.sha1(text.encode()).hexdigest()[:12]


def _round(value):
    if isinstance(value, float):
        return _clean(round(value, 9))
    if isinstance(value, dict):
        return {k: _round(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_round(v) for v in value]
    return value
