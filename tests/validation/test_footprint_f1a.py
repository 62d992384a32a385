"""Hemisphere propagation against direct F1A with the moving aircraft and fixed ground observers.

The helicopter in seg2 (level flight, 40.5 m/s) is trimmed, its blade loads computed and its
thickness + loading noise radiated (nps.noise.acoustics, compact F1A) twice: (1) to a 20 R hemisphere
moving with the aircraft, turned into the source-hemisphere product (referred to 10 R) and propagated
by nps.mission.propagation to three fixed ground receivers; (2) directly to the same fixed receivers
with the moving rotors (non-periodic F1A: every blade over the source times the window needs,
Doppler and retarded times from the solver). Without ground and absorption the two OASPLs over
a 4-revolution window agree within 1.5 dB (acceptance of issue 15); measured 0.2, 0.1 and 0.6 dB
(with the product taken on the 10 R hemisphere itself: 1.1, 0.4 and 1.8 dB, see
nps.mission.source_hemisphere). Slow (~1 min).
"""

import numpy as np
import pytest

from nps.noise.acoustics import LOADING, THICKNESS, Observers, TimeGrid
from nps.core.atmosphere import isa
from nps.rotor.bet import DiskGrid, trim_rotor
from nps.app.config import load_aircraft
from nps.noise.metrics import rotor_solidities
from nps.noise.observers import hemisphere
from nps.mission.propagation import Ground, Trajectory, propagate
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.noise.signals import signals_table
from nps.noise.sources import ThicknessModel, common_grid, radiate_rotor
from nps.mission.source_hemisphere import hemisphere_from_table, source_hemisphere_table
from nps.noise.spectra import P_REF_PA
from nps.rotor.trim import FlightCondition, trim_aircraft, trim_row

HEIGHT_M = 150.0
N_REV = 4
SAMPLES_PER_REV = 1024


@pytest.mark.slow
def test_hemisphere_propagation_matches_direct_f1a(repo_root):
    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    trim = trim_aircraft(aircraft, FlightCondition(40.5, 0.0, isa(0.0)))
    rotors = {r["name"]: r for r in aircraft["rotors"]}
    disks = {}
    for _, row in trim.iterrows():
        geometry = RotorGeometry.from_config(rotors[row["rotor"]])
        disks[row["rotor"]] = trim_rotor(geometry, OperatingPoint.from_trim_row(row), DiskGrid(360, 50)).disk
    main = trim.iloc[0]
    hub = main[["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)
    velocity = main[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)
    c = float(main["speed_of_sound_mps"])
    radius = 20.0 * float(main["radius_m"])  # the far-field product hemisphere, referred to 10 R
    model = ThicknessModel()
    hinge = {name: float(r.get("hinge_offset_m", 0.0)) for name, r in rotors.items()}

    # (1) hemisphere product -> propagation
    obs = hemisphere(hub, radius, 10, 36, velocity)
    moving = Observers(obs[["x_m", "y_m", "z_m"]].to_numpy(float), obs[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float))
    one_rev = common_grid(trim_row(trim, "main"), SAMPLES_PER_REV)
    signals = {name: signals_table(obs["observer"].to_numpy(), (LOADING, THICKNESS),
                                   radiate_rotor(disks[name], trim_row(trim, name), moving, one_rev, thickness=model,
                                                 hinge_offset_m=hinge[name]), one_rev, total=False)
               for name in disks}
    table = source_hemisphere_table(signals, obs, trim, rotor_solidities(aircraft), broadband_on=False,
                                    reference_radius_m=radius / 2.0)
    hemi = hemisphere_from_table(table)
    # E frame: ground at z = 0, the CG HEIGHT_M above it at t = 0 (E = G + HEIGHT_M z)
    lift = np.array([0.0, 0.0, HEIGHT_M])
    span = 60.0
    traj = Trajectory(np.array([-span, span]), np.array([hub + velocity * -span, hub + velocity * span]) + lift,
                      np.array([0]), (None,))
    receivers_g = np.array([[0.0, 0.0, -HEIGHT_M], [150.0, 150.0, -HEIGHT_M], [-200.0, -250.0, -HEIGHT_M]])
    period = 2.0 * np.pi / float(main["omega_rad_s"])
    t_start = 0.55  # reception window [t_start, t_start + 4 revolutions]
    grid = TimeGrid(t_start, N_REV * period, N_REV * SAMPLES_PER_REV)
    times = grid.times_s[:: SAMPLES_PER_REV // 8]
    hist = propagate([hemi], traj, receivers_g + [0.0, 0.0, HEIGHT_M], times, c, Ground("none"), store_bands=True)
    band_msp = np.where(hist.bands_db > -100.0, 10.0 ** (hist.bands_db / 10.0), 0.0)
    propagated = 10.0 * np.log10(band_msp.sum(axis=2).mean(axis=1))

    # (2) direct F1A: moving rotors, fixed ground observers
    fixed = Observers(receivers_g, np.zeros_like(receivers_g))
    p = sum(radiate_rotor(disks[name], trim_row(trim, name), fixed, grid, thickness=model, hinge_offset_m=hinge[name]).sum(axis=1)
            for name in disks)
    p = p - p.mean(axis=1, keepdims=True)
    direct = 10.0 * np.log10(np.mean(p**2, axis=1) / P_REF_PA**2)
    print("direct F1A OASPL", direct.round(2), "hemisphere-propagated", propagated.round(2))
    assert np.abs(propagated - direct).max() < 1.5
