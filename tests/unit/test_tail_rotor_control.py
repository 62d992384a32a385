"""Tail-rotor control as flown (control collective_only, nps.rotor.control): the collective alone trimmed to the
thrust, cyclic zero, the teeter free with δ3 acting; the default of an antitorque rotor with a teetering hub.

Closed form of the free teeter (harmonic balance of the e = 0 flap equation, linear lift, small angles; Johnson,
Helicopter Theory, ch. 5 and §9 for δ3): with x = r/R, u_T = x + μ sin ψ, u_P = λ(x, ψ) + x β' + μ cos ψ β,
β = β_p + β1c cos ψ + β1s sin ψ, θ = θ0 + θ_tw(x) − K_P (β − β_p), K_P = tan δ3, the flap moment about the teeter
hinge per I_βΩ² is m(ψ) = (γ/2) ∫ x (u_T² θ − u_T u_P) dx, and the teeter equation's first harmonics
(ν² − 1) β1 = m1 with ν = 1 (teeter: no spring, no offset) read m1c = m1s = 0 — two linear equations for
(β1c, β1s). In hover they reduce to the flap frequency ν_e² = 1 + (γ/8) K_P (x0 = 0), in forward flight the
μ terms force a teeter that δ3 reduces. The integrals here are on the solver's stations, the azimuth projection
exact (a trigonometric polynomial of degree ≤ 4 on 64 azimuths); λ0 and the skew k_x are the code's converged
momentum inflow (the flap response to a given inflow is what is checked).
"""

import math

import numpy as np
import pytest

from nps.app.config import ConfigError, load_aircraft, load_rig
from nps.rotor import bet
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.control import RotorControl, default_mode, solve_rotor
from nps.rotor.geometry import OperatingPoint, RotorGeometry

# lift only, no stall, no compressibility: the linear section of the closed form
LINEAR = LinearAirfoil(cl_max=5.0, cd0=0.0, cd1=0.0, cd2=0.0, mach_cap=1e-6)
GRID = bet.DiskGrid(36, 16)


def tail(delta3_deg: float, precone_deg: float = 1.0) -> RotorGeometry:
    """A two-bladed teetering tail rotor (R 1.2 m, root cutout 0.2 R, −8° twist, γ 5)."""
    return RotorGeometry(name="tail", n_blades=2, radius_m=1.2, chord_m=0.18, root_cutout_m=0.24,
                         twist_rad=math.radians(-8.0), thickness_ratio=0.1, lock_number=5.0, airfoil=LINEAR,
                         hub="teetering", delta3_rad=math.radians(delta3_deg), precone_rad=math.radians(precone_deg))


def closed_form_teeter(g: RotorGeometry, op: OperatingPoint, theta0: float, inflow: bet.Inflow) -> np.ndarray:
    """(β1c, β1s) of the module docstring's harmonic balance."""
    edges = np.linspace(g.root_cutout_m, g.radius_m, GRID.n_r + 1) / g.radius_m
    x, dx = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    psi = 2.0 * np.pi * np.arange(64)[:, None] / 64
    c, s = np.cos(psi), np.sin(psi)
    mu, k_p, beta_p = op.mu_x, math.tan(g.delta3_rad), g.precone_rad
    lam = op.mu_z + inflow.lambda0 * (1.0 + inflow.kx * x * c)
    u_t = x + mu * s
    theta = theta0 + g.twist_at(x * g.radius_m)

    def first_harmonics(b1c: float, b1s: float) -> np.ndarray:
        teeter = b1c * c + b1s * s
        u_p = lam + x * (-b1c * s + b1s * c) + mu * c * (beta_p + teeter)
        m = 0.5 * g.lock_number * np.sum(x * (u_t**2 * (theta - k_p * teeter) - u_t * u_p) * dx, axis=1)
        return 2.0 / 64 * np.array([m @ c[:, 0], m @ s[:, 0]])

    m0 = first_harmonics(0.0, 0.0)
    jacobian = np.column_stack([first_harmonics(1.0, 0.0) - m0, first_harmonics(0.0, 1.0) - m0])  # linear in β1
    return np.linalg.solve(jacobian, -m0)


@pytest.mark.parametrize("delta3_deg", [0.0, 45.0])
def test_collective_only_reaches_the_thrust_with_zero_cyclic_and_the_free_teeter_of_the_closed_form(delta3_deg):
    """μ 0.2: thrust within 0.1 %, θ1c = θ1s = 0 exactly, β0 = β_p; the teeter (β1c, β1s) within 1.5 % (vector
    error; measured 0.58 % for δ3 0°, 0.61 % for 45°, exact angles against small angles) of the harmonic balance
    at the trimmed θ0; no hub moment."""
    g = tail(delta3_deg)
    op = OperatingPoint(omega_rad_s=150.0, mu_x=0.2, mu_y=0.0, mu_z=0.01, density_kg_m3=1.225, speed_of_sound_mps=340.0,
                        thrust_N=2000.0)
    solution = solve_rotor(g, op, GRID, RotorControl("collective_only"), tip_loss=False)
    result = solution.result
    assert result.totals.thrust_N == pytest.approx(2000.0, rel=1e-3)
    assert result.controls.theta1c_rad == 0.0 and result.controls.theta1s_rad == 0.0
    assert result.flapping.beta0_rad == g.precone_rad
    teeter = np.array([result.flapping.beta1c_rad, result.flapping.beta1s_rad])
    expected = closed_form_teeter(g, op, result.controls.theta0_rad, result.inflow)
    assert np.linalg.norm(expected) > math.radians(0.5)
    assert np.linalg.norm(teeter - expected) <= 0.015 * np.linalg.norm(expected)
    assert result.totals.roll_moment_Nm == 0.0 and result.totals.pitch_moment_Nm == 0.0


def test_delta3_reduces_the_free_teeter_and_collective_trims_it_away():
    """The same tail rotor: the free teeter with δ3 45° is smaller than without; control collective (cyclic) nulls
    it instead (|β1| ≤ 1e-3 rad) with non-zero cyclic."""
    op = OperatingPoint(150.0, 0.2, 0.0, 0.01, 1.225, 340.0, 2000.0)
    free = [solve_rotor(tail(d), op, GRID, RotorControl("collective_only")).result.flapping for d in (0.0, 45.0)]
    amplitude = [math.hypot(f.beta1c_rad, f.beta1s_rad) for f in free]
    assert amplitude[1] < 0.8 * amplitude[0]
    cyclic = solve_rotor(tail(45.0), op, GRID, RotorControl("collective")).result
    assert math.hypot(cyclic.flapping.beta1c_rad, cyclic.flapping.beta1s_rad) <= 1e-3
    assert math.hypot(cyclic.controls.theta1c_rad, cyclic.controls.theta1s_rad) > math.radians(0.5)


def test_collective_only_is_the_default_of_a_teetering_antitorque_rotor(tmp_path, repo_root):
    text = (repo_root / "config/aircraft/helicopter.yaml").read_text().replace("name: helicopter", "name: teeter")
    old = ("    n_blades: 4                    # Table 7.1\n    radius_m: 1.55")
    assert old in text
    text = text.replace(old, "    n_blades: 2\n    hub: teetering\n    delta3_deg: 45.0\n    radius_m: 1.55")
    text = text.replace("    hinge_offset_m: 0.08           # stiff in flap, estimate (~5 % R)\n", "")
    (tmp_path / "teeter.yaml").write_text(text)
    rotors = {r["name"]: r for r in load_aircraft(tmp_path / "teeter.yaml")["rotors"]}
    assert (rotors["main"]["control"], rotors["tail"]["control"]) == ("collective", "collective_only")
    assert RotorControl.from_config(rotors["tail"]) == RotorControl("collective_only")
    assert default_mode({"role": "lift", "hub": "teetering"}) == "collective"
    assert default_mode({"role": "antitorque"}) == "collective"
    (tmp_path / "teeter.yaml").write_text(text.replace("    hub: teetering\n", "    hub: teetering\n    control: collective\n"))
    assert {r["name"]: r["control"] for r in load_aircraft(tmp_path / "teeter.yaml")["rotors"]}["tail"] == "collective"
    (tmp_path / "teeter.yaml").write_text(text.replace("    hub: teetering\n", "    hub: teetering\n    pitch_deg: 8.0\n"))
    with pytest.raises(ConfigError, match=r"teeter.yaml: rotors\[1\].pitch_deg: expected no pitch_deg with control "
                                          r"'collective_only' \(the trim sets the pitch\)"):
        load_aircraft(tmp_path / "teeter.yaml")


def _tail_rig(tmp_path, repo_root, wake_model: str, extra: str = "") -> str:
    """The bundled main + tail rig with a teetering tail rotor under control collective_only."""
    (tmp_path / "main_tail").mkdir()
    (tmp_path / "main_tail/main.yaml").write_text((repo_root / "config/rigs/main_tail/main.yaml").read_text())
    rotor = (repo_root / "config/rigs/main_tail/tail.yaml").read_text().replace("n_blades: 3", "n_blades: 2\nhub: teetering\ndelta3_deg: 45.0")
    (tmp_path / "main_tail/tail.yaml").write_text(rotor.replace("flapping: false\n", ""))
    rig = (repo_root / "config/rigs/main_tail_rig.yaml").read_text().replace("name: main_tail_rig", "name: teeter_rig")
    old = "    control: fixed\n    pitch_deg: 6.0\n"
    assert old in rig and "model: free" in rig
    rig = rig.replace(old, "    control: collective_only\n    thrust_N: 60.0\n" + extra).replace("model: free", f"model: {wake_model}")
    (tmp_path / "teeter_rig.yaml").write_text(rig)
    return tmp_path / "teeter_rig.yaml"


def test_a_rig_tail_rotor_under_collective_only_is_validated(tmp_path, repo_root):
    rig = load_rig(_tail_rig(tmp_path, repo_root, "beddoes"))
    assert rig["rotor_configs"][1]["control"] == "collective_only"


@pytest.mark.parametrize("wake_model, extra, message", [
    ("free", "", r"rotors\[1\] 'tail'.control: 'collective_only' is not available for a rotor coupled to others "
                 r"through the free wake"),
    ("beddoes", "    pitch_deg: 6.0\n", r"rotors\[1\] 'tail'.pitch_deg: got 6.0, but control 'collective_only' trims "
                                        r"the pitch"),
    ("beddoes", "    roll_moment_Nm: 5.0\n", r"rotors\[1\] 'tail'.roll_moment_Nm: got 5.0, but only control "
                                            r"'collective' with flapping trims the hub moments"),
])
def test_rig_collective_only_errors_name_file_and_field(tmp_path, repo_root, wake_model, extra, message):
    with pytest.raises(ConfigError, match=r"teeter_rig.yaml: " + message):
        load_rig(_tail_rig(tmp_path, repo_root, wake_model, extra))
