"""Hovering ring sources against Gutin's closed-form harmonics, and hover azimuthal symmetry.

Sources are built by ``nps.noise.sources.rotor_sources`` from a one-station disk table (thrust and
torque at one radius) and radiated by the periodic (one blade + symmetry) path.
* tests/data/gutin (closed form, B = 2, Re = 4 m, Ω = 40.8 rad/s, r = 500 m): loading (Gutin)
  and compact-monopole thickness harmonics m = 1…4 within 0.1 dB at θ = 30…150°.
* Issue 5 case: B = 4 at r = 200 R, harmonics 1–4 within 0.1 dB wherever within 40 dB of the
  loudest harmonic, θ from 10° to 170°. Gutin (design-notes): p_m,rms = mBΩ/(2√2 π c r)
  |−T cos θ + Q c/(Ω Re²)| |J_mB(mBΩ Re sin θ / c)|.
* Hover symmetry: OASPL of a full 4-blade rotor with dual-compact thickness on a hemisphere is
  independent of azimuth to 0.01 dB.
"""

import numpy as np
import pandas as pd
from scipy.special import jv

from nps.noise.acoustics import Observers, TimeGrid
from nps.noise.sources import radiate_rotor
from nps.noise.observers import hemisphere
from nps.noise.sources import ThicknessModel


def _hover_row(n_blades, omega, c0, rho0):
    row = {"rotation_sign": 1, "n_blades": n_blades, "omega_rad_s": omega, "hub_x_m": 0.0, "hub_y_m": 0.0, "hub_z_m": 0.0,
           "vel_x_mps": 0.0, "vel_y_mps": 0.0, "vel_z_mps": 0.0, "speed_of_sound_mps": c0, "density_kg_m3": rho0}
    row.update({f"r_gh_{i}{j}": float(i == j) for i in range(3) for j in range(3)})
    return row


def _ring_disk(radius, thrust, torque, n_blades, volume=0.0, n_psi=360, dr=0.1):
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    return pd.DataFrame({"psi_rad": psi, "r_m": radius, "dr_m": dr, "chord_m": 0.5, "thickness_m": volume / (0.685 * 0.5 * dr),
                         "theta_rad": 0.0, "beta_rad": 0.0, "fz_N_per_m": thrust / n_blades / dr,
                         "fx_N_per_m": torque / (n_blades * radius) / dr})


def _harmonics(pressure, n):
    spec = np.fft.rfft(pressure, axis=-1) / pressure.shape[-1]
    return np.sqrt(2) * np.abs(spec[..., n])


def test_gutin_and_compact_thickness_reference_case(data_dir):
    """Loading and monopole thickness harmonics vs tests/data/gutin within 0.1 dB."""
    ref = pd.read_csv(data_dir / "gutin/analytic_gutin_compact_thickness_case.csv", comment="#")
    b, re, omega, c0, rho0, r_obs = 2, 4.0, 40.8, 340.0, 1.226, 500.0
    theta = np.radians(np.sort(ref.theta_deg.unique()))
    pos = r_obs * np.stack([np.sin(theta), 0 * theta, np.cos(theta)], axis=1)
    p = radiate_rotor(_ring_disk(re, 20000.0, 8000.0, b, volume=0.01), _hover_row(b, omega, c0, rho0),
                      Observers(pos, np.zeros_like(pos)), TimeGrid(0.0, 2 * np.pi / omega, 512),
                      thickness=ThicknessModel(kind="compact_monopole"))
    for k, theta_deg in enumerate(np.sort(ref.theta_deg.unique())):
        sub = ref[ref.theta_deg == theta_deg]
        for group, column in ((0, "p_load_rms_Pa"), (1, "p_thick_rms_Pa")):
            level = 20 * np.log10(_harmonics(p[k, group], sub.n.to_numpy()) / sub[column].to_numpy())
            assert np.abs(level).max() < 0.1, (theta_deg, column, level)


def test_gutin_four_blades_200_radii():
    """B = 4 ring, r = 200 R, θ = 10…170°: harmonics 1–4 within 0.1 dB where within 40 dB of the loudest."""
    b, re, omega, c0, rho0 = 4, 5.0, 40.0, 340.0, 1.225
    thrust, torque = 40000.0, 30000.0
    r_obs = 200 * re / 0.8
    theta = np.radians(np.arange(10.0, 171.0, 10.0))
    pos = r_obs * np.stack([np.sin(theta), 0 * theta, np.cos(theta)], axis=1)
    p = radiate_rotor(_ring_disk(re, thrust, torque, b), _hover_row(b, omega, c0, rho0), Observers(pos, np.zeros_like(pos)),
                      TimeGrid(0.0, 2 * np.pi / omega, 512))
    n = b * np.arange(1, 5)
    mine = _harmonics(p[:, 0], n)
    exact = n * omega / (2 * np.sqrt(2) * np.pi * c0 * r_obs) * np.abs(-thrust * np.cos(theta)[:, None] + torque * c0 / (omega * re**2)) \
        * np.abs(jv(n, n * omega * re * np.sin(theta)[:, None] / c0))
    relevant = exact > exact.max() * 10 ** (-40 / 20)
    error_db = 20 * np.log10(mine[relevant] / exact[relevant])
    print(f"Gutin B=4 r=200R: max |error| {np.abs(error_db).max():.4f} dB over {relevant.sum()} harmonics")
    assert np.abs(error_db).max() < 0.1


def test_hover_oaspl_independent_of_azimuth():
    """Full rotor (50 stations, dual compact, loading) in hover: OASPL spread over azimuth < 0.01 dB."""
    n_psi, n_r, radius, omega = 360, 20, 7.62, 28.0
    r = np.linspace(0.2, 1.0, n_r, endpoint=False) * radius + 0.02 * radius
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    disk = pd.DataFrame({"psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": 0.04 * radius, "chord_m": 0.58, "thickness_m": 0.052,
                         "theta_rad": 0.12, "beta_rad": 0.05, "fz_N_per_m": (1000 * (rr / radius) ** 2).ravel(), "fx_N_per_m": 60.0})
    obs = hemisphere([0.0, 0.0, 0.0], 10 * radius, 4, 23)  # 23 azimuths: not aligned with the 1° source steps
    observers = Observers(obs[["x_m", "y_m", "z_m"]].to_numpy(), obs[["vx_mps", "vy_mps", "vz_mps"]].to_numpy())
    p = radiate_rotor(disk, _hover_row(4, omega, 340.294, 1.225), observers, TimeGrid(0.0, 2 * np.pi / omega, 512)).sum(axis=1)
    oaspl = 10 * np.log10((p**2).mean(axis=-1) / 4e-10).reshape(4, 23)
    spread = np.ptp(oaspl, axis=1)
    print(f"hover OASPL azimuthal spread per elevation (dB): {np.round(spread, 5)}")
    assert spread.max() < 0.01
