"""Design-study files (nps.app.designs): expansion, ids, links, constraints, errors."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml

from nps.app.config import ConfigError
from nps.app.designs import PREVIEW_RESOLUTION, design_id, load_study

REPO = Path(__file__).resolve().parents[2]
OMEGA = "aircraft.helicopter.rotors.main.omega_rad_s"
BLADES = "aircraft.helicopter.rotors.main.n_blades"
CHORD = "aircraft.helicopter.rotors.main.chord_m"


@pytest.fixture()
def root(tmp_path):
    shutil.copytree(REPO / "config", tmp_path / "config", ignore=shutil.ignore_patterns("rigs", "studies"))
    (tmp_path / "config" / "studies").mkdir()
    return tmp_path


def study(root: Path, **spec) -> Path:
    spec = {"name": "s", "base": {"aircraft": ["helicopter"], "segments": ["seg2", "seg3"]}, **spec}
    path = root / "config" / "studies" / f"{spec['name']}.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False))
    return path


def test_two_variable_factorial_expands_to_every_combination(root):
    path = study(root, variables=[{"path": OMEGA, "label": "omega", "scale": [0.9, 1.0]},
                                  {"path": BLADES, "label": "blades", "values": [3, 4, 5]}])
    s = load_study(path, root)
    assert [d.values for d in s.designs] == [{"omega": w, "blades": b} for w in (25.2, 28.0) for b in (3, 4, 5)]
    for d in s.designs:
        rotor = d.campaign.aircraft["helicopter"]["rotors"][0]
        assert (rotor["omega_rad_s"], rotor["n_blades"]) == (d.values["omega"], d.values["blades"])
        assert d.campaign.segments == ["seg2", "seg3"] and list(d.campaign.aircraft) == ["helicopter"]
    assert len({d.id for d in s.designs}) == 6


def test_adding_a_value_keeps_every_existing_id(root):
    first = load_study(study(root, variables=[{"path": OMEGA, "label": "omega", "values": [25.0, 28.0]}]), root)
    second = load_study(study(root, variables=[{"path": OMEGA, "label": "omega", "values": [25.0, 28.0, 30.0]}]), root)
    assert {d.id for d in first.designs} < {d.id for d in second.designs}
    assert design_id({"omega": 25.0}) == first.designs[0].id


def test_linked_chord_holds_the_solidity(root):
    path = study(root, variables=[{"path": BLADES, "label": "blades", "values": [3, 5]}],
                 linked=[{"path": CHORD, "follows": BLADES, "exponent": -1.0}])
    for d in load_study(path, root).designs:
        rotor = d.campaign.aircraft["helicopter"]["rotors"][0]
        assert rotor["n_blades"] * rotor["chord_m"] == pytest.approx(4 * 0.58, rel=1e-11)


def test_constraint_drops_variants_and_lists_them(root):
    path = study(root, variables=[{"path": OMEGA, "label": "omega", "values": [20.0, 28.0, 31.0]}],
                 constraints=[{"name": "tip speed", "terms": {OMEGA: 1.0, "aircraft.helicopter.rotors.main.radius_m": 1.0}, "max": 225.0}])
    s = load_study(path, root)
    assert [d.values["omega"] for d in s.designs] == [20.0, 28.0]
    assert s.dropped == (({"omega": 31.0}, "tip speed"),)


def test_latin_hypercube_is_seeded_and_fills_every_stratum(root):
    spec = dict(variables=[{"path": OMEGA, "label": "omega", "range": {"low": 24.0, "high": 30.0}},
                           {"path": "mission.seg2.forward_speed_mps", "label": "speed", "range": {"low": 30.0, "high": 50.0}}],
                design={"kind": "latin_hypercube", "samples": 8, "seed": 3})
    a, b = load_study(study(root, **spec), root), load_study(study(root, **spec), root)
    assert [d.values for d in a.designs] == [d.values for d in b.designs]
    omega = np.array([d.values["omega"] for d in a.designs])
    assert sorted(np.floor((omega - 24.0) / 6.0 * 8).astype(int)) == list(range(8))
    segment = a.designs[0].campaign.segment("seg2")["aircraft"]["helicopter"]
    assert segment["forward_speed_mps"] == a.designs[0].values["speed"] and "flight_path_deg" not in segment


def test_one_at_a_time_varies_each_variable_about_the_base(root):
    path = study(root, variables=[{"path": OMEGA, "label": "omega", "values": [25.0, 30.0]},
                                  {"path": BLADES, "label": "blades", "values": [3, 5]}], design={"kind": "one_at_a_time"})
    values = [d.values for d in load_study(path, root).designs]
    assert values == [{"omega": 28.0, "blades": 4}, {"omega": 25.0, "blades": 4}, {"omega": 30.0, "blades": 4},
                      {"omega": 28.0, "blades": 3}, {"omega": 28.0, "blades": 5}]


def test_preview_fidelity_sets_the_preset_and_a_config_variable_wins(root):
    path = study(root, fidelity="preview", variables=[{"path": "resolution.n_psi", "label": "n_psi", "values": [72]}])
    campaign = load_study(path, root).designs[0].campaign
    assert campaign.config["resolution"] == {**PREVIEW_RESOLUTION, "n_psi": 72}


@pytest.mark.parametrize("variables, field, expected", [
    ([{"path": "aircraft.helicopter.rotors.rear.omega_rad_s", "values": [1.0]}], "variables[0].path", "rotor 'rear'"),
    ([{"path": "aircraft.tandem.gross_weight_kg", "values": [1.0]}], "variables[0].path", "aircraft 'tandem'"),
    ([{"path": "mission.seg9.forward_speed_mps", "values": [1.0]}], "variables[0].path", "segment 'seg9'"),
    ([{"path": "resolution.n_psii", "values": [1]}], "variables[0].path", "no field 'n_psii'"),
    ([{"path": OMEGA, "values": [-5.0]}], "variables[0].values[0]", "expected a number > 0, got -5.0 for " + OMEGA),
    ([{"path": OMEGA, "range": {"low": 30.0, "high": 20.0}}], "variables[0].range", "low < high"),
])
def test_bad_study_names_the_file_and_field(root, variables, field, expected):
    with pytest.raises(ConfigError) as error:
        load_study(study(root, variables=variables), root)
    assert "s.yaml" in str(error.value) and field in str(error.value) and expected in str(error.value)


def test_bundled_studies_validate():
    for path in sorted((REPO / "config" / "studies").glob("*.yaml")):
        assert load_study(path, REPO).designs
