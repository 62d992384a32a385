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
