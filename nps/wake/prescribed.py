"""Beddoes prescribed tip-vortex wake: geometry, snapshots, induced velocity at the blades.

Thesis chapter 5 (eq. 5.1–5.9), with the errata documented in ``docs/reference/wake_bvi.md``.
Frames (docs/reference/conventions.md): everything here is computed in the rotor's
*counterclockwise-equivalent* hub frame H' (x aft, y toward the advancing side, z along the
thrust; H' = H for s = +1, y mirrored for s = −1). :func:`to_hub_frame` maps H' to H.

Geometry (normalised by R, wake age φ = ψ_b − ψ_v in rad, ψ_v the release azimuth measured
from the downwind in-plane direction, μ = |(μ_x, μ_y')|, NPS sign of μ_z: + when the free
stream goes down through the disk):

    λ0   = C_T / (2 sqrt(μ² + (μ_z + λ0)²))                                     (eq. 5.2)
    χ    = atan(μ / |μ_z + λ0|)                                                   (eq. 5.3)
    r_v  = r_r (D + (1 − D) exp(−(0.145 + 27 C_T) φ))                             (eq. 5.5)
    x    = r_v cos ψ_v + μ φ,   y = r_v sin ψ_v                                   (eq. 5.6–5.7)
    z    = r_r sin β(ψ_v) − μ_z φ
           − λ0 φ [A χ (cos ψ_v + μ φ / (2 r_v) − |r_v sin ψ_v|³) − 2 B μ sin ψ_v + C]  (eq. 5.4)

Vortex: :class:`nps.wake.vortex.VortexModel` (``WakeModel.vortex``; core, growth, Vatistas n,
Betz structure) with the strength Γ_v(ψ_v) = max_r Γ(ψ_v, r) of the bound circulation
(Γ = L'/(ρ U_T), eq. 5.9); its velocity from :mod:`nps.wake.vortex` (eq. 5.10–5.15).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np
import pandas as pd

from nps.core.jit import kernel, prange
from nps.wake.vortex import PROFILE_POINTS, VortexModel, add_polyline_velocity, core_radius, profile_row


@dataclass(frozen=True)
class WakeModel:
    """Numerical and model parameters of the prescribed wake (config ``wake:`` block).

    ``a_skew``, ``b_lateral``, ``c_mean``: Beddoes inflow coefficients A, B, C (eq. 5.1);
    ``d_contraction``: Landgrebe D (eq. 5.5); ``revolutions``: wake age kept, in revolutions;
    ``steps_per_rev``: vortex segments per revolution of wake age (segment length 2π/N rad of
    age); ``release_radius_fraction``: r_r; ``vortex``: the tip vortex it carries (core, growth,
    Vatistas n, structure; :class:`nps.wake.vortex.VortexModel`).
    """

    a_skew: float = 0.5
    b_lateral: float = 1.0
    c_mean: float = 1.1
    d_contraction: float = 0.85
    revolutions: float = 4.0
    steps_per_rev: int = 360
    release_radius_fraction: float = 1.0
    vortex: VortexModel = VortexModel()

    def __post_init__(self):
        checks = {
            "d_contraction": 0.0 < self.d_contraction <= 1.0,
            "revolutions": self.revolutions > 0.0,
            "steps_per_rev": self.steps_per_rev >= 8,
            "release_radius_fraction": 0.0 < self.release_radius_fraction <= 1.0,
        }
        bad = [name for name, ok in checks.items() if not ok]
        if bad:
            raise ValueError(f"WakeModel: invalid {bad} in {self}")

    @property
    def n_age(self) -> int:
        """Number of vortex segments per blade."""
        return int(round(self.revolutions * self.steps_per_rev))

    @property
    def dphi_rad(self) -> float:
        return 2.0 * np.pi / self.steps_per_rev

    def record(self) -> dict:
        """Every parameter by name, the vortex's beside the geometry's (artifact metadata)."""
        own = {name: getattr(self, name) for name in self.__dataclass_fields__ if name != "vortex"}
        return {**own, **self.vortex.__dict__}

    @classmethod
    def from_config(cls, wake: Mapping, revolutions: float, steps_per_rev: int) -> "WakeModel":
        """From the validated config ``wake:`` block and ``resolution`` entries."""
        return cls(
            a_skew=float(wake["A"]),
            b_lateral=float(wake["B"]),
            c_mean=float(wake["C"]),
            d_contraction=float(wake["D"]),
            vortex=VortexModel.from_config(wake),
            revolutions=float(revolutions),
            steps_per_rev=int(steps_per_rev),
        )


@dataclass(frozen=True)
class WakeState:
    """The flow state one rotor's wake depends on (SI units, NPS advance-ratio signs).

    ``psi_table_rad``: uniform periodic release azimuths ψ_i = 2π i / N (rotor's own sense);
    ``gamma_table_m2_s``: tip-vortex strength at release (> 0 for positive lift);
    ``beta_table_rad``: blade flap angle at release. ``mu_y`` is the hub-frame value (the
    ccw-equivalent μ_y' = s μ_y is used internally). ``vortex_profile``: optional enclosed-
    circulation fractions B (N, PROFILE_POINTS) of the rolled-up vortex per release azimuth
    (:func:`nps.wake.vortex.vortex_profile_table`), needed by ``VortexModel(vortex_structure="betz")``.
    """

    radius_m: float
    chord_m: float
    n_blades: int
    omega_rad_s: float
    rotation_sign: int
    mu_x: float
    mu_y: float
    mu_z: float
    ct: float
    gamma_table_m2_s: np.ndarray
    beta_table_rad: np.ndarray
    vortex_profile: np.ndarray | None = None

    def __post_init__(self):
        gamma = np.asarray(self.gamma_table_m2_s, dtype=float)
        beta = np.asarray(self.beta_table_rad, dtype=float)
        problems = []
        if self.vortex_profile is not None:
            profile = np.asarray(self.vortex_profile, dtype=float)
            if profile.shape != (gamma.size, PROFILE_POINTS) or not np.all((profile >= 0.0) & (profile <= 1.0)):
                problems.append(f"vortex_profile must be ({gamma.size}, {PROFILE_POINTS}) fractions in [0, 1], "
                                f"got shape {profile.shape}")
        if gamma.ndim != 1 or gamma.size < 4 or beta.shape != gamma.shape:
            problems.append(f"gamma/beta tables must be 1-D of equal length >= 4, got {gamma.shape}, {beta.shape}")
        if not (np.isfinite(gamma).all() and np.isfinite(beta).all()):
            problems.append("gamma/beta tables contain non-finite values")
        for name in ("radius_m", "chord_m", "omega_rad_s"):
            if not getattr(self, name) > 0.0:
                problems.append(f"{name} must be > 0")
        if self.n_blades < 1 or self.rotation_sign not in (1, -1):
            problems.append("n_blades must be >= 1 and rotation_sign +-1")
        if not (self.ct > 0.0 and all(np.isfinite([self.mu_x, self.mu_y, self.mu_z, self.ct]))):
            problems.append("ct must be > 0 and advance ratios finite")
        if problems:
            raise ValueError("WakeState: " + "; ".join(problems))

    @property
    def psi_table_rad(self) -> np.ndarray:
        n = len(self.gamma_table_m2_s)
        return 2.0 * np.pi * np.arange(n) / n

    @property
    def mu_inplane(self) -> float:
        return float(np.hypot(self.mu_x, self.rotation_sign * self.mu_y))

    @property
    def wind_azimuth_rad(self) -> float:
        """Azimuth (H') toward which the in-plane free stream blows the wake."""
        return float(np.arctan2(self.rotation_sign * self.mu_y, self.mu_x))


def mean_inflow(ct: float, mu: float, mu_z: float, tol: float = 1e-12) -> float:
    """Mean induced inflow ratio λ0 of eq. 5.2 (Glauert), by Newton iteration.

    Solves f(λ0) = 2 λ0 sqrt(μ² + (μ_z + λ0)²) − C_T = 0 for the root λ0 > 0 (unique for
    μ > 0 or μ_z > −2 sqrt(C_T/2); in the vortex-ring state without forward speed the
    largest root is returned).
    """
    if not ct > 0.0:
        raise ValueError(f"mean_inflow: C_T must be > 0, got {ct}")
    lam = math.sqrt(ct / 2.0) + max(0.0, -mu_z)
    for _ in range(200):
        s = math.hypot(mu, mu_z + lam)
        f = 2.0 * lam * s - ct
        df = 2.0 * s + 2.0 * lam * (mu_z + lam) / s
        step = f / df
        lam = max(lam - step, 0.5 * lam)
        if abs(step) < tol * max(lam, 1e-12):
            return lam
    raise RuntimeError(f"mean_inflow: no convergence for C_T={ct}, mu={mu}, mu_z={mu_z}")


def wake_scalars(state: WakeState, model: WakeModel) -> np.ndarray:
    """Packed float64 parameters of the Beddoes geometry kernels (see :func:`node_position`)."""
    mu = state.mu_inplane
    lam0 = mean_inflow(state.ct, mu, state.mu_z)
    chi = math.atan2(mu, abs(state.mu_z + lam0))
    return np.array(
        [
            state.radius_m,
            state.n_blades,
            mu,
            state.wind_azimuth_rad,
            state.mu_z,
            lam0,
            chi,
            state.ct,
            model.a_skew,
            model.b_lateral,
            model.c_mean,
            model.d_contraction,
            model.release_radius_fraction,
            model.dphi_rad,
        ]
    )


@kernel(inline=True)
def _periodic_interp(table, psi):
    """Linear interpolation in a uniform periodic table on ψ_i = 2π i / N."""
    n = table.shape[0]
    u = (psi / (2.0 * math.pi)) % 1.0 * n
    i0 = int(math.floor(u))
    w = u - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    return (1.0 - w) * table[i0] + w * table[i1]


@kernel
def node_position(p, gamma_tab, beta_tab, psi_v, phi):
    """Position (x, y, z) (m, H') and strength Γ_v (m²/s) of the tip vortex released at ψ_v, at
    age φ (eq. 5.4–5.7; ``p``: :func:`wake_scalars`, tables on ψ_i = 2π i / N)."""
    return node_position_at(p, gamma_tab, beta_tab, psi_v, phi, vortex_radius(p, phi), math.cos(p[3]), math.sin(p[3]))


@kernel(inline=True)
def vortex_radius(p, phi):
    """Radius r_v / R of the contracting tip vortex at age φ (eq. 5.4)."""
    ct, d, r_r = p[7], p[11], p[12]
    return r_r * (d + (1.0 - d) * math.exp(-(0.145 + 27.0 * ct) * phi))


@kernel(inline=True)
def node_position_at(p, gamma_tab, beta_tab, psi_v, phi, r_v, cpw, spw):
    """:func:`node_position` given the age's radius ``r_v`` (:func:`vortex_radius`) and cos, sin of the
    wind azimuth ψ_w (``cpw``, ``spw``), which loops over the nodes of a snapshot evaluate once."""
    radius, mu, psi_w, mu_z, lam0, chi = p[0], p[2], p[3], p[4], p[5], p[6]
    a, b, c, r_r = p[8], p[9], p[10], p[12]
    psi_rel = psi_v - psi_w
    cw, sw = math.cos(psi_rel), math.sin(psi_rel)
    xw = r_v * cw + mu * phi
    yw = r_v * sw
    beta = _periodic_interp(beta_tab, psi_v)
    lateral = abs(r_v * sw)
    z = r_r * math.sin(beta) - mu_z * phi - lam0 * phi * (
        a * chi * (cw + mu * phi / (2.0 * r_v) - lateral * lateral * lateral) - 2.0 * b * mu * sw + c
    )
    gamma = _periodic_interp(gamma_tab, psi_v)
    return (
        radius * (xw * cpw - yw * spw),
        radius * (xw * spw + yw * cpw),
        radius * z,
        gamma,
    )


@kernel
def _blade_wake(p, vortex_core, gamma_tab, beta_tab, psi_blade, n_age, n_rows, nodes, strength, core, row):
    """Nodes of every blade's tip vortex when blade 0 is at ``psi_blade`` (into given arrays).

    nodes (B, n_age+1, 3) in m (H'); strength Γ(ψ_v), core radius r_c(Γ, φ)
    (:func:`nps.wake.vortex.core_radius` of ``vortex_core``) and the row of the structure-factor
    table (``n_rows`` rows, :func:`nps.wake.vortex.profile_row` of ψ_v) per node
    (B, n_age+1). A segment carries the mean of its two nodes' strengths and cores and the
    first node's row.
    """
    n_blades = int(p[1])
    dphi = p[13]
    cpw, spw = math.cos(p[3]), math.sin(p[3])
    for j in range(n_age + 1):
        phi = j * dphi
        r_v = vortex_radius(p, phi)
        for k in range(n_blades):
            psi_k = psi_blade + 2.0 * math.pi * k / n_blades
            x, y, z, g = node_position_at(p, gamma_tab, beta_tab, psi_k - phi, phi, r_v, cpw, spw)
            nodes[k, j, 0], nodes[k, j, 1], nodes[k, j, 2] = x, y, z
            strength[k, j] = g
            core[k, j] = core_radius(vortex_core, g, phi)
            row[k, j] = profile_row(psi_k - phi, n_rows)


@kernel(parallel=True)
def _disk_kernel(p, vortex_core, gamma_tab, beta_tab, profiles, s2, psi_eval, points, n_age, n):
    """Induced velocity (H', m/s) at points (n_psi, n_r, 3) when blade 0 is at psi_eval[i].

    Each azimuth row builds its own wake snapshot (periodic flight: the wake seen at ψ_b
    depends only on ψ_b), so rows run in parallel. ``profiles`` (n_rows, STRUCTURE_DEGREE + 1):
    structure-factor coefficients per release azimuth, or (1, 1) for the point vortex
    (:meth:`nps.wake.vortex.VortexModel.structure_coefficients`), scale ``s2`` (m²); ``vortex_core``:
    :meth:`nps.wake.vortex.VortexModel.core_constants`; ``n``: Vatistas exponent.
    """
    n_psi, n_r = points.shape[0], points.shape[1]
    n_blades = int(p[1])
    out = np.zeros((n_psi, n_r, 3))
    for i in prange(n_psi):
        nodes = np.empty((n_blades, n_age + 1, 3))
        strength = np.empty((n_blades, n_age + 1))
        core = np.empty((n_blades, n_age + 1))
        row = np.empty((n_blades, n_age + 1), dtype=np.int64)
        _blade_wake(p, vortex_core, gamma_tab, beta_tab, psi_eval[i], n_age, profiles.shape[0], nodes, strength, core, row)
        px, py, pz = points[i, :, 0].copy(), points[i, :, 1].copy(), points[i, :, 2].copy()
        scratch = np.empty((4, n_r))
        vx, vy, vz = np.zeros(n_r), np.zeros(n_r), np.zeros(n_r)
        for k in range(n_blades):
            add_polyline_velocity(px, py, pz, nodes, strength, core, profiles, row, s2, k, 0, n_age, 1.0, n,
                                  scratch[0], scratch[1], scratch[2], scratch[3], vx, vy, vz)
        out[i, :, 0], out[i, :, 1], out[i, :, 2] = vx, vy, vz
    return out


@dataclass(frozen=True)
class WakeSnapshot:
    """Tip-vortex geometry when blade 0 is at ``psi_blade_rad`` (frame H', metres).

    ``nodes_m`` (B, n_age+1, 3): node j of blade k has age j·Δφ (node 0 at the blade tip);
    ``age_rad`` (n_age+1,); ``strength_m2_s`` and ``core_radius_m`` (B, n_age+1) per node
    (segment j joins nodes j and j+1 and carries their mean; Γ > 0 circulates right-handed
    about young → old).
    """

    psi_blade_rad: float
    nodes_m: np.ndarray
    age_rad: np.ndarray
    strength_m2_s: np.ndarray
    core_radius_m: np.ndarray


def wake_snapshot(state: WakeState, model: WakeModel, psi_blade_rad: float) -> WakeSnapshot:
    """The wake of all blades when blade 0 is at ``psi_blade_rad`` (H' frame)."""
    p = wake_scalars(state, model)
    n_age = model.n_age
    nodes = np.empty((state.n_blades, n_age + 1, 3))
    strength = np.empty((state.n_blades, n_age + 1))
    core = np.empty((state.n_blades, n_age + 1))
    gamma_tab = np.ascontiguousarray(state.gamma_table_m2_s, dtype=float)
    beta_tab = np.ascontiguousarray(state.beta_table_rad, dtype=float)
    row = np.empty((state.n_blades, n_age + 1), dtype=np.int64)
    vortex_core = model.vortex.core_constants(state.chord_m, state.omega_rad_s)
    _blade_wake(p, vortex_core, gamma_tab, beta_tab, float(psi_blade_rad), n_age, 1, nodes, strength, core, row)
    return WakeSnapshot(float(psi_blade_rad), nodes, np.arange(n_age + 1) * model.dphi_rad, strength, core)


def blade_points(psi_rad, r_m, beta_rad) -> np.ndarray:
    """Blade stations (n_psi, n_r, 3) in H' (m): r (cos β cos ψ, cos β sin ψ, sin β).

    ``beta_rad`` broadcast to (n_psi, n_r).
    """
    psi = np.asarray(psi_rad, dtype=float)[:, None]
    r = np.asarray(r_m, dtype=float)[None, :]
    beta = np.broadcast_to(np.asarray(beta_rad, dtype=float), (psi.shape[0], r.shape[1]))
    return np.stack([r * np.cos(beta) * np.cos(psi), r * np.cos(beta) * np.sin(psi), r * np.sin(beta)], axis=-1)


def disk_induced_velocity(state: WakeState, model: WakeModel, psi_rad, r_m, beta_rad) -> np.ndarray:
    """Velocity (m/s, frame H') induced by all blades' tip vortices at the blade stations.

    ``psi_rad`` (n_psi,) azimuths of blade 0, ``r_m`` (n_r,) radial stations, ``beta_rad``
    flap angle broadcastable to (n_psi, n_r). Returns (n_psi, n_r, 3).
    """
    psi = np.ascontiguousarray(psi_rad, dtype=float)
    points = np.ascontiguousarray(blade_points(psi, r_m, beta_rad))
    vortex = model.vortex
    profiles, s2 = vortex.structure_coefficients(state.vortex_profile, state.radius_m, state.chord_m)
    return _disk_kernel(
        wake_scalars(state, model),
        vortex.core_constants(state.chord_m, state.omega_rad_s),
        np.ascontiguousarray(state.gamma_table_m2_s, dtype=float),
        np.ascontiguousarray(state.beta_table_rad, dtype=float),
        profiles,
        s2,
        psi,
        points,
        model.n_age,
        float(vortex.vatistas_n),
    )


def to_hub_frame(vectors_hp, rotation_sign: int) -> np.ndarray:
    """Map vectors or positions (..., 3) from the ccw-equivalent frame H' to the hub frame H."""
    out = np.array(vectors_hp, dtype=float, copy=True)
    out[..., 1] *= rotation_sign
    return out


WAKE_COLUMNS = (
    "step", "psi_blade_rad", "time_s", "blade", "node", "age_rad", "x_h_m", "y_h_m", "z_h_m",
    "x_m", "y_m", "z_m", "circulation_m2_s", "core_radius_m",
)


def hub_to_ground(points_h, time_s, hub_position_m, velocity_mps, r_gh) -> np.ndarray:
    """Positions (..., 3) from H to G at time t: hub(t) + R_GH x_H, hub(t) = hub0 + V t."""
    hub = np.asarray(hub_position_m, dtype=float) + np.asarray(velocity_mps, dtype=float) * float(time_s)
    return np.asarray(points_h, dtype=float) @ np.asarray(r_gh, dtype=float).T + hub


def wake_table(state: WakeState, model: WakeModel, psi_blade_rad, motion, snapshot=None) -> pd.DataFrame:
    """Wake-geometry artifact rows (``wake/{rotor}.parquet``): one row per vortex node per step.

    ``psi_blade_rad``: blade-0 azimuths of the snapshots (time t = ψ/Ω after t = 0);
    ``motion``: :class:`nps.rotor.geometry.RotorMotion` (hub position, velocity, R_GH). Positions in
    the hub frame H (``*_h_m``) and the ground frame G (``x_m``, ``y_m``, ``z_m``).
    ``snapshot``: ψ → :class:`WakeSnapshot` (H'); default the Beddoes :func:`wake_snapshot`
    (e.g. ``lambda psi: nps.wake.free.wake_snapshot(solution, rotor, psi)`` for the free wake).
    """
    snapshot = snapshot or (lambda psi: wake_snapshot(state, model, psi))
    frames = []
    for step, psi_b in enumerate(np.asarray(psi_blade_rad, dtype=float)):
        snap = snapshot(psi_b)
        nodes_h = to_hub_frame(snap.nodes_m, state.rotation_sign)
        time_s = psi_b / state.omega_rad_s
        nodes_g = hub_to_ground(nodes_h, time_s, motion.hub_position_m, motion.velocity_mps, motion.r_gh)
        n_b, n_n = nodes_h.shape[:2]
        frames.append(
            pd.DataFrame(
                {
                    "step": np.full(n_b * n_n, step, dtype=np.int32),
                    "psi_blade_rad": np.full(n_b * n_n, psi_b),
                    "time_s": np.full(n_b * n_n, time_s),
                    "blade": np.repeat(np.arange(n_b, dtype=np.int16), n_n),
                    "node": np.tile(np.arange(n_n, dtype=np.int32), n_b),
                    "age_rad": np.tile(snap.age_rad, n_b),
                    "x_h_m": nodes_h[..., 0].ravel(),
                    "y_h_m": nodes_h[..., 1].ravel(),
                    "z_h_m": nodes_h[..., 2].ravel(),
                    "x_m": nodes_g[..., 0].ravel(),
                    "y_m": nodes_g[..., 1].ravel(),
                    "z_m": nodes_g[..., 2].ravel(),
                    "circulation_m2_s": snap.strength_m2_s.ravel(),
                    "core_radius_m": snap.core_radius_m.ravel(),
                }
            )
        )
    return pd.concat(frames, ignore_index=True)


def filament_plane_crossings(nodes_m: np.ndarray, axis: int, value: float) -> np.ndarray:
    """Points (K, 3) where the polylines ``nodes_m`` (B, N, 3) cross the plane x_axis = value.

    Linear interpolation along each crossing segment (used to compare with PIV cuts).
    """
    nodes = np.asarray(nodes_m, dtype=float)
    d = nodes[..., axis] - value
    k, j = np.nonzero(np.sign(d[:, :-1]) * np.sign(d[:, 1:]) < 0)
    t = d[k, j] / (d[k, j] - d[k, j + 1])
    return nodes[k, j] + t[:, None] * (nodes[k, j + 1] - nodes[k, j])


def blade_lines_hub(state: WakeState, psi_blade_rad: float, root_cutout_m: float, n_points: int = 2) -> np.ndarray:
    """Lifting lines (B, n_points, 3) in the hub frame H (m) when blade 0 is at ``psi_blade_rad``:
    root cutout to tip, flapped by β(ψ) from the state's table."""
    psi_k = psi_blade_rad + 2.0 * np.pi * np.arange(state.n_blades) / state.n_blades
    beta = np.interp(psi_k % (2.0 * np.pi), state.psi_table_rad, state.beta_table_rad, period=2.0 * np.pi)
    r = np.linspace(root_cutout_m, state.radius_m, n_points)
    return to_hub_frame(blade_points(psi_k, r, beta[:, None]), state.rotation_sign)


def snapshot_azimuths(n_blades: int, step_deg: float) -> np.ndarray:
    """Blade-0 azimuths (rad) covering one blade passage [0, 2π/B) every ``step_deg`` (the wake is periodic in 2π/B)."""
    if not step_deg > 0.0:
        raise ValueError(f"snapshot step: expected > 0 deg, got {step_deg}")
    return np.radians(np.arange(0.0, 360.0 / n_blades - 1e-9, step_deg))
