"""Rotor blade loads: blade element theory, linear inflow, rigid flapping and the three-step trim.

Thesis chapter 4 (eq. 4.1–4.13, Fig. 4.3), errata and choices in ``docs/reference/loads.md``.
Frames and signs: ``docs/reference/conventions.md``. All quantities SI; angles in rad.

Rotor aerodynamic frame
    Every rotor is treated as counterclockwise (seen from +z_H); a clockwise rotor (s = −1)
    uses μ_y' = s μ_y, and its roll quantities are mirrored back (M_x = s M_x', Y = s Y')
    when totals are reported in the hub frame H. ψ is the blade azimuth in the rotor's own
    sense, ψ = 0 aft (along x_H).

Velocities (eq. 4.6–4.7 generalised)
    U_T = Ω r + ΩR (μ_x sin ψ − μ_y' cos ψ)            (toward the leading edge)
    U_R = ΩR (μ_x cos ψ + μ_y' sin ψ)                  (outward)
    U_P = ΩR λ(r, ψ) + (r − e) β̇ + U_R β              (down through the disk)
    with the hinge offset e (the thesis' r β̇ for e = 0).

Linear inflow (eq. 4.3–4.5, design-notes erratum for eq. 4.5)
    λ(r, ψ) = μ_z + λ0 (1 + k_x (r/R) cos ψ + k_y (r/R) sin ψ)
    λ0 = C_T / (2 √(μ² + (μ_z + λ0)²)),  μ² = μ_x² + μ_y²   (Glauert, C_T from the BET itself)
    Coleman: k = tan(χ/2), χ = atan(μ / |μ_z + λ0|) the wake skew, pointing downstream:
    (k_x, k_y) = k (μ_x, μ_y') / μ, i.e. the thesis' k_x = tan(χ/2), k_y = 0 when μ_y = 0.

Pitch (eq. 4.13, erratum)
    θ(r, ψ) = θ0 + θ1c cos ψ + θ1s sin ψ + θ_tw(r), θ_tw from ``RotorGeometry.twist_at``.

Sectional aerodynamics (eq. 4.1–4.2 without the small-angle approximation): see
:func:`section_forces`.

Flapping (rigid blade, hinge offset e, uniform mass; hingeless: a hinge spring K_β, zero at the precone β_p)
    β'' + ν_β² β = M_β(ψ) / (I_β Ω²) + (ν_β² − ν_0²) β_p,   I_β = ρ a c R⁴ / γ,
    ν_0² = 1 + 3e / (2 (R − e)),   ν_β² = ν_0² + K_β / (I_β Ω²)   (Johnson, Helicopter Theory, ch. 9)
    (articulated and teetering hubs: K_β = 0, ν_β = ν_0; hingeless: ν_β configured, held per rev).
    M_β(ψ) = Σ_r (r − e) F_z dr the aerodynamic moment about the hinge, ' = d/dψ. Solved for
    the periodic response by first-harmonic balance, β = β0 + β1c cos ψ + β1s sin ψ:
    ν² β0 = M̄_β / (I_β Ω²) + (ν² − ν_0²) β_p, (ν² − 1) β1c = M_β,1c / (I_β Ω²), (ν² − 1) β1s = M_β,1s / (I_β Ω²),
    solved together with λ0 by Newton's method; β, β̇ then enter U_P. I_β uses the operating
    density (the configured atmosphere) with the configured Lock number.

Pitch–flap coupling (δ3) and teetering hubs (docs/reference/loads.md)
    θ gains −tan δ3 · β_h, β_h the flap angle about the hinge: β for an articulated blade, the teeter
    angle β − β_p for a teetering rotor (β_p its precone). With the harmonic balance above this raises
    the effective flap frequency to ν_e² = ν_β² + (γ/2) tan δ3 ∫(x − ε)x² dx (ν_e² = 1 + (γ/8) tan δ3
    for ε = 0 and no root cutout). A teetering rotor (two blades in one piece on a central hinge,
    e = 0) has no coning degree of freedom: β0 = β_p is held and only λ0, β1c, β1s are solved. Its first-
    harmonic equations are those of an e = 0 blade (the teeter equation 2I_β(β_t'' + β_t) = M_β(ψ) −
    M_β(ψ + π) has twice one blade's first harmonic on the right), so the second blade, at ψ + π, flaps
    β(ψ + π) − β_p = −(β(ψ) − β_p): equal and opposite; the hub moment is zero (K = 0).

Hub moments (H frame, conventions' signs)
    M_x = s (B/2) K β1s (roll, + lifts the advancing side), M_y = −(B/2) K β1c (pitch, + nose
    up), K = I_β Ω² (ν_β² − 1): the blade that flaps up pulls the hub up on its side through
    the hinge offset and the spring. With e = 0 and no spring, K = 0 and the hub moment vanishes
    identically. The blade's mean root moment, I_β Ω² (ν_β² − 1) β0 − K_β β_p, cancels in the rotor's
    hub moment; with e = 0 it is K_β (β0 − β_p), zero when the precone equals the coning.

Trim (Fig. 4.3)
    The thesis pairs "M_x with θ1s and M_y with θ1c". With flapping dynamics the disk answers
    cyclic pitch with a phase lag δ (90° for e = 0 in hover: β1c = −θ1s, β1s = θ1c; ≈ 85° for
    the demonstration helicopter; ≈ 40° for the stiff coaxial rotors), so neither fixed pairing
    converges for every rotor. NPS reads the pairing as "each cyclic step trims one moment":
    the cyclic is phased (as a swashplate is) from the 2 × 2 sensitivity of (M_x, M_y) to
    (θ1c, θ1s), measured once by finite differences at the start, so that the pitch step moves
    (θ1c, θ1s) along the direction that changes M_y only and the roll step along the one that
    changes M_x only. Steps: 1 θ0 → T, 2 phased cyclic → M_y (pitch; mostly θ1s for an
    articulated rotor), 3 phased cyclic → M_x (roll; mostly θ1c), each a secant iteration to a
    quarter of its tolerance with the other directions frozen, repeated until all three meet
    their targets. Tolerances: |T − T*| ≤ tol_rel |T*|; |M − M*| ≤ max(tol_rel |M*|,
    tol_rel T* R) (the absolute part, 0.1 % of T*·R, serves targets near zero). With e = 0 the
    moment steps drive the first-harmonic flapping to zero (tip-path plane perpendicular to the
    shaft) with the same criterion applied to the thrust-tilt moment T* R β1, i.e.
    |β1c|, |β1s| ≤ tol_rel rad; non-zero moment targets are refused for e = 0. Zero moment
    targets mean the same for e > 0.

Prescribed (measured) flapping (``RotorGeometry.prescribed_flap_harmonics``)
    β(ψ) and β̇ = Ω dβ/dψ come from the given harmonics (all of them, n = 0 with the precone);
    only λ0 is solved at given controls. The hub moments are then those the harmonic balance
    gives at convergence, (B/2) K β1 = (B/2) M_β,1 (the first-harmonic aerodynamic moment about
    the hinge): M_x = s (B/2) M_β,1s, M_y = −(B/2) M_β,1c, trimmed by the same phased-cyclic
    steps (the measured blade motion is matched by the airloads that go with it; any e ≥ 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from nps.core.solvers import ConvergenceError, forward_difference_jacobian, limited_secant, newton_fd
from nps.rotor.geometry import TEETERING, OperatingPoint, RotorGeometry, hinge_flap_frequency_sq

DISK_COLUMNS = (
    "psi_rad", "r_m", "dr_m", "chord_m", "thickness_m", "theta_rad", "beta_rad", "beta_dot_rad_s",
    "ut_mps", "up_mps", "inflow_ratio", "alpha_eff_rad", "mach", "fz_N_per_m", "fx_N_per_m",
    "circulation_m2_s",
)
# inflow and flapping at given controls (nps.core.solvers.newton_fd, chord method): converged when every residual
# is below _INNER_TOL (λ0 residual dimensionless, flap harmonic balance in rad); at most _MAX_INNER Newton updates;
# difference steps _INNER_FD_STEP · max(1, 10 |x_j|); the Jacobian is kept while each residual is at most
# _JACOBIAN_REFRESH times the previous one
_INNER_TOL = 1e-10
_MAX_INNER = 30
_INNER_FD_STEP = 1e-7
_JACOBIAN_REFRESH = 0.2
# control steps (nps.core.solvers.limited_secant): each to _SECANT_TOL_FRACTION of its tolerance, control moves
# within ±_MAX_CONTROL_STEP_RAD per step and ±MAX_CONTROL_RAD overall, probes of _PROBE_RAD, a new slope kept
# when above _SLOPE_KEEP_RATIO of the old one
MAX_CONTROL_RAD = 0.7
_MAX_CONTROL_STEP_RAD = 0.1
_SECANT_TOL_FRACTION = 0.25
_PROBE_RAD = 0.01
_SLOPE_KEEP_RATIO = 0.05


class TrimError(RuntimeError):
    """The rotor trim (or its inflow/flapping solution) did not converge."""


@dataclass(frozen=True)
class DiskGrid:
    """Azimuth × radius discretisation: ψ_i = 2π i / n_psi, n_r equal radial elements."""

    n_psi: int
    n_r: int

    def __post_init__(self):
        if not (isinstance(self.n_psi, (int, np.integer)) and self.n_psi >= 8):
            raise ValueError(f"DiskGrid.n_psi: expected an integer >= 8, got {self.n_psi!r}")
        if not (isinstance(self.n_r, (int, np.integer)) and self.n_r >= 2):
            raise ValueError(f"DiskGrid.n_r: expected an integer >= 2, got {self.n_r!r}")

    @property
    def psi_rad(self) -> np.ndarray:
        return 2.0 * np.pi * np.arange(self.n_psi) / self.n_psi


@dataclass(frozen=True)
class SectionForces:
    """Sectional loads per unit span, blade frame (docs/reference/conventions.md), broadcast shape.

    ``fz_N_per_m`` along +z_H (thrust +), ``fx_N_per_m`` in plane opposing the blade's motion,
    ``alpha_eff_rad`` the aerodynamic angle of attack (mod π, see :func:`section_forces`),
    ``mach`` the resultant section Mach number, ``circulation_m2_s`` the bound circulation.
    """

    fz_N_per_m: np.ndarray
    fx_N_per_m: np.ndarray
    alpha_eff_rad: np.ndarray
    mach: np.ndarray
    circulation_m2_s: np.ndarray


@dataclass(frozen=True)
class Controls:
    """Blade pitch controls (rad): collective, lateral (cos ψ) and longitudinal (sin ψ) cyclic."""

    theta0_rad: float
    theta1c_rad: float = 0.0
    theta1s_rad: float = 0.0


@dataclass(frozen=True)
class Flapping:
    """First-harmonic flapping (rad), rotor aerodynamic frame: β = β0 + β1c cos ψ + β1s sin ψ."""

    beta0_rad: float
    beta1c_rad: float
    beta1s_rad: float


@dataclass(frozen=True)
class Inflow:
    """Linear inflow λ_i = λ0 (1 + k_x r/R cos ψ + k_y r/R sin ψ) (aerodynamic frame)."""

    lambda0: float
    kx: float
    ky: float


@dataclass(frozen=True)
class RotorTotals:
    """Rotor forces and moments in the hub frame H (N, N·m, W).

    ``h_force_N`` along +x_H (aft, rotor drag +), ``y_force_N`` along +y_H, ``torque_Nm``
    = Σ r f_x dr (drag torque), ``power_W`` = Q Ω. ``roll_moment_Nm``/``pitch_moment_Nm``:
    hub moments transmitted by flapping; ``aero_*``: moments of the disk's F_z about the hub
    (thesis Fig. 4.7), M_x = s Σ r sin ψ F_z dr, M_y = −Σ r cos ψ F_z dr, averaged × B.
    ``mean_cl`` = 6 C_T / σ, the blade-loading mean lift coefficient.
    """

    thrust_N: float
    h_force_N: float
    y_force_N: float
    torque_Nm: float
    power_W: float
    roll_moment_Nm: float
    pitch_moment_Nm: float
    aero_roll_moment_Nm: float
    aero_pitch_moment_Nm: float
    ct: float
    mean_cl: float


@dataclass(frozen=True)
class RotorTrim:
    """Result of :func:`trim_rotor` (or :func:`rotor_loads` with imposed controls)."""

    disk: pd.DataFrame
    controls: Controls
    flapping: Flapping
    totals: RotorTotals
    history: pd.DataFrame
    inflow: Inflow
    iterations: int
    rotor: str

    def summary(self) -> pd.DataFrame:
        """Long table (``quantity``, ``value``, ``unit``) of the rotor loads summary artifact."""
        t, c, f, i = self.totals, self.controls, self.flapping, self.inflow
        rows = [
            ("theta0_rad", c.theta0_rad, "rad"), ("theta1c_rad", c.theta1c_rad, "rad"),
            ("theta1s_rad", c.theta1s_rad, "rad"), ("beta0_rad", f.beta0_rad, "rad"),
            ("beta1c_rad", f.beta1c_rad, "rad"), ("beta1s_rad", f.beta1s_rad, "rad"),
            ("lambda0", i.lambda0, "-"), ("kx", i.kx, "-"), ("ky", i.ky, "-"),
            ("thrust_N", t.thrust_N, "N"), ("h_force_N", t.h_force_N, "N"), ("y_force_N", t.y_force_N, "N"),
            ("torque_Nm", t.torque_Nm, "N m"), ("power_W", t.power_W, "W"),
            ("roll_moment_Nm", t.roll_moment_Nm, "N m"), ("pitch_moment_Nm", t.pitch_moment_Nm, "N m"),
            ("aero_roll_moment_Nm", t.aero_roll_moment_Nm, "N m"),
            ("aero_pitch_moment_Nm", t.aero_pitch_moment_Nm, "N m"),
            ("ct", t.ct, "-"), ("trim_iterations", float(self.iterations), "-"),
            ("mean_cl", t.mean_cl, "-"),
        ]
        return pd.DataFrame(
            {
                "quantity": [q for q, _, _ in rows],
                "value": np.array([v for _, v, _ in rows], dtype=np.float64),
                "unit": [u for _, _, u in rows],
            }
        )


def radial_stations(geometry: RotorGeometry, n_r: int) -> tuple[np.ndarray, np.ndarray]:
    """Midpoints r (m) and widths dr (m) of n_r equal elements from the root cutout to the tip."""
    edges = np.linspace(geometry.root_cutout_m, geometry.radius_m, int(n_r) + 1)
    return 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)


def section_forces(
    ut_mps,
    up_mps,
    theta_rad,
    r_m,
    geometry: RotorGeometry,
    density_kg_m3: float,
    speed_of_sound_mps: float,
    *,
    tip_loss: bool = True,
) -> SectionForces:
    """Quasi-steady lifting-line section loads (thesis eq. 4.1–4.2, exact angles).

    Arguments broadcast together; velocities in m/s (U_T toward the leading edge, U_P down
    through the disk), pitch θ (rad), radius r (m). With the resultant W = √(U_T² + U_P²),
    inflow angle φ (cos φ = U_T/W, sin φ = U_P/W, any quadrant):

    - angle of attack α = θ − φ reduced mod π to [−π/2, π/2) (the reported angle);
    - c_l, c_d of the local section at M = W / c (:meth:`RotorGeometry.coefficients_at`,
      ``nps.rotor.airfoils``): for the default linear airfoil c_l = a (α − α0) / √(1 − min(M, M_cap)²)
      clipped to ±c_l,max and c_d = cd0 + cd1 α + cd2 α², a section in reverse flow (U_T < 0)
      being a symmetric section seen from behind; a ±180° table is read at the full angle;
    - Prandtl tip loss on the lift, F = (2/π) arccos(exp(−B (R − r) / (2 r |sin φ|)))
      (F → 0 at the tip), when ``tip_loss`` (not on the drag);
    - c the local chord (:meth:`RotorGeometry.chord_at`);
    - F_z = ½ ρ c W (F c_l U_T − c_d U_P) = L cos φ − D sin φ,
      F_x = ½ ρ c W (F c_l U_P + c_d U_T) = L sin φ + D cos φ;
    - Γ = ½ c F c_l W, which is Kutta–Joukowski L/(ρ W) and equals the thrust-direction
      lift L cos φ over ρ U_T (eq. 5.9 with the in-plane velocity), finite where U_T → 0.

    Eq. 4.1–4.2 are the small-angle limit (W → U_T, φ → U_P/U_T) of these expressions.
    """
    ut, up, theta, r = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (ut_mps, up_mps, theta_rad, r_m))
    )
    w = np.sqrt(ut * ut + up * up)
    # atan(U_P/U_T) without the division: equal to φ modulo π
    phi_mod = np.arctan2(np.where(ut < 0.0, -up, up), np.abs(ut))
    alpha = theta - phi_mod
    alpha = alpha - np.pi * np.floor(alpha / np.pi + 0.5)
    mach = w / speed_of_sound_mps
    cl, cd, _ = geometry.coefficients_at(alpha, ut < 0.0, mach, r)
    if tip_loss:
        cl = cl * _tip_loss(w, up, r, geometry)
    chord = geometry.chord_at(r)
    half_rho_c_w = 0.5 * density_kg_m3 * chord * w
    return SectionForces(
        fz_N_per_m=half_rho_c_w * (cl * ut - cd * up),
        fx_N_per_m=half_rho_c_w * (cl * up + cd * ut),
        alpha_eff_rad=alpha,
        mach=mach,
        circulation_m2_s=0.5 * chord * cl * w,
    )


def prandtl_tip_loss(ut_mps, up_mps, r_m, geometry: RotorGeometry) -> np.ndarray:
    """Prandtl tip-loss factor F = (2/π) arccos(exp(−f)), f = B (R − r) W / (2 r |U_P|).

    f uses the local inflow angle |sin φ| = |U_P| / W; F = 0 at and beyond the tip, F → 1
    where U_P → 0 (no trailed-vortex spacing to resolve).
    """
    ut, up, r = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (ut_mps, up_mps, r_m)))
    return _tip_loss(np.sqrt(ut * ut + up * up), up, r, geometry)


def _tip_loss(w, up, r, geometry: RotorGeometry) -> np.ndarray:
    gap = np.maximum(geometry.radius_m - r, 0.0)
    f = (0.5 * geometry.n_blades) * gap * w / (np.maximum(r, 1e-12) * np.maximum(np.abs(up), 1e-12))
    return (2.0 / np.pi) * np.arccos(np.exp(-f))


def flap_frequency_sq(geometry: RotorGeometry) -> float:
    """ν_β² (per rev, squared): 1 + 3e / (2 (R − e)) for a uniform rigid blade hinged at e
    (:func:`~nps.rotor.geometry.hinge_flap_frequency_sq`), the configured ν_β² of a hingeless hub."""
    if geometry.flap_frequency_per_rev is not None:
        return geometry.flap_frequency_per_rev**2
    return hinge_flap_frequency_sq(geometry)


def flap_spring_sq(geometry: RotorGeometry) -> float:
    """K_β / (I_β Ω²) = ν_β² − ν_0² (per rev, squared): the hinge spring of a hingeless hub (0 without one)."""
    if geometry.flap_frequency_per_rev is None:
        return 0.0
    return geometry.flap_frequency_per_rev**2 - hinge_flap_frequency_sq(geometry)


def flap_inertia(geometry: RotorGeometry, density_kg_m3: float) -> float:
    """I_β = ρ a c R⁴ / γ (kg m²), from the Lock number at the operating density."""
    return density_kg_m3 * geometry.airfoil.lift_slope_per_rad * geometry.chord_m * geometry.radius_m**4 / geometry.lock_number


def hub_flap_stiffness(geometry: RotorGeometry, omega_rad_s: float, density_kg_m3: float) -> float:
    """(B/2) K with K = I_β Ω² (ν_β² − 1): hub moment per radian of first-harmonic flapping."""
    k = flap_inertia(geometry, density_kg_m3) * omega_rad_s**2 * (flap_frequency_sq(geometry) - 1.0)
    return 0.5 * geometry.n_blades * k


def check_geometry(geometry: RotorGeometry) -> None:
    """Raise ValueError naming the first invalid field of ``geometry``."""
    g = geometry
    checks = [
        ("n_blades", g.n_blades >= 1, "an integer >= 1"),
        ("radius_m", math.isfinite(g.radius_m) and g.radius_m > 0.0, "a positive number"),
        ("chord_m", math.isfinite(g.chord_m) and g.chord_m > 0.0, "a positive number"),
        ("root_cutout_m", 0.0 <= g.root_cutout_m < g.radius_m, f"0 <= root_cutout_m < radius_m ({g.radius_m})"),
        ("hinge_offset_m", 0.0 <= g.hinge_offset_m < g.radius_m, f"0 <= hinge_offset_m < radius_m ({g.radius_m})"),
        ("twist_rad", math.isfinite(g.twist_rad), "a finite number"),
        ("thickness_ratio", 0.0 < g.thickness_ratio < 1.0, "0 < t/c < 1"),
        ("lock_number", math.isfinite(g.lock_number) and g.lock_number > 0.0, "a positive number"),
        ("rotation_sign", g.rotation_sign in (1, -1), "+1 or -1"),
        ("higher_harmonic_pitch", all(_harmonic_ok(h) for h in g.higher_harmonic_pitch),
         "(n >= 1, finite amplitude and phase in rad) entries"),
        ("elastic_twist_harmonics", all(_harmonic_ok(h, 0) for h in g.elastic_twist_harmonics),
         "(n >= 0, finite cos and sin coefficients in rad) entries"),
        ("prescribed_flap_harmonics", all(_harmonic_ok(h, 0) for h in g.prescribed_flap_harmonics),
         "(n >= 0, finite cos and sin coefficients in rad) entries"),
    ]
    for name, ok, expected in checks:
        if not ok:
            raise ValueError(f"rotor '{g.name}': {name}: expected {expected}, got {getattr(g, name.split('.')[0])!r}")


def _harmonic_ok(entry, lowest: int = 1) -> bool:
    """A prescribed-motion entry (n, a, b): integer n >= ``lowest``, finite a and b."""
    try:
        n, a, b = entry
    except (TypeError, ValueError):
        return False
    return float(n) == int(n) and int(n) >= lowest and math.isfinite(a) and math.isfinite(b)


def check_operating_point(op: OperatingPoint, name: str) -> None:
    """Raise ValueError naming the first invalid field of ``op``."""
    for field in ("omega_rad_s", "mu_x", "mu_y", "mu_z", "density_kg_m3", "speed_of_sound_mps",
                  "thrust_N", "roll_moment_Nm", "pitch_moment_Nm"):
        value = getattr(op, field)
        if not math.isfinite(value):
            raise ValueError(f"rotor '{name}': operating point {field}: expected a finite number, got {value!r}")
    for field in ("omega_rad_s", "density_kg_m3", "speed_of_sound_mps"):
        if getattr(op, field) <= 0.0:
            raise ValueError(f"rotor '{name}': operating point {field}: expected > 0, got {getattr(op, field)!r}")


class _Disk:
    """Static arrays of one rotor × operating point × grid and the disk evaluation.

    ``interference``: optional (ΔU_T, ΔU_P) fields (n_psi, n_r) in m/s added to the velocities
    (other rotors' induced velocity, ``nps.wake.interaction``); None leaves the model untouched.
    """

    def __init__(self, geometry: RotorGeometry, op: OperatingPoint, grid: DiskGrid, tip_loss: bool,
                 interference: tuple[np.ndarray, np.ndarray] | None = None):
        self.g, self.op, self.grid, self.tip_loss = geometry, op, grid, tip_loss
        R, omega, s = geometry.radius_m, op.omega_rad_s, geometry.rotation_sign
        self.r, self.dr = radial_stations(geometry, grid.n_r)
        psi = grid.psi_rad
        self.sin, self.cos = np.sin(psi)[:, None], np.cos(psi)[:, None]
        self.tip_speed = omega * R
        self.mu_yp = s * op.mu_y
        self.mu = math.hypot(op.mu_x, op.mu_y)
        self.ut = omega * self.r[None, :] + self.tip_speed * (op.mu_x * self.sin - self.mu_yp * self.cos)
        self.extra_up = None
        if interference is not None:
            d_ut, d_up = (np.asarray(a, dtype=float) for a in interference)
            if d_ut.shape != (grid.n_psi, grid.n_r) or d_up.shape != d_ut.shape:
                raise ValueError(f"rotor '{geometry.name}': interference: expected two ({grid.n_psi}, {grid.n_r}) "
                                 f"fields, got {d_ut.shape}, {d_up.shape}")
            if not (np.isfinite(d_ut).all() and np.isfinite(d_up).all()):
                raise ValueError(f"rotor '{geometry.name}': interference: non-finite velocities")
            self.ut = self.ut + d_ut
            self.extra_up = d_up
        self.ur = self.tip_speed * (op.mu_x * self.cos + self.mu_yp * self.sin)
        self.rbar = self.r[None, :] / R
        self.twist = geometry.twist_at(self.r)[None, :]
        self.prescribed_pitch = geometry.prescribed_pitch(psi, self.r)
        flap = geometry.prescribed_flap(psi)
        self.prescribed_flap = None if flap is None else (flap[0][:, None], omega * flap[1][:, None])
        self.flap_arm = np.maximum(self.r - geometry.hinge_offset_m, 0.0)
        self.nu2 = flap_frequency_sq(geometry)
        self.pitch_flap = math.tan(geometry.delta3_rad)  # K_P = tan δ3: Δθ = −K_P β_h
        self.flap_ref = geometry.precone_rad  # β_h = β − precone, the flap from the unloaded blade (0: articulated)
        self.precone_forcing = flap_spring_sq(geometry) * geometry.precone_rad  # (K_β/I_βΩ²) β_p, the spring's zero
        self.i_omega2 = flap_inertia(geometry, op.density_kg_m3) * omega**2
        self.norm_ct = op.density_kg_m3 * np.pi * R**2 * self.tip_speed**2
        self.blade_avg = geometry.n_blades / grid.n_psi
        self.evaluations = 0

    def inflow(self, lambda0: float) -> Inflow:
        lam = abs(self.op.mu_z + lambda0)
        if self.mu == 0.0:
            return Inflow(lambda0, 0.0, 0.0)
        # tan(χ/2) / μ with χ = atan(μ/|λ|), by the half-angle identity (finite for λ = 0)
        k_over_mu = 1.0 / (math.hypot(self.mu, lam) + lam)
        return Inflow(lambda0, k_over_mu * self.op.mu_x, k_over_mu * self.mu_yp)

    def fields(self, c: Controls, x: np.ndarray) -> dict:
        lambda0, beta0, beta1c, beta1s = x
        i = self.inflow(lambda0)
        omega = self.op.omega_rad_s
        theta = c.theta0_rad + c.theta1c_rad * self.cos + c.theta1s_rad * self.sin + self.twist
        if self.prescribed_pitch is not None:
            theta = theta + self.prescribed_pitch
        lam = self.op.mu_z + lambda0 * (1.0 + self.rbar * (i.kx * self.cos + i.ky * self.sin))
        if self.prescribed_flap is None:
            beta = beta0 + beta1c * self.cos + beta1s * self.sin
            beta_dot = omega * (beta1s * self.cos - beta1c * self.sin)
        else:
            beta, beta_dot = self.prescribed_flap
        if self.pitch_flap != 0.0:  # δ3: the blade pitches down as it flaps up about its hinge
            theta = theta - self.pitch_flap * (beta - self.flap_ref)
        up = self.tip_speed * lam + (self.r[None, :] - self.g.hinge_offset_m) * beta_dot + self.ur * beta
        if self.extra_up is not None:
            up = up + self.extra_up
        forces = section_forces(self.ut, up, theta, self.r[None, :], self.g, self.op.density_kg_m3,
                                self.op.speed_of_sound_mps, tip_loss=self.tip_loss)
        self.evaluations += 1
        return {"theta": theta, "lam": lam, "beta": beta, "beta_dot": beta_dot, "up": up, "forces": forces, "inflow": i}

    def residual(self, c: Controls, x: np.ndarray) -> tuple[np.ndarray, dict]:
        """Residuals of Glauert's λ0 and of the three flap harmonic-balance equations."""
        f = self.fields(c, x)
        fz = f["forces"].fz_N_per_m
        thrust = self.blade_avg * float(np.sum(fz @ self.dr))
        ct = thrust / self.norm_ct
        lam_total = self.op.mu_z + x[0]
        m_hinge = (fz @ (self.flap_arm * self.dr)) / self.i_omega2
        n = self.grid.n_psi
        m0 = m_hinge.mean()
        m1c = 2.0 / n * float(m_hinge @ self.cos[:, 0])
        m1s = 2.0 / n * float(m_hinge @ self.sin[:, 0])
        res = np.array([
            x[0] - ct / (2.0 * math.hypot(self.mu, lam_total)),
            self.nu2 * x[1] - m0 - self.precone_forcing,
            (self.nu2 - 1.0) * x[2] - m1c,
            (self.nu2 - 1.0) * x[3] - m1s,
        ])
        f["thrust"] = thrust
        # hub moments (H') of the first-harmonic aerodynamic flap moment, (B/2) M_β,1s and −(B/2) M_β,1c
        f["flap_hub_moments"] = 0.5 * self.g.n_blades * self.i_omega2 * np.array([m1s, -m1c])
        return res, f


class _StateSolver:
    """Newton (chord) solution of λ0 and the flap harmonics for given controls, warm-started."""

    def __init__(self, disk: _Disk, x0: np.ndarray, flapping: bool = True):
        self.disk, self.x, self.jac = disk, np.array(x0, dtype=float), None
        self.active = np.arange(4) if flapping and disk.prescribed_flap is None else np.arange(1)
        if disk.g.hub == TEETERING or self.active.size == 1:  # no coning freedom (teeter, rigid blades): β0 = precone
            self.x[1] = disk.g.precone_rad
            if self.active.size == 4:
                self.active = np.array([0, 2, 3])
        if disk.prescribed_flap is not None:  # reported flapping: the prescribed mean and first harmonics
            beta = disk.prescribed_flap[0][:, 0]
            n = beta.size
            self.x[1:] = beta.mean(), 2.0 / n * float(beta @ disk.cos[:, 0]), 2.0 / n * float(beta @ disk.sin[:, 0])

    def _residual(self, c: Controls, x: np.ndarray) -> tuple[np.ndarray, dict]:
        res, fields = self.disk.residual(c, x)
        return res[self.active], fields

    def _steps(self, x: np.ndarray) -> list[float]:
        return [_INNER_FD_STEP * max(1.0, abs(x[j]) * 10.0) for j in self.active]

    @staticmethod
    def _limit_inflow(x: np.ndarray, dx: np.ndarray) -> np.ndarray:
        """Keep the mean inflow on its branch: λ0 may shrink to half or grow threefold per step."""
        if x[0] != 0.0:
            ratio = (x[0] + dx[0]) / x[0]
            if ratio < 0.5 or ratio > 3.0:
                dx *= (min(max(ratio, 0.5), 3.0) - 1.0) / (ratio - 1.0)
        return dx

    def solve(self, c: Controls) -> tuple[dict, int]:
        """Disk fields at the converged state (kept as the next start) and the residual evaluations it took."""
        try:
            solution = newton_fd(lambda x: self._residual(c, x), self.x, steps=self._steps, tol=_INNER_TOL,
                                 max_iter=_MAX_INNER, what="inflow/flapping", columns=self.active,
                                 jacobian=self.jac, refresh_ratio=_JACOBIAN_REFRESH, limit_step=self._limit_inflow)
        except ConvergenceError as failure:
            self.jac = failure.jacobian
            raise TrimError(
                f"rotor '{self.disk.g.name}': inflow/flapping solution did not converge for controls {c} "
                f"(state {failure.x}, {_case(self.disk)})"
            ) from failure
        self.x, self.jac = solution.x, solution.jacobian
        return solution.payload, solution.iterations + 1


def _case(disk: _Disk) -> str:
    op = disk.op
    return (f"Ω {op.omega_rad_s:.4g} rad/s, μ_x {op.mu_x:.4g}, μ_y {op.mu_y:.4g}, μ_z {op.mu_z:.4g}, "
            f"ρ {op.density_kg_m3:.4g} kg/m³, grid {disk.grid.n_psi}×{disk.grid.n_r}")


def _momentum_lambda0(ct: float, mu: float, mu_z: float) -> float:
    """Glauert's λ0 = C_T / (2 √(μ² + (μ_z + λ0)²)) by damped fixed-point iteration (a start value)."""
    lambda0 = math.copysign(math.sqrt(max(abs(ct), 1e-8) / 2.0), ct)
    for _ in range(60):
        lambda0 = 0.5 * lambda0 + 0.5 * ct / (2.0 * max(math.hypot(mu, mu_z + lambda0), 1e-4))
    return lambda0


def _initial_state(geometry: RotorGeometry, op: OperatingPoint, thrust_N: float) -> tuple[np.ndarray, float]:
    """Momentum λ0 for thrust_N and the blade-element collective that gives it (linear theory)."""
    ct = thrust_N / (op.density_kg_m3 * np.pi * geometry.radius_m**2 * (op.omega_rad_s * geometry.radius_m) ** 2)
    mu = math.hypot(op.mu_x, op.mu_y)
    lambda0 = _momentum_lambda0(ct, mu, op.mu_z)
    sigma_a = geometry.solidity * geometry.airfoil.lift_slope_per_rad
    theta0 = (6.0 * ct / sigma_a + 1.5 * (op.mu_z + lambda0)) / (1.0 + 1.5 * mu * mu)
    return np.array([lambda0, 0.0, 0.0, 0.0]), float(np.clip(theta0, -0.5, 0.5))


def _initial_state_for_controls(geometry: RotorGeometry, op: OperatingPoint, theta0_rad: float) -> np.ndarray:
    """Linear-theory λ0 for an imposed collective: C_T = σa/2 (θ0 (1 + 3μ²/2)/3 − λ/2)."""
    mu = math.hypot(op.mu_x, op.mu_y)
    sigma_a = geometry.solidity * geometry.airfoil.lift_slope_per_rad
    lambda0 = 0.05
    for _ in range(60):
        ct = 0.5 * sigma_a * (theta0_rad * (1.0 + 1.5 * mu * mu) / 3.0 - 0.5 * (op.mu_z + lambda0))
        lambda0 = 0.5 * lambda0 + 0.5 * _momentum_lambda0(ct, mu, op.mu_z)
    return np.array([lambda0, 0.0, 0.0, 0.0])


def _outputs(disk: _Disk, fields: dict, x: np.ndarray, thrust_ref: float, k_hub: float) -> np.ndarray:
    """Trim outputs (T, M_x', M_y') in the aerodynamic frame; for e = 0 the thrust-tilt moment T* R β1;
    with prescribed flapping the aerodynamic first-harmonic flap moments (module doc)."""
    if disk.prescribed_flap is not None:
        return np.array([fields["thrust"], *fields["flap_hub_moments"]])
    stiffness = k_hub if k_hub > 0.0 else abs(thrust_ref) * disk.g.radius_m
    return np.array([fields["thrust"], stiffness * x[3], -stiffness * x[2]])


def rotor_loads(
    geometry: RotorGeometry,
    op: OperatingPoint,
    grid: DiskGrid,
    controls: Controls,
    *,
    tip_loss: bool = True,
    flapping: bool = True,
) -> RotorTrim:
    """Disk loads for imposed controls (no trim): inflow and flapping solved consistently.

    ``flapping=False`` holds β ≡ 0 (controls read relative to the tip-path plane) and solves
    only the inflow.
    """
    check_geometry(geometry)
    check_operating_point(op, geometry.name)
    disk = _Disk(geometry, op, grid, tip_loss)
    solver = _StateSolver(disk, _initial_state_for_controls(geometry, op, controls.theta0_rad), flapping)
    fields, inner = solver.solve(controls)
    history = _history_frame([_history_row(0, 0, "none", controls, fields, solver.x, inner, disk)])
    return _result(disk, controls, solver.x, fields, history, 0)


def _trim_targets(geometry: RotorGeometry, op: OperatingPoint, tol_rel: float):
    """Checked trim targets: (target (T, s·M_x, M_y) in N and N m, tolerances (same units), |T|, hub stiffness)."""
    check_geometry(geometry)
    check_operating_point(op, geometry.name)
    if not 0.0 < tol_rel < 0.1:
        raise ValueError(f"trim_rotor: tol_rel: expected 0 < tol_rel < 0.1, got {tol_rel!r}")
    k_hub = hub_flap_stiffness(geometry, op.omega_rad_s, op.density_kg_m3)
    thrust_ref = abs(op.thrust_N)
    if thrust_ref == 0.0:
        raise ValueError(f"rotor '{geometry.name}': operating point thrust_N: expected a non-zero thrust target")
    if k_hub == 0.0 and not geometry.prescribed_flap_harmonics and (op.roll_moment_Nm != 0.0 or op.pitch_moment_Nm != 0.0):
        raise ValueError(
            f"rotor '{geometry.name}': roll_moment_Nm/pitch_moment_Nm: expected 0 for a rotor without hinge offset "
            f"(it transmits no hub moment), got {op.roll_moment_Nm}, {op.pitch_moment_Nm}"
        )
    target = np.array([op.thrust_N, geometry.rotation_sign * op.roll_moment_Nm, op.pitch_moment_Nm])
    m_abs = tol_rel * thrust_ref * geometry.radius_m
    tol = np.array([tol_rel * thrust_ref, max(tol_rel * abs(target[1]), m_abs), max(tol_rel * abs(target[2]), m_abs)])
    return target, tol, thrust_ref, k_hub


class _TrimIteration:
    """The trim's current controls ``ctrl`` = (θ0, θ1c, θ1s) (rad), the disk solution there (``fields``,
    ``inner`` iterations), the residuals ``res`` to the targets and the history rows."""

    def __init__(self, disk: _Disk, solver: _StateSolver, target: np.ndarray, thrust_ref: float, k_hub: float,
                 ctrl: np.ndarray):
        self.disk, self.solver, self.target, self.thrust_ref, self.k_hub = disk, solver, target, thrust_ref, k_hub
        self.rows: list[dict] = []
        self.accept(ctrl, self.evaluate(ctrl), 0, 0, "start")

    def evaluate(self, v: np.ndarray):
        """(fields, inner iterations, residuals) with controls ``v``; the inflow and flapping re-solved."""
        fields, inner = self.solver.solve(_controls(v))
        return fields, inner, _outputs(self.disk, fields, self.solver.x, self.thrust_ref, self.k_hub) - self.target

    def accept(self, v: np.ndarray, evaluated, outer: int, step: int, name: str) -> None:
        """Move to controls ``v`` (evaluated just before) and record the history row."""
        self.ctrl = v
        self.fields, self.inner, self.res = evaluated
        self.rows.append(_history_row(outer, step, name, _controls(v), self.fields, self.solver.x, self.inner, self.disk))


def _controls(v: np.ndarray) -> Controls:
    return Controls(float(v[0]), float(v[1]), float(v[2]))


def _control_steps(it: _TrimIteration) -> tuple:
    """The three trim steps (direction in (θ0, θ1c, θ1s), output index, name, initial slope): θ0 → T, then the
    swashplate-phased cyclic directions that change one hub moment each (first order) → M_y and → M_x."""
    sens = forward_difference_jacobian(lambda v: it.evaluate(v)[2][1:], it.ctrl, it.res[1:], (_PROBE_RAD, _PROBE_RAD),
                                       columns=(1, 2))
    mix = np.linalg.inv(sens)
    return (
        (np.array([1.0, 0.0, 0.0]), 0, "theta0", None),
        (np.array([0.0, mix[0, 1], mix[1, 1]]), 2, "cyclic_pitch", 1.0),
        (np.array([0.0, mix[0, 0], mix[1, 0]]), 1, "cyclic_roll", 1.0),
    )


def _secant_step(it: _TrimIteration, direction, oi: int, name: str, slope0, slopes: dict, tol: np.ndarray,
                 outer: int, step: int, max_secant: int) -> None:
    """Secant iteration of output ``oi`` along ``direction`` to _SECANT_TOL_FRACTION of its tolerance
    (:func:`nps.core.solvers.limited_secant`; steps limited to _MAX_CONTROL_STEP_RAD, controls to
    ±MAX_CONTROL_RAD); the slope of each output is kept between outer iterations and only updated when
    the new estimate is consistent. The first slope of θ0 is probed with a _PROBE_RAD step."""
    goal = _SECANT_TOL_FRACTION * tol[oi]
    if abs(it.res[oi]) > goal and oi not in slopes:
        if slope0 is None:
            probe = it.ctrl + _PROBE_RAD * direction
            evaluated = it.evaluate(probe)
            slope0 = (evaluated[2][oi] - it.res[oi]) / _PROBE_RAD
            it.accept(probe, evaluated, outer, step, name)
        slopes[oi] = slope0
    if oi not in slopes:
        return

    def move(du: float):
        trial = np.clip(it.ctrl + du * direction, -MAX_CONTROL_RAD, MAX_CONTROL_RAD)
        if np.array_equal(trial, it.ctrl):
            return None
        evaluated = it.evaluate(trial)
        it.accept(trial, evaluated, outer, step, name)
        return evaluated[2][oi]

    slopes[oi] = limited_secant(move, it.res[oi], slopes[oi], tol=goal, max_iter=max_secant,
                                max_step=_MAX_CONTROL_STEP_RAD / np.abs(direction).max(), keep_ratio=_SLOPE_KEEP_RATIO)


def trim_rotor(
    geometry: RotorGeometry,
    op: OperatingPoint,
    grid: DiskGrid,
    *,
    tol_rel: float = 1e-3,
    max_outer: int = 20,
    max_secant: int = 12,
    tip_loss: bool = True,
    interference: tuple[np.ndarray, np.ndarray] | None = None,
) -> RotorTrim:
    """Trim θ0, θ1s, θ1c to the thrust and hub-moment targets of ``op`` (thesis Fig. 4.3).

    ``interference``: optional (ΔU_T, ΔU_P) (n_psi, n_r) m/s added to the section velocities
    (other rotors' wakes, see :class:`_Disk`); λ0 stays the rotor's own momentum inflow.

    Each outer iteration runs the three steps (θ0 → T, phased cyclic → M_y, then → M_x;
    module docstring), each a secant iteration to a quarter of its tolerance with the inflow and
    flapping re-solved at every evaluation. Converged when all three residuals are within
    tolerance; otherwise :class:`TrimError` with the residuals and the case.
    """
    target, tol, thrust_ref, k_hub = _trim_targets(geometry, op, tol_rel)
    disk = _Disk(geometry, op, grid, tip_loss, interference)
    x0, theta0 = _initial_state(geometry, op, op.thrust_N)
    if interference is not None:  # linear theory: the same thrust needs Δθ0 = 3/2 Δλ more collective
        theta0 = float(np.clip(theta0 + 1.5 * np.mean(disk.extra_up) / disk.tip_speed, -0.5, 0.5))
    it = _TrimIteration(disk, _StateSolver(disk, x0), target, thrust_ref, k_hub, np.array([theta0, 0.0, 0.0]))
    steps = _control_steps(it)
    slopes: dict = {}
    outer = 0
    converged = bool(np.all(np.abs(it.res) <= tol))
    while not converged and outer < max_outer:
        outer += 1
        for step, (direction, oi, name, slope0) in enumerate(steps, start=1):
            _secant_step(it, direction, oi, name, slope0, slopes, tol, outer, step, max_secant)
            if np.all(np.abs(it.res) <= tol):
                converged = True
                break
    if not converged:
        names = ("thrust_N", "roll_moment_Nm", "pitch_moment_Nm")
        residuals = it.res * np.array([1, geometry.rotation_sign, 1])
        detail = ", ".join(f"{n}: residual {r:.4g} (tol {t:.3g})" for n, r, t in zip(names, residuals, tol))
        ctrl = it.ctrl
        raise TrimError(
            f"rotor '{geometry.name}': trim did not converge in {max_outer} outer iterations; {detail}; "
            f"controls θ0 {ctrl[0]:.4f}, θ1c {ctrl[1]:.4f}, θ1s {ctrl[2]:.4f} rad; targets T {op.thrust_N:.6g} N, "
            f"M_x {op.roll_moment_Nm:.6g} N m, M_y {op.pitch_moment_Nm:.6g} N m; {_case(disk)}"
        )
    return _result(disk, _controls(it.ctrl), it.solver.x, it.fields, _history_frame(it.rows), outer)


def _history_row(outer, step, name, c: Controls, fields, x, inner, disk: _Disk) -> dict:
    totals = _totals(disk, fields, x)
    return {
        "outer_iteration": outer, "step": step, "control": name,
        "theta0_rad": c.theta0_rad, "theta1c_rad": c.theta1c_rad, "theta1s_rad": c.theta1s_rad,
        "thrust_N": totals.thrust_N, "roll_moment_Nm": totals.roll_moment_Nm,
        "pitch_moment_Nm": totals.pitch_moment_Nm, "lambda0": x[0], "beta0_rad": x[1],
        "beta1c_rad": x[2], "beta1s_rad": x[3], "inner_iterations": inner,
    }


def _history_frame(rows: list[dict]) -> pd.DataFrame:
    df = pd.DataFrame(rows)
    for name in ("outer_iteration", "step", "inner_iterations"):
        df[name] = df[name].astype(np.int64)
    return df


def _totals(disk: _Disk, fields: dict, x: np.ndarray) -> RotorTotals:
    g, op, s = disk.g, disk.op, disk.g.rotation_sign
    forces = fields["forces"]
    fz_dr = forces.fz_N_per_m * disk.dr
    fx_dr = forces.fx_N_per_m * disk.dr
    beta = fields["beta"]
    avg = disk.blade_avg
    thrust = avg * float(np.sum(fz_dr))
    # in-plane force on the blades: drag-like F_x opposes the motion e_ψ = (−sin ψ, cos ψ);
    # the flapped blade's normal force leans inward by β along e_r = (cos ψ, sin ψ)
    h = avg * float(np.sum(fx_dr * disk.sin - fz_dr * beta * disk.cos))
    y_aero = avg * float(np.sum(-fx_dr * disk.cos - fz_dr * beta * disk.sin))
    torque = avg * float(np.sum(fx_dr * disk.r[None, :]))
    k_hub = hub_flap_stiffness(g, op.omega_rad_s, op.density_kg_m3)
    if disk.prescribed_flap is None:
        roll, pitch = k_hub * x[3], -k_hub * x[2]
    else:
        roll, pitch = fields["flap_hub_moments"]
    return RotorTotals(
        thrust_N=thrust,
        h_force_N=h,
        y_force_N=s * y_aero,
        torque_Nm=torque,
        power_W=torque * op.omega_rad_s,
        roll_moment_Nm=s * roll,
        pitch_moment_Nm=pitch,
        aero_roll_moment_Nm=s * avg * float(np.sum(fz_dr * disk.r[None, :] * disk.sin)),
        aero_pitch_moment_Nm=-avg * float(np.sum(fz_dr * disk.r[None, :] * disk.cos)),
        ct=thrust / disk.norm_ct,
        mean_cl=6.0 * thrust / disk.norm_ct / g.solidity,
    )


def _result(disk: _Disk, c: Controls, x: np.ndarray, fields: dict, history: pd.DataFrame, outer: int) -> RotorTrim:
    g = disk.g
    n_psi, n_r = disk.grid.n_psi, disk.grid.n_r
    shape = (n_psi, n_r)
    forces = fields["forces"]

    def full(a):
        return np.broadcast_to(a, shape).ravel().astype(np.float64)

    table = pd.DataFrame({
        "psi_rad": np.repeat(disk.grid.psi_rad, n_r),
        "r_m": np.tile(disk.r, n_psi),
        "dr_m": np.tile(disk.dr, n_psi),
        "chord_m": full(g.chord_at(disk.r)),
        "thickness_m": full(g.chord_at(disk.r) * g.thickness_ratio_at(disk.r)),
        "theta_rad": full(fields["theta"]),
        "beta_rad": full(fields["beta"]),
        "beta_dot_rad_s": full(fields["beta_dot"]),
        "ut_mps": full(disk.ut),
        "up_mps": full(fields["up"]),
        "inflow_ratio": full(fields["lam"]),
        "alpha_eff_rad": full(forces.alpha_eff_rad),
        "mach": full(forces.mach),
        "fz_N_per_m": full(forces.fz_N_per_m),
        "fx_N_per_m": full(forces.fx_N_per_m),
        "circulation_m2_s": full(forces.circulation_m2_s),
    })
    return RotorTrim(
        disk=table[list(DISK_COLUMNS)],
        controls=c,
        flapping=Flapping(float(x[1]), float(x[2]), float(x[3])),
        totals=_totals(disk, fields, x),
        history=history,
        inflow=fields["inflow"],
        iterations=outer,
        rotor=g.name,
    )
