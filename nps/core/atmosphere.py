"""Atmosphere: ISA troposphere state and (see below) ISO 9613-1 absorption.

ISA (ICAO Doc 7488) below 11 km: T = T0 − L h + ΔT, p = p0 (1 − L h / T0)^(g/(R L)) with
T0 = 288.15 K, p0 = 101 325 Pa, L = 0.0065 K/m; a temperature offset ΔT changes T and ρ but
not p (the usual "ISA + ΔT" convention). ρ = p/(R T), c = sqrt(γ R T).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

GAS_CONSTANT_J_KG_K = 287.05287
GAMMA_AIR = 1.4
G0_M_S2 = 9.80665
T0_K = 288.15
P0_PA = 101_325.0
LAPSE_K_M = 0.0065


@dataclass(frozen=True)
class AtmosphereState:
    """Static air state: temperature (K), pressure (Pa), density (kg/m³), sound speed (m/s)."""

    temperature_k: float
    pressure_pa: float
    density_kg_m3: float
    speed_of_sound_mps: float
    relative_humidity_pct: float


def isa(altitude_m: float, delta_t_k: float = 0.0, relative_humidity_pct: float = 70.0) -> AtmosphereState:
    """ISA + ΔT state at geopotential ``altitude_m`` (0 ≤ h ≤ 11 000 m)."""
    if not 0.0 <= altitude_m <= 11_000.0:
        raise ValueError(f"altitude_m must be within 0..11000 m (troposphere), got {altitude_m}")
    temperature = T0_K - LAPSE_K_M * altitude_m + delta_t_k
    pressure = P0_PA * (1.0 - LAPSE_K_M * altitude_m / T0_K) ** (G0_M_S2 / (GAS_CONSTANT_J_KG_K * LAPSE_K_M))
    density = pressure / (GAS_CONSTANT_J_KG_K * temperature)
    speed = float(np.sqrt(GAMMA_AIR * GAS_CONSTANT_J_KG_K * temperature))
    return AtmosphereState(temperature, pressure, density, speed, relative_humidity_pct)


# ------------------------------------------------------------------ ISO 9613-1 air absorption
ISO_T0_K = 293.15  # reference temperature
ISO_T01_K = 273.16  # triple-point isotherm temperature
ISO_PR_PA = 101_325.0  # reference pressure


def absorption_db_per_m(frequency_hz, temperature_k, relative_humidity_pct, pressure_pa):
    """Pure-tone atmospheric absorption coefficient α (dB/m), ISO 9613-1:1993 eq. (3)-(5), (B.1)-(B.3).

    h = h_r·(p_sat/p_r)/(p_a/p_r) with p_sat/p_r = 10^C, C = −6.8346 (T01/T)^1.261 + 4.6151;
    relaxation frequencies f_rO = (p_a/p_r)(24 + 4.04e4 h (0.02 + h)/(0.391 + h)) and
    f_rN = (p_a/p_r)(T/T0)^(−1/2)(9 + 280 h exp{−4.170[(T/T0)^(−1/3) − 1]});
    α = 8.686 f² [1.84e−11 (p_a/p_r)^(−1)(T/T0)^(1/2) + (T/T0)^(−5/2)(0.01275 e^(−2239.1/T)/(f_rO + f²/f_rO)
    + 0.1068 e^(−3352.0/T)/(f_rN + f²/f_rN))]. Arguments broadcast. Valid (±10 %) for
    50 Hz–10 kHz, −20…50 °C, 10…100 % RH, p < 200 kPa; computed outside too.
    """
    f = np.asarray(frequency_hz, dtype=float)
    t = np.asarray(temperature_k, dtype=float)
    rh = np.asarray(relative_humidity_pct, dtype=float)
    pa = np.asarray(pressure_pa, dtype=float)
    if np.any(~np.isfinite(f)) or np.any(f < 0.0):
        raise ValueError(f"absorption_db_per_m: frequency_hz must be finite and >= 0, got {f}")
    for name, value in (("temperature_k", t), ("pressure_pa", pa)):
        if np.any(~np.isfinite(value)) or np.any(value <= 0.0):
            raise ValueError(f"absorption_db_per_m: {name} must be finite and positive, got {value}")
    if np.any(~np.isfinite(rh)) or np.any((rh < 0.0) | (rh > 100.0)):
        raise ValueError(f"absorption_db_per_m: relative_humidity_pct must be within 0..100, got {rh}")
    p_ratio = pa / ISO_PR_PA
    t_ratio = t / ISO_T0_K
    c_exp = -6.8346 * (ISO_T01_K / t) ** 1.261 + 4.6151
    h = rh * 10.0**c_exp / p_ratio
    fr_o = p_ratio * (24.0 + 4.04e4 * h * (0.02 + h) / (0.391 + h))
    fr_n = p_ratio * t_ratio**-0.5 * (9.0 + 280.0 * h * np.exp(-4.170 * (t_ratio ** (-1.0 / 3.0) - 1.0)))
    f2 = f * f
    return 8.686 * f2 * (
        1.84e-11 / p_ratio * np.sqrt(t_ratio)
        + t_ratio**-2.5
        * (0.01275 * np.exp(-2239.1 / t) / (fr_o + f2 / fr_o) + 0.1068 * np.exp(-3352.0 / t) / (fr_n + f2 / fr_n))
    )


def _absorption_loss_db(frequency_hz, distance_m, state: AtmosphereState) -> np.ndarray:
    """Loss α(f)·r (dB, ≥ 0) over radiation distance ``distance_m``; thesis eq. 3.4.

    Eq. 3.4 writes ΔdB = −10 log10 e^{2 α' r} with α' the amplitude attenuation in Np/m; since
    ISO's α (dB/m) = 20 log10(e)·α' = 8.686 α', this is ΔdB = −α r.
    """
    r = np.asarray(distance_m, dtype=float)
    if np.any(~np.isfinite(r)) or np.any(r < 0.0):
        raise ValueError(f"radiation distance_m must be finite and >= 0, got {r}")
    alpha = absorption_db_per_m(frequency_hz, state.temperature_k, state.relative_humidity_pct, state.pressure_pa)
    return alpha * r


def absorb_band_levels(band_levels_db, center_hz, distance_m, state: AtmosphereState) -> np.ndarray:
    """Band levels (dB, bands on the last axis) after absorption over ``distance_m`` (m).

    Uses α at each band's exact mid-band frequency ``center_hz`` (ISO 9613-1 §8.2.1 approximation
    for 1/3-octave bands); ``distance_m`` broadcasts against the leading axes (append an axis).
    """
    return np.asarray(band_levels_db, dtype=float) - _absorption_loss_db(center_hz, distance_m, state)


def absorb_msp(frequency_hz, msp_pa2, distance_m, state: AtmosphereState) -> np.ndarray:
    """Narrowband MSP (Pa², frequency on the last axis) after absorption over ``distance_m`` (m).

    The 0 Hz line is left unchanged (α(0) = 0).
    """
    loss = _absorption_loss_db(frequency_hz, distance_m, state)
    return np.asarray(msp_pa2, dtype=float) * 10.0 ** (-loss / 10.0)


def periodic_absorption_gain(n_samples: int, dt_s: float, distance_m, state: AtmosphereState) -> np.ndarray:
    """Amplitude gain 10^(−α(f) r / 20) (−) of the Fourier lines f_k = k/(N dt), k = 0…N/2, of a
    periodic record of N = ``n_samples`` samples every ``dt_s`` s, over ``distance_m`` (m; scalar
    or array): shape distance_m.shape + (N//2 + 1,)."""
    f = np.fft.rfftfreq(n_samples, dt_s)
    r = np.asarray(distance_m, dtype=float)[..., None]
    return 10.0 ** (-_absorption_loss_db(f, r, state) / 20.0)


def apply_line_gain(p_pa, gain) -> np.ndarray:
    """Periodic record p (Pa, time on the last axis, N samples) with each Fourier line scaled by
    ``gain`` (shape broadcasting against p.shape[:-1] + (N//2 + 1,)), zero phase."""
    p = np.asarray(p_pa, dtype=float)
    return np.fft.irfft(np.fft.rfft(p, axis=-1) * gain, n=p.shape[-1], axis=-1)


def absorb_periodic_signal(p_pa, dt_s: float, distance_m, state: AtmosphereState) -> np.ndarray:
    """Periodic pressure record (Pa, time on the last axis) after absorption over ``distance_m``.

    Each Fourier line of the record is scaled by 10^(−α(f) r / 20) (zero phase,
    :func:`periodic_absorption_gain`): exact for a record that is one period of the signal.
    ``distance_m``: scalar or one value per record (shape p.shape[:-1]).
    """
    p = np.asarray(p_pa, dtype=float)
    return apply_line_gain(p, periodic_absorption_gain(p.shape[-1], dt_s, distance_m, state))
