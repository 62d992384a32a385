"""Unit tests of nps.noise.sources: placement, signs, analytic kinematics, force on the fluid."""

import numpy as np
import pandas as pd
import pytest

from nps.noise.acoustics import AcousticsError
from nps.rotor.geometry import RotorMotion
from nps.noise.sources import ThicknessModel, periodic_dpsi, rotor_sources


def _motion(sign=1, speed=0.0):
    return RotorMotion(np.array([0.0, 0.0, 2.0]), np.array([speed, 0.0, 0.0]), np.eye(3), 20.0, sign, 4)


def _disk(n_psi=72, beta=lambda p: 0.0 * p, theta=0.0, fz=500.0, fx=30.0):
    r = np.array([2.0, 3.0, 4.0])
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    return pd.DataFrame({"psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": 1.0, "chord_m": 0.5, "thickness_m": 0.05,
                         "theta_rad": theta, "beta_rad": beta(pp).ravel(), "fz_N_per_m": fz, "fx_N_per_m": fx})


def test_rigid_rotor_kinematics_and_rotation_sign():
    """Blade 0 at ψ = 90° lies on s·y_H; velocity = Ω ẑ·s × r (+ V); acceleration centripetal; |jerk| = Ω³ r."""
    for sign in (1, -1):
        src = rotor_sources(_disk(), _motion(sign, 10.0), rho0_kg_m3=1.2, c0_mps=340.0)
        j = 18  # ψ = 90°
        rel = src.position_m[0, j] - np.array([10.0 * src.time_s[j], 0.0, 2.0])
        assert np.allclose(rel, [0.0, sign * 2.0, 0.0], atol=1e-12)
        omega_vec = np.array([0.0, 0.0, sign * 20.0])
        rel_all = src.position_m[:3] - (np.array([0.0, 0.0, 2.0]) + src.time_s[:, None] * [10.0, 0.0, 0.0])[None]
        assert np.allclose(src.velocity_mps[:3], np.cross(omega_vec, rel_all) + [10.0, 0.0, 0.0], atol=1e-9)
        assert np.allclose(src.acceleration_mps2[:3], -400.0 * rel_all * [1, 1, 0], atol=1e-8)
        assert np.allclose(np.linalg.norm(src.jerk_mps3[:3], axis=-1), 8000.0 * np.linalg.norm(rel_all, axis=-1))


def test_force_on_fluid_is_minus_blade_force():
    """Σ fz on the fluid = −thrust; the in-plane force on the fluid points along the blade motion."""
    src = rotor_sources(_disk(), _motion(), rho0_kg_m3=1.2, c0_mps=340.0)
    loading = src.dipole_group == 0
    assert np.allclose(src.force_N[loading, :, 2].sum(axis=0), -3 * 500.0)
    motion_dir = src.velocity_mps[loading] / np.linalg.norm(src.velocity_mps[loading], axis=-1, keepdims=True)
    assert np.allclose(np.einsum("ntk,ntk->nt", src.force_N[loading], motion_dir), 30.0)


def test_dual_compact_lines():
    """Lines 0.12 c ahead / 0.62 c behind the pitch axis; force on the fluid ±ρ0 (A/D)(v·e_c) v dr with v each line's
    own velocity relative to the air (rotation + flight speed 10 m/s), A = 0.685 t c, D = 0.74 c; the force rate is
    the time derivative of the force (periodic 6th-order check to 1e-6 of the force scale).

    In hover the pair's net force is −ρ0 (A/D) Ω² r D dr e_r (radial only; none along the chord).
    """
    rho0, c0 = 1.2, 340.0
    src = rotor_sources(_disk(), _motion(speed=10.0), rho0_kg_m3=rho0, c0_mps=c0)
    thick = np.nonzero(src.dipole_group == 1)[0]
    front, rear = thick[:3], thick[3:]
    rotation = src.velocity_mps[:3] - [10.0, 0.0, 0.0]
    e_c = rotation / np.linalg.norm(rotation, axis=-1, keepdims=True)  # chord direction toward the leading edge (θ = 0)
    ahead = np.einsum("ntk,ntk->nt", src.position_m[front] - src.position_m[:3], e_c)
    behind = np.einsum("ntk,ntk->nt", src.position_m[rear] - src.position_m[:3], e_c)
    assert np.allclose(ahead, 0.12 * 0.5) and np.allclose(behind, -0.62 * 0.5)
    strength = rho0 * 0.685 * 0.05 * 0.5 / (0.74 * 0.5) * 1.0
    for nodes, sign in ((front, 1.0), (rear, -1.0)):
        v = src.velocity_mps[nodes]
        assert np.allclose(src.force_N[nodes], sign * strength * np.einsum("ntk,ntk->nt", v, e_c)[..., None] * v, rtol=1e-12)
        dt = src.time_s[1] - src.time_s[0]
        numeric = sum(w * (np.roll(src.force_N[nodes], -k, axis=1) - np.roll(src.force_N[nodes], k, axis=1))
                      for k, w in ((1, 3 / 4), (2, -3 / 20), (3, 1 / 60))) / dt
        assert np.abs(numeric - src.force_rate_N_s[nodes]).max() < 1e-6 * np.abs(src.force_rate_N_s[nodes]).max()
    hover = rotor_sources(_disk(), _motion(), rho0_kg_m3=rho0, c0_mps=c0)
    net = hover.force_N[front] + hover.force_N[rear]
    r = np.array([2.0, 3.0, 4.0])[:, None, None]
    radial = (hover.position_m[:3] - [0.0, 0.0, 2.0]) / r
    assert np.allclose(net, -strength * 20.0**2 * r * 0.74 * 0.5 * radial, rtol=1e-9, atol=1e-9)
    mono = rotor_sources(_disk(), _motion(), rho0_kg_m3=rho0, c0_mps=c0, thickness=ThicknessModel(kind="compact_monopole"))
    assert np.allclose(mono.volume_m3, 0.685 * 0.05 * 0.5)


def test_thickness_model_and_speed_errors():
    with pytest.raises(AcousticsError, match="area_factor"):
        ThicknessModel(area_factor=0.0)
    with pytest.raises(AcousticsError, match="chord_fractions"):
        ThicknessModel(chord_fractions=(0.9, 0.1))
    with pytest.raises(AcousticsError, match="subsonic"):
        rotor_sources(_disk(), _motion(), rho0_kg_m3=1.2, c0_mps=70.0)  # tip speed 80 m/s


def test_flapping_velocity_matches_analytic():
    """β = 0.1 cos ψ: vertical velocity of the tip node = −0.1 Ω r sin ψ · cos β (6th-order ψ differences)."""
    src = rotor_sources(_disk(n_psi=180, beta=lambda p: 0.1 * np.cos(p)), _motion(), rho0_kg_m3=1.2, c0_mps=340.0)
    psi = 20.0 * src.time_s
    beta = 0.1 * np.cos(psi)
    assert np.allclose(src.position_m[2, :, 2] - 2.0, 4.0 * np.sin(beta))
    assert np.allclose(src.velocity_mps[2, :, 2], 4.0 * np.cos(beta) * (-0.1 * 20.0 * np.sin(psi)), rtol=0, atol=1e-6)


def test_periodic_dpsi_order():
    psi = 2 * np.pi * np.arange(90) / 90
    assert np.abs(periodic_dpsi(np.sin(3 * psi), psi[1]) - 3 * np.cos(3 * psi)).max() < 3e-6  # 6th order: (3Δψ)^6/140·3 ≈ 1.9e-6


def test_bad_disk_tables():
    with pytest.raises(AcousticsError, match="missing column"):
        rotor_sources(_disk().drop(columns="fz_N_per_m"), _motion(), rho0_kg_m3=1.2, c0_mps=340.0)
    bad = _disk()
    bad.loc[5, "fx_N_per_m"] = np.nan
    with pytest.raises(AcousticsError, match="fx_N_per_m"):
        rotor_sources(bad, _motion(), rho0_kg_m3=1.2, c0_mps=340.0)
    with pytest.raises(AcousticsError, match="divisible"):
        rotor_sources(_disk(n_psi=70), _motion(), rho0_kg_m3=1.2, c0_mps=340.0, tau_range_s=(0.0, 0.1))
