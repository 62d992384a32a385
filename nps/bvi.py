"""Blade–vortex-interaction loads: the tip-vortex wake's induced velocity added to the BET.

Thesis eq. 5.16–5.17: the wake-induced velocity v (``nps.wake``, frame H') at each disk
station is resolved into the blade frame and added to the trimmed disk table's velocities,

    ΔU_T = −v·e_t,   e_t = (−sin ψ, cos ψ, 0)                (blade motion direction)
    ΔU_P = −v·n,     n   = (−sin β cos ψ, −sin β sin ψ, cos β) (blade normal, flap β)

(U_T positive toward the leading edge, U_P positive down through the disk), and the sectional
loads are recomputed with ``nps.bet.section_forces`` without re-trimming.

The trimmed loads already carry the wake's mean and once-per-revolution effect through the
BET's inflow model (λ0, kx, ky) and its trim, so by default the 0 and 1/rev Fourier
harmonics of v (per radial station) are removed before adding: what is added is the
impulsive, higher-harmonic part the linear inflow cannot represent
(``BVIModel.removed_harmonics``; ``None`` adds the raw velocity as the thesis did).

Unsteady response (``BVIModel.unsteady``): in the blade frame an old tip vortex is a gust
convected past the section at ≈ U_T, with a width of the order of the chord (r_c ≈ c/2), so
the quasi-steady lift overstates the impulsive response. Each harmonic n of the increments at
radius r is multiplied by the Sears function S(k_n) of the reduced frequency
k_n = n Ω (c/2) / (Ω r) = n c / (2r) (time dependence e^{inψ}, ψ = Ωt),

    S(k) = [J0(k) − i J1(k)] C(k) + i J1(k),   C(k) = H1⁽²⁾(k) / (H1⁽²⁾(k) + i H0⁽²⁾(k))

(Theodorsen's C), referred to the mid-chord: the lifting-line value (quarter chord) reaches
the mid-chord a quarter chord later, a factor e^{−in c/(4r)}. S → 1 as k → 0, |S| ≈ 0.4 at
k = 1: the 1/rev–few/rev content is unchanged, the BVI impulses (10–40/rev) are attenuated
and delayed. This also carries the chordwise non-uniformity of the gust, which a single
lifting-line point misses.

Frames and signs: docs/conventions.md; choices: docs/models/wake_bvi.md.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np
import pandas as pd
from scipy import special

from nps import wake
from nps.rotor import RotorGeometry

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
    """Azimuths (n_psi,), radial stations (n_r,) and the reshape of a ψ-major disk table."""

    psi_rad: np.ndarray
    r_m: np.ndarray

    @property
    def shape(self) -> tuple[int, int]:
        return (self.psi_rad.size, self.r_m.size)


def disk_grid(disk: pd.DataFrame, what: str = "disk table") -> DiskGridView:
    """Check that ``disk`` is a ψ-major table on ψ_i = 2πi/N_ψ and return its grid.

    Raises ValueError naming the table and the failed expectation.
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
    if not np.allclose(psi_u, 2.0 * np.pi * np.arange(n_psi) / n_psi, atol=1e-9):
        raise ValueError(f"{what}: psi_rad must be 2*pi*i/N_psi, i = 0..N_psi-1")
    psi2 = psi.reshape(n_psi, n_r)
    r2 = r.reshape(n_psi, n_r)
    if not (np.all(psi2 == psi2[:, :1]) and np.all(r2 == r2[:1, :])):
        raise ValueError(f"{what}: rows must be psi-major (all radial stations of one azimuth together)")
    return DiskGridView(psi2[:, 0].copy(), r2[0].copy())


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
    (:func:`nps.wake.tip_vortex_strength`); β(ψ) the flap angle of the outermost station.
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
        gamma_table_m2_s=wake.tip_vortex_strength(gamma),
        beta_table_rad=beta[:, -1].copy(),
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
    k = np.asarray(k, dtype=float)
    out = np.ones(k.shape, dtype=complex)
    pos = k > 0.0
    kp = k[pos]
    h1, h0 = special.hankel2(1, kp), special.hankel2(0, kp)
    theodorsen = h1 / (h1 + 1j * h0)
    out[pos] = (special.j0(kp) - 1j * special.j1(kp)) * theodorsen + 1j * special.j1(kp)
    return out


def unsteady_response(values: np.ndarray, r_m: np.ndarray, chord_m: float) -> np.ndarray:
    """Sears-filtered periodic disk field (n_psi, n_r) of lifting-line increments (module doc)."""
    n_psi = values.shape[0]
    spectrum = np.fft.rfft(values, axis=0)
    n = np.arange(spectrum.shape[0])[:, None]
    r = np.asarray(r_m, dtype=float)[None, :]
    transfer = sears(n * chord_m / (2.0 * r)) * np.exp(-1j * n * chord_m / (4.0 * r))
    return np.fft.irfft(spectrum * transfer, n=n_psi, axis=0)


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
    from nps import bet  # the loads stage; imported here so the wake can be used on its own

    grid = disk_grid(disk)
    state = wake_state(disk, trim_row, ct)
    beta = disk["beta_rad"].to_numpy(dtype=float).reshape(grid.shape)
    v = wake.disk_induced_velocity(state, wake_model, grid.psi_rad, grid.r_m, beta)
    d_ut, d_up = blade_frame_increments(v, grid.psi_rad, beta)
    if model.removed_harmonics is not None:
        d_ut = remove_low_harmonics(d_ut, model.removed_harmonics)
        d_up = remove_low_harmonics(d_up, model.removed_harmonics)
    if model.unsteady:
        d_ut = unsteady_response(d_ut, grid.r_m, geometry.chord_m)
        d_up = unsteady_response(d_up, grid.r_m, geometry.chord_m)
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
    return BVIResult(out.reset_index(drop=True), d_ut, d_up, v)
