"""Synthetic aircraft for the rotor–rotor interaction tests: identical 3-bladed rotors placed
freely, trimmed by ``nps.rotor.bet`` to a thrust coefficient, and the artifacts the ``wake`` job reads
(trim table, rotor configs, loads disk tables and summaries) built in memory.

Rotor: R = 5 m, c = 0.35 m (σ = 0.067), −10° twist, root cutout 0.2 R, Lock number 6, hinge
offset 5 % R, Ω = 40 rad/s; ISA sea level. Hub frames share the G axes (r_gh = I).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry

RADIUS_M, OMEGA, RHO, C0 = 5.0, 40.0, 1.225, 340.0


def geometry(name: str, sign: int, radius_m: float = RADIUS_M) -> RotorGeometry:
    return RotorGeometry(name=name, n_blades=3, radius_m=radius_m, chord_m=0.07 * radius_m, root_cutout_m=0.2 * radius_m,
                         twist_rad=np.radians(-10.0), thickness_ratio=0.1, lock_number=6.0,
                         hinge_offset_m=0.05 * radius_m, rotation_sign=sign)


def rotor_config(g: RotorGeometry) -> dict:
    """The validated-config form of ``g`` (``rotors[]`` entry)."""
    return dict(name=g.name, n_blades=g.n_blades, radius_m=g.radius_m, chord_m=g.chord_m, root_cutout_m=g.root_cutout_m,
                twist_deg=float(np.degrees(g.twist_rad)), thickness_ratio=g.thickness_ratio, lock_number=g.lock_number,
                hinge_offset_m=g.hinge_offset_m, rotation="ccw" if g.rotation_sign == 1 else "cw")


def artifacts(layout, mu_x: float = 0.1, mu_z: float = -0.01, ct: float = 0.005, n_psi: int = 72, n_r: int = 16,
              radius_m: float = RADIUS_M, omega: float = OMEGA):
    """(trim, rotor configs, disks, summaries) for ``layout`` = [(name, rotation sign, hub (3,) m), ...]."""
    rows, configs, disks, summaries = [], {}, {}, {}
    thrust = ct * RHO * np.pi * radius_m**2 * (omega * radius_m) ** 2
    for name, sign, hub in layout:
        g = geometry(name, sign, radius_m)
        loads = bet.trim_rotor(g, OperatingPoint(omega, mu_x, 0.0, mu_z, RHO, C0, thrust), bet.DiskGrid(n_psi, n_r))
        row = dict(rotor=name, rotation_sign=sign, n_blades=g.n_blades, radius_m=radius_m, omega_rad_s=omega, mu_x=mu_x,
                   mu_y=0.0, mu_z=mu_z, ct=ct, density_kg_m3=RHO, speed_of_sound_mps=C0, thrust_N=thrust,
                   roll_moment_Nm=0.0, pitch_moment_Nm=0.0)
        rows.append(placed(row, hub))
        configs[name], disks[name], summaries[name] = rotor_config(g), loads.disk, loads.summary()
    return pd.DataFrame(rows), configs, disks, summaries


def placed(row: dict, hub_m=(0.0, 0.0, 0.0)) -> dict:
    """A trim-table row for a rotor whose hub sits at ``hub_m`` (m, G axes) at t = 0, hub frame
    along the G axes (r_gh = I), aircraft not moving in that frame."""
    out = dict(row, hub_x_m=float(hub_m[0]), hub_y_m=float(hub_m[1]), hub_z_m=float(hub_m[2]),
               vel_x_mps=0.0, vel_y_mps=0.0, vel_z_mps=0.0)
    out.update({f"r_gh_{i}{j}": float(i == j) for i in range(3) for j in range(3)})
    return out


def induced_power_W(disk: pd.DataFrame, n_blades: int = 3) -> float:
    """Induced power of a hovering rotor's disk table: B/N_ψ Σ F_z U_P dr (W)."""
    n_psi = disk["psi_rad"].nunique()
    return n_blades / n_psi * float(np.sum(disk["fz_N_per_m"] * disk["up_mps"] * disk["dr_m"]))


def mean_inflow_mps(disk: pd.DataFrame) -> float:
    """Area-weighted mean U_P over the disk (m/s, + down through the disk)."""
    return float(np.average(disk["up_mps"], weights=disk["r_m"] * disk["dr_m"]))
