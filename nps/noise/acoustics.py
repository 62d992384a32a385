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

Implementation (numba, float64, no fastmath, no reassociation: every value is the same IEEE operation
sequence as the per-observer formulation, bit for bit): sources are stored as one contiguous row of
source steps per (node, quantity), with the source-only quantities (M², f·M) precomputed. Observers
are processed in blocks of ``OBSERVER_BLOCK`` (parallel over blocks); within a block, node after node
and observer after observer, every loop runs over source steps or targets with unit stride, which LLVM
vectorises: the reception times, the F1A integrand, the Newton divided differences, each interval's
first target (an estimate checked against the targets' own rounded times), the cubic at up to n targets
per interval (one loop over intervals per slot) and the scatter of those values into target order,
added to the observer's buffer. A signal whose interval holds more than ``MAX_SLOTS`` targets, or whose
reception times do not check, takes the scalar walk over targets (:func:`_interpolate_walk`), the
reference of the vectorised path. Sums run in the same order whatever the block
(tests/unit/test_acoustics_reference.py pins the output to a scalar reference, ``np.array_equal``).

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

from nps.core.jit import kernel, kernel_array, prange

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
# Source layout: one contiguous row of n_tau float64 per (node, quantity) (see :func:`_pack_sources`), so that
# every per-observer loop runs over the source steps with unit stride and LLVM vectorises it.
S_POS, S_VEL, S_ACC, S_FRC, S_FRD, S_JERK, S_M2, S_FM, S_FLUX, S_FLUXD = 0, 3, 6, 9, 12, 15, 18, 19, 20, 21
N_S = 22
# Observers per parallel block: a node's source rows are read from cache by the block's observers, one after
# the other, and the block is the unit of the parallel partition (nps.app.resources sizes a job's threads by it).
OBSERVER_BLOCK = 16
# Most targets a source interval may hold on the vectorised interpolation path (:func:`_interpolate_signal`);
# a signal with more (a very fine target grid) takes the scalar walk of :func:`_interpolate_walk`.
MAX_SLOTS = 16
PAD = 2  # periodic mode: samples copied before (PAD) and after (PAD + 1) one period


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
def _receive(node, xp, ov, inv_a, tau, lo, hi, shift, rs, tb):
    """Reception of the source steps lo…hi−1 of one node (rows (N_S, n_tau)) at one observer, position xp (3,) (m) at
    t = 0, velocity ov (3,) (m/s), inv_a = 1/(c0² − v_o²): rs[j] = s = t − τ_j (s), tb[shift + j] = t (s). The
    arithmetic of :func:`_reception`, in a loop over source steps of its own (vectorised; the loops of the F1A
    terms recompute r = x(t) − y, :func:`_radiation_vector`: two short dependency chains, each writing one or two
    arrays, run faster than one long loop)."""
    ox, oy, oz = ov[0], ov[1], ov[2]
    x0, x1, x2 = xp[0], xp[1], xp[2]
    for j in range(lo, hi):
        d0 = x0 + ox * tau[j] - node[S_POS, j]
        d1 = x1 + oy * tau[j] - node[S_POS + 1, j]
        d2 = x2 + oz * tau[j] - node[S_POS + 2, j]
        dv = d0 * ox + d1 * oy + d2 * oz
        dd = d0 * d0 + d1 * d1 + d2 * d2
        s = (dv + np.sqrt(dv * dv + dd / inv_a)) * inv_a
        rs[j] = s
        tb[shift + j] = tau[j] + s


@kernel(inline=True)
def _radiation_vector(node, xp, ov, tau, s, j):
    """r = x(t) − y (m) of source step j received after s (:func:`_receive`), as :func:`_reception` computes it."""
    return (xp[0] + ov[0] * tau[j] - node[S_POS, j] + ov[0] * s,
            xp[1] + ov[1] * tau[j] - node[S_POS + 1, j] + ov[1] * s,
            xp[2] + ov[2] * tau[j] - node[S_POS + 2, j] + ov[2] * s)


@kernel
def _dipole(node, xp, ov, tau, rs, lo, hi, shift, c0, p):
    """Compact F1A dipole (4π p) of source steps lo…hi−1 into p[shift + j]: with W = 1/(1 − M_r),
    W²/r · [ḟ_r/c0 + (f_r − f_M)/r + f_r W (Ṁ_r/c0 + (M_r − M²)/r)] (module docstring)."""
    inv_c = 1.0 / c0
    for j in range(lo, hi):
        s = rs[j]
        r0, r1, r2 = _radiation_vector(node, xp, ov, tau, s, j)
        inv_r = 1.0 / (c0 * s)
        n0 = r0 * inv_r
        n1 = r1 * inv_r
        n2 = r2 * inv_r
        mr = (node[S_VEL, j] * n0 + node[S_VEL + 1, j] * n1 + node[S_VEL + 2, j] * n2) * inv_c
        mdot_r = (node[S_ACC, j] * n0 + node[S_ACC + 1, j] * n1 + node[S_ACC + 2, j] * n2) * inv_c
        w = 1.0 / (1.0 - mr)
        fr = node[S_FRC, j] * n0 + node[S_FRC + 1, j] * n1 + node[S_FRC + 2, j] * n2
        fdr = node[S_FRD, j] * n0 + node[S_FRD + 1, j] * n1 + node[S_FRD + 2, j] * n2
        p[shift + j] = w * w * inv_r * (fdr * inv_c + (fr - node[S_FM, j]) * inv_r
                                        + fr * w * (mdot_r * inv_c + (mr - node[S_M2, j]) * inv_r))


@kernel
def _monopole_signal(node, xp, ov, tau, rs, lo, hi, shift, c0, rho0_vol, p):
    """Compact thickness monopole, ρ0V × :func:`_monopole`, of source steps lo…hi−1 into p[shift + j]."""
    for j in range(lo, hi):
        r0, r1, r2 = _radiation_vector(node, xp, ov, tau, rs[j], j)
        p[shift + j] = rho0_vol * _monopole(rs[j], r0, r1, r2, node[S_VEL, j], node[S_VEL + 1, j],
                                            node[S_VEL + 2, j], node[S_ACC, j], node[S_ACC + 1, j], node[S_ACC + 2, j],
                                            node[S_JERK, j], node[S_JERK + 1, j], node[S_JERK + 2, j], node[S_M2, j], c0)


@kernel
def _surface_signal(node, xp, ov, tau, rs, lo, hi, shift, c0, p):
    """Surface-panel thickness term W²/r · [Q̇ + Q W (Ṁ_r + c0 (M_r − M²)/r)] of source steps lo…hi−1 into
    p[shift + j]."""
    inv_c = 1.0 / c0
    for j in range(lo, hi):
        s = rs[j]
        r0, r1, r2 = _radiation_vector(node, xp, ov, tau, s, j)
        inv_r = 1.0 / (c0 * s)
        mr = (node[S_VEL, j] * r0 + node[S_VEL + 1, j] * r1 + node[S_VEL + 2, j] * r2) * inv_r * inv_c
        mdot_r = (node[S_ACC, j] * r0 + node[S_ACC + 1, j] * r1 + node[S_ACC + 2, j] * r2) * inv_r * inv_c
        w = 1.0 / (1.0 - mr)
        p[shift + j] = w * w * inv_r * (node[S_FLUXD, j]
                                        + node[S_FLUX, j] * w * (mdot_r + c0 * (mr - node[S_M2, j]) * inv_r))


@kernel
def _divided_differences(tb, p, lo, hi, d1, d2, d3):
    """Newton divided differences of the samples (tb[j], p[j]), j = lo…hi−1: d1[j] = p[t_j, t_j+1],
    d2[j] = p[t_j, t_j+1, t_j+2], d3[j] = p[t_j … t_j+3] (where defined)."""
    for j in range(lo, hi - 1):
        d1[j] = (p[j + 1] - p[j]) / (tb[j + 1] - tb[j])
    for j in range(lo, hi - 2):
        d2[j] = (d1[j + 1] - d1[j]) / (tb[j + 2] - tb[j])
    for j in range(lo, hi - 3):
        d3[j] = (d2[j + 1] - d2[j]) / (tb[j + 3] - tb[j])


@kernel
def _target_bounds(tb, base, dt, count, lo, hi, qs):
    """First target of every source interval: targets t_q = base + q·dt, q < count, go to the first interval
    j ≥ lo with t_q < tb[j+1], the last interval (hi − 2) taking the rest (the rule of :func:`_interpolate_walk`).
    qs[j] (float, an integer) is the first target of interval j, qs[hi − 1] = count. Returns the most targets of
    an interval, or −1 (the caller walks instead) unless every boundary checks exactly and they do not decrease.

    The first target at or after tb[j] is estimated as ⌈(tb[j] − base)/dt⌉ (clipped to 0…count) and checked
    against the targets' own rounded times, t_{q−1} < tb[j] ≤ t_q: the estimate is off only when tb[j] lies within a
    few ulps of a target time (or is not finite), and then the check fails."""
    inv_dt = 1.0 / dt
    fcount = float(count)
    bad = 0
    for j in range(lo + 1, hi - 1):
        tn = tb[j]
        e = min(max(np.ceil((tn - base) * inv_dt), 0.0), fcount)
        bad += not (((e == 0.0) | (base + (e - 1.0) * dt < tn)) & ((e == fcount) | (base + e * dt >= tn)))
        qs[j] = e
    qs[lo] = 0.0
    qs[hi - 1] = fcount
    most = np.int32(0)
    for j in range(lo, hi - 1):
        n = np.int32(qs[j + 1] - qs[j])
        bad += n < 0
        most = max(most, n)
    return -1 if bad else int(most)


@kernel
def _cubic_slots(tb, p, d1, d2, d3, qs, base, dt, lo, hi, n_slots, v):
    """v[r, j]: the cubic of interval j (Newton form, nodes j−1…j+2 shifted inward at the ends, as
    :func:`_interpolate_walk`) at target qs[j] + r, r < n_slots, for every interval (one vectorised loop per r)."""
    for r in range(n_slots):
        fr = float(r)
        row = v[r]
        for j in range(lo + 1, hi - 2):
            t = base + (qs[j] + fr) * dt
            row[j] = p[j - 1] + (t - tb[j - 1]) * (d1[j - 1] + (t - tb[j]) * (d2[j - 1] + (t - tb[j + 1]) * d3[j - 1]))
        for j in (lo, hi - 2):
            k = min(max(j - 1, lo), hi - 4)
            t = base + (qs[j] + fr) * dt
            row[j] = p[k] + (t - tb[k]) * (d1[k] + (t - tb[k + 1]) * (d2[k] + (t - tb[k + 2]) * d3[k]))


@kernel
def _scatter_slots(v, qs, lo, hi, n_slots, vals):
    """vals[q] = the value of target q: slot r of interval j is written to vals[qs[j] + r], intervals in increasing
    order, so the last write of a target is that of its own interval (the slots past an interval's targets belong
    to later intervals, which overwrite them, or lie past the last target). Unsigned indices: no wrap-around test."""
    if n_slots <= 4:
        v0, v1, v2, v3 = v[0], v[1], v[2], v[3]
        for j in range(lo, hi - 1):
            q = np.uint64(qs[j])
            vals[q] = v0[j]
            vals[q + np.uint64(1)] = v1[j]
            vals[q + np.uint64(2)] = v2[j]
            vals[q + np.uint64(3)] = v3[j]
    elif n_slots <= 6:
        v0, v1, v2, v3, v4, v5 = v[0], v[1], v[2], v[3], v[4], v[5]
        for j in range(lo, hi - 1):
            q = np.uint64(qs[j])
            vals[q] = v0[j]
            vals[q + np.uint64(1)] = v1[j]
            vals[q + np.uint64(2)] = v2[j]
            vals[q + np.uint64(3)] = v3[j]
            vals[q + np.uint64(4)] = v4[j]
            vals[q + np.uint64(5)] = v5[j]
    else:
        for j in range(lo, hi - 1):
            q = int(qs[j])
            for r in range(n_slots):
                vals[q + r] = v[r, j]


@kernel
def _accumulate(vals, row, count):
    """row[q] += vals[q], q < count."""
    for q in range(count):
        row[q] += vals[q]


@kernel
def _interpolate_walk(tb, p, d1, d2, d3, lo, hi, base, dt, count, row):
    """Add the cubic interpolant of (tb, p), samples lo…hi−1, at targets t_q = base + q·dt, q < count, to row[q].

    A target between tb[j] and tb[j+1] uses the cubic through the four nodes j−1…j+2 (shifted inward at the ends;
    the last interval also takes targets past its end), in Newton form from the divided differences. The scalar
    reference of the vectorised path (:func:`_target_bounds`, :func:`_cubic_slots`, :func:`_scatter_slots`)."""
    q = 0
    t = base
    for j in range(lo, hi - 1):
        if q >= count:
            break
        t_next = tb[j + 1]
        last = j == hi - 2
        if t >= t_next and not last:
            continue
        k = min(max(j - 1, lo), hi - 4)
        x0 = tb[k]
        x1 = tb[k + 1]
        x2 = tb[k + 2]
        c0 = p[k]
        c1 = d1[k]
        c2 = d2[k]
        c3 = d3[k]
        while q < count and (t < t_next or last):
            row[q] += c0 + (t - x0) * (c1 + (t - x1) * (c2 + (t - x2) * c3))
            q += 1
            t = base + q * dt


@kernel
def _interpolate_signal(tb, p, lo, hi, base, dt, count, row, d1, d2, d3, qs, v, vals):
    """Add the cubic interpolant of the samples (tb[j], p[j]), j = lo…hi−1, at t_q = base + q·dt, q < count, to
    row[q]: divided differences, every target's interval (:func:`_target_bounds`), the cubic at up to n targets per
    interval (vectorised over intervals), the values in target order, added to row. Same arithmetic as the walk
    of :func:`_interpolate_walk`, which takes over when an interval holds more than MAX_SLOTS targets."""
    _divided_differences(tb, p, lo, hi, d1, d2, d3)
    n = _target_bounds(tb, base, dt, count, lo, hi, qs)
    if n < 0 or n > MAX_SLOTS:
        _interpolate_walk(tb, p, d1, d2, d3, lo, hi, base, dt, count, row)
        return
    _cubic_slots(tb, p, d1, d2, d3, qs, base, dt, lo, hi, n, v)
    _scatter_slots(v, qs, lo, hi, n, vals)
    _accumulate(vals, row, count)


@kernel
def _direct_window(tb, n_tau, t_first, t_end):
    """Direct mode: the source steps [lo, hi) whose cubic stencils cover the window [t_first, t_end] at one
    observer, reception times tb (at least 4 steps, PAD extra on each side)."""
    first = 0
    while first < n_tau - 1 and tb[first + 1] <= t_first:
        first += 1
    stop = n_tau
    while stop > first + 1 and tb[stop - 2] >= t_end:
        stop -= 1
    first = max(first - PAD, 0)
    stop = min(stop + PAD, n_tau)
    if stop - first < 4:
        first = max(0, min(first, n_tau - 4))
        stop = first + 4
    return first, stop


@kernel
def _periodic_extension(tb, pa, pb, n_tau, period):
    """Periodic mode: samples PAD … PAD+n_tau−1 are one period (s); copy them PAD steps before and PAD + 1 after,
    shifted by ∓period in time."""
    for q in range(PAD):
        tb[q] = tb[n_tau + q] - period
        pa[q] = pa[n_tau + q]
        pb[q] = pb[n_tau + q]
    for q in range(PAD + 1):
        tb[n_tau + PAD + q] = tb[PAD + q] + period
        pa[n_tau + PAD + q] = pa[PAD + q]
        pb[n_tau + PAD + q] = pb[PAD + q]


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
def _observer_block(xo, vo, o_first, n_b, c0, xp, ov, inv_a):
    """The block's observers: position at t = 0 into xp (n_b, 3) (m, G), velocity into ov (n_b, 3) (m/s) and
    1/(c0² − v_o²) into inv_a (s²/m²), for the n_b observers from index ``o_first`` of xo, vo (n_obs, 3). Block-local
    copies: views of them made in the node loop touch no reference count shared with the other threads."""
    for b in range(n_b):
        o = o_first + b
        inv_a[b] = 1.0 / (c0 * c0 - (vo[o, 0] ** 2 + vo[o, 1] ** 2 + vo[o, 2] ** 2))
        for c in range(3):
            ov[b, c] = vo[o, c]
            xp[b, c] = xo[o, c]


@kernel
def _node_signals(node, kind, rho0_vol, xp, ov, tau, rs, lo, hi, shift, c0, pa, pb):
    """4π p of source steps lo…hi−1 of one node at one observer (position xp at t = 0, velocity ov, s = t − τ_j in
    rs) into pa[shift + j] (dipole) and pb[shift + j] (compact monopole or surface panel), as ``kind`` = (dipole,
    monopole, panel) says."""
    has_a, mono, panel = kind
    if has_a:
        _dipole(node, xp, ov, tau, rs, lo, hi, shift, c0, pa)
    if mono:
        _monopole_signal(node, xp, ov, tau, rs, lo, hi, shift, c0, rho0_vol, pb)
    if panel:
        _surface_signal(node, xp, ov, tau, rs, lo, hi, shift, c0, pb)


@kernel
def _radiate_periodic(node, kind, rho0_vol, xp, ov, inv_a, tau, c0, t_first, dt, n_out, period, out_a, out_b, work):
    """Periodic mode: 4π p of one node at one observer over one period, added to its output rows out_a (dipole)
    and out_b (monopole or panel) of 2·n_out unwrapped samples from the first target after the node's first
    reception. ``kind``: (dipole, compact monopole, surface panel) flags; ``ov``: observer velocity (3,);
    ``work``: scratch (rs, tb, pa, pb, d1, d2, d3, qs, slots, vals)."""
    rs, tb, pa, pb, d1, d2, d3, qs, v, vals = work
    n_tau = tau.size
    _receive(node, xp, ov, inv_a, tau, 0, n_tau, PAD, rs, tb)
    _node_signals(node, kind, rho0_vol, xp, ov, tau, rs, 0, n_tau, PAD, c0, pa, pb)
    _periodic_extension(tb, pa, pb, n_tau, period)
    n_ext = n_tau + 2 * PAD + 1
    m0 = int(np.ceil((tb[PAD] - t_first) / dt))
    base = t_first + m0 * dt
    off = m0 % n_out
    if kind[0]:
        _interpolate_signal(tb, pa, 0, n_ext, base, dt, n_out, out_a[off:off + n_out], d1, d2, d3, qs, v, vals)
    if kind[1] or kind[2]:
        _interpolate_signal(tb, pb, 0, n_ext, base, dt, n_out, out_b[off:off + n_out], d1, d2, d3, qs, v, vals)


@kernel
def _radiate_direct(node, kind, rho0_vol, xp, ov, inv_a, tau, c0, t_first, dt, n_out, out_a, out_b, work):
    """Direct mode: 4π p of one node at one observer at the targets t_first + k·dt, k < n_out, added to out_a
    (dipole) and out_b (monopole or panel), from the source steps the window needs (:func:`_direct_window`)."""
    rs, tb, pa, pb, d1, d2, d3, qs, v, vals = work
    n_tau = tau.size
    _receive(node, xp, ov, inv_a, tau, 0, n_tau, 0, rs, tb)
    lo, hi = _direct_window(tb, n_tau, t_first, t_first + (n_out - 1) * dt)
    _node_signals(node, kind, rho0_vol, xp, ov, tau, rs, lo, hi, 0, c0, pa, pb)
    if kind[0]:
        _interpolate_signal(tb, pa, lo, hi, t_first, dt, n_out, out_a, d1, d2, d3, qs, v, vals)
    if kind[1] or kind[2]:
        _interpolate_signal(tb, pb, lo, hi, t_first, dt, n_out, out_b, d1, d2, d3, qs, v, vals)


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
def _radiate_kernel(src, tau, vol, surf, gdip, gmono, n_groups, xo, vo, c0, rho0, t_first, dt, n_out, period):
    """Pressure (Pa, shape (n_obs, n_groups, n_out)) of all nodes at every observer.

    ``src``: sources (n_node, N_S, n_tau), see :func:`_pack_sources`; ``tau`` (n_tau,) source times (s);
    ``vol`` (n_node,) m³; ``surf`` (n_node,) bool: the node carries a surface-panel mass flux;
    ``gdip``, ``gmono`` (n_node,) output group of each node's dipole / monopole part (−1: none);
    ``xo``, ``vo`` (n_obs, 3) observer position at t = 0 (m) and velocity (m/s), G; c0 (m/s), rho0 (kg/m³).
    period <= 0: direct mode, targets t_first + k·dt (s), F1A evaluated only on the source steps the window
    needs. period > 0: the samples are one period and the output is that periodic signal at
    t_first + k·dt (mod period), dt = period/n_out; the samples are extended periodically by
    two steps on each side so every target has a centred stencil.

    Parallel over blocks of OBSERVER_BLOCK observers; within a block, node after node, observer after observer
    (:func:`_radiate_periodic`, :func:`_radiate_direct`: every loop over source steps or targets). An observer's
    signals accumulate node by node in an unwrapped buffer of 2·n_out samples per group (a periodic target index
    never exceeds 2·n_out), folded into the output; every sum runs in the order of the per-observer formulation,
    whatever the block.
    """
    n_obs = xo.shape[0]
    n_node, n_tau = src.shape[0], src.shape[2]
    out = np.zeros((n_obs, n_groups, n_out))
    n_ext = n_tau + 2 * PAD + 1
    n_blocks = (n_obs + OBSERVER_BLOCK - 1) // OBSERVER_BLOCK
    for blk in prange(n_blocks):
        o_first = blk * OBSERVER_BLOCK
        n_b = min(OBSERVER_BLOCK, n_obs - o_first)
        xp = np.empty((n_b, 3))
        ov = np.empty((n_b, 3))
        inv_a = np.empty(n_b)
        _observer_block(xo, vo, o_first, n_b, c0, xp, ov, inv_a)
        work = (np.zeros(n_tau), np.zeros(n_ext), np.zeros(n_ext), np.zeros(n_ext), np.zeros(n_ext), np.zeros(n_ext),
                np.zeros(n_ext), np.zeros(n_ext), np.zeros((MAX_SLOTS, n_ext)), np.zeros(n_out + MAX_SLOTS))
        buf = np.zeros((n_b, n_groups, 2 * n_out))
        for i in range(n_node):
            compact = vol[i] != 0.0
            has_b = gmono[i] >= 0 and (compact or surf[i])
            if gdip[i] < 0 and not has_b:
                continue
            kind = (gdip[i] >= 0, has_b and compact, has_b and surf[i])
            node = src[i]
            for b in range(n_b):
                out_a = buf[b, max(gdip[i], 0)]
                out_b = buf[b, max(gmono[i], 0)]
                if period > 0.0:
                    _radiate_periodic(node, kind, rho0 * vol[i], xp[b], ov[b], inv_a[b], tau, c0, t_first, dt,
                                      n_out, period, out_a, out_b, work)
                else:
                    _radiate_direct(node, kind, rho0 * vol[i], xp[b], ov[b], inv_a[b], tau, c0, t_first, dt,
                                    n_out, out_a, out_b, work)
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
    """Kernel arguments: sources (n_node, N_S, n_tau), source times (n_tau,), volumes, surface-panel flags, group
    indices, group count.

    A node's rows hold y, v, a, f, ḟ, jerk (G), M² = |v|²/c0², f_M = f·v/c0 and the mass flux Q and its rate
    (0 without); the source times are τ_j (periodic sources: τ_0 + j·T/n_tau). M² and f_M are computed as they
    always were (einsum over the vectors of a (n_node, n_tau, 23) array, the previous row layout), so their bits
    are unchanged.
    """
    n_node, n_tau = sources.position_m.shape[:2]
    rows = np.empty((n_node, n_tau, 23))
    for q, value in enumerate((sources.position_m, sources.velocity_mps, sources.acceleration_mps2, sources.force_N,
                               sources.force_rate_N_s, sources.jerk_mps3)):
        rows[:, :, 3 * q:3 * q + 3] = value
    vel = rows[:, :, S_VEL:S_VEL + 3]
    src = np.empty((n_node, N_S, n_tau))
    src[:, :S_M2] = np.moveaxis(rows[:, :, :S_M2], 2, 1)
    src[:, S_M2] = np.einsum("ijk,ijk->ij", vel, vel) / (c0 * c0)
    src[:, S_FM] = np.einsum("ijk,ijk->ij", rows[:, :, S_FRC:S_FRC + 3], vel) / c0
    time_s = np.asarray(sources.time_s, dtype=float)
    tau = time_s[0] + np.arange(n_tau) * (period / n_tau) if period > 0 else time_s
    if sources.mass_flux_kg_s is None:
        src[:, S_FLUX:S_FLUXD + 1] = 0.0
        surface = np.zeros(n_node, dtype=np.bool_)
    else:
        src[:, S_FLUX] = sources.mass_flux_kg_s
        src[:, S_FLUXD] = sources.mass_flux_rate_kg_s2
        surface = np.any(sources.mass_flux_kg_s != 0.0, axis=1) | np.any(sources.mass_flux_rate_kg_s2 != 0.0, axis=1)
    return (
        src,
        kernel_array(tau),
        kernel_array(sources.volume_m3),
        surface,
        kernel_array(sources.dipole_group, dtype=np.int64),
        kernel_array(sources.monopole_group, dtype=np.int64),
        len(sources.groups),
    )


def covered_interval(sources: CompactSources, observers: Observers, c0_mps: float = C0_MPS) -> np.ndarray:
    """(n_obs, 2): observer-time interval (s) that every source node covers at each observer."""
    return _coverage(kernel_array(sources.position_m), kernel_array(sources.time_s), kernel_array(observers.position_m),
                     kernel_array(observers.velocity_mps), float(c0_mps))


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
    xo = kernel_array(observers.position_m)
    vo = kernel_array(observers.velocity_mps)
    tau = np.asarray(sources.time_s, dtype=float)
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
