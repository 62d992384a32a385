"""The compiled F1A kernel equals, bit for bit, a plain-Python evaluation of the per-observer formulation.

The reference below runs observer by observer and node by node, with Python floats (IEEE double, one rounding
per operation, as the compiled kernel without fastmath): reception time, F1A dipole, compact monopole or
surface-panel term, Newton divided differences, the interval walk of the cubic interpolation, the unwrapped
periodic buffer and its fold. The kernel (vectorised loops, slots of targets per interval, observer blocks)
must give the same bits (``np.array_equal``), in the periodic and the direct mode, for targets sparser and
denser than the source steps and with more than one block of observers.
"""

import math

import numpy as np
import pytest

from nps.noise.acoustics import (LOADING, OBSERVER_BLOCK, THICKNESS, CompactSources, _monopole, _pack_sources,
                                 _radiate_kernel, _reception)

C0, RHO0, PAD = 340.294, 1.225, 2


def _sources(n_tau: int, period: float | None, tau0: float = 0.0) -> CompactSources:
    """Seven nodes on circles (Ω = 30 rad/s, r = 2 m): loading and thickness dipoles, one compact monopole,
    surface panels (mass flux on the odd nodes), nodes without a dipole or a monopole."""
    rng = np.random.default_rng(7)
    n_node, omega = 7, 30.0
    step = period / n_tau if period else 2e-3
    tau = tau0 + np.arange(n_tau) * step
    phase = omega * tau[None, :] + rng.uniform(0.0, 2.0 * np.pi, (n_node, 1))
    c, s = np.cos(phase), np.sin(phase)
    pos = np.stack([2 * c, 2 * s, 0.1 * s], -1)
    vel = np.stack([-2 * omega * s, 2 * omega * c, 0.1 * omega * c], -1)
    acc = np.stack([-2 * omega**2 * c, -2 * omega**2 * s, -0.1 * omega**2 * s], -1)
    jerk = np.stack([2 * omega**3 * s, -2 * omega**3 * c, -0.1 * omega**3 * c], -1)
    force = rng.normal(size=(n_node, 1, 3)) * (1.0 + 0.3 * np.sin(2 * phase))[..., None]
    rate = rng.normal(size=(n_node, 1, 3)) * np.cos(2 * phase)[..., None]
    panel = (np.arange(n_node) % 2 == 1)[:, None]
    flux = np.where(panel, 1.0 + 0.5 * s, 0.0)
    flux_rate = np.where(panel, 0.5 * omega * c, 0.0)
    volume = np.array([2e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 1e-3])
    dipole = np.array([0, -1, 1, 0, 1, -1, -1])
    monopole = np.array([1, 1, 1, 1, 1, 1, 1])
    kwargs = dict(period_s=period, frame_velocity_mps=np.zeros(3), copies=2) if period else {}
    return CompactSources(tau, pos, vel, acc, jerk, force, rate, volume, (LOADING, THICKNESS), dipole, monopole,
                          mass_flux_kg_s=flux, mass_flux_rate_kg_s2=flux_rate, **kwargs)


def _observers():
    """OBSERVER_BLOCK + 3 observers 6…40 m away, at rest."""
    rng = np.random.default_rng(3)
    n = OBSERVER_BLOCK + 3
    direction = rng.normal(size=(n, 3))
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    return direction * np.geomspace(6.0, 40.0, n)[:, None], np.zeros((n, 3))


def _node_samples(src, tau, i, xo, vo, kind, rho0_vol):
    """Reception times and 4π p (dipole, thickness part) of node i at one observer, source step by step."""
    inv_a = 1.0 / (C0 * C0 - (vo[0] * vo[0] + vo[1] * vo[1] + vo[2] * vo[2]))
    inv_c = 1.0 / C0
    tb, pa, pb = [], [], []
    for j in range(tau.size):
        y, v, a, f, e, jk = (src[i, q:q + 3, j].tolist() for q in (0, 3, 6, 9, 12, 15))
        m2, fm, flux, flux_rate = (float(src[i, q, j]) for q in (18, 19, 20, 21))
        t, s, r0, r1, r2 = _reception.py_func(*y, *xo, *vo, float(tau[j]), C0, inv_a)
        inv_r = 1.0 / (C0 * s)
        n0, n1, n2 = r0 * inv_r, r1 * inv_r, r2 * inv_r
        mr = (v[0] * n0 + v[1] * n1 + v[2] * n2) * inv_c
        mdot_r = (a[0] * n0 + a[1] * n1 + a[2] * n2) * inv_c
        w = 1.0 / (1.0 - mr)
        fr = f[0] * n0 + f[1] * n1 + f[2] * n2
        fdr = e[0] * n0 + e[1] * n1 + e[2] * n2
        tb.append(t)
        pa.append(w * w * inv_r * (fdr * inv_c + (fr - fm) * inv_r + fr * w * (mdot_r * inv_c + (mr - m2) * inv_r)))
        if kind == "monopole":
            pb.append(rho0_vol * _monopole.py_func(s, r0, r1, r2, *v, *a, *jk, m2, C0))
        elif kind == "panel":
            mr = (v[0] * r0 + v[1] * r1 + v[2] * r2) * inv_r * inv_c
            mdot_r = (a[0] * r0 + a[1] * r1 + a[2] * r2) * inv_r * inv_c
            w = 1.0 / (1.0 - mr)
            pb.append(w * w * inv_r * (flux_rate + flux * w * (mdot_r + C0 * (mr - m2) * inv_r)))
        else:
            pb.append(0.0)
    return tb, pa, pb


def _walk(tb, p, lo, hi, base, dt, count, row, off):
    """Divided differences and the cubic interpolation walk (targets base + q·dt added at row[off + q])."""
    d1 = [0.0] * len(tb)
    d2 = [0.0] * len(tb)
    d3 = [0.0] * len(tb)
    for j in range(lo, hi - 1):
        d1[j] = (p[j + 1] - p[j]) / (tb[j + 1] - tb[j])
    for j in range(lo, hi - 2):
        d2[j] = (d1[j + 1] - d1[j]) / (tb[j + 2] - tb[j])
    for j in range(lo, hi - 3):
        d3[j] = (d2[j + 1] - d2[j]) / (tb[j + 3] - tb[j])
    q, t = 0, base
    for j in range(lo, hi - 1):
        if q >= count:
            break
        last = j == hi - 2
        if t >= tb[j + 1] and not last:
            continue
        k = min(max(j - 1, lo), hi - 4)
        while q < count and (t < tb[j + 1] or last):
            row[off + q] += p[k] + (t - tb[k]) * (d1[k] + (t - tb[k + 1]) * (d2[k] + (t - tb[k + 2]) * d3[k]))
            q += 1
            t = base + q * dt


def _window(tb, t_first, t_end):
    """Direct mode: the source steps whose stencils cover [t_first, t_end]."""
    n_tau = len(tb)
    first = 0
    while first < n_tau - 1 and tb[first + 1] <= t_first:
        first += 1
    stop = n_tau
    while stop > first + 1 and tb[stop - 2] >= t_end:
        stop -= 1
    first, stop = max(first - PAD, 0), min(stop + PAD, n_tau)
    if stop - first < 4:
        first = max(0, min(first, n_tau - 4))
        stop = first + 4
    return first, stop


def _reference(packed, xo, vo, t_first, dt, n_out, period):
    """Pressure (Pa, (n_obs, n_groups, n_out)) by the per-observer formulation, in plain Python floats."""
    src, tau, vol, surf, gdip, gmono, n_groups = packed
    out = np.zeros((len(xo), n_groups, n_out))
    for o in range(len(xo)):
        buf = [[0.0] * (2 * n_out) for _ in range(n_groups)]
        for i in range(src.shape[0]):
            has_b = gmono[i] >= 0 and (vol[i] != 0.0 or surf[i])
            if gdip[i] < 0 and not has_b:
                continue
            kind = "monopole" if has_b and vol[i] != 0.0 else "panel" if has_b else "none"
            tb, pa, pb = _node_samples(src, tau, i, xo[o].tolist(), vo[o].tolist(), kind, RHO0 * float(vol[i]))
            if period > 0.0:
                n_tau = len(tb)
                tb = [x - period for x in tb[n_tau - PAD:]] + tb + [x + period for x in tb[:PAD + 1]]
                pa, pb = (x[n_tau - PAD:] + x + x[:PAD + 1] for x in (pa, pb))
                lo, hi = 0, len(tb)
                m0 = math.ceil((tb[PAD] - t_first) / dt)
                base, off = t_first + m0 * dt, m0 % n_out
            else:
                lo, hi = _window(tb, t_first, t_first + (n_out - 1) * dt)
                base, off = t_first, 0
            if gdip[i] >= 0:
                _walk(tb, pa, lo, hi, base, dt, n_out, buf[gdip[i]], off)
            if has_b:
                _walk(tb, pb, lo, hi, base, dt, n_out, buf[gmono[i]], off)
        for g in range(n_groups):
            for k in range(n_out):
                out[o, g, k] = (buf[g][k] + buf[g][k + n_out]) * (1.0 / (4.0 * np.pi))
    return out


@pytest.mark.parametrize("n_out", [9, 40, 160])
def test_periodic_kernel_equals_the_scalar_reference(n_out):
    """One period of 24 source steps, 9 (fewer than the steps), 40 and 160 targets (up to about 12 per source
    interval: the kernel's generic slot scatter): kernel == reference, every bit."""
    period = 2.0 * np.pi / 30.0
    sources = _sources(24, period)
    xo, vo = _observers()
    packed = _pack_sources(sources, C0, period)
    args = (xo, vo, C0, RHO0, 0.013, period / n_out, n_out, period)
    kernel = _radiate_kernel(*packed, *args)
    assert np.abs(kernel).max() > 0
    assert np.array_equal(kernel, _reference(packed, *args[:2], *args[4:]))


@pytest.mark.parametrize("n_out", [12, 80, 700])
def test_direct_kernel_equals_the_scalar_reference(n_out):
    """64 source steps (0.126 s), a 0.03 s window sampled coarsely, finely and with over 20 targets per source
    interval (the scalar walk): kernel == reference, every bit."""
    sources = _sources(64, None)
    xo, vo = _observers()
    packed = _pack_sources(sources, C0, 0.0)
    args = (xo, vo, C0, RHO0, 0.13, 0.03 / n_out, n_out, 0.0)
    kernel = _radiate_kernel(*packed, *args)
    assert np.abs(kernel).max() > 0
    assert np.array_equal(kernel, _reference(packed, *args[:2], *args[4:]))
