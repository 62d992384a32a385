"""High-speed-impulsive (HSI) noise: amplify, shear and shock-fit each rotor's signal (thesis ch. 6).

Each rotor's pressure signal (thickness + loading, one reference-rotor revolution on the
uniform grid of docs/reference/conventions.md "Pressure signals") is processed per observer with that
rotor's own maximum radiation Mach number M_r and radiation distance r; the processed rotors are
then summed (:func:`combine_rotors`). Steps, in order:

1. **Kinematics** (:func:`radiation_mach`): M_r = max over one revolution and over the blades of
   v_tip·r̂ / c, with v_tip the tip velocity in the ground frame G (air at rest) and r̂ the unit
   vector from the tip's emission position to the observer's reception position (retarded-time
   geometry, closed form for an observer moving at constant velocity). The radiation distance r
   is |x_obs(t*) − x_hub(τ*)|: from the hub at the emission time τ* of the max-M_r sound to the
   observer at its reception time t* (in hover: the hub-to-observer distance, the quantity the
   calibration distance r0 = 3.09 R of Baeder's data refers to).
2. **Amplification** eq. 6.1: p_amp = AMP(M_r) · p (:func:`amplification`).
3. **Shear** eq. 6.3–6.6 (:func:`shear_angle_rad`, :func:`shear_delay_s`). Non-dimensional
   pressure p̃ = p/(ρ c²) and time t̃ = t Ω/(2π) (revolutions of this rotor). Eq. 6.5 as printed
   (Ã = p̃ r) is not dimensionless; NPS reads the "amplitude at release" as the spreading-
   corrected amplitude referred to the calibration distance, Ã = p̃ · r / r0, so that
   δt̃ = Ã tan γ_s · r/r0 = p̃ tan γ_s (r/r0)². At r = r0 this is exactly the calibrated shear
   δt̃ = p̃ tan γ_s; for a source of fixed strength (p ∝ 1/r) the delay grows linearly with
   distance. r0 = 3.09 R of the rotor being processed (the model is non-dimensional, so a
   geometrically similar rotor at the same M_r and r/R is sheared alike). Sheared time
   t_shear = t − δt: higher pressure arrives earlier (compressive steepening).
4. **Shock fitting** (:func:`equal_area_shock_fit`): where the sheared curve is multivalued,
   Whitham's equal-area rule, computed as the entropy weak solution of the inviscid Burgers
   equation (see :func:`fit_shocks`), with any number of shocks, periodic wrap-around and
   merging shocks.
5. **Resampling** to the uniform input grid by point sampling of the single-valued (fitted)
   signal. NPS fits before it resamples: resampling a multivalued curve is ill-defined.

Validity: M_r < 1 (the retarded-time geometry has a unique solution and eq. 6.1/6.4 were fitted
for M_r ≤ 0.95); observers must move with the aircraft (periodic signals, conventions.md).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.noise.signals import signal_arrays
from nps.rotor.geometry import RotorMotion

#: Calibration distance of eq. 6.5 in rotor radii (Baeder et al. in-plane observer, Table 6.1).
R0_OVER_RADIUS = 3.09
#: Azimuth samples per revolution for the search of max M_r (refined by a parabola).
MACH_SAMPLES_PER_REV = 720
OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps")


# --------------------------------------------------------------------------- empirical fits
def amplification(mach_r) -> np.ndarray:
    """Amplification factor AMP(M_r), thesis eq. 6.1 (dimensionless, ≥ 1).

    AMP = 1 + 0.1800844 M_r for M_r ≤ 0.687, else the cubic
    42.504 M_r³ − 80.822 M_r² + 50.869 M_r − 9.4594 (continuous at 0.687 to 1e-4).
    """
    m = np.asarray(mach_r, dtype=float)
    cubic = ((42.504 * m - 80.822) * m + 50.869) * m - 9.4594
    return np.where(m <= 0.687, 1.0 + 0.1800844 * m, cubic)


def shear_angle_rad(mach_r) -> np.ndarray:
    """Shear angle γ_s(M_r) in rad in the (t̃, p̃) plane, thesis eq. 6.4.

    γ_s = 0.0006 exp(8.0675 M_r) for M_r ≤ 0.87, else the cubic
    914.12 M_r³ − 2645.3 M_r² + 2548.9 M_r − 816.7. The two branches differ by 0.10 rad at
    0.87 (0.670 vs 0.566: the printed fit is discontinuous); NPS keeps the printed coefficients.
    """
    m = np.asarray(mach_r, dtype=float)
    cubic = ((914.12 * m - 2645.3) * m + 2548.9) * m - 816.7
    return np.where(m <= 0.87, 0.0006 * np.exp(8.0675 * m), cubic)


# --------------------------------------------------------------------------- rotor state
@dataclass(frozen=True)
class HsiRotor:
    """What the HSI model needs of one rotor (one ``trim.parquet`` row, SI units).

    ``motion`` gives the hub path and blade azimuths in G (docs/reference/conventions.md); ``radius_m``
    is the tip radius; the air state sets ρ c² and the Mach numbers.
    """

    name: str
    motion: RotorMotion
    radius_m: float
    density_kg_m3: float
    speed_of_sound_mps: float

    @classmethod
    def from_trim_row(cls, row: Mapping) -> "HsiRotor":
        return cls(
            name=str(row["rotor"]),
            motion=RotorMotion.from_trim_row(row),
            radius_m=float(row["radius_m"]),
            density_kg_m3=float(row["density_kg_m3"]),
            speed_of_sound_mps=float(row["speed_of_sound_mps"]),
        )

    @property
    def period_s(self) -> float:
        """One revolution 2π/Ω."""
        return 2.0 * np.pi / self.motion.omega_rad_s

    @property
    def reference_distance_m(self) -> float:
        """Calibration distance r0 = 3.09 R of eq. 6.5."""
        return R0_OVER_RADIUS * self.radius_m


# --------------------------------------------------------------------------- kinematics
def radiation_mach(
    rotor: HsiRotor,
    observer_position_m: np.ndarray,
    observer_velocity_mps: np.ndarray,
    time_start_s: float = 0.0,
    n_samples: int = MACH_SAMPLES_PER_REV,
) -> tuple[np.ndarray, np.ndarray]:
    """Maximum radiation Mach number over one revolution and radiation distance per observer.

    ``observer_position_m`` (n, 3): observer positions in G at t = 0; ``observer_velocity_mps``
    (n, 3) their constant velocities in G. The revolution searched starts at the hub's emission
    time for reception at ``time_start_s`` (the first sample of the signal grid). Blade k's tip
    is at hub(τ) + R·R_GH·e_r(ψ_k(τ)), e_r = (cos ψ, s sin ψ, 0), ψ_k = Ωτ + 2πk/B; its velocity
    in G is V + RΩ·R_GH·(−sin ψ, s cos ψ, 0); an observer moving with the hub sees all blades
    alike, so only blade 0 is searched for it. Source-time dominant: for each emission time the
    reception time solves |x(t) − y(τ)| = c (t − τ) in closed form. The maximum over
    ``n_samples`` per revolution and blade is refined by a parabola through the three samples
    around it. Returns (mach_r, distance_m), both shape (n,).
    """
    pos = np.ascontiguousarray(np.atleast_2d(observer_position_m), dtype=float)
    vel = np.ascontiguousarray(np.atleast_2d(observer_velocity_mps), dtype=float)
    if pos.shape != vel.shape or pos.shape[1] != 3:
        raise ValueError(f"observer positions {pos.shape} and velocities {vel.shape} must both be (n, 3)")
    c = rotor.speed_of_sound_mps
    m = rotor.motion
    for what, speeds in (("observer", np.linalg.norm(vel, axis=1)), ("hub", np.linalg.norm(m.velocity_mps)[None])):
        if np.any(speeds >= c):
            raise ValueError(f"{what} speed {speeds.max():.1f} m/s is not subsonic (c = {c:.1f} m/s)")
    from nps.noise.hsi_kernels import radiation_mach_kernel

    return radiation_mach_kernel(
        m.hub_position_m.astype(float), m.velocity_mps.astype(float), np.ascontiguousarray(m.r_gh, dtype=float),
        rotor.radius_m, m.omega_rad_s, float(m.rotation_sign), m.n_blades, c, pos, vel, float(time_start_s),
        int(n_samples),
    )


def shear_delay_s(p_pa, mach_r, distance_m, rotor: HsiRotor) -> np.ndarray:
    """Arrival-time delay δt (s) of eq. 6.5 in NPS's dimensionally consistent reading.

    δt = (2π/Ω) · p/(ρ c²) · tan γ_s(M_r) · (r/r0)², with ``p_pa`` the amplified pressure;
    ``mach_r`` and ``distance_m`` broadcast against ``p_pa``. Sheared time t − δt (eq. 6.6).
    """
    scale = (np.asarray(distance_m, dtype=float) / rotor.reference_distance_m) ** 2
    tan_gamma = np.tan(shear_angle_rad(mach_r))
    rho_c2 = rotor.density_kg_m3 * rotor.speed_of_sound_mps**2
    return rotor.period_s * np.asarray(p_pa, dtype=float) / rho_c2 * tan_gamma * scale


# --------------------------------------------------------------------------- shock fitting
_STATUS_TEXT = {
    1: "the curve does not cover the whole period (time steps must advance by less than a period overall)",
    2: "the fold orientation is inconsistent (the equal-area envelope is discontinuous)",
    3: "backward time steps both raise and lower the pressure (no consistent shock orientation)",
}


@dataclass(frozen=True)
class ShockFit:
    """Single-valued signal from :func:`fit_shocks` and its shocks.

    ``time_s`` strictly increasing; a shock at t_s is the pair (t_s, p_before), (t_s⁺, p_after)
    with t_s⁺ = nextafter(t_s, +inf), so linear interpolation reproduces the jump exactly.
    """

    time_s: np.ndarray
    p_pa: np.ndarray
    shock_time_s: np.ndarray
    p_before_pa: np.ndarray
    p_after_pa: np.ndarray


def fit_shocks(time_s, p_pa, period_s: float | None = None) -> ShockFit:
    """Equal-area (Whitham) shock fit of a possibly multivalued signal (t_i, p_i).

    The input is the polyline through the samples in order (linear in between). Where time runs
    backward the curve is multivalued; the fitted signal is the entropy weak solution of the
    inviscid Burgers equation for which the fold is a compression: with Φ = ∫ p dt along the
    curve, the fitted Φ(t) is the upper envelope of the multivalued Φ (lower envelope when
    backward steps lower the pressure), Hopf–Lax. At each shock the two branches have equal Φ,
    i.e. the loop cut off by the vertical line at t_s has zero net signed area: the areas on
    both sides are equal (Whitham). Several folds, overlapping (merging) shocks and, with
    ``period_s``, folds across the period boundary are handled; a periodic input (closing
    segment to time_s[0] + period_s) returns one period starting at time_s[0] (a shock exactly
    at time_s[0] is listed there and encoded by the last point, at the time just below
    time_s[0] + period_s, and the first). An input that
    is already strictly increasing in time is returned unchanged. Aperiodic inputs must start
    and end on their earliest and latest times.
    """
    from nps.noise.hsi_kernels import envelope, fit_periodic, fold_orientation

    t = np.ascontiguousarray(time_s, dtype=float)
    p = np.ascontiguousarray(p_pa, dtype=float)
    if t.ndim != 1 or t.shape != p.shape or t.size < 3:
        raise ValueError(f"time_s and p_pa must be 1-D of equal length >= 3, got {t.shape} and {p.shape}")
    if not (np.isfinite(t).all() and np.isfinite(p).all()):
        raise ValueError("time_s and p_pa must be finite")
    empty = np.empty(0)
    if period_s is None:
        steps = np.diff(t)
        if (steps > 0).all():
            return ShockFit(t.copy(), p.copy(), empty, empty, empty)
        if t.min() < t[0] or t.max() > t[-1]:
            raise ValueError("aperiodic signal folds past its first or last sample; pass period_s for a periodic one")
        sigma = fold_orientation(t, p, 0.0)
        status = 3
        if sigma != 2:
            result = envelope(t, p, t[0], t[-1], float(sigma), float(p.mean()))
            status = result[-1]
    else:
        period = float(period_s)
        if not period > 0.0:
            raise ValueError(f"period_s must be > 0, got {period_s}")
        if (np.diff(t) > 0).all() and t[0] + period > t[-1]:
            return ShockFit(t.copy(), p.copy(), empty, empty, empty)
        result = fit_periodic(t, p, period, t[0])
        status = result[-1]
        if status == 0:
            keep = result[0] < t[0] + period
            result = (result[0][keep], result[1][keep], *result[2:])
    if status:
        raise ValueError(f"shock fit failed: {_STATUS_TEXT[status]}")
    return ShockFit(*result[:5])


def equal_area_shock_fit(time_s, p_pa, period_s: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Single-valued ``(time_s, p_pa)`` from a possibly multivalued signal; see :func:`fit_shocks`."""
    fit = fit_shocks(time_s, p_pa, period_s)
    return fit.time_s, fit.p_pa


# --------------------------------------------------------------------------- per-rotor processing
@dataclass(frozen=True)
class HsiIntermediate:
    """The steps of thesis Fig. 6.3 for one observer (times in s, pressures in Pa)."""

    observer: int
    mach_r: float
    distance_m: float
    amplification: float
    shear_angle_rad: float
    time_s: np.ndarray
    p_original_pa: np.ndarray
    p_amplified_pa: np.ndarray
    time_sheared_s: np.ndarray
    fitted: ShockFit
    p_final_pa: np.ndarray


@dataclass(frozen=True)
class HsiResult:
    """Output of :func:`process`: the ``hsi`` signal table, per-observer diagnostics and the
    optional intermediate signals of one observer."""

    signals: pd.DataFrame
    diagnostics: pd.DataFrame
    intermediate: HsiIntermediate | None


def process_signals(time_s, p_pa, mach_r, distance_m, rotor: HsiRotor) -> tuple[np.ndarray, np.ndarray]:
    """Amplify, shear, shock-fit and resample the periodic signals ``p_pa`` (n_obs, N).

    ``time_s`` (N,) is the uniform grid t0 + k T/N of one period T = N Δt; ``mach_r`` and
    ``distance_m`` (n_obs,) from :func:`radiation_mach`. Returns (p_hsi (n_obs, N) on the same
    grid, number of shocks per observer).
    """
    t = np.ascontiguousarray(time_s, dtype=float)
    period = _grid_period(t)
    p_amp = np.ascontiguousarray(np.atleast_2d(p_pa) * amplification(mach_r)[:, None], dtype=float)
    delay = np.ascontiguousarray(shear_delay_s(p_amp, np.asarray(mach_r)[:, None], np.asarray(distance_m)[:, None], rotor))
    from nps.noise.hsi_kernels import shear_fit_resample

    out, n_shocks, status = shear_fit_resample(t, p_amp, delay, period)
    if status.any():
        o = int(np.argmax(status != 0))
        raise ValueError(f"rotor {rotor.name}: shock fit failed for signal row {o}: {_STATUS_TEXT[int(status[o])]}")
    return out, n_shocks


def _grid_period(t: np.ndarray) -> float:
    steps = np.diff(t)
    if t.ndim != 1 or t.size < 3 or not (steps > 0).all():
        raise ValueError("time_s must be a strictly increasing 1-D grid of >= 3 samples")
    dt = (t[-1] - t[0]) / (t.size - 1)
    if np.max(np.abs(steps - dt)) > 1e-6 * dt:
        raise ValueError(f"time_s must be uniform (max step deviation {np.max(np.abs(steps - dt)):.3g} s)")
    return dt * t.size


def _signal_matrix(signals: pd.DataFrame, groups=("thickness", "loading")) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(observer ids, time grid, sum over the groups of p (n_obs, N)) from a signal table."""
    ids, time_s, p = signal_arrays(signals, groups)
    return ids, time_s, sum(p.values())


def process(
    signals: pd.DataFrame,
    observers: pd.DataFrame,
    trim_row: Mapping,
    *,
    intermediate_observer: int | None = None,
) -> HsiResult:
    """HSI processing of one rotor's pressure-signal table (docs/reference/conventions.md artifacts).

    ``signals``: columns observer, group (thickness, loading), time_s, p_Pa, one period on a
    uniform grid; the rotor total (sum of the groups) is processed. ``observers``: observer,
    x_m, y_m, z_m (G at t = 0), vx_mps, vy_mps, vz_mps, which must equal the aircraft velocity
    (observers moving with the aircraft: periodic signals). ``trim_row``: this rotor's trim row.
    Returns the ``hsi`` group table on the same grid, diagnostics (observer, mach_r,
    radiation_distance_m, amplification, shear_angle_rad, n_shocks) and, if asked, the
    intermediate signals of ``intermediate_observer``.
    """
    rotor = HsiRotor.from_trim_row(trim_row)
    ids, time_s, p = _signal_matrix(signals)
    pos, vel = _comoving_observers(observers, ids, rotor)
    if intermediate_observer is not None and intermediate_observer not in set(ids.tolist()):
        raise ValueError(f"intermediate observer {intermediate_observer} is not in the pressure signals")
    mach_r, distance = radiation_mach(rotor, pos, vel, float(time_s[0]))
    if np.any(mach_r >= 1.0):
        bad = int(ids[np.argmax(mach_r)])
        raise ValueError(f"rotor {rotor.name}: observer {bad} sees M_r = {mach_r.max():.3f} >= 1; HSI model needs M_r < 1")
    p_hsi, n_shocks = process_signals(time_s, p, mach_r, distance, rotor)
    diagnostics = pd.DataFrame(
        {
            "observer": ids,
            "mach_r": mach_r,
            "radiation_distance_m": distance,
            "amplification": amplification(mach_r),
            "shear_angle_rad": shear_angle_rad(mach_r),
            "n_shocks": n_shocks.astype(np.int32),
        }
    )
    inter = None
    if intermediate_observer is not None:
        o = int(np.nonzero(ids == intermediate_observer)[0][0])
        inter = _intermediate(int(intermediate_observer), time_s, p[o], p_hsi[o], mach_r[o], distance[o], rotor)
    return HsiResult(_signal_table(ids, time_s, p_hsi, "hsi"), diagnostics, inter)


def _comoving_observers(observers: pd.DataFrame, ids: np.ndarray, rotor: HsiRotor) -> tuple[np.ndarray, np.ndarray]:
    """(positions (n, 3) m, velocities (n, 3) m/s) in G of the observers ``ids`` (in that order);
    errors for missing columns or rows and for observers not moving with the aircraft."""
    missing = [c for c in OBSERVER_COLUMNS if c not in observers.columns]
    if missing:
        raise ValueError(f"observers: missing column(s) {missing}; expected {list(OBSERVER_COLUMNS)}")
    obs = observers.set_index("observer")
    absent = sorted(set(ids.tolist()) - set(obs.index.tolist()))
    if absent:
        raise ValueError(f"observers: no row for observer(s) {absent[:5]} present in the pressure signals")
    obs = obs.loc[ids]
    pos = obs[["x_m", "y_m", "z_m"]].to_numpy(dtype=float)
    vel = obs[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(dtype=float)
    off = np.abs(vel - rotor.motion.velocity_mps).max(axis=1)
    if np.any(off > 1e-6 * max(1.0, np.linalg.norm(rotor.motion.velocity_mps))):
        bad = int(ids[np.argmax(off)])
        raise ValueError(
            f"observers: observer {bad} velocity {vel[np.argmax(off)]} m/s differs from the aircraft velocity "
            f"{rotor.motion.velocity_mps} m/s; the HSI stage needs observers moving with the aircraft (periodic signals)"
        )
    return pos, vel


def _intermediate(observer: int, time_s, p_pa, p_hsi_pa, mach_r: float, distance_m: float,
                  rotor: HsiRotor) -> HsiIntermediate:
    """The steps of one observer's processing (signal p_pa (N,) Pa on the grid time_s (N,) s)."""
    amp = float(amplification(mach_r))
    p_amp = p_pa * amp
    t_sheared = time_s - shear_delay_s(p_amp, mach_r, distance_m, rotor)
    return HsiIntermediate(
        observer=observer,
        mach_r=float(mach_r),
        distance_m=float(distance_m),
        amplification=amp,
        shear_angle_rad=float(shear_angle_rad(mach_r)),
        time_s=time_s,
        p_original_pa=p_pa,
        p_amplified_pa=p_amp,
        time_sheared_s=t_sheared,
        fitted=fit_shocks(t_sheared, p_amp, _grid_period(time_s)),
        p_final_pa=p_hsi_pa,
    )


def _signal_table(ids: np.ndarray, time_s: np.ndarray, p_pa: np.ndarray, group: str) -> pd.DataFrame:
    """Signal table (observer, group, time_s, p_Pa) of p_pa (n_obs, N) Pa for observers ``ids``."""
    n = time_s.size
    return pd.DataFrame(
        {"observer": np.repeat(ids, n).astype(np.int32), "group": group, "time_s": np.tile(time_s, ids.size), "p_Pa": p_pa.ravel()}
    )


def combine_rotors(tables: Sequence[pd.DataFrame], group: str = "hsi") -> pd.DataFrame:
    """Sum per-rotor signal tables (same observers and time grid) into one aircraft signal.

    Rows of every table are summed per (observer, time_s) over all its groups; the result has
    group ``group``. Rotors are combined after each has been processed with its own M_r and
    distance (thesis ch. 6).
    """
    if not tables:
        raise ValueError("combine_rotors: no tables given")
    total = None
    for k, table in enumerate(tables):
        ids, time_s, p = _signal_matrix(table, groups=("thickness", "loading", "hsi"))
        if total is None:
            total, ids0, time0 = p, ids, time_s
        elif not (np.array_equal(ids, ids0) and np.allclose(time_s, time0, rtol=0, atol=1e-9 * (time0[-1] - time0[0]))):
            raise ValueError(f"combine_rotors: table {k} has other observers or another time grid than table 0")
        else:
            total = total + p
    return _signal_table(ids0, time0, total, group)
