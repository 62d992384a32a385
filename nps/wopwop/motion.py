"""Change-of-base (``&CB``) kinematics: positions, velocities, accelerations and jerks of a CB chain, analytic.

A CB maps its local frame to its parent frame, x_parent = R(t) x_local + T(t), t the source time (s):

- **Rotation** (an AngleType given): active and right-handed about the unit vector of AxisValue (Rodrigues:
  R = I + sinθ K + (1 − cosθ) K², K the cross-product matrix of the unit axis), angle θ(t) in rad:
  TimeIndependent θ = AngleValue; KnownFunction θ = Omega t + Psi0; Periodic, with ψ = Omega t + Psi0,
  θ = A0 + Σ_n (A_n cos nψ + B_n sin nψ), n = 1, 2, ... (A1, A2 or A(n); B likewise).
- **Translation** (a TranslationType given): TimeIndependent T = TranslationValue; KnownFunction
  T = Y0 + VH t + AH t²/2.
- A CB with both: rotate, then translate (T is the position of the local origin in the parent frame).
- A **chain** (a container's CB list, ancestors first): the first CB listed is applied last,
  x_parent = CB1(CB2(…CBn(x_local))).

Sources and how sure: PSU-WOPWOP's COB.f90 (the CB module) was not readable in the public index, so the
formulas above are the documented conventions of /work/shared/psu-wopwop-formats.md and of the public case
writers, not a reading of COB.f90. The chain order is confirmed by container.f90 CreateContainer (a child's list
is its parent's list with its own CBs appended) together with the writers' physical order
(DanWeitsman/VSP2WOPWOP Model360.nam, PsuAeroacoustics/OpenCOPTER case.nam list aircraft motion, disk tilt, shaft
rotation, blade azimuth offset, pitch: the pitch acts on the blade first, the aircraft motion last). The active
right-handed sign agrees with VSP2WOPWOP placing blade k at AngleValue = +kπ/2 with periodicKeyOffset = +kπ/2 for
Omega > 0. **Unconfirmed readings**: the Periodic series (ψ = Omega t + Psi0 and the plus signs of A_n cos nψ +
B_n sin nψ), the KnownFunction translation Y0 + VH t + AH t²/2, and rotate-then-translate inside one CB.
NonPeriodic data files, Periodic translations and wind-frame CBs are refused (:mod:`nps.wopwop.case` refuses them
with the file and line; here a ValueError names the CB).

Every quantity carries orders 0..3 along its first axis (value, d/dt, d²/dt², d³/dt³), derived analytically
(Leibniz's rule for products, Faà di Bruno for R(θ(t))).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from nps.wopwop.case import CB

ORDERS = 4  # value and three time derivatives
_BINOMIAL = ((1,), (1, 1), (1, 2, 1), (1, 3, 3, 1))


@dataclass(frozen=True, eq=False)
class FrameMotion:
    """x_parent = R x_local + T at n_t times, with time derivatives: ``rotation`` (4, n_t, 3, 3) R, dR/dt,
    d²R/dt², d³R/dt³; ``translation`` (4, n_t, 3) T and its derivatives (m, m/s, m/s², m/s³)."""

    rotation: np.ndarray
    translation: np.ndarray


def _times(t_s) -> np.ndarray:
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    if t.ndim != 1 or not np.all(np.isfinite(t)):
        raise ValueError(f"times must be a finite 1-D array (s), got shape {t.shape}")
    return t


def identity(n_t: int) -> FrameMotion:
    """No motion: R = I, T = 0, all derivatives 0."""
    rotation = np.zeros((ORDERS, n_t, 3, 3))
    rotation[0] = np.eye(3)
    return FrameMotion(rotation, np.zeros((ORDERS, n_t, 3)))


def _unsupported(cb: CB, what: str) -> ValueError:
    return ValueError(f"&CB '{cb.title}': {what} is not supported (refused when the case is read)")


def angle_series(cb: CB, t_s) -> np.ndarray:
    """The rotation angle θ (rad) of a CB and its first three time derivatives, (4, n_t)."""
    t = _times(t_s)
    out = np.zeros((ORDERS, t.size))
    if cb.angle_type == "TimeIndependent":
        out[0] = cb.angle_value
    elif cb.angle_type == "KnownFunction":
        out[0] = cb.omega_rad_s * t + cb.psi0_rad
        out[1] = cb.omega_rad_s
    elif cb.angle_type == "Periodic":
        n_harm = max(len(cb.a), len(cb.b))
        n = np.arange(1, n_harm + 1)
        a, b = (np.pad(np.asarray(c, dtype=float), (0, n_harm - len(c))) for c in (cb.a, cb.b))
        phase = np.exp(1j * np.outer(cb.omega_rad_s * t + cb.psi0_rad, n))  # (n_t, n_harm)
        for order in range(ORDERS):  # Re Σ (A_n − i B_n) (i n Ω)^k e^{i n ψ}
            out[order] = np.real(phase @ ((a - 1j * b) * (1j * n * cb.omega_rad_s) ** order))
        out[0] += cb.a0
    elif cb.angle_type is not None:
        raise _unsupported(cb, f"AngleType '{cb.angle_type}'")
    return out


def _rotation_series(axis, angle: np.ndarray) -> np.ndarray:
    """R(θ(t)) about a fixed axis and its time derivatives (4, n_t, 3, 3), from θ and its derivatives (4, n_t)."""
    u = np.asarray(axis, dtype=float)
    u = u / np.linalg.norm(u)
    k = np.array([[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]])
    k2 = k @ k
    c, s = np.cos(angle[0])[:, None, None], np.sin(angle[0])[:, None, None]
    d = [np.eye(3) + s * k + (1.0 - c) * k2, c * k + s * k2, -s * k + c * k2, -c * k - s * k2]  # d^jR/dθ^j
    w1, w2, w3 = (angle[i][:, None, None] for i in (1, 2, 3))
    return np.stack([d[0], d[1] * w1, d[2] * w1**2 + d[1] * w2, d[3] * w1**3 + 3.0 * d[2] * w1 * w2 + d[1] * w3])


def translation_series(cb: CB, t_s) -> np.ndarray:
    """The translation T (m) of a CB and its first three time derivatives, (4, n_t, 3)."""
    t = _times(t_s)
    out = np.zeros((ORDERS, t.size, 3))
    if cb.translation_type == "TimeIndependent":
        out[0] = cb.translation_value
    elif cb.translation_type == "KnownFunction":
        y0, vh, ah = (np.asarray(v, dtype=float) for v in (cb.y0, cb.vh, cb.ah))
        out[0] = y0 + np.outer(t, vh) + 0.5 * np.outer(t**2, ah)
        out[1] = vh + np.outer(t, ah)
        out[2] = ah
    elif cb.translation_type is not None:
        raise _unsupported(cb, f"TranslationType '{cb.translation_type}'")
    return out


def cb_motion(cb: CB, t_s) -> FrameMotion:
    """One CB's motion at the times ``t_s`` (s): rotation about its axis, then translation."""
    t = _times(t_s)
    if cb.windframe:
        raise _unsupported(cb, "a wind-frame CB")
    if cb.axis_type != "TimeIndependent":
        raise _unsupported(cb, f"AxisType '{cb.axis_type}'")
    motion = identity(t.size)
    rotation = _rotation_series(cb.axis_value, angle_series(cb, t)) if cb.angle_type else motion.rotation
    return FrameMotion(rotation, translation_series(cb, t))


def _leibniz(a: np.ndarray, b: np.ndarray, subscripts: str, orders: int) -> np.ndarray:
    """Derivatives 0..orders−1 of a product: (ab)^(m) = Σ_j C(m, j) a^(j) b^(m−j)."""
    return np.stack([sum(_BINOMIAL[m][j] * np.einsum(subscripts, a[j], b[m - j]) for j in range(m + 1))
                     for m in range(orders)])


def compose(outer: FrameMotion, inner: FrameMotion) -> FrameMotion:
    """outer(inner(x)) = R_o (R_i x + T_i) + T_o: R = R_o R_i, T = R_o T_i + T_o, with their derivatives."""
    if outer.rotation.shape != inner.rotation.shape:
        raise ValueError(f"motions at different times: {outer.rotation.shape[1]} and {inner.rotation.shape[1]}")
    rotation = _leibniz(outer.rotation, inner.rotation, "tij,tjk->tik", ORDERS)
    translation = _leibniz(outer.rotation, inner.translation, "tij,tj->ti", ORDERS) + outer.translation
    return FrameMotion(rotation, translation)


def chain_motion(cbs: Sequence[CB], t_s) -> FrameMotion:
    """A CB chain (first CB listed applied last): x_parent = CB1(CB2(…CBn(x))); no CB: the identity."""
    t = _times(t_s)
    motion = identity(t.size)
    for cb in reversed(tuple(cbs)):
        motion = compose(cb_motion(cb, t), motion)
    return motion


def _local_series(motion: FrameMotion, fixed, moving, name: str) -> tuple[np.ndarray, int]:
    """Local kinematics as (orders, n_t, n, 3): fixed points/vectors (n, 3) have zero rates (4 orders out);
    moving ones are given with their rates (k, n_t, n, 3) and give k orders."""
    n_t = motion.rotation.shape[1]
    if (fixed is None) == (moving is None):
        raise ValueError(f"give either fixed {name} (n, 3) or their time series with rates (k, n_t, n, 3)")
    if fixed is not None:
        x = np.asarray(fixed, dtype=float)
        if x.ndim != 2 or x.shape[1] != 3:
            raise ValueError(f"fixed {name}: expected shape (n, 3), got {x.shape}")
        series = np.zeros((ORDERS, n_t) + x.shape)
        series[0] = x
        return series, ORDERS
    x = np.asarray(moving, dtype=float)
    if x.ndim != 4 or not 1 <= x.shape[0] <= ORDERS or x.shape[1] != n_t or x.shape[3] != 3:
        raise ValueError(f"moving {name}: expected shape (k <= {ORDERS}, {n_t}, n, 3), got {x.shape}")
    return x, x.shape[0]


def apply(motion: FrameMotion, x_local, derivatives_local=None) -> np.ndarray:
    """Parent-frame position, velocity, acceleration, jerk (orders, n_t, n, 3) of points: fixed in the local frame
    (``x_local`` (n, 3); 4 orders) or moving in it (``x_local`` None and ``derivatives_local`` (k, n_t, n, 3): the
    local position and its first k − 1 rates; k orders)."""
    local, orders = _local_series(motion, x_local, derivatives_local, "points")
    return _leibniz(motion.rotation, local, "tij,tnj->tni", orders) + motion.translation[:orders, :, None, :]


def rotate_vectors(motion: FrameMotion, v_local, *local_rates) -> np.ndarray:
    """R v and its time derivatives (orders, n_t, n, 3), no translation (loading vectors, normals): ``v_local``
    (n, 3) fixed in the local frame (4 orders), or (n_t, n, 3) with its local rates (n_t, n, 3) d v/dt, ... in
    ``local_rates`` (1 + len(local_rates) orders)."""
    v = np.asarray(v_local, dtype=float)
    moving = np.stack((v,) + tuple(np.asarray(r, dtype=float) for r in local_rates)) if v.ndim == 3 else None
    if v.ndim != 3 and local_rates:
        raise ValueError("local rates go with time-varying vectors (n_t, n, 3)")
    local, orders = _local_series(motion, v if moving is None else None, moving, "vectors")
    return _leibniz(motion.rotation, local, "tij,tnj->tni", orders)
