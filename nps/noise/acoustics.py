"""Compact Farassat 1A: pressure time histories of compact line sources at any observers.

Model (docs/reference/acoustics.md). Every source node is a compact point that moves along a
known path y(τ) in the ground frame G (medium at rest) and carries

* a force ``f`` (N) exerted *on the fluid* (the loading dipole, or a dual-compact thickness
  line), radiated with Farassat's formulation 1A reduced to a point (thesis eq. 2.4, read with
  the denominators of the published formulation; see below), and optionally
* a volume ``V`` (m³), a compact thickness monopole: p_T = ρ0 V/(4π) ∂²/∂t² [1/(r|1−M_r|)]_ret,
  the compact limit of the thesis' eq. 2.3 (the model ANOPP2 and AcousticAnalogies.jl use), or
* a mass flux ``Q`` = ρ0 v·A (kg/s) with its rate Q̇: a surface panel of area vector A (outward, m²) moving
  with v, whose thickness term of formulation 1A reduced to the panel centre is
  4π p_T = Q̇/(r(1−M_r)²) + Q (r Ṁ_r + c0 M_r − c0 M²)/(r²(1−M_r)³) (Farassat 2007, eq. 1A's thickness
  integrand times the panel area; midpoint quadrature of the surface integral over the panels).

Compact F1A loading, with r = x(t) − y(τ), r = |r| = c0 (t − τ), M = v/c0, Ṁ = a/c0 and the
subscripts r, M meaning dot products with r̂ and M::

    4π p_L = ḟ_r / (c0 r (1−M_r)²) + (f_r − f_M) / (r² (1−M_r)²)
             + f_r (r Ṁ_r + c0 M_r − c0 M²) / (c0 r² (1−M_r)³)

(the thesis prints r|1−M_r|² garbled in the first two denominators; the consistent reading is
r(1−M_r)² and r²(1−M_r)²). All near- and far-field terms are kept.

Algorithm (source-time dominant): for each observer, node and source time τ_j the reception
time t_j = τ_j + r/c0 comes in closed form (the observer moves with constant velocity, so
|x0 + v_o t − y(τ)| = c0 (t − τ) is a quadratic in t − τ), the contribution p_j is evaluated
there, and the non-uniform samples (t_j, p_j) are interpolated onto the uniform observer grid
with 4-point (cubic) Lagrange interpolation on the non-uniform nodes, then summed over nodes.
Observer motion enters only through the reception point x(t_j): F1A gives p(x, t) at any fixed
point, and the receiver is at x(t_j) when it hears τ_j.

Implementation (numba, float64, no fastmath): sources are packed into one contiguous row per
(node, source step) with the source-only quantities (M², f·M) precomputed; observers are
processed in blocks of ``OBSERVER_BLOCK`` (parallel over blocks), so each source row is read once
per block and the F1A and divided-difference loops run over the block's observers as
vectorisable 1-D loops; the cubic is evaluated in Newton form. Same results as the per-observer
formulation to rounding (≈1e-14 of the peak, checked when the kernel was restructured).

Two drivers share the kernel:

* :func:`radiate_arrays` (``periodic=False``): sources given over a finite source-time span,
  any observers; the requested window must be covered (error names the observer).
* periodic sources (:class:`CompactSources` with ``period_s``): one period of blade 0 of a
  rotor in steady flight, observers moving with the aircraft. The received signal is then
  exactly periodic; it is interpolated onto ``M`` points per period, the B identical blades are
  added in the Fourier domain (harmonics that are multiples of B, times B: exact for identical
  blades), and the Fourier series is evaluated on the common grid (band-limited resampling, exact
  for rotors of any speed).

Units SI; positions, velocities and forces in G. Pressure in Pa.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.core.jit import kernel, prange

C0_MPS = 340.294
RHO0_KG_M3 = 1.225
THICKNESS = "thickness"
LOADING = "loading"


class AcousticsError(ValueError):
    """Bad acoustic input (names the field or observer and what was expected)."""


@dataclass(frozen=True)
class CompactSources:
    """Compact source nodes sampled at uniform source times (SI, ground frame G).

    Arrays have shape (n_node, n_tau, 3) for vectors: ``position_m``, ``velocity_mps``,
    ``acceleration_mps2``, ``jerk_mps3`` (d³y/dτ³, needed only by monopole nodes),
    ``force_N`` (force on the fluid, N) and ``force_rate_N_s`` (dF/dτ). ``volume_m3`` (n_node,)
    is the compact-monopole volume (0 for a pure dipole node). ``mass_flux_kg_s`` and
    ``mass_flux_rate_kg_s2`` (n_node, n_tau), optional: the surface-panel thickness source Q = ρ0 v·A and
    dQ/dτ (a node carries a volume or a mass flux, not both). ``groups`` names the output
    groups; ``dipole_group`` and ``monopole_group`` (n_node,) index into it (−1: none); the monopole
    group receives the volume's or the mass flux's thickness noise. ``time_s`` (n_tau,) is uniform.

    Periodic sources: ``period_s`` is set, the samples are one period (τ_j = time_s[0] + j·T/n),
    the motion is periodic in a frame translating with ``frame_velocity_mps`` and ``copies``
    identical copies shifted by T/copies in time are implied (the other blades).
    """

    time_s: np.ndarray
    position_m: np.ndarray
    velocity_mps: np.ndarray
    acceleration_mps2: np.ndarray
    jerk_mps3: np.ndarray
    force_N: np.ndarray
    force_rate_N_s: np.ndarray
    volume_m3: np.ndarray
    groups: tuple[str, ...]
    dipole_group: np.ndarray
    monopole_group: np.ndarray
    period_s: float | None = None
    frame_velocity_mps: np.ndarray | None = None
    copies: int = 1
    mass_flux_kg_s: np.ndarray | None = None
    mass_flux_rate_kg_s2: np.ndarray | None = None

    def __post_init__(self):
        n_node, n_tau = self.position_m.shape[:2]
        for name in ("position_m", "velocity_mps", "acceleration_mps2", "jerk_mps3", "force_N", "force_rate_N_s"):
            value = getattr(self, name)
            if value.shape != (n_node, n_tau, 3):
                raise AcousticsError(f"sources: '{name}' has shape {value.shape}, expected {(n_node, n_tau, 3)}")
            if not np.isfinite(value).all():
                raise AcousticsError(f"sources: '{name}' has non-finite values")
        if self.time_s.shape != (n_tau,) or n_tau < 4:
            raise AcousticsError(f"sources: need at least 4 source times matching the arrays, got {self.time_s.shape}")
        if self.volume_m3.shape != (n_node,) or not np.isfinite(self.volume_m3).all():
            raise AcousticsError("sources: 'volume_m3' must be finite with one value per node")
        if self.period_s is not None and (self.frame_velocity_mps is None or self.copies < 1):
            raise AcousticsError("periodic sources need frame_velocity_mps and copies >= 1")
        if (self.mass_flux_kg_s is None) != (self.mass_flux_rate_kg_s2 is None):
            raise AcousticsError("sources: give both 'mass_flux_kg_s' and 'mass_flux_rate_kg_s2' or neither")
        if self.mass_flux_kg_s is not None:
            for name in ("mass_flux_kg_s", "mass_flux_rate_kg_s2"):
                value = getattr(self, name)
                if value.shape != (n_node, n_tau) or not np.isfinite(value).all():
                    raise AcousticsError(f"sources: '{name}' must be finite with shape {(n_node, n_tau)}, got {value.shape}")
            both = (self.volume_m3 != 0.0) & np.any(self.mass_flux_kg_s != 0.0, axis=1)
            if both.any():
                raise AcousticsError(f"sources: node {int(np.argmax(both))} has both a volume and a mass flux; "
                                     "a node is a compact monopole or a surface panel, not both")


@dataclass(frozen=True)
class Observers:
    """Observers: position at t = 0 (m, G) and constant velocity (m/s, G), shape (n, 3)."""

    position_m: np.ndarray
    velocity_mps: np.ndarray

    def __post_init__(self):
        if self.position_m.ndim != 2 or self.position_m.shape[1] != 3 or self.velocity_mps.shape != self.position_m.shape:
            raise AcousticsError(f"observers: positions {self.position_m.shape} and velocities {self.velocity_mps.shape} must be (n, 3)")
        if not (np.isfinite(self.position_m).all() and np.isfinite(self.velocity_mps).all()):
            raise AcousticsError("observers: non-finite position or velocity")


@dataclass(frozen=True)
class TimeGrid:
    """Uniform observer times t_k = t_start_s + k·duration_s/n_samples, k = 0…n_samples−1."""

    t_start_s: float
    duration_s: float
    n_samples: int

    @property
    def dt_s(self) -> float:
        return self.duration_s / self.n_samples

    @property
    def times_s(self) -> np.ndarray:
        return self.t_start_s + np.arange(self.n_samples) * self.dt_s


# ----------------------------------------------------------------------------------------------
# numba kernel
# ----------------------------------------------------------------------------------------------
# Packed source layout: one contiguous row of N_Q float64 per (node, source step), read once per
# block of observers (see :func:`_pack_sources`).
Q_POS, Q_VEL, Q_ACC, Q_FRC, Q_FRD, Q_JERK, Q_M2, Q_FM, Q_TAU, Q_FLUX, Q_FLUXD = 0, 3, 6, 9, 12, 15, 18, 19, 20, 21, 22
N_Q = 23
# Observers per block: every source row is loaded once per block and the per-observer inner loops
# run over the block (contiguous, vectorisable); 16 was fastest on the benchmark (8: -10 %, 32: -20 %).
OBSERVER_BLOCK = 16


@kernel(inline=True)
def _reception(y0, y1, y2, xo0, xo1, xo2, vo0, vo1, vo2, tau, c0, inv_a):
    """Closed-form reception for an observer x(t) = xo + vo t and an emission (y, τ).

    With d = x(τ) − y and s = t − τ: (c0² − v_o²) s² − 2 (d·v_o) s − |d|² = 0, positive root;
    ``inv_a`` = 1/(c0² − v_o²). Returns (t, s, r = x(t) − y components).
    """
    d0 = xo0 + vo0 * tau - y0
    d1 = xo1 + vo1 * tau - y1
    d2 = xo2 + vo2 * tau - y2
    dv = d0 * vo0 + d1 * vo1 + d2 * vo2
    dd = d0 * d0 + d1 * d1 + d2 * d2
    s = (dv + np.sqrt(dv * dv + dd / inv_a)) * inv_a
    return tau + s, s, d0 + vo0 * s, d1 + vo1 * s, d2 + vo2 * s


@kernel(inline=True)
def _monopole(s, r0, r1, r2, v0, v1, v2, a0, a1, a2, j0, j1, j2, m2, c0):
    """Compact monopole W d/dτ[W d/dτ(W/r)] per unit ρ0V (×4π), W = 1/(1 − M_r).

    τ-derivatives at a fixed receiver point: R = x − y, Ṙ = −v, R̈ = −a, R⃛ = −jerk.
    """
    r = c0 * s
    inv_r = 1.0 / r
    inv_c = 1.0 / c0
    n0 = r0 * inv_r
    n1 = r1 * inv_r
    n2 = r2 * inv_r
    mr = (v0 * n0 + v1 * n1 + v2 * n2) * inv_c
    w = 1.0 / (1.0 - mr)
    w2 = w * w
    rdot = -mr * c0
    # d r̂/dτ = (Ṙ − ṙ r̂)/r
    h0 = (-v0 - rdot * n0) * inv_r
    h1 = (-v1 - rdot * n1) * inv_r
    h2 = (-v2 - rdot * n2) * inv_r
    rddot = (c0 * c0 * m2 - (r0 * a0 + r1 * a1 + r2 * a2) - rdot * rdot) * inv_r
    # d²r̂/dτ² = (R̈ − r̈ r̂ − 2 ṙ dr̂/dτ)/r
    g0 = (-a0 - rddot * n0 - 2.0 * rdot * h0) * inv_r
    g1 = (-a1 - rddot * n1 - 2.0 * rdot * h1) * inv_r
    g2 = (-a2 - rddot * n2 - 2.0 * rdot * h2) * inv_r
    mr_d = (a0 * n0 + a1 * n1 + a2 * n2 + v0 * h0 + v1 * h1 + v2 * h2) * inv_c
    mr_dd = (j0 * n0 + j1 * n1 + j2 * n2 + 2.0 * (a0 * h0 + a1 * h1 + a2 * h2) + v0 * g0 + v1 * g1 + v2 * g2) * inv_c
    wd = w2 * mr_d
    gq = w * inv_r
    rate = -rdot * inv_r + w * mr_d
    gd = gq * rate
    gdd = gd * rate + gq * (-rddot * inv_r + rdot * rdot * inv_r * inv_r + wd * mr_d + w * mr_dd)
    return w * (wd * gd + w * gdd)


@kernel
def _emit(row, col, obs, n_b, tb, pa, pb, monopole, surface, c0, rho0_vol):
    """Reception time and 4π × pressure of one source row at the n_b observers of a block.

    ``row``: packed source row (N_Q,); ``obs`` (7, block): the block's observers, rows x, y, z,
    vx, vy, vz (G) and 1/(c0² − v_o²). Compact F1A dipole (module docstring), written as
    W²/r · [ḟ_r/c0 + (f_r − f_M)/r + f_r W (Ṁ_r/c0 + (M_r − M²)/r)], W = 1/(1 − M_r);
    with ``monopole`` also ρ0V × :func:`_monopole` into pb; with ``surface`` the panel thickness term
    W²/r · [Q̇ + Q W (Ṁ_r + c0 (M_r − M²)/r)] into pb. Results go to row ``col`` of tb, pa, pb
    (shape (n_ext, block)). Loops over observers on 1-D rows so that they vectorise.
    """
    y0, y1, y2 = row[Q_POS], row[Q_POS + 1], row[Q_POS + 2]
    v0, v1, v2 = row[Q_VEL], row[Q_VEL + 1], row[Q_VEL + 2]
    a0, a1, a2 = row[Q_ACC], row[Q_ACC + 1], row[Q_ACC + 2]
    f0, f1, f2 = row[Q_FRC], row[Q_FRC + 1], row[Q_FRC + 2]
    e0, e1, e2 = row[Q_FRD], row[Q_FRD + 1], row[Q_FRD + 2]
    m2, fm, tau = row[Q_M2], row[Q_FM], row[Q_TAU]
    inv_c = 1.0 / c0
    ox, oy, oz, ovx, ovy, ovz, inv_a = obs[0], obs[1], obs[2], obs[3], obs[4], obs[5], obs[6]
    tb_row = tb[col]
    pa_row = pa[col]
    for b in range(n_b):
        t, s, r0, r1, r2 = _reception(y0, y1, y2, ox[b], oy[b], oz[b], ovx[b], ovy[b], ovz[b], tau, c0, inv_a[b])
        inv_r = 1.0 / (c0 * s)
        n0 = r0 * inv_r
        n1 = r1 * inv_r
        n2 = r2 * inv_r
        mr = (v0 * n0 + v1 * n1 + v2 * n2) * inv_c
        mdot_r = (a0 * n0 + a1 * n1 + a2 * n2) * inv_c
        w = 1.0 / (1.0 - mr)
        fr = f0 * n0 + f1 * n1 + f2 * n2
        fdr = e0 * n0 + e1 * n1 + e2 * n2
        tb_row[b] = t
        pa_row[b] = w * w * inv_r * (fdr * inv_c + (fr - fm) * inv_r + fr * w * (mdot_r * inv_c + (mr - m2) * inv_r))
    if monopole:
        j0, j1, j2 = row[Q_JERK], row[Q_JERK + 1], row[Q_JERK + 2]
        pb_row = pb[col]
        for b in range(n_b):
            t, s, r0, r1, r2 = _reception(y0, y1, y2, ox[b], oy[b], oz[b], ovx[b], ovy[b], ovz[b], tau, c0, inv_a[b])
            pb_row[b] = rho0_vol * _monopole(s, r0, r1, r2, v0, v1, v2, a0, a1, a2, j0, j1, j2, m2, c0)
    if surface:
        q, qd = row[Q_FLUX], row[Q_FLUXD]
        pb_row = pb[col]
        for b in range(n_b):
            t, s, r0, r1, r2 = _reception(y0, y1, y2, ox[b], oy[b], oz[b], ovx[b], ovy[b], ovz[b], tau, c0, inv_a[b])
            inv_r = 1.0 / (c0 * s)
            mr = (v0 * r0 + v1 * r1 + v2 * r2) * inv_r * inv_c
            mdot_r = (a0 * r0 + a1 * r1 + a2 * r2) * inv_r * inv_c
            w = 1.0 / (1.0 - mr)
            pb_row[b] = w * w * inv_r * (qd + q * w * (mdot_r + c0 * (mr - m2) * inv_r))


@kernel
def _divided_differences(tb, p, lo, hi, n_b, d1, d2, d3):
    """Newton divided differences of the samples (tb[j], p[j]), j = lo…hi−1, for n_b observers.

    d1[j] = p[t_j, t_j+1], d2[j] = p[t_j, t_j+1, t_j+2], d3[j] = p[t_j … t_j+3] (arrays (n_ext, block),
    computed where defined); the loops run over observers on 1-D rows so that they vectorise.
    """
    for j in range(lo, hi - 1):
        t0, t1, p0, p1, out = tb[j], tb[j + 1], p[j], p[j + 1], d1[j]
        for b in range(n_b):
            out[b] = (p1[b] - p0[b]) / (t1[b] - t0[b])
    for j in range(lo, hi - 2):
        t0, t2, e0, e1, out = tb[j], tb[j + 2], d1[j], d1[j + 1], d2[j]
        for b in range(n_b):
            out[b] = (e1[b] - e0[b]) / (t2[b] - t0[b])
    for j in range(lo, hi - 3):
        t0, t3, e0, e1, out = tb[j], tb[j + 3], d2[j], d2[j + 1], d3[j]
        for b in range(n_b):
            out[b] = (e1[b] - e0[b]) / (t3[b] - t0[b])


@kernel
def _interpolate_add(tb, p, d1, d2, d3, b, lo, hi, base, dt, count, row, off):
    """Add the cubic interpolant of (tb[:, b], p[:, b]), samples lo…hi−1, to ``row``.

    Targets t_q = base + q·dt, q < count, inside [tb[lo], tb[hi−1]], added at row[off + q].
    A target between tb[j] and tb[j+1] uses the cubic through the four nodes j−1…j+2 (shifted
    inward at the ends; the last interval also takes targets past its end), evaluated in Newton
    form from the divided differences of :func:`_divided_differences`.
    """
    q = 0
    t = base
    for j in range(lo, hi - 1):
        if q >= count:
            break
        t_next = tb[j + 1, b]
        last = j == hi - 2
        if t >= t_next and not last:
            continue
        k = min(max(j - 1, lo), hi - 4)
        x0 = tb[k, b]
        x1 = tb[k + 1, b]
        x2 = tb[k + 2, b]
        c0 = p[k, b]
        c1 = d1[k, b]
        c2 = d2[k, b]
        c3 = d3[k, b]
        while q < count and (t < t_next or last):
            row[off + q] += c0 + (t - x0) * (c1 + (t - x1) * (c2 + (t - x2) * c3))
            q += 1
            t = base + q * dt


@kernel(parallel=True)
def _coverage(pos, tau, xo, vo, c0):
    """Per observer: [latest first reception, earliest last reception] over all nodes (s)."""
    n_obs = xo.shape[0]
    n_node = pos.shape[0]
    last = pos.shape[1] - 1
    out = np.empty((n_obs, 2))
    for o in prange(n_obs):
        inv_a = 1.0 / (c0 * c0 - (vo[o, 0] ** 2 + vo[o, 1] ** 2 + vo[o, 2] ** 2))
        lo = -np.inf
        hi = np.inf
        for i in range(n_node):
            t0 = _reception(pos[i, 0, 0], pos[i, 0, 1], pos[i, 0, 2], xo[o, 0], xo[o, 1], xo[o, 2], vo[o, 0], vo[o, 1], vo[o, 2], tau[0], c0, inv_a)[0]
            t1 = _reception(pos[i, last, 0], pos[i, last, 1], pos[i, last, 2], xo[o, 0], xo[o, 1], xo[o, 2], vo[o, 0], vo[o, 1], vo[o, 2], tau[last], c0, inv_a)[0]
            lo = max(lo, t0)
            hi = min(hi, t1)
        out[o, 0] = lo
        out[o, 1] = hi
    return out


@kernel
def _observer_block(xo, vo, o_first, n_b, c0):
    """The block's observers as rows (7, OBSERVER_BLOCK): x, y, z, vx, vy, vz (G, m and m/s) and
    1/(c0² − v_o²) (s²/m²), for the n_b observers from index ``o_first`` of xo, vo (n_obs, 3)."""
    obs = np.zeros((7, OBSERVER_BLOCK))
    for b in range(n_b):
        for c in range(3):
            obs[c, b] = xo[o_first + b, c]
            obs[3 + c, b] = vo[o_first + b, c]
        obs[6, b] = 1.0 / (c0 * c0 - (obs[3, b] ** 2 + obs[4, b] ** 2 + obs[5, b] ** 2))
    return obs


@kernel
def _direct_window(node, obs, n_b, c0, t_first, t_end, pad, tb, lo, hi):
    """Direct mode: reception times tb[j, b] (s) of every source step j of one node (packed rows (n_tau, N_Q))
    at the block's observers, and per observer the steps [lo[b], hi[b]) whose cubic stencils cover the
    window [t_first, t_end] (at least 4, ``pad`` extra on each side). Returns the union (j_lo, j_hi)."""
    n_tau = node.shape[0]
    for j in range(n_tau):
        for b in range(n_b):
            tb[j, b] = _reception(node[j, Q_POS], node[j, Q_POS + 1], node[j, Q_POS + 2], obs[0, b], obs[1, b],
                                  obs[2, b], obs[3, b], obs[4, b], obs[5, b], node[j, Q_TAU], c0, obs[6, b])[0]
    j_lo = n_tau
    j_hi = 0
    for b in range(n_b):
        first = 0
        while first < n_tau - 1 and tb[first + 1, b] <= t_first:
            first += 1
        stop = n_tau
        while stop > first + 1 and tb[stop - 2, b] >= t_end:
            stop -= 1
        first = max(first - pad, 0)
        stop = min(stop + pad, n_tau)
        if stop - first < 4:
            first = max(0, min(first, n_tau - 4))
            stop = first + 4
        lo[b] = first
        hi[b] = stop
        j_lo = min(j_lo, first)
        j_hi = max(j_hi, stop)
    return j_lo, j_hi


@kernel
def _periodic_extension(tb, pa, pb, n_tau, pad, n_b, period):
    """Periodic mode: samples j = pad … pad+n_tau−1 of (tb, pa, pb) (n_ext, block) are one period (s);
    copy them ``pad`` steps before and ``pad + 1`` after, shifted by ∓period in time."""
    for q in range(pad):
        for b in range(n_b):
            tb[q, b] = tb[n_tau + q, b] - period
            pa[q, b] = pa[n_tau + q, b]
            pb[q, b] = pb[n_tau + q, b]
    for q in range(pad + 1):
        for b in range(n_b):
            tb[n_tau + pad + q, b] = tb[pad + q, b] + period
            pa[n_tau + pad + q, b] = pa[pad + q, b]
            pb[n_tau + pad + q, b] = pb[pad + q, b]


@kernel
def _fold_block(buf, out, o_first, n_b):
    """Fold the unwrapped block buffer buf (block, n_groups, 2·n_out) of 4π·p into the output
    out (n_obs, n_groups, n_out) in Pa: out[o] = (buf[k] + buf[k + n_out]) / 4π."""
    n_groups, n_out = out.shape[1], out.shape[2]
    for b in range(n_b):
        for g in range(n_groups):
            for k in range(n_out):
                out[o_first + b, g, k] = (buf[b, g, k] + buf[b, g, k + n_out]) * (1.0 / (4.0 * np.pi))


@kernel(parallel=True)
def _radiate_kernel(src, vol, surf, gdip, gmono, n_groups, xo, vo, c0, rho0, t_first, dt, n_out, period):
    """Pressure (Pa, shape (n_obs, n_groups, n_out)) of all nodes at every observer.

    ``src``: packed sources (n_node, n_tau, N_Q), see :func:`_pack_sources`; ``vol`` (n_node,) m³;
    ``surf`` (n_node,) bool: the node carries a surface-panel mass flux;
    ``gdip``, ``gmono`` (n_node,) output group of each node's dipole / monopole part (−1: none);
    ``xo``, ``vo`` (n_obs, 3) observer position at t = 0 (m) and velocity (m/s), G; c0 (m/s), rho0 (kg/m³).
    period <= 0: direct mode, targets t_first + k·dt (s), F1A evaluated only on the source steps the window
    needs. period > 0: the samples are one period and the output is that periodic signal at
    t_first + k·dt (mod period), dt = period/n_out; the samples are extended periodically by
    two steps on each side so every target has a centred stencil.

    Parallel over blocks of OBSERVER_BLOCK observers: each source row is read once per block,
    the block's per-observer signals accumulate in an unwrapped buffer of 2·n_out samples per
    group (a periodic target index never exceeds 2·n_out) that is folded into the output.
    """
    n_obs = xo.shape[0]
    n_node, n_tau = src.shape[0], src.shape[1]
    out = np.zeros((n_obs, n_groups, n_out))
    pad = 2
    n_ext = n_tau + 2 * pad + 1
    t_end = t_first + (n_out - 1) * dt
    n_blocks = (n_obs + OBSERVER_BLOCK - 1) // OBSERVER_BLOCK
    for blk in prange(n_blocks):
        o_first = blk * OBSERVER_BLOCK
        n_b = min(OBSERVER_BLOCK, n_obs - o_first)
        obs = _observer_block(xo, vo, o_first, n_b, c0)
        tb = np.empty((n_ext, OBSERVER_BLOCK))
        pa = np.zeros((n_ext, OBSERVER_BLOCK))
        pb = np.zeros((n_ext, OBSERVER_BLOCK))
        d1a = np.zeros((n_ext, OBSERVER_BLOCK))
        d2a = np.zeros((n_ext, OBSERVER_BLOCK))
        d3a = np.zeros((n_ext, OBSERVER_BLOCK))
        d1b = np.zeros((n_ext, OBSERVER_BLOCK))
        d2b = np.zeros((n_ext, OBSERVER_BLOCK))
        d3b = np.zeros((n_ext, OBSERVER_BLOCK))
        buf = np.zeros((OBSERVER_BLOCK, n_groups, 2 * n_out))
        lo = np.empty(OBSERVER_BLOCK, dtype=np.int64)
        hi = np.empty(OBSERVER_BLOCK, dtype=np.int64)
        for i in range(n_node):
            has_a = gdip[i] >= 0
            compact = vol[i] != 0.0
            has_b = gmono[i] >= 0 and (compact or surf[i])
            if not has_a and not has_b:
                continue
            ga = max(gdip[i], 0)
            gb = max(gmono[i], 0)
            if period <= 0.0:
                # reception times first (cheap), then F1A only where some observer's window needs it
                j_lo, j_hi = _direct_window(src[i], obs, n_b, c0, t_first, t_end, pad, tb, lo, hi)
                for j in range(j_lo, j_hi):
                    _emit(src[i, j], j, obs, n_b, tb, pa, pb, has_b and compact, has_b and surf[i], c0, rho0 * vol[i])
            else:
                for j in range(n_tau):
                    _emit(src[i, j], j + pad, obs, n_b, tb, pa, pb, has_b and compact, has_b and surf[i], c0, rho0 * vol[i])
                _periodic_extension(tb, pa, pb, n_tau, pad, n_b, period)
                j_lo = 0
                j_hi = n_ext
                lo[:] = j_lo
                hi[:] = j_hi
            if has_a:
                _divided_differences(tb, pa, j_lo, j_hi, n_b, d1a, d2a, d3a)
            if has_b:
                _divided_differences(tb, pb, j_lo, j_hi, n_b, d1b, d2b, d3b)
            for b in range(n_b):
                base = t_first
                off = 0
                if period > 0.0:
                    m0 = int(np.ceil((tb[pad, b] - t_first) / dt))
                    base = t_first + m0 * dt
                    off = m0 % n_out
                if has_a:
                    _interpolate_add(tb, pa, d1a, d2a, d3a, b, lo[b], hi[b], base, dt, n_out, buf[b, ga], off)
                if has_b:
                    _interpolate_add(tb, pb, d1b, d2b, d3b, b, lo[b], hi[b], base, dt, n_out, buf[b, gb], off)
        _fold_block(buf, out, o_first, n_b)
    return out


# ----------------------------------------------------------------------------------------------
# drivers
# ----------------------------------------------------------------------------------------------
def _check_speeds(sources: CompactSources, observers: Observers, c0: float) -> None:
    speed = np.linalg.norm(sources.velocity_mps, axis=-1).max(axis=1)
    if (speed >= c0).any():
        node = int(np.argmax(speed))
        raise AcousticsError(f"sources: node {node} reaches Mach {speed[node] / c0:.3f}; compact F1A needs subsonic sources")
    v_obs = np.linalg.norm(observers.velocity_mps, axis=1)
    if (v_obs >= c0).any():
        raise AcousticsError(f"observers: observer {int(np.argmax(v_obs))} moves at or above c0")


def _pack_sources(sources: CompactSources, c0: float, period: float):
    """Kernel arguments: packed rows (n_node, n_tau, N_Q), volumes, surface-panel flags, group indices, group count.

    A row holds y, v, a, f, ḟ, jerk (G), M² = |v|²/c0², f_M = f·v/c0, the source time τ_j
    (periodic sources: τ_0 + j·T/n_tau) and the mass flux Q and its rate (0 without).
    """
    n_node, n_tau = sources.position_m.shape[:2]
    src = np.empty((n_node, n_tau, N_Q))
    for q, value in ((Q_POS, sources.position_m), (Q_VEL, sources.velocity_mps), (Q_ACC, sources.acceleration_mps2),
                     (Q_FRC, sources.force_N), (Q_FRD, sources.force_rate_N_s), (Q_JERK, sources.jerk_mps3)):
        src[:, :, q:q + 3] = value
    vel = src[:, :, Q_VEL:Q_VEL + 3]
    src[:, :, Q_M2] = np.einsum("ijk,ijk->ij", vel, vel) / (c0 * c0)
    src[:, :, Q_FM] = np.einsum("ijk,ijk->ij", src[:, :, Q_FRC:Q_FRC + 3], vel) / c0
    tau = np.asarray(sources.time_s, dtype=float)
    src[:, :, Q_TAU] = tau[0] + np.arange(n_tau) * (period / n_tau) if period > 0 else tau
    if sources.mass_flux_kg_s is None:
        src[:, :, Q_FLUX:Q_FLUXD + 1] = 0.0
        surface = np.zeros(n_node, dtype=np.bool_)
    else:
        src[:, :, Q_FLUX] = sources.mass_flux_kg_s
        src[:, :, Q_FLUXD] = sources.mass_flux_rate_kg_s2
        surface = np.any(sources.mass_flux_kg_s != 0.0, axis=1) | np.any(sources.mass_flux_rate_kg_s2 != 0.0, axis=1)
    return (
        src,
        np.ascontiguousarray(sources.volume_m3, dtype=float),
        surface,
        np.ascontiguousarray(sources.dipole_group, dtype=np.int64),
        np.ascontiguousarray(sources.monopole_group, dtype=np.int64),
        len(sources.groups),
    )


def covered_interval(sources: CompactSources, observers: Observers, c0_mps: float = C0_MPS) -> np.ndarray:
    """(n_obs, 2): observer-time interval (s) that every source node covers at each observer."""
    pos = np.ascontiguousarray(sources.position_m, dtype=float)
    return _coverage(pos, np.asarray(sources.time_s, float), observers.position_m.astype(float),
                     observers.velocity_mps.astype(float), float(c0_mps))


def radiate_arrays(sources: CompactSources, observers: Observers, grid: TimeGrid, *,
                   c0_mps: float = C0_MPS, rho0_kg_m3: float = RHO0_KG_M3) -> np.ndarray:
    """Acoustic pressure (Pa), shape (n_obs, n_groups, n_samples), groups as ``sources.groups``.

    Non-periodic sources: every observer's window must be covered by the retarded source
    times, else :class:`AcousticsError` names the first observer and the uncovered interval.
    Periodic sources (``period_s`` set): observers must move with ``frame_velocity_mps``; the
    result is the sum over the ``copies`` blades, resampled onto ``grid`` (see module doc).
    """
    if grid.n_samples < 1 or not grid.duration_s > 0:
        raise AcousticsError(f"time grid: need n_samples >= 1 and duration > 0, got {grid}")
    _check_speeds(sources, observers, c0_mps)
    xo = np.ascontiguousarray(observers.position_m, dtype=float)
    vo = np.ascontiguousarray(observers.velocity_mps, dtype=float)
    tau = np.ascontiguousarray(sources.time_s, dtype=float)
    if sources.period_s is None:
        dtau = np.diff(tau)
        if not np.allclose(dtau, dtau[0], rtol=1e-9, atol=0.0) or dtau[0] <= 0:
            raise AcousticsError("sources: source times must be uniform and increasing")
        cover = covered_interval(sources, observers, c0_mps)
        t_last = grid.t_start_s + (grid.n_samples - 1) * grid.dt_s
        bad = np.nonzero((cover[:, 0] > grid.t_start_s + 1e-12 * abs(grid.t_start_s)) | (cover[:, 1] < t_last))[0]
        if bad.size:
            o = int(bad[0])
            raise AcousticsError(
                f"observer {o}: the sources cover observer times [{cover[o, 0]:.6g}, {cover[o, 1]:.6g}] s but the "
                f"window needs [{grid.t_start_s:.6g}, {t_last:.6g}] s ({bad.size} observer(s) uncovered); extend the source times")
        return _radiate_kernel(*_pack_sources(sources, float(c0_mps), 0.0), xo, vo, float(c0_mps), float(rho0_kg_m3),
                               float(grid.t_start_s), float(grid.dt_s), int(grid.n_samples), 0.0)
    if not np.allclose(vo, sources.frame_velocity_mps[None, :], rtol=0.0, atol=1e-9 * c0_mps):
        raise AcousticsError("observers: periodic (one-blade, one-period) sources need observers moving with the "
                             f"aircraft velocity {sources.frame_velocity_mps.tolist()} m/s; use non-periodic sources")
    period = float(sources.period_s)
    n_per = periodic_samples(period, grid)
    one = _radiate_kernel(*_pack_sources(sources, float(c0_mps), period), xo, vo, float(c0_mps), float(rho0_kg_m3),
                          float(grid.t_start_s), period / n_per, n_per, period)
    return fourier_resample(one, period, grid, copies=sources.copies)


def periodic_samples(period_s: float, grid: TimeGrid) -> int:
    """Samples per source period: even, at least the grid's density (and at least 8)."""
    density = grid.n_samples / grid.duration_s
    return max(8, 2 * int(np.ceil(0.5 * period_s * density - 1e-9)))


def fourier_resample(one_period: np.ndarray, period_s: float, grid: TimeGrid, copies: int = 1) -> np.ndarray:
    """Evaluate a periodic signal, sampled at grid.t_start_s + m·T/M (last axis), on ``grid``.

    The sum of ``copies`` identical signals shifted by T/copies keeps only harmonics that are
    multiples of ``copies``, times ``copies`` (exact). Band-limited (trigonometric) evaluation.
    """
    m_samples = one_period.shape[-1]
    spec = np.fft.rfft(one_period, axis=-1) / m_samples
    n = np.arange(spec.shape[-1])
    weight = np.where((n == 0) | ((m_samples % 2 == 0) & (n == m_samples // 2)), 1.0, 2.0)
    keep = n % copies == 0
    spec = spec[..., keep] * (weight[keep] * copies)
    n = n[keep]
    phase = 2.0 * np.pi * np.outer(n, grid.times_s - grid.t_start_s) / period_s
    flat = spec.reshape(-1, n.size)
    out = flat.real @ np.cos(phase) - flat.imag @ np.sin(phase)
    return out.reshape(one_period.shape[:-1] + (grid.n_samples,))


# ----------------------------------------------------------------------------------------------
# long-format tables (CLI and Python API)
# ----------------------------------------------------------------------------------------------


def fd_weights(offsets: np.ndarray, order: int) -> np.ndarray:
    """Finite-difference weights (unit step) of the ``order``-th derivative at 0 on ``offsets``."""
    offsets = np.asarray(offsets, dtype=float)
    k = np.arange(offsets.size)
    vander = offsets[None, :] ** k[:, None]
    rhs = np.zeros(offsets.size)
    rhs[order] = float(np.prod(np.arange(1, order + 1)))
    return np.linalg.solve(vander, rhs)


def time_derivative(values: np.ndarray, dt: float, axis: int = 1, points: int = 7) -> np.ndarray:
    """d/dτ of samples on a uniform grid: ``points``-point (6th order) Lagrange differences.

    Central stencils inside, one-sided stencils of the same width near the ends.
    """
    values = np.moveaxis(np.asarray(values, dtype=float), axis, 0)
    n = values.shape[0]
    if n < points:
        raise AcousticsError(f"sources: need at least {points} source times for derivatives, got {n}")
    half = points // 2
    out = np.empty_like(values)
    for start_shift in range(points):
        # rows whose stencil starts ``start_shift`` before them
        if start_shift == half:
            rows = np.arange(half, n - half)
        elif start_shift < half:
            rows = np.array([start_shift])
        else:
            rows = np.array([n - points + start_shift])
        w = fd_weights(np.arange(points) - start_shift, 1)
        acc = np.zeros((rows.size,) + values.shape[1:])
        for q in range(points):
            acc += w[q] * values[rows - start_shift + q]
        out[rows] = acc / dt
    return np.moveaxis(out, 0, axis)
