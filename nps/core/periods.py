"""Common period of rotors turning at different speeds.

Rotors q = 0…n−1 with speeds Ω_q (rad/s) repeat their joint pattern after the common period T when every
rotor completes a whole number m_q of its own revolutions in it: Ω_q T = 2π m_q. With the first rotor as
the reference, T = 2π n/Ω_0 (n = m_0) and m_q/n = Ω_q/Ω_0: the speed ratios must be rational.

:func:`common_period` finds the smallest n (at most ``max_revolutions``) for which every ratio Ω_q/Ω_0 is
within the relative ``tolerance`` of m_q/n. A ratio met within 1e-9 is exact (5:1, 3:2, 29:7); otherwise the
period is an approximation: the wake and the loads are made periodic with the speed ratio m_q/n instead of
Ω_q/Ω_0 (docs/reference/wake_bvi.md, "Common period"). No such n: :class:`PeriodError` names the rotors,
their speeds and the best fraction found.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

EXACT_RTOL = 1e-9  # a speed ratio within this of its fraction counts as exact
DEFAULT_TOLERANCE = 0.005  # relative speed-ratio error accepted for the approximate period
DEFAULT_MAX_REVOLUTIONS = 16  # revolutions of the reference rotor in the longest period searched


class PeriodError(ValueError):
    """No common period within the tolerance and the largest number of revolutions."""


@dataclass(frozen=True)
class CommonPeriod:
    """``names`` and ``omega_rad_s`` of the rotors (the first is the reference), ``revolutions`` m_q of
    each in the period, and the relative speed-ratio errors m_q Ω_0/(n Ω_q) − 1 of the approximation."""

    names: tuple[str, ...]
    omega_rad_s: tuple[float, ...]
    revolutions: tuple[int, ...]

    @property
    def period_s(self) -> float:
        """T = 2π m_0/Ω_0 (s)."""
        return 2.0 * math.pi * self.revolutions[0] / self.omega_rad_s[0]

    @property
    def ratio_errors(self) -> tuple[float, ...]:
        n, w0 = self.revolutions[0], self.omega_rad_s[0]
        return tuple(m * w0 / (n * w) - 1.0 for m, w in zip(self.revolutions, self.omega_rad_s))

    @property
    def exact(self) -> bool:
        return all(abs(e) <= EXACT_RTOL for e in self.ratio_errors)

    def describe(self) -> str:
        """One line: the period and, per rotor, its revolutions and the ratio error."""
        parts = [f"'{name}' {m} rev" + ("" if abs(e) <= EXACT_RTOL else f" (speed ratio approximated by {e:+.3%})")
                 for name, m, e in zip(self.names, self.revolutions, self.ratio_errors)]
        return f"common period {self.period_s:.6g} s: " + ", ".join(parts)


def common_period(names: Sequence[str], omega_rad_s: Sequence[float], tolerance: float = DEFAULT_TOLERANCE,
                  max_revolutions: int = DEFAULT_MAX_REVOLUTIONS) -> CommonPeriod:
    """The shortest common period of rotors at ``omega_rad_s`` (module doc); the first rotor is the reference."""
    names, omega = tuple(str(n) for n in names), tuple(float(w) for w in omega_rad_s)
    if not names or len(names) != len(omega):
        raise ValueError(f"common_period: expected one speed per rotor, got names {names} and speeds {omega}")
    if not all(math.isfinite(w) and w > 0.0 for w in omega):
        raise ValueError(f"common_period: speeds must be finite and > 0 rad/s, got {dict(zip(names, omega))}")
    if not 0.0 <= tolerance < 0.5 or max_revolutions < 1:
        raise ValueError(f"common_period: tolerance {tolerance} (expected 0 <= tolerance < 0.5) and max_revolutions "
                         f"{max_revolutions} (expected >= 1)")
    ratios = [w / omega[0] for w in omega]
    best = None
    for n in range(1, int(max_revolutions) + 1):
        ms = [max(1, round(r * n)) for r in ratios]
        error = max(abs(m / (n * r) - 1.0) for m, r in zip(ms, ratios))
        if error <= max(tolerance, EXACT_RTOL):
            g = math.gcd(*ms)
            return CommonPeriod(names, omega, tuple(m // g for m in ms))
        if best is None or error < best[0]:
            best = (error, n, ms)
    error, n, ms = best
    listing = ", ".join(f"'{a}' {w:.6g} rad/s" for a, w in zip(names, omega))
    raise PeriodError(f"no common period of the rotors ({listing}) within {max_revolutions} revolutions of "
                      f"'{names[0]}' and a speed-ratio tolerance of {tolerance:.3%}: the best is {n} revolutions "
                      f"({', '.join(f'{a} {m}' for a, m in zip(names, ms))}) with a ratio error of {error:.3%}; "
                      "raise wake.free.period_tolerance or max_period_revolutions, or give the rotors speeds in a "
                      "simple ratio")


def table_revolutions(psi_unique) -> int:
    """Revolutions m spanned by the sorted distinct azimuths ψ_i = 2πi/N (i < mN) of a disk table:
    round(n Δψ/2π), at least 1 (a one-revolution table gives 1)."""
    psi_unique = np.asarray(psi_unique, dtype=float)
    if psi_unique.size < 2 or not psi_unique[1] > psi_unique[0]:
        return 1
    return max(1, int(round(psi_unique.size * (psi_unique[1] - psi_unique[0]) / (2.0 * math.pi))))
