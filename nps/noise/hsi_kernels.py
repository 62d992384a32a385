"""Compiled kernels of the HSI model (:mod:`nps.noise.hsi`): radiation Mach search and equal-area shock fit.

Kept apart from :mod:`nps.noise.hsi` so that code which only sums or plots HSI signals does not import
numba; :mod:`nps.noise.hsi` imports this module when it first needs a kernel. All kernels are declared
with :func:`nps.core.jit.kernel`. Units: SI (m, s, m/s, rad, Pa); frames: the ground frame G of
docs/reference/conventions.md. Arrays are float64 unless stated.

Shock fit (Hopf–Lax / Whitham): along the polyline (t_j, p_j), segment j (t_j → t_j+1, linear p
with slope g_j) carries Ψ_j(x) = Ψ(t_j) + σ[(p_j − p_ref)(x − t_j) + ½ g_j (x − t_j)²], the running
integral σ∫(p − p_ref) dt; the fitted signal follows the segment on top of the envelope of all Ψ_j.
"""

from __future__ import annotations

import numpy as np

from nps.core.jit import kernel, prange

#: Relative tolerance below which a pressure jump in the fitted signal is not a shock.
JUMP_RTOL = 1e-10
#: Relative tolerance (of max|p − p_ref| × window) on a jump of Ψ between adjacent top segments.
_PSI_RTOL = 1e-9


# --------------------------------------------------------------------------- radiation Mach number
@kernel(inline=True)
def _emission_delay(dx, dy, dz, v, c):
    """Propagation time Δ (s) > 0 with |d + v Δ| = c Δ, d = (dx, dy, dz) (m), v (3,) (m/s),
    |v| < c (m/s): the positive root of the quadratic, in closed form."""
    a = c * c - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    b = dx * v[0] + dy * v[1] + dz * v[2]
    return (b + np.sqrt(b * b + a * (dx * dx + dy * dy + dz * dz))) / a


@kernel
def hub_delay(d, v, c):
    """:func:`_emission_delay` for d (3,) (m): hub-to-observer vector, v (3,) observer velocity (m/s)."""
    return _emission_delay(d[0], d[1], d[2], v, c)


@kernel(inline=True)
def _tip_sample(hub0, vel, r_gh, radius, omega, sign, c, x0, vo, tau, psi):
    """(M_r, radiation distance (m)) of the sound a blade tip at azimuth ψ (rad) emits at time τ (s).

    hub0 (3,) hub position at t = 0 (m), vel (3,) hub velocity (m/s), r_gh (3, 3) hub→G rotation,
    radius (m), omega (rad/s), sign ±1 rotation sense, c (m/s); x0 (3,), vo (3,) observer position
    at t = 0 (m) and velocity (m/s). M_r = v_tip·(x_obs(t) − y_tip(τ)) / (c · c(t − τ)); the distance
    is hub(τ) → observer(t).
    """
    cp = np.cos(psi)
    sp = sign * np.sin(psi)
    dcp = -np.sin(psi)
    dsp = sign * np.cos(psi)
    hx = hub0[0] + vel[0] * tau
    hy = hub0[1] + vel[1] * tau
    hz = hub0[2] + vel[2] * tau
    dx = x0[0] + vo[0] * tau - hx - radius * (r_gh[0, 0] * cp + r_gh[0, 1] * sp)
    dy = x0[1] + vo[1] * tau - hy - radius * (r_gh[1, 0] * cp + r_gh[1, 1] * sp)
    dz = x0[2] + vo[2] * tau - hz - radius * (r_gh[2, 0] * cp + r_gh[2, 1] * sp)
    delta = _emission_delay(dx, dy, dz, vo, c)
    rx = dx + vo[0] * delta
    ry = dy + vo[1] * delta
    rz = dz + vo[2] * delta
    ro = radius * omega
    mach = ((vel[0] + ro * (r_gh[0, 0] * dcp + r_gh[0, 1] * dsp)) * rx
            + (vel[1] + ro * (r_gh[1, 0] * dcp + r_gh[1, 1] * dsp)) * ry
            + (vel[2] + ro * (r_gh[2, 0] * dcp + r_gh[2, 1] * dsp)) * rz) / (c * c * delta)
    ox = x0[0] + vo[0] * (tau + delta) - hx
    oy = x0[1] + vo[1] * (tau + delta) - hy
    oz = x0[2] + vo[2] * (tau + delta) - hz
    return mach, np.sqrt(ox * ox + oy * oy + oz * oz)


@kernel(inline=True)
def _periodic_peak(vals, i):
    """Parabola-refined value of the sample ``vals[i]`` of a periodic sequence (n,) if it is a
    local maximum (≥ both neighbours), else −inf."""
    n = vals.size
    f0 = vals[i - 1] if i > 0 else vals[n - 1]
    f1 = vals[i]
    f2 = vals[i + 1] if i < n - 1 else vals[0]
    if not (f1 >= f0 and f1 >= f2):
        return -np.inf
    curv = 2.0 * f1 - f0 - f2
    return f1 + (f2 - f0) ** 2 / (8.0 * curv) if curv > 0.0 else f1


@kernel
def _observer_max_mach(hub0, vel, r_gh, radius, omega, sign, n_blades, c, x0, vo, t0, n_samples):
    """(max M_r, radiation distance (m)) for one observer x0 (3,) m, vo (3,) m/s over one revolution
    from the hub's emission time for reception at t0 (s): ``n_samples`` source times per blade,
    maxima refined by a parabola; an observer moving with the hub searches blade 0 only."""
    period = 2.0 * np.pi / omega
    d_hub = x0 + vo * t0 - hub0 - vel * t0
    tau0 = t0 - hub_delay(d_hub, vel, c)
    best = -np.inf
    best_dist = 0.0
    vals = np.empty(n_samples)
    same = vo[0] == vel[0] and vo[1] == vel[1] and vo[2] == vel[2]
    for k in range(1 if same else n_blades):
        phase = 2.0 * np.pi * k / n_blades
        for i in range(n_samples):
            tau = tau0 + period * i / n_samples
            vals[i] = _tip_sample(hub0, vel, r_gh, radius, omega, sign, c, x0, vo, tau, omega * tau + phase)[0]
        for i in range(n_samples):
            peak = _periodic_peak(vals, i)
            if peak > best:
                best = peak
                tau = tau0 + period * i / n_samples
                best_dist = _tip_sample(hub0, vel, r_gh, radius, omega, sign, c, x0, vo, tau, omega * tau + phase)[1]
    return best, best_dist


@kernel(parallel=True)
def radiation_mach_kernel(hub0, vel, r_gh, radius, omega, sign, n_blades, c, obs_x, obs_v, t0, n_samples):
    """:func:`_observer_max_mach` for observers obs_x (n, 3) m, obs_v (n, 3) m/s in parallel.

    Rotor: hub0 (3,) m, vel (3,) m/s, r_gh (3, 3), radius m, omega rad/s, sign ±1, n_blades; c m/s.
    Returns (mach_r (n,), distance_m (n,)).
    """
    n_obs = obs_x.shape[0]
    mach = np.empty(n_obs)
    dist = np.empty(n_obs)
    for o in prange(n_obs):
        mach[o], dist[o] = _observer_max_mach(hub0, vel, r_gh, radius, omega, sign, n_blades, c,
                                              obs_x[o], obs_v[o], t0, n_samples)
    return mach, dist


# --------------------------------------------------------------------------- equal-area shock fit
@kernel
def fold_orientation(t, p, period):
    """+1 if every backward time step of the polyline t (n,) s, p (n,) Pa raises p (compressive
    folds), −1 if every one lowers it, 0 when time is strictly increasing, 2 when inconsistent.
    ``period`` > 0 (s) includes the closing step to (t[0] + period, p[0])."""
    n = t.size
    pos = 0
    neg = 0
    bad = 0
    last = n if period > 0.0 else n - 1
    for i in range(last):
        j = i + 1
        tj = t[j] if j < n else t[0] + period
        pj = p[j] if j < n else p[0]
        dt = tj - t[i]
        dp = pj - p[i]
        if dt <= 0.0:
            if dp > 0.0:
                pos += 1
            elif dp < 0.0:
                neg += 1
            else:
                bad += 1
    if pos == 0 and neg == 0 and bad == 0:
        return 0
    if bad > 0 or (pos > 0 and neg > 0):
        return 2
    return 1 if pos > 0 else -1


@kernel(inline=True)
def _psi_vertices(t, p, sigma, p_ref):
    """Ψ (Pa·s) at the vertices t (n,) s of the polyline p (n,) Pa: σ∫(p − p_ref) dt, trapezoids."""
    psi = np.zeros(t.size)
    for i in range(t.size - 1):
        psi[i + 1] = psi[i] + sigma * (0.5 * (p[i] + p[i + 1]) - p_ref) * (t[i + 1] - t[i])
    return psi


@kernel(inline=True)
def _segment_table(t, p, wa, wb):
    """Per segment j of the polyline (n − 1 of them): slope g (Pa/s), time span [lo, hi] (s), and
    the indices of the non-vertical segments overlapping (wa, wb) in ascending lo (stable order)."""
    nseg = t.size - 1
    g = np.zeros(nseg)
    lo = np.empty(nseg)
    hi = np.empty(nseg)
    valid = np.zeros(nseg, dtype=np.bool_)
    for j in range(nseg):
        dt = t[j + 1] - t[j]
        lo[j] = min(t[j], t[j + 1])
        hi[j] = max(t[j], t[j + 1])
        if dt != 0.0 and hi[j] > wa and lo[j] < wb:
            valid[j] = True
            g[j] = (p[j + 1] - p[j]) / dt
    segs = np.nonzero(valid)[0]
    return g, lo, hi, segs[np.argsort(lo[segs], kind="mergesort")]


@kernel(inline=True)
def _event_times(t, wa, wb):
    """Sweep events (s): wa, the vertex times strictly inside (wa, wb) in ascending order, wb."""
    inside = (t > wa) & (t < wb)
    ev = np.empty(inside.sum() + 2)
    ev[0] = wa
    ev[1:-1] = np.sort(t[inside])
    ev[-1] = wb
    return ev


@kernel(inline=True)
def _psi_at(j, x, t, p, g, psi, sigma, p_ref):
    """Ψ_j(x) (Pa·s) of segment j at time x (s)."""
    u = x - t[j]
    return psi[j] + sigma * ((p[j] - p_ref) * u + 0.5 * g[j] * u * u)


@kernel(inline=True)
def _psi_slope_at(j, x, t, p, g, sigma, p_ref):
    """dΨ_j/dx (Pa) of segment j at time x (s): σ(p_j(x) − p_ref)."""
    return sigma * (p[j] + g[j] * (x - t[j]) - p_ref)


@kernel(inline=True)
def _sweep_active(active, na, ptr, order, lo, hi, a):
    """Update the active segments (those spanning time a) in place: append the segments of
    ``order`` from ``ptr`` on with lo ≤ a, drop those with hi ≤ a. Returns (na, ptr)."""
    while ptr < order.size and lo[order[ptr]] <= a:
        active[na] = order[ptr]
        na += 1
        ptr += 1
    keep = 0
    for q in range(na):
        if hi[active[q]] > a:
            active[keep] = active[q]
            keep += 1
    return keep, ptr


@kernel(inline=True)
def _add_roots_in(c0, c1, c2, a, b, roots, nb):
    """Append to ``roots`` (from index nb) the times a + x (s) with x a root of c0 + c1 x + c2 x²
    inside (0, b − a), by the cancellation-free quadratic formula; returns the new count."""
    if c2 == 0.0:
        if c1 != 0.0:
            x = -c0 / c1
            if 0.0 < x < b - a:
                roots[nb] = a + x
                nb += 1
        return nb
    disc = c1 * c1 - 4.0 * c2 * c0
    if disc < 0.0:
        return nb
    qq = -0.5 * (c1 + np.copysign(np.sqrt(disc), c1))
    for x in (qq / c2, c0 / qq if qq != 0.0 else -1.0):
        if 0.0 < x < b - a:
            roots[nb] = a + x
            nb += 1
    return nb


@kernel(inline=True)
def _cut_times(active, na, a, b, t, p, g, psi, sigma, p_ref):
    """Sorted times (s) a, crossings of the Ψ_j of the active segments inside (a, b), b: between two
    consecutive cuts the top segment does not change."""
    if na == 1:
        cuts = np.empty(2)
        cuts[0] = a
        cuts[1] = b
        return cuts
    roots = np.empty(na * (na - 1))
    nb = 0
    for q in range(na):
        i = active[q]
        vi = _psi_at(i, a, t, p, g, psi, sigma, p_ref)
        si = _psi_slope_at(i, a, t, p, g, sigma, p_ref)
        for r in range(q + 1, na):
            j = active[r]
            vj = _psi_at(j, a, t, p, g, psi, sigma, p_ref)
            sj = _psi_slope_at(j, a, t, p, g, sigma, p_ref)
            nb = _add_roots_in(vi - vj, si - sj, 0.5 * sigma * (g[i] - g[j]), a, b, roots, nb)
    cuts = np.empty(nb + 2)
    cuts[0] = a
    cuts[1 : nb + 1] = np.sort(roots[:nb])
    cuts[nb + 1] = b
    return cuts


@kernel(inline=True)
def _top_segment(active, na, x, t, p, g, psi, sigma, p_ref):
    """Active segment with the largest Ψ_j(x) (the first one on ties)."""
    top = active[0]
    best = -np.inf
    for q in range(na):
        j = active[q]
        v = _psi_at(j, x, t, p, g, psi, sigma, p_ref)
        if v > best:
            best = v
            top = j
    return top


@kernel
def envelope(t, p, wa, wb, sigma, p_ref):
    """Upper envelope over [wa, wb] (s) of the Ψ_j of the polyline t (n,) s, p (n,) Pa.

    σ = ±1 orientation (:func:`fold_orientation`), p_ref (Pa) the reference pressure of Ψ. The
    envelope's slope σ(p − p_ref) is the weak solution, so the pressure of the top segment at each
    time is the fitted signal. A sweep over the vertex times keeps the active segments; between
    crossings of their Ψ the top segment is fixed. Returns (time (m,), p (m,), shock_time (k,),
    p_before (k,), p_after (k,), status); status 1: the curve leaves a gap in [wa, wb]; 2: the
    envelope jumps (fold of the wrong orientation).
    """
    psi = _psi_vertices(t, p, sigma, p_ref)
    g, lo, hi, order = _segment_table(t, p, wa, wb)
    ev = _event_times(t, wa, wb)
    pscale = np.max(np.abs(p - p_ref)) + 1e-300
    ptol = JUMP_RTOL * pscale
    psitol = _PSI_RTOL * pscale * (wb - wa)
    # fitted points and shocks (typed lists; each starts with a placeholder until n_out, n_sh > 0)
    out_t = [wa]
    out_p = [0.0]
    sh_t = [0.0]
    sh_m = [0.0]
    sh_p = [0.0]
    n_out = 0
    n_sh = 0
    active = np.empty(order.size, dtype=np.int64)
    na = 0
    ptr = 0
    prev = -1
    status = 0
    for ie in range(ev.size - 1):
        a = ev[ie]
        b = ev[ie + 1]
        if b <= a:
            continue
        na, ptr = _sweep_active(active, na, ptr, order, lo, hi, a)
        if na == 0:
            status = 1
            break
        cuts = _cut_times(active, na, a, b, t, p, g, psi, sigma, p_ref)
        for ic in range(cuts.size - 1):
            x0 = cuts[ic]
            x1 = cuts[ic + 1]
            if x1 <= x0:
                continue
            top = _top_segment(active, na, 0.5 * (x0 + x1), t, p, g, psi, sigma, p_ref)
            if prev >= 0 and top != prev:
                jump = _psi_at(top, x0, t, p, g, psi, sigma, p_ref) - _psi_at(prev, x0, t, p, g, psi, sigma, p_ref)
                if abs(jump) > psitol:
                    status = 2
            prev = top
            for x in (x0, x1):
                pv = p[top] + g[top] * (x - t[top])
                # append (x, pv); a second value at the same time is a shock, encoded by a point at
                # nextafter(t_s, +inf); the first point keeps the window start wa as its time
                if n_out == 0:
                    out_p[0] = pv
                    n_out = 1
                elif x > out_t[n_out - 1]:
                    out_t.append(x)
                    out_p.append(pv)
                    n_out += 1
                elif abs(pv - out_p[n_out - 1]) > ptol:
                    if n_sh == 0:
                        sh_t[0] = out_t[n_out - 1]
                        sh_m[0] = out_p[n_out - 1]
                        sh_p[0] = pv
                    else:
                        sh_t.append(out_t[n_out - 1])
                        sh_m.append(out_p[n_out - 1])
                        sh_p.append(pv)
                    n_sh += 1
                    out_t.append(np.nextafter(out_t[n_out - 1], np.inf))
                    out_p.append(pv)
                    n_out += 1
    return (np.array(out_t), np.array(out_p), np.array(sh_t)[:n_sh], np.array(sh_m)[:n_sh],
            np.array(sh_p)[:n_sh], status)


@kernel(inline=True)
def _unrolled(t, p, period):
    """The periodic polyline t (n,) s, p (n,) Pa repeated over three periods starting one period
    early, closed at t[0] + 2·period: arrays (3n + 1,)."""
    n = t.size
    tt = np.empty(3 * n + 1)
    pp = np.empty(3 * n + 1)
    for m in range(3):
        tt[m * n : (m + 1) * n] = t + (m - 1) * period
        pp[m * n : (m + 1) * n] = p
    tt[3 * n] = t[0] + 2.0 * period
    pp[3 * n] = p[0]
    return tt, pp


@kernel(inline=True)
def _period_mean(t, p, period):
    """Mean pressure (Pa) over one period (s) of the closed polyline, trapezoids."""
    n = t.size
    area = 0.0
    for i in range(n):
        tj = t[i + 1] if i + 1 < n else t[0] + period
        pj = p[i + 1] if i + 1 < n else p[0]
        area += 0.5 * (p[i] + pj) * (tj - t[i])
    return area / period


@kernel
def fit_periodic(t, p, period, wa):
    """Envelope (:func:`envelope`) of the periodic polyline t (n,) s, p (n,) Pa (closing segment to
    t[0] + period) over [wa, wa + period]; unrolled over three periods so folds may wrap around.
    A shock on the window edge is kept as the pair (wb⁻, p_before), (wa + period, p_after) and
    listed at wa. Returns as :func:`envelope`; status 3: inconsistent fold orientation."""
    sigma = fold_orientation(t, p, period)
    if sigma == 2:
        return np.empty(0), np.empty(0), np.empty(0), np.empty(0), np.empty(0), 3
    if sigma == 0:
        sigma = 1
    tt, pp = _unrolled(t, p, period)
    p_ref = _period_mean(t, p, period)
    ot, op, st, sm, sp, status = envelope(tt, pp, wa, wa + period, float(sigma), p_ref)
    if status == 0 and ot[-1] == wa + period and abs(op[-1] - op[0]) > JUMP_RTOL * np.max(np.abs(p - p_ref)):
        ot[-1] = np.nextafter(wa + period, -np.inf)
        st = np.concatenate((np.array([wa]), st))
        sm = np.concatenate((np.array([op[-1]]), sm))
        sp = np.concatenate((np.array([op[0]]), sp))
    return ot, op, st, sm, sp, status


@kernel(inline=True)
def _sample(xp, fp, x):
    """Linear interpolation of the increasing polyline xp (m,), fp (m,) at increasing x (k,)."""
    out = np.empty(x.size)
    j = 0
    for i in range(x.size):
        while j < xp.size - 2 and xp[j + 1] < x[i]:
            j += 1
        w = (x[i] - xp[j]) / (xp[j + 1] - xp[j])
        w = min(max(w, 0.0), 1.0)
        out[i] = fp[j] + w * (fp[j + 1] - fp[j])
    return out


@kernel(parallel=True)
def shear_fit_resample(time_s, p_amp, delay_s, period):
    """Shear, shock-fit and resample the periodic signals of all observers in parallel.

    time_s (N,) s uniform grid of one period (s); p_amp (n_obs, N) Pa amplified signals; delay_s
    (n_obs, N) s shear delays (sheared time t − δt). Returns (p (n_obs, N) Pa on ``time_s``, NaN
    rows where the fit failed; shocks per observer (n_obs,) int64; fit status (n_obs,) int64).
    """
    n_obs = p_amp.shape[0]
    out = np.empty_like(p_amp)
    n_shocks = np.zeros(n_obs, dtype=np.int64)
    status = np.zeros(n_obs, dtype=np.int64)
    for o in prange(n_obs):
        ts = time_s - delay_s[o]
        ft, fp, st, _, _, stat = fit_periodic(ts, p_amp[o], period, time_s[0])
        status[o] = stat
        if stat == 0:
            out[o] = _sample(ft, fp, time_s)
            n_shocks[o] = st.size
        else:
            out[o] = np.nan
    return out, n_shocks, status
