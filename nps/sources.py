"""Compact acoustic source lines of a rotor from its disk table and trim row.

Per blade (docs/conventions.md for frames and signs):

* the **lifting line** at the pitch axis (quarter chord) carries the force the blade exerts on
  the fluid, −(fx, fz) of the disk table: in the rotating frame (e_r, e_t, z_H), with e_t the
  blade's direction of motion, the force on the fluid per node is (0, +fx, −fz)·dr
  (fx opposes the motion on the blade, so the blade pushes the air forward);
* **thickness**, one of two models (:class:`ThicknessModel`):
  - ``dual_compact`` (default): two lines at chord fractions (0.13, 0.87) from the leading edge,
    radiated by the same dipole kernel as the loading. Each line carries the force on the fluid
    ±ρ0 (A/D) (v·e_c) v dr (front line +, rear line −), v the line's own velocity relative to the
    medium (ground frame), e_c the chord direction toward the leading edge, A the section area,
    D the line separation. In the compact limit of a section in steady motion this is exactly the
    compact monopole ρ0 A dr ∂²/∂t²[1/(4π r|1−M_r|)]; at finite chord it is that monopole
    averaged over a box-shaped chordwise thickness distribution (docs/models/acoustics.md has the
    derivation and why the thesis' ±ρ0c²·t·dr along the chord was rejected);
  - ``compact_monopole``: the lifting-line nodes also carry the volume A·dr
    (ANOPP2 / AcousticAnalogies.jl model).
  A = area_factor·t·c (0.685 for NACA 00xx sections).

Geometry of a node at chord offset d (positive toward the leading edge from the pitch axis),
radius r, flap β (up positive, hinge at ``hinge_offset_m`` = e), pitch θ (nose up), in the
rotating components (e_r, e_t, z_H) of the hub frame:

    q = (e + (r−e) cos β − d sin θ sin β,  d cos θ,  (r−e) sin β + d sin θ cos β)

with e_r = (cos ψ, s sin ψ, 0), e_t = de_r/dψ = (−sin ψ, s cos ψ, 0). Because de_r/dψ = e_t and
de_t/dψ = −e_r, d/dψ of a vector with rotating components (a, b, c) has components
(a' − b, b' + a, c'): velocities, accelerations, jerks and force rates are this operator
applied analytically for the rotation, with ψ-derivatives of the tabulated β, θ, fx, fz from
periodic 6th-order central differences (exact for a rigid rotor with constant loads). Ground
frame: y = hub + V t + R_GH q_H, v = V + Ω R_GH (Dq)_H, a = Ω² R_GH (D²q)_H, ...; the dual-compact
line forces use v in rotating components, Ω (Dq) + (V_H·e_r, V_H·e_t, V_H·z_H), V_H = R_GHᵀ V.
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
    ``area_factor``: section area A / (t·c) (0.685 for NACA 00xx), used by both models;
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
        if not 0.0 < self.area_factor <= 1.0:
            raise AcousticsError(f"thickness model: area_factor {self.area_factor}, expected 0 < area_factor <= 1 (A/(t c))")


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


def _blade_components(disk: Mapping[str, np.ndarray], model: ThicknessModel, hinge_offset_m: float, rho0: float,
                      omega: float, air_rot: np.ndarray):
    """Rotating-frame position and force-on-fluid components per line: lists of (n_psi, n_r, 3).

    ``air_rot`` (n_psi, 1, 3): the hub's velocity relative to the medium (aircraft velocity) in
    rotating components at each table azimuth; the dual-compact forces need the lines' own
    velocities relative to the medium, Ω·(Dq) + air_rot.
    """
    r, dr, chord, thick = disk["r_m"], disk["dr_m"], disk["chord_m"], disk["thickness_m"]
    theta, beta = disk["theta_rad"], disk["beta_rad"]
    e = hinge_offset_m
    sb, cb, st, ct = np.sin(beta), np.cos(beta), np.sin(theta), np.cos(theta)
    area = model.area_factor * thick * chord

    def position(offset):
        return np.stack([e + (r - e) * cb - offset * st * sb, offset * ct, (r - e) * sb + offset * st * cb], axis=-1)

    lines = [(position(np.zeros_like(r)), np.stack([np.zeros_like(r), disk["fx_N_per_m"] * dr, -disk["fz_N_per_m"] * dr], axis=-1),
              LOADING, np.zeros(r.shape[1]))]
    if model.kind == DUAL_COMPACT:
        dpsi = 2.0 * np.pi / r.shape[0]
        chord_dir = np.stack([-st * sb, ct, st * cb], axis=-1)  # e_c, toward the leading edge
        front, rear = model.chord_fractions
        strength = rho0 * area * dr / ((rear - front) * chord)  # ρ0 (A/D) dr, kg/m
        for fraction, sign in ((front, 1.0), (rear, -1.0)):
            q = position((model.pitch_axis_chord - fraction) * chord)
            vel = omega * _rotating_derivative(q, dpsi) + air_rot
            chordwise = np.einsum("prk,prk->pr", vel, chord_dir)
            lines.append((q, (sign * strength * chordwise)[..., None] * vel, THICKNESS, np.zeros(r.shape[1])))
    else:
        lines[0] = lines[0][:3] + (area[0] * dr[0],)
    return lines


def rotor_sources(disk: pd.DataFrame, motion: RotorMotion, *, thickness: ThicknessModel = ThicknessModel(),
                  hinge_offset_m: float = 0.0, rho0_kg_m3: float, c0_mps: float,
                  tau_range_s: tuple[float, float] | None = None) -> CompactSources:
    """Compact source lines of one rotor in the ground frame (ρ0 in kg/m³; c0 in m/s, every line
    must move subsonically relative to the medium).

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
    s = motion.rotation_sign
    psi_table = 2.0 * np.pi * np.arange(n_psi) / n_psi
    v_h = motion.r_gh.T @ np.asarray(motion.velocity_mps, dtype=float)
    air_rot = np.stack([v_h[0] * np.cos(psi_table) + v_h[1] * s * np.sin(psi_table),
                        -v_h[0] * np.sin(psi_table) + v_h[1] * s * np.cos(psi_table),
                        np.full(n_psi, v_h[2])], axis=-1)[:, None, :]
    lines = _blade_components(arrays, thickness, hinge_offset_m, rho0_kg_m3, omega, air_rot)

    pos_c, vel_c, acc_c, jerk_c, frc_c, frd_c, groups_d, volumes = [], [], [], [], [], [], [], []
    for q, g, group, volume in lines:
        d1 = _rotating_derivative(q, dpsi)
        speed = float(np.linalg.norm(omega * d1 + air_rot, axis=-1).max())
        if not speed < c0_mps:
            raise AcousticsError(f"disk table: a {group} line moves at {speed:.1f} m/s relative to the air, not below "
                                 f"c0 = {c0_mps} m/s; the compact F1A needs subsonic sources")
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
