"""Root finders of the trims: Newton's method (forward-difference or analytic derivative) and the secant method.

Every trim of NPS solves through these functions: :func:`newton_fd` the aircraft balance
(:mod:`nps.rotor.trim`) and the rotor's inflow and flapping (:mod:`nps.rotor.bet`),
:func:`newton` Glauert's induced inflow, :func:`limited_secant` the rotor trim's control steps
and :func:`secant` the one-control trims (:mod:`nps.rotor.control`). The callers name their
tolerances next to the call (module constants); here each function states what its ``tol``
bounds, in the units of the residual or of the unknown.

Why not scipy.optimize: its iterations (``root``'s hybrid and Levenberg–Marquardt steps, the
secant and bracketing updates of ``newton``/``brentq``) differ from these in update formula,
stopping test or order of floating-point operations, so every converged value would move in its
last bits and every artifact digest with it. These functions are the iterations NPS has always
run, written once: the results stay bit-identical.

A finder that does not converge raises :class:`ConvergenceError`, which carries the last
iterate; callers re-raise it as their own error naming what did not converge.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Sequence

import numpy as np


class ConvergenceError(RuntimeError):
    """A root finder stopped without converging.

    ``x`` the last iterate, ``value`` the function's value at the last evaluated iterate (the
    residual for Newton, f(x) for the secant), ``iterations`` the updates made, ``jacobian`` the
    last Jacobian (:func:`newton_fd`, else None).
    """

    def __init__(self, message: str, x, value, iterations: int, jacobian: np.ndarray | None = None):
        super().__init__(message)
        self.x, self.value, self.iterations, self.jacobian = x, value, iterations, jacobian


@dataclass(frozen=True)
class NewtonResult:
    """Converged :func:`newton_fd`: root ``x``, its ``residual`` and ``payload`` (what the residual
    function returned with it), ``iterations`` Newton updates made (evaluations − 1), and the last
    ``jacobian`` (to warm-start the next solve)."""

    x: np.ndarray
    residual: np.ndarray
    payload: Any
    iterations: int
    jacobian: np.ndarray | None


def forward_difference_jacobian(residual: Callable[[np.ndarray], np.ndarray], x: np.ndarray, r0: np.ndarray,
                                steps: Sequence[float], columns: Sequence[int] | None = None) -> np.ndarray:
    """J[:, k] = (F(x + h_k e_j) − F(x)) / h_k for the unknowns j = ``columns``[k] (default 0, 1, …).

    ``r0`` = F(x); ``steps`` h_k in the units of x_j. One evaluation of F per column.
    """
    columns = range(len(steps)) if columns is None else columns
    jac = np.empty((np.size(r0), len(steps)))
    for k, (j, h) in enumerate(zip(columns, steps)):
        shifted = x.copy()
        shifted[j] += h
        jac[:, k] = (residual(shifted) - r0) / h
    return jac


def newton_fd(residual: Callable[[np.ndarray], tuple[np.ndarray, Any]], x0, *, steps, tol: float, max_iter: int,
              what: str, columns: Sequence[int] | None = None, rcond: float | None = None,
              jacobian: np.ndarray | None = None, refresh_ratio: float | None = None,
              limit_step: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None) -> NewtonResult:
    """Newton's method for F(x) = 0 with a forward-difference Jacobian.

    ``residual(x)`` returns (F(x), payload). Converged when max_i |F_i(x)| < ``tol`` (units of F),
    tested before each update; at most ``max_iter`` updates. Update: Δx = −J⁻¹ F with
    ``np.linalg.solve`` (``rcond`` None, square J) or Δx = −J⁺ F, the minimum-norm least-squares
    step of the pseudo-inverse with singular values below ``rcond`` σ_max dropped; then
    ``limit_step(x, Δx)`` may shorten it and x ← x + Δx.

    Only the unknowns x[``columns``] are solved (default all; F has one component per unknown
    solved unless ``rcond`` is given); ``steps(x)`` gives their difference steps h (units of x),
    or ``steps`` is that sequence. ``refresh_ratio`` None recomputes J at every update; a number
    r keeps J (chord method, starting from ``jacobian`` when given) while each max |F| is at most
    r times the previous one. Raises :class:`ConvergenceError` naming ``what`` when F is not
    finite or after ``max_iter`` updates.
    """
    x = np.array(x0, dtype=float)
    previous = np.inf
    for iteration in range(max_iter):
        r, payload = residual(x)
        norm = float(np.max(np.abs(r)))
        if not math.isfinite(norm):
            raise ConvergenceError(f"{what}: residual not finite after {iteration} Newton updates", x, r, iteration,
                                   jacobian)
        if norm < tol:
            return NewtonResult(x, r, payload, iteration, jacobian)
        if jacobian is None or refresh_ratio is None or norm > refresh_ratio * previous:
            h = steps(x) if callable(steps) else steps
            jacobian = forward_difference_jacobian(lambda v: residual(v)[0], x, r, h, columns)
        previous = norm
        step = np.linalg.solve(jacobian, -r) if rcond is None else -(np.linalg.pinv(jacobian, rcond=rcond) @ r)
        if columns is not None:
            dx = np.zeros(x.size)
            dx[np.asarray(columns)] = step
            step = dx
        if limit_step is not None:
            step = limit_step(x, step)
        x = x + step
    raise ConvergenceError(f"{what}: max |residual| {norm:.3g} not below {tol:.3g} after {max_iter} Newton updates",
                           x, r, max_iter, jacobian)


def newton(value_and_slope: Callable[[float], tuple[float, float]], x0: float, *, tol: float, max_iter: int,
           what: str, min_ratio: float = 0.0) -> float:
    """Newton's method for a scalar f(x) = 0 with the analytic derivative: ``value_and_slope(x)`` = (f, f').

    Update x ← max(x − f/f', ``min_ratio`` x) (a positive root stays positive when min_ratio > 0:
    each step shrinks x at most to that fraction). Converged when the update |f/f'| < ``tol``
    (units of x); returns the updated x. Raises :class:`ConvergenceError` naming ``what`` after
    ``max_iter`` updates.
    """
    x = x0
    for _ in range(max_iter):
        value, slope = value_and_slope(x)
        step = value / slope
        x = max(x - step, min_ratio * x)
        if abs(step) < tol:
            return x
    raise ConvergenceError(f"{what}: Newton step {step:.3g} not below {tol:.3g} after {max_iter} updates", x, value,
                           max_iter)


@dataclass(frozen=True)
class SecantRoot:
    """Converged :func:`secant`: ``x``, ``payload`` what ``evaluate(x)`` returned, ``value`` f(x)."""

    x: float
    payload: Any
    value: float


def secant(evaluate: Callable[[float], Any], x0: float, first: Any, x1: float, *, target: float, tol: float,
           max_iter: int, what: str, value: Callable[[Any], float] = float) -> SecantRoot:
    """Secant method for f(x) = ``target`` from x0 (evaluated: ``first``) and x1.

    f(x) = ``value(evaluate(x))``. x₂ = x₁ − (f₁ − target)(x₁ − x₀)/(f₁ − f₀). Converged when
    |f(x) − target| ≤ ``tol`` (units of f), tested on every evaluation; at most ``max_iter``
    evaluations. Raises :class:`ConvergenceError` naming ``what`` (``x`` the last iterate, ``value``
    the last f) after them, when f₁ = f₀ or when the update is not finite.
    """
    y0 = value(first)
    for iteration in range(max_iter):
        payload = evaluate(x1)
        y1 = value(payload)
        if abs(y1 - target) <= tol:
            return SecantRoot(x1, payload, y1)
        if y1 == y0:
            break
        x0, x1, y0 = x1, x1 - (y1 - target) * (x1 - x0) / (y1 - y0), y1
        if not math.isfinite(x1):
            break
    raise ConvergenceError(f"{what}: |f − target| {abs(y1 - target):.3g} not within {tol:.3g} after "
                           f"{iteration + 1} secant evaluations", x1, y1, iteration + 1)


def limited_secant(move: Callable[[float], float | None], residual: float, slope: float, *, tol: float,
                   max_iter: int, max_step: float, keep_ratio: float) -> float:
    """Step-limited secant iteration of a scalar residual r(u) = 0 that keeps its slope estimate s.

    From the current point (u = 0, residual ``residual``, slope ``slope``): Δu = clip(−r/s,
    ±``max_step``); ``move(Δu)`` moves there and returns the new residual r', or None when the
    move changes nothing (then the iteration stops). s ← (r' − r)/Δu only when that estimate is
    finite, has the sign of s and |·| > ``keep_ratio`` |s| (a bounded or noisy move keeps the old
    slope). Stops when |r| ≤ ``tol`` (units of r) or after ``max_iter`` moves, without raising
    (the caller judges the residual); returns the slope to start the next iteration with.
    """
    for _ in range(max_iter):
        if abs(residual) <= tol:
            break
        du = float(np.clip(-residual / slope, -max_step, max_step))
        new = move(du)
        if new is None:
            break
        new_slope = (new - residual) / du
        if math.isfinite(new_slope) and new_slope * slope > 0.0 and abs(new_slope) > keep_ratio * abs(slope):
            slope = new_slope
        residual = new
    return slope
