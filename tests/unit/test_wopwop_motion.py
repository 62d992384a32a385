"""CB kinematics: closed forms, analytic derivatives against high-order finite differences, chain order."""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from nps.wopwop.case import CB
from nps.wopwop.motion import (FrameMotion, angle_series, apply, cb_motion, chain_motion, compose, identity,
                               rotate_vectors, translation_series)

H_S = 2e-3       # finite-difference step (s)
OFFSETS = np.arange(-5, 6)  # 11-point central stencils: order 10 (1st, 2nd derivative), order 8 (3rd)
FD_RTOL = 1e-8   # |analytic - FD| <= FD_RTOL * max|analytic of that order| (truncation ~ (Omega h)^8 ~ 1e-10)

SPIN = CB(title="spin", rotation=True, angle_type="KnownFunction", axis_value=(0.0, 0.0, 1.0), omega_rad_s=31.4,
          psi0_rad=0.4)
TILT = CB(title="tilt", angle_type="TimeIndependent", axis_value=(0.0, 1.0, 0.0), angle_value=-0.1)
FLAP = CB(title="flap", angle_type="Periodic", axis_value=(1.0, 0.2, 0.0), omega_rad_s=31.4, psi0_rad=0.4, a0=0.05,
          a=(-0.02, 0.01), b=(0.03, -0.004))
PITCH = CB(title="pitch", angle_type="TimeIndependent", axis_value=(0.0, 1.0, 0.0), angle_value=0.2)
HOLD = CB(title="hub offset", translation_type="TimeIndependent", translation_value=(0.3, -0.1, 1.2))
FLIGHT = CB(title="flight", translation_type="KnownFunction", y0=(5.0, 0.0, 100.0), vh=(-20.0, 1.0, 0.5),
            ah=(2.0, -0.5, 0.1))
BOTH = CB(title="both", angle_type="KnownFunction", axis_value=(1.0, 1.0, 1.0), omega_rad_s=-12.0, psi0_rad=0.1,
          translation_type="KnownFunction", vh=(0.0, 3.0, 0.0), ah=(1.0, 0.0, 0.0))
POINTS = np.array([[4.0, 0.0, 0.0], [1.0, 0.3, -0.02], [0.0, 0.0, 0.0]])


def _fd_weights(order: int) -> np.ndarray:
    """Central finite-difference weights of ``order`` on OFFSETS (unit step): the Taylor conditions
    sum_k w_k k^m = m! [m == order], m = 0..10, solved exactly in rationals."""
    n = OFFSETS.size
    rows = [[Fraction(int(k) ** m) for k in OFFSETS] + [Fraction(math.factorial(order) if m == order else 0)]
            for m in range(n)]
    for col in range(n):  # Gauss-Jordan elimination, exact
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        rows[col] = [v / rows[col][col] for v in rows[col]]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                rows[r] = [a - rows[r][col] * b for a, b in zip(rows[r], rows[col])]
    return np.array([float(row[-1]) for row in rows])


def _fd(positions, t0: float, order: int) -> np.ndarray:
    """d^order/dt^order of positions(t) at t0 by finite differences of the positions themselves."""
    samples = np.stack([positions(t0 + k * H_S) for k in OFFSETS])
    return np.tensordot(_fd_weights(order), samples, axes=1) / H_S**order


def _check_rates(series, positions, t0: float) -> None:
    """Orders 1..3 of an analytic series at t0 against finite differences of its order-0 values. Tolerance:
    FD_RTOL of the largest value of that order (truncation) plus the rounding of the samples,
    64 eps max|x| sum|w| / h^order."""
    x_max = np.max(np.abs(series[0]))
    for order in (1, 2, 3):
        rounding = 64 * np.finfo(float).eps * x_max * np.sum(np.abs(_fd_weights(order))) / H_S**order
        tolerance = FD_RTOL * max(np.max(np.abs(series[order])), 1.0) + rounding
        assert np.max(np.abs(series[order] - _fd(positions, t0, order))) <= tolerance, order


def test_known_function_rotation_closed_form():
    """About +z at Omega t + Psi0: position, velocity, acceleration and jerk of a point at radius r, height h."""
    t = np.linspace(-0.3, 0.7, 9)
    theta, w, r, h = SPIN.omega_rad_s * t + SPIN.psi0_rad, SPIN.omega_rad_s, 2.5, 0.4
    kin = apply(cb_motion(SPIN, t), np.array([[r, 0.0, h]]))[:, :, 0]
    c, s, z = np.cos(theta), np.sin(theta), np.zeros_like(t)
    expected = [np.c_[r * c, r * s, z + h], r * w * np.c_[-s, c, z], -r * w**2 * np.c_[c, s, z],
                r * w**3 * np.c_[s, -c, z]]
    for order in range(4):
        np.testing.assert_allclose(kin[order], expected[order], rtol=0, atol=1e-12 * r * abs(w) ** order)


def test_rotation_about_a_tilted_axis_is_rodrigues():
    """Active right-handed rotation about the unit AxisValue (scipy's rotation vector θ u as the reference)."""
    t = np.array([0.0, 0.05, 0.11])
    rotation = cb_motion(BOTH, t).rotation[0]
    u = np.array(BOTH.axis_value) / np.sqrt(3.0)
    reference = Rotation.from_rotvec(np.outer(BOTH.omega_rad_s * t + BOTH.psi0_rad, u)).as_matrix()
    np.testing.assert_allclose(rotation, reference, rtol=0, atol=1e-14)


def test_periodic_angle_closed_form():
    """θ = A0 + A1 cos ψ + B1 sin ψ + A2 cos 2ψ + B2 sin 2ψ, ψ = Omega t + Psi0 (the unconfirmed sign reading)."""
    t = np.linspace(0.0, 0.2, 7)
    psi = FLAP.omega_rad_s * t + FLAP.psi0_rad
    expected = (0.05 - 0.02 * np.cos(psi) + 0.03 * np.sin(psi) + 0.01 * np.cos(2 * psi) - 0.004 * np.sin(2 * psi))
    np.testing.assert_allclose(angle_series(FLAP, t)[0], expected, rtol=0, atol=1e-15)


@pytest.mark.parametrize("cb", [SPIN, TILT, FLAP, PITCH, HOLD, FLIGHT, BOTH], ids=lambda cb: cb.title)
def test_every_cb_kind_rates_match_finite_differences(cb):
    t0 = 0.137
    series = apply(cb_motion(cb, [t0]), POINTS)[:, 0]
    _check_rates(series, lambda t: apply(cb_motion(cb, [t]), POINTS)[0, 0], t0)
    _check_rates(angle_series(cb, [t0])[:, :, None], lambda t: angle_series(cb, [t])[0][:, None], t0)
    _check_rates(translation_series(cb, [t0]), lambda t: translation_series(cb, [t])[0], t0)


def test_composed_chain_rates_match_finite_differences():
    """Aircraft flight, disk tilt, rotor spin, hub offset, Periodic flap, pitch: positions, rates and the rotated
    vectors of the whole chain."""
    chain = [FLIGHT, TILT, SPIN, HOLD, FLAP, PITCH]
    t0 = 0.0421
    series = apply(chain_motion(chain, [t0]), POINTS)[:, 0]
    _check_rates(series, lambda t: apply(chain_motion(chain, [t]), POINTS)[0, 0], t0)
    vectors = rotate_vectors(chain_motion(chain, [t0]), POINTS)[:, 0]
    _check_rates(vectors, lambda t: rotate_vectors(chain_motion(chain, [t]), POINTS)[0, 0], t0)


def test_moving_points_and_vectors():
    """Points and vectors moving in the local frame: Leibniz's rule, against finite differences of R x(t) + T."""
    chain = [FLIGHT, SPIN, FLAP]

    def local(t):
        return np.array([[1.0 + 0.1 * np.sin(3 * t), 0.2 * t**2, 0.05 * np.cos(5 * t)]])

    def local_series(t):  # x, x', x'', x''' of ``local``
        return np.array([local(t)[0], [0.3 * np.cos(3 * t), 0.4 * t, -0.25 * np.sin(5 * t)],
                         [-0.9 * np.sin(3 * t), 0.4, -1.25 * np.cos(5 * t)],
                         [-2.7 * np.cos(3 * t), 0.0, 6.25 * np.sin(5 * t)]])[:, None, None, :]

    t0 = 0.3
    series = apply(chain_motion(chain, [t0]), None, local_series(t0))[:, 0]
    _check_rates(series, lambda t: apply(chain_motion(chain, [t]), local(t))[0, 0], t0)
    rotated = rotate_vectors(chain_motion(chain, [t0]), local_series(t0)[0], local_series(t0)[1])
    assert rotated.shape == (2, 1, 1, 3)
    np.testing.assert_allclose(rotated, series[:2, None] - apply(chain_motion(chain, [t0]), np.zeros((1, 3)))[:2, :1],
                               rtol=0, atol=1e-12)


def test_chain_order_first_cb_applied_last():
    """Rotate 90° about z and translate by (1, 0, 0): [rotate, translate] maps the origin to R(0 + T) = (0, 1, 0);
    [translate, rotate] maps it to R 0 + T = (1, 0, 0); a point (0, 2, 0): (-2, 1, 0) and (-1, 0, 0)."""
    quarter = CB(title="quarter", angle_type="TimeIndependent", axis_value=(0.0, 0.0, 1.0), angle_value=math.pi / 2)
    shift = CB(title="shift", translation_type="TimeIndependent", translation_value=(1.0, 0.0, 0.0))
    points = np.array([[0.0, 0.0, 0.0], [0.0, 2.0, 0.0]])
    np.testing.assert_allclose(apply(chain_motion([quarter, shift], [0.0]), points)[0, 0],
                               [[0.0, 1.0, 0.0], [-2.0, 1.0, 0.0]], atol=1e-15)
    np.testing.assert_allclose(apply(chain_motion([shift, quarter], [0.0]), points)[0, 0],
                               [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]], atol=1e-15)
    both = CB(title="both", angle_type="TimeIndependent", axis_value=(0.0, 0.0, 1.0), angle_value=math.pi / 2,
              translation_type="TimeIndependent", translation_value=(1.0, 0.0, 0.0))
    np.testing.assert_allclose(apply(cb_motion(both, [0.0]), points)[0, 0], [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]],
                               atol=1e-15)  # one CB: rotate, then translate


def test_compose_and_identity():
    t = np.linspace(0.0, 0.1, 4)
    empty = chain_motion([], t)
    assert np.array_equal(empty.rotation, identity(4).rotation) and not empty.translation.any()
    outer, inner = cb_motion(FLIGHT, t), cb_motion(BOTH, t)
    both = compose(outer, inner)
    np.testing.assert_allclose(both.rotation[0], outer.rotation[0] @ inner.rotation[0], atol=1e-15)
    np.testing.assert_allclose(both.translation[0], np.einsum("tij,tj->ti", outer.rotation[0], inner.translation[0])
                               + outer.translation[0], atol=1e-12)
    assert isinstance(both, FrameMotion)


@pytest.mark.parametrize("cb", [CB(title="np", angle_type="NonPeriodic", axis_value=(0, 0, 1.0)),
                                CB(title="wf", windframe=True),
                                CB(title="pt", translation_type="Periodic")], ids=lambda cb: cb.title)
def test_unsupported_cbs_raise(cb):
    with pytest.raises(ValueError, match=f"&CB '{cb.title}': .* is not supported"):
        cb_motion(cb, [0.0])
