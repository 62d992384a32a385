"""The tip vortex shared by both wakes: core, core growth, Vatistas profile, Betz structure, Biot–Savart.

Thesis chapter 5 (eq. 5.10–5.15), with the errata documented in ``docs/reference/wake_bvi.md``. The
prescribed wake (:mod:`nps.wake.prescribed`) and the free wake (:mod:`nps.wake.free`) place the
vortex; this module says what it is and what velocity it induces.

Core (:class:`VortexModel`): Vatistas profile with exponent n (n = 2 in the thesis, eq. 5.15),
radius r_c0 = ``core_radius_chords`` · c, optionally grown with wake age φ (Lamb–Oseen/Squire with
Bhagwat & Leishman's turbulent viscosity):

    r_c² = r_c0² + 4 α δ ν φ/Ω,   α = 1.25643,   δ = 1 + a₁ |Γ|/ν                  (:func:`core_radius`)

Vortex structure (``VortexModel.vortex_structure``): ``"betz"`` gives each vortex the radial
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
radius wide is diffuse. ``"point"`` is the thesis' point vortex (T ≡ 1). Strength: Γ_v(ψ_v) =
max_r Γ(ψ_v, r), the bound circulation rolled up outboard of its spanwise maximum
(:func:`tip_vortex_strength`).

Biot–Savart: straight segments (:func:`segment_velocity`, eq. 5.10–5.15) and polylines of them
(:func:`add_polyline_velocity`); any frame, metres, Γ > 0 right-handed about start → end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from nps.core.jit import kernel, prange

LAMB_OSEEN_ALPHA = 1.25643
AIR_KINEMATIC_VISCOSITY_M2_S = 1.5e-5
# Bhagwat & Leishman (2000): δ = 1 + a₁ Γ_v/ν with a₁ = 6.5e-5 from rotor tip-vortex measurements.
BHAGWAT_LEISHMAN_A1 = 6.5e-5
VORTEX_STRUCTURES = ("betz", "point")
PROFILE_POINTS = 129  # vortex-structure tables: values at u_m = m / (PROFILE_POINTS − 1)
PROFILE_SCALE_RADII = 0.1  # s / R of the table's radius mapping r_p² = s² u / (1 − u)
STRUCTURE_DEGREE = 10  # T(u) as a polynomial of this degree in x = 2u − 1 per release azimuth
POINT_VORTEX_PROFILE = np.ones((1, 1))  # one coefficient: T ≡ 1 (point vortex)


@dataclass(frozen=True)
class VortexModel:
    """The tip vortex (module doc): ``core_radius_chords`` r_c0/c (–); ``core_growth``: Squire
    core growth with age on/off, with ``growth_a1`` a₁ (–, Bhagwat & Leishman turbulence
    coefficient) and ``viscosity_m2_s`` ν (m²/s); ``vatistas_n``: Vatistas exponent n (eq. 5.15);
    ``vortex_structure``: ``"betz"`` (rolled-up circulation distribution) or ``"point"`` (the
    thesis' point vortex)."""

    core_radius_chords: float = 0.5
    core_growth: bool = False
    growth_a1: float = BHAGWAT_LEISHMAN_A1
    viscosity_m2_s: float = AIR_KINEMATIC_VISCOSITY_M2_S
    vatistas_n: float = 2.0
    vortex_structure: str = "betz"

    def __post_init__(self):
        checks = {
            "core_radius_chords": self.core_radius_chords > 0.0,
            "growth_a1": self.growth_a1 >= 0.0,
            "viscosity_m2_s": self.viscosity_m2_s > 0.0,
            "vatistas_n": self.vatistas_n >= 1.0,
            "vortex_structure": self.vortex_structure in VORTEX_STRUCTURES,
        }
        bad = [name for name, ok in checks.items() if not ok]
        if bad:
            raise ValueError(f"VortexModel: invalid {bad} in {self}")

    @classmethod
    def from_config(cls, wake: Mapping) -> "VortexModel":
        """From the validated config ``wake:`` block (``core_radius_chords``, ``core_growth``,
        ``vortex_structure``; the other fields keep their values)."""
        return cls(
            core_radius_chords=float(wake["core_radius_chords"]),
            core_growth=bool(wake["core_growth"]),
            vortex_structure=str(wake["vortex_structure"]),
        )

    def core_constants(self, chord_m: float, omega_rad_s: float) -> np.ndarray:
        """(r_c0 (m), growth coefficient 4 α ν / Ω (m²/rad, 0 without growth), a₁/ν (s/m²)) of
        :func:`core_radius` for a blade of chord ``chord_m`` turning at ``omega_rad_s``."""
        return np.array([
            self.core_radius_chords * chord_m,
            # Squire growth: r_c^2 = r_c0^2 + (4 alpha nu / Omega) (1 + a1 Gamma / nu) phi
            (4.0 * LAMB_OSEEN_ALPHA * self.viscosity_m2_s / omega_rad_s) if self.core_growth else 0.0,
            self.growth_a1 / self.viscosity_m2_s,
        ])

    def structure_coefficients(self, enclosed_fraction, radius_m: float, chord_m: float) -> tuple[np.ndarray, float]:
        """(structure-factor coefficients (n_rows, STRUCTURE_DEGREE + 1), scale s² in m²) of the
        vortex structure: the Betz roll-up ``enclosed_fraction`` (n_rows, PROFILE_POINTS)
        (:func:`vortex_profile_table`) with the core r_c0 for ``"betz"``
        (:func:`structure_factor_coefficients`), the one-coefficient point vortex for ``"point"``."""
        if self.vortex_structure == "point":
            return POINT_VORTEX_PROFILE, 1.0
        if enclosed_fraction is None:
            raise ValueError("vortex_structure 'betz' needs the vortex profile (WakeState.vortex_profile: the loads' "
                             "circulation through nps.wake.vortex.vortex_profile_table; nps.wake.bvi.wake_state builds it)")
        scale = PROFILE_SCALE_RADII * radius_m
        coefficients = structure_factor_coefficients(enclosed_fraction, scale, self.core_radius_chords * chord_m,
                                                     self.vatistas_n)
        return coefficients, scale * scale


@kernel(inline=True)
def core_radius(core, gamma, phi):
    """Core radius r_c (m) of a vortex of strength ``gamma`` (m²/s) at wake age ``phi`` (rad);
    ``core`` (3,): :meth:`VortexModel.core_constants`."""
    return math.sqrt(core[0] * core[0] + core[1] * (1.0 + core[2] * abs(gamma)) * phi)


@kernel(inline=True)
def _structure_factor(coefficients, c2, r0sq, s2):
    """T(r_p): the polynomial ``coefficients`` (STRUCTURE_DEGREE + 1,) (power basis, constant
    first) in x = 2u − 1, u = r_p² / (r_p² + s²) = |r1×r2|² / (|r1×r2|² + s²|r0|²) with
    r_p² = |r1×r2|²/|r0|² (``c2`` = |r1×r2|², ``r0sq`` = |r0|², :func:`segment_velocity`;
    :func:`structure_factor_coefficients`); no table look-up, so the loop over points still
    vectorises. Non-finite u reads T(0)."""
    u = c2 / (c2 + s2 * r0sq)
    x = 2.0 * min(u, 1.0) - 1.0 if u >= 0.0 else -1.0
    t = coefficients[STRUCTURE_DEGREE]
    for d in range(STRUCTURE_DEGREE - 1, -1, -1):
        t = t * x + coefficients[d]
    return t


@kernel(inline=True)
def structure_row(profiles, row, structured):
    """Row ``row`` of the structure-factor table ``profiles`` (n_rows, STRUCTURE_DEGREE + 1) as a tuple
    of scalars, (1, 0, …, 0) (T ≡ 1) when not ``structured``: the compiler keeps a tuple in registers,
    while an array row may alias the velocity sums and is read again at every point, which stops the
    loop over points from vectorising (3x slower, measured)."""
    if structured:
        c = profiles[row]
        return (c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9], c[10])
    return (1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


assert STRUCTURE_DEGREE == 10, "structure_row spells out STRUCTURE_DEGREE + 1 coefficients"


@kernel(inline=True)
def segment_velocity(r1x, r1y, r1z, n1, r2x, r2y, r2z, n2, gamma, rc, n, structured, profile, s2):
    """Velocity at P induced by the straight vortex segment A→B (eq. 5.10–5.15, Vatistas).

    Arguments are r1 = P − A, r2 = P − B and their norms (so that a polyline sweep reuses
    each node's vector). With r0 = B − A = r1 − r2 and r_p = |r1×r2|/|r0| (distance to the
    segment's line):

        V = Γ T(r_p)/(4π) (r1×r2) r0·(r1/|r1| − r2/|r2|) / (|r0|² (r_c^{2n} + r_p^{2n})^{1/n})

    which is eq. 5.15 (with ê r_p = r1×r2/|r0|) times the vortex-structure factor T of
    ``profile`` when ``structured`` (one release azimuth's coefficients, :func:`structure_row`, :func:`_structure_factor`
    with the scale ``s2`` = s²); the point vortex (``structured`` False, T ≡ 1) is eq. 5.15 itself. Finite
    everywhere; zero on the line itself. Branch-free in the geometry (a degenerate segment, P on
    an end node or a zero denominator select k = 0), so that loops over points vectorise
    (:func:`add_polyline_velocity`; pass ``structured`` as a literal so that the compiler drops the
    unused branch).

    Evaluated with one division and two square roots per segment and point (the divider bounds the
    sweep): the factor is
    [(r0·r1)|r2| − (r0·r2)|r1|] / (|r1| |r2| D) with D = |r0|² (r_c^{2n} + r_p^{2n})^{1/n}, which
    for n = 2 is (r_c⁴|r0|⁴ + |r1×r2|⁴)^{1/2} (no division by |r0|²).
    """
    r0x, r0y, r0z = r1x - r2x, r1y - r2y, r1z - r2z
    cx = r1y * r2z - r1z * r2y
    cy = r1z * r2x - r1x * r2z
    cz = r1x * r2y - r1y * r2x
    r0sq = r0x * r0x + r0y * r0y + r0z * r0z
    c2 = cx * cx + cy * cy + cz * cz
    dot = (r0x * r1x + r0y * r1y + r0z * r1z) * n2 - (r0x * r2x + r0y * r2y + r0z * r2z) * n1
    if n == 2.0:
        rc2 = rc * rc
        vatistas = math.sqrt(rc2 * rc2 * r0sq * r0sq + c2 * c2)
    else:
        vatistas = r0sq * (rc ** (2.0 * n) + (c2 / r0sq) ** n) ** (1.0 / n)
    if structured:
        gamma = gamma * _structure_factor(profile, c2, r0sq, s2)
    den = n1 * n2 * vatistas
    k = gamma / (4.0 * math.pi) * dot / den
    k = k if (r0sq != 0.0) & (den != 0.0) else 0.0
    return k * cx, k * cy, k * cz


@kernel(inline=True)
def add_polyline_velocity(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n,
                          r1x, r1y, r1z, n1, vx, vy, vz):
    """Add to (vx, vy, vz) (n_pts,) the velocity at the points (px, py, pz) (n_pts,) of blade k's
    tip vortex between nodes ``j_start`` and ``j_end`` of ``nodes`` (B, J+1, 3): segment j joins
    nodes j and j+1 and carries g_sign · their mean strength, their mean core and the
    structure-factor coefficients ``profiles[row[k, j]]`` (scale ``s2``; :func:`segment_velocity`; one
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


@kernel(inline=True)
def _sweep_n(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
             r1x, r1y, r1z, n1, vx, vy, vz):
    """:func:`_sweep` with the Vatistas exponent as a literal where it is 2."""
    if n == 2.0:
        _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, 2.0, structured,
               r1x, r1y, r1z, n1, vx, vy, vz)
    else:
        _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
               r1x, r1y, r1z, n1, vx, vy, vz)


@kernel(inline=True)
def _sweep(px, py, pz, nodes, strength, core, profiles, row, s2, k, j_start, j_end, g_sign, n, structured,
           r1x, r1y, r1z, n1, vx, vy, vz):
    """The loops of :func:`add_polyline_velocity`."""
    n_pts = px.shape[0]
    for m in range(n_pts):
        r1x[m], r1y[m], r1z[m] = px[m] - nodes[k, j_start, 0], py[m] - nodes[k, j_start, 1], pz[m] - nodes[k, j_start, 2]
        n1[m] = math.sqrt(r1x[m] * r1x[m] + r1y[m] * r1y[m] + r1z[m] * r1z[m])
    for j in range(j_start, j_end):
        ax, ay, az = nodes[k, j + 1, 0], nodes[k, j + 1, 1], nodes[k, j + 1, 2]
        gamma = g_sign * 0.5 * (strength[k, j] + strength[k, j + 1])
        rc = 0.5 * (core[k, j] + core[k, j + 1])
        profile = structure_row(profiles, row[k, j], structured)
        for m in range(n_pts):
            r2x, r2y, r2z = px[m] - ax, py[m] - ay, pz[m] - az
            n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z)
            dx, dy, dz = segment_velocity(r1x[m], r1y[m], r1z[m], n1[m], r2x, r2y, r2z, n2, gamma, rc, n, structured, profile,
                                  s2)
            r1x[m], r1y[m], r1z[m], n1[m] = r2x, r2y, r2z, n2
            vx[m] += dx
            vy[m] += dy
            vz[m] += dz


@kernel(parallel=True)
def _segments_kernel(points, starts, ends, gamma, rc, n):
    """Velocity (N, 3) at ``points`` of the point-vortex segments start→end (:func:`segment_induced_velocity`)."""
    out = np.zeros_like(points)
    for i in prange(points.shape[0]):
        vx = vy = vz = 0.0
        for j in range(starts.shape[0]):
            r1x, r1y, r1z = points[i, 0] - starts[j, 0], points[i, 1] - starts[j, 1], points[i, 2] - starts[j, 2]
            r2x, r2y, r2z = points[i, 0] - ends[j, 0], points[i, 1] - ends[j, 1], points[i, 2] - ends[j, 2]
            n1 = math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z)
            n2 = math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z)
            dx, dy, dz = segment_velocity(r1x, r1y, r1z, n1, r2x, r2y, r2z, n2, gamma[j], rc[j], n, False,
                                          POINT_VORTEX_PROFILE[0], 1.0)
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


@kernel(inline=True)
def profile_row(psi_v, n_rows):
    """Row of a periodic table of ``n_rows`` release azimuths ψ_i = 2π i / n nearest to ψ_v."""
    return int(math.floor((psi_v / (2.0 * math.pi)) % 1.0 * n_rows + 0.5)) % n_rows


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


def tip_vortex_strength(circulation_m2_s: np.ndarray) -> np.ndarray:
    """Γ_v per azimuth row: the spanwise maximum of the bound circulation (n_psi, n_r) → (n_psi,).

    Betz rollup: all trailed vorticity outboard of the circulation peak rolls up into the tip
    vortex, whose strength is then Γ_max − Γ_tip ≈ Γ_max (Γ → 0 at the tip with tip loss).
    """
    gamma = np.asarray(circulation_m2_s, dtype=float)
    if gamma.ndim != 2:
        raise ValueError(f"tip_vortex_strength: expected (n_psi, n_r) circulation, got {gamma.shape}")
    return gamma.max(axis=1)
