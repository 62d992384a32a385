"""Dual-compact thickness lines against a full-surface F1A thickness computation done here.

Case (issue 5; the 1/7-scale UH-1H hover rotor of Boxwell et al. used by Baeder's CFD): B = 2
untwisted rectangular blades, R = 1.045 m, c = 0.0762 m, NACA 0012 (closed trailing edge,
y_t coefficient −0.1036, so the surface is closed; area 0.68088 t c), zero pitch, root cut-out
0.2 R (assumed: thickness noise comes from the outer span), ρ0 = 1.225 kg/m³, c0 = 340.294 m/s,
observer at 3.09 R from the hub, in the rotor plane and 30° below it.

Reference, independent of nps: the thickness term of Farassat's formulation 1A on the blade
surface, 4π p_T = ∫ [ρ0 (v̇_n)/(r(1−M_r)²) + ρ0 v_n (r Ṁ_r + c0(M_r − M²))/(r²(1−M_r)³)]_ret dS,
in numpy. In hover a rigid blade has v_n = (Ω ẑ × y)·n constant in time, so the first term
vanishes exactly. Panels: cosine-spaced chordwise strips on upper and lower surfaces × uniform
spanwise strips; each panel's ∫ v_n dS is exact (Ω r dr [y_t(x_k+1) − y_t(x_k)] c) and placed
at its centroid (midpoint quadrature of the surface integral). The tip and root faces are left
open: on them v_n = ∓Ω d (d the chord offset from the pitch axis), a net flux ∓ρ0 Ω ∫ d dA;
closing them changes the signal by 0.67–0.95 % of peak-to-peak
(tests/validation/test_wopwop_surface_thickness.py). Source-time dominant: one blade over one
revolution, reception times in closed form (stationary observer), linear periodic interpolation
onto the observer grid, the second blade added by the half-period shift. Its resolution (24 × 60
panels per side, 1024 source steps) is within 0.7 % (peak) and 0.3 % (width) of 80 × 80 panels,
8192 steps.

Compared: negative peak pressure and pulse width (full width at half the negative peak).
Tolerances: issue 5 acceptance, dual compact within 10 % of the full surface at M_tip 0.88 in
plane; also asserted at −30° and over M_tip 0.88–0.95 in plane. At M_tip 0.3 the blade is
compact: full surface, compact monopole and dual compact agree within 1 %.
Measured (dual compact / full surface − 1, peak and width): M 0.88 in plane +3.4 %, −2.5 %
(−171.4 Pa, 224 µs full surface); −30°: +1.0 %, −0.6 % (−22.9 Pa, 536 µs); in plane M 0.90 +3.6 %,
−2.1 %; M 0.925 +1.8 %, +1.1 %; M 0.95 −1.7 %, +8.1 %. M 0.3: +0.3 %, −0.03 %. The compact
monopole's peak is +36 % at M 0.88 in plane and +358 % at 0.95.
"""

import numpy as np
import pandas as pd
import pytest

from nps.noise.acoustics import Observers, TimeGrid, radiate_arrays
from nps.rotor.geometry import RotorMotion
from nps.noise.sources import ThicknessModel, rotor_sources

RADIUS, CHORD, B, C0, RHO0 = 1.045, 0.0762, 2, 340.294, 1.225
ROOT = 0.2 * RADIUS
THICKNESS_RATIO = 0.12
AREA_FACTOR = 0.68088  # ∫ 2 y_t dx / (t c) for the closed-trailing-edge NACA 00xx
N_OUT = 4096


def _half_thickness(x):
    """NACA 00xx half thickness / c at x = x/c (closed trailing edge)."""
    return 5 * THICKNESS_RATIO * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)


def _panels(n_chord, n_span):
    """Panel centroids (rotating components e_r, e_t toward the leading edge, z; m) and ∫ v_n dS / Ω (m³)."""
    x_edge = 0.5 * (1 - np.cos(np.linspace(0, np.pi, n_chord + 1)))
    x_mid = 0.5 * (x_edge[1:] + x_edge[:-1])
    r_edge = np.linspace(ROOT, RADIUS, n_span + 1)
    r_mid = 0.5 * (r_edge[1:] + r_edge[:-1])
    rr, xx = np.meshgrid(r_mid, x_mid, indexing="ij")
    # outward n dS = (0, y_t'(x), ±1) dr d(offset) on both sides: ∫ v_n dS = Ω r dr ∫ y_t' dx
    flux = (rr * np.diff(r_edge)[:, None] * np.diff(_half_thickness(x_edge))[None, :] * CHORD).ravel()
    offset = (0.25 - xx) * CHORD  # pitch axis at the quarter chord, as in nps.noise.sources
    points = [np.stack([rr, offset, side * _half_thickness(xx) * CHORD], axis=-1).reshape(-1, 3) for side in (1.0, -1.0)]
    return np.concatenate(points), np.concatenate([flux, flux])


def full_surface_pressure(mach_tip, observer_m, n_chord=24, n_span=60, n_tau=1024):
    """Thickness pressure (Pa) of the two-blade rotor at t_k = k T / N_OUT (full-surface F1A)."""
    omega = mach_tip * C0 / RADIUS
    period = 2 * np.pi / omega
    points, flux = _panels(n_chord, n_span)
    strength = RHO0 * omega * flux  # ρ0 ∫ v_n dS, kg/s
    tau = np.arange(n_tau) * period / n_tau
    cos_psi, sin_psi = np.cos(omega * tau), np.sin(omega * tau)
    times = np.arange(N_OUT) * period / N_OUT
    blade = np.zeros(N_OUT)
    for chunk in np.array_split(np.arange(len(flux)), max(1, len(flux) // 400)):
        r_c, d_c, z_c = (points[chunk, k, None] for k in range(3))
        y = np.stack([r_c * cos_psi - d_c * sin_psi, r_c * sin_psi + d_c * cos_psi, np.broadcast_to(z_c, (chunk.size, n_tau))], -1)
        vel = omega * np.stack([-y[..., 1], y[..., 0], np.zeros_like(y[..., 2])], -1)
        acc = -omega**2 * np.stack([y[..., 0], y[..., 1], np.zeros_like(y[..., 2])], -1)
        rel = observer_m - y
        dist = np.linalg.norm(rel, axis=-1)
        unit = rel / dist[..., None]
        m_r = np.einsum("ijk,ijk->ij", vel, unit) / C0
        m_2 = np.einsum("ijk,ijk->ij", vel, vel) / C0**2
        mdot_r = np.einsum("ijk,ijk->ij", acc, unit) / C0
        p = strength[chunk, None] * (dist * mdot_r + C0 * (m_r - m_2)) / (4 * np.pi * dist**2 * (1 - m_r) ** 3)
        t_rec = tau + dist / C0
        for k in range(chunk.size):
            blade += np.interp(times, t_rec[k], p[k], period=period)
    return sum(np.roll(blade, k * N_OUT // B) for k in range(B))


def compact_pressure(mach_tip, observer_m, kind, n_r=50, n_psi=256):
    """Thickness pressure (Pa) from nps.noise.sources + nps.noise.acoustics (periodic path), same grid."""
    omega = mach_tip * C0 / RADIUS
    r_mid = ROOT + (np.arange(n_r) + 0.5) * (RADIUS - ROOT) / n_r
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r_mid, indexing="ij")
    disk = pd.DataFrame({"psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": (RADIUS - ROOT) / n_r, "chord_m": CHORD,
                         "thickness_m": THICKNESS_RATIO * CHORD, "theta_rad": 0.0, "beta_rad": 0.0,
                         "fz_N_per_m": 0.0, "fx_N_per_m": 0.0})
    motion = RotorMotion(np.zeros(3), np.zeros(3), np.eye(3), omega, 1, B)
    sources = rotor_sources(disk, motion, thickness=ThicknessModel(kind=kind, area_factor=AREA_FACTOR), rho0_kg_m3=RHO0, c0_mps=C0)
    p = radiate_arrays(sources, Observers(observer_m[None], np.zeros((1, 3))), TimeGrid(0.0, 2 * np.pi / omega, N_OUT),
                       c0_mps=C0, rho0_kg_m3=RHO0)
    return p[0, sources.groups.index("thickness")]


def negative_pulse(p, dt):
    """(negative peak in Pa, full width in s at half the negative peak) of a periodic signal."""
    i = int(np.argmin(p))
    half = 0.5 * p[i]
    n = p.size

    def crossing(step):
        j = i
        while p[(j + step) % n] < half:
            j += step
        a, b = p[j % n], p[(j + step) % n]
        return j + step * (half - a) / (b - a)

    return p[i], (crossing(1) - crossing(-1)) * dt


def _observer(elevation_deg):
    e = np.radians(elevation_deg)
    return 3.09 * RADIUS * np.array([np.cos(e), 0.0, np.sin(e)])


def _compare(mach_tip, elevation_deg, kind="dual_compact"):
    obs = _observer(elevation_deg)
    dt = 2 * np.pi * RADIUS / (mach_tip * C0) / N_OUT
    full = negative_pulse(full_surface_pressure(mach_tip, obs), dt)
    model = negative_pulse(compact_pressure(mach_tip, obs, kind), dt)
    peak, width = model[0] / full[0] - 1, model[1] / full[1] - 1
    print(f"M_tip {mach_tip} el {elevation_deg:+.0f} deg {kind}: full surface {full[0]:.4g} Pa, {full[1] * 1e6:.1f} us; "
          f"model {model[0]:.4g} Pa, {model[1] * 1e6:.1f} us; peak {peak:+.2%}, width {width:+.2%}")
    return peak, width


@pytest.mark.parametrize("elevation_deg", [0.0, -30.0])
def test_compact_limit_full_surface_monopole_dual(elevation_deg):
    """M_tip 0.3: full surface, compact monopole and dual compact agree within 1 % (peak and width).

    Checks the reference surface integral against the compact monopole (ANOPP2-validated) where the
    blade is compact, and that the dual-compact force law has the monopole as its compact limit
    (the thesis' ±ρ0c²·t·dr lines give 12.7× the full-surface peak here, see docs/reference/acoustics.md).
    """
    for kind in ("compact_monopole", "dual_compact"):
        peak, width = _compare(0.3, elevation_deg, kind)
        assert abs(peak) < 0.01 and abs(width) < 0.01


@pytest.mark.parametrize("elevation_deg", [0.0, -30.0])
def test_dual_compact_vs_full_surface_uh1h(elevation_deg):
    """Issue 5 acceptance, M_tip 0.88: negative peak and pulse width within 10 % of the full surface."""
    peak, width = _compare(0.88, elevation_deg)
    assert abs(peak) < 0.10 and abs(width) < 0.10


@pytest.mark.parametrize("mach_tip", [0.90, 0.925, 0.95])
def test_dual_compact_vs_full_surface_high_mach(mach_tip):
    """In plane, M_tip 0.90–0.95: negative peak and pulse width within 10 % (the compact monopole is 60–360 % loud)."""
    peak, width = _compare(mach_tip, 0.0)
    assert abs(peak) < 0.10 and abs(width) < 0.10
