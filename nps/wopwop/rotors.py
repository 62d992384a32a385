"""The rotors of a PSU-WOPWOP case as rows of NPS's trim table, so that NPS's own stages (HSI, metrics, tones) run
on the pressures of the case.

A rotor is a source group of :func:`nps.wopwop.run.source_containers`: the outermost container whose chain turns
(a CB with a nonzero Omega). From the case at t = 0: the hub is the origin of the turning CB's frame, the shaft axis
that CB's axis in G, Ω = |Omega|, the blades the patch-bearing containers of the group, the radius the farthest
point of their zones from the shaft axis (a lifting line's end node counts with half its span), the velocity the hub's. From the loads over one period of the data (their key
grid, or the container's dTau over one turn for constant loads): the thrust T = ⟨Σ F·z_H⟩ and the torque
Q = −s⟨Σ ((y − hub) × F)·z_H⟩ of the force F on the blades (the loading zones only: zones written with
``loadingOutput`` = 1 carry thickness sources), z_H the shaft axis turned to the thrust's side, s = +1 when the
rotor turns counterclockwise about z_H. Quantities a case does not hold are set to NPS's neutral values and said
so: induced inflow λ_i = 0, body attitude 0, role ``lift``.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from nps.noise.acoustics import LOADING
from nps.rotor.trim import TRIM_COLUMNS
from nps.wopwop.errors import WopwopError
from nps.wopwop.motion import apply, chain_motion
from nps.wopwop.run import SourceContainer, pair_points, pair_timing, spins
from nps.wopwop.sources import zone_outline


def _spin_index(source: SourceContainer) -> int:
    return next(k for k, cb in enumerate(source.chain) if spins(cb))


def _one_period_steps(source: SourceContainer, timing) -> tuple[np.ndarray, np.ndarray]:
    """Source steps and times over one period of the data (periodic keys), the data's keys (aperiodic), or one
    turn at the container's dTau (constant data)."""
    if timing.kind == "periodic":
        steps = np.arange(timing.n_rows)
        return steps, steps * timing.dtau_s
    if timing.kind == "aperiodic":
        steps = np.arange(timing.n_rows)
        return steps, timing.t0_s + steps * timing.dtau_s
    spin = source.chain[_spin_index(source)]
    period = 2.0 * math.pi / abs(float(spin.omega_rad_s))
    step = source.d_tau_s or period / 360.0
    n = max(8, int(round(period / step)))
    steps = np.arange(n)
    return steps, steps * (period / n)


def _loads(source: SourceContainer, rho0: float, hub_chain: tuple):
    """(mean force on the blades (3,), mean moment about the moving hub (3,), the zones' outline points relative to
    the hub at the first step (n, 3), :func:`nps.wopwop.sources.zone_outline`) of one source container: loading
    zones only for the loads.
    ``hub_chain``: the CBs down to the turning one (the hub frame's origin is the hub)."""
    force, moment, points = np.zeros(3), np.zeros(3), []
    for pair in source.patches:
        timing = pair_timing(pair)
        steps, tau = _one_period_steps(source, timing)
        hub = chain_motion(hub_chain, tau).translation[0][:, None, :]
        for part, group in pair_points(source, pair, steps, tau, timing, rho0):
            offset = part.kinematics[0] - hub
            if group == LOADING:
                on_blade = -part.force_N
                force += on_blade.sum(axis=1).mean(axis=0)
                moment += np.cross(offset, on_blade).sum(axis=1).mean(axis=0)
        start = chain_motion(source.chain, tau[:1])
        points += [apply(start, zone_outline(zone))[0, 0] - hub[0] for zone in pair.geometry.zones]
    return force, moment, np.concatenate(points)


def has_rotor(sources: tuple[SourceContainer, ...]) -> bool:
    """Whether any source container's chain turns (a CB with a nonzero Omega)."""
    return any(spins(cb) for source in sources for cb in source.chain)


def rotor_rows(sources: tuple[SourceContainer, ...], rho0: float, c0: float) -> pd.DataFrame:
    """One trim-table row (:data:`nps.rotor.trim.TRIM_COLUMNS`) per rotor of the case (module doc); refuses a case
    without any turning container (NPS's rotor stages need a rotor)."""
    rotors = [name for name in dict.fromkeys(s.rotor for s in sources)
              if any(spins(cb) for s in sources if s.rotor == name for cb in s.chain)]
    if not rotors:
        raise WopwopError("no container of the case turns (a CB with a nonzero Omega): NPS's rotor stages need a rotor")
    return pd.DataFrame([_rotor_row(name, [s for s in sources if s.rotor == name], rho0, c0) for name in rotors],
                        columns=list(TRIM_COLUMNS))


def _rotor_row(name: str, group: list[SourceContainer], rho0: float, c0: float) -> dict:
    first = group[0]
    k = _spin_index(first)
    spin = first.chain[k]
    frame = chain_motion(first.chain[:k + 1], np.zeros(1))
    hub, velocity = frame.translation[0, 0], frame.translation[1, 0]
    outer = chain_motion(first.chain[:k], np.zeros(1)).rotation[0, 0]
    axis = outer @ (np.asarray(spin.axis_value, dtype=float) / np.linalg.norm(spin.axis_value))
    loads = [_loads(source, rho0, first.chain[:k + 1]) for source in group]
    force, moment = sum(f for f, _, _ in loads), sum(m for _, m, _ in loads)
    points = np.concatenate([p for _, _, p in loads])
    z_h = axis if force @ axis >= 0.0 else -axis
    omega_signed = float(spin.omega_rad_s) * float(np.sign(axis @ z_h))
    sign = 1 if omega_signed > 0 else -1
    radial = points - np.outer(points @ z_h, z_h)
    radius = float(np.linalg.norm(radial, axis=1).max())
    x_h = radial[int(np.argmax(np.linalg.norm(radial, axis=1)))] / radius
    r_gh = np.column_stack([x_h, np.cross(z_h, x_h), z_h])
    omega = abs(float(spin.omega_rad_s))
    thrust, torque = float(force @ z_h), float(-sign * (moment @ z_h))
    v_h = -r_gh.T @ velocity
    tip = omega * radius
    row = {"rotor": name, "role": "lift", "rotation_sign": np.int8(sign), "n_blades": np.int32(len(group)),
           "radius_m": radius, "omega_rad_s": omega, "thrust_N": thrust, "roll_moment_Nm": 0.0, "pitch_moment_Nm": 0.0,
           "torque_Nm": torque, "power_W": torque * omega, "mu_x": v_h[0] / tip, "mu_y": v_h[1] / tip, "mu_z": -v_h[2] / tip,
           "lambda_i": 0.0, "ct": thrust / (rho0 * math.pi * radius**2 * tip**2), "tip_mach": tip / c0,
           "hub_x_m": hub[0], "hub_y_m": hub[1], "hub_z_m": hub[2],
           "vel_x_mps": velocity[0], "vel_y_mps": velocity[1], "vel_z_mps": velocity[2],
           "density_kg_m3": rho0, "speed_of_sound_mps": c0, "pitch_rad": 0.0, "roll_rad": 0.0,
           "flight_path_rad": math.atan2(velocity[2], math.hypot(velocity[0], velocity[1])), "trim_iterations": np.int32(0)}
    row.update({f"r_gh_{i}{j}": float(r_gh[i, j]) for i in range(3) for j in range(3)})
    return row
