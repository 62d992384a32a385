"""Bad flight-path files (config/paths/*.yaml, nps.app.config.load_path) and ``python -m nps path`` options: one line
naming the file, the field and what was expected, before any computation; the command exits 2 and writes nothing."""

from __future__ import annotations

import copy

import pytest
import yaml

from nps.__main__ import main as nps_main
from nps.app.config import ConfigError, load_path

GOOD = {
    "name": "p", "aircraft": "helicopter",
    "start": {"position_m": [0.0, 0.0], "height_m": 150.0, "heading_deg": 0.0, "speed_mps": 30.0},
    "legs": [{"straight": {"distance_m": 500.0}},
             {"turn": {"heading_change_deg": 90.0, "radius_m": 400.0}, "height_change_m": -20.0}],
}


def _with(edit):
    document = copy.deepcopy(GOOD)
    edit(document)
    return document


CASES = {
    "missing_start": (lambda d: d.pop("start"), "start", "required field is missing"),
    "typo_key": (lambda d: d["start"].update(heading=0.0), "start.heading", "did you mean 'heading_deg'"),
    "negative_height": (lambda d: d["start"].update(height_m=-5.0), "start.height_m", "expected a number >= 0"),
    "both_kinds": (lambda d: d["legs"][0].update(turn={"heading_change_deg": 10.0, "radius_m": 300.0}), "legs[0]",
                   "exactly one of 'straight' and 'turn'"),
    "no_kind": (lambda d: d["legs"][0].pop("straight"), "legs[0]", "exactly one of 'straight' and 'turn'"),
    "straight_without_length": (lambda d: d["legs"][0].update(straight={}), "legs[0].straight",
                                "exactly one of 'distance_m' and 'duration_s'"),
    "turn_radius_and_bank": (lambda d: d["legs"][1]["turn"].update(bank_deg=20.0), "legs[1].turn",
                             "exactly one of 'radius_m' and 'bank_deg'"),
    "speed_and_acceleration": (lambda d: d["legs"][0].update(end_speed_mps=25.0, acceleration_mps2=-0.5),
                               "legs[0].acceleration_mps2", "at most one of"),
    "height_and_angle": (lambda d: d["legs"][1].update(flight_path_deg=-3.0), "legs[1].flight_path_deg", "at most one of"),
    "rotor_fraction_range": (lambda d: d["legs"][0].update(end_rotor_speed_fraction=2.0), "legs[0].end_rotor_speed_fraction",
                             "expected a number <= 1.2"),
    # a tight turn rolled in fast (at 5°/s its roll-in would not fit in the turn: "too_short_to_roll_in")
    "bank_over_limit": (lambda d: (d["legs"][1]["turn"].update(radius_m=60.0), d["legs"][1].pop("height_change_m"),
                                   d.update(roll_rate_deg_s=100.0)), "legs[1].turn.radius_m", "max_bank_deg"),
    "height_change_in_a_short_leg": (lambda d: (d["legs"][1]["turn"].update(radius_m=60.0), d.update(roll_rate_deg_s=100.0)),
                                     "legs[1].height_change_m",
                                     "expected a longer leg, a smaller height change or a larger flight_path_change_g"),
    "too_short_to_roll_in": (lambda d: d["legs"][1]["turn"].update(radius_m=60.0), "legs[1].turn.heading_change_deg",
                             "more than the turn's R |Δψ| = 94.25 m: expected a larger heading change or radius, or a faster "
                             "roll rate"),
    "roll_rate_zero": (lambda d: d.update(roll_rate_deg_s=0.0), "roll_rate_deg_s", "expected a number > 0"),
    "steep_descent": (lambda d: d["legs"][1].update(height_change_m=-400.0), "legs[1].height_change_m", "flight-path angle"),
    "hard_deceleration": (lambda d: d["legs"][0].update(straight={"distance_m": 100.0}, end_speed_mps=5.0), "legs[0].end_speed_mps", "longitudinal acceleration"),
    "zero_heading_change": (lambda d: d["legs"][1]["turn"].update(heading_change_deg=0.0), "legs[1].turn.heading_change_deg",
                            "non-zero heading change"),
    "distance_in_hover": (lambda d: d["start"].update(speed_mps=0.0), "legs[0].straight.distance_m",
                          "a leg without speed covers no distance"),
    "hard_push_over": (lambda d: (d.update(flight_path_change_g=0.6), d["legs"][0].update(flight_path_deg=-5.0)),
                       "flight_path_change_g", "load factor 0.4"),
    "name_not_stem": (lambda d: d.update(name="other"), "name", "expected the file stem 'p'"),
    "nan_speed": (lambda d: d["start"].update(speed_mps=float("nan")), "start.speed_mps", "finite number"),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_path_file_is_one_line_naming_file_and_field(tmp_path, case):
    edit, field, words = CASES[case]
    path = tmp_path / "p.yaml"
    path.write_text(yaml.safe_dump(_with(edit)))
    with pytest.raises(ConfigError) as error:
        load_path(path, 0.5)
    message = str(error.value)
    assert message.startswith(f"{path}: {field}: ") and words in message and "\n" not in message, message


def test_the_good_document_loads(tmp_path):
    path = tmp_path / "p.yaml"
    path.write_text(yaml.safe_dump(GOOD))
    assert load_path(path, 0.5)["limits"]["max_bank_deg"] == 45.0


@pytest.mark.parametrize("args, words", [
    (["--dt-s", "0"], "--dt-s: expected a number > 0"),
    (["--tolerance-advance-ratio", "-0.1"], "--tolerance-advance-ratio: expected a number > 0"),
])
def test_path_command_refuses_bad_options_and_writes_nothing(tmp_path, repo_root, capsys, args, words):
    out = tmp_path / "out"
    status = nps_main(["path", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"),
                       "--path", str(repo_root / "config/paths/helicopter_approach_6deg.yaml"), "--out", str(out), *args])
    error = capsys.readouterr().err
    assert status == 2 and words in error and error.count("\n") == 1 and not out.exists()


def test_path_command_refuses_a_path_of_another_aircraft(tmp_path, repo_root, capsys):
    status = nps_main(["path", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"),
                       "--path", str(repo_root / "config/paths/hexacopter_transition.yaml"), "--out", str(tmp_path / "o")])
    error = capsys.readouterr().err
    assert status == 2 and "hexacopter_transition.yaml: aircraft: expected the aircraft of --aircraft 'helicopter'" in error
