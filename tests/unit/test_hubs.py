"""Hubs: teetering, hingeless (equivalent hinge and spring, precone) and δ3 pitch–flap coupling (rotors[].hub,
precone_deg, flap_frequency_per_rev, delta3_deg; docs/reference/loads.md "Hingeless rotors", "Teetering rotors",
"Pitch–flap coupling (δ3)").

Analytic first-harmonic flapping of the code's blade model (rigid blade, hinge offset ε = e/R, root cutout
x0, uniform inflow in hover, linear lift, I_β = ρacR⁴/γ, ν² = 1 + 3ε/(2(1 − ε)) + K_β/(I_βΩ²), the configured
ν_β² of a hingeless hub), Δθ = −tan δ3 · (β − β_p):

    [ν² − 1 + (γ/2) A K]  β1c + (γ/2) D β1s = (γ/2) A θ1c
    −(γ/2) D β1c + [ν² − 1 + (γ/2) A K] β1s = (γ/2) A θ1s,    K = tan δ3,
    A = ∫ (x − ε) x² dx,  D = ∫ (x − ε)² x dx  (x0 … 1, the solver's midpoint stations),

which for ε = 0, x0 = 0 is ν_e² = 1 + (γ/8) tan δ3 (Johnson, Helicopter Theory, §9; Leishman, Principles of
Helicopter Aerodynamics, §4.14): |β1| = |θ1| cos δ3, lagging the cyclic by 90° − δ3; and without δ3 for a spring
(ν > 1) |β1| = |θ1| / √(1 + ((ν² − 1)/(γ/8))²), lagging by atan((γ/8)/(ν² − 1)) < 90°.
"""

import math

import numpy as np
import pytest

from nps.app.config import ConfigError, load_aircraft
from nps.rotor import bet
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.geometry import HubError, OperatingPoint, RotorGeometry

N_R = 40
THETA1 = (math.radians(1.0), math.radians(-0.5))  # θ1c, θ1s
# lift only, no stall, no compressibility: the linear section of the analytic result
LINEAR = LinearAirfoil(cl_max=5.0, cd0=0.0, cd1=0.0, cd2=0.0, mach_cap=1e-6)


def rotor(hub="articulated", delta3_deg=0.0, hinge_offset_m=0.0, precone_deg=0.0, airfoil=LINEAR, n_blades=2, nu=None,
          root_cutout_m=0.5):
    return RotorGeometry(name="t", n_blades=n_blades, radius_m=5.0, chord_m=0.3, root_cutout_m=root_cutout_m,
                         twist_rad=0.0, thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=hinge_offset_m,
                         airfoil=airfoil, hub=hub, delta3_rad=math.radians(delta3_deg),
                         precone_rad=math.radians(precone_deg), flap_frequency_per_rev=nu)


def hover(thrust_N=1.0) -> OperatingPoint:
    return OperatingPoint(omega_rad_s=30.0, mu_x=0.0, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225, speed_of_sound_mps=340.0,
                          thrust_N=thrust_N)


def analytic_first_harmonics(g: RotorGeometry, theta1c: float, theta1s: float, n_r: int = N_R) -> np.ndarray:
    """(β1c, β1s) of the module docstring's equations, integrals on the solver's midpoint stations."""
    eps = g.hinge_offset_m / g.radius_m
    edges = np.linspace(g.root_cutout_m, g.radius_m, n_r + 1) / g.radius_m
    x, dx = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    a, d = np.sum((x - eps) * x**2 * dx), np.sum((x - eps) ** 2 * x * dx)
    nu2 = 1.0 + 1.5 * eps / (1.0 - eps) if g.flap_frequency_per_rev is None else g.flap_frequency_per_rev**2
    stiffness = nu2 - 1.0 + 0.5 * g.lock_number * a * math.tan(g.delta3_rad)  # ν_e² − 1
    half_gamma = 0.5 * g.lock_number
    matrix = np.array([[stiffness, half_gamma * d], [-half_gamma * d, stiffness]])
    return np.linalg.solve(matrix, half_gamma * a * np.array([theta1c, theta1s]))


def numerical_first_harmonics(g: RotorGeometry) -> np.ndarray:
    result = bet.rotor_loads(g, hover(), bet.DiskGrid(36, N_R), bet.Controls(math.radians(3.0), *THETA1), tip_loss=False)
    return np.array([result.flapping.beta1c_rad, result.flapping.beta1s_rad])


@pytest.mark.parametrize("delta3_deg", [0.0, 30.0, 45.0, -20.0])
@pytest.mark.parametrize("hub, hinge_offset_m", [("articulated", 0.0), ("articulated", 0.3), ("teetering", 0.0)])
def test_first_harmonic_flapping_matches_the_analytic_delta3_response(delta3_deg, hub, hinge_offset_m):
    """Within 1 % (vector error of (β1c, β1s)); measured 0.05–0.2 % (exact angles against small angles)."""
    g = rotor(hub, delta3_deg, hinge_offset_m)
    numerical, analytic = numerical_first_harmonics(g), analytic_first_harmonics(g, *THETA1)
    assert np.linalg.norm(numerical - analytic) <= 0.01 * np.linalg.norm(analytic)


def test_delta3_with_central_hinge_and_no_cutout_is_cos_delta3_and_a_lag_of_90_minus_delta3():
    """The closed form the equations reduce to for ε = 0, x0 = 0 (checks the analytic function itself)."""
    for delta3 in (0.0, 30.0, 60.0):
        g = RotorGeometry(name="t", n_blades=2, radius_m=5.0, chord_m=0.3, root_cutout_m=0.0, twist_rad=0.0,
                          thickness_ratio=0.12, lock_number=8.0, delta3_rad=math.radians(delta3))
        b1c, b1s = analytic_first_harmonics(g, 0.01, 0.0, n_r=4000)
        assert math.hypot(b1c, b1s) == pytest.approx(0.01 * math.cos(math.radians(delta3)), rel=1e-6)
        assert math.degrees(math.atan2(b1s, b1c)) == pytest.approx(90.0 - delta3, abs=1e-4)


def test_delta3_zero_is_bit_identical_to_no_coupling():
    base = bet.rotor_loads(rotor(), hover(), bet.DiskGrid(36, 12), bet.Controls(0.1, 0.01, -0.02))
    plain = RotorGeometry(name="t", n_blades=2, radius_m=5.0, chord_m=0.3, root_cutout_m=0.5, twist_rad=0.0,
                          thickness_ratio=0.12, lock_number=8.0, airfoil=LINEAR)
    assert base.disk.equals(bet.rotor_loads(plain, hover(), bet.DiskGrid(36, 12), bet.Controls(0.1, 0.01, -0.02)).disk)


def _forward_flight(thrust_N: float) -> OperatingPoint:
    return OperatingPoint(omega_rad_s=30.0, mu_x=0.25, mu_y=0.0, mu_z=-0.01, density_kg_m3=1.225, speed_of_sound_mps=340.0,
                          thrust_N=thrust_N)


@pytest.mark.parametrize("delta3_deg", [0.0, 45.0])
def test_teetering_blades_flap_equal_and_opposite_with_no_hub_moment(delta3_deg):
    """Forward flight μ 0.25, imposed cyclic: β(ψ + π) − β_p = −(β(ψ) − β_p) at every station, β0 = precone held
    (an articulated e = 0 blade cones to ≈ 3°), hub moment zero: the code's hub moment (B/2)Kβ1 (K = I_βΩ²(ν² − 1)
    = 0) and the first-harmonic aerodynamic flap moment about the teeter hinge, (B/2)M_β,1, which the hinge would
    have to transmit (< 1e-6 of T·R)."""
    grid, controls = bet.DiskGrid(36, 12), bet.Controls(math.radians(8.0), math.radians(1.0), math.radians(-2.0))
    result = bet.rotor_loads(rotor("teetering", delta3_deg, precone_deg=2.0, airfoil=LinearAirfoil()), _forward_flight(1.0),
                             grid, controls)
    beta = result.disk["beta_rad"].to_numpy().reshape(grid.n_psi, grid.n_r)
    precone = math.radians(2.0)
    np.testing.assert_allclose(beta + np.roll(beta, -grid.n_psi // 2, axis=0), 2.0 * precone, atol=1e-15)
    assert result.flapping.beta0_rad == precone and math.hypot(result.flapping.beta1c_rad, result.flapping.beta1s_rad) > 0.01
    assert result.totals.roll_moment_Nm == 0.0 and result.totals.pitch_moment_Nm == 0.0
    disk = result.disk
    psi = disk["psi_rad"].to_numpy().reshape(grid.n_psi, grid.n_r)[:, 0]
    moment = (disk["fz_N_per_m"] * disk["r_m"] * disk["dr_m"]).to_numpy().reshape(grid.n_psi, grid.n_r).sum(axis=1)
    first = 2.0 / grid.n_psi * np.array([moment @ np.cos(psi), moment @ np.sin(psi)])
    assert np.abs(first).max() < 1e-6 * result.totals.thrust_N * 5.0
    articulated = bet.rotor_loads(rotor("articulated", delta3_deg, airfoil=LinearAirfoil()), _forward_flight(1.0), grid, controls)
    assert articulated.flapping.beta0_rad > math.radians(2.5)


def test_teetering_rotor_trims_to_thrust_with_zero_first_harmonic_flapping():
    """A two-bladed teetering tail-rotor-like rotor with δ3 45° trims (collective and phased cyclic) at μ 0.25."""
    g = rotor("teetering", 45.0, precone_deg=1.5, airfoil=LinearAirfoil())
    result = bet.trim_rotor(g, _forward_flight(2500.0), bet.DiskGrid(36, 12))
    assert result.totals.thrust_N == pytest.approx(2500.0, rel=1e-3)
    assert max(abs(result.flapping.beta1c_rad), abs(result.flapping.beta1s_rad)) <= 1e-3
    assert result.flapping.beta0_rad == math.radians(1.5)


def test_hub_errors_name_the_field():
    with pytest.raises(HubError, match="rotor 't': n_blades: a teetering hub .* expected n_blades 2, got 3"):
        rotor("teetering", n_blades=3)
    with pytest.raises(HubError, match="hinge_offset_m: a teetering hub flaps about the rotor axis"):
        rotor("teetering", hinge_offset_m=0.1)
    with pytest.raises(HubError, match="precone_deg: applies to a teetering or hingeless hub only"):
        rotor("articulated", precone_deg=2.0)
    with pytest.raises(HubError, match="hub: expected one of"):
        rotor("gimballed")


def test_a_teetering_rotor_with_four_blades_is_a_config_error_naming_file_and_field(tmp_path, repo_root):
    text = (repo_root / "config/aircraft/helicopter.yaml").read_text().replace("name: helicopter", "name: teeter")
    text = text.replace("    n_blades: 4                    # Table 7.1\n", "    n_blades: 4\n    hub: teetering\n", 1)
    (tmp_path / "teeter.yaml").write_text(text)
    with pytest.raises(ConfigError, match=r"teeter.yaml: rotors\[0\]: rotor '\w+': n_blades: a teetering hub .* got 4"):
        load_aircraft(tmp_path / "teeter.yaml")
    defaults = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")["rotors"][0]
    assert (defaults["hub"], defaults["delta3_deg"], defaults["precone_deg"]) == ("articulated", 0.0, 0.0)


# ---- hingeless hubs: an equivalent hinge at e with a flap spring, its zero at the precone ----

@pytest.mark.parametrize("delta3_deg", [0.0, 30.0])
@pytest.mark.parametrize("nu, hinge_offset_m", [(1.12, 0.0), (1.15, 0.3), (None, 0.6)])
def test_hingeless_first_harmonic_flapping_matches_the_spring_hinge_response(nu, hinge_offset_m, delta3_deg):
    """Hover, imposed cyclic, ν_β 1.12 and 1.15/rev (a spring) or the offset alone: within 1 % (vector error);
    the precone (2°, a constant) does not enter the first harmonics."""
    g = rotor("hingeless", delta3_deg, hinge_offset_m, precone_deg=2.0 if nu else 0.0, nu=nu)
    numerical, analytic = numerical_first_harmonics(g), analytic_first_harmonics(g, *THETA1)
    assert np.linalg.norm(numerical - analytic) <= 0.01 * np.linalg.norm(analytic)


def test_hingeless_blade_answers_a_1_per_rev_pitch_with_less_than_90_deg_lag_and_the_closed_form_amplitude():
    """ν_β 1.12, γ 8, θ1c 1°: the closed form (ε = 0, x0 = 0) |β1| = θ1 / √(1 + ((ν² − 1)/(γ/8))²) = 0.9691°,
    lag atan((γ/8)/(ν² − 1)) = 75.73°; the code with root cutout 0.1 R (x0 changes A and D: the analytic function
    on its stations) within 1 % in amplitude and 0.5° in lag, and the lag below the articulated blade's 90°."""
    nu, gamma8 = 1.12, 1.0
    amplitude = 1.0 / math.sqrt(1.0 + ((nu**2 - 1.0) / gamma8) ** 2)
    lag = math.degrees(math.atan2(gamma8, nu**2 - 1.0))
    closed = rotor("hingeless", nu=nu, root_cutout_m=0.0)
    b1c, b1s = analytic_first_harmonics(closed, math.radians(1.0), 0.0, n_r=4000)
    assert math.degrees(math.hypot(b1c, b1s)) == pytest.approx(amplitude, rel=1e-5)
    assert math.degrees(math.atan2(b1s, b1c)) == pytest.approx(lag, abs=1e-3)
    g = rotor("hingeless", nu=nu)
    result = bet.rotor_loads(g, hover(), bet.DiskGrid(36, N_R), bet.Controls(math.radians(3.0), math.radians(1.0)),
                             tip_loss=False)
    b1c, b1s = result.flapping.beta1c_rad, result.flapping.beta1s_rad
    a1c, a1s = analytic_first_harmonics(g, math.radians(1.0), 0.0)
    assert math.hypot(b1c, b1s) == pytest.approx(math.hypot(a1c, a1s), rel=0.01)
    assert math.degrees(math.atan2(b1s, b1c)) == pytest.approx(math.degrees(math.atan2(a1s, a1c)), abs=0.5)
    assert 60.0 < math.degrees(math.atan2(b1s, b1c)) < 85.0


@pytest.mark.parametrize("nu, hinge_offset_m", [(1.12, 0.0), (1.15, 0.3)])
def test_precone_shifts_the_coning_as_the_spring_equation_says(nu, hinge_offset_m):
    """Hover, no cyclic: ν² β0 = M̄ + (ν² − ν_0²) β_p with M̄ independent of β0 (U_P has no β term in hover), so
    β0(β_p) − β0(0) = (ν² − ν_0²)/ν² β_p (to the solver's 1e-10), the thrust unchanged."""
    controls, grid = bet.Controls(math.radians(8.0)), bet.DiskGrid(24, 12)
    flat = bet.rotor_loads(rotor("hingeless", hinge_offset_m=hinge_offset_m, nu=nu), hover(), grid, controls)
    coned = bet.rotor_loads(rotor("hingeless", hinge_offset_m=hinge_offset_m, nu=nu, precone_deg=2.5), hover(), grid,
                            controls)
    nu0_sq = 1.0 + 1.5 * hinge_offset_m / (5.0 - hinge_offset_m)
    shift = coned.flapping.beta0_rad - flat.flapping.beta0_rad
    assert shift == pytest.approx((nu**2 - nu0_sq) / nu**2 * math.radians(2.5), abs=1e-9)
    assert coned.totals.thrust_N == pytest.approx(flat.totals.thrust_N, rel=1e-9)


def test_precone_equal_to_the_natural_coning_leaves_no_root_moment():
    """e = 0: the articulated blade's coning β0* = M̄ (ν = 1). A hingeless blade (ν 1.12) preconed by β0* cones to
    β0* exactly (its spring moment K_β (β0 − β_p) vanishes); preconed by 0 it cones to M̄/ν², less."""
    controls, grid = bet.Controls(math.radians(8.0)), bet.DiskGrid(24, 12)
    natural = bet.rotor_loads(rotor(), hover(), grid, controls).flapping.beta0_rad
    preconed = bet.rotor_loads(rotor("hingeless", nu=1.12, precone_deg=math.degrees(natural)), hover(), grid, controls)
    assert preconed.flapping.beta0_rad == pytest.approx(natural, abs=1e-9)
    flat = bet.rotor_loads(rotor("hingeless", nu=1.12), hover(), grid, controls)
    assert flat.flapping.beta0_rad == pytest.approx(natural / 1.12**2, abs=1e-9)


def test_rigid_hingeless_blades_are_held_at_their_precone():
    """flapping: false holds a hingeless blade at its unloaded position β = β_p (an articulated one at 0)."""
    result = bet.rotor_loads(rotor("hingeless", nu=1.12, precone_deg=2.5), hover(), bet.DiskGrid(24, 12),
                             bet.Controls(math.radians(8.0)), flapping=False)
    assert np.all(result.disk["beta_rad"] == math.radians(2.5)) and result.flapping.beta0_rad == math.radians(2.5)


def test_hingeless_rotor_trims_to_hub_moments_through_its_spring():
    """Four blades, e = 0, ν_β 1.12, μ 0.25: trimmed to T and to hub moments (B/2) I_βΩ²(ν² − 1) β1 (no offset:
    the spring alone transmits them); an articulated e = 0 rotor refuses moment targets."""
    g = rotor("hingeless", nu=1.12, n_blades=4, precone_deg=2.5, airfoil=LinearAirfoil())
    op = OperatingPoint(omega_rad_s=30.0, mu_x=0.25, mu_y=0.0, mu_z=-0.01, density_kg_m3=1.225, speed_of_sound_mps=340.0,
                        thrust_N=5000.0, roll_moment_Nm=400.0, pitch_moment_Nm=-300.0)
    result = bet.trim_rotor(g, op, bet.DiskGrid(36, 12))
    assert result.totals.thrust_N == pytest.approx(5000.0, rel=1e-3)
    k = 2.0 * bet.flap_inertia(g, 1.225) * 30.0**2 * (1.12**2 - 1.0)
    assert result.totals.roll_moment_Nm == pytest.approx(k * result.flapping.beta1s_rad, rel=1e-12)
    assert result.totals.roll_moment_Nm == pytest.approx(400.0, abs=1e-3 * 5000.0 * 5.0)
    assert result.totals.pitch_moment_Nm == pytest.approx(-300.0, abs=1e-3 * 5000.0 * 5.0)


def test_hingeless_hub_errors_name_the_field():
    with pytest.raises(HubError, match="rotor 't': flap_frequency_per_rev: applies to a hingeless hub only"):
        rotor("articulated", nu=1.1)
    with pytest.raises(HubError, match="flap_frequency_per_rev: a hingeless hub .* needs its flap stiffness"):
        rotor("hingeless")
    with pytest.raises(HubError, match="precone_deg: the precone of a hingeless hub is the zero of its flap spring"):
        rotor("hingeless", hinge_offset_m=0.5, precone_deg=2.0)
    with pytest.raises(HubError, match=r"flap_frequency_per_rev: expected within \[1.08\d*, 3\]"):
        rotor("hingeless", hinge_offset_m=0.5, nu=1.05)


def test_a_hingeless_rotor_in_an_aircraft_file_loads_and_a_wrong_one_names_file_and_field(tmp_path, repo_root):
    text = (repo_root / "config/aircraft/helicopter.yaml").read_text().replace("name: helicopter", "name: stiff")
    hub = "    n_blades: 4                    # Table 7.1\n"
    (tmp_path / "stiff.yaml").write_text(text.replace(hub, hub + "    hub: hingeless\n    flap_frequency_per_rev: 1.12\n"
                                                            "    precone_deg: 2.5\n", 1))
    main = load_aircraft(tmp_path / "stiff.yaml")["rotors"][0]
    g = RotorGeometry.from_config(main)
    assert (g.hub, g.flap_frequency_per_rev, g.precone_rad) == ("hingeless", 1.12, math.radians(2.5))
    (tmp_path / "stiff.yaml").write_text(text.replace(hub, hub + "    flap_frequency_per_rev: 1.12\n", 1))
    with pytest.raises(ConfigError, match=r"stiff.yaml: rotors\[0\]: rotor '\w+': flap_frequency_per_rev: applies to "
                                          r"a hingeless hub only"):
        load_aircraft(tmp_path / "stiff.yaml")
