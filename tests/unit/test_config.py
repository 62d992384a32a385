"""Configuration validation: every bad input gives one clear message naming file, field, expectation."""

import copy
import shutil
from pathlib import Path

import pytest
import yaml

from nps.app.config import ConfigError, load_aircraft, load_campaign, load_mission, read_yaml

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def config_tree(tmp_path):
    """A writable copy of config/ and the campaign configuration."""
    shutil.copytree(REPO / "config", tmp_path / "config")
    return tmp_path


def _edit_yaml(path, edit):
    data = yaml.safe_load(path.read_text())
    edit(data)
    path.write_text(yaml.safe_dump(data, sort_keys=False))


def _aircraft_error(tree, edit):
    path = tree / "config" / "aircraft" / "helicopter.yaml"
    _edit_yaml(path, edit)
    with pytest.raises(ConfigError) as info:
        load_aircraft(path)
    return str(info.value)


def test_bundled_configuration_is_valid(repo_root):
    campaign = load_campaign(read_yaml(repo_root / "config/config.yaml"), root=repo_root)
    assert set(campaign.aircraft) == {"helicopter", "tandem", "coaxial", "hexacopter"}
    assert campaign.segments == [f"seg{i}" for i in range(1, 7)]
    assert campaign.rotor_names("hexacopter") == ["front", "front_right", "rear_right", "rear", "rear_left", "front_left"]


def test_bundled_campaign_runs_broadband_auto_and_thesis_pegg_differs_only_there(repo_root):
    """config/config.yaml runs the broadband model valid for each rotor (auto); config/thesis_pegg.yaml, the thesis'
    Pegg-only reproduction, is the same campaign with models.broadband: pegg."""
    bundled, thesis = read_yaml(repo_root / "config/config.yaml"), read_yaml(repo_root / "config/thesis_pegg.yaml")
    assert bundled["models"]["broadband"] == "auto" and thesis["models"]["broadband"] == "pegg"
    thesis["models"]["broadband"] = "auto"
    assert thesis == bundled
    assert load_campaign(read_yaml(repo_root / "config/thesis_pegg.yaml"), "config/thesis_pegg.yaml", root=repo_root).broadband_model() == "pegg"


def test_missing_required_field(config_tree):
    message = _aircraft_error(config_tree, lambda d: d["rotors"][0].pop("chord_m"))
    assert "helicopter.yaml: rotors[0].chord_m: required field is missing" in message


def test_wrong_type(config_tree):
    message = _aircraft_error(config_tree, lambda d: d["rotors"][1].__setitem__("n_blades", "four"))
    assert "helicopter.yaml: rotors[1].n_blades: expected integer, got str 'four'" in message


@pytest.mark.parametrize("field", ["radius_m", "n_blades", "omega_rad_s"])
@pytest.mark.parametrize("value", [0, -1])
def test_zero_or_negative(config_tree, field, value):
    message = _aircraft_error(config_tree, lambda d: d["rotors"][0].__setitem__(field, value))
    assert f"rotors[0].{field}: expected a number >" in message
    assert f"got {value}" in message


@pytest.mark.parametrize("value", [float("nan"), float("inf"), float("-inf")])
def test_non_finite(config_tree, value):
    message = _aircraft_error(config_tree, lambda d: d.__setitem__("gross_weight_kg", value))
    assert "helicopter.yaml: gross_weight_kg: expected a finite number" in message


def test_unknown_key_typo(config_tree):
    message = _aircraft_error(config_tree, lambda d: d["rotors"][0].__setitem__("raduis_m", 7.0))
    assert "rotors[0].raduis_m: unknown key (did you mean 'radius_m'?" in message
    # the required radius_m it replaces is not reported a second time
    assert "radius_m: required" not in message


def test_root_cutout_beyond_tip(config_tree):
    message = _aircraft_error(config_tree, lambda d: d["rotors"][0].__setitem__("root_cutout_m", 8.0))
    assert "rotors[0].root_cutout_m: expected < radius_m" in message


def test_campaign_names_missing_aircraft(config_tree):
    config = read_yaml(config_tree / "config" / "config.yaml")
    config["campaign"]["aircraft"].append("gyroplane")
    with pytest.raises(ConfigError, match=r"config\.yaml: campaign\.aircraft\[4\]: expected an aircraft file .*gyroplane\.yaml"):
        load_campaign(config, "config.yaml", root=config_tree)


def test_campaign_names_missing_segment(config_tree):
    config = read_yaml(config_tree / "config" / "config.yaml")
    config["campaign"]["segments"] = ["seg1", "seg9"]
    with pytest.raises(ConfigError, match=r"campaign\.segments\[1\]: expected one of the mission's segments"):
        load_campaign(config, "config.yaml", root=config_tree)


def test_segment_with_an_aircraft_outside_the_campaign_is_accepted(config_tree):
    """A mission may list more aircraft than the campaign (another campaign's, or none on file): only the
    campaign's aircraft run."""
    path = config_tree / "config" / "missions" / "demo.yaml"
    _edit_yaml(path, lambda d: d["segments"][2]["aircraft"].__setitem__("blimp", {"forward_speed_mps": 10.0, "climb_speed_mps": 0.0}))
    config = read_yaml(config_tree / "config" / "config.yaml")
    assert "blimp" not in load_campaign(config, "config.yaml", root=config_tree).aircraft


def test_segment_without_a_campaign_aircraft_suggests_the_misspelt_one(config_tree):
    path = config_tree / "config" / "missions" / "demo.yaml"
    _edit_yaml(path, lambda d: d["segments"][2]["aircraft"].__setitem__("tandm", d["segments"][2]["aircraft"].pop("tandem")))
    config = read_yaml(config_tree / "config" / "config.yaml")
    with pytest.raises(ConfigError, match=r"demo\.yaml: segments\[2\]\.aircraft: expected speeds for aircraft 'tandem' of "
                                          r"the campaign \(did you mean 'tandm'\?\)"):
        load_campaign(config, "config.yaml", root=config_tree)


def test_segment_names_missing_rotor(config_tree):
    path = config_tree / "config" / "missions" / "demo.yaml"
    _edit_yaml(path, lambda d: d["segments"][0]["aircraft"]["helicopter"].__setitem__("rotor_omega_scale", {"mian": 0.95}))
    config = read_yaml(config_tree / "config" / "config.yaml")
    with pytest.raises(ConfigError, match=r"segments\[0\]\.aircraft\.helicopter\.rotor_omega_scale\.mian: names a rotor that does not exist"):
        load_campaign(config, "config.yaml", root=config_tree)


def test_flight_path_inconsistent_with_speeds(config_tree):
    path = config_tree / "config" / "missions" / "demo.yaml"
    _edit_yaml(path, lambda d: d["segments"][0]["aircraft"]["tandem"].__setitem__("flight_path_deg", -5.28))
    with pytest.raises(ConfigError, match=r"segments\[0\]\.aircraft\.tandem\.flight_path_deg: expected atan2"):
        load_mission(path)


def test_campaign_config_bad_enum(repo_root):
    config = copy.deepcopy(read_yaml(repo_root / "config/config.yaml"))
    config["models"]["thickness"] = "full_surface"
    with pytest.raises(ConfigError, match=r"config\.yaml: models\.thickness: expected one of \['dual_compact', 'compact_monopole'\]"):
        load_campaign(config, "config.yaml", root=repo_root)


def test_yaml_syntax_error_names_file(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text("name: [unclosed\n")
    with pytest.raises(ConfigError, match=r"broken.yaml: line 2, column 1: not valid YAML: expected ',' or '\]'"):
        read_yaml(path)


@pytest.mark.parametrize("text, line, key", [
    ("resolution:\n  n_psi: 72\n  n_r: 16\n  n_psi: 36000\n", 4, "n_psi"),
    ("name: a\nrotors:\n  - name: main\n    radius_m: 5.0\n    radius_m: 50.0\n", 5, "radius_m"),
    ("campaign: {mission: demo, mission: other}\n", 1, "mission"),
])
def test_a_key_given_twice_is_refused_with_its_line(tmp_path, text, line, key):
    """PyYAML keeps the last of two equal keys; NPS refuses the file and names both lines."""
    path = tmp_path / "config.yaml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=rf"config.yaml: line {line}, column \d+: not valid YAML: duplicate key '{key}'"):
        read_yaml(path)


def test_merge_keys_may_override_what_they_merge(tmp_path):
    path = tmp_path / "config.yaml"
    path.write_text("base: &b {n_psi: 72, n_r: 16}\nresolution:\n  <<: *b\n  n_psi: 36\n")
    assert read_yaml(path)["resolution"] == {"n_psi": 36, "n_r": 16}
