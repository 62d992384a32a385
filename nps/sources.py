"""Compact acoustic source lines of a rotor from its disk table and trim row.

Per blade (docs/conventions.md for frames and signs):

* the **lifting line** at the pitch axis (quarter chord) carries the force the blade exerts on
  the fluid, −(fx, fz) of the disk table: in the rotating frame (e_r, e_t, z_H), with e_t the
  blade's direction of motion, the force on the fluid per node is (0, +fx, −fz)·dr
  (fx opposes the motion on the blade, so the blade pushes the air forward);
* **thickness**, one of two models (:class:`ThicknessModel`):
  - ``dual_compact`` (default, Isom / Yang–Brentner–Walsh): two lines at chord fractions
    (0.13, 0.87) carrying ±ρ0 c0²·t(r)·dr along the chord (front line toward the leading edge,
    rear line toward the trailing edge), radiated by the same dipole kernel as the loading: a
    uniform pressure ρ0c² on the closed surface radiates exactly the thickness noise, and the
    section is split at maximum thickness;
  - ``compact_monopole``: the lifting-line nodes also carry the volume A·dr, A = 0.685·t·c
    (NACA 00xx section area; ANOPP2 / AcousticAnalogies.jl model).

Geometry of a node at chord offset d (positive toward the leading edge from the pitch axis),
radius r, flap β (up positive, hinge at ``hinge_offset_m`` = e), pitch θ (nose up), in the
rotating components (e_r, e_t, z_H) of the hub frame:

    q = (e + (r−e) cos β − d sin θ sin β,  d cos θ,  (r−e) sin β + d sin θ cos β)

with e_r = (cos ψ, s sin ψ, 0), e_t = de_r/dψ = (−sin ψ, s cos ψ, 0). Because de_r/dψ = e_t and
de_t/dψ = −e_r, d/dψ of a vector with rotating components (a, b, c) has components
(a' − b, b' + a, c'): velocities, accelerations, jerks and force rates are this operator
applied analytically for the rotation, with ψ-derivatives of the tabulated β, θ, fx, fz from
periodic 6th-order central differences (exact for a rigid rotor with constant loads). Ground
frame: y = hub + V t + R_GH q_H, v = V + Ω R_GH (Dq)_H, a = Ω² R_GH (D²q)_H, ...
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np
import pandas as pd

from nps.acoustics import LOADING, THICKNESS, AcousticsError, CompactSources
from nps.rotor import RotorMotion

DISK_COLUMNS = ("psi_rad", "r_m", "dr_m", "chord_m", "thickness_m", "theta_rad", "beta_rad", "fz_N_per_m", "fx_N_per_m")
DUAL_COMPACT = "dual_compact"
COMPACT_MONOPOLE = "compact_monopole"


@dataclass(frozen=True)
class ThicknessModel:
    """Thickness-noise model: ``kind`` in {"dual_compact", "compact_monopole"}.

    ``chord_fractions``: dual-compact line positions from the leading edge (fractions of chord);
    ``area_factor``: section area / (t·c) for the monopole (0.685 for NACA 00xx);
    ``pitch_axis_chord``: lifting line / pitch axis from the leading edge (fraction of chord).
    """

    kind: str = DUAL_COMPACT
    chord_fractions: tuple[float, float] = (0.13, 0.87)
    area_factor: float = 0.685
    pitch_axis_chord: float = 0.25

    def __post_init__(self):
        if self.kind not in (DUAL_COMPACT, COMPACT_MONOPOLE):
            raise AcousticsError(f"thickness model: kind '{self.kind}', expected '{DUAL_COMPACT}' or '{COMPACT_MONOPOLE}'")
        front, rear = self.chord_fractions
        if not 0.0 <= front < rear <= 1.0:
            raise AcousticsError(f"thickness model: chord_fractions {self.chord_fractions}, expected 0 <= front < rear <= 1")


def periodic_dpsi(values: np.ndarray, dpsi: float) -> np.ndarray:
    """d/dψ along axis 0 of periodic samples: 6th-order central differences."""
    w = (1.0 / 60.0, -3.0 / 20.0, 3.0 / 4.0)
    out = np.zeros_like(values)
    for k, wk in enumerate(w):
        shift = 3 - k
        out += wk * (np.roll(values, -shift, axis=0) - np.roll(values, shift, axis=0))
    return out / dpsi


def _rotating_derivative(comp: np.ndarray, dpsi: float) -> np.ndarray:
    """d/dψ of a vector given by rotating components (..., 3) = (e_r, e_t, z_H)."""
    d = periodic_dpsi(comp, dpsi)
    return np.stack([d[..., 0] - comp[..., 1], d[..., 1] + comp[..., 0], d[..., 2]], axis=-1)


def disk_arrays(disk: pd.DataFrame, what: str = "disk table") -> dict[str, np.ndarray]:
    """Disk table → (n_psi, n_r) arrays; checks columns, ψ-major order, uniform ψ grid, finiteness."""
    missing = [c for c in DISK_COLUMNS if c not in disk.columns]
    if missing:
        raise AcousticsError(f"{what}: missing column(s) {missing}")
    for c in DISK_COLUMNS:
        if not np.isfinite(disk[c].to_numpy(float)).all():
            raise AcousticsError(f"{what}: column '{c}' has non-finite values")
    psi_values = np.unique(disk["psi_rad"].to_numpy(float))
    n_psi = psi_values.size
    if len(disk) % n_psi:
        raise AcousticsError(f"{what}: {len(disk)} rows is not n_psi x n_r with n_psi = {n_psi}")
    n_r = len(disk) // n_psi
    out = {c: disk[c].to_numpy(float).reshape(n_psi, n_r) for c in DISK_COLUMNS}
    expected = 2.0 * np.pi * np.arange(n_psi) / n_psi
    if not np.allclose(out["psi_rad"], expected[:, None], atol=1e-9):
        raise AcousticsError(f"{what}: 'psi_rad' must be ψ-major with ψ_i = 2π i / {n_psi}")
    return out


def _blade_components(disk: Mapping[str, np.ndarray], model: ThicknessModel, hinge_offset_m: float,
                      rho0: float, c0: float):
    """Rotating-frame position and force-on-fluid components per line: lists of (n_psi, n_r, 3)."""
    r, dr, chord, thick = disk["r_m"], disk["dr_m"], disk["chord_m"], disk["thickness_m"]
    theta, beta = disk["theta_rad"], disk["beta_rad"]
    e = hinge_offset_m
    sb, cb, st, ct = np.sin(beta), np.cos(beta), np.sin(theta), np.cos(theta)

    def position(offset):
        return np.stack([e + (r - e) * cb - offset * st * sb, offset * ct, (r - e) * sb + offset * st * cb], axis=-1)

    lines = [(position(np.zeros_like(r)), np.stack([np.zeros_like(r), disk["fx_N_per_m"] * dr, -disk["fz_N_per_m"] * dr], axis=-1),
              LOADING, np.zeros(r.shape[1]))]
    if model.kind == DUAL_COMPACT:
        chord_dir = np.stack([-st * sb, ct, st * cb], axis=-1)
        push = (rho0 * c0 * c0 * thick * dr)[..., None] * chord_dir
        for fraction, sign in zip(model.chord_fractions, (1.0, -1.0)):
            lines.append((position((model.pitch_axis_chord - fraction) * chord), sign * push, THICKNESS, np.zeros(r.shape[1])))
    else:
        volume = model.area_factor * thick[0] * chord[0] * dr[0]
        lines[0] = lines[0][:3] + (volume,)
    return lines


def rotor_sources(disk: pd.DataFrame, motion: RotorMotion, *, thickness: ThicknessModel = ThicknessModel(),
                  hinge_offset_m: float = 0.0, rho0_kg_m3: float, c0_mps: float,
                  tau_range_s: tuple[float, float] | None = None) -> CompactSources:
    """Compact source lines of one rotor in the ground frame.

    ``tau_range_s=None``: periodic sources, blade 0 over one revolution starting at τ = 0 (the
    other B − 1 blades are implied by symmetry: identical loads vs ψ). Otherwise all blades at
    τ_i = i·T/n_psi covering ``tau_range_s`` (requires n_psi divisible by B so every blade sits on
    the table's ψ grid).
    """
    arrays = disk_arrays(disk)
    n_psi, n_r = arrays["r_m"].shape
    dpsi = 2.0 * np.pi / n_psi
    omega = motion.omega_rad_s
    if not omega > 0:
        raise AcousticsError(f"trim row: omega_rad_s must be positive, got {omega}")
    period = 2.0 * np.pi / omega
    lines = _blade_components(arrays, thickness, hinge_offset_m, rho0_kg_m3, c0_mps)

    pos_c, vel_c, acc_c, jerk_c, frc_c, frd_c, groups_d, volumes = [], [], [], [], [], [], [], []
    for q, g, group, volume in lines:
        d1 = _rotating_derivative(q, dpsi)
        d2 = _rotating_derivative(d1, dpsi)
        d3 = _rotating_derivative(d2, dpsi)
        pos_c.append(q)
        vel_c.append(omega * d1)
        acc_c.append(omega**2 * d2)
        jerk_c.append(omega**3 * d3)
        frc_c.append(g)
        frd_c.append(omega * _rotating_derivative(g, dpsi))
        groups_d.append(np.full(n_r, group, dtype=object))
        volumes.append(np.broadcast_to(volume, (n_r,)))
    # (n_psi, n_line*n_r, 3) rotating components
    stack = [np.concatenate(a, axis=1) for a in (pos_c, vel_c, acc_c, jerk_c, frc_c, frd_c)]
    group_names = np.concatenate(groups_d)
    volume = np.concatenate(volumes).astype(float)

    n_blades = motion.n_blades
    if tau_range_s is None:
        steps = np.arange(n_psi)
        blades = [0]
    else:
        if n_psi % n_blades:
            raise AcousticsError(f"disk table: n_psi = {n_psi} must be divisible by n_blades = {n_blades} for stationary observers")
        steps = np.arange(int(np.floor(tau_range_s[0] / period * n_psi)), int(np.ceil(tau_range_s[1] / period * n_psi)) + 1)
        blades = list(range(n_blades))
    tau = steps * period / n_psi
    s = motion.rotation_sign
    r_gh = motion.r_gh
    out = [[] for _ in range(6)]
    for k in blades:
        index = (steps + k * n_psi // n_blades) % n_psi
        psi = omega * tau + 2.0 * np.pi * k / n_blades
        e_r = np.stack([np.cos(psi), s * np.sin(psi), np.zeros_like(psi)], axis=-1)
        e_t = np.stack([-np.sin(psi), s * np.cos(psi), np.zeros_like(psi)], axis=-1)
        basis = np.stack([e_r, e_t, np.broadcast_to([0.0, 0.0, 1.0], e_r.shape)], axis=-1)  # (n_tau, 3 H, 3 comp)
        to_g = np.einsum("gh,thc->tgc", r_gh, basis)
        for slot, comp in enumerate(stack):
            vec = np.einsum("tgc,tnc->ntg", to_g, comp[index])
            if slot == 0:
                vec = vec + (motion.hub_position_m[None, :] + tau[:, None] * motion.velocity_mps[None, :])[None]
            elif slot == 1:
                vec = vec + motion.velocity_mps[None, None, :]
            out[slot].append(vec)
    arrays6 = [np.ascontiguousarray(np.concatenate(a, axis=0)) for a in out]
    names = np.tile(group_names, len(blades))
    volume = np.tile(volume, len(blades))
    groups = (LOADING, THICKNESS)
    dipole = np.array([groups.index(g) for g in names], dtype=np.int64)
    if thickness.kind == COMPACT_MONOPOLE:
        monopole = np.where(volume > 0, groups.index(THICKNESS), -1).astype(np.int64)
    else:
        monopole = np.full(names.size, -1, dtype=np.int64)
    return CompactSources(
        tau, *arrays6, volume, groups, dipole, monopole,
        period_s=period if tau_range_s is None else None,
        frame_velocity_mps=np.asarray(motion.velocity_mps, float) if tau_range_s is None else None,
        copies=n_blades if tau_range_s is None else 1,
    )
