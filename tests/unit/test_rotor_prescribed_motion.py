"""Prescribed blade motion of RotorGeometry (HHC pitch, elastic-twist harmonics) in the BET."""

import dataclasses

import numpy as np
import pytest

from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry

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


def test_prescribed_flap_with_the_rigid_solution_reproduces_the_rigid_trim():
    """Prescribing exactly the flapping the rigid-flap trim found (β0, β1c, β1s) must give the same
    controls, inflow and loads: at convergence the hub moment (B/2) K β1 equals (B/2) × the
    aerodynamic first-harmonic flap moment that the prescribed-flap trim matches to the targets."""
    op = dataclasses.replace(OP, roll_moment_Nm=20.0, pitch_moment_Nm=-20.0)
    rigid = bet.trim_rotor(G, op, bet.DiskGrid(72, 16), tol_rel=1e-5)
    f = rigid.flapping
    g = dataclasses.replace(G, prescribed_flap_harmonics=((0, f.beta0_rad, 0.0), (1, f.beta1c_rad, f.beta1s_rad)))
    prescribed = bet.trim_rotor(g, op, bet.DiskGrid(72, 16), tol_rel=1e-5)
    for a, b in zip((rigid.controls.theta0_rad, rigid.controls.theta1c_rad, rigid.controls.theta1s_rad),
                    (prescribed.controls.theta0_rad, prescribed.controls.theta1c_rad, prescribed.controls.theta1s_rad)):
        assert b == pytest.approx(a, abs=2e-5)
    assert prescribed.totals.roll_moment_Nm == pytest.approx(20.0, abs=0.2)
    assert prescribed.totals.pitch_moment_Nm == pytest.approx(-20.0, abs=0.2)
    assert np.allclose(prescribed.disk["beta_rad"], rigid.disk["beta_rad"], atol=1e-12)
    assert np.allclose(prescribed.disk["fz_N_per_m"], rigid.disk["fz_N_per_m"], rtol=0, atol=1e-3 * rigid.disk["fz_N_per_m"].abs().max())


def test_prescribed_flap_enters_the_kinematics():
    """β(ψ) and β̇ = Ω dβ/dψ of the given harmonics (n = 0…2) in the disk table; the reported
    flapping is its mean and first harmonic."""
    h = ((0, 0.04, 0.0), (1, 0.002, -0.008), (2, 0.001, 0.0005))
    g = dataclasses.replace(G, prescribed_flap_harmonics=h)
    t = bet.trim_rotor(g, OP, bet.DiskGrid(72, 8))
    psi = t.disk["psi_rad"].to_numpy()
    beta = sum(c * np.cos(n * psi) + s * np.sin(n * psi) for n, c, s in h)
    rate = OP.omega_rad_s * sum(n * (s * np.cos(n * psi) - c * np.sin(n * psi)) for n, c, s in h)
    assert np.allclose(t.disk["beta_rad"], beta, rtol=0, atol=1e-15)
    assert np.allclose(t.disk["beta_dot_rad_s"], rate, rtol=0, atol=1e-12)
    assert (t.flapping.beta0_rad, t.flapping.beta1c_rad, t.flapping.beta1s_rad) == pytest.approx((0.04, 0.002, -0.008))
    assert t.totals.thrust_N == pytest.approx(3300.0, rel=1e-3)


def test_prescribed_flap_config_and_errors():
    """``prescribed_flap: [{n, cos_deg, sin_deg}]`` is read in degrees, accepted by the aircraft
    schema, and a bad entry is named before computing."""
    from nps.app import config as cfg

    rotor = dict(name="r", role="lift", n_blades=4, radius_m=2.0, chord_m=0.121, root_cutout_m=0.44, twist_deg=-8.0,
                 thickness_ratio=0.12, omega_rad_s=109.0, rotation="ccw", hub_position_m=[0, 0, 1],
                 thrust_axis_body=[0, 0, 1], lock_number=8.0,
                 higher_harmonic_pitch=[dict(n=3, amplitude_deg=0.8, phase_deg=300.0)],
                 elastic_twist_harmonics=[dict(n=0, cos_deg=-0.5, sin_deg=0.0)],
                 prescribed_flap=[dict(n=0, cos_deg=2.5, sin_deg=0.0), dict(n=1, cos_deg=0.1, sin_deg=-0.4)])
    aircraft = dict(name="a", description="d", gross_weight_kg=330.0, fuselage_drag_area_m2=0.0, rotors=[rotor])
    cfg.validate(aircraft, "aircraft", "a.yaml")
    assert RotorGeometry.from_config(rotor).prescribed_flap_harmonics == (
        (0, np.radians(2.5), 0.0), (1, np.radians(0.1), np.radians(-0.4)))
    with pytest.raises(ValueError, match="prescribed_flap"):
        cfg.validate(dict(aircraft, rotors=[dict(rotor, prescribed_flap=[dict(n=-1, cos_deg=1.0, sin_deg=0.0)])]),
                     "aircraft", "a.yaml")
    g = dataclasses.replace(G, prescribed_flap_harmonics=((1, 0.01, np.inf),))
    with pytest.raises(ValueError, match="prescribed_flap_harmonics"):
        bet.trim_rotor(g, OP, bet.DiskGrid(16, 4))
