"""Blade and airfoil tables and control modes in an aircraft file: a valid propeller with a blade
CSV, the NACA 0012 deck (SAND80-2114) and rpm control, and each bad input stopping with file and field."""

import math
import shutil

import numpy as np
import pytest
import yaml

from nps.rotor.airfoils import AirfoilError
from nps.rotor.bet import DiskGrid
from nps.app.config import ConfigError, load_aircraft
from nps.rotor.control import RotorControl, solve_rotor
from nps.rotor.geometry import OperatingPoint, RotorGeometry

PROP = {
    "name": "prop", "role": "lift", "n_blades": 2, "radius_m": 0.12, "root_cutout_m": 0.015,
    "omega_rad_s": 700.0, "rotation": "ccw", "hub_position_m": [0.0, 0.0, 0.0], "thrust_axis_body": [0.0, 0.0, 1.0],
    "lock_number": 1.0, "control": "rpm", "pitch_deg": 12.0, "flapping": False,
    "airfoil": {"table": "../airfoils/naca0012.c81"}, "blade": {"table": "../blades/prop.csv"},
}
BLADE_CSV = """# r/R, c/R, twist (deg), t/c
r_over_R,chord_over_R,twist_deg,thickness_ratio
0.125,0.20,18.0,0.22
0.5,0.17,6.0,0.12
1.0,0.09,-4.0,0.07
"""


@pytest.fixture
def tree(tmp_path, repo_root):
    (tmp_path / "config" / "aircraft").mkdir(parents=True)
    (tmp_path / "config" / "blades").mkdir()
    shutil.copytree(repo_root / "config" / "airfoils", tmp_path / "config" / "airfoils")
    (tmp_path / "config" / "blades" / "prop.csv").write_text(BLADE_CSV)
    return tmp_path / "config"


def _write(tree, rotor):
    path = tree / "aircraft" / "drone.yaml"
    path.write_text(yaml.safe_dump({"name": "drone", "description": "test", "gross_weight_kg": 1.0,
                                    "fuselage_drag_area_m2": 0.0, "rotors": [rotor]}, sort_keys=False))
    return path


def _error(tree, rotor) -> str:
    with pytest.raises(ConfigError) as info:
        load_aircraft(_write(tree, rotor))
    return str(info.value)


def test_propeller_with_tables_and_rpm_control(tree):
    """Paths resolve against the aircraft file; the loads use the table's chord and the deck;
    rpm control meets the thrust at the configured pitch."""
    rotor = load_aircraft(_write(tree, PROP))["rotors"][0]
    g = RotorGeometry.from_config(rotor)
    assert g.blade is not None and g.airfoil.full_range and math.isclose(g.airfoil.lift_slope_per_rad, 0.22 / math.radians(2.0), rel_tol=1e-12)
    assert np.allclose(g.chord_at(np.array([0.015, 0.12])), [0.024, 0.0108])
    assert g.twist_at(0.09) == pytest.approx(0.0, abs=1e-15)  # θ0 is the pitch at 75 % R
    op = OperatingPoint(700.0, 0.0, 0.0, 0.0, 1.225, 340.0, 4.0)
    s = solve_rotor(g, op, DiskGrid(36, 20), RotorControl.from_config(rotor))
    assert abs(s.result.totals.thrust_N / 4.0 - 1.0) <= 1e-3
    assert s.result.controls.theta0_rad == math.radians(12.0)


def test_missing_airfoil_table_names_file_and_field(tree):
    message = _error(tree, {**PROP, "airfoil": {"table": "../airfoils/nope.c81"}})
    assert "drone.yaml: rotors[0].airfoil.table: file not found:" in message and "nope.c81" in message


def test_malformed_airfoil_table_names_both_files_and_the_row(tree):
    deck = tree / "airfoils" / "naca0012.c81"
    lines = deck.read_text().splitlines()
    lines[3] = lines[3][:7] + "  oops " + lines[3][14:]
    deck.write_text("\n".join(lines) + "\n")
    message = _error(tree, PROP)
    assert "drone.yaml: rotors[0]:" in message and "naca0012.c81: line 4: CL row 2: columns 8-14" in message


def test_alpha_range_not_covering_the_operating_point_names_file_and_field(tree):
    """A −6…8° polar without extension: the blade root of this propeller runs at larger angles;
    the loads stop with the polar file, the coefficient and the range; with Viterna they run."""
    polar = tree / "airfoils" / "narrow.csv"
    polar.write_text("alpha_deg,cl,cd\n" + "\n".join(f"{a},{0.1 * a},{0.01}" for a in range(-6, 9)) + "\n")
    rotor = load_aircraft(_write(tree, {**PROP, "airfoil": {"table": "../airfoils/narrow.csv"}}))["rotors"][0]
    op = OperatingPoint(700.0, 0.0, 0.0, 0.0, 1.225, 340.0, 4.0)
    with pytest.raises(AirfoilError, match=r"narrow\.csv: CL: angle of attack .* outside the table's range \[-6\.00, 8\.00\] deg"):
        solve_rotor(RotorGeometry.from_config(rotor), op, DiskGrid(36, 20), RotorControl.from_config(rotor))
    rotor = load_aircraft(_write(tree, {**PROP, "airfoil": {"table": "../airfoils/narrow.csv", "extrapolation": "viterna"}}))["rotors"][0]
    s = solve_rotor(RotorGeometry.from_config(rotor), op, DiskGrid(36, 20), RotorControl.from_config(rotor))
    assert abs(s.result.totals.thrust_N / 4.0 - 1.0) <= 1e-3


@pytest.mark.parametrize("change, expected", [
    ({"control": "collective"}, "rotors[0].pitch_deg: expected no pitch_deg with control 'collective'"),
    ({"pitch_deg": None}, "rotors[0].pitch_deg: required with control 'rpm'"),
    ({"chord_m": 0.02}, "rotors[0].chord_m: expected no linear-blade field next to a blade table"),
    ({"airfoil": {"table": "../airfoils/naca0012.c81", "cd0": 0.01}}, "rotors[0].airfoil.cd0: expected no linear-model parameter"),
    ({"control": "throttle"}, "rotors[0].control: expected one of ['collective', 'collective_only', 'rpm', 'fixed']"),
    ({"blade": {"table": "../blades/none.csv"}}, "rotors[0].blade.table: file not found"),
    ({"blade": None}, "rotors[0].chord_m: required field is missing"),
    ({"blade": {"table": "../blades/prop.csv"}, "airfoils": {}, "airfoil": {"extrapolation": "viterna"}},
     "rotors[0].airfoil.extrapolation: applies to a table only"),
])
def test_bad_rotor_fields(tree, change, expected):
    rotor = {k: v for k, v in {**PROP, **change}.items() if v is not None}
    assert expected in _error(tree, rotor)


def test_blade_airfoil_names_must_be_defined(tree):
    (tree / "blades" / "prop.csv").write_text("r_over_R,chord_over_R,twist_deg,thickness_ratio,airfoil\n"
                                              "0.125,0.2,18,0.22,root\n0.5,0.17,6,0.12,root\n0.8,0.12,0,0.08,tip\n"
                                              "1.0,0.09,-4,0.07,tip\n")
    message = _error(tree, {**PROP, "airfoils": {"root": {"cl_max": 1.0}}})
    assert "drone.yaml: rotors[0]:" in message and "defines no airfoil named 'tip'" in message
    rotor = load_aircraft(_write(tree, {**PROP, "airfoils": {"root": {"cl_max": 1.0}, "tip": {"table": "../airfoils/naca0012.c81"}}}))
    g = RotorGeometry.from_config(rotor["rotors"][0])
    assert g.airfoil is g.airfoils["tip"]  # the airfoil nearest 0.75 R is the reference
