"""Property tests of the equal-area shock fit over random smooth periodic signals and shears.

For p0 a random 1–4 harmonic Fourier series (period 1, 512 samples) sheared by t = t0 − k p0
with k up to 5× the shock-formation value, the fitted signal must be single-valued (strictly
increasing time), finite, keep ∫p dt over the period of the input closed curve (to 1e-9 of
∫|p| dt), stay periodic (fitting the input started at another sample gives the same function, to
1e-9 of max|p|), and every shock must cut off equal signed areas (1e-9 relative, checked with
an independent polyline integration; plus 1e-15 of ∫|p| dt over the period, the double-precision
floor that matters only for shocks just formed, whose lobes are ~1e-10 of that integral).
"""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.noise.hsi import fit_shocks

N = 512


@st.composite
def sheared_signals(draw):
    n_harm = draw(st.integers(1, 4))
    amps = np.array(draw(st.lists(st.floats(0.05, 1.0), min_size=n_harm, max_size=n_harm)))
    phases = np.array(draw(st.lists(st.floats(0.0, 2 * np.pi), min_size=n_harm, max_size=n_harm)))
    offset = draw(st.floats(-0.5, 0.5))
    factor = draw(st.floats(0.0, 5.0))
    t0 = np.arange(N) / N
    m = np.arange(1, n_harm + 1)[:, None]
    p = offset + (amps[:, None] * np.sin(2 * np.pi * m * t0 + phases[:, None])).sum(axis=0)
    slope = (amps[:, None] * 2 * np.pi * m * np.cos(2 * np.pi * m * t0 + phases[:, None])).sum(axis=0).max()
    k = factor / slope
    return t0 - k * p, p


def closed_area(t, p, period=1.0):
    tt = np.append(t, t[0] + period)
    pp = np.append(p, p[0])
    return np.sum(0.5 * (pp[1:] + pp[:-1]) * np.diff(tt)), np.sum(0.5 * np.abs(pp[1:] + pp[:-1]) * np.abs(np.diff(tt)))


def loop_split(t, p, t_s, p_minus, p_plus):
    """∫p dt of the closed input curve between its crossings of t = t_s at p_minus and p_plus (walking
    forward, periodically), split into the parts left and right of the line."""
    n = t.size
    tt = np.concatenate([t - 1, t, t + 1, [t[0] + 2]])
    pp = np.concatenate([p, p, p, [p[0]]])
    cross = []
    for i in range(tt.size - 1):
        a, b = tt[i] - t_s, tt[i + 1] - t_s
        if a != b and a * b <= 0:
            w = a / (a - b)
            cross.append((i + w, pp[i] + w * (pp[i + 1] - pp[i])))
    s_a = min(cross, key=lambda c: abs(c[1] - p_minus))[0]
    after = [c for c in cross if s_a < c[0] < s_a + n]
    s_b = min(after, key=lambda c: abs(c[1] - p_plus))[0]
    grid = np.unique(np.concatenate([[s_a, s_b], np.arange(np.ceil(s_a), np.floor(s_b) + 1), [c[0] for c in cross if s_a < c[0] < s_b]]))
    idx = np.arange(tt.size)
    gt, gp = np.interp(grid, idx, tt), np.interp(grid, idx, pp)
    seg = 0.5 * (gp[1:] + gp[:-1]) * np.diff(gt)
    mid = 0.5 * (gt[1:] + gt[:-1])
    return seg[mid < t_s].sum(), seg[mid > t_s].sum()


def periodic_eval(fit, probe):
    """Value of the fitted one-period polyline at ``probe`` (wrapped into its window); np.interp's own
    ``period`` option would reorder the nextafter pair that encodes a shock."""
    x = np.append(fit.time_s, fit.time_s[0] + 1.0)
    y = np.append(fit.p_pa, fit.p_pa[0])
    return np.interp(x[0] + (probe - x[0]) % 1.0, x, y)


@settings(max_examples=50, deadline=None)
@given(sheared_signals(), st.integers(1, N - 1))
def test_fit_properties(signal, start):
    t, p = signal
    fit = fit_shocks(t, p, period_s=1.0)
    assert np.isfinite(fit.time_s).all() and np.isfinite(fit.p_pa).all()
    assert np.all(np.diff(fit.time_s) > 0)
    assert fit.time_s[0] == t[0] and fit.time_s[-1] < t[0] + 1.0
    area_in, scale = closed_area(t, p)
    area_out, _ = closed_area(fit.time_s, fit.p_pa)
    assert abs(area_out - area_in) <= 1e-9 * scale
    # periodicity: the same closed curve started elsewhere gives the same single-valued function
    other = fit_shocks(np.roll(t, -start) + np.where(np.arange(N) >= N - start, 1.0, 0.0), np.roll(p, -start), period_s=1.0)
    probe = t[0] + (np.arange(997) + 0.5) / 997
    a = periodic_eval(fit, probe)
    b = periodic_eval(other, probe)
    near_shock = np.zeros_like(probe, dtype=bool)
    for ts in fit.shock_time_s:
        near_shock |= np.abs((probe - ts + 0.5) % 1.0 - 0.5) < 1e-6
    np.testing.assert_allclose(a[~near_shock], b[~near_shock], atol=1e-9 * np.abs(p).max())
    for ts, pm, pp in zip(fit.shock_time_s, fit.p_before_pa, fit.p_after_pa):
        left, right = loop_split(t, p, ts, pm, pp)
        assert abs(left + right) <= 1e-9 * max(abs(left), abs(right)) + 1e-15 * scale
