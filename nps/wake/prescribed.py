"""Tip-vortex wake: Beddoes prescribed geometry, vortex strength, Vatistas core, Biot–Savart.

Thesis chapter 5 (eq. 5.1–5.15), with the errata documented in ``docs/models/wake_bvi.md``.
Frames (docs/conventions.md): everything here is computed in the rotor's
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

Vortex strength: Γ_v(ψ_v) = max_r Γ(ψ_v, r), the bound circulation (Γ = L'/(ρ U_T), eq. 5.9)
rolled up outboard of its spanwise maximum (Betz). Core: Vatistas, n = 2 (eq. 5.15), radius
r_c0 = ``core_radius_chords`` · c, optionally grown with age (Lamb–Oseen/Squire):
r_c² = r_c0² + 4 α δ ν φ/Ω, α = 1.25643, δ = 1 + a₁ Γ/ν.

Vortex structure (``WakeModel.vortex_structure``): ``"betz"`` gives each vortex the radial
distribution of circulation that Betz's roll-up makes of the sheet trailed outboard of the
circulation peak (Betz 1932; Donaldson 1971; Rossow 1973): the vorticity trailed between y and
the tip lies within ρ(y) = ∫_y^R Γ dr / Γ(y) of the vortex centre, so the circulation enclosed
within ρ(y) is Γ(y) (:func:`betz_enclosed_circulation`, fraction B = Γ_enclosed/Γ_v). Each
annulus dΓ_enclosed(ρ) of that distribution induces as a Vatistas vortex whose core is its own
radius or the model's core, whichever is larger, so a segment induces the point-vortex velocity
times the structure factor

    T(r_p) = ∫ dB(ρ) (r_c^{2n} + r_p^{2n})^{1/n} / (max(ρ, r_c)^{2n} + r_p^{2n})^{1/n}

(:func:`structure_factor_table`; T ≡ 1 when all circulation lies within r_c, T → 1 far away).
A vortex rolled up from a narrow tip-loaded sheet stays concentrated, one from a sheet half a
radius wide is diffuse. ``"point"`` is the thesis' point vortex (T ≡ 1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numba as nb
import numpy as np
import pandas as pd

LAMB_OSEEN_ALPHA = 1.25643
AIR_KINEMATIC_VISCOSITY_M2_S = 1.5e-5
VORTEX_STRUCTURES = ("betz", "point")
PROFILE_POINTS = 129  # vortex-structure tables: values at u_m = m / (PROFILE_POINTS − 1)
PROFILE_SCALE_RADII = 0.1  # s / R of the table's radius mapping r_p² = s² u / (1 − u)
STRUCTURE_DEGREE = 10  # T(u) as a polynomial of this degree in x = 2u − 1 per release azimuth
POINT_VORTEX_PROFILE = np.ones((1, 1))  # one coefficient: T ≡ 1 (point vortex)


@dataclass(frozen=True)
class WakeModel:
    """Numerical and model parameters of the prescribed wake (config ``wake:`` block).

    ``a_skew``, ``b_lateral``, ``c_mean``: Beddoes inflow coefficients A, B, C (eq. 5.1);
    ``d_contraction``: Landgrebe D (eq. 5.5); ``revolutions``: wake age kept, in revolutions;
    ``steps_per_rev``: vortex segments per revolution of wake age (segment length 2π/N rad of
    age); ``core_radius_chords``: r_c0 / c; ``core_growth``: Squire core growth on/off with
    ``growth_a1`` (Bhagwat & Leishman turbulence coefficient) and ``viscosity_m2_s``;
    ``release_radius_fraction``: r_r; ``vortex_structure``: ``"betz"`` (rolled-up circulation
    distribution, module doc) or ``"point"`` (the thesis' point vortex).
    """

    a_skew: float = 0.5
    b_lateral: float = 1.0
    c_mean: float = 1.1
    d_contraction: float = 0.85
    revolutions: float = 4.0
    steps_per_rev: int = 360
    core_radius_chords: float = 0.5
    core_growth: bool = False
    growth_a1: float = 6.5e-5
    viscosity_m2_s: float = AIR_KINEMATIC_VISCOSITY_M2_S
    release_radius_fraction: float = 1.0
    vatistas_n: float = 2.0
    vortex_structure: str = "betz"

    def __post_init__(self):
        checks = {
            "vortex_structure": self.vortex_structure in VORTEX_STRUCTURES,
            "d_contraction": 0.0 < self.d_contraction <= 1.0,
            "revolutions": self.revolutions > 0.0,
            "steps_per_rev": self.steps_per_rev >= 8,
            "core_radius_chords": self.core_radius_chords > 0.0,
            "release_radius_fraction": 0.0 < self.release_radius_fraction <= 1.0,
            "vatistas_n": self.vatistas_n >= 1.0,
            "viscosity_m2_s": self.viscosity_m2_s > 0.0,
            "growth_a1": self.growth_a1 >= 0.0,
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

    @classmethod
    def from_config(cls, wake: Mapping, revolutions: float, steps_per_rev: int) -> "WakeModel":
        """From the validated config ``wake:`` block and ``resolution`` entries."""
        return cls(
            a_skew=float(wake["A"]),
            b_lateral=float(wake["B"]),
            c_mean=float(wake["C"]),
            d_contraction=float(wake["D"]),
            core_radius_chords=float(wake["core_radius_chords"]),
            core_growth=bool(wake["core_growth"]),
            vortex_structure=str(wake.get("vortex_structure", "betz")),
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
    (:func:`vortex_profile_table`), needed by ``WakeModel(vortex_structure="betz")``.
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
    """Packed float64 parameters of the numba kernels (see ``_node``)."""
    mu = state.mu_inplane
    lam0 = mean_inflow(state.ct, mu, state.mu_z)
    chi = math.atan2(mu, abs(state.mu_z + lam0))
    r_c0 = model.core_radius_chords * state.chord_m
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
            r_c0,
            # Squire growth: r_c^2 = r_c0^2 + (4 alpha nu / Omega) (1 + a1 Gamma / nu) phi
            (4.0 * LAMB_OSEEN_ALPHA * model.viscosity_m2_s / state.omega_rad_s) if model.core_growth else 0.0,
            model.growth_a1 / model.viscosity_m2_s,
            model.vatistas_n,
        ]
    )


@nb.njit(cache=True, inline="always")
def _periodic_interp(table, psi):
    """Linear interpolation in a uniform periodic table on ψ_i = 2π i / N."""
    n = table.shape[0]
    u = (psi / (2.0 * math.pi)) % 1.0 * n
    i0 = int(math.floor(u))
    w = u - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    return (1.0 - w) * table[i0] + w * table[i1]


@nb.njit(cache=True)
def _node(p, gamma_tab, beta_tab, psi_v, phi):
    """Position (m, H'), strength and core radius of the tip vortex released at ψ_v, age φ."""
    radius, mu, psi_w, mu_z, lam0, chi = p[0], p[2], p[3], p[4], p[5], p[6]
    ct, a, b, c, d, r_r = p[7], p[8], p[9], p[10], p[11], p[12]
    r_v = r_r * (d + (1.0 - d) * math.exp(-(0.145 + 27.0 * ct) * phi))
    psi_rel = psi_v - psi_w
    cw, sw = math.cos(psi_rel), math.sin(psi_rel)
    xw = r_v * cw + mu * phi
    yw = r_v * sw
    beta = _periodic_interp(beta_tab, psi_v)
    lateral = abs(r_v * sw)
    z = r_r * math.sin(beta) - mu_z * phi - lam0 * phi * (
        a * chi * (cw + mu * phi / (2.0 * r_v) - lateral * lateral * lateral) - 2.0 * b * mu * sw + c
    )
    cpw, spw = math.cos(psi_w), math.sin(psi_w)
    gamma = _periodic_interp(gamma_tab, psi_v)
    return (
        radius * (xw * cpw - yw * spw),
        radius * (xw * spw + yw * cpw),
        radius * z,
        gamma,
    )


@nb.njit(cache=True, inline="always")
def _core_radius(p, gamma, phi):
    r_c0, growth, a1_over_nu = p[14], p[15], p[16]
    return math.sqrt(r_c0 * r_c0 + growth * (1.0 + a1_over_nu * abs(gamma)) * phi)


@nb.njit(cache=True, inline="always")
def _structure_factor(coefficients, rp2, s2):
    """T(r_p): the polynomial ``coefficients`` (STRUCTURE_DEGREE + 1,) (power basis, constant
    first) in x = 2u − 1, u = r_p² / (r_p² + s²) (:func:`structure_factor_coefficients`); no
    table look-up, so the loop over points still vectorises. Non-finite r_p² reads T(0)."""
    u = rp2 / (rp2 + s2)
    x = 2.0 * min(u, 1.0) - 1.0 if u >= 0.0 else -1.0
    t = coefficients[STRUCTURE_DEGREE]
    for d in range(STRUCTURE_DEGREE - 1, -1, -1):
        t = t * x + coefficients[d]
    return t


@nb.njit(cache=True, inline="always")
def _segment(r1x, r1y, r1z, n1, r2x, r2y, r2z, n2, gamma, rc, n, structured, profile, s2):
    """Velocity at P induced by the straight vortex segment A→B (eq. 5.10–5.15, Vatistas).

    Arguments are r1 = P − A, r2 = P − B and their norms (so that a polyline sweep reuses
    each node's vector). With r0 = B − A = r1 − r2 and r_p = |r1×r2|/|r0| (distance to the
    segment's line):

        V = Γ T(r_p)/(4π) (r1×r2) r0·(r1/|r1| − r2/|r2|) / (|r0|² (r_c^{2n} + r_p^{2n})^{1/n})

    which is eq. 5.15 (with ê r_p = r1×r2/|r0|) times the vortex-structure factor T of
    ``profile`` when ``structured`` (one release azimuth's coefficients, :func:`_structure_factor`
    with the scale ``s2`` = s²); the point vortex (``structured`` False, T ≡ 1) is eq. 5.15 itself. Finite
    everywhere; zero on the line itself. Branch-free in the geometry (a degenerate segment, P on
    an end node or a zero denominator select k = 0), so that loops over points vectorise
    (:func:`_polyline_points`; pass ``structured`` as a literal so that the compiler drops the
    unused branch).
    """
    r0x, r0y, r0z = r1x - r2x, r1y - r2y, r1z - r2z
    cx = r1y * r2z - r1z * r2y
    cy = r1z * r2x - r1x * r2z
    cz = r1x * r2y - r1y * r2x
    r0sq = r0x * r0x + r0y * r0y + r0z * r0z
    dot = (r0x * r1x + r0y * r1y + r0z * r1z) / n1 - (r0x * r2x + r0y * r2y + r0z * r2z) / n2
    rp2 = (cx * cx + cy * cy + cz * cz) / r0sq
    if n == 2.0:
        den = math.sqrt(rc * rc * rc * rc + rp2 * rp2)
    else:
        den = (rc ** (2.0 * n) + rp2**n) ** (1.0 / n)
    if structured:
        gamma = gamma * _structure_factor(profile, rp2, s2)
    k = gamma / (4.0 * math.pi) * dot / (r0sq * den)
    k = k if (r0sq != 0.0) & (n1 != 0.0) & (n2 != 0.0) & (den != 0.0) else 0.0
    return k * cx, k * cy, k * cz


@nb.njit(cache=True, inline="always")
def _polyline_points(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n,
                     r1x, r1y, r1z, n1, vx, vy, vz):
    """Add to (vx, vy, vz) (n_pts,) the velocity at the points (px, py, pz) (n_pts,) of blade k's
    tip vortex between nodes ``j_start`` and ``j_end`` of ``nodes`` (B, J+1, 3): segment j joins
    nodes j and j+1 and carries g_sign · their mean strength, their mean core and the
    structure-factor coefficients ``profiles[row[k, j]]`` (scale ``s2``; :func:`_segment`; one
    column: point vortex).
    Segment-outer, point-inner (vectorises); each point sums segment by segment in order.
    r1x … n1 (n_pts,): scratch."""
    # literals let the compiler drop the structure factor (point vortex) and the general-n power law from the
    # loop (a run-time flag is not unswitched: the point-vortex kernel then runs about 2x slower, measured)
    if profiles.shape[1] == 1:
        _sweep_n(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, False,
                 r1x, r1y, r1z, n1, vx, vy, vz)
    else:
        _sweep_n(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, True,
                 r1x, r1y, r1z, n1, vx, vy, vz)


@nb.njit(cache=True, inline="always")
def _sweep_n(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
             r1x, r1y, r1z, n1, vx, vy, vz):
    """:func:`_sweep` with the Vatistas exponent as a literal where it is 2."""
    if n == 2.0:
        _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, 2.0, structured,
               r1x, r1y, r1z, n1, vx, vy, vz)
    else:
        _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
               r1x, r1y, r1z, n1, vx, vy, vz)


@nb.njit(cache=True, inline="always")
def _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
           r1x, r1y, r1z, n1, vx, vy, vz):
    """The loops of :func:`_polyline_points`."""
    n_pts = px.shape[0]
    for m in range(n_pts):
        r1x[m], r1y[m], r1z[m] = px[m] - nodes[k, j_start, 0], py[m] - nodes[k, j_start, 1], pz[m] - nodes[k, j_start, 2]
        n1[m] = math.sqrt(r1x[m] * r1x[m] + r1y[m] * r1y[m] + r1z[m] * r1z[m])
    for j in range(j_start, j_end):
        ax, ay, az = nodes[k, j + 1, 0], nodes[k, j + 1, 1], nodes[k, j + 1, 2]
        gamma = g_sign * 0.5 * (strength[k, j] + strength[k, j + 1])
        rc = 0.5 * (core[k, j] + core[k, j + 1])
        profile = profiles[row[k, j]]
        for m in range(n_pts):
            r2x, r2y, r2z = px[m] - ax, py[m] - ay, pz[m] - az
            n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z)
            dx, dy, dz = _segment(r1x[m], r1y[m], r1z[m], n1[m], r2x, r2y, r2z, n2, gamma, rc, n, structured, profile,
                                  s2)
            r1x[m], r1y[m], r1z[m], n1[m] = r2x, r2y, r2z, n2
            vx[m] += dx
            vy[m] += dy
            vz[m] += dz


@nb.njit(cache=True, parallel=True, error_model="numpy")
def _segments_kernel(points, starts, ends, gamma, rc, n):
    out = np.zeros_like(points)
    for i in nb.prange(points.shape[0]):
        vx = vy = vz = 0.0
        for j in range(starts.shape[0]):
            r1x, r1y, r1z = points[i, 0] - starts[j, 0], points[i, 1] - starts[j, 1], points[i, 2] - starts[j, 2]
            r2x, r2y, r2z = points[i, 0] - ends[j, 0], points[i, 1] - ends[j, 1], points[i, 2] - ends[j, 2]
            n1 = math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z)
            n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z)
            dx, dy, dz = _segment(r1x, r1y, r1z, n1, r2x, r2y, r2z, n2, gamma[j], rc[j], n, False, POINT_VORTEX_PROFILE[0],
                                  1.0)
            vx += dx
            vy += dy
            vz += dz
        out[i, 0], out[i, 1], out[i, 2] = vx, vy, vz
    return out


def segment_induced_velocity(points, starts, ends, gamma_m2_s, core_radius_m, vatistas_n: float = 2.0) -> np.ndarray:
    """Velocity (m/s) at ``points`` (N, 3) induced by straight vortex segments start→end (M, 3).

    Γ > 0 circulates right-handed about start→end. Vatistas core of radius ``core_radius_m``
    (scalar or (M,)) with exponent ``vatistas_n`` (eq. 5.15); any frame, metres.
    """
    points = np.ascontiguousarray(np.atleast_2d(points), dtype=float)
    starts = np.ascontiguousarray(np.atleast_2d(starts), dtype=float)
    ends = np.ascontiguousarray(np.atleast_2d(ends), dtype=float)
    if points.shape[1] != 3 or starts.shape != ends.shape or starts.shape[1] != 3:
        raise ValueError(f"segment_induced_velocity: shapes {points.shape}, {starts.shape}, {ends.shape}")
    m = starts.shape[0]
    gamma = np.broadcast_to(np.asarray(gamma_m2_s, dtype=float), (m,)).copy()
    rc = np.broadcast_to(np.asarray(core_radius_m, dtype=float), (m,)).copy()
    if np.any(rc < 0.0):
        raise ValueError("segment_induced_velocity: core radius must be >= 0")
    return _segments_kernel(points, starts, ends, gamma, rc, float(vatistas_n))


@nb.njit(cache=True, inline="always")
def profile_row(psi_v, n_rows):
    """Row of a periodic table of ``n_rows`` release azimuths ψ_i = 2π i / n nearest to ψ_v."""
    return int(math.floor((psi_v / (2.0 * math.pi)) % 1.0 * n_rows + 0.5)) % n_rows


@nb.njit(cache=True)
def _blade_wake(p, gamma_tab, beta_tab, psi_blade, n_age, n_rows, nodes, strength, core, row):
    """Nodes of every blade's tip vortex when blade 0 is at ``psi_blade`` (into given arrays).

    nodes (B, n_age+1, 3) in m (H'); strength Γ(ψ_v), core radius r_c(Γ, φ) and the row of the
    structure-factor table (``n_rows`` rows, :func:`profile_row` of ψ_v) per node
    (B, n_age+1). A segment carries the mean of its two nodes' strengths and cores and the
    first node's row.
    """
    n_blades = int(p[1])
    dphi = p[13]
    for k in range(n_blades):
        psi_k = psi_blade + 2.0 * math.pi * k / n_blades
        for j in range(n_age + 1):
            phi = j * dphi
            x, y, z, g = _node(p, gamma_tab, beta_tab, psi_k - phi, phi)
            nodes[k, j, 0], nodes[k, j, 1], nodes[k, j, 2] = x, y, z
            strength[k, j] = g
            core[k, j] = _core_radius(p, g, phi)
            row[k, j] = profile_row(psi_k - phi, n_rows)


@nb.njit(cache=True, parallel=True, error_model="numpy")
def _disk_kernel(p, gamma_tab, beta_tab, profiles, s2, psi_eval, points, n_age):
    """Induced velocity (H', m/s) at points (n_psi, n_r, 3) when blade 0 is at psi_eval[i].

    Each azimuth row builds its own wake snapshot (periodic flight: the wake seen at ψ_b
    depends only on ψ_b), so rows run in parallel. ``profiles`` (n_rows, STRUCTURE_DEGREE + 1):
    structure-factor coefficients per release azimuth, or (1, 1) for the point vortex
    (:func:`vortex_profiles`), scale ``s2`` (m²).
    """
    n_psi, n_r = points.shape[0], points.shape[1]
    n_blades = int(p[1])
    n = p[17]
    out = np.zeros((n_psi, n_r, 3))
    for i in nb.prange(n_psi):
        nodes = np.empty((n_blades, n_age + 1, 3))
        strength = np.empty((n_blades, n_age + 1))
        core = np.empty((n_blades, n_age + 1))
        row = np.empty((n_blades, n_age + 1), dtype=np.int64)
        _blade_wake(p, gamma_tab, beta_tab, psi_eval[i], n_age, profiles.shape[0], nodes, strength, core, row)
        px, py, pz = points[i, :, 0].copy(), points[i, :, 1].copy(), points[i, :, 2].copy()
        scratch = np.empty((4, n_r))
        vx, vy, vz = np.zeros(n_r), np.zeros(n_r), np.zeros(n_r)
        for k in range(n_blades):
            _polyline_points(px, py, pz, nodes, strength, core, profiles, row, s2, k, 0, n_age, 1.0, n,
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
    _blade_wake(p, gamma_tab, beta_tab, float(psi_blade_rad), n_age, 1, nodes, strength, core, row)
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
    p = wake_scalars(state, model)
    profiles, s2 = vortex_profiles(state, model)
    return _disk_kernel(
        p,
        np.ascontiguousarray(state.gamma_table_m2_s, dtype=float),
        np.ascontiguousarray(state.beta_table_rad, dtype=float),
        profiles,
        s2,
        psi,
        points,
        model.n_age,
    )


def vortex_profiles(state: WakeState, model: WakeModel) -> tuple[np.ndarray, float]:
    """(structure-factor coefficients (n_rows, STRUCTURE_DEGREE + 1), scale s² in m²) of the
    model's vortex structure: the state's Betz roll-up with the model's core r_c0 for ``"betz"``
    (:func:`structure_factor_coefficients`), the one-coefficient point vortex for ``"point"``."""
    if model.vortex_structure == "point":
        return POINT_VORTEX_PROFILE, 1.0
    if state.vortex_profile is None:
        raise ValueError("WakeModel(vortex_structure='betz') needs WakeState.vortex_profile (the loads' "
                         "circulation through nps.wake.prescribed.vortex_profile_table; nps.wake.bvi.wake_state builds it)")
    scale = PROFILE_SCALE_RADII * state.radius_m
    coefficients = structure_factor_coefficients(state.vortex_profile, scale, model.core_radius_chords * state.chord_m,
                                                 model.vatistas_n)
    return coefficients, scale * scale


def structure_factor_coefficients(enclosed_fraction, scale_m: float, core_radius_m: float,
                                  vatistas_n: float = 2.0) -> np.ndarray:
    """Power-basis coefficients (n_rows, STRUCTURE_DEGREE + 1) in x = 2u − 1 of the structure
    factor of each row of enclosed-circulation fractions (:func:`structure_factor_table`): the
    Chebyshev interpolant through the Gauss–Lobatto points x_k = cos(πk/D), D = STRUCTURE_DEGREE
    (discrete cosine transform), converted to powers of x. Elementwise sums only (no BLAS or LAPACK),
    so that the coefficients, and the loads, are bit-identical on every CPU."""
    degree = STRUCTURE_DEGREE
    k = np.arange(degree + 1)
    u = 0.5 * (np.cos(np.pi * k / degree) + 1.0)
    with np.errstate(divide="ignore"):
        radii = scale_m * np.sqrt(u / (1.0 - u))
    values = structure_factor_table(enclosed_fraction, scale_m, core_radius_m, vatistas_n, radii)
    end_halved = np.where((k == 0) | (k == degree), 0.5, 1.0)
    cosines = np.cos(np.pi * np.outer(k, k) / degree) * end_halved[None, :]
    chebyshev = (2.0 / degree) * (values[:, None, :] * cosines[None, :, :]).sum(axis=-1) * end_halved[None, :]
    to_powers = np.zeros((degree + 1, degree + 1))  # row j: T_j(x) in powers of x (integers)
    for j in range(degree + 1):
        powers = np.polynomial.chebyshev.cheb2poly(np.eye(degree + 1)[j])
        to_powers[j, : powers.size] = powers
    return np.ascontiguousarray((chebyshev[:, :, None] * to_powers[None, :, :]).sum(axis=1))


def profile_radii(scale_m: float) -> np.ndarray:
    """Radii ρ_m = s √(u_m / (1 − u_m)) (m) of the vortex-structure tables (the last is +inf)."""
    u = np.linspace(0.0, 1.0, PROFILE_POINTS)
    with np.errstate(divide="ignore"):
        return scale_m * np.sqrt(u / (1.0 - u))


def structure_factor_table(enclosed_fraction, scale_m: float, core_radius_m: float, vatistas_n: float = 2.0,
                           radii_m=None) -> np.ndarray:
    """Structure factor T (n_rows, n_radii) of enclosed-circulation fractions B (n_rows, M) on the
    :func:`profile_radii` grid (module doc), at ``radii_m`` (default: that grid; +inf gives 1): the
    increment of B between two grid radii counts at their mean radius (the last, infinite interval
    carries no circulation once B = 1). Elementwise sums (bit-identical on every CPU)."""
    b = np.asarray(enclosed_fraction, dtype=float)
    rho = profile_radii(scale_m)
    r = rho if radii_m is None else np.asarray(radii_m, dtype=float)
    finite = np.isfinite(r)
    mid = np.maximum(0.5 * (rho[1:-1] + rho[:-2]), core_radius_m)
    two_n = 2.0 * vatistas_n
    rf = r[finite][:, None]
    weights = (core_radius_m**two_n + rf**two_n) ** (1.0 / vatistas_n) / (mid[None, :] ** two_n + rf**two_n) ** (1.0 / vatistas_n)
    table = np.ones((b.shape[0], r.size))
    table[:, finite] = b[:, :1] + (np.diff(b[:, :-1], axis=1)[:, None, :] * weights[None, :, :]).sum(axis=-1)
    return np.ascontiguousarray(table)


def betz_enclosed_circulation(r_m, circulation_m2_s, radius_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Betz roll-up of one blade's trailed sheet: (ρ (m), Γ_enclosed (m²/s)), ascending in ρ.

    The vorticity trailed outboard of y (between the circulation peak and the tip, where
    Γ(R) = 0 closes the distribution) rolls up within ρ(y) = ∫_y^R Γ dr / Γ(y) of the vortex
    centre (the distance from y to the centroid of that vorticity; Betz 1932, Donaldson 1971),
    so Γ_enclosed(ρ(y)) = Γ(y). Trapezoidal integration over the stations ``r_m`` (ascending,
    < R) plus the tip; stations with Γ ≤ 0 (negative tip loading) trail no positive vorticity
    and are skipped; the enclosed circulation is made monotone (running maximum from the centre).
    Starts with (0, 0) and ends at (ρ_max, Γ_max); empty beyond (0, 0) when Γ_max ≤ 0.
    """
    r = np.append(np.asarray(r_m, dtype=float), float(radius_m))
    gamma = np.append(np.asarray(circulation_m2_s, dtype=float), 0.0)
    peak = int(np.argmax(gamma))
    outer_integral = np.concatenate([np.cumsum((0.5 * (gamma[1:] + gamma[:-1]) * np.diff(r))[::-1])[::-1], [0.0]])
    keep = np.arange(r.size) >= peak
    keep &= gamma > 0.0
    rho = outer_integral[keep] / gamma[keep]
    enclosed = gamma[keep]
    order = np.argsort(rho, kind="stable")
    rho, enclosed = rho[order], np.maximum.accumulate(enclosed[order])
    return np.concatenate([[0.0], rho]), np.concatenate([[0.0], enclosed])


def vortex_profile_table(r_m, circulation_m2_s, radius_m: float) -> np.ndarray:
    """Enclosed-circulation fractions B = Γ_enclosed / Γ_max (n_psi, PROFILE_POINTS) of every
    azimuth row of the bound circulation (n_psi, n_r) (:func:`betz_enclosed_circulation`) on the
    :func:`profile_radii` grid, s = PROFILE_SCALE_RADII · R (B = 1 at the last, infinite radius).
    A row whose circulation is nowhere positive is a point vortex (B = 0 at ρ = 0, 1 beyond)."""
    gamma = np.asarray(circulation_m2_s, dtype=float)
    if gamma.ndim != 2 or gamma.shape[1] != np.size(r_m):
        raise ValueError(f"vortex_profile_table: expected (n_psi, {np.size(r_m)}) circulation, got {gamma.shape}")
    rho_grid = profile_radii(PROFILE_SCALE_RADII * radius_m)
    out = np.ones((gamma.shape[0], PROFILE_POINTS))
    out[:, 0] = 0.0
    for i, row in enumerate(gamma):
        rho, enclosed = betz_enclosed_circulation(r_m, row, radius_m)
        if enclosed[-1] > 0.0:
            out[i] = np.interp(rho_grid, rho, enclosed / enclosed[-1], right=1.0)
    return out


def to_hub_frame(vectors_hp, rotation_sign: int) -> np.ndarray:
    """Map vectors or positions (..., 3) from the ccw-equivalent frame H' to the hub frame H."""
    out = np.array(vectors_hp, dtype=float, copy=True)
    out[..., 1] *= rotation_sign
    return out


def tip_vortex_strength(circulation_m2_s: np.ndarray) -> np.ndarray:
    """Γ_v per azimuth row: the spanwise maximum of the bound circulation (n_psi, n_r) → (n_psi,).

    Betz rollup: all trailed vorticity outboard of the circulation peak rolls up into the tip
    vortex, whose strength is then Γ_max − Γ_tip ≈ Γ_max (Γ → 0 at the tip with tip loss).
    """
    gamma = np.asarray(circulation_m2_s, dtype=float)
    if gamma.ndim != 2:
        raise ValueError(f"tip_vortex_strength: expected (n_psi, n_r) circulation, got {gamma.shape}")
    return gamma.max(axis=1)


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
