"""Root finders (nps.core.solvers): roots of known functions, convergence orders, tolerance semantics, failures."""

import math

import numpy as np
import pytest

from nps.core.solvers import (ConvergenceError, forward_difference_jacobian, limited_secant, newton, newton_fd,
                              secant)

SQRT2 = math.sqrt(2.0)


def _newton_errors(x0: float, max_iter: int) -> list[float]:
    """|x_k − √2| of newton_fd on x² − 2 = 0 after k = 1 … max_iter updates (each run stopped by max_iter)."""
    errors = []
    for n in range(1, max_iter + 1):
        with pytest.raises(ConvergenceError) as failure:
            newton_fd(lambda x: (x * x - 2.0, None), [x0], steps=[1e-8], tol=0.0, max_iter=n, what="sqrt2")
        errors.append(abs(failure.value.x[0] - SQRT2))
    return errors


def test_forward_difference_jacobian_of_a_linear_map_and_selected_columns():
    a = np.array([[2.0, -1.0, 0.5], [0.0, 3.0, 4.0]])
    x = np.array([0.3, -0.2, 1.0])
    jac = forward_difference_jacobian(lambda v: a @ v, x, a @ x, [1e-6, 1e-6, 1e-6])
    assert np.allclose(jac, a, atol=1e-8)
    assert np.allclose(forward_difference_jacobian(lambda v: a @ v, x, a @ x, [1e-6, 1e-6], columns=(2, 0)),
                       a[:, [2, 0]], atol=1e-8)


def test_newton_fd_finds_the_root_of_a_nonlinear_system():
    """x² + y² = 4, x = y: (√2, √2); the payload of the converged evaluation is returned."""
    def residual(v):
        return np.array([v[0] ** 2 + v[1] ** 2 - 4.0, v[0] - v[1]]), "payload"

    solution = newton_fd(residual, [1.0, 0.5], steps=[1e-8, 1e-8], tol=1e-12, max_iter=30, what="circle")
    assert np.allclose(solution.x, [SQRT2, SQRT2], rtol=0.0, atol=1e-12)
    assert np.max(np.abs(solution.residual)) < 1e-12 and solution.payload == "payload"
    assert 3 <= solution.iterations < 30


def test_newton_fd_converges_quadratically():
    """e_{k+1} ≈ C e_k² with C = f''/(2 f') = 1/(2√2) for x² − 2 (the difference step adds only O(h e_k))."""
    errors = _newton_errors(1.0, 4)
    assert all(b < a for a, b in zip(errors, errors[1:]))
    for a, b in zip(errors[1:], errors[2:]):
        assert b / a**2 == pytest.approx(1.0 / (2.0 * SQRT2), rel=0.05)


def test_newton_fd_tolerance_is_a_strict_bound_on_the_residual():
    """Converged means max |F| < tol, tested before the update: a start exactly at the root with tol = 0
    is not converged; with tol above its residual it returns it without an update."""
    with pytest.raises(ConvergenceError):
        newton_fd(lambda x: (x - 1.0, None), [1.0], steps=[1e-6], tol=0.0, max_iter=3, what="strict")
    solution = newton_fd(lambda x: (x - 1.0, None), [1.25], steps=[1e-6], tol=0.3, max_iter=3, what="loose")
    assert solution.iterations == 0 and solution.x[0] == 1.25


def test_newton_fd_minimum_norm_step_and_held_unknowns():
    """One equation x + y = 2 in two unknowns: the pseudo-inverse step from 0 is the minimum-norm (1, 1).
    With columns=(0,), y is held."""
    solution = newton_fd(lambda v: (np.array([v[0] + v[1] - 2.0]), None), [0.0, 0.0], steps=[1e-6, 1e-6],
                         tol=1e-9, max_iter=5, what="underdetermined", rcond=1e-12)
    assert np.allclose(solution.x, [1.0, 1.0], atol=1e-9)
    held = newton_fd(lambda v: (np.array([v[0] + v[1] - 2.0]), None), [0.0, 0.5], steps=[1e-6], tol=1e-9,
                     max_iter=5, what="held", columns=(0,))
    assert held.x[1] == 0.5 and held.x[0] == pytest.approx(1.5, abs=1e-9)


def test_newton_fd_chord_method_keeps_the_jacobian_and_the_step_limit_applies():
    """A given Jacobian is kept while the residual falls fast enough (no difference evaluation); the step
    limiter shortens every update."""
    calls = []

    def residual(v):
        calls.append(v.copy())
        return np.array([3.0 * (v[0] - 1.0)]), None

    solution = newton_fd(residual, [0.0], steps=[1e-6], tol=1e-12, max_iter=10, what="chord",
                         jacobian=np.array([[3.0]]), refresh_ratio=0.2)
    assert solution.x[0] == 1.0 and len(calls) == 2
    halved = newton_fd(lambda v: (v - 1.0, None), [0.0], steps=[1e-6], tol=1e-3, max_iter=20, what="halved",
                       limit_step=lambda x, dx: 0.5 * dx)
    assert abs(halved.x[0] - 1.0) < 1e-3 and halved.iterations == 10


def test_newton_fd_failure_names_what_and_carries_the_last_state():
    with pytest.raises(ConvergenceError, match=r"no real root: max \|residual\| .* after 7 Newton updates") as failure:
        newton_fd(lambda x: (x * x + 1.0, None), [0.5], steps=[1e-7], tol=1e-12, max_iter=7, what="no real root")
    assert failure.value.iterations == 7 and failure.value.value[0] >= 1.0 and failure.value.jacobian is not None
    with pytest.raises(ConvergenceError, match="not finite"):
        newton_fd(lambda x: (np.sqrt(x - 2.0) if x[0] >= 2.0 else np.array([np.nan]), None), [1.0], steps=[1e-7], tol=1e-12, max_iter=7, what="log")


def test_scalar_newton_root_quadratic_order_and_floor():
    """√2 from x² − 2 with the analytic derivative; the error squares each step; min_ratio bounds the shrink."""
    root = newton(lambda x: (x * x - 2.0, 2.0 * x), 1.0, tol=1e-15, max_iter=20, what="sqrt2")
    assert root == pytest.approx(SQRT2, abs=1e-15)
    with pytest.raises(ConvergenceError, match="sqrt2: Newton step .* after 3 updates"):
        newton(lambda x: (x * x - 2.0, 2.0 * x), 1.0, tol=0.0, max_iter=3, what="sqrt2")
    errors = [_scalar_newton_error(n) for n in range(1, 5)]
    for a, b in zip(errors[1:], errors[2:]):
        assert b / a**2 == pytest.approx(1.0 / (2.0 * SQRT2), rel=0.05)
    # f = x − 10 from 100: the full step would go to 10, the floor stops it at 50 (then 25, 12.5, 10)
    assert newton(lambda x: (x - 10.0, 1.0), 100.0, tol=np.inf, max_iter=1, what="floor", min_ratio=0.5) == 50.0
    assert newton(lambda x: (x - 10.0, 1.0), 100.0, tol=1e-12, max_iter=10, what="floor", min_ratio=0.5) == 10.0


def _scalar_newton_error(n: int) -> float:
    x = 1.0
    for _ in range(n):
        x = newton(lambda v: (v * v - 2.0, 2.0 * v), x, tol=np.inf, max_iter=1, what="")
    return abs(x - SQRT2)


def test_secant_root_and_order_golden_ratio():
    """Root of x³ − 2 (2^{1/3}); the errors follow e_{k+1} ≈ C e_k^φ, φ = (1 + √5)/2 ≈ 1.618."""
    f = lambda x: x**3 - 2.0  # noqa: E731
    exact = 2.0 ** (1.0 / 3.0)
    root = secant(f, 1.0, f(1.0), 1.5, target=0.0, tol=1e-14, max_iter=30, what="cube root")
    assert root.x == pytest.approx(exact, abs=1e-14) and root.value == root.payload
    errors = []
    for n in range(1, 7):
        with pytest.raises(ConvergenceError) as failure:
            secant(f, 1.0, f(1.0), 1.5, target=0.0, tol=0.0, max_iter=n, what="cube root")
        errors.append(abs(failure.value.x - exact))
    orders = [math.log(c / b) / math.log(b / a) for a, b, c in zip(errors, errors[1:], errors[2:])]
    assert orders[-1] == pytest.approx((1.0 + math.sqrt(5.0)) / 2.0, abs=0.15)


def test_secant_target_value_and_tolerance_semantics():
    """f(x) = target with |f − target| ≤ tol (inclusive) on an evaluated iterate; ``value`` reads f from the
    payload."""
    evaluate = lambda x: {"thrust": 2.0 * x}  # noqa: E731
    root = secant(evaluate, 0.0, evaluate(0.0), 1.0, target=3.0, tol=0.0, max_iter=5, what="linear",
                  value=lambda p: p["thrust"])
    assert root.x == 1.5 and root.payload == {"thrust": 3.0}
    exact = secant(evaluate, 0.0, evaluate(0.0), 1.25, target=3.0, tol=0.5, max_iter=1, what="inclusive",
                   value=lambda p: p["thrust"])
    assert exact.x == 1.25  # |2.5 − 3| = 0.5 ≤ tol


def test_secant_failures_name_what():
    with pytest.raises(ConvergenceError, match=r"flat: \|f − target\| 1 not within 0.001 after 1 secant evaluations"):
        secant(lambda x: 1.0, 0.0, 1.0, 1.0, target=0.0, tol=1e-3, max_iter=30, what="flat")
    with pytest.raises(ConvergenceError, match="after 4 secant evaluations") as failure:
        secant(lambda x: x * x + 1.0, 0.3, 1.09, 1.0, target=0.0, tol=1e-3, max_iter=4, what="no root")
    assert failure.value.value >= 1.0


def test_limited_secant_steps_bounds_and_slope_memory():
    """r(u) = 2u − 1 from u = 0 with slope 2: one step lands on the root; steps are clipped to max_step; a
    move returning None stops; an inconsistent slope estimate is not kept."""
    state = {"u": 0.0, "moves": 0}

    def move(du, f=lambda u: 2.0 * u - 1.0):
        state["u"] += du
        state["moves"] += 1
        return f(state["u"])

    assert limited_secant(move, -1.0, 2.0, tol=1e-12, max_iter=10, max_step=1.0, keep_ratio=0.05) == 2.0
    assert state == {"u": 0.5, "moves": 1}
    state.update(u=0.0, moves=0)
    limited_secant(move, -1.0, 2.0, tol=1e-12, max_iter=10, max_step=0.1, keep_ratio=0.05)
    assert state["moves"] == 5 and state["u"] == pytest.approx(0.5, abs=1e-12)
    assert limited_secant(lambda du: None, -1.0, 2.0, tol=1e-12, max_iter=10, max_step=1.0, keep_ratio=0.05) == 2.0
    # r(u) = −u − 1 has the opposite slope sign: the estimate −1 is refused, the slope 2 kept
    state.update(u=0.0, moves=0)
    slope = limited_secant(lambda du: move(du, lambda u: -u - 1.0), -1.0, 2.0, tol=1e-12, max_iter=3, max_step=1.0,
                           keep_ratio=0.05)
    assert slope == 2.0 and state["moves"] == 3
    # tolerance inclusive: |r| ≤ tol needs no move
    assert limited_secant(lambda du: pytest.fail("moved"), 0.5, 2.0, tol=0.5, max_iter=3, max_step=1.0,
                          keep_ratio=0.05) == 2.0
