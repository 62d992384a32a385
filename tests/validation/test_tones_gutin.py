"""Tone table (nps.noise.tones.tone_table) of a hovering ring rotor against Gutin's closed form.

Setup of tests/validation/test_acoustics_gutin.py (issue-5 case): B = 4 ring at R_e = 5 m, Ω = 40 rad/s,
T = 40 kN, Q = 30 kN·m, observers at r = 200 R_e/0.8, θ = 10…170° from the thrust axis, signals radiated by
``nps.noise.sources.radiate_rotor`` on one revolution (512 samples) and written as a signal table.
Gutin: p_m,rms = mBΩ/(2√2 π c r) |−T cos θ + Q c/(Ω R_e²)| |J_mB(mBΩ R_e sin θ / c)|.

* BPF1 and BPF2 SPL of the rotor's rows and of the total within 0.1 dB (the acoustics test's tolerance)
  wherever within 40 dB of the loudest harmonic;
* phase convention: an observer turned by Δφ about the shaft in the sense of rotation hears the signal
  Δφ/Ω later, so φ_m(Δφ) − φ_m(0) = −m B Δφ; within 1e-3 rad.
"""

import numpy as np
import pandas as pd
from scipy.special import jv

from nps.noise.acoustics import Observers, TimeGrid
from nps.noise.signals import signals_table
from nps.noise.sources import radiate_rotor
from nps.noise.tones import tone_table
from tests.trim_tables import complete_trim
from tests.validation.test_acoustics_gutin import _hover_row, _ring_disk

B, RE, OMEGA, C0, RHO0 = 4, 5.0, 40.0, 340.0, 1.225
THRUST, TORQUE = 40000.0, 30000.0
R_OBS = 200 * RE / 0.8


def _tones(positions):
    row = _hover_row(B, OMEGA, C0, RHO0)
    grid = TimeGrid(0.0, 2 * np.pi / OMEGA, 512)
    p = radiate_rotor(_ring_disk(RE, THRUST, TORQUE, B), row, Observers(positions, np.zeros_like(positions)), grid)
    table = signals_table(np.arange(len(positions), dtype=np.int32), ("loading", "thickness"), p, grid, total=False)
    trim = complete_trim(pd.DataFrame([{"rotor": "ring", **row, "n_blades": np.int32(B)}]))
    return tone_table({"ring": table}, trim, 2)


def test_bpf1_bpf2_levels_match_gutin():
    theta = np.radians(np.arange(10.0, 171.0, 10.0))
    tones = _tones(R_OBS * np.stack([np.sin(theta), 0 * theta, np.cos(theta)], axis=1))
    m = np.arange(1, 3)
    n = B * m
    exact = n * OMEGA / (2 * np.sqrt(2) * np.pi * C0 * R_OBS) * np.abs(-THRUST * np.cos(theta)[:, None] + TORQUE * C0 / (OMEGA * RE**2)) \
        * np.abs(jv(n, n * OMEGA * RE * np.sin(theta)[:, None] / C0))
    exact_db = 20 * np.log10(exact / 20e-6)
    relevant = exact > exact.max() * 10 ** (-40 / 20)
    for source in ("ring", "total"):
        rows = tones[tones.source == source].sort_values(["observer", "harmonic"])
        np.testing.assert_allclose(rows.frequency_hz.to_numpy().reshape(-1, 2), np.tile(m * B * OMEGA / (2 * np.pi), (theta.size, 1)))
        error = rows.spl_db.to_numpy().reshape(-1, 2) - exact_db
        print(f"{source}: BPF1/BPF2 max |error| {np.abs(error[relevant]).max():.4f} dB over {relevant.sum()} tones")
        assert np.abs(error[relevant]).max() < 0.1


def test_phase_follows_the_rotation():
    theta, turn = np.radians(60.0), np.radians(10.0)
    positions = R_OBS * np.array([[np.sin(theta), 0.0, np.cos(theta)],
                                  [np.sin(theta) * np.cos(turn), np.sin(theta) * np.sin(turn), np.cos(theta)]])
    rows = _tones(positions)
    rows = rows[rows.source == "ring"].pivot(index="harmonic", columns="observer", values="phase_rad")
    shift = np.angle(np.exp(1j * (rows[1] - rows[0] + rows.index.to_numpy() * B * turn)))
    assert np.abs(shift).max() < 1e-3, shift
