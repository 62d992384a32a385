"""Airfoil self-noise of Brooks, Pope & Marcolini (NASA RP-1218, 1989): 1/3-octave band spectra.

Every function evaluates the report's semi-empirical scaling laws for blade sections ("elements")
of a NACA 0012-like airfoil, vectorised with numpy over elements × frequencies: element arrays
broadcast together (shape S), frequencies broadcast against ``S + (n_f,)`` (a 1-D band list, or
one list per element when the bands are Doppler shifted). Equation numbers are RP-1218's.

Units and conventions (SI, docs/reference/bpm.md):

- chord c, span L (the element's spanwise length), trailing-edge thickness h, distance r_e in m;
  flow speed U (the speed of the flow over the section, normal to its span) in m/s; kinematic
  viscosity ν in m²/s; speed of sound c0 in m/s; frequency f in Hz.
- angles are given in **radians** (α*, the trailing-edge solid angle Ψ, the directivity angles
  Θ_e, Φ_e); the report's correlations are in degrees and are converted inside. α* is the
  effective (free-air) angle of attack; the correlations use |α*| (NACA 0012 is symmetric: a
  negative angle swaps the suction and pressure sides, which the far field does not tell apart).
- Θ_e: angle between the chordwise axis x_e (pointing downstream, from the leading to the
  trailing edge, i.e. opposite to the section's motion through the air) and the source→observer
  vector; Φ_e: angle between the spanwise axis y_e and the projection of that vector on the
  (y_e, z_e) plane (RP-1218 Appendix B, figure B3). Θ_e = Φ_e = 90° is the report's microphone
  normal to the chord.
- outputs are band **mean-square pressures** (Pa²) of 1/3-octave bands centred at f, the report's
  SPL_{1/3} = 10 log10(MSP/p_ref²); a mechanism that does not occur (stall side levels, LBL-VS
  on a tripped section) gives exactly 0 Pa².
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.noise.spectra import P_REF_PA

COMPONENTS = ("tbl_te_pressure", "tbl_te_suction", "separation", "lbl_vs", "bluntness", "tip")
"""Mechanism names, in the order used by every spectrum dictionary of NPS's BPM modules."""

TIP_SHAPES = ("flat", "round")

# RP-1218's data: NACA 0012, chords 2.54-30.48 cm (60.96 cm for bluntness), 31.7-71.3 m/s,
# tunnel angles 0-25.2 deg (see valid_range docstring).
DATA_REYNOLDS_RANGE = (4.0e4, 3.0e6)
DATA_MACH_RANGE = (0.0, 0.21)
DATA_ALPHA_RANGE_DEG = (0.0, 25.2)


@dataclass(frozen=True)
class Medium:
    """Still air: speed of sound (m/s) and kinematic viscosity ν (m²/s)."""

    speed_of_sound_mps: float
    kinematic_viscosity_m2_s: float

    def __post_init__(self):
        for name in ("speed_of_sound_mps", "kinematic_viscosity_m2_s"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0.0):
                raise ValueError(f"Medium.{name} must be finite and positive, got {value}")


@dataclass(frozen=True)
class Sections:
    """Blade sections (elements); every field broadcasts to one shape S.

    ``chord_m`` c, ``span_m`` L, ``speed_mps`` U, ``alpha_rad`` α* (effective angle of attack,
    rad), ``te_thickness_m`` h, ``te_angle_rad`` Ψ (solid angle between the surfaces at the
    trailing edge, rad; RP-1218 covers 0-14°), ``tripped`` True for a boundary layer tripped
    near the leading edge (heavy tripping, eq. 2-4, 11-13), False for natural transition.
    """

    chord_m: np.ndarray
    span_m: np.ndarray
    speed_mps: np.ndarray
    alpha_rad: np.ndarray
    te_thickness_m: np.ndarray
    te_angle_rad: np.ndarray
    tripped: np.ndarray

    def __post_init__(self):
        for name in ("chord_m", "span_m", "speed_mps"):
            value = np.asarray(getattr(self, name), dtype=float)
            if not (np.all(np.isfinite(value)) and np.all(value > 0.0)):
                raise ValueError(f"Sections.{name} must be finite and positive")
        if not np.all(np.isfinite(np.asarray(self.alpha_rad, dtype=float))):
            raise ValueError("Sections.alpha_rad must be finite")
        for name in ("te_thickness_m", "te_angle_rad"):
            value = np.asarray(getattr(self, name), dtype=float)
            if not (np.all(np.isfinite(value)) and np.all(value >= 0.0)):
                raise ValueError(f"Sections.{name} must be finite and non-negative")
        try:
            np.broadcast_shapes(*(np.shape(getattr(self, n)) for n in self.__dataclass_fields__))
        except ValueError as error:
            raise ValueError(f"Sections fields do not broadcast to one shape: {error}") from None


@dataclass(frozen=True)
class Directivity:
    """Source→observer distance r_e (m) and the directivity factors D̄_h (eq. B1), D̄_l (eq. B2).

    Broadcast to the sections' shape S. Build them from the angles with :func:`directivity`; a
    rotor average may pass factors averaged over an azimuth interval (both enter the band
    mean-square pressure linearly).
    """

    distance_m: np.ndarray
    high: np.ndarray
    low: np.ndarray

    def __post_init__(self):
        r = np.asarray(self.distance_m, dtype=float)
        if not (np.all(np.isfinite(r)) and np.all(r > 0.0)):
            raise ValueError("Directivity.distance_m must be finite and positive")
        for name in ("high", "low"):
            value = np.asarray(getattr(self, name), dtype=float)
            if not (np.all(np.isfinite(value)) and np.all(value >= 0.0)):
                raise ValueError(f"Directivity.{name} must be finite and non-negative")


# --------------------------------------------------------------------------------------------
# Boundary-layer thickness at the trailing edge (section 3, NACA 0012)
# --------------------------------------------------------------------------------------------


def bl_thickness_zero_alpha(reynolds, tripped) -> np.ndarray:
    """δ0/c, boundary-layer thickness at α* = 0: eq. (2) tripped, eq. (5) untripped."""
    lr = np.log10(np.asarray(reynolds, dtype=float))
    return np.where(tripped, 10.0 ** (1.892 - 0.9045 * lr + 0.0596 * lr * lr),
                    10.0 ** (1.6569 - 0.9045 * lr + 0.0596 * lr * lr))


def displacement_thickness_zero_alpha(reynolds, tripped) -> np.ndarray:
    """δ*0/c at α* = 0: eq. (3) tripped (two Reynolds-number ranges), eq. (6) untripped."""
    re = np.asarray(reynolds, dtype=float)
    lr = np.log10(re)
    tripped_value = np.where(re <= 3.0e5, 0.0601 * re ** (-0.114),
                             10.0 ** (3.411 - 1.5397 * lr + 0.1059 * lr * lr))
    return np.where(tripped, tripped_value, 10.0 ** (3.0187 - 1.5397 * lr + 0.1059 * lr * lr))


def pressure_side_ratios(alpha_deg) -> tuple[np.ndarray, np.ndarray]:
    """(δ_p/δ0, δ*_p/δ*0), eq. (8) and (9) (tripped and untripped alike), α* in degrees."""
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    return 10.0 ** (-0.04175 * a + 0.00106 * a * a), 10.0 ** (-0.0432 * a + 0.00113 * a * a)


def suction_side_ratios(alpha_deg, tripped) -> tuple[np.ndarray, np.ndarray]:
    """(δ_s/δ0, δ*_s/δ*0): eq. (11), (12) tripped; eq. (14), (15) untripped; α* in degrees."""
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    delta_tripped = np.select([a <= 5.0, a <= 12.5],
                              [10.0 ** (0.0311 * a), 0.3468 * 10.0 ** (0.1231 * a)], 5.718 * 10.0 ** (0.0258 * a))
    star_tripped = np.select([a <= 5.0, a <= 12.5],
                             [10.0 ** (0.0679 * a), 0.381 * 10.0 ** (0.1516 * a)], 14.296 * 10.0 ** (0.0258 * a))
    delta_free = np.select([a <= 7.5, a <= 12.5],
                           [10.0 ** (0.03114 * a), 0.0303 * 10.0 ** (0.2336 * a)], 12.0 * 10.0 ** (0.0258 * a))
    star_free = np.select([a <= 7.5, a <= 12.5],
                          [10.0 ** (0.0679 * a), 0.0162 * 10.0 ** (0.3066 * a)], 52.42 * 10.0 ** (0.0258 * a))
    return np.where(tripped, delta_tripped, delta_free), np.where(tripped, star_tripped, star_free)


def trailing_edge_thicknesses(chord_m, reynolds, alpha_deg, tripped) -> dict[str, np.ndarray]:
    """Boundary-layer thickness δ_p and displacement thicknesses δ*_p, δ*_s (m) at the trailing edge."""
    chord = np.asarray(chord_m, dtype=float)
    delta_p_ratio, star_p_ratio = pressure_side_ratios(alpha_deg)
    _, star_s_ratio = suction_side_ratios(alpha_deg, tripped)
    star0 = chord * displacement_thickness_zero_alpha(reynolds, tripped)
    return {
        "delta_p_m": chord * bl_thickness_zero_alpha(reynolds, tripped) * delta_p_ratio,
        "delta_star_p_m": star0 * star_p_ratio,
        "delta_star_s_m": star0 * star_s_ratio,
    }


# --------------------------------------------------------------------------------------------
# Directivity (Appendix B)
# --------------------------------------------------------------------------------------------


def directivity_factors(cos_theta, sin2_phi, mach):
    """(D̄_h, D̄_l) of eq. (B1), (B2) from cos Θ_e, sin²Φ_e and M, with 2 sin²(Θ_e/2) = 1 − cos Θ_e and
    sin²Θ_e = (1 − cos Θ_e)(1 + cos Θ_e).

    Arithmetic only, so that numpy arrays (:func:`directivity_high`, :func:`directivity_low`) and the compiled
    rotation average of :mod:`nps.noise.broadband.rotor` (scalars) evaluate the same expressions.
    """
    convection = 1.0 + mach * cos_theta
    high = (1.0 - cos_theta) * sin2_phi / (convection * (1.0 + 0.2 * mach * cos_theta) ** 2)
    low = (1.0 - cos_theta) * (1.0 + cos_theta) * sin2_phi / convection**4
    return high, low


def directivity_high(theta_e_rad, phi_e_rad, mach) -> np.ndarray:
    """D̄_h, eq. (B1): 2 sin²(Θ_e/2) sin²Φ_e / ((1 + M cos Θ_e)(1 + (M − M_c) cos Θ_e)²), M_c = 0.8 M."""
    return directivity_factors(np.cos(theta_e_rad), np.sin(phi_e_rad) ** 2, np.asarray(mach, dtype=float))[0]


def directivity_low(theta_e_rad, phi_e_rad, mach) -> np.ndarray:
    """D̄_l, eq. (B2): sin²Θ_e sin²Φ_e / (1 + M cos Θ_e)⁴."""
    return directivity_factors(np.cos(theta_e_rad), np.sin(phi_e_rad) ** 2, np.asarray(mach, dtype=float))[1]


def directivity(distance_m, theta_e_rad, phi_e_rad, mach) -> Directivity:
    """Directivity of an observer at r_e (m), Θ_e, Φ_e (rad) from a section at Mach number M = U/c0."""
    return Directivity(distance_m, directivity_high(theta_e_rad, phi_e_rad, mach),
                       directivity_low(theta_e_rad, phi_e_rad, mach))


# --------------------------------------------------------------------------------------------
# TBL-TE and separation (section 5.1.1)
# --------------------------------------------------------------------------------------------


def _sqrt0(x):
    return np.sqrt(np.maximum(x, 0.0))


def _piecewise_curve(x, circle, line, cubic, breaks) -> np.ndarray:
    """Shape shared by eq. (35), (36), (41), (42): √(c0 − 886.788 x²) − c1 for x < breaks[0],
    the line l0 x + l1 up to breaks[1], the cubic k0 x³ + k1 x² + k2 x + k3 beyond."""
    x = np.asarray(x, dtype=float)
    return np.select([x < breaks[0], x <= breaks[1]],
                     [_sqrt0(circle[0] - 886.788 * x * x) - circle[1], line[0] * x + line[1]],
                     ((cubic[0] * x + cubic[1]) * x + cubic[2]) * x + cubic[3])


def a_min(a) -> np.ndarray:
    """(A)_min(a), eq. (35)."""
    return _piecewise_curve(a, (67.552, 8.219), (-32.665, 3.981), (-142.795, 103.656, -57.757, 6.006), (0.204, 0.244))


def a_max(a) -> np.ndarray:
    """(A)_max(a), eq. (36)."""
    return _piecewise_curve(a, (67.552, 8.219), (-15.901, 1.098), (-4.669, 3.491, -16.699, 1.149), (0.13, 0.321))


def b_min(b) -> np.ndarray:
    """(B)_min(b), eq. (41)."""
    return _piecewise_curve(b, (16.888, 4.109), (-83.607, 8.138), (-817.810, 355.210, -135.024, 10.619), (0.13, 0.145))


def b_max(b) -> np.ndarray:
    """(B)_max(b), eq. (42)."""
    return _piecewise_curve(b, (16.888, 4.109), (-31.330, 1.854), (-80.541, 44.174, -39.381, 2.344), (0.10, 0.187))


def _interpolated_curve(ratio, reynolds, curve_min, curve_max, at_0, at_max, quad):
    """Eq. (37)-(40) / (43)-(46): curve through −20 dB at x0(Re), between the min and max curves."""
    re = np.asarray(reynolds, dtype=float)
    x0 = np.select([re < 9.52e4, re <= 8.57e5], [at_0, quad * (re - 8.57e5) ** 2 + at_max], at_max)
    lo0, hi0 = curve_min(x0), curve_max(x0)
    x = np.abs(np.log10(ratio))
    lo = curve_min(x)
    return lo + (-20.0 - lo0) / (hi0 - lo0) * (curve_max(x) - lo)


def a_curve(strouhal_ratio, reynolds) -> np.ndarray:
    """A(St/St_peak) (dB) at chord Reynolds number Re_c, eq. (37)-(40) with a0(Re_c) of eq. (38)."""
    return _interpolated_curve(strouhal_ratio, reynolds, a_min, a_max, 0.57, 1.13, -9.57e-13)


def b_curve(strouhal_ratio, reynolds) -> np.ndarray:
    """B(St/St_peak) (dB), eq. (43)-(46) with b0(Re_c) of eq. (44)."""
    return _interpolated_curve(strouhal_ratio, reynolds, b_min, b_max, 0.30, 0.56, -4.48e-13)


def st1(mach) -> np.ndarray:
    """St_1 = 0.02 M^−0.6, eq. (31)."""
    return 0.02 * np.asarray(mach, dtype=float) ** (-0.6)


def st2(mach, alpha_deg) -> np.ndarray:
    """St_2, eq. (34) (α* in degrees)."""
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    return st1(mach) * np.select([a < 1.33, a <= 12.5], [1.0, 10.0 ** (0.0054 * (a - 1.33) ** 2)], 4.72)


def k1(reynolds) -> np.ndarray:
    """K_1 (dB), eq. (47)."""
    re = np.asarray(reynolds, dtype=float)
    lr = np.log10(re)
    return np.select([re < 2.47e5, re <= 8.0e5], [-4.31 * lr + 156.3, -9.0 * lr + 181.6], 128.5)


def delta_k1(alpha_deg, reynolds_delta_star_p) -> np.ndarray:
    """ΔK_1 (dB), eq. (48): α*(1.43 log R_δ*p − 5.29) for R_δ*p ≤ 5000, else 0."""
    rd = np.asarray(reynolds_delta_star_p, dtype=float)
    return np.where(rd <= 5000.0, np.abs(alpha_deg) * (1.43 * np.log10(rd) - 5.29), 0.0)


def stall_angle_deg(mach) -> np.ndarray:
    """Angle (deg) above which the stalled forms apply: min(γ0, 12.5°), γ0 = 23.43 M + 4.651 (eq. 50)."""
    return np.minimum(23.43 * np.asarray(mach, dtype=float) + 4.651, 12.5)


def is_stalled(sections: Sections, medium: Medium) -> np.ndarray:
    """True where |α*| > min(γ0, 12.5°): SPL_p = SPL_s = −∞ and SPL_α takes the stalled form (28)."""
    mach = np.asarray(sections.speed_mps, dtype=float) / medium.speed_of_sound_mps
    return np.degrees(np.abs(np.asarray(sections.alpha_rad, dtype=float))) > stall_angle_deg(mach)


def k2_minus_k1(mach, alpha_deg) -> np.ndarray:
    """K_2 − K_1 (dB), eq. (49) with γ, γ0, β, β0 of eq. (50); −1000 dB below γ0 − γ."""
    m = np.asarray(mach, dtype=float)
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    gamma, gamma0 = 27.094 * m + 3.31, 23.43 * m + 4.651
    beta, beta0 = 72.65 * m + 10.74, -34.19 * m - 13.82
    middle = _sqrt0(beta * beta - (beta / gamma) ** 2 * (a - gamma0) ** 2) + beta0
    return np.select([a < gamma0 - gamma, a <= gamma0 + gamma], [-1000.0, middle], -12.0)


def _scaled_msp(level_db):
    return P_REF_PA**2 * 10.0 ** (0.1 * level_db)


def _columns(sections: Sections, radiation: Directivity, medium: Medium) -> dict[str, np.ndarray]:
    """Element quantities as S + (1,) arrays (to broadcast against frequencies), α* in degrees."""
    col = {name: np.asarray(getattr(sections, name), dtype=float)[..., None]
           for name in ("chord_m", "span_m", "speed_mps", "te_thickness_m")}
    col["alpha_deg"] = np.degrees(np.abs(np.asarray(sections.alpha_rad, dtype=float)))[..., None]
    col["psi_deg"] = np.degrees(np.asarray(sections.te_angle_rad, dtype=float))[..., None]
    col["tripped"] = np.asarray(sections.tripped, dtype=bool)[..., None]
    for name in ("distance_m", "high", "low"):
        col[name] = np.asarray(getattr(radiation, name), dtype=float)[..., None]
    col["mach"] = col["speed_mps"] / medium.speed_of_sound_mps
    col["reynolds"] = col["speed_mps"] * col["chord_m"] / medium.kinematic_viscosity_m2_s
    return col


def tbl_te_msp(frequency_hz, sections: Sections, radiation: Directivity, medium: Medium) -> dict[str, np.ndarray]:
    """TBL-TE pressure side, suction side and separation band MSP (Pa²), eq. (24)-(28).

    Unstalled (|α*| ≤ min(γ0, 12.5°)): SPL_p (25), SPL_s (26) and SPL_α (27) with D̄_h.
    Stalled: SPL_p = SPL_s = −∞ and SPL_α from eq. (28): A'(St_s/St_2) (the A curve at 3 Re_c)
    with the low-frequency directivity D̄_l. Shapes S + (n_f,).
    """
    f = np.asarray(frequency_hz, dtype=float)
    col = _columns(sections, radiation, medium)
    c, span, u, alpha, mach, re_c = (col[k] for k in ("chord_m", "span_m", "speed_mps", "alpha_deg", "mach", "reynolds"))
    r_e, d_h, d_l = col["distance_m"], col["high"], col["low"]
    nu = medium.kinematic_viscosity_m2_s
    bl = trailing_edge_thicknesses(c, re_c, alpha, col["tripped"])
    dsp, dss = bl["delta_star_p_m"], bl["delta_star_s_m"]
    st_1, st_2 = st1(mach), st2(mach, alpha)
    st_1bar = 0.5 * (st_1 + st_2)
    kk1 = k1(re_c)
    kk2 = kk1 + k2_minus_k1(mach, alpha)
    geom = mach**5 * span / (r_e * r_e)
    st_p, st_s = f * dsp / u, f * dss / u
    stalled = is_stalled(sections, medium)[..., None]
    spl_p = 10.0 * np.log10(dsp * geom * d_h) + a_curve(st_p / st_1, re_c) + kk1 - 3.0 + delta_k1(alpha, u * dsp / nu)
    spl_s = 10.0 * np.log10(dss * geom * d_h) + a_curve(st_s / st_1bar, re_c) + kk1 - 3.0
    spl_a = np.where(stalled,
                     10.0 * np.log10(dss * geom * d_l) + a_curve(st_s / st_2, 3.0 * re_c) + kk2,
                     10.0 * np.log10(dss * geom * d_h) + b_curve(st_s / st_2, re_c) + kk2)
    return {
        "tbl_te_pressure": np.where(stalled, 0.0, _scaled_msp(spl_p)),
        "tbl_te_suction": np.where(stalled, 0.0, _scaled_msp(spl_s)),
        "separation": np.where(kk2 - kk1 <= -1000.0, 0.0, _scaled_msp(spl_a)),
    }


# --------------------------------------------------------------------------------------------
# LBL-VS (section 5.1.2)
# --------------------------------------------------------------------------------------------


def st1_prime(reynolds) -> np.ndarray:
    """St'_1, eq. (55)."""
    re = np.asarray(reynolds, dtype=float)
    return np.select([re <= 1.3e5, re <= 4.0e5], [0.18, 0.001756 * re**0.3931], 0.28)


def g1(e) -> np.ndarray:
    """G_1(St'/St'_peak) (dB), eq. (57)."""
    e = np.asarray(e, dtype=float)
    le = np.log10(e)
    return np.select(
        [e <= 0.5974, e <= 0.8545, e <= 1.17, e <= 1.674],
        [39.8 * le - 11.12, 98.409 * le + 2.0, -5.076 + _sqrt0(2.484 - 506.25 * le * le), -98.409 * le + 2.0],
        -39.8 * le - 11.12,
    )


def reynolds_0(alpha_deg) -> np.ndarray:
    """(Re_c)_0, eq. (59) (α* in degrees)."""
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    return np.where(a <= 3.0, 10.0 ** (0.215 * a + 4.978), 10.0 ** (0.120 * a + 5.263))


def g2(d) -> np.ndarray:
    """G_2(Re_c/(Re_c)_0) (dB), eq. (58)."""
    d = np.asarray(d, dtype=float)
    ld = np.log10(d)
    return np.select(
        [d <= 0.3237, d <= 0.5689, d <= 1.7579, d <= 3.0889],
        [77.852 * ld + 15.328, 65.188 * ld + 9.125, -114.052 * ld * ld, -65.188 * ld + 9.125],
        -77.852 * ld + 15.328,
    )


def lbl_vs_msp(frequency_hz, sections: Sections, radiation: Directivity, medium: Medium) -> np.ndarray:
    """LBL-VS band MSP (Pa²), eq. (53)-(60), with the untripped δ_p (eq. 5, 8); 0 on tripped sections."""
    f = np.asarray(frequency_hz, dtype=float)
    col = _columns(sections, radiation, medium)
    c, span, u, alpha, mach, re_c = (col[k] for k in ("chord_m", "span_m", "speed_mps", "alpha_deg", "mach", "reynolds"))
    r_e, d_h = col["distance_m"], col["high"]
    delta_p = c * bl_thickness_zero_alpha(re_c, False) * pressure_side_ratios(alpha)[0]
    st_peak = st1_prime(re_c) * 10.0 ** (-0.04 * alpha)
    level = (10.0 * np.log10(delta_p * mach**5 * span * d_h / (r_e * r_e))
             + g1(f * delta_p / u / st_peak) + g2(re_c / reynolds_0(alpha)) + 171.04 - 3.03 * alpha)
    return np.where(col["tripped"], 0.0, _scaled_msp(level))


# --------------------------------------------------------------------------------------------
# Trailing-edge bluntness vortex shedding (section 5.1.4)
# --------------------------------------------------------------------------------------------


def st3_peak(h_over_dstar, psi_deg) -> np.ndarray:
    """St'''_peak, eq. (72) (Ψ in degrees)."""
    x = np.asarray(h_over_dstar, dtype=float)
    xs = np.maximum(x, 0.2)
    return np.where(x >= 0.2, (0.212 - 0.0045 * psi_deg) / (1.0 + 0.235 / xs - 0.0132 / (xs * xs)),
                    0.1 * x + 0.095 - 0.00243 * psi_deg)


def g4(h_over_dstar, psi_deg) -> np.ndarray:
    """G_4 (dB), eq. (74)."""
    x = np.asarray(h_over_dstar, dtype=float)
    return np.where(x <= 5.0, 17.5 * np.log10(np.minimum(x, 5.0)) + 157.5, 169.7) - 1.114 * np.asarray(psi_deg)


def g5_psi14(h_over_dstar, eta) -> np.ndarray:
    """G_5 at Ψ = 14° (dB), eq. (76)-(81); η = log10(St'''/St'''_peak)."""
    x = np.asarray(h_over_dstar, dtype=float)
    eta = np.asarray(eta, dtype=float)
    mu = np.select([x < 0.25, x < 0.62, x < 1.15], [0.1221, -0.2175 * x + 0.1755, -0.0308 * x + 0.0596], 0.0242)
    m = np.select([x <= 0.02, x <= 0.5, x <= 0.62, x <= 1.15, x <= 1.2],
                  [0.0, 68.724 * x - 1.35, 308.475 * x - 121.23, 224.811 * x - 69.35, 1583.28 * x - 1631.59],
                  268.344)
    eta0 = -np.sqrt(m * m * mu**4 / (6.25 + m * m * mu * mu))
    k = 2.5 * _sqrt0(1.0 - (eta0 / mu) ** 2) - 2.5 - m * eta0
    return np.select(
        [eta < eta0, eta < 0.0, eta < 0.03616],
        [m * eta + k, 2.5 * _sqrt0(1.0 - (eta / mu) ** 2) - 2.5, _sqrt0(1.5625 - 1194.99 * eta * eta) - 1.25],
        -155.543 * eta + 4.375,
    )


def g5(h_over_dstar, psi_deg, eta) -> np.ndarray:
    """G_5 (dB), eq. (75) with G_5|Ψ=0 from eq. (76) at (h/δ*_avg)' of eq. (82).

    As in RP-1218's program listing (Appendix D, subroutine BLUNT), which drew the report's
    prediction curves, G_5 is limited to ≤ 0 and to ≤ G_5|Ψ=14 at h/δ*_avg = 0.25.
    """
    x = np.asarray(h_over_dstar, dtype=float)
    g14 = g5_psi14(x, eta)
    g0 = g5_psi14(6.724 * x * x - 4.019 * x + 1.107, eta)
    value = g0 + 0.0714 * np.asarray(psi_deg) * (g14 - g0)
    return np.minimum(np.minimum(value, 0.0), g5_psi14(0.25, eta))


def bluntness_msp(frequency_hz, sections: Sections, radiation: Directivity, medium: Medium) -> np.ndarray:
    """Bluntness vortex-shedding band MSP (Pa²), eq. (70)-(82); 0 where h = 0."""
    f = np.asarray(frequency_hz, dtype=float)
    col = _columns(sections, radiation, medium)
    c, span, u, h, mach = (col[k] for k in ("chord_m", "span_m", "speed_mps", "te_thickness_m", "mach"))
    psi, r_e, d_h = col["psi_deg"], col["distance_m"], col["high"]
    bl = trailing_edge_thicknesses(c, col["reynolds"], col["alpha_deg"], col["tripped"])
    x = h / (0.5 * (bl["delta_star_p_m"] + bl["delta_star_s_m"]))  # eq. (73)
    blunt = h > 0.0
    hs, xs = np.where(blunt, h, 1.0), np.where(blunt, x, 1.0)
    eta = np.log10(f * hs / u / st3_peak(xs, psi))
    level = (10.0 * np.log10(hs * mach**5.5 * span * d_h / (r_e * r_e))
             + g4(xs, psi) + g5(xs, psi, eta))
    return np.where(blunt, _scaled_msp(level), 0.0)


# --------------------------------------------------------------------------------------------
# Tip vortex formation (section 5.1.3)
# --------------------------------------------------------------------------------------------


def tip_vortex_msp(frequency_hz, chord_m, speed_mps, alpha_tip_rad, radiation: Directivity, medium: Medium,
                   shape: str = "flat") -> np.ndarray:
    """Tip-vortex formation band MSP (Pa²), eq. (61)-(66); broadcast shape + (n_f,).

    ``alpha_tip_rad`` is α'_TIP of eq. (67), the tip angle already scaled by the lift-slope
    ratio (see :func:`tip_lift_slope_ratio`). Spanwise extent ℓ: eq. (63) for a rounded tip
    (ℓ/c = 0.008 α'_TIP), eq. (66) for a flat (square) tip; M_max/M = 1 + 0.036 α'_TIP (64),
    U_max = c0 M_max (65), St'' = f ℓ / U_max (62), all angles in degrees in the fits.
    """
    if shape not in TIP_SHAPES:
        raise ValueError(f"tip shape must be one of {TIP_SHAPES}, got {shape!r}")
    f = np.asarray(frequency_hz, dtype=float)
    c, u = (np.asarray(v, dtype=float)[..., None] for v in (chord_m, speed_mps))
    if not (np.all(np.isfinite(c)) and np.all(c > 0.0) and np.all(np.isfinite(u)) and np.all(u > 0.0)):
        raise ValueError("tip chord_m and speed_mps must be finite and positive")
    a = np.degrees(np.abs(np.asarray(alpha_tip_rad, dtype=float)))[..., None]
    r_e, d_h = (np.asarray(v, dtype=float)[..., None] for v in (radiation.distance_m, radiation.high))
    if shape == "round":
        ell = 0.008 * a * c
    else:
        ell = np.where(a <= 2.0, 0.0230 + 0.0169 * a, 0.0378 + 0.0095 * a) * c
    mach = u / medium.speed_of_sound_mps
    mach_max = (1.0 + 0.036 * a) * mach
    ells = np.where(ell > 0.0, ell, 1.0)
    st = f * ells / (mach_max * medium.speed_of_sound_mps)
    level = (10.0 * np.log10(mach * mach * mach_max**3 * ells * ells * d_h / (r_e * r_e))
             - 30.5 * (np.log10(st) + 0.3) ** 2 + 126.0)
    return np.where(ell > 0.0, _scaled_msp(level), 0.0)


# Brooks & Marcolini, "Airfoil tip vortex formation noise", AIAA J. 24(2), 1986: ratio of the tip
# lift-curve slope to the two-dimensional one against the blade aspect ratio (as BPM.jl tabulates it).
_ASPECT_RATIO = np.array([2.0, 2.67, 4.0, 6.0, 12.0, 24.0])
_LIFT_SLOPE_RATIO = np.array([0.54, 0.62, 0.71, 0.79, 0.89, 0.95])


def tip_lift_slope_ratio(aspect_ratio: float) -> float:
    """(∂L'/∂y)_TIP / (∂L'/∂y)_ref of eq. (67) from the blade aspect ratio (R / mean chord).

    Linear interpolation of Brooks & Marcolini's (1986) table, held constant beyond its ends
    (aspect ratios 2 and 24).
    """
    if not (np.isfinite(aspect_ratio) and aspect_ratio > 0.0):
        raise ValueError(f"aspect_ratio must be finite and positive, got {aspect_ratio}")
    return float(np.interp(aspect_ratio, _ASPECT_RATIO, _LIFT_SLOPE_RATIO))


# --------------------------------------------------------------------------------------------
# All section mechanisms and the data range
# --------------------------------------------------------------------------------------------


def section_msp(frequency_hz, sections: Sections, radiation: Directivity, medium: Medium) -> dict[str, np.ndarray]:
    """Band MSP (Pa²) of the five section mechanisms (all of COMPONENTS but ``tip``), shape S + (n_f,).

    LBL-VS without any untripped section and bluntness without any h > 0 are 0 Pa² everywhere: not evaluated.
    """
    f = np.asarray(frequency_hz, dtype=float)
    if not (np.all(np.isfinite(f)) and np.all(f > 0.0)):
        raise ValueError("frequency_hz must be finite and positive")
    out = tbl_te_msp(f, sections, radiation, medium)
    fields = [getattr(sections, n) for n in sections.__dataclass_fields__]
    fields += [getattr(radiation, n) for n in radiation.__dataclass_fields__]
    shape = np.broadcast_shapes(*(np.shape(v) + (1,) for v in fields), f.shape)
    out["lbl_vs"] = (np.zeros(shape) if np.all(sections.tripped)
                     else lbl_vs_msp(f, sections, radiation, medium))
    out["bluntness"] = (np.zeros(shape) if not np.any(np.asarray(sections.te_thickness_m) > 0.0)
                        else bluntness_msp(f, sections, radiation, medium))
    return out


def valid_range(speed_mps, chord_m, alpha_rad, medium: Medium) -> dict[str, np.ndarray]:
    """Which elements lie outside the range of RP-1218's measurements (True = outside).

    The data: NACA 0012 sections of 2.54-30.48 cm chord (60.96 cm in the bluntness tests) at
    31.7-71.3 m/s (Mach 0.093-0.209), tunnel angles of attack 0-25.2° (the effective α* is
    smaller), so chord Reynolds numbers ≈ 4e4-3e6 (DATA_* constants). Returns boolean arrays
    ``reynolds``, ``mach``, ``alpha`` and ``any``, broadcast over the inputs. Brooks & Burley
    (AIAA 2001-2210) used the model up to rotor tip Mach numbers near 0.6: outside the data
    the scaling laws are extrapolated, not wrong by construction, hence a warning, not an error.
    """
    u = np.asarray(speed_mps, dtype=float)
    re = u * np.asarray(chord_m, dtype=float) / medium.kinematic_viscosity_m2_s
    mach = u / medium.speed_of_sound_mps
    alpha = np.degrees(np.abs(np.asarray(alpha_rad, dtype=float)))
    out = {
        "reynolds": (re < DATA_REYNOLDS_RANGE[0]) | (re > DATA_REYNOLDS_RANGE[1]),
        "mach": mach > DATA_MACH_RANGE[1],
        "alpha": alpha > DATA_ALPHA_RANGE_DEG[1],
    }
    out["any"] = out["reynolds"] | out["mach"] | out["alpha"]
    return out
