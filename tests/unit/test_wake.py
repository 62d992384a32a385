"""Unit tests of nps.wake.vortex and nps.wake.prescribed: Biot–Savart segment kernel, core growth, Betz
structure, Beddoes geometry, frames."""

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.wake import prescribed as wake
from nps.wake import vortex
from nps.wake.vortex import VortexModel
from nps.core.frames import rot_x, rot_y, rot_z

POINT = VortexModel(vortex_structure="point")


def _analytic_segment(x, h, a, b, gamma, rc, n=2.0):
    """Eq. 5.10/5.15 written with angles: segment a→b on the x axis, point at (x, h) (h > 0).

    |V| = Γ/(4π) h/(r_c^{2n}+h^{2n})^{1/n} (cos θ1 − cos θ2), cos θ1 = (x−a)/|P−A|,
    cos θ2 = (x−b)/|P−B|; direction +z for the point on +y (right-hand rule about +x).
    """
    c1 = (x - a) / math.hypot(x - a, h)
    c2 = (x - b) / math.hypot(x - b, h)
    return gamma / (4 * math.pi) * h / (rc ** (2 * n) + h ** (2 * n)) ** (1 / n) * (c1 - c2)


@settings(max_examples=60, deadline=None)
@given(
    x=st.floats(-3.0, 3.0),
    h=st.floats(0.2, 4.0),
    a=st.floats(-2.0, 0.0),
    length=st.floats(0.05, 3.0),
    angles=st.tuples(st.floats(-3.1, 3.1), st.floats(-3.1, 3.1), st.floats(-3.1, 3.1)),
)
def test_segment_matches_analytic_finite_segment(x, h, a, length, angles):
    """Far from the core (h ≥ 20 r_c) the kernel equals the classical finite-segment law,
    in any orientation (random rotation): to 1e-9 Γ/(4πh) with the core factor, to the core
    factor (r_c/h)⁴ ≤ 6e-6 without it."""
    gamma, rc = 3.7, 0.01
    b = a + length
    rot = rot_z(angles[0]) @ rot_y(angles[1]) @ rot_x(angles[2])
    point = rot @ np.array([x, h, 0.0])
    start, end = rot @ np.array([a, 0, 0.0]), rot @ np.array([b, 0, 0.0])
    v = vortex.segment_induced_velocity(point[None], start[None], end[None], gamma, rc)[0]
    expected = _analytic_segment(x, h, a, b, gamma, rc) * (rot @ np.array([0.0, 0.0, 1.0]))
    # the analytic expression includes the (here ~1e-8) Vatistas factor as well
    assert np.allclose(v, expected, rtol=0, atol=1e-9 * gamma / (4 * math.pi * h))
    # and the pure Biot–Savart value differs only by the core factor 1/sqrt(1+(rc/h)^4)
    pure = _analytic_segment(x, h, a, b, gamma, 0.0)
    assert abs(np.linalg.norm(v) - abs(pure)) <= abs(pure) * (rc / h) ** 4 + 1e-12


def test_long_segment_gives_infinite_line_law():
    """A segment 2×10⁵ h long gives Γ/(2πh) far from the core (rel. error < 1e-8)."""
    gamma, h, rc = 12.0, 0.5, 0.005
    v = vortex.segment_induced_velocity([[0.3, h, 0.0]], [[-1e5, 0, 0]], [[1e5, 0, 0]], gamma, rc)[0]
    assert v[0] == 0.0 and v[1] == 0.0
    assert v[2] == pytest.approx(gamma / (2 * math.pi * h), rel=1e-8)


def test_core_is_finite_and_continuous():
    """Crossing an infinite line: Vatistas n=2 profile Γ/(2π) h/sqrt(r_c⁴+h⁴), zero on the
    axis, peak Γ/(2√2 π r_c) at h = r_c; samples 1e-3 r_c apart differ by ≤ the profile's
    maximum slope × step (continuity)."""
    gamma, rc = 5.0, 0.06
    h = np.linspace(-3 * rc, 3 * rc, 6001)
    pts = np.column_stack([np.zeros_like(h), h, np.zeros_like(h)])
    v = vortex.segment_induced_velocity(pts, [[-1e4, 0, 0]], [[1e4, 0, 0]], gamma, rc)[:, 2]
    assert np.isfinite(v).all()
    profile = gamma / (2 * math.pi) * h / np.sqrt(rc**4 + h**4)
    assert np.allclose(v, profile, rtol=1e-7, atol=1e-12)
    assert v[np.argmin(np.abs(h))] == pytest.approx(0.0, abs=1e-9)
    assert np.abs(v).max() == pytest.approx(gamma / (2 * math.sqrt(2) * math.pi * rc), rel=1e-6)
    slope_max = gamma / (2 * math.pi * rc**2)
    assert np.abs(np.diff(v)).max() <= slope_max * (h[1] - h[0]) * 1.0001
    # general exponent: n = 1 is the Scully core, Γ/(2π) h/(r_c² + h²)
    v1 = vortex.segment_induced_velocity(pts, [[-1e4, 0, 0]], [[1e4, 0, 0]], gamma, rc, vatistas_n=1.0)[:, 2]
    assert np.allclose(v1, gamma / (2 * math.pi) * h / (rc**2 + h**2), rtol=1e-7, atol=1e-12)


def test_point_on_segment_and_at_nodes_gives_zero():
    v = vortex.segment_induced_velocity([[0, 0, 0], [1, 0, 0], [0.5, 0, 0]], [[0, 0, 0]], [[1, 0, 0]], 1.0, 0.1)
    assert np.all(v == 0.0)


def test_mean_inflow_limits():
    """Eq. 5.2: hover λ0 = sqrt(C_T/2); high speed λ0 → C_T/(2μ) (rel. 1e-9 and 1e-3)."""
    assert wake.mean_inflow(0.005, 0.0, 0.0) == pytest.approx(math.sqrt(0.0025), rel=1e-9)
    assert wake.mean_inflow(0.005, 0.4, 0.0) == pytest.approx(0.005 / 0.8, rel=1e-3)
    lam = wake.mean_inflow(0.0095, 0.23, -0.024)
    assert 2 * lam * math.hypot(0.23, lam - 0.024) == pytest.approx(0.0095, rel=1e-10)
    with pytest.raises(ValueError):
        wake.mean_inflow(-1.0, 0.1, 0.0)


def _state(**kw):
    base = dict(
        radius_m=2.0, chord_m=0.121, n_blades=4, omega_rad_s=109.12, rotation_sign=1,
        mu_x=0.15, mu_y=0.0, mu_z=-0.011, ct=0.0044,
        gamma_table_m2_s=np.full(72, 2.5), beta_table_rad=np.full(72, 0.04),
    )
    base.update(kw)
    return wake.WakeState(**base)


def test_beddoes_geometry_matches_equations():
    """Nodes equal an independent evaluation of eq. 5.4–5.7 (with the documented sign
    reading) to 1e-12 m; node 0 is the flapped blade tip."""
    model = wake.WakeModel(revolutions=2.0, steps_per_rev=90)
    s = _state(gamma_table_m2_s=np.linspace(1, 3, 72), beta_table_rad=0.04 + 0.01 * np.cos(2 * np.pi * np.arange(72) / 72))
    snap = wake.wake_snapshot(s, model, psi_blade_rad=0.3)
    lam0 = wake.mean_inflow(s.ct, s.mu_x, s.mu_z)
    chi = math.atan(s.mu_x / (s.mu_z + lam0))
    for k in range(4):
        phi = snap.age_rad
        psi_v = 0.3 + k * np.pi / 2 - phi
        beta = 0.04 + 0.01 * np.cos(psi_v)  # table is exactly sampled harmonic; linear interp error below
        r_v = 0.85 + 0.15 * np.exp(-(0.145 + 27 * s.ct) * phi)
        x = r_v * np.cos(psi_v) + s.mu_x * phi
        y = r_v * np.sin(psi_v)
        z = np.sin(beta) - s.mu_z * phi - lam0 * phi * (
            0.5 * chi * (np.cos(psi_v) + s.mu_x * phi / (2 * r_v) - np.abs(r_v * np.sin(psi_v)) ** 3)
            - 2 * s.mu_x * np.sin(psi_v) + 1.1
        )
        assert np.allclose(snap.nodes_m[k, :, 0], 2 * x, atol=1e-12)
        assert np.allclose(snap.nodes_m[k, :, 1], 2 * y, atol=1e-12)
        # flap table linear interpolation: |error| <= (dpsi^2/8) * 0.01 rad * R
        assert np.allclose(snap.nodes_m[k, :, 2], 2 * z, atol=2 * 0.01 * (2 * np.pi / 72) ** 2 / 8 + 1e-12)
    assert np.allclose(snap.nodes_m[:, 0, :2], 2 * np.column_stack([np.cos(0.3 + np.arange(4) * np.pi / 2), np.sin(0.3 + np.arange(4) * np.pi / 2)]))


def test_hover_wake_convects_below_disk_and_contracts():
    """Hover: every node older than 0 lies below its release height, descends
    monotonically, and the radius tends to D·R (within 1 % after 4 revolutions)."""
    s = _state(mu_x=0.0, mu_z=0.0, beta_table_rad=np.zeros(72))
    snap = wake.wake_snapshot(s, wake.WakeModel(), 0.0)
    z = snap.nodes_m[..., 2]
    assert np.all(z[:, 1:] < 0.0) and np.all(np.diff(z, axis=1) < 0.0)
    radius = np.hypot(snap.nodes_m[..., 0], snap.nodes_m[..., 1])
    assert radius[:, -1] == pytest.approx(0.85 * 2.0, rel=1e-2)


def test_hover_induced_velocity_is_axisymmetric_downwash():
    """Hover, constant Γ: induced velocity is a downwash (v_z < 0) inside the disk and the
    same at every azimuth (no impulsive content: spread over ψ < 1e-6 of the mean)."""
    s = _state(mu_x=0.0, mu_z=0.0, beta_table_rad=np.zeros(72))
    psi = 2 * np.pi * np.arange(36) / 36
    r = np.linspace(0.5, 1.8, 14)
    v = wake.disk_induced_velocity(s, wake.WakeModel(revolutions=4, steps_per_rev=180, vortex=POINT), psi, r, 0.0)
    assert np.all(v[:, :-1, 2] < 0.0)
    spread = np.ptp(v[..., 2], axis=0)
    assert np.all(spread < 1e-6 * np.abs(v[..., 2]).mean())


def test_disk_kernel_equals_generic_segment_kernel():
    """The disk kernel (node-vector reuse, per-row snapshot) equals the generic segment
    kernel applied to the snapshot's segments (rel. 1e-12)."""
    s = _state(gamma_table_m2_s=1.0 + np.sin(2 * np.pi * np.arange(72) / 72) ** 2)
    model = wake.WakeModel(revolutions=1.5, steps_per_rev=72, vortex=replace(POINT, core_growth=True))
    psi = np.array([0.0, 1.0, 2.5])
    r = np.array([0.8, 1.5, 1.95])
    v = wake.disk_induced_velocity(s, model, psi, r, 0.04)
    pts = wake.blade_points(psi, r, 0.04)
    for i, p in enumerate(psi):
        snap = wake.wake_snapshot(s, model, p)
        starts = snap.nodes_m[:, :-1].reshape(-1, 3)
        ends = snap.nodes_m[:, 1:].reshape(-1, 3)
        g = 0.5 * (snap.strength_m2_s[:, :-1] + snap.strength_m2_s[:, 1:]).ravel()
        rc = 0.5 * (snap.core_radius_m[:, :-1] + snap.core_radius_m[:, 1:]).ravel()
        ref = vortex.segment_induced_velocity(pts[i], starts, ends, g, rc)
        assert np.allclose(v[i], ref, rtol=1e-12, atol=1e-12)


def test_core_growth_law():
    """Squire growth: r_c² = r_c0² + 4αν(1 + a₁Γ/ν)φ/Ω (rel. 1e-12); constant when off."""
    s = _state()
    on = wake.wake_snapshot(s, wake.WakeModel(revolutions=2, vortex=VortexModel(core_growth=True)), 0.0)
    off = wake.wake_snapshot(s, wake.WakeModel(revolutions=2, vortex=VortexModel(core_growth=False)), 0.0)
    rc0 = 0.5 * 0.121
    phi = on.age_rad
    expected = np.sqrt(rc0**2 + 4 * 1.25643 * 1.5e-5 * (1 + 6.5e-5 * 2.5 / 1.5e-5) * phi / 109.12)
    assert np.allclose(on.core_radius_m[0], expected, rtol=1e-12)
    assert np.all(off.core_radius_m == rc0)


def test_clockwise_rotor_is_the_mirror_of_the_counterclockwise_rotor():
    """A cw rotor with side wind μ_y is the y-mirror of the ccw rotor with −μ_y.

    Independent check of handedness: the cw wake is built in the hub frame H (mirrored
    nodes); its bound circulation points inboard (−e_r for lift up with e_r = (cos ψ, −sin ψ, 0)),
    so its trailed tip vortex carries −Γ from young to old. The generic segment kernel on
    that geometry, resolved on the cw blade (motion e_t = (−sin ψ, −cos ψ, 0)), must give
    the same ΔU_T and the same vertical velocity as the ccw disk kernel (rel. 1e-10)."""
    ccw = _state(mu_y=-0.03, rotation_sign=1)
    cw = _state(mu_y=0.03, rotation_sign=-1)
    model = wake.WakeModel(revolutions=1.0, steps_per_rev=72, vortex=POINT)
    psi = np.array([0.4, 2.0])
    r = np.array([1.0, 1.9])
    v_ccw = wake.disk_induced_velocity(ccw, model, psi, r, 0.0)
    for i, p in enumerate(psi):
        snap = wake.wake_snapshot(cw, model, p)
        nodes_h = wake.to_hub_frame(snap.nodes_m, -1)
        starts, ends = nodes_h[:, :-1].reshape(-1, 3), nodes_h[:, 1:].reshape(-1, 3)
        g = -0.5 * (snap.strength_m2_s[:, :-1] + snap.strength_m2_s[:, 1:]).ravel()
        pts = r[:, None] * np.array([np.cos(p), -np.sin(p), 0.0])
        v_h = vortex.segment_induced_velocity(pts, starts, ends, g, 0.5 * 0.121)
        e_t = np.array([-np.sin(p), -np.cos(p), 0.0])
        e_t_ccw = np.array([-np.sin(p), np.cos(p), 0.0])
        assert np.allclose(v_h @ e_t, v_ccw[i] @ e_t_ccw, rtol=1e-10, atol=1e-12)
        assert np.allclose(v_h[:, 2], v_ccw[i][:, 2], rtol=1e-10, atol=1e-12)
    assert np.allclose(wake.to_hub_frame(v_ccw, -1)[..., 1], -v_ccw[..., 1])


def test_bad_inputs_are_rejected():
    with pytest.raises(ValueError, match="non-finite"):
        _state(gamma_table_m2_s=np.array([1.0, np.nan, 1.0, 1.0]), beta_table_rad=np.zeros(4))
    with pytest.raises(ValueError, match="ct"):
        _state(ct=0.0)
    with pytest.raises(ValueError, match="d_contraction"):
        wake.WakeModel(d_contraction=1.5)
    with pytest.raises(ValueError, match="shapes"):
        vortex.segment_induced_velocity(np.zeros((2, 3)), np.zeros((2, 3)), np.zeros((3, 3)), 1.0, 0.1)


def test_betz_roll_up_of_elliptic_loading_is_analytic():
    """Betz roll-up of an elliptic sheet Γ = Γ0 √(1 − (r/R)²) (peak at r = 0): with r = R cos θ,
    the vorticity outboard of r lies within ρ = R (θ/2 − sin 2θ / 4) / sin θ and encloses
    Γ0 sin θ (∫_r^R Γ dr = Γ0 R (θ/2 − sin 2θ/4)). Numerical (2000 stations) within 0.5 % of Γ0
    at every ρ."""
    radius, gamma0 = 2.0, 3.0
    r = np.linspace(0.0, radius, 2001)[:-1]
    rho, enclosed = vortex.betz_enclosed_circulation(r, gamma0 * np.sqrt(1.0 - (r / radius) ** 2), radius)
    theta = np.linspace(0.05, np.pi / 2, 200)
    rho_exact = radius * (theta / 2 - np.sin(2 * theta) / 4) / np.sin(theta)
    assert np.allclose(np.interp(rho_exact, rho, enclosed), gamma0 * np.sin(theta), atol=5e-3 * gamma0)
    assert enclosed[-1] == pytest.approx(gamma0) and rho[-1] == pytest.approx(radius * np.pi / 4, rel=1e-3)


def _linear_sheet_state(**kw):
    """Γ falling linearly from 4 m²/s at 0.5 R to 0 at the tip at ψ = 90° (a sheet half a radius
    wide, as HART-II's advancing side), tip-loaded (peak at 0.98 R) at ψ = 270°, blended
    smoothly in between."""
    radius = 2.0
    r = np.linspace(0.3, 1.96, 40)
    wide = np.where(r < 1.0, 4.0, 4.0 * (radius - r) / (radius - 1.0))
    narrow = 4.0 * np.minimum(r / 1.96, 1.0)
    weight = 0.5 * (1.0 + np.sin(2 * np.pi * np.arange(360) / 360))[:, None]
    gamma = weight * wide + (1.0 - weight) * narrow
    return _state(gamma_table_m2_s=gamma.max(axis=1), beta_table_rad=np.full(360, 0.04),
                  vortex_profile=vortex.vortex_profile_table(r, gamma, radius), **kw)


def test_betz_structure_equals_its_vortex_layers():
    """The structure factor equals the explicit sum it stands for: every annulus of the Betz
    distribution a point vortex of circulation ΔΓ and Vatistas core max(ρ, r_c) on the same
    path (40 geometric layers). Disk velocities agree within 2 % of the point-vortex peak
    (measured 0.9 %: the 129-point table). The
    wide sheet's vortex (ψ = 90°) is diffuse (< 30 % of Γ_v within 10 cm of its centre), the
    tip-loaded one (ψ = 270°) concentrated (> 95 %)."""
    s = _linear_sheet_state(mu_x=0.15, mu_z=-0.011)
    model = wake.WakeModel(revolutions=1.5, steps_per_rev=72)
    point = wake.WakeModel(revolutions=1.5, steps_per_rev=72, vortex=POINT)
    psi = 2 * np.pi * np.arange(72) / 72
    r = np.linspace(1.0, 1.95, 8)
    v = wake.disk_induced_velocity(s, model, psi, r, 0.04)
    v_point = wake.disk_induced_velocity(s, point, psi, r, 0.04)
    rho = vortex.profile_radii(vortex.PROFILE_SCALE_RADII * s.radius_m)
    edges = 0.002 * 1.2 ** np.arange(40)
    enclosed = np.array([np.interp(edges, rho[:-1], row[:-1], right=1.0) for row in s.vortex_profile])
    layers = np.diff(np.concatenate([np.zeros((360, 1)), enclosed], axis=1), axis=1) * s.gamma_table_m2_s[:, None]
    layer_radius = 0.5 * (np.concatenate([[0.0], edges[:-1]]) + edges)
    v_layers = sum(
        wake.disk_induced_velocity(replace(s, gamma_table_m2_s=layers[:, m]),
                                   replace(point, vortex=replace(POINT, core_radius_chords=max(layer_radius[m], 0.5 * s.chord_m) / s.chord_m)),
                                   psi, r, 0.04)
        for m in range(edges.size))
    peak = np.abs(v_point).max()
    assert np.abs(v - v_layers).max() < 0.02 * peak
    fraction_within_10_cm = [np.interp(0.1, rho[:-1], s.vortex_profile[i, :-1]) for i in (90, 270)]
    assert fraction_within_10_cm[0] < 0.3 and fraction_within_10_cm[1] > 0.95, fraction_within_10_cm


def test_betz_structure_needs_the_profile():
    """vortex_structure 'betz' without the loads' profile is refused with a message; a profile
    of the wrong shape is refused when the state is built."""
    with pytest.raises(ValueError, match="vortex_profile"):
        wake.disk_induced_velocity(_state(), wake.WakeModel(), np.zeros(1), np.ones(1), 0.0)
    with pytest.raises(ValueError, match="vortex_profile"):
        _state(vortex_profile=np.ones((72, 5)))
    with pytest.raises(ValueError, match="vortex_structure"):
        VortexModel(vortex_structure="lamb")


def test_structure_factor_polynomial_fits_its_table():
    """The kernel's polynomial T(u) reproduces the structure-factor table within 1e-3 for a wide
    sheet, a tip-loaded one and every blend (T between 0 and 1, T = 1 at u = 1)."""
    s = _linear_sheet_state()
    scale = vortex.PROFILE_SCALE_RADII * s.radius_m
    table = vortex.structure_factor_table(s.vortex_profile, scale, 0.5 * s.chord_m)
    coefficients, s2 = VortexModel().structure_coefficients(s.vortex_profile, s.radius_m, s.chord_m)
    x = np.linspace(-1.0, 1.0, table.shape[1])
    fitted = np.array([np.polynomial.polynomial.polyval(x, c) for c in coefficients])
    assert s2 == pytest.approx(scale**2)
    assert np.abs(fitted - table).max() < 1e-3
    assert np.all((table > 0.0) & (table <= 1.0 + 1e-12)) and np.allclose(table[:, -1], 1.0)
