"""Descent sweep 0°–10° of the thesis Table 5.2 rotor (thesis Fig. 5.11: BVI strongest near
6° descent, little in level flight, gone again by ≈ 8°).

Rotor: the bundled helicopter main rotor (config/aircraft/helicopter.yaml) at Table 5.2's
μ = 0.23 and C_T = 0.0095, trimmed by nps.rotor.bet (zero hub moments, so the tip-path plane is the
shaft plane), BVI loads with the model defaults (360 × 30 disk, 3-revolution wake).

Disk attitude (trim-consistent, not the thesis' μ_z = μ tan γ, which leaves the disk parallel
to the flight path): in steady flight at descent angle γ the rotor force balances the weight
W = T and the fuselage drag D = ½ρV²f (f from the aircraft file) along the path, so the
resultant is tilted forward of the vertical by τ_f = atan(D cos γ / (W − D sin γ)); the disk
normal lies a further atan(H/T) ahead of the resultant (H the rotor's own in-plane drag from
the BET, taken from a coarse 72 × 20 trim at the drag-only attitude: one fixed-point update).
The free stream meets the disk at α = γ − τ_f − atan(H/T) (positive from below): α = −2.3° in
level flight (the wake is blown below the disk), +3.8° at 6°; μ_x = μ cos α, μ_z = −μ sin α.

BVI intensity (a BVISPL proxy from the loads alone): the energy over one revolution of the
blade's ≥ 10/rev total normal-force rate,

    I = Σ_ψ [ d/dψ ∫_{0.5R}^{R} F_z^{(≥10/rev)}(ψ, r) dr ]²,

the sound power of the BVI band of a compact blade dipole radiating below the rotor. Parallel
interactions (vortex along the span) load the whole blade at once and count fully; oblique
ones (the level-flight advancing-side crossings) cancel along the span, as their noise does.
Measured (relative to the maximum; Betz vortex structure, the default), γ = 0°: 0.06, 3°: 0.41,
4°: 0.66, 5°: 0.90, 6°: 1.00, 7°: 0.95, 8°: 0.78, 10°: 0.28; the maximum intensity is 4.3 dB
below the point vortex's. With the thesis' point vortex: 0.06, 0.47, 0.77, 1.00, 0.94, 0.66,
0.43, 0.13. Threshold for "small": ≤ 0.5 of the peak, i.e. at least 3 dB below it. The thesis
describes 8° as resembling 2°–3° (point vortex: 0.43 against 0.47 at 3°); with the Betz
structure the fall beyond the peak is slower (8°: −1.1 dB): the diffuse vortices of the wide
sheets lose less of their induced velocity as the miss distance grows, so only 10° is "small".

The free-vortex wake (issue 12; ``wake.model: free``, one-rotor aircraft through
:func:`nps.wake.interaction.aircraft_bvi_loads`, default ``FreeWakeModel``, the same trims and the
Beddoes model above as its initial guess and blade-load evaluation) gives the same regime with a
sharper fall beyond the peak: 0°: 0.05, 3°: 0.53, 4°: 0.80, 5°: 0.98, 6°: 1.00, 7°: 0.87,
8°: 0.60, 10°: 0.11 (peak intensity +0.2 dB against Beddoes'; 12–19 relaxation iterations). The
same four tests run for both wakes.

Earlier measure (max |∂F_z/∂ψ| at any station, disk parallel to the path): 0.61 in level flight
and 0.66 at 8°; with the trim-consistent tilt it peaks at 8° because single-station maxima come
from retreating-side tip crossings (r = 0.99 R) that do not radiate coherently. Without the
tilt (disk parallel to the path) the measure below peaks at 3° with 0.29 in level flight.
"""

import numpy as np
import pandas as pd
import pytest

from multirotor_case import placed
from nps.rotor import bet
from nps.wake import bvi
from nps.wake import interaction
from nps.wake import prescribed as wake
from nps.app.config import load_aircraft
from nps.rotor.geometry import OperatingPoint, RotorGeometry

ANGLES_DEG = (0, 3, 4, 5, 6, 7, 8, 10)
RHO, C0, OMEGA, MU, CT = 1.225, 340.3, 28.0, 0.23, 0.0095


def _trimmed_disk(gamma_deg: float, geometry: RotorGeometry, drag_area_m2: float):
    """Trim at the trim-consistent disk angle (module doc); returns (trim, trim row, α rad)."""
    radius = geometry.radius_m
    thrust = CT * RHO * np.pi * radius**2 * (OMEGA * radius) ** 2
    gamma = np.radians(gamma_deg)
    drag = 0.5 * RHO * (MU * OMEGA * radius) ** 2 * drag_area_m2
    tau_f = np.arctan2(drag * np.cos(gamma), thrust - drag * np.sin(gamma))
    h_over_t = 0.0
    for grid in (bet.DiskGrid(72, 20), bet.DiskGrid(360, 30)):  # H/T (an integral) from a coarse trim
        alpha = gamma - tau_f - np.arctan(h_over_t)
        mu_x, mu_z = MU * np.cos(alpha), -MU * np.sin(alpha)
        op = OperatingPoint(omega_rad_s=OMEGA, mu_x=mu_x, mu_y=0.0, mu_z=mu_z, density_kg_m3=RHO,
                            speed_of_sound_mps=C0, thrust_N=thrust)
        trim = bet.trim_rotor(geometry, op, grid)
        h_over_t = trim.totals.h_force_N / trim.totals.thrust_N
    row = dict(n_blades=geometry.n_blades, radius_m=radius, omega_rad_s=OMEGA, rotation_sign=1, mu_x=mu_x,
               mu_y=0.0, mu_z=mu_z, density_kg_m3=RHO, speed_of_sound_mps=C0)
    return trim, row, alpha


def bvi_intensity(disk, radius_m: float) -> float:
    """I = Σ_ψ (d/dψ ∫_{0.5R}^R F_z^{≥10/rev} dr)² ((N/rad)², module doc)."""
    grid = bvi.disk_grid(disk)
    fz = bvi.remove_low_harmonics(disk["fz_N_per_m"].to_numpy().reshape(grid.shape), 9)
    dr = disk["dr_m"].to_numpy().reshape(grid.shape)[0]
    outer = grid.r_m >= 0.5 * radius_m
    blade_force = fz[:, outer] @ dr[outer]
    return float(np.sum(np.gradient(blade_force, grid.psi_rad) ** 2))


@pytest.fixture(scope="module")
def trims(repo_root):
    """(rotor config, geometry, [(trim, trim row, α rad) per angle of ANGLES_DEG])."""
    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    config = aircraft["rotors"][0]
    geometry = RotorGeometry.from_config(config)
    drag_area = float(aircraft["fuselage_drag_area_m2"])
    return config, geometry, [_trimmed_disk(gamma, geometry, drag_area) for gamma in ANGLES_DEG]


def _bvi_disk(wake_kind: str, config, geometry, trim, row):
    """The BVI loads disk of the isolated Beddoes wake or of the rotor's free wake."""
    model = wake.WakeModel(revolutions=3)
    if wake_kind == "beddoes":
        return bvi.bvi_loads(trim.disk, row, geometry, trim.totals.ct, model).disk
    name = config["name"]
    trim_row = placed(dict(row, rotor=name, ct=trim.totals.ct, thrust_N=trim.totals.thrust_N,
                           roll_moment_Nm=0.0, pitch_moment_Nm=0.0))
    result = interaction.aircraft_bvi_loads(pd.DataFrame([trim_row]), {name: config}, {name: trim.disk},
                                            {name: trim.summary()}, model)
    return result.results[name].disk


@pytest.fixture(scope="module", params=["beddoes", "free"])
def sweep(request, trims):
    config, geometry, cases = trims
    values = np.array([bvi_intensity(_bvi_disk(request.param, config, geometry, trim, row), geometry.radius_m)
                       for trim, row, _ in cases])
    return dict(zip(ANGLES_DEG, values / values.max()))


def test_disk_tilted_forward_in_level_flight(trims):
    """Trim-consistent attitude: in level flight the free stream enters the disk from above
    (α = −2.3° ± 0.3°: D/W = 0.031 from f = 2 m², plus H/T ≈ 0.01); at 6° descent from below."""
    alpha = dict(zip(ANGLES_DEG, (np.degrees(a) for _, _, a in trims[2])))
    assert alpha[0] == pytest.approx(-2.3, abs=0.3)
    assert 3.0 < alpha[6] < 4.5


def test_bvi_intensity_peaks_between_5_and_7_degrees(sweep):
    peak = max(sweep, key=sweep.get)
    assert 5 <= peak <= 7, sweep


def test_bvi_intensity_small_in_level_flight_and_at_10_degrees(sweep):
    """Level flight and 10° at most half the peak intensity (≥ 3 dB below; module doc); level
    flight, where the wake passes below the disk, under a tenth (measured 0.06 Beddoes, 0.05 free;
    10°: 0.28, 0.11)."""
    assert sweep[0] <= 0.1 and sweep[10] <= 0.5, sweep


def test_bvi_intensity_rises_from_level_flight_to_the_peak(sweep):
    """The intensity grows monotonically from level flight to 6° (Beddoes 0.06, 0.41, 0.66, 0.90,
    1.00; free wake 0.05, 0.53, 0.80, 0.98, 1.00) and falls monotonically from 6° to 10°: one
    interaction regime, not scattered events."""
    assert sweep[0] < sweep[3] < sweep[4] < sweep[5] < sweep[6], sweep
    assert sweep[6] > sweep[7] > sweep[8] > sweep[10], sweep
