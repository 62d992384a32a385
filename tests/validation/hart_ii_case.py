"""HART-II baseline case (tests/data/hart_ii/README.md): rotor, trim, BVI loads and the data.

Geometry and operating condition from the OpenCOPTER set-up of the test: R = 2 m, B = 4,
c = 0.121 m, −8° linear twist, root cutout 0.44 m, Ω = 109.12 rad/s, V = 32.9 m/s, shaft
4.3° aft (free stream up through the disk: μ_z < 0), T = 3300 N, hub moments 20 / −20 N·m,
ρ = 1.2055 kg/m³, c0 = 341.7 m/s, Lock number 8. Assumptions (not in the data): NACA 23012
lift slope 6.0 /rad and zero-lift angle −1.2°, equivalent flap-hinge offset 0.29 m
(Bo105 hingeless rotor, ≈ 14.5 % R).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from nps import bet, bvi, wake
from nps.airfoils import LinearAirfoil
from nps.rotor import OperatingPoint, RotorGeometry

DATA = Path(__file__).resolve().parents[1] / "data" / "hart_ii"
RADIUS_M, OMEGA, SPEED, SHAFT_RAD = 2.0, 109.12, 32.9, np.radians(4.3)
RHO, C0, CHORD = 1.2055, 341.7, 0.121
R_OVER_R = 0.87

GEOMETRY = RotorGeometry(
    name="hart_ii", n_blades=4, radius_m=RADIUS_M, chord_m=CHORD, root_cutout_m=0.44,
    twist_rad=np.radians(-8.0), thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29,
    rotation_sign=1, airfoil=LinearAirfoil(lift_slope_per_rad=6.0, alpha0_rad=np.radians(-1.2)),
)
MU_X = SPEED * np.cos(SHAFT_RAD) / (OMEGA * RADIUS_M)
MU_Z = -SPEED * np.sin(SHAFT_RAD) / (OMEGA * RADIUS_M)
OPERATING_POINT = OperatingPoint(
    omega_rad_s=OMEGA, mu_x=MU_X, mu_y=0.0, mu_z=MU_Z, density_kg_m3=RHO, speed_of_sound_mps=C0,
    thrust_N=3300.0, roll_moment_Nm=20.0, pitch_moment_Nm=-20.0,
)
TRIM_ROW = dict(
    n_blades=4, radius_m=RADIUS_M, omega_rad_s=OMEGA, rotation_sign=1, mu_x=MU_X, mu_y=0.0, mu_z=MU_Z,
    density_kg_m3=RHO, speed_of_sound_mps=C0,
)


@dataclass(frozen=True)
class HartResult:
    trim: bet.RotorTrim
    bvi: bvi.BVIResult
    state: wake.WakeState
    psi_deg: np.ndarray
    cn_base: np.ndarray
    cn_bvi: np.ndarray
    r_station_m: float


def cn_m2(fz_N_per_m):
    """M²C_n = F_n / (½ ρ c0² c), F_n ≈ F_z (normal force per span)."""
    return np.asarray(fz_N_per_m) / (0.5 * RHO * C0**2 * CHORD)


def run(n_psi: int = 360, n_r: int = 50, model: wake.WakeModel | None = None, bvi_model: bvi.BVIModel = bvi.BVIModel()) -> HartResult:
    trim = bet.trim_rotor(GEOMETRY, OPERATING_POINT, bet.DiskGrid(n_psi, n_r))
    model = model or wake.WakeModel(steps_per_rev=n_psi)
    res = bvi.bvi_loads(trim.disk, TRIM_ROW, GEOMETRY, trim.totals.ct, model, bvi_model)
    grid = bvi.disk_grid(res.disk)
    j = int(np.argmin(np.abs(grid.r_m / RADIUS_M - R_OVER_R)))
    fz0 = trim.disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
    fz1 = res.disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
    state = bvi.wake_state(trim.disk, TRIM_ROW, trim.totals.ct)
    return HartResult(trim, res, state, np.degrees(grid.psi_rad), cn_m2(fz0), cn_m2(fz1), float(grid.r_m[j]))


def measured_cn():
    """(ψ deg, M²C_n) measured at r/R = 0.87, 2048 samples."""
    values = np.loadtxt(DATA / "CnM2_BL_ca.tec", skiprows=3)
    return np.arange(values.size) * 360.0 / values.size, values


def read_piv(name: str) -> np.ndarray:
    """Rows (psi_deg, x_m, y_m, z_m) of a DNW PIV vortex-position file (hub frame)."""
    rows = []
    for line in (DATA / name).read_text().splitlines():
        parts = line.split()
        if len(parts) == 6 and not line.lstrip().startswith(("TITLE", "VARIABLES", "ZONE")):
            rows.append([float(p) for p in parts[2:]])
    return np.array(rows)


def high_pass(values: np.ndarray, lowest: int = 10) -> np.ndarray:
    """Periodic signal with harmonics below ``lowest`` removed (BVI content is ≳ 10/rev)."""
    spectrum = np.fft.rfft(values)
    spectrum[:lowest] = 0.0
    return np.fft.irfft(spectrum, n=values.size)


def window_metrics(psi_deg, values, lo, hi):
    """(ψ of the steepest high-passed change, peak-to-peak) inside [lo, hi] deg."""
    hp = high_pass(values)
    slope = np.gradient(hp, psi_deg)
    inside = (psi_deg >= lo) & (psi_deg <= hi)
    i = np.flatnonzero(inside)[np.argmax(np.abs(slope[inside]))]
    return float(psi_deg[i]), float(np.ptp(hp[inside])), float(slope[i])


def piv_miss_distances(state: wake.WakeState, model: wake.WakeModel) -> list[tuple]:
    """For each PIV vortex: (side, ψ, y, measured x, z, predicted x, z, miss distance in the
    cut plane y = y_meas), matching the nearest predicted crossing of any blade's vortex."""
    out = []
    for side, name in (("advancing", "dnw_adv_bl53.tec"), ("retreating", "dnw_ret_bl53.tec")):
        data = read_piv(name)
        for psi_deg in np.unique(data[:, 0]):
            snap = wake.wake_snapshot(state, model, np.radians(psi_deg))
            for p, x, y, z in data[data[:, 0] == psi_deg]:
                cross = wake.filament_plane_crossings(snap.nodes_m, 1, y)
                d = np.hypot(cross[:, 0] - x, cross[:, 2] - z)
                k = int(np.argmin(d))
                out.append((side, psi_deg, y, x, z, cross[k, 0], cross[k, 2], float(d[k])))
    return out


def window_lag(psi_model_deg, model, psi_meas_deg, meas, lo, hi, max_lag_deg=15.0):
    """Lag (deg, + = model later) maximising the correlation of the high-passed signals in
    [lo, hi], and that correlation coefficient. The model is interpolated (periodic) to the
    measured azimuths."""
    hp_model = high_pass(model)
    hp_meas = high_pass(meas)
    step = psi_meas_deg[1] - psi_meas_deg[0]
    inside = (psi_meas_deg >= lo) & (psi_meas_deg <= hi)
    best = (0.0, -2.0)
    for lag in np.arange(-max_lag_deg, max_lag_deg + step / 2, step):
        shifted = np.interp(psi_meas_deg[inside] + lag, psi_model_deg, hp_model, period=360.0)
        rho = float(np.corrcoef(shifted, hp_meas[inside])[0, 1])
        if rho > best[1]:
            best = (float(lag), rho)
    return best
