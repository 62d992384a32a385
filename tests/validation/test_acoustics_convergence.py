"""Source-time convergence of the acoustic chain (issue 5): doubling the source-time resolution
changes OASPL by less than 0.05 dB on the study cases.

Chain: config/aircraft/<aircraft>.yaml and the seg3 speeds of config/missions/demo.yaml (6° descent,
the BVI segment, 25.7 m/s), ISA sea level → nps.rotor.trim.trim_aircraft → nps.rotor.bet.trim_rotor on
n_psi = 180 and 360 azimuths (the source steps of the acoustic lines), n_r = 30 →
nps.noise.sources.radiate_rotor (dual-compact thickness + loading, every rotor of the aircraft summed
on the main rotor's grid of 1024 samples per revolution, the campaign default) → OASPL (dB re
20 µPa) of the total signal at 16 observers of the 10 R hemisphere about the first rotor's hub,
moving with the aircraft (elevation 0°, −30°, −60°, −90° × azimuth 0°, 90°, 180°, 270°).
Tolerance: |ΔOASPL| < 0.05 dB at every observer (issue 5 acceptance). The 180-step case includes
the change of the BET solution itself with ψ resolution.
Measured max |ΔOASPL| (180 → 360): helicopter 2.4e-5 dB, tandem 3.8e-5, coaxial 2.1e-5, hexacopter
5.3e-5 dB (OASPL 74–106 dB). Sensitivity: helicopter 24 / 48 / 90 steps vs 360 give 0.064 / 0.0047 /
0.0004 dB, so a source-time error would fail this test. All four aircraft run in ≈ 6 s.
"""

import numpy as np
import pytest

from nps.noise import acoustics

from nps.rotor import bet

from nps.noise import sources
from nps.core.atmosphere import isa
from nps.app.config import load_aircraft, load_mission
from nps.noise.observers import hemisphere
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import FlightCondition, trim_aircraft

SAMPLES_PER_REV = 1024
N_R = 30
TOLERANCE_DB = 0.05


def _oaspl(repo_root, aircraft_name, n_psi):
    """OASPL (dB) of all rotors' thickness + loading at the 16 hemisphere observers, n_psi source steps per revolution."""
    aircraft = load_aircraft(repo_root / f"config/aircraft/{aircraft_name}.yaml")
    mission = load_mission(repo_root / "config/missions/demo.yaml")
    speeds = next(s for s in mission["segments"] if s["id"] == "seg3")["aircraft"][aircraft_name]
    trim = trim_aircraft(aircraft, FlightCondition(speeds["forward_speed_mps"], speeds["climb_speed_mps"], isa(0.0)), None)
    reference = trim.iloc[0]
    hub = reference[["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)
    velocity = reference[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)
    table = hemisphere(hub, 10.0 * reference["radius_m"], 4, 4, velocity_mps=velocity)
    observers = acoustics.Observers(table[["x_m", "y_m", "z_m"]].to_numpy(), table[["vx_mps", "vy_mps", "vz_mps"]].to_numpy())
    grid = acoustics.TimeGrid(0.0, 2.0 * np.pi / reference["omega_rad_s"], SAMPLES_PER_REV)
    total = np.zeros((len(table), SAMPLES_PER_REV))
    for rotor in aircraft["rotors"]:
        geometry = RotorGeometry.from_config(rotor)
        row = trim[trim["rotor"] == geometry.name].iloc[0]
        loads = bet.trim_rotor(geometry, OperatingPoint.from_trim_row(row), bet.DiskGrid(n_psi, N_R))
        total += sources.radiate_rotor(loads.disk, row, observers, grid, hinge_offset_m=geometry.hinge_offset_m).sum(axis=1)
    return 10.0 * np.log10((total**2).mean(axis=-1) / 4e-10)


@pytest.mark.parametrize("aircraft_name", ["helicopter", "tandem", "coaxial", "hexacopter"])
def test_source_time_convergence(repo_root, aircraft_name):
    """Bundled aircraft (every rotor), seg3: |ΔOASPL| < 0.05 dB at all 16 observers."""
    coarse, fine = _oaspl(repo_root, aircraft_name, 180), _oaspl(repo_root, aircraft_name, 360)
    change = np.abs(fine - coarse)
    print(f"{aircraft_name} seg3: OASPL {fine.min():.1f}…{fine.max():.1f} dB, max |change| 180 -> 360 source steps "
          f"{change.max():.2e} dB")
    assert change.max() < TOLERANCE_DB
