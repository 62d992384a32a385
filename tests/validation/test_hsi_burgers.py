"""Equal-area shock fitting against the weak solution of the inviscid Burgers equation.

A periodic signal p0(t0) sheared as t = t0 − k p0(t0) is the characteristic solution of inviscid
Burgers (x = −t, y = −t0, "time" k). Its entropy weak solution is given independently here by
the Lax–Oleinik (Hopf–Lax) formula p(t) = (t0*(t) − t)/k, with
t0* = argmin over t0 of [(t0 − t)²/(2k) − P(t0)], P(t0) = ∫_0^t0 p0 (closed form), minimised by
brute force on a 10⁻⁵-period grid and located to 10⁻¹² by bisection at the shocks.
Acceptance (issue 7): shock positions (relative to the period) and jumps (relative to the jump)
within 1 %; measured: below 1e-4 for 4096 samples per period.
"""

import numpy as np
import pytest

from nps.noise.hsi import fit_shocks

A3, PHASE = 0.5, 1.0  # p0 = sin 2πt + A3 sin(6πt + PHASE), period 1: two compression regions


def p0(t):
    return np.sin(2 * np.pi * t) + A3 * np.sin(6 * np.pi * t + PHASE)


def big_p(t):
    return (1 - np.cos(2 * np.pi * t)) / (2 * np.pi) + A3 * (np.cos(PHASE) - np.cos(6 * np.pi * t + PHASE)) / (6 * np.pi)


T0_GRID = np.linspace(-1.5, 2.5, 400_001)
P_GRID = big_p(T0_GRID)


def minimiser(t, k):
    """Global minimiser of (t0 − t)²/(2k) − P(t0), refined by golden-section search around the grid minimum."""
    j = np.argmin((T0_GRID - t) ** 2 / (2 * k) - P_GRID)
    a, b = T0_GRID[max(j - 1, 0)], T0_GRID[min(j + 1, T0_GRID.size - 1)]
    f = lambda s: (s - t) ** 2 / (2 * k) - big_p(s)
    g = (np.sqrt(5) - 1) / 2
    for _ in range(60):
        c, d = b - g * (b - a), a + g * (b - a)
        if f(c) < f(d):
            b = d
        else:
            a = c
    return 0.5 * (a + b)


def lax_oleinik_shocks(k, n_scan=2000):
    """(shock times in [0, 1), p before, p after) of the weak solution at shear k."""
    scan = np.arange(n_scan) / n_scan
    t0s = np.array([minimiser(t, k) for t in scan])
    jumps = np.nonzero(np.diff(np.append(t0s, t0s[0] + 1.0)) > 20.0 / n_scan)[0]
    shocks = []
    for j in jumps:
        lo, hi = scan[j], scan[j] + 1.0 / n_scan
        left, right = t0s[j], minimiser(hi, k)
        for _ in range(45):
            mid = 0.5 * (lo + hi)
            s = minimiser(mid, k)
            if abs(s - left) < abs(s - right):
                lo, left = mid, s
            else:
                hi, right = mid, s
        t_s = 0.5 * (lo + hi)
        shocks.append((t_s % 1.0, (left - t_s) / k, (right - t_s) / k))
    return np.array(sorted(shocks))


@pytest.mark.parametrize("k, n_expected", [(0.06, 0), (0.08, 1), (0.15, 2), (0.3, 2)])
def test_sheared_signal_fit_matches_lax_oleinik(k, n_expected):
    """k = 0.06: no shock yet; 0.08: one; 0.15: two; 0.3: those two have merged into one (jump
    −0.84 → 1.19) while a third has formed near t = 0.81. Position error relative to the period,
    jump error relative to the reference jump: both < 1 % (acceptance), < 1e-4 and 1e-3 reached.
    """
    n = 4096
    t0 = np.arange(n) / n
    fit = fit_shocks(t0 - k * p0(t0), p0(t0), period_s=1.0)
    ref = lax_oleinik_shocks(k)
    assert len(ref) == n_expected
    assert fit.shock_time_s.size == n_expected
    if n_expected == 0:
        return
    order = np.argsort(fit.shock_time_s % 1.0)
    t_fit = fit.shock_time_s[order] % 1.0
    jump_fit = (fit.p_after_pa - fit.p_before_pa)[order]
    jump_ref = ref[:, 2] - ref[:, 1]
    dt = np.abs((t_fit - ref[:, 0] + 0.5) % 1.0 - 0.5)
    assert dt.max() < 0.01
    assert np.max(np.abs(jump_fit - jump_ref) / np.abs(jump_ref)) < 0.01
    # tighter figures actually reached (documented in docs/reference/hsi.md)
    assert dt.max() < 1e-4
    assert np.max(np.abs(jump_fit - jump_ref) / np.abs(jump_ref)) < 1e-3
