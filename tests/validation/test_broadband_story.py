"""Study case for the thesis' Fig. 3.8 story: Pegg broadband raises the total level under the rotor
and barely changes it in plane ahead at high speed.

Demonstration helicopter, main rotor alone, segment 5 (maximum speed, 82.8 m/s level), full NPS
chain: aircraft trim -> BET rotor trim (120 x 30 disk) -> compact F1A thickness and
loading at two observers 10 R from the hub moving with the aircraft (straight below; in the
rotor plane straight ahead) -> metrics with ISO 9613-1 absorption, without and with Pegg.

Measured (ISA sea level, 70 % RH): below, OASPL 100.7 -> 101.3 dB (+0.6), OASPL_A 49 -> 89 dBA,
PNL 53 -> 101 PNdB; ahead in plane, OASPL 109.22 -> 109.23 dB (+0.01), OASPL_A 86.4 -> 87.3 dBA.
Below the rotor the tonal noise is the low-frequency loading fundamental (little weighted
energy), and Pegg's directivity (cos²θ + 0.1) is 10.4 dB stronger on the axis than in plane;
ahead the high-speed thickness noise dominates every band. Asserted: OASPL gain below > 0.3 dB
and > 10x the gain ahead (< 0.1 dB); A-weighted gain below > 20 dB, ahead < 2 dB.
"""

import numpy as np
import pandas as pd

from nps.noise import acoustics

from nps.rotor import bet

from nps.noise import metrics

from nps.noise import sources
from nps.core.atmosphere import isa
from nps.app.config import load_aircraft, load_mission
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import FlightCondition, trim_aircraft

GRID = bet.DiskGrid(120, 30)
SAMPLES_PER_REV = 1024


def test_broadband_matters_below_not_ahead(repo_root):
    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    mission = load_mission(repo_root / "config/missions/demo.yaml")
    speeds = next(s for s in mission["segments"] if s["id"] == "seg5")["aircraft"]["helicopter"]
    atmosphere = isa(0.0)
    trim = trim_aircraft(aircraft, FlightCondition(speeds["forward_speed_mps"], speeds["climb_speed_mps"], atmosphere), None)
    trim = trim.iloc[:1].reset_index(drop=True)
    row = trim.iloc[0]
    geometry = RotorGeometry.from_config(aircraft["rotors"][0])
    loads = bet.trim_rotor(geometry, OperatingPoint.from_trim_row(row), GRID)
    hub = row[["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)
    velocity = row[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)
    elevation, azimuth = np.radians([-90.0, 0.0]), np.radians([0.0, 180.0])
    direction = np.stack([-np.cos(azimuth) * np.cos(elevation), -np.sin(azimuth) * np.cos(elevation), np.sin(elevation)], 1)
    position = hub + 10.0 * geometry.radius_m * direction
    grid = acoustics.TimeGrid(0.0, 2.0 * np.pi / row["omega_rad_s"], SAMPLES_PER_REV)
    p = sources.radiate_rotor(loads.disk, row, acoustics.Observers(position, np.tile(velocity, (2, 1))), grid)
    frames = [
        pd.DataFrame({"observer": np.int32(o), "group": group, "time_s": grid.times_s, "p_Pa": p[o, g]})
        for g, group in enumerate(("loading", "thickness"))
        for o in range(2)
    ]
    observers = pd.DataFrame({"observer": np.int32([0, 1]), "x_m": position[:, 0], "y_m": position[:, 1],
                              "z_m": position[:, 2], "elevation_deg": [-90.0, 0.0], "azimuth_deg": [0.0, 180.0]})
    solidity = metrics.rotor_solidities(aircraft)
    signals = {"main": pd.concat(frames, ignore_index=True)}
    tonal, _, _ = metrics.metrics_tables(signals, observers, trim, solidity, atmosphere, None, broadband_on=False)
    total, _, _ = metrics.metrics_tables(signals, observers, trim, solidity, atmosphere, None, broadband_on=True)
    gain = (total["oaspl_db"] - tonal["oaspl_db"]).to_numpy()
    gain_a = (total["oaspl_dba"] - tonal["oaspl_dba"]).to_numpy()
    below, ahead = 0, 1
    assert gain[below] > 0.3 and gain[ahead] < 0.1 and gain[below] > 10 * gain[ahead]
    assert gain_a[below] > 20.0 and gain_a[ahead] < 2.0
    assert tonal["oaspl_thickness_db"][ahead] > tonal["oaspl_loading_db"][ahead]  # high-speed thickness ahead
