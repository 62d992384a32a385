"""Loads at a radial station: the normal-force coefficient C_n and M²C_n of a blade section against azimuth.

The HART-II convention (van der Wall et al.; the measured ``CnM2_*`` data of tests/data/hart_ii/):

- M²c_n = F_n / (½ ρ a² c): F_n the section normal force per span (N/m, the disk table's ``fz_N_per_m``,
  along the thrust axis), ρ the density, a the speed of sound, c the local chord (``chord_m``);
- c_n = F_n / (½ ρ U² c) = M²c_n / M², U = M a the section's resultant speed (the disk table's ``mach``).

At a station r/R between two of the disk table's radial stations, both are interpolated linearly in r (the
stations are the midpoints of the radial elements; a station outside the first and last is refused, not
extrapolated). Works on any loads-schema disk table (the trimmed loads or the loads with the wake's induced
velocity), of a rig's rotor or an aircraft's.
"""

from __future__ import annotations

from typing import Sequence

import numpy as np
import pandas as pd

STATION_COLUMNS = ("rotor", "r_over_R", "psi_rad", "cn", "m2cn")
DISK_COLUMNS = ("psi_rad", "r_m", "chord_m", "mach", "fz_N_per_m")


def m2cn(fz_N_per_m, density_kg_m3: float, speed_of_sound_mps: float, chord_m) -> np.ndarray:
    """M²c_n = F_n / (½ ρ a² c) of section normal forces per span ``fz_N_per_m`` (N/m), chord ``chord_m`` (m)."""
    return np.asarray(fz_N_per_m) / (0.5 * density_kg_m3 * speed_of_sound_mps**2 * chord_m)


def _grid(disk: pd.DataFrame, what: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ψ (n_psi,), r (n_r,), row order) of a disk table: every (ψ, r) pair once, any row order."""
    missing = [c for c in DISK_COLUMNS if c not in disk.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}")
    psi, r = disk["psi_rad"].to_numpy(dtype=float), disk["r_m"].to_numpy(dtype=float)
    psi_u, r_u = np.unique(psi), np.unique(r)
    if psi_u.size * r_u.size != psi.size or r_u.size < 2:
        raise ValueError(f"{what}: expected a disk table of every azimuth x radius pair once (at least 2 radii), got "
                         f"{psi.size} rows for {psi_u.size} azimuths x {r_u.size} radii")
    return psi_u, r_u, np.lexsort((r, psi))


def station_loads(disk: pd.DataFrame, rotor: str, radius_m: float, density_kg_m3: float, speed_of_sound_mps: float,
                  stations_r_over_R: Sequence[float], what: str | None = None) -> pd.DataFrame:
    """C_n and M²c_n against azimuth at each station r/R of ``stations_r_over_R`` (module doc) of one rotor's
    disk table: columns :data:`STATION_COLUMNS`, station-major, azimuth ascending. ``radius_m``: the rotor
    radius R; ``density_kg_m3``, ``speed_of_sound_mps``: the trim row's. Raises ValueError naming ``what``
    (default: the rotor's disk table) and the station when it lies outside the table's radial stations."""
    what = what or f"rotor '{rotor}' disk table"
    psi, r, order = _grid(disk, what)
    shape = (psi.size, r.size)
    column = {c: disk[c].to_numpy(dtype=float)[order].reshape(shape) for c in DISK_COLUMNS[2:]}
    m2 = m2cn(column["fz_N_per_m"], density_kg_m3, speed_of_sound_mps, column["chord_m"])
    cn = m2 / column["mach"] ** 2
    parts = []
    for station in stations_r_over_R:
        target = float(station) * float(radius_m)
        if not r[0] <= target <= r[-1]:
            raise ValueError(f"{what}: station r/R {station}: outside the table's radial stations r/R "
                             f"[{r[0] / radius_m:.6g}, {r[-1] / radius_m:.6g}] (loads are interpolated, not extrapolated)")
        j = min(int(np.searchsorted(r, target, side="right")) - 1, r.size - 2)
        w = (target - r[j]) / (r[j + 1] - r[j])
        parts.append(pd.DataFrame({
            "rotor": rotor, "r_over_R": float(station), "psi_rad": psi,
            "cn": (1.0 - w) * cn[:, j] + w * cn[:, j + 1], "m2cn": (1.0 - w) * m2[:, j] + w * m2[:, j + 1],
        }))
    return pd.concat(parts, ignore_index=True).loc[:, list(STATION_COLUMNS)]
