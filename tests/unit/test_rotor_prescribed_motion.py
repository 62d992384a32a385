"""Prescribed blade motion of RotorGeometry (HHC pitch, elastic-twist harmonics) in the BET."""

import dataclasses

import numpy as np
import pytest

from nps import bet
from nps.rotor import OperatingPoint, RotorGeometry

G = RotorGeometry(name="r", n_blades=4, radius_m=2.0, chord_m=0.121, root_cutout_m=0.44, twist_rad=np.radians(-8.0),
                  thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29)
OP = OperatingPoint(109.0, 0.15, 0.0, -0.01, 1.2, 341.0, 3300.0)


def test_prescribed_pitch_values():
    """θ3 cos(3ψ − ψ3) on the whole blade plus the tip elastic twist scaled by r/R."""
    g = dataclasses.replace(G, higher_harmonic_pitch=((3, 0.01, np.radians(300.0)),),
                            elastic_twist_harmonics=((0, -0.009, 0.0), (2, 0.001, -0.002)))
    psi, r = np.array([0.0, 0.7]), np.array([1.0, 2.0])
    expected = (0.01 * np.cos(3 * psi[:, None] - np.radians(300.0))
                + r[None, :] / 2.0 * (-0.009 + 0.001 * np.cos(2 * psi[:, None]) - 0.002 * np.sin(2 * psi[:, None])))
    assert np.allclose(g.prescribed_pitch(psi, r), expected, rtol=0, atol=1e-15)
    assert G.prescribed_pitch(psi, r) is None


def test_hhc_pitch_enters_the_loads():
    """A 3/rev pitch input appears as 3/rev pitch in the disk table and the loads keep the trim."""
    g = dataclasses.replace(G, higher_harmonic_pitch=((3, np.radians(0.8), np.radians(300.0)),))
    base = bet.trim_rotor(G, OP, bet.DiskGrid(72, 12))
    hhc = bet.trim_rotor(g, OP, bet.DiskGrid(72, 12))
    d_theta = (hhc.disk["theta_rad"] - base.disk["theta_rad"]).to_numpy().reshape(72, 12)[:, 0]
    spectrum = np.abs(np.fft.rfft(d_theta)) / 36
    assert spectrum[3] == pytest.approx(np.radians(0.8), rel=1e-6)
    assert hhc.totals.thrust_N == pytest.approx(3300.0, rel=1e-3)


def test_bad_harmonics_are_named():
    g = dataclasses.replace(G, higher_harmonic_pitch=((0, 0.01, 0.0),))
    with pytest.raises(ValueError, match="higher_harmonic_pitch"):
        bet.trim_rotor(g, OP, bet.DiskGrid(16, 4))
    g = dataclasses.replace(G, elastic_twist_harmonics=((1, np.nan, 0.0),))
    with pytest.raises(ValueError, match="elastic_twist_harmonics"):
        bet.trim_rotor(g, OP, bet.DiskGrid(16, 4))


def test_from_config_reads_degrees():
    config = dict(name="r", n_blades=4, radius_m=2.0, chord_m=0.121, root_cutout_m=0.44, twist_deg=-8.0,
                  thickness_ratio=0.12, lock_number=8.0, rotation="ccw",
                  higher_harmonic_pitch=[dict(n=3, amplitude_deg=0.8, phase_deg=300.0)],
                  elastic_twist_harmonics=[dict(n=0, cos_deg=-0.5, sin_deg=0.0)])
    g = RotorGeometry.from_config(config)
    assert g.higher_harmonic_pitch == ((3, np.radians(0.8), np.radians(300.0)),)
    assert g.elastic_twist_harmonics == ((0, np.radians(-0.5), 0.0),)
