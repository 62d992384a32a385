"""Rotor broadband noise: Pegg's semi-empirical 1/3-octave spectrum (NASA TM-80200, 1979).

Thesis eq. 3.1-3.3, with Pegg's normalised spectrum shape as PSU-WOPWOP codes it
(tests/data/pegg/pegg_broadband_spectrum_psuwopwop.csv):

- peak frequency (eq. 3.1)  f_p = −240·log10(T) + 2.448·V_T + 942  [Hz], T thrust in N, V_T tip
  speed in m/s. Units: TM-80200 states this fit in SI (thrust in newtons, tip speed in m/s), and
  PSU-WOPWOP codes it in the same units; it gives a peak of a few hundred Hz for a 5-t helicopter,
  as in Pegg's data (imperial units would move it to ≈ 1.7 kHz).
- 1/3-octave level (eq. 3.2)  SPL(n) = 60·log10(V_T/c0) + 10·log10(A_b/r²·(cos²θ + 0.1)) + S(n − n_p)
  + f(C̄_L) + 130  [dB re 20 µPa], n_p the base-10 band containing f_p, A_b = B·c·R the total blade
  area (m²), r the hub-observer distance (m), θ the angle between the rotor axis and the hub-observer
  line (only cos²θ enters, so the sign of the axis does not matter).
- lift term (eq. 3.3)  f(C̄_L) = 10·log10(C̄_L/0.4) for C̄_L ≤ 0.48, else 0.8 + 80·log10(C̄_L/0.48),
  with the mean lift coefficient C̄_L = 6·C_T/σ (blade-element theory, uniform lift).

Spectrum shape S: Pegg gives it at whole-octave offsets from the peak band (−5…+7 octaves); NPS
uses PSU-WOPWOP's interpolated values for every 1/3-octave band in between (its ``spreadBands``
option) *without* its energy offset (``keepEnergyConst``, −4.5458 dB), because eq. 3.2 defines a
1/3-octave band level: the peak band keeps exactly the eq. 3.2 level and every band of the
continuous spectrum is a 1/3-octave level on the same curve. Bands beyond the table carry no energy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.noise.spectra import LEVEL_FLOOR_DB, band_number_of

# S(n − n_p) (dB) for offsets −15…+21 1/3-octave bands (PSU-WOPWOP GetPeggInterpSpectrum)
SHAPE_OFFSET_MIN = -15
SHAPE_DB = np.array([
    -29.0, -27.83035528, -26.35669527, -24.5, -23.20039475, -21.56299474, -19.5, -18.40833159,
    -17.03291558, -15.3, -14.36428422, -13.18535621, -11.7, -10.60833159, -9.232915582, -7.5,
    -8.5396842, -9.849604208, -11.5, -11.65595263, -11.85244063, -12.1, -13.24365262, -14.68456463,
    -16.5, -16.62996052, -16.79370053, -17.0, -18.24762104, -19.81952505, -21.8, -22.99563683,
    -24.50204484, -26.4, -27.33571578, -28.51464379, -30.0,
])


@dataclass(frozen=True)
class PeggRotor:
    """Rotor operating state for Pegg's model (SI units).

    ``thrust_N`` rotor thrust, ``tip_speed_mps`` ΩR, ``blade_area_m2`` A_b = B·c·R,
    ``mean_lift_coefficient`` C̄_L (see :func:`mean_lift_coefficient`).
    """

    thrust_N: float
    tip_speed_mps: float
    blade_area_m2: float
    mean_lift_coefficient: float

    def __post_init__(self):
        for name in ("thrust_N", "tip_speed_mps", "blade_area_m2", "mean_lift_coefficient"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0.0):
                raise ValueError(f"PeggRotor.{name} must be finite and positive, got {value}")


def mean_lift_coefficient(ct: float, solidity: float) -> float:
    """C̄_L = 6 C_T / σ (C_T = T/(ρ π R² (ΩR)²), σ = B c/(π R))."""
    if not (solidity > 0.0):
        raise ValueError(f"solidity must be positive, got {solidity}")
    return 6.0 * ct / solidity


def peak_frequency_hz(thrust_N: float, tip_speed_mps: float) -> float:
    """Pegg's broadband peak frequency f_p (Hz), eq. 3.1 (T in N, V_T in m/s)."""
    fp = -240.0 * np.log10(thrust_N) + 2.448 * tip_speed_mps + 942.0
    if not fp > 0.0:
        raise ValueError(
            f"Pegg peak frequency is not positive ({fp:.1f} Hz) for T={thrust_N} N, V_T={tip_speed_mps} m/s"
        )
    return float(fp)


def lift_term_db(mean_cl: float) -> float:
    """f(C̄_L) (dB), eq. 3.3."""
    if mean_cl <= 0.48:
        return float(10.0 * np.log10(mean_cl / 0.4))
    return float(0.8 + 80.0 * np.log10(mean_cl / 0.48))


def shape_db(offset) -> np.ndarray:
    """Normalised spectrum S (dB) at integer 1/3-octave offsets from the peak band; NaN outside."""
    k = np.asarray(offset, dtype=np.int64) - SHAPE_OFFSET_MIN
    inside = (k >= 0) & (k < SHAPE_DB.size)
    return np.where(inside, SHAPE_DB[np.clip(k, 0, SHAPE_DB.size - 1)], np.nan)


def band_levels_db(
    rotor: PeggRotor,
    band_numbers,
    distance_m,
    cos_theta,
    speed_of_sound_mps: float,
) -> np.ndarray:
    """Pegg 1/3-octave levels (dB re 20 µPa), shape (n_observers, n_bands).

    ``band_numbers``: base-10 band numbers (0 = 1 kHz); ``distance_m``, ``cos_theta``: per
    observer, hub-observer distance (m) and cosine of the angle from the rotor axis. Bands
    outside the shape table get LEVEL_FLOOR_DB.
    """
    r = np.atleast_1d(np.asarray(distance_m, dtype=float))
    cos_t = np.atleast_1d(np.asarray(cos_theta, dtype=float))
    if r.shape != cos_t.shape or r.ndim != 1:
        raise ValueError(f"distance_m and cos_theta must be 1-D of equal length, got {r.shape}, {cos_t.shape}")
    if np.any(~np.isfinite(r)) or np.any(r <= 0.0):
        raise ValueError("Pegg: observer distance_m must be finite and positive")
    if np.any(~np.isfinite(cos_t)) or np.any(np.abs(cos_t) > 1.0 + 1e-12):
        raise ValueError("Pegg: cos_theta must lie in [-1, 1]")
    if not speed_of_sound_mps > 0.0:
        raise ValueError(f"speed_of_sound_mps must be positive, got {speed_of_sound_mps}")
    bands = np.atleast_1d(np.asarray(band_numbers, dtype=np.int64))
    n_peak = int(band_number_of(peak_frequency_hz(rotor.thrust_N, rotor.tip_speed_mps)))
    shape = shape_db(bands - n_peak)
    base = (
        60.0 * np.log10(rotor.tip_speed_mps / speed_of_sound_mps)
        + 10.0 * np.log10(rotor.blade_area_m2 / r**2 * (cos_t**2 + 0.1))
        + lift_term_db(rotor.mean_lift_coefficient)
        + 130.0
    )
    levels = base[:, None] + shape[None, :]
    return np.where(np.isnan(levels), LEVEL_FLOOR_DB, np.maximum(levels, LEVEL_FLOOR_DB))


def observer_geometry(hub_m, axis, observers_m) -> tuple[np.ndarray, np.ndarray]:
    """Distance (m) and cos θ from a hub at ``hub_m`` with unit thrust ``axis`` to ``observers_m`` (n, 3).

    Pegg's model is empirical: the geometry is taken at the same instant for hub and observer
    (no retarded-time correction); for observers moving with the aircraft it is constant.
    """
    d = np.asarray(observers_m, dtype=float) - np.asarray(hub_m, dtype=float)[None, :]
    dist = np.linalg.norm(d, axis=1)
    if np.any(dist <= 0.0):
        raise ValueError("Pegg: an observer coincides with the rotor hub")
    axis = np.asarray(axis, dtype=float)
    return dist, d @ (axis / np.linalg.norm(axis)) / dist


# Pegg's method was built on and compared with full-scale helicopter *main* rotors. TM-80200 does
# not tabulate a validity envelope; NPS states the span of that class of rotors (light to heavy
# helicopters of the data's era, from R ≈ 4 m / T ≈ 10 kN to R ≈ 12 m / T ≈ 350 kN, tip speeds
# 180-240 m/s) and warns outside it (docs/reference/broadband_metrics.md).
PEGG_DATA_RANGE = {"radius_m": (4.0, 12.0), "tip_speed_mps": (180.0, 240.0), "thrust_N": (1.0e4, 3.5e5)}


def pegg_outside_range(radius_m: float, tip_speed_mps: float, thrust_N: float) -> list[str]:
    """Messages naming each rotor quantity outside PEGG_DATA_RANGE; an empty list when inside."""
    values = {"radius_m": radius_m, "tip_speed_mps": tip_speed_mps, "thrust_N": thrust_N}
    messages = []
    for name, value in values.items():
        if not np.isfinite(value):
            raise ValueError(f"pegg_outside_range: {name} must be finite, got {value}")
        low, high = PEGG_DATA_RANGE[name]
        if not low <= value <= high:
            messages.append(f"{name}={value:g} outside Pegg's helicopter main-rotor range [{low:g}, {high:g}]")
    return messages
