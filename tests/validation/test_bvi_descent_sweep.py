"""Descent sweep 0°–10° of the thesis Table 5.2 rotor (thesis Fig. 5.11: BVI strongest near
6° descent, weak in level flight and beyond ≈ 8°).

Rotor: the bundled helicopter main rotor (config/aircraft/helicopter.yaml) at Table 5.2's
μ_x = 0.23 and C_T = 0.0095, μ_z = −μ_x tan γ (Table 5.2: μ_z = 0.024 at 5.96°, thesis sign),
trimmed by nps.bet, BVI loads with the model defaults (360 × 30 disk, 3-revolution wake).

BVI intensity: the largest |∂F_z/∂ψ| (N/m per rad) of the BVI loading's ≥ 10/rev content over
the disk at r ≥ 0.5 R. Measured at the time of writing (relative to the maximum):
γ = 0°: 0.61, 3°: 0.87, 5°: 0.92, 6°: 1.00, 7°: 0.91, 8°: 0.66, 10°: 0.20. The maximum lies
in 5°–7° as in the thesis and the intensity falls steeply beyond 8°, but level flight keeps
0.6 of the peak: the Beddoes inflow's reduced downwash at the front of the disk keeps the
young vortices near the advancing blades at μ = 0.23 (docs/models/wake_bvi.md). The
advancing side alone peaks at 4°, the retreating side at 6°.
"""

import numpy as np
import pytest

from nps import bet, bvi, wake
from nps.config import load_aircraft
from nps.rotor import OperatingPoint, RotorGeometry

ANGLES_DEG = (0, 3, 5, 6, 7, 8, 10)


def _intensity(gamma_deg: float, geometry: RotorGeometry) -> float:
    rho, c0, omega, mu_x, ct = 1.225, 340.3, 28.0, 0.23, 0.0095
    radius = geometry.radius_m
    mu_z = -mu_x * np.tan(np.radians(gamma_deg))
    thrust = ct * rho * np.pi * radius**2 * (omega * radius) ** 2
    op = OperatingPoint(omega_rad_s=omega, mu_x=mu_x, mu_y=0.0, mu_z=mu_z, density_kg_m3=rho,
                        speed_of_sound_mps=c0, thrust_N=thrust)
    trim = bet.trim_rotor(geometry, op, bet.DiskGrid(360, 30))
    row = dict(n_blades=geometry.n_blades, radius_m=radius, omega_rad_s=omega, rotation_sign=1, mu_x=mu_x,
               mu_y=0.0, mu_z=mu_z, density_kg_m3=rho, speed_of_sound_mps=c0)
    res = bvi.bvi_loads(trim.disk, row, geometry, trim.totals.ct, wake.WakeModel(revolutions=3))
    grid = bvi.disk_grid(res.disk)
    fz = bvi.remove_low_harmonics(res.disk["fz_N_per_m"].to_numpy().reshape(grid.shape), 9)
    slope = np.gradient(fz, grid.psi_rad, axis=0)
    return float(np.abs(slope[:, grid.r_m >= 0.5 * radius]).max())


@pytest.fixture(scope="module")
def sweep(repo_root):
    geometry = RotorGeometry.from_config(load_aircraft(repo_root / "config/aircraft/helicopter.yaml")["rotors"][0])
    values = np.array([_intensity(g, geometry) for g in ANGLES_DEG])
    return dict(zip(ANGLES_DEG, values / values.max()))


def test_bvi_intensity_peaks_between_5_and_7_degrees(sweep):
    peak = max(sweep, key=sweep.get)
    assert 5 <= peak <= 7, sweep


def test_bvi_intensity_falls_beyond_8_degrees(sweep):
    """Beyond 8° the wake is blown above the disk: intensity ≤ 0.75 of the peak at 8° and
    ≤ 0.3 at 10° (measured 0.66 and 0.20)."""
    assert sweep[8] <= 0.75 and sweep[10] <= 0.3, sweep


def test_level_flight_below_peak(sweep):
    """Level flight is below the 5°–7° levels (measured 0.61 of the peak; the thesis shows it
    much weaker: a known shortfall of the prescribed wake, see the module docstring)."""
    assert sweep[0] < 0.75 and sweep[0] < min(sweep[5], sweep[6], sweep[7]), sweep
