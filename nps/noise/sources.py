"""Compact acoustic sources for the F1A solver (nps.noise.acoustics): a rotor from its disk table and trim row, or long source tables.

Rotor sources, per blade (docs/reference/conventions.md for frames and signs):

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
    averaged over a box-shaped chordwise thickness distribution (docs/reference/acoustics.md has the
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

from nps.core import periods
from nps.noise.acoustics import (C0_MPS, LOADING, RHO0_KG_M3, THICKNESS, AcousticsError, CompactSources, Observers, TimeGrid,
                           radiate_arrays, time_derivative)
from nps.rotor.geometry import RotorMotion
from nps.noise.signals import TOTAL, signals_table

SOURCE_COLUMNS = ("node", "time_s", "x_m", "y_m", "z_m", "fx_N", "fy_N", "fz_N")
OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps")
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
    """Disk table → (n_psi, n_r) arrays; checks columns, ψ-major order, uniform ψ grid, finiteness.
    A table over m revolutions of a common period (ψ_i = 2πi/N, i < mN) gives (mN, n_r) arrays."""
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
    revolutions = periods.table_revolutions(psi_values)
    expected = 2.0 * np.pi * np.arange(n_psi) * revolutions / n_psi
    if n_psi % revolutions or not np.allclose(out["psi_rad"], expected[:, None], atol=1e-9):
        raise AcousticsError(f"{what}: 'psi_rad' must be ψ-major with ψ_i = 2π i / N, i < {n_psi} (N = {n_psi} for one "
                             "revolution, or N per revolution over the revolutions of a common period)")
    return out


def _blade_components(disk: Mapping[str, np.ndarray], model: ThicknessModel, hinge_offset_m: float, rho0: float,
                      omega: float, air_rot: np.ndarray, dpsi: float):
    """Rotating-frame position and force-on-fluid components per line: lists of (n_psi, n_r, 3).

    ``air_rot`` (n_psi, 1, 3): the hub's velocity relative to the medium (aircraft velocity) in
    rotating components at each table azimuth; the dual-compact forces need the lines' own
    velocities relative to the medium, Ω·(Dq) + air_rot; ``dpsi``: the table's azimuth step (rad).
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


def _air_velocity_rotating(motion: RotorMotion, n_rows: int, n_psi: int) -> np.ndarray:
    """Flight velocity in the blade-fixed rotating frame at the table's azimuths ψ_i = 2πi/``n_psi``,
    i < ``n_rows``, (n_rows, 1, 3) m/s."""
    s = motion.rotation_sign
    psi_table = 2.0 * np.pi * np.arange(n_rows) / n_psi
    v_h = motion.r_gh.T @ np.asarray(motion.velocity_mps, dtype=float)
    return np.stack([v_h[0] * np.cos(psi_table) + v_h[1] * s * np.sin(psi_table),
                     -v_h[0] * np.sin(psi_table) + v_h[1] * s * np.cos(psi_table),
                     np.full(n_rows, v_h[2])], axis=-1)[:, None, :]


def _rotating_kinematics(lines, omega: float, dpsi: float, air_rot: np.ndarray, c0_mps: float, n_r: int):
    """Rotating-frame position, velocity, acceleration, jerk, force and force rate of every line, stacked along
    the source axis ((n_psi, n_line·n_r, 3) each), their group names and volumes; refuses supersonic lines."""
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
    stack = [np.concatenate(a, axis=1) for a in (pos_c, vel_c, acc_c, jerk_c, frc_c, frd_c)]
    return stack, np.concatenate(groups_d), np.concatenate(volumes).astype(float)


def _source_steps(tau_range_s, n_psi: int, period: float, phase_rad: float = 0.0) -> np.ndarray:
    """Source-time steps covering ``tau_range_s``: step i is τ_i = (2π i/n_psi − phase_rad)/Ω, when blade 0 is
    at the table azimuth ψ_i (``period`` = 2π/Ω)."""
    shift = phase_rad / (2.0 * np.pi) * period  # the step grid's time shift (s)
    return np.arange(int(np.floor((tau_range_s[0] + shift) / period * n_psi)),
                     int(np.ceil((tau_range_s[1] + shift) / period * n_psi)) + 1)


def _blade_shifts(n_psi: int, n_blades: int, blade_shift_steps, why: str) -> list[int]:
    """Table-row shift of each blade (blade k's loads at row i are those of row i + shift_k): the given
    ``blade_shift_steps`` (a common-period table's, from the wake), else equal spacing k n_psi/B."""
    if blade_shift_steps is None:
        if n_psi % n_blades:
            raise AcousticsError(f"disk table: n_psi = {n_psi} must be divisible by n_blades = {n_blades} {why}")
        return [k * n_psi // n_blades for k in range(n_blades)]
    shifts = [int(x) for x in blade_shift_steps]
    if len(shifts) != n_blades or shifts[0] != 0 or any(x < 0 for x in shifts):
        raise AcousticsError(f"disk table: blade_shift_steps {list(blade_shift_steps)}: expected {n_blades} table-row "
                             "shifts (one per blade, 0 for blade 0, none negative)")
    return shifts


def _ground_frame_lines(stack, motion: RotorMotion, steps: np.ndarray, blades: list[int], tau: np.ndarray,
                        shifts: list[int], phase_rad: float = 0.0) -> list[np.ndarray]:
    """The six rotating-frame components of every blade at source times ``tau`` in the ground frame (position
    and velocity with the hub's flight added), each (n_blade·n_source, n_tau, 3); blade k at
    ψ_k = Ω τ + phase_rad + 2πk/B, with the table's row ``steps`` + ``shifts[k]`` (periodic in the table's rows)."""
    omega, s, n_blades, r_gh = motion.omega_rad_s, motion.rotation_sign, motion.n_blades, motion.r_gh
    n_rows = stack[0].shape[0]
    out = [[] for _ in range(6)]
    for k in blades:
        index = (steps + shifts[k]) % n_rows
        psi = omega * tau + phase_rad + 2.0 * np.pi * k / n_blades
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
    return [np.ascontiguousarray(np.concatenate(a, axis=0)) for a in out]


def blade_lines(disk: pd.DataFrame, motion: RotorMotion, thickness: ThicknessModel, hinge_offset_m: float,
                rho0_kg_m3: float):
    """Blade 0's source lines in the rotating frame at the table's rows: (disk arrays (:func:`disk_arrays`), lines,
    air velocity in rotating components (n_rows, 1, 3) m/s). Each line is (position (n_rows, n_r, 3) in rotating
    components (e_r, e_t, z_H), m; force on the fluid per node (n_rows, n_r, 3), N; group; volume (n_r,) m³): the
    loading line, then the dual-compact thickness lines (front, rear) when the model has them. The rows are the
    table's azimuths ψ_i = 2πi/N (over the revolutions of a common period)."""
    arrays = disk_arrays(disk)
    n_rows = arrays["r_m"].shape[0]
    n_psi = n_rows // periods.table_revolutions(arrays["psi_rad"][:, 0])
    omega = motion.omega_rad_s
    if not omega > 0:
        raise AcousticsError(f"trim row: omega_rad_s must be positive, got {omega}")
    air_rot = _air_velocity_rotating(motion, n_rows, n_psi)
    lines = _blade_components(arrays, thickness, hinge_offset_m, rho0_kg_m3, omega, air_rot, 2.0 * np.pi / n_psi)
    return arrays, lines, air_rot


def rotor_sources(disk: pd.DataFrame, motion: RotorMotion, *, thickness: ThicknessModel = ThicknessModel(),
                  hinge_offset_m: float = 0.0, rho0_kg_m3: float, c0_mps: float,
                  tau_range_s: tuple[float, float] | None = None, phase_rad: float = 0.0,
                  blade_shift_steps=None) -> CompactSources:
    """Compact source lines of one rotor in the ground frame (ρ0 in kg/m³; c0 in m/s, every line
    must move subsonically relative to the medium).

    ``phase_rad``: blade phase, the azimuth of blade 0 at t = 0 (ψ_0(t) = Ω t + phase_rad, in the
    rotor's own sense; docs/reference/acoustics.md "Blade phasing"). The source times are those at
    which blade 0 sits on the table's azimuths, τ_i = (2π i/n_psi − phase_rad)/Ω, so the loads are
    used as tabulated (no interpolation in ψ) for any phase.

    ``tau_range_s=None``: periodic sources, blade 0 over one revolution from τ_0 = −phase_rad/Ω (the
    other B − 1 blades are implied by symmetry: identical loads vs ψ). Otherwise all blades at
    the τ_i covering ``tau_range_s`` (requires n_psi divisible by B so every blade sits on
    the table's ψ grid).

    A table over m revolutions of a common period (ψ_i = 2πi/N, i < mN; docs/reference/wake_bvi.md
    "Common period"): blade 0's loads over the period, blade k's those of row i + ``blade_shift_steps[k]``
    at row i (None: kN/B, the same revolution); periodic sources hold every blade over the period m 2π/Ω.
    """
    arrays, lines, air_rot = blade_lines(disk, motion, thickness, hinge_offset_m, rho0_kg_m3)
    n_rows, n_r = arrays["r_m"].shape
    revolutions = periods.table_revolutions(arrays["psi_rad"][:, 0])
    n_psi = n_rows // revolutions
    dpsi = 2.0 * np.pi / n_psi
    omega = motion.omega_rad_s
    period = 2.0 * np.pi / omega
    stack, group_names, volume = _rotating_kinematics(lines, omega, dpsi, air_rot, c0_mps, n_r)
    n_blades = motion.n_blades
    symmetric = revolutions == 1 and blade_shift_steps is None
    if tau_range_s is None and symmetric:  # blade 0 over one revolution, the others by symmetry
        steps, blades, shifts, copies, source_period = np.arange(n_psi), [0], [0], n_blades, period
    elif tau_range_s is None:  # every blade over the common period
        shifts = _blade_shifts(n_psi, n_blades, blade_shift_steps, "for a table over several revolutions")
        steps, blades, copies, source_period = np.arange(n_rows), list(range(n_blades)), 1, revolutions * period
    else:
        shifts = _blade_shifts(n_psi, n_blades, blade_shift_steps, "for stationary observers")
        steps, blades, copies, source_period = _source_steps(tau_range_s, n_psi, period, phase_rad), list(range(n_blades)), 1, None
    tau = steps * period / n_psi - phase_rad / omega
    arrays6 = _ground_frame_lines(stack, motion, steps, blades, tau, shifts, phase_rad)
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
        period_s=source_period,
        frame_velocity_mps=np.asarray(motion.velocity_mps, float) if tau_range_s is None else None,
        copies=copies,
    )


# ----------------------------------------------------------------------------------------------
# rotor radiation: disk table + trim row -> compact sources -> F1A solver
# ----------------------------------------------------------------------------------------------
def common_grid(reference_trim_row, samples_per_rev: int, revolutions: int = 1) -> TimeGrid:
    """The aircraft's common observer grid: one revolution of the reference rotor from t = 0
    (blade 0 of every rotor at ψ = 0) with ``samples_per_rev`` samples; ``revolutions`` of it over a
    common period (``revolutions`` × ``samples_per_rev`` samples)."""
    if samples_per_rev < 8:
        raise AcousticsError(f"samples_per_rev: expected at least 8, got {samples_per_rev}")
    if int(revolutions) != revolutions or revolutions < 1:
        raise AcousticsError(f"revolutions: expected a whole number >= 1, got {revolutions}")
    omega = float(reference_trim_row["omega_rad_s"])
    if not omega > 0:
        raise AcousticsError(f"rotor '{reference_trim_row['rotor']}': omega_rad_s must be positive, got {omega}")
    m = int(revolutions)
    return TimeGrid(0.0, 2.0 * np.pi * m / omega, int(samples_per_rev) * m)


def _emission_time(x0: np.ndarray, v_obs: np.ndarray, t_s: float, y0: np.ndarray, v_src: np.ndarray, c0: float) -> np.ndarray:
    """Emission time τ of a point y0 + v_src τ heard at t_s by observers x0 + v_obs t (closed form)."""
    d = x0 + v_obs * t_s - (y0 + v_src * t_s)
    dv = d @ v_src
    a = c0 * c0 - v_src @ v_src
    return t_s - (dv + np.sqrt(dv * dv + a * np.einsum("ij,ij->i", d, d))) / a


def radiate_rotor(disk: pd.DataFrame, trim_row, observers: Observers, grid: TimeGrid, *, thickness=None,
                  hinge_offset_m: float = 0.0, phase_rad: float = 0.0, blade_shift_steps=None) -> np.ndarray:
    """Pressure (Pa) of one rotor, shape (n_obs, 2, n_samples), groups (loading, thickness).

    ``disk``: disk table (docs/reference/conventions.md), ``trim_row``: the rotor's ``trim.parquet`` row
    (kinematics, ρ0 and c0); ``phase_rad`` the azimuth of its blade 0 at t = 0, ``blade_shift_steps`` the blades'
    rows in a common-period table (:func:`rotor_sources`).
    Observers moving with the aircraft use the periodic one-blade
    path (exact periodicity and blade symmetry); any other observers get all blades over the
    source-time span their window needs.
    """
    thickness = ThicknessModel() if thickness is None else thickness
    motion = RotorMotion.from_trim_row(trim_row)
    c0 = float(trim_row["speed_of_sound_mps"])
    rho0 = float(trim_row["density_kg_m3"])
    kwargs = dict(thickness=thickness, hinge_offset_m=hinge_offset_m, rho0_kg_m3=rho0, c0_mps=c0, phase_rad=phase_rad,
                  blade_shift_steps=blade_shift_steps)
    if np.allclose(observers.velocity_mps, motion.velocity_mps[None, :], rtol=0.0, atol=1e-9 * c0):
        sources = rotor_sources(disk, motion, **kwargs)
    else:
        reach = float((disk["r_m"] + disk["dr_m"] + disk["chord_m"]).max())
        psi = np.unique(disk["psi_rad"].to_numpy(float))
        n_psi = psi.size // periods.table_revolutions(psi)  # azimuths per revolution
        margin = 2.0 * reach / (c0 - np.linalg.norm(motion.velocity_mps)) + 8.0 * 2.0 * np.pi / motion.omega_rad_s / n_psi
        t_last = grid.t_start_s + (grid.n_samples - 1) * grid.dt_s
        first = _emission_time(observers.position_m, observers.velocity_mps, grid.t_start_s, motion.hub_position_m, motion.velocity_mps, c0)
        last = _emission_time(observers.position_m, observers.velocity_mps, t_last, motion.hub_position_m, motion.velocity_mps, c0)
        sources = rotor_sources(disk, motion, tau_range_s=(first.min() - margin, last.max() + margin), **kwargs)
    return radiate_arrays(sources, observers, grid, c0_mps=c0, rho0_kg_m3=rho0)


# ----------------------------------------------------------------------------------------------
# tabulated sources (``python -m nps radiate``): long source and observer tables
# ----------------------------------------------------------------------------------------------
def _require(df: pd.DataFrame, columns, what: str) -> None:
    missing = [c for c in columns if c not in df.columns]
    if missing:
        raise AcousticsError(f"{what}: missing column(s) {missing}; has {list(df.columns)}")
    for c in df.columns:
        if pd.api.types.is_float_dtype(df[c]) and not np.isfinite(df[c].to_numpy()).all():
            bad = int((~np.isfinite(df[c].to_numpy())).sum())
            raise AcousticsError(f"{what}: column '{c}' has {bad} NaN/inf value(s)")


def sources_from_table(table: pd.DataFrame, what: str = "sources") -> CompactSources:
    """Long-format source table (module CLI format) → :class:`CompactSources`.

    Velocities from ``vx_mps…`` when present, else 6th-order differences of the positions;
    accelerations, jerks and force rates by 6th-order differences in source time. The dipole
    part of a node goes to its ``group`` (default "loading"), its monopole part (``volume_m3``)
    to "thickness".
    """
    _require(table, SOURCE_COLUMNS, what)
    table = table.sort_values(["node", "time_s"], kind="stable")
    nodes = table["node"].unique()
    n_node = nodes.size
    counts = table.groupby("node", sort=True).size()
    if (counts != counts.iloc[0]).any():
        raise AcousticsError(f"{what}: every node needs the same source times; counts differ {counts.to_dict()}")
    n_tau = int(counts.iloc[0])
    time = table["time_s"].to_numpy(float).reshape(n_node, n_tau)
    if not np.allclose(time, time[0][None, :], rtol=0, atol=1e-12 * max(1.0, np.abs(time).max())):
        raise AcousticsError(f"{what}: 'time_s' must be the same for all nodes")
    tau = time[0]
    if n_tau < 7:
        raise AcousticsError(f"{what}: need at least 7 source times per node, got {n_tau}")
    step = np.diff(tau)
    if step[0] <= 0 or not np.allclose(step, step[0], rtol=1e-6, atol=0):
        raise AcousticsError(f"{what}: 'time_s' must be uniform and increasing (steps {step.min():.6g}…{step.max():.6g} s)")
    dt = float(step[0])

    def vec(cols):
        return np.stack([table[c].to_numpy(float).reshape(n_node, n_tau) for c in cols], axis=-1)

    pos = vec(("x_m", "y_m", "z_m"))
    vel_cols = ("vx_mps", "vy_mps", "vz_mps")
    if all(c in table.columns for c in vel_cols):
        vel = vec(vel_cols)
    elif any(c in table.columns for c in vel_cols):
        raise AcousticsError(f"{what}: give all of {list(vel_cols)} or none")
    else:
        vel = time_derivative(pos, dt)
    acc = time_derivative(vel, dt)
    jerk = time_derivative(acc, dt)
    force = vec(("fx_N", "fy_N", "fz_N"))
    if "volume_m3" in table.columns:
        volume = table["volume_m3"].to_numpy(float).reshape(n_node, n_tau)
        if not np.allclose(volume, volume[:, :1]):
            raise AcousticsError(f"{what}: 'volume_m3' must be constant in time for each node")
        volume = volume[:, 0]
    else:
        volume = np.zeros(n_node)
    names = table["group"].astype(str).to_numpy().reshape(n_node, n_tau)[:, 0] if "group" in table.columns else np.full(n_node, LOADING)
    groups = list(dict.fromkeys(names.tolist()))
    if (volume != 0).any() and THICKNESS not in groups:
        groups.append(THICKNESS)
    if TOTAL in groups:
        raise AcousticsError(f"{what}: group name '{TOTAL}' is reserved")
    dip = np.array([groups.index(g) for g in names], dtype=np.int64)
    dip[np.all(force == 0.0, axis=(1, 2))] = -1
    mono = np.where(volume != 0, groups.index(THICKNESS) if THICKNESS in groups else -1, -1).astype(np.int64)
    return CompactSources(tau, pos, vel, acc, jerk, force, time_derivative(force, dt), volume, tuple(groups), dip, mono)


def observers_from_table(table: pd.DataFrame, what: str = "observers") -> tuple[np.ndarray, Observers]:
    """Observer table → (observer ids, :class:`Observers`)."""
    _require(table, OBSERVER_COLUMNS, what)
    ids = table["observer"].to_numpy()
    if len(np.unique(ids)) != len(ids):
        raise AcousticsError(f"{what}: duplicate observer ids")
    return ids, Observers(table[["x_m", "y_m", "z_m"]].to_numpy(float), table[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float))


def radiate(sources: pd.DataFrame, observers: pd.DataFrame, t_start_s: float, duration_s: float, n_samples: int,
            c0_mps: float = C0_MPS, rho0_kg_m3: float = RHO0_KG_M3) -> pd.DataFrame:
    """Python equivalent of ``python -m nps radiate`` (long tables in, long table out).

    ``sources``: columns node, [group], time_s, x_m, y_m, z_m (G, m), fx_N, fy_N, fz_N (force on
    the fluid, N), optional volume_m3, optional vx_mps, vy_mps, vz_mps. ``observers``: observer,
    x_m, y_m, z_m (position at t = 0), vx_mps, vy_mps, vz_mps. Returns observer, group (each
    group and "total"), time_s (t_k = t_start_s + k·duration_s/n_samples), p_Pa.
    """
    src = sources_from_table(sources)
    ids, obs = observers_from_table(observers)
    grid = TimeGrid(float(t_start_s), float(duration_s), int(n_samples))
    pressure = radiate_arrays(src, obs, grid, c0_mps=c0_mps, rho0_kg_m3=rho0_kg_m3)
    return signals_table(ids, src.groups, pressure, grid)
