"""Pegg broadband model against its published shape table and level formula.

Reference: tests/data/pegg/pegg_broadband_spectrum_psuwopwop.csv (Pegg, NASA TM-80200, as coded
in PSU-WOPWOP's broadbandModule; README there). Thesis eq. 3.1-3.3.
"""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from nps.noise.broadband import pegg as broadband

TABLE = pd.read_csv(Path(__file__).resolve().parents[1] / "data" / "pegg" / "pegg_broadband_spectrum_psuwopwop.csv", comment="#")

# Demonstration helicopter main rotor (thesis ch. 7, Table 7.1; chord 0.58 m per design notes)
B, R, CHORD, OMEGA = 4, 7.62, 0.58, 28.0
THRUST = 5140.0 * 9.80665
RHO, C0 = 1.225, 340.29399


def test_shape_table_is_the_published_one():
    """S(offset) equals the table's interpolated column (exact) for −15…+21 bands, hence the
    baseline column at whole octaves; NaN outside."""
    offsets = TABLE["third_octave_offset"].to_numpy()
    assert np.array_equal(broadband.shape_db(offsets), TABLE["S_interp_dB"].to_numpy())
    base = TABLE.dropna(subset=["S_baseline_dB"])
    assert np.array_equal(broadband.shape_db(base["third_octave_offset"]), base["S_baseline_dB"].to_numpy())
    assert np.isnan(broadband.shape_db([-16, 22])).all()


def test_continuous_spectrum_energy_vs_octave_sampling():
    """Filling every 1/3-octave band (NPS's choice) carries 4.5458 dB more energy than PSU-WOPWOP's
    default whole-octave sampling: exactly the magnitude of its keepEnergyConst offset (file
    header), to 1e-4 dB. So NPS totals = PSU-WOPWOP (spreadBands, no keepEnergyConst)."""
    s = broadband.shape_db(np.arange(-15, 22))
    whole = broadband.shape_db(np.arange(-15, 22, 3))
    delta = 10 * np.log10(np.sum(10 ** (s / 10)) / np.sum(10 ** (whole / 10)))
    assert delta == pytest.approx(4.5458, abs=1e-4)


def test_level_formula_against_reference_header():
    """Band levels equal the file's SPL formula evaluated independently here (1e-9 dB), for a
    low-lift (C̄_L ≤ 0.48) and a high-lift case, two observers."""
    bands = np.arange(-20, 14)
    for cl in (0.3, 0.7):
        rotor = broadband.PeggRotor(thrust_N=2.0e4, tip_speed_mps=200.0, blade_area_m2=10.0, mean_lift_coefficient=cl)
        r = np.array([50.0, 120.0])
        cos_t = np.array([0.2, -0.9])
        ours = broadband.band_levels_db(rotor, bands, r, cos_t, 340.0)
        fp = -240 * np.log10(2.0e4) + 2.448 * 200.0 + 942
        n_peak = int(np.floor(10 * np.log10(fp / 1000) + 0.5))
        f_cl = 10 * np.log10(cl / 0.4) if cl <= 0.48 else 0.8 + 80 * np.log10(cl / 0.48)
        lookup = dict(zip(TABLE["third_octave_offset"], TABLE["S_interp_dB"]))
        for j, n in enumerate(bands):
            s = lookup.get(n - n_peak)
            for i in range(2):
                if s is None:
                    assert ours[i, j] == broadband.LEVEL_FLOOR_DB
                    continue
                ref = s + 60 * np.log10(200.0 / 340.0) + 10 * np.log10(10.0 / r[i] ** 2 * (cos_t[i] ** 2 + 0.1)) + f_cl + 130
                assert ours[i, j] == pytest.approx(ref, abs=1e-9)


def test_demonstration_helicopter_peak():
    """Demonstration main rotor (B=4, R=7.62 m, c=0.58 m, Ω=28 rad/s, T=5140 kg·g, ρ=1.225,
    c0=340.29 m/s), observer 76.2 m below the hub:
    f_p = −240 log10(50406 N) + 2.448·213.36 + 942 = 335.7 Hz → band 315 Hz (n = −5);
    C_T = 0.004955, σ = 0.09691, C̄_L = 0.3068, f(C̄_L) = −1.152 dB;
    peak band level = 60 log10(213.36/340.29) + 10 log10(17.68/76.2²·1.1) − 7.5 − 1.152 + 130
    = 84.43 dB (to 0.01 dB)."""
    vt = OMEGA * R
    ct = THRUST / (RHO * np.pi * R**2 * vt**2)
    sigma = B * CHORD / (np.pi * R)
    cl = broadband.mean_lift_coefficient(ct, sigma)
    assert cl == pytest.approx(0.3068, abs=1e-4)
    fp = broadband.peak_frequency_hz(THRUST, vt)
    assert fp == pytest.approx(335.7, abs=0.05)
    rotor = broadband.PeggRotor(THRUST, vt, B * CHORD * R, cl)
    bands = np.arange(-20, 14)
    levels = broadband.band_levels_db(rotor, bands, [76.2], [1.0], C0)[0]
    assert bands[np.argmax(levels)] == -5
    assert levels.max() == pytest.approx(84.43, abs=0.01)


def test_directivity_below_vs_in_plane():
    """On the axis (cos²θ = 1) the spectrum is 10 log10(1.1/0.1) = 10.41 dB above the rotor plane
    (cos θ = 0), at every band: Pegg's broadband matters under the rotor, little in plane."""
    rotor = broadband.PeggRotor(5.0e4, 213.0, 17.7, 0.31)
    lv = broadband.band_levels_db(rotor, np.arange(-10, 5), [100.0, 100.0], [1.0, 0.0], 340.0)
    assert np.allclose(lv[0] - lv[1], 10 * np.log10(11.0), atol=1e-12)
