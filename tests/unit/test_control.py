"""Rotor control modes (nps.rotor.control): rpm trim, fixed pitch and speed against the closed-form
hover, rigid-blade collective trim, and configuration errors."""

import math

import numpy as np
import pytest

from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.bet import DiskGrid, TrimError, trim_rotor
from nps.rotor.control import RotorControl, at_rotor_speed, solve_rotor
from nps.rotor.geometry import OperatingPoint, RotorGeometry

PROP = RotorGeometry(name="prop", n_blades=2, radius_m=0.12, chord_m=0.018, root_cutout_m=0.015,
                     twist_rad=math.radians(-20.0), thickness_ratio=0.1, lock_number=1.0)
GRID = DiskGrid(36, 24)


@pytest.mark.parametrize("mu_x, flapping", [(0.0, False), (0.08, False), (0.08, True)])
def test_rpm_trim_meets_thrust_with_pitch_unchanged(mu_x, flapping):
    """Fixed pitch 12°: Ω found so that T = 6 N within 0.1 %; θ0 and zero cyclic untouched;
    the free stream kept (μ Ω constant)."""
    pitch = math.radians(12.0)
    op = OperatingPoint(700.0, mu_x, 0.0, 0.01, 1.225, 340.0, 6.0)
    s = solve_rotor(PROP, op, GRID, RotorControl("rpm", pitch, flapping))
    assert abs(s.result.totals.thrust_N / 6.0 - 1.0) <= 1e-3
    c = s.result.controls
    assert c.theta0_rad == pitch and c.theta1c_rad == 0.0 and c.theta1s_rad == 0.0
    w = s.operating_point.omega_rad_s
    assert w != 700.0 and math.isclose(s.operating_point.mu_x * w, mu_x * 700.0, rel_tol=1e-12, abs_tol=1e-15)
    assert math.isclose(s.operating_point.mu_z * w, 0.01 * 700.0, rel_tol=1e-12)
    summary = s.summary().set_index("quantity")["value"]
    assert summary["omega_rad_s"] == w and summary["theta0_rad"] == pitch


def test_fixed_pitch_and_speed_reproduce_closed_form_hover():
    """Hover, no twist or root cutout, linear lift without drag, tip loss or compressibility,
    rigid blades: C_T = (σa/2)(θ/3 − λ/2) with uniform λ = √(C_T/2), i.e.
    λ = (−k/2 + √(k²/4 + 8kθ/3))/4, k = σa/2; θ = 8°: T within 0.5 %."""
    foil = LinearAirfoil(cd0=0.0, cd2=0.0, cl_max=10.0)
    g = RotorGeometry(**{**PROP.__dict__, "root_cutout_m": 0.0, "twist_rad": 0.0, "airfoil": foil})
    theta, omega, rho, radius = math.radians(8.0), 800.0, 1.225, PROP.radius_m
    k = g.solidity * foil.lift_slope_per_rad / 2.0
    lam = (-k / 2.0 + math.sqrt(k * k / 4.0 + 8.0 * k * theta / 3.0)) / 4.0
    thrust = 2.0 * lam**2 * rho * math.pi * radius**2 * (omega * radius) ** 2
    op = OperatingPoint(omega, 0.0, 0.0, 0.0, rho, 1e9, 123.0)  # thrust target unused by 'fixed'
    s = solve_rotor(g, op, DiskGrid(8, 200), RotorControl("fixed", theta, False), tip_loss=False)
    assert abs(s.result.totals.thrust_N / thrust - 1.0) < 5e-3
    assert s.operating_point is op and s.result.totals.power_W > 0.0
    assert np.all(s.result.disk["beta_rad"] == 0.0)


def test_rigid_collective_trim_and_flapping_collective_is_trim_rotor():
    op = OperatingPoint(700.0, 0.05, 0.0, 0.0, 1.225, 340.0, 5.0)
    rigid = solve_rotor(PROP, op, GRID, RotorControl("collective", None, False))
    assert abs(rigid.result.totals.thrust_N / 5.0 - 1.0) <= 1e-3
    assert np.all(rigid.result.disk["beta_rad"] == 0.0) and rigid.result.controls.theta1s_rad == 0.0
    flapping = solve_rotor(PROP, op, GRID, RotorControl())
    reference = trim_rotor(PROP, op, GRID)
    assert flapping.result.totals == reference.totals and flapping.result.controls == reference.controls


def test_control_errors():
    with pytest.raises(ValueError, match="control pitch_deg: required"):
        RotorControl("rpm")
    with pytest.raises(ValueError, match="expected one of"):
        RotorControl("throttle", 0.1)
    with pytest.raises(ValueError, match="expected none with control 'collective'"):
        RotorControl("collective", 0.1)
    assert RotorControl.from_config({"control": "fixed", "pitch_deg": 10.0, "flapping": False}) == \
        RotorControl("fixed", math.radians(10.0), False)
    op = OperatingPoint(700.0, 0.0, 0.0, 0.02, 1.225, 340.0, 5.0)
    with pytest.raises(TrimError, match="gives no positive thrust"):
        solve_rotor(PROP, op, GRID, RotorControl("rpm", math.radians(-10.0), False))
    assert at_rotor_speed(op, 350.0).mu_z == 0.04


def test_rpm_controlled_hexacopter_carries_one_rotor_speed_through_trim_and_loads(tmp_path):
    """The hexacopter with ``control: rpm`` (pitch 10°): the trim stage solves every rotor's Ω with the
    blade-element loads and re-trims the aircraft; the loads stage, at the trim table's Ω, meets the
    table's thrust to 0.1 % with the pitch unchanged and reports that same Ω in its summary (the Ω the
    wake, acoustics and HSI stages read from the table)."""
    from pathlib import Path

    from nps.app.config import load_aircraft
    from nps.app.io import read_table
    from nps.stages import loads as loads_stage
    from nps.stages import trim as trim_stage

    aircraft = load_aircraft(Path(__file__).resolve().parents[2] / "config/aircraft/hexacopter.yaml")
    for rotor in aircraft["rotors"]:
        rotor.update(control="rpm", pitch_deg=10.0)
    resolution = {"n_psi": 36, "n_r": 12}
    trim_stage.run({}, {"trim": tmp_path / "trim.parquet"},
                   {"aircraft_config": aircraft, "speeds": {"forward_speed_mps": 20.0, "climb_speed_mps": 0.0},
                    "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0},
                    "segment": "seg1", **resolution})
    loads_stage.run({"trim": tmp_path / "trim.parquet"}, {"loads": tmp_path / "loads"},
                    {"rotors": {r["name"]: r for r in aircraft["rotors"]}, "aircraft": "hexacopter", "segment": "seg1",
                     **resolution})
    trim = read_table(tmp_path / "trim.parquet").set_index("rotor")
    assert np.all(trim["omega_rad_s"] != 70.0)
    for name, row in trim.iterrows():
        summary = read_table(tmp_path / "loads" / f"{name}_summary.parquet").set_index("quantity")["value"]
        assert summary["omega_rad_s"] == row["omega_rad_s"]
        assert abs(summary["thrust_N"] / row["thrust_N"] - 1.0) <= 1e-3
        assert summary["theta0_rad"] == pytest.approx(math.radians(10.0), abs=1e-15)
