"""Blade–vortex-interaction loads: the tip-vortex wake's induced velocity added to the BET.

Thesis eq. 5.16–5.17: the wake-induced velocity v (``nps.wake.prescribed``, frame H') at each disk
station is resolved into the blade frame and added to the trimmed disk table's velocities,

    ΔU_T = −v·e_t,   e_t = (−sin ψ, cos ψ, 0)                (blade motion direction)
    ΔU_P = −v·n,     n   = (−sin β cos ψ, −sin β sin ψ, cos β) (blade normal, flap β)

(U_T positive toward the leading edge, U_P positive down through the disk), and the sectional
loads are recomputed with ``nps.rotor.bet.section_forces`` without re-trimming.

The trimmed loads already carry the wake's mean and once-per-revolution effect through the
BET's inflow model (λ0, kx, ky) and its trim, so by default the 0 and 1/rev Fourier
harmonics of v (per radial station) are removed before adding: what is added is the
impulsive, higher-harmonic part the linear inflow cannot represent
(``BVIModel.removed_harmonics``; ``None`` adds the raw velocity as the thesis did).

Unsteady response (``BVIModel.unsteady``): in the blade frame an old tip vortex is a gust
convected past the section at the local in-plane speed U_T, with a width of the order of the
chord (r_c ≈ c/2), so the quasi-steady lift overstates the impulsive response. Each harmonic n
of the increments (time dependence e^{inψ}, ψ = Ωt, ω = nΩ) is multiplied by the Sears
function of the local reduced frequency

    k_n(ψ, r) = n Ω (c/2) / U_T(ψ, r),   U_T = Ωr + μ_x ΩR sin ψ (the trimmed table's ``ut_mps``)

    S(k) = [J0(k) − i J1(k)] C(k) + i J1(k),   C(k) = H1⁽²⁾(k) / (H1⁽²⁾(k) + i H0⁽²⁾(k))

(Theodorsen's C), referred to the mid-chord: the lifting-line value (quarter chord) reaches
the mid-chord a quarter chord later, a factor e^{−i k_n/2}. Because U_T varies around the
azimuth, the filter is applied with frozen coefficients: y(ψ) = Re Σ_n w_n X_n S(k_n(ψ))
e^{−i k_n(ψ)/2} e^{inψ} / N (X_n the DFT of the station's series, w_n the one-sided weights),
which is the ordinary Sears filter where U_T is constant. The faster advancing blade sees a
lower k (less attenuation) than the retreating blade. In reversed or near-zero in-plane flow
(inboard retreating side) U_T is floored at ``UT_FLOOR_FRACTION`` ΩR, where the model no longer
applies and the increments are anyway small. S → 1 as k → 0, |S| ≈ 0.4 at k = 1: the
1/rev–few/rev content is unchanged, the BVI impulses (10–40/rev) are attenuated and delayed.
This also carries the chordwise non-uniformity of the gust, which a single lifting-line point
misses.

Compressibility (on with the unsteady response): the BET's quasi-steady c_l already carries the
Prandtl–Glauert 1/β. The remaining compressible attenuation of a gust response is a time
scaling by β² (Amiet 1974, low-frequency result; Leishman's compressible indicial gust
functions): |S| is taken at k/β², β² = 1 − M², M = U_T/c0. Only the magnitude is applied;
the phase stays the incompressible one (Amiet's phase terms, and its factor |J0 + iJ1|(M²k/β²)
≥ 0.94 for k ≤ 1 and M ≤ 0.65, are left out). At the advancing-side BVI (M ≈ 0.6–0.65) this
lowers the 10–40/rev response by a further ≈ 20 %.

Frames and signs: docs/reference/conventions.md; choices: docs/reference/wake_bvi.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Mapping

import numpy as np
import pandas as pd

from nps.core import periods
from nps.core.jit import kernel, kernel_array, prange
from nps.wake import prescribed as wake
from nps.wake import vortex
from nps.rotor.geometry import RotorGeometry

DISK_COLUMNS = (
    "psi_rad", "r_m", "dr_m", "chord_m", "thickness_m", "theta_rad", "beta_rad", "beta_dot_rad_s",
    "ut_mps", "up_mps", "inflow_ratio", "alpha_eff_rad", "mach", "fz_N_per_m", "fx_N_per_m",
    "circulation_m2_s",
)
TRIM_COLUMNS = (
    "rotor", "rotation_sign", "n_blades", "radius_m", "omega_rad_s", "mu_x", "mu_y", "mu_z", "ct",
    "density_kg_m3", "speed_of_sound_mps", "hub_x_m", "hub_y_m", "hub_z_m", "vel_x_mps", "vel_y_mps",
    "vel_z_mps", *(f"r_gh_{i}{j}" for i in range(3) for j in range(3)),
)


@dataclass(frozen=True)
class BVIModel:
    """``removed_harmonics``: Fourier harmonics 0…h of the induced velocity removed per radial
    station before it is added (default 1: mean and 1/rev, carried by the trimmed BET inflow);
    ``None`` adds the raw wake velocity (thesis behaviour). ``unsteady``: Sears gust response
    of the section (module doc); off gives the thesis' quasi-steady lifting line."""

    removed_harmonics: int | None = 1
    unsteady: bool = True

    def __post_init__(self):
        if self.removed_harmonics is not None and self.removed_harmonics < 0:
            raise ValueError(f"BVIModel.removed_harmonics must be None or >= 0, got {self.removed_harmonics}")


@dataclass(frozen=True)
class DiskGridView:
    """Azimuths (n_psi,), radial stations (n_r,) and the reshape of a ψ-major disk table;
    ``revolutions``: the turns of blade 0 the table spans (1, or m of a common period)."""

    psi_rad: np.ndarray
    r_m: np.ndarray
    revolutions: int = 1

    @property
    def shape(self) -> tuple[int, int]:
        return (self.psi_rad.size, self.r_m.size)


def disk_grid(disk: pd.DataFrame, what: str = "disk table", common_period: bool = False) -> DiskGridView:
    """Check that ``disk`` is a ψ-major table on ψ_i = 2πi/N_ψ and return its grid.

    ``common_period``: also accept a table over m revolutions of a common period, ψ_i = 2πi/N for
    i = 0…mN−1 (docs/reference/wake_bvi.md, "Common period"). Raises ValueError naming the table
    and the failed expectation.
    """
    missing = [c for c in DISK_COLUMNS if c not in disk.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}")
    psi = disk["psi_rad"].to_numpy(dtype=float)
    r = disk["r_m"].to_numpy(dtype=float)
    psi_u = np.unique(psi)
    n_psi = psi_u.size
    n_r = psi.size // max(n_psi, 1)
    if n_psi < 4 or n_psi * n_r != psi.size:
        raise ValueError(f"{what}: psi_rad/r_m do not form a full grid ({psi.size} rows, {n_psi} azimuths)")
    revolutions = periods.table_revolutions(psi_u)
    if not np.allclose(psi_u, 2.0 * np.pi * np.arange(n_psi) * revolutions / n_psi, atol=1e-9):
        raise ValueError(f"{what}: psi_rad must be 2*pi*i/N_psi, i = 0..N_psi-1"
                         + (" (or over m revolutions i = 0..m*N_psi-1)" if common_period else ""))
    if revolutions > 1 and not common_period:
        raise ValueError(f"{what}: psi_rad spans {revolutions} revolutions (a common-period table); expected one "
                         "revolution, psi_rad = 2*pi*i/N_psi, i = 0..N_psi-1")
    psi2 = psi.reshape(n_psi, n_r)
    r2 = r.reshape(n_psi, n_r)
    if not (np.all(psi2 == psi2[:, :1]) and np.all(r2 == r2[:1, :])):
        raise ValueError(f"{what}: rows must be psi-major (all radial stations of one azimuth together)")
    return DiskGridView(psi2[:, 0].copy(), r2[0].copy(), revolutions)


def tile_disk(disk: pd.DataFrame, revolutions: int) -> pd.DataFrame:
    """A one-revolution ψ-major disk table repeated over ``revolutions`` turns, ψ_i = 2πi/N for
    i = 0…mN−1 (the loads of a rotor before its rev-to-rev interference is added)."""
    if revolutions == 1:
        return disk
    n_psi = disk["psi_rad"].nunique()
    out = pd.concat([disk.loc[:, list(DISK_COLUMNS)]] * int(revolutions), ignore_index=True)
    n_r = len(disk) // n_psi
    out["psi_rad"] = np.repeat(2.0 * np.pi * np.arange(n_psi * revolutions) / n_psi, n_r)
    return out


def split_period_harmonics(values: np.ndarray, revolutions: int, highest: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """(low, high) of a field (m N, n_r) over ``revolutions`` = m turns: ``low`` (N, n_r) the once-per-
    revolution harmonics 0…``highest`` (the period's harmonics h = m n, n ≤ ``highest``), ``high``
    (m N, n_r) all the rest (higher harmonics and the rev-to-rev variation, h not a multiple of m)."""
    if revolutions == 1:
        high = remove_low_harmonics(values, highest)
        return values - high, high
    n_rev = values.shape[0] // revolutions
    spectrum = np.fft.rfft(values, axis=0)
    keep = np.zeros(spectrum.shape[0], dtype=bool)
    keep[: revolutions * highest + 1: revolutions] = True
    low = np.fft.irfft(np.where(keep[:, None], spectrum, 0.0), n=values.shape[0], axis=0)
    return low[:n_rev].copy(), values - low


def summary_value(summary: pd.DataFrame, quantity: str, what: str = "loads summary") -> float:
    """One value of a long summary table (columns quantity, value, unit)."""
    rows = summary.loc[summary["quantity"] == quantity, "value"]
    if rows.size != 1:
        raise ValueError(f"{what}: expected one row with quantity '{quantity}', found {rows.size}")
    return float(rows.iloc[0])


def select_trim_row(trim: pd.DataFrame, rotor: str, what: str = "trim.parquet") -> dict:
    """The ``trim.parquet`` row of ``rotor`` as a dict; ValueError naming what is missing."""
    missing = [c for c in TRIM_COLUMNS if c not in trim.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}")
    rows = trim[trim["rotor"] == rotor]
    if len(rows) != 1:
        raise ValueError(f"{what}: expected one row for rotor '{rotor}', found {len(rows)} (rotors {list(trim['rotor'])})")
    return rows.iloc[0].to_dict()


def wake_state(disk: pd.DataFrame, trim_row: Mapping, ct: float) -> wake.WakeState:
    """The wake's flow state from a trimmed disk table, its trim row and the loads' C_T.

    Γ_v(ψ) is the spanwise maximum bound circulation of each azimuth row
    (:func:`nps.wake.vortex.tip_vortex_strength`), the vortex structure its Betz roll-up
    (:func:`nps.wake.vortex.vortex_profile_table`); β(ψ) the flap angle of the outermost station.
    """
    grid = disk_grid(disk)
    missing = [c for c in ("n_blades", "radius_m", "omega_rad_s", "rotation_sign", "mu_x", "mu_y", "mu_z") if c not in trim_row]
    if missing:
        raise ValueError(f"trim row: missing {missing}")
    gamma = disk["circulation_m2_s"].to_numpy(dtype=float).reshape(grid.shape)
    beta = disk["beta_rad"].to_numpy(dtype=float).reshape(grid.shape)
    chord = disk["chord_m"].to_numpy(dtype=float).reshape(grid.shape)
    return wake.WakeState(
        radius_m=float(trim_row["radius_m"]),
        chord_m=float(chord[0, -1]),
        n_blades=int(trim_row["n_blades"]),
        omega_rad_s=float(trim_row["omega_rad_s"]),
        rotation_sign=int(trim_row["rotation_sign"]),
        mu_x=float(trim_row["mu_x"]),
        mu_y=float(trim_row["mu_y"]),
        mu_z=float(trim_row["mu_z"]),
        ct=float(ct),
        gamma_table_m2_s=vortex.tip_vortex_strength(gamma),
        beta_table_rad=beta[:, -1].copy(),
        vortex_profile=vortex.vortex_profile_table(grid.r_m, gamma, float(trim_row["radius_m"])),
    )


def blade_frame_increments(v_hp: np.ndarray, psi_rad: np.ndarray, beta_rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(ΔU_T, ΔU_P) in m/s from an induced velocity (n_psi, n_r, 3) in H' (eq. 5.16–5.17)."""
    psi = np.asarray(psi_rad, dtype=float)[:, None]
    beta = np.broadcast_to(np.asarray(beta_rad, dtype=float), v_hp.shape[:2])
    vx, vy, vz = v_hp[..., 0], v_hp[..., 1], v_hp[..., 2]
    d_ut = vx * np.sin(psi) - vy * np.cos(psi)
    d_up = vx * np.sin(beta) * np.cos(psi) + vy * np.sin(beta) * np.sin(psi) - vz * np.cos(beta)
    return d_ut, d_up


def remove_low_harmonics(values: np.ndarray, highest: int) -> np.ndarray:
    """``values`` (n_psi, n_r) with Fourier harmonics 0…``highest`` in ψ removed per column."""
    spectrum = np.fft.rfft(values, axis=0)
    spectrum[: highest + 1] = 0.0
    return np.fft.irfft(spectrum, n=values.shape[0], axis=0)


def sears(k) -> np.ndarray:
    """Sears function S(k) (complex, e^{iωt} convention, gust referred to the mid-chord)."""
    from scipy import special  # here: only the unsteady BVI loads need it, not every job importing the wake

    k = np.asarray(k, dtype=float)
    out = np.ones(k.shape, dtype=complex)
    pos = k > 0.0
    kp = k[pos]
    h1, h0 = special.hankel2(1, kp), special.hankel2(0, kp)
    theodorsen = h1 / (h1 + 1j * h0)
    out[pos] = (special.j0(kp) - 1j * special.j1(kp)) * theodorsen + 1j * special.j1(kp)
    return out


UT_FLOOR_FRACTION = 0.1  # U_T floor, fraction of ΩR (reversed / near-zero in-plane flow)
MACH_CAP = 0.95  # section Mach number cap of the compressibility factor (as the BET's c_l)
_SEARS_K_MIN, _SEARS_K_MAX, _SEARS_N = 1e-5, 1e3, 8000
_SEARS_STEP = math.log(_SEARS_K_MAX / _SEARS_K_MIN) / _SEARS_N
_LOG_K_MIN, _LOG_K_MAX = math.log(_SEARS_K_MIN), math.log(_SEARS_K_MAX)


@lru_cache(maxsize=1)
def _sears_table() -> np.ndarray:
    """S at k = 0 and at _SEARS_N + 1 log-spaced k in [_SEARS_K_MIN, _SEARS_K_MAX]: (n, 2) re, im."""
    s = sears(np.concatenate([[0.0], np.geomspace(_SEARS_K_MIN, _SEARS_K_MAX, _SEARS_N + 1)]))
    return np.ascontiguousarray(np.stack([s.real, s.imag], axis=1))


@kernel(inline=True)
def _sears_log(log_k, table):
    """S(k) (re, im) from ln k by linear interpolation in the log-spaced table."""
    if log_k < _LOG_K_MIN:
        u = math.exp(log_k) / _SEARS_K_MIN
    else:
        u = 1.0 + (min(log_k, _LOG_K_MAX) - _LOG_K_MIN) / _SEARS_STEP
    i = min(int(u), _SEARS_N)
    w = u - i
    return (1.0 - w) * table[i, 0] + w * table[i + 1, 0], (1.0 - w) * table[i, 1] + w * table[i + 1, 1]


@kernel(inline=True)
def _sears_scaled(log_k, log_inv_beta_sq, table):
    """S(k) with magnitude |S(k/β²)| (phase of S(k)); log_inv_beta_sq = ln(1/β²), 0 = off."""
    s_re, s_im = _sears_log(log_k, table)
    if log_inv_beta_sq != 0.0:
        c_re, c_im = _sears_log(log_k + log_inv_beta_sq, table)
        mag = math.hypot(s_re, s_im)
        if mag > 0.0:
            scale = math.hypot(c_re, c_im) / mag
            s_re, s_im = s_re * scale, s_im * scale
    return s_re, s_im


@kernel
def _transfer_array(k, log_inv_beta_sq, table):
    """S(k) e^{−ik/2} (compressible magnitude) for arrays k ≥ 0 (k = 0 gives 1)."""
    out = np.empty(k.size, dtype=np.complex128)
    for i in range(k.size):
        if k[i] <= 0.0:
            out[i] = 1.0
            continue
        s_re, s_im = _sears_scaled(math.log(k[i]), log_inv_beta_sq[i], table)
        out[i] = complex(s_re, s_im) * complex(math.cos(0.5 * k[i]), -math.sin(0.5 * k[i]))
    return out


def gust_transfer(k, beta_sq=None) -> np.ndarray:
    """Lifting-line gust response factor at reduced frequency k (module doc): S(k) e^{−ik/2},
    with magnitude |S(k/β²)| when ``beta_sq`` (1 − M², broadcast with k) is given
    (compressible), phase unchanged. S is interpolated in a log-spaced table: |error| < 3e-4
    for k ≤ 100 (BVI harmonics), < 1e-2 up to k = 1e3 where |S| < 0.04, S(k > 1e3) = S(1e3)."""
    k = np.asarray(k, dtype=float)
    if np.any(k < 0.0):
        raise ValueError("gust_transfer: reduced frequency must be >= 0")
    log_inv = np.zeros_like(k) if beta_sq is None else np.broadcast_to(-np.log(np.asarray(beta_sq, dtype=float)), k.shape)
    flat = _transfer_array(kernel_array(k.ravel()), kernel_array(log_inv).ravel(), _sears_table())
    return flat.reshape(k.shape)


@kernel(parallel=True)
def _frozen_filter(spectrum, half_chord_time, log_inv_beta_sq, weight, table):
    """y[i, j, m] = Re Σ_n w_n X[n, j, m] S(k) e^{i(nψ_i − k/2)} / N, k = n h[i, j] (module doc)."""
    n_h, n_r, n_f = spectrum.shape
    n_psi = half_chord_time.shape[0]
    log_n = np.log(np.maximum(np.arange(n_h), 1.0))
    out = np.zeros((n_psi, n_r, n_f))
    for j in prange(n_r):
        for i in range(n_psi):
            h = half_chord_time[i, j]
            log_h, lib = math.log(h), log_inv_beta_sq[i, j]
            for m in range(n_f):
                out[i, j, m] = weight[0] * spectrum[0, j, m].real
            for n in range(1, n_h):
                s_re, s_im = _sears_scaled(log_n[n] + log_h, lib, table)
                angle = 2.0 * math.pi * ((i * n) % n_psi) / n_psi - 0.5 * n * h
                c, sn = math.cos(angle), math.sin(angle)
                h_re, h_im = (s_re * c - s_im * sn) * weight[n], (s_re * sn + s_im * c) * weight[n]
                for m in range(n_f):
                    x = spectrum[n, j, m]
                    out[i, j, m] += h_re * x.real - h_im * x.imag
    return out / n_psi


@kernel(parallel=True)
def _frozen_filter_period(spectrum, half_chord_time, log_inv_beta_sq, weight, table, revolutions):
    """:func:`_frozen_filter` of a series over m = ``revolutions`` turns (n_psi = m N samples) whose
    coefficients repeat every turn (``half_chord_time``, ``log_inv_beta_sq``: (N, n_r), harmonic n at n/m per
    turn): at ψ_{r+jN} the phase e^{2πi n(r+jN)/(mN)} = e^{2πi n r/(mN)} e^{2πi (n mod m) j/m}, so per r the
    harmonics are summed into m classes of n mod m, then a length-m sum gives the m samples (O(N n_h + N m²)
    instead of O(m N n_h))."""
    n_h, n_r, n_f = spectrum.shape
    n_rev = half_chord_time.shape[0]
    m = revolutions
    n_psi = n_rev * m
    log_n = np.log(np.maximum(np.arange(n_h), 1.0))
    out = np.zeros((n_psi, n_r, n_f))
    for j in prange(n_r):
        bucket = np.zeros((m, n_f), dtype=np.complex128)
        for r in range(n_rev):
            bucket[:, :] = 0.0
            h = half_chord_time[r, j]
            log_h, lib = math.log(h), log_inv_beta_sq[r, j]
            for f in range(n_f):
                bucket[0, f] += weight[0] * spectrum[0, j, f]
            for n in range(1, n_h):
                s_re, s_im = _sears_scaled(log_n[n] + log_h, lib, table)
                angle = 2.0 * math.pi * ((r * n) % n_psi) / n_psi - 0.5 * n * h
                c, sn = math.cos(angle), math.sin(angle)
                gain = complex((s_re * c - s_im * sn) * weight[n], (s_re * sn + s_im * c) * weight[n])
                for f in range(n_f):
                    bucket[n % m, f] += gain * spectrum[n, j, f]
            for jj in range(m):
                for cls in range(m):
                    angle = 2.0 * math.pi * ((cls * jj) % m) / m
                    c, sn = math.cos(angle), math.sin(angle)
                    for f in range(n_f):
                        x = bucket[cls, f]
                        out[r + jj * n_rev, j, f] += x.real * c - x.imag * sn
    return out / n_psi


def unsteady_response(
    values: np.ndarray,
    ut_mps: np.ndarray,
    omega_rad_s: float,
    radius_m: float,
    chord_m: float,
    speed_of_sound_mps: float | None = None,
    revolutions: int = 1,
) -> np.ndarray:
    """Gust-response-filtered periodic disk field(s) of lifting-line increments (module doc).

    ``values`` (n_psi, n_r) or (n_psi, n_r, m) (m fields filtered together) and ``ut_mps``
    (n_psi, n_r), the in-plane velocity in m/s, on the ψ-major grid ψ_i = 2πi/N. Harmonic n at
    (ψ, r) has k = n Ω c / (2 max(U_T, f ΩR)), f = ``UT_FLOOR_FRACTION``, and is multiplied
    by :func:`gust_transfer` (frozen coefficients). ``speed_of_sound_mps``: compressible
    magnitude with M = U_T / c0 (capped at ``MACH_CAP``); None: incompressible Sears.
    ``revolutions``: the series spans m turns (a common period), harmonic n is at n/m per revolution
    (U_T repeating every turn: :func:`_frozen_filter_period`).
    """
    values = np.asarray(values, dtype=float)
    n_psi, n_r = values.shape[:2]
    ut = np.broadcast_to(np.asarray(ut_mps, dtype=float), (n_psi, n_r))
    if not np.all(np.isfinite(ut)):
        raise ValueError("unsteady_response: ut_mps must be finite")
    if speed_of_sound_mps is not None and not speed_of_sound_mps > 0.0:
        raise ValueError(f"unsteady_response: speed_of_sound_mps must be > 0, got {speed_of_sound_mps}")
    spectrum = np.fft.rfft(values.reshape(n_psi, n_r, -1), axis=0)
    weight = np.full(spectrum.shape[0], 2.0)  # one-sided spectrum
    weight[0] = 1.0
    if n_psi % 2 == 0:
        weight[-1] = 1.0
    speed = np.maximum(ut, UT_FLOOR_FRACTION * omega_rad_s * radius_m)
    half_chord_time = 0.5 * chord_m * omega_rad_s / speed  # k per harmonic number
    if revolutions != 1:
        half_chord_time = half_chord_time / revolutions
    half_chord_time = np.ascontiguousarray(half_chord_time)
    if speed_of_sound_mps is None:
        log_inv_beta_sq = np.zeros((n_psi, n_r))
    else:
        log_inv_beta_sq = np.ascontiguousarray(-np.log(1.0 - np.minimum(speed / speed_of_sound_mps, MACH_CAP) ** 2))
    n_rev = n_psi // revolutions
    if revolutions > 1 and n_rev * revolutions == n_psi and np.array_equal(ut, np.tile(ut[:n_rev], (revolutions, 1))):
        out = _frozen_filter_period(np.ascontiguousarray(spectrum), np.ascontiguousarray(half_chord_time[:n_rev]),
                                    np.ascontiguousarray(log_inv_beta_sq[:n_rev]), weight, _sears_table(), int(revolutions))
    else:
        out = _frozen_filter(np.ascontiguousarray(spectrum), half_chord_time, log_inv_beta_sq, weight, _sears_table())
    return out.reshape(values.shape)


@dataclass(frozen=True)
class BVIResult:
    """BVI disk table (loads schema), induced increments (n_psi, n_r) in m/s, raw H' velocity."""

    disk: pd.DataFrame
    d_ut_mps: np.ndarray
    d_up_mps: np.ndarray
    velocity_hp_mps: np.ndarray


def bvi_loads(
    disk: pd.DataFrame,
    trim_row: Mapping,
    geometry: RotorGeometry,
    ct: float,
    wake_model: wake.WakeModel,
    model: BVIModel = BVIModel(),
) -> BVIResult:
    """BVI-adjusted disk table: the trimmed ``disk`` with the wake's induced velocity added.

    ``trim_row``: this rotor's ``trim.parquet`` row (advance ratios, density, speed of sound);
    ``ct``: the loads' thrust coefficient. Returns a table with exactly the disk-table
    columns, the trim's θ, β and geometry unchanged (no re-trim).
    """
    grid = disk_grid(disk)
    state = wake_state(disk, trim_row, ct)
    beta = disk["beta_rad"].to_numpy(dtype=float).reshape(grid.shape)
    v = wake.disk_induced_velocity(state, wake_model, grid.psi_rad, grid.r_m, beta)
    d_ut, d_up = blade_frame_increments(v, grid.psi_rad, beta)
    if model.removed_harmonics is not None:
        d_ut = remove_low_harmonics(d_ut, model.removed_harmonics)
        d_up = remove_low_harmonics(d_up, model.removed_harmonics)
    return loads_with_increments(disk, trim_row, geometry, d_ut, d_up, v, model)


def loads_with_increments(
    disk: pd.DataFrame,
    trim_row: Mapping,
    geometry: RotorGeometry,
    d_ut: np.ndarray,
    d_up: np.ndarray,
    velocity_hp: np.ndarray,
    model: BVIModel = BVIModel(),
) -> BVIResult:
    """The disk table (one revolution, or m of a common period: :func:`tile_disk`) with lifting-line
    increments (ΔU_T, ΔU_P) (n_psi, n_r) in m/s added:
    gust response (``model.unsteady``, with the disk's U_T) and section loads recomputed with the
    disk's θ (no re-trim). ``velocity_hp`` is only carried into the result."""
    from nps.rotor import bet  # the loads stage; imported here so the wake can be used on its own

    grid = disk_grid(disk, common_period=True)
    if model.unsteady:
        ut0 = disk["ut_mps"].to_numpy(dtype=float).reshape(grid.shape)
        omega, radius = float(trim_row["omega_rad_s"]), float(trim_row["radius_m"])
        filtered = unsteady_response(
            np.stack([d_ut, d_up], axis=-1), ut0, omega, radius, geometry.chord_m, float(trim_row["speed_of_sound_mps"]),
            grid.revolutions,
        )
        d_ut, d_up = filtered[..., 0], filtered[..., 1]
    ut = disk["ut_mps"].to_numpy(dtype=float) + d_ut.ravel()
    up = disk["up_mps"].to_numpy(dtype=float) + d_up.ravel()
    forces = bet.section_forces(
        ut,
        up,
        disk["theta_rad"].to_numpy(dtype=float),
        disk["r_m"].to_numpy(dtype=float),
        geometry,
        float(trim_row["density_kg_m3"]),
        float(trim_row["speed_of_sound_mps"]),
    )
    tip_speed = float(trim_row["omega_rad_s"]) * float(trim_row["radius_m"])
    out = disk.loc[:, list(DISK_COLUMNS)].copy()
    out["ut_mps"] = ut
    out["up_mps"] = up
    out["inflow_ratio"] = disk["inflow_ratio"].to_numpy(dtype=float) + d_up.ravel() / tip_speed
    for column in ("alpha_eff_rad", "mach", "fz_N_per_m", "fx_N_per_m", "circulation_m2_s"):
        out[column] = np.broadcast_to(np.asarray(getattr(forces, column), dtype=float), ut.shape)
    return BVIResult(out.reset_index(drop=True), d_ut, d_up, velocity_hp)
