"""Rotor description shared by the loads, wake, BVI and acoustics stages.

Geometry comes from an aircraft configuration file (``config/aircraft/*.yaml``, validated
by ``workflow/schemas/aircraft.schema.yaml``); the operating point comes from the aircraft
trim artifact (``trim.parquet``, one row per rotor). Frames and signs: docs/conventions.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np


@dataclass(frozen=True)
class Airfoil:
    """Section aerodynamics.

    c_l = a (α − α0) / sqrt(1 − M²) (Prandtl–Glauert, M capped at ``mach_cap``), limited to
    ±``cl_max``; c_d = cd0 + cd1 α + cd2 α² (α in rad).
    """

    lift_slope_per_rad: float = 5.73
    alpha0_rad: float = 0.0
    cl_max: float = 1.4
    cd0: float = 0.008
    cd1: float = 0.0
    cd2: float = 0.4
    mach_cap: float = 0.95


@dataclass(frozen=True)
class RotorGeometry:
    """Blade and hub description of one rotor (SI units).

    Pitch θ(ψ, r) = θ0 + θ1c cos ψ + θ1s sin ψ + θtw(r), with linear twist
    θtw(r) = twist_rad · (r/R − 0.75) so that θ0 is the pitch at 75 % radius.
    ``thickness_ratio`` t/c of the section; ``hinge_offset_m`` e of the flap hinge;
    ``lock_number`` γ = ρ a c R⁴ / I_β (at the reference density of the configuration).

    Optional prescribed blade motion (e.g. a wind-tunnel test run as measured; empty = none):
    ``higher_harmonic_pitch`` ((n, θ_n rad, ψ_n rad), ...) adds Σ θ_n cos(nψ − ψ_n) to the pitch
    of the whole blade (higher-harmonic control); ``elastic_twist_harmonics`` ((n, c_n rad,
    s_n rad), ...) adds (r/R) Σ (c_n cos nψ + s_n sin nψ), an elastic torsion given at the tip
    and linear along the span (n = 0 is the mean).
    """

    name: str
    n_blades: int
    radius_m: float
    chord_m: float
    root_cutout_m: float
    twist_rad: float
    thickness_ratio: float
    lock_number: float
    hinge_offset_m: float = 0.0
    rotation_sign: int = 1
    airfoil: Airfoil = field(default_factory=Airfoil)
    higher_harmonic_pitch: tuple[tuple[int, float, float], ...] = ()
    elastic_twist_harmonics: tuple[tuple[int, float, float], ...] = ()

    @property
    def solidity(self) -> float:
        """σ = B c / (π R)."""
        return self.n_blades * self.chord_m / (np.pi * self.radius_m)

    def twist_at(self, r_m) -> np.ndarray:
        """θtw(r) in rad."""
        return self.twist_rad * (np.asarray(r_m, dtype=float) / self.radius_m - 0.75)

    def prescribed_pitch(self, psi_rad, r_m) -> np.ndarray | None:
        """Prescribed pitch (rad), (n_psi, n_r), of the higher-harmonic and elastic-twist
        inputs at azimuths ``psi_rad`` (n_psi,) and stations ``r_m`` (n_r,); None without them."""
        if not (self.higher_harmonic_pitch or self.elastic_twist_harmonics):
            return None
        psi = np.asarray(psi_rad, dtype=float)[:, None]
        rbar = np.asarray(r_m, dtype=float)[None, :] / self.radius_m
        hhc = sum((amp * np.cos(n * psi - phase) for n, amp, phase in self.higher_harmonic_pitch), np.zeros_like(psi))
        elastic = sum((c * np.cos(n * psi) + s * np.sin(n * psi) for n, c, s in self.elastic_twist_harmonics),
                      np.zeros_like(psi))
        return hhc + rbar * elastic

    @classmethod
    def from_config(cls, rotor: Mapping) -> "RotorGeometry":
        """Build from one validated ``rotors[]`` entry of an aircraft configuration.

        Optional prescribed motion entries: ``higher_harmonic_pitch: [{n, amplitude_deg,
        phase_deg}, ...]``, ``elastic_twist_harmonics: [{n, cos_deg, sin_deg}, ...]``.
        """
        foil = rotor.get("airfoil", {})
        airfoil = Airfoil(
            lift_slope_per_rad=float(foil.get("lift_slope_per_rad", Airfoil.lift_slope_per_rad)),
            alpha0_rad=np.radians(float(foil.get("alpha0_deg", 0.0))),
            cl_max=float(foil.get("cl_max", Airfoil.cl_max)),
            cd0=float(foil.get("cd0", Airfoil.cd0)),
            cd1=float(foil.get("cd1", Airfoil.cd1)),
            cd2=float(foil.get("cd2", Airfoil.cd2)),
            mach_cap=float(foil.get("mach_cap", Airfoil.mach_cap)),
        )
        return cls(
            name=str(rotor["name"]),
            n_blades=int(rotor["n_blades"]),
            radius_m=float(rotor["radius_m"]),
            chord_m=float(rotor["chord_m"]),
            root_cutout_m=float(rotor["root_cutout_m"]),
            twist_rad=np.radians(float(rotor["twist_deg"])),
            thickness_ratio=float(rotor["thickness_ratio"]),
            lock_number=float(rotor["lock_number"]),
            hinge_offset_m=float(rotor.get("hinge_offset_m", 0.0)),
            rotation_sign=1 if rotor["rotation"] == "ccw" else -1,
            airfoil=airfoil,
            higher_harmonic_pitch=tuple(
                (int(h["n"]), math.radians(float(h["amplitude_deg"])), math.radians(float(h["phase_deg"])))
                for h in rotor.get("higher_harmonic_pitch", ())),
            elastic_twist_harmonics=tuple(
                (int(h["n"]), math.radians(float(h["cos_deg"])), math.radians(float(h["sin_deg"])))
                for h in rotor.get("elastic_twist_harmonics", ())),
        )


@dataclass(frozen=True)
class OperatingPoint:
    """Steady operating state of one rotor from the aircraft trim (one ``trim.parquet`` row).

    Advance ratios in the hub frame (docs/conventions.md): μ_x, μ_y in plane, μ_z positive
    when the free stream goes down through the disk. Targets: thrust along +z_H and hub
    moments about x_H (roll) and y_H (pitch).
    """

    omega_rad_s: float
    mu_x: float
    mu_y: float
    mu_z: float
    density_kg_m3: float
    speed_of_sound_mps: float
    thrust_N: float
    roll_moment_Nm: float = 0.0
    pitch_moment_Nm: float = 0.0

    @classmethod
    def from_trim_row(cls, row: Mapping) -> "OperatingPoint":
        return cls(
            omega_rad_s=float(row["omega_rad_s"]),
            mu_x=float(row["mu_x"]),
            mu_y=float(row["mu_y"]),
            mu_z=float(row["mu_z"]),
            density_kg_m3=float(row["density_kg_m3"]),
            speed_of_sound_mps=float(row["speed_of_sound_mps"]),
            thrust_N=float(row["thrust_N"]),
            roll_moment_Nm=float(row["roll_moment_Nm"]),
            pitch_moment_Nm=float(row["pitch_moment_Nm"]),
        )


@dataclass(frozen=True)
class RotorMotion:
    """Rigid motion of a rotor hub in the ground frame G (one ``trim.parquet`` row).

    Hub position at time t: hub_position_m + velocity_mps · t. ``r_gh`` takes H components
    to G components. Blade k azimuth ψ_k(t) = Ω t + 2πk/B.
    """

    hub_position_m: np.ndarray
    velocity_mps: np.ndarray
    r_gh: np.ndarray
    omega_rad_s: float
    rotation_sign: int
    n_blades: int

    @classmethod
    def from_trim_row(cls, row: Mapping) -> "RotorMotion":
        return cls(
            hub_position_m=np.array([row["hub_x_m"], row["hub_y_m"], row["hub_z_m"]], dtype=float),
            velocity_mps=np.array([row["vel_x_mps"], row["vel_y_mps"], row["vel_z_mps"]], dtype=float),
            r_gh=np.array([[row[f"r_gh_{i}{j}"] for j in range(3)] for i in range(3)], dtype=float),
            omega_rad_s=float(row["omega_rad_s"]),
            rotation_sign=int(row["rotation_sign"]),
            n_blades=int(row["n_blades"]),
        )
