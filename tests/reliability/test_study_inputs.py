"""Design-study inputs (nps.app.designs.check_study, nps.api.Study, ``snakemake -n study_NAME``) and rig axes
(nps.app.config.load_rig): every input a study or rig cannot honour as written is refused before any variant
is made, in one line naming the file, the field as written and what was expected; every accepted one gives
the designs it says. The 100,000-sample Latin hypercube is refused with its size and estimated cost without
validating a single variant (its wall time is benchmarks/bench_study_size.py's)."""

from __future__ import annotations

import copy
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

import nps.app.designs as designs
from nps.api.study import Study
from nps.app.config import ConfigError, load_rig
from nps.app.designs import check_study, load_study
from nps.app.trade import trade_tables
from nps.rig.case import rotor_axis_test

REPO = Path(__file__).resolve().parents[2]
MAIN = "aircraft.helicopter.rotors.main"
OMEGA, BLADES, CHORD, TWIST = f"{MAIN}.omega_rad_s", f"{MAIN}.n_blades", f"{MAIN}.chord_m", f"{MAIN}.twist_deg"
DOWNLOAD = "aircraft.helicopter.hover_download_fraction"  # base value 0.0 (schema default)
OMEGAS = {"path": OMEGA, "label": "omega", "values": [26.0, 28.0]}
DESCENT = "paths.helicopter_approach_6deg.legs.1"  # the 6 deg approach's descent leg
PROCEDURE_BASE = {"aircraft": ["helicopter"], "paths": ["helicopter_approach_6deg"]}
PROCEDURE = {"base": PROCEDURE_BASE, "products": ["procedure"]}


@pytest.fixture()
def root(tmp_path):
    shutil.copytree(REPO / "config", tmp_path / "config", ignore=shutil.ignore_patterns("rigs", "studies"))
    (tmp_path / "config" / "studies").mkdir()
    return tmp_path


def write(root: Path, name: str = "s", **spec) -> Path:
    spec = {"name": name, "base": {"aircraft": ["helicopter"], "segments": ["seg2", "seg3"]}, **spec}
    path = root / "config" / "studies" / f"{name}.yaml"
    path.write_text(yaml.safe_dump(spec, sort_keys=False))
    return path


def refusal(root: Path, spec: dict, resolution: dict | None = None) -> str:
    """The first line a study is refused with (a ConfigError of check_study: one line per problem, after an
    "N problems:" line when there are several), nothing written but the study."""
    path = write(root, **spec)
    with pytest.raises(ConfigError) as error:
        load_study(path, root, resolution)
    lines = str(error.value).splitlines()
    if len(lines) > 1:
        assert lines[0] == f"{len(lines) - 1} problems:", lines
        lines = [line.strip() for line in lines[1:]]
    assert all(line.startswith(str(root)) and "Traceback" not in line for line in lines), lines
    assert sorted(p.name for p in root.iterdir()) == ["config"], "an artifact was written"
    return lines[0]


# (id, study fields, field as written, what the line says)
REFUSED = [
    ("same_field_twice", {"variables": [OMEGAS, {"path": OMEGA, "label": "w", "values": [25.0]}]},
     "variables[1].path", f"sets {OMEGA}, as variables[0].path does; expected each field in one variable"),
    ("same_field_by_alias", {"variables": [{"path": "resolution.n_psi", "label": "a", "values": [360]},
                                           {"path": "config.resolution.n_psi", "label": "b", "values": [720]}]},
     "variables[1].path", "sets config.resolution.n_psi, as variables[0].path does"),
    ("segment_field_for_every_aircraft_and_one", {"variables": [
        {"path": "mission.seg2.forward_speed_mps", "label": "v", "values": [40.0]},
        {"path": "mission.seg2.helicopter.forward_speed_mps", "label": "vh", "values": [45.0]}]},
     "variables[1].path", "sets mission.seg2.helicopter.forward_speed_mps, as variables[0].path does"),
    ("variable_and_link", {"variables": [OMEGAS, {"path": BLADES, "label": "b", "values": [4, 5]}],
                           "linked": [{"path": OMEGA, "follows": BLADES, "exponent": 1}]},
     "linked[0].path", f"sets {OMEGA}, as variables[0].path does; expected a field no variable or other link sets"),
    ("two_links", {"variables": [{"path": BLADES, "label": "b", "values": [4, 5]}],
                   "linked": [{"path": CHORD, "follows": BLADES, "exponent": -1}, {"path": CHORD, "follows": BLADES, "exponent": 1}]},
     "linked[1].path", f"sets {CHORD}, as linked[0].path does"),
    ("samples_without_kind", {"variables": [OMEGAS], "design": {"samples": 5}},
     "design.samples", "only a latin_hypercube uses it, the design kind is 'factorial' (the default)"),
    ("seed_with_one_at_a_time", {"variables": [OMEGAS], "design": {"kind": "one_at_a_time", "seed": 3}},
     "design.seed", "only a latin_hypercube uses it, the design kind is 'one_at_a_time'; expected kind: latin_hypercube"),
    ("hypercube_without_samples", {"variables": [OMEGAS], "design": {"kind": "latin_hypercube"}},
     "design.samples", "required with kind 'latin_hypercube'"),
    ("num_in_a_hypercube", {"variables": [{"path": OMEGA, "range": {"low": 24.0, "high": 30.0, "num": 4}}],
                            "design": {"kind": "latin_hypercube", "samples": 4}},
     "variables[0].range.num", "not used by a latin_hypercube, which samples the range"),
    ("integer_scaled_into_duplicates", {"variables": [{"path": BLADES, "scale": [1.0, 1.1]}]},
     "variables[0].scale", "gives [4, 4], 4 more than once (an integer field: the values are rounded); expected distinct values"),
    ("repeated_value", {"variables": [{"path": OMEGA, "values": [26.0, 26.0]}]},
     "variables[0].values", "gives [26.0, 26.0], 26.0 more than once"),
    ("integer_range_into_duplicates", {"variables": [{"path": BLADES, "range": {"low": 3, "high": 4, "num": 4}}]},
     "variables[0].range", "gives [3, 3, 4, 4], 3 more than once (an integer field"),
    ("fraction_for_an_integer_field", {"variables": [{"path": BLADES, "values": [3.5]}]},
     "variables[0].values[0]", f"expected integer, got float 3.5 for {BLADES}"),
    ("boolean_for_a_number", {"variables": [{"path": OMEGA, "values": [True]}]},
     "variables[0].values[0]", f"expected number, got bool True for {OMEGA}"),
    ("scale_of_text", {"variables": [{"path": f"{MAIN}.rotation", "scale": [1.0, 2.0]}]},
     "variables[0].scale", f"scale and range need a numeric field, {MAIN}.rotation is 'ccw'"),
    ("reserved_label", {"variables": [{"path": OMEGA, "label": "power_W", "values": [26.0]}]},
     "variables[0].label", "'power_W' is a trade-table column"),
    ("link_of_a_zero_base", {"variables": [{"path": DOWNLOAD, "label": "dl", "values": [0.05, 0.1]}],
                             "linked": [{"path": CHORD, "follows": DOWNLOAD, "exponent": 1}]},
     "linked[0].follows", "has the base value 0.0 and the values [0.05, 0.1]: expected numbers and a base value other than 0"),
    ("fractional_power_of_a_negative_ratio", {"variables": [{"path": TWIST, "label": "tw", "values": [-16.0, 4.0]}],
                                              "linked": [{"path": CHORD, "follows": TWIST, "exponent": 0.5}]},
     "linked[0].exponent", "(tw 4.0 / its base value -16.0)^0.5 has no real value"),
    ("negative_power_of_zero", {"variables": [{"path": TWIST, "label": "tw", "values": [-16.0, 0.0]}],
                                "linked": [{"path": CHORD, "follows": TWIST, "exponent": -1}]},
     "linked[0].exponent", "(tw 0.0 / its base value -16.0)^-1 divides by zero"),
    ("overflowing_power", {"variables": [{"path": OMEGA, "label": "w", "values": [56.0]}],
                           "linked": [{"path": CHORD, "follows": OMEGA, "exponent": 5000}]},
     "linked[0].exponent", "overflows"),
    ("link_of_an_integer_field", {"variables": [OMEGAS], "linked": [{"path": BLADES, "follows": OMEGA, "exponent": 1}]},
     "linked[0].path", f"{BLADES} is 4 (an integer field): expected a real-valued field"),
    ("link_of_text", {"variables": [OMEGAS], "linked": [{"path": f"{MAIN}.rotation", "follows": OMEGA, "exponent": 1}]},
     "linked[0].path", f"{MAIN}.rotation is 'ccw': expected a real-valued field"),
    ("link_following_text", {"variables": [{"path": "models.thickness", "label": "th", "values": ["compact_monopole"]}],
                             "linked": [{"path": CHORD, "follows": "models.thickness", "exponent": 1}]},
     "linked[0].follows", "expected numbers and a base value other than 0"),
    ("link_following_no_variable", {"variables": [OMEGAS], "linked": [{"path": CHORD, "follows": BLADES, "exponent": -1}]},
     "linked[0].follows", f"expected the path of a variable, got '{BLADES}'"),
    ("linked_value_the_schema_refuses", {"variables": [{"path": TWIST, "label": "tw", "values": [2.0]}],
                                         "linked": [{"path": CHORD, "follows": TWIST, "exponent": 1}]},
     "linked[0].path", f"{CHORD} = 0.58 × (2.0 / -16.0)^1 = -0.0725 at tw 2.0: expected a number > 0"),
    ("constraint_without_bounds", {"variables": [OMEGAS], "constraints": [{"name": "c", "terms": {OMEGA: 1}}]},
     "constraints[0]", "expected min or max (a constraint without bounds drops nothing)"),
    ("constraint_min_above_max", {"variables": [OMEGAS], "constraints": [{"name": "c", "terms": {OMEGA: 1}, "min": 3, "max": 2}]},
     "constraints[0].min", "expected min <= max, got min 3 and max 2"),
    ("constraint_term_of_two_aircraft", {"base": {"aircraft": ["helicopter", "coaxial"], "segments": ["seg2"]}, "variables": [OMEGAS],
                                         "constraints": [{"name": "c", "terms": {"mission.seg2.forward_speed_mps": 1}, "max": 50}]},
     "constraints[0].terms.mission.seg2.forward_speed_mps", "names 2 fields (mission.seg2.helicopter.forward_speed_mps, "
     "mission.seg2.coaxial.forward_speed_mps); expected one"),
    ("constraint_term_of_text", {"variables": [OMEGAS], "constraints": [{"name": "c", "terms": {f"{MAIN}.rotation": 1}, "max": 1}]},
     f"constraints[0].terms.{MAIN}.rotation", "takes 'ccw': expected a numeric field"),
    ("constraint_negative_power_of_zero", {"variables": [OMEGAS], "constraints": [{"name": "c", "terms": {DOWNLOAD: -1}, "max": 1}]},
     f"constraints[0].terms.{DOWNLOAD}", "to the power -1 divides by zero"),
    ("constraint_fractional_power_of_negative", {"variables": [OMEGAS], "constraints": [{"name": "c", "terms": {TWIST: 0.5}, "max": 1}]},
     f"constraints[0].terms.{TWIST}", "to the power 0.5 has no real value"),
    ("base_aircraft_unknown", {"base": {"aircraft": ["gyro"]}, "variables": [OMEGAS]},
     "base.aircraft[0]", "expected one of the aircraft of"),
    ("base_segment_unknown", {"base": {"aircraft": ["helicopter"], "segments": ["seg2", "seg9"]}, "variables": [OMEGAS]},
     "base.segments[1]", "expected one of the segments of"),
    ("base_config_missing", {"base": {"config": "config/nope.yaml"}, "variables": [OMEGAS]},
     "base.config", "expected a campaign configuration file"),
    ("mission_segment_not_run", {"variables": [{"path": "mission.seg5.forward_speed_mps", "values": [80.0]}]},
     "variables[0].path", "segment 'seg5' is not one of the campaign's segments (['seg2', 'seg3'])"),
    ("mission_aircraft_not_run", {"variables": [{"path": "mission.seg2.tandem.forward_speed_mps", "values": [40.0]}]},
     "variables[0].path", "aircraft 'tandem' is not in the campaign (['helicopter'])"),
    ("five_blades_at_72_azimuths", {"variables": [{"path": BLADES, "values": [4, 5]}, {"path": "resolution.n_psi", "values": [72]}]},
     "variables[0].values", "with resolution.n_psi 72 azimuth steps per revolution, expected a multiple of 5 (each of the 5 "
     "blades of helicopter rotor 'main' sits on the azimuth grid)"),
    ("azimuths_not_a_multiple", {"variables": [{"path": "resolution.n_psi", "values": [360, 250]}]},
     "variables[0].values", "250 azimuth steps per revolution, expected a multiple of 4"),
    ("seven_blades_in_a_hypercube", {"variables": [{"path": BLADES, "range": {"low": 3, "high": 7}}, {"path": OMEGA, "range": {"low": 24, "high": 30}}],
                                     "design": {"kind": "latin_hypercube", "samples": 10}},
     "variables[0].range", "expected a multiple of 7"),
    ("hypercube_repeating_designs", {"variables": [{"path": BLADES, "values": [3, 4]}], "design": {"kind": "latin_hypercube", "samples": 5}},
     "design.samples", "5 samples of seed 0 give 2 distinct designs"),
    ("factorial_above_the_cost_limit", {"variables": [{"path": OMEGA, "range": {"low": 24.0, "high": 30.0, "num": 100}},
                                                      {"path": f"{MAIN}.radius_m", "range": {"low": 7.0, "high": 8.0, "num": 100}}]},
     "variables", "10000 designs × 1 aircraft × 2 segments = 20000 cases, estimated"),
    # procedure studies (base.paths, products [procedure])
    ("path_field_without_base_paths", {"variables": [{"path": f"{DESCENT}.flight_path_deg", "values": [-9.0]}]},
     "variables[0].path", "expected paths.<path>.<field> of a path of base.paths ([])"),
    ("procedure_without_paths", {"variables": [OMEGAS], "products": ["procedure"]},
     "products", "a procedure study flies base.paths and has one row per design x path: expected products [procedure]"),
    ("paths_without_procedure", {"base": PROCEDURE_BASE, "variables": [OMEGAS]},
     "products", "got ['performance', 'noise'] and base.paths ['helicopter_approach_6deg']"),
    ("procedure_with_other_products", {"base": PROCEDURE_BASE, "variables": [OMEGAS], "products": ["procedure", "noise"]},
     "products", "expected products [procedure] with base.paths"),
    ("path_file_missing", {"base": {"aircraft": ["helicopter"], "paths": ["helicopter_nowhere"]}, "variables": [OMEGAS],
                           "products": ["procedure"]},
     "base.paths[0]", "expected a flight path of"),
    ("path_of_another_aircraft", {"base": {"aircraft": ["coaxial"], "paths": ["helicopter_approach_6deg"]},
                                  "variables": [{"path": "aircraft.coaxial.gross_weight_kg", "values": [2500.0]}],
                                  "products": ["procedure"]},
     "base.paths[0]", "flies 'helicopter': expected one of the study's aircraft ['coaxial']"),
    ("paths_with_other_microphones", {"base": {"aircraft": ["hexacopter", "helicopter"],
                                               "paths": ["helicopter_approach_6deg", "hexacopter_transition"]},
                                      "variables": [OMEGAS], "products": ["procedure"]},
     "base.paths", "name the microphones ['final', 'north', 'south', 'threshold', 'village'] and ['climb', 'cruise', "
     "'pad_side']: expected the same microphones"),
    ("path_value_the_schema_refuses", {**PROCEDURE, "variables": [{"path": f"{DESCENT}.flight_path_deg", "values": [-95.0]}]},
     "variables[0].values[0]", f"expected a number >= -89, got -95.0 for {DESCENT}.flight_path_deg"),
    ("path_field_not_written", {**PROCEDURE, "variables": [{"path": f"{DESCENT}.end_rotor_speed_fraction", "values": [0.9]}]},
     "variables[0].path", "no field 'end_rotor_speed_fraction'"),
    ("path_leg_beyond_the_legs", {**PROCEDURE, "variables": [{"path": "paths.helicopter_approach_6deg.legs.5.flight_path_deg",
                                                               "values": [-9.0]}]},
     "variables[0].path", "no field '5'"),
    ("procedure_column_as_label", {**PROCEDURE, "variables": [{"path": f"{DESCENT}.flight_path_deg", "label": "sel_village_db",
                                                                "values": [-9.0]}]},
     "variables[0].label", "'sel_village_db' is a trade-table column"),
    ("pareto_column_unknown", {**PROCEDURE, "variables": [{"path": f"{DESCENT}.flight_path_deg", "values": [-9.0]}],
                               "pareto": {"noise": "sel_nowhere_db"}},
     "pareto.noise", "expected a trade-table column of the study's products (distance_m, duration_s, energy_J, "),
    ("pareto_column_of_another_product", {"variables": [OMEGAS], "pareto": {"cost": "energy_J"}},
     "pareto.cost", "got 'energy_J'"),
]


def test_corpus_size():
    assert len(REFUSED) >= 30


@pytest.mark.parametrize("case, spec, field, expected", REFUSED, ids=[c[0] for c in REFUSED])
def test_refused_in_one_line_naming_file_and_field(root, case, spec, field, expected):
    message = refusal(root, spec)
    assert message.startswith(f"{root / 'config/studies/s.yaml'}: {field}: "), message
    assert expected in message, message


def test_procedure_variants_fly_their_own_paths(root):
    """A path field and a field linked to it set in each variant's path, which is validated and planned again:
    the 9 deg descent (its leg shortened as 1/γ to hold the height drop) passes other trim states than the 6 deg."""
    angle = f"{DESCENT}.flight_path_deg"
    path = write(root, **PROCEDURE, variables=[{"path": angle, "label": "descent.deg", "values": [-6.0, -9.0]}],
                 linked=[{"path": f"{DESCENT}.straight.distance_m", "follows": angle, "exponent": -1}])
    study = load_study(path, root)
    assert study.aircraft == ["helicopter"]
    six, nine = (d.campaign for d in study.designs)
    assert six.paths == study.base.paths
    descent = nine.paths["helicopter_approach_6deg"]["legs"][1]
    assert descent["flight_path_deg"] == -9.0 and descent["straight"]["distance_m"] == pytest.approx(1250.0 * 6.0 / 9.0)
    assert set(nine.path_keys["helicopter_approach_6deg"]) != set(six.path_keys["helicopter_approach_6deg"])


def test_procedure_variant_the_path_limits_refuse_names_variant_and_path_file(root):
    path = write(root, **PROCEDURE, variables=[{"path": f"{DESCENT}.flight_path_deg", "label": "descent.deg", "values": [-20.0]}])
    with pytest.raises(ConfigError) as error:
        load_study(path, root)
    message = str(error.value)
    assert message.startswith(f"{path}: variant {{'descent.deg': -20.0}}: "
                              f"{root / 'config/paths/helicopter_approach_6deg.yaml'}: legs[1]"), message
    assert "15" in message and "Traceback" not in message


def test_error_in_the_base_configuration_names_the_study_and_the_config(root):
    bad = yaml.safe_load((root / "config/config.yaml").read_text())
    bad["resolution"]["n_psi"] = 10
    (root / "config/bad.yaml").write_text(yaml.safe_dump(bad))
    message = refusal(root, {"base": {"config": "config/bad.yaml"}, "variables": [OMEGAS]})
    assert message.startswith(f"{root / 'config/studies/s.yaml'}: base.config: {root / 'config/bad.yaml'}: resolution.n_psi: "
                              "expected a number >= 36, got 10"), message


def test_resolution_of_the_call_against_the_blades_is_named(root):
    message = refusal(root, {"variables": [OMEGAS]}, resolution={"n_psi": 102})
    assert message.startswith(f"{root / 'config/studies/s.yaml'}: fidelity: the campaign resolution and the resolution "
                              "{'n_psi': 102} of the call:"), message
    assert "resolution.n_psi: 102 azimuth steps per revolution, expected a multiple of 4" in message


def test_error_of_an_extended_study_names_its_file(root):
    write(root, "parent", variables=[{"path": f"{MAIN}.omega_rad", "values": [26.0]}])
    path = root / "config/studies/child.yaml"
    path.write_text(yaml.safe_dump({"name": "child", "extends": "parent", "fidelity": "preview"}))
    with pytest.raises(ConfigError, match="^" + str(root / "config/studies/parent.yaml") + ": variables\\[0\\].path: no field"):
        load_study(path, root)


def test_hundred_thousand_samples_answer_with_size_and_cost_without_validating_a_variant(root, monkeypatch):
    """The size and cost come from the study file alone: the base campaign is validated (twice: as written and
    as the study runs it), no variant is."""
    calls = []
    real = designs.load_campaign
    monkeypatch.setattr(designs, "load_campaign", lambda *a, **k: calls.append(a) or real(*a, **k))
    spec = {"fidelity": "preview", "design": {"kind": "latin_hypercube", "samples": 100000, "seed": 1},
            "variables": [{"path": OMEGA, "range": {"low": 22.4, "high": 29.4}}, {"path": f"{MAIN}.radius_m", "range": {"low": 7.0, "high": 8.2}}]}
    message = refusal(root, spec)
    assert len(calls) == 2
    assert f"{root / 'config/studies/s.yaml'}: design.samples: 100000 designs × 1 aircraft × 2 segments = 200000 cases, " \
           "estimated " in message and "core-hours of jobs" in message and "above max_cost_core_h 10" in message, message


# ---- accepted studies: the designs they say ----

def test_size_and_cost_before_expansion_equal_the_expanded_study(root):
    path = write(root, variables=[OMEGAS, {"path": BLADES, "label": "b", "values": [3, 4, 5]}])
    plan = check_study(path, root)
    study = load_study(path, root)
    assert plan.n_points == len(study.designs) == 6 and plan.design_cost_s == study.design_cost_s > 0
    assert "6 designs × 1 aircraft × 2 segments = 12 cases, estimated" in study.describe()
    assert sorted((d.values["omega"], d.values["b"]) for d in study.designs) == [(w, b) for w in (26.0, 28.0) for b in (3, 4, 5)]


def test_raising_the_cost_limit_accepts_the_study(root):
    spec = {"variables": [OMEGAS, {"path": BLADES, "label": "b", "values": [3, 4]}]}
    assert "above max_cost_core_h 0.001" in refusal(root, {**spec, "max_cost_core_h": 0.001})
    assert len(load_study(write(root, **spec), root).designs) == 4


def test_one_at_a_time_counts_the_base_design_once(root):
    path = write(root, variables=[{"path": OMEGA, "label": "w", "values": [26.0, 28.0, 30.0]}, {"path": BLADES, "label": "b", "values": [4, 5]}],
                 design={"kind": "one_at_a_time"})
    study = load_study(path, root)
    assert check_study(path, root).n_points == len(study.designs) == 4
    assert [d.values for d in study.designs] == [{"w": 28.0, "b": 4}, {"w": 26.0, "b": 4}, {"w": 30.0, "b": 4}, {"w": 28.0, "b": 5}]


def test_hypercube_of_ranges_gives_its_samples_inside_the_ranges(root):
    path = write(root, variables=[{"path": OMEGA, "label": "w", "range": {"low": 24.0, "high": 30.0}},
                                  {"path": BLADES, "label": "b", "range": {"low": 3, "high": 6}}],
                 design={"kind": "latin_hypercube", "samples": 8, "seed": 2})
    study = load_study(path, root)
    values = pd.DataFrame([d.values for d in study.designs])
    assert len(values) == 8 and values["w"].between(24.0, 30.0).all() and set(values["b"]) <= {3, 4, 5, 6}
    assert all(isinstance(b, int) for b in values["b"])  # an integer field is rounded without integer: true


def test_integer_range_is_rounded_and_integral_floats_are_integers(root):
    study = load_study(write(root, variables=[{"path": BLADES, "label": "b", "range": {"low": 3, "high": 5, "num": 3}},
                                             {"path": "resolution.n_psi", "label": "n", "values": [360.0]}]), root)
    assert [d.values for d in study.designs] == [{"b": 3, "n": 360}, {"b": 4, "n": 360}, {"b": 5, "n": 360}]
    assert all(type(d.campaign.config["resolution"]["n_psi"]) is int for d in study.designs)


def test_link_scales_each_aircraft_from_its_own_base_value(root):
    path = write(root, base={"aircraft": ["helicopter", "coaxial"], "segments": ["seg1"]},
                 variables=[{"path": "mission.seg1.forward_speed_mps", "label": "v", "scale": [1.0, 1.1]}],
                 linked=[{"path": "mission.seg1.climb_speed_mps", "follows": "mission.seg1.forward_speed_mps", "exponent": 1}])
    fast = load_study(path, root).designs[1].campaign.segment("seg1")["aircraft"]
    assert fast["helicopter"]["forward_speed_mps"] == fast["coaxial"]["forward_speed_mps"] == pytest.approx(48.5 * 1.1)
    assert fast["helicopter"]["climb_speed_mps"] == pytest.approx(3.96 * 1.1)
    assert fast["coaxial"]["climb_speed_mps"] == pytest.approx(5.02 * 1.1)


def test_constraint_on_one_aircraft_sees_the_variable_of_every_aircraft(root):
    """The constraint names the helicopter's seg2 speed, the variable every aircraft's: it reads the variable."""
    path = write(root, variables=[{"path": "mission.seg2.forward_speed_mps", "label": "v", "values": [30.0, 40.5, 60.0]}],
                 constraints=[{"name": "slow", "terms": {"mission.seg2.helicopter.forward_speed_mps": 1}, "max": 50.0}])
    study = load_study(path, root)
    assert [d.values["v"] for d in study.designs] == [30.0, 40.5] and study.dropped == (({"v": 60.0}, "slow"),)


def test_extended_study_merges_a_mapping_key_by_key(root):
    write(root, "parent", variables=[{"path": OMEGA, "label": "w", "range": {"low": 24.0, "high": 30.0}}],
          design={"kind": "latin_hypercube", "samples": 4, "seed": 1})
    path = root / "config/studies/child.yaml"
    path.write_text(yaml.safe_dump({"name": "child", "extends": "parent", "design": {"samples": 6}}))
    study = load_study(path, root)
    assert study.spec["design"] == {"kind": "latin_hypercube", "samples": 6, "seed": 1} and len(study.designs) == 6


def test_boolean_variable_runs_through_the_trade_table(root):
    study = load_study(write(root, variables=[{"path": "models.bvi", "label": "bvi", "values": [True, False]}, OMEGAS]), root)
    assert sorted((d.values["bvi"], d.campaign.config["models"]["bvi"]) for d in study.designs) == [(False, False)] * 2 + [(True, True)] * 2
    rows = [pd.DataFrame([{"design": d.id, **d.values, "aircraft": "helicopter", "segment": "seg2", "segment_name": "s",
                           "max_dba_db": 80.0 + k, "max_oaspl_db": 90.0 + k, "max_bvispl_db": 70.0, "power_W": 1e6 + k}])
            for k, d in enumerate(study.designs)]
    _, sensitivity, _ = trade_tables(rows, [d.id for d in study.designs], {v.label: v.base_value for v in study.variables})
    assert set(sensitivity["variable"]) == {"omega"}  # a boolean has no relative change


def test_progress_is_reported_for_every_variant(root):
    seen = []
    study = load_study(write(root, variables=[OMEGAS]), root, progress=lambda done, total: seen.append((done, total)))
    assert seen == [(1, 2), (2, 2)] and len(study.designs) == 2


def test_unknown_design_id_is_named(root):
    study = load_study(write(root, variables=[OMEGAS]), root)
    with pytest.raises(KeyError, match="design 'd0000000000' is not one of the study's 2 designs"):
        study.design("d0000000000")


@pytest.fixture()
def fake_rows(monkeypatch):
    """nps.api.study.design_rows without the physics: one row per segment asked, the segments recorded."""
    asked = []

    def rows(campaign, aircraft, segments, values, observer_sets, products, cache):
        asked.append(list(segments))
        table = pd.DataFrame([{**values, "aircraft": aircraft, "segment": s, "segment_name": s, "max_dba_db": 80.0,
                               "max_oaspl_db": 90.0, "max_bvispl_db": 70.0, "power_W": 1e6} for s in segments])
        return table, None, None

    monkeypatch.setattr("nps.api.study.design_rows", rows)
    return asked


@pytest.mark.parametrize("segments, expected", [(["seg9"], "got ['seg9']"), ("seg7", "got ['seg7']"), ([], "got none"),
                                                (["seg2", "seg2"], "got one twice")])
def test_study_run_refuses_segments_it_does_not_have(root, fake_rows, segments, expected):
    study = Study.from_file(write(root, variables=[OMEGAS]), root, cache_dir=root / "cache")
    with pytest.raises(ConfigError) as error:
        study.run(segments=segments)
    message = str(error.value)
    assert message.startswith(f"{root / 'config/studies/s.yaml'}: Study.run(segments={segments!r}): expected one or more "
                              "of the study's segments ['seg2', 'seg3'], each once; ") and message.endswith(expected), message
    assert not fake_rows and not (root / "cache").exists()


def test_study_run_takes_one_segment_by_name(root, fake_rows):
    result = Study.from_file(write(root, variables=[OMEGAS]), root, cache_dir=root / "cache").run(segments="seg2")
    assert fake_rows == [["seg2"], ["seg2"]] and list(result.table["segment"]) == ["seg2", "seg2"]


# ---- rigs: the thrust axis given one way ----

BUNDLED_RIG = yaml.safe_load((REPO / "config/rigs/main_tail_rig.yaml").read_text())


def _rig(tmp_path: Path, **tail) -> Path:
    shutil.copytree(REPO / "config/rigs/main_tail", tmp_path / "main_tail")
    rig = copy.deepcopy(BUNDLED_RIG)
    rig["name"] = "axis_rig"
    rig["rotors"][1].pop("lateral_angle_deg")
    rig["rotors"][1].update(tail)
    path = tmp_path / "axis_rig.yaml"
    path.write_text(yaml.safe_dump(rig, sort_keys=False))
    return path


@pytest.mark.parametrize("angles", [{"lateral_angle_deg": 90.0}, {"shaft_angle_deg": 4.0},
                                    {"lateral_angle_deg": 0.0, "shaft_angle_deg": 0.0}])
def test_rig_axis_given_twice_is_refused(tmp_path, angles):
    path = _rig(tmp_path, thrust_axis_T=[0.0, 1.0, 0.0], **angles)
    with pytest.raises(ConfigError) as error:
        load_rig(path)
    message = str(error.value)
    assert message == (f"{path}: rotors[1].thrust_axis_T: given with {' and '.join(sorted(angles, reverse=True))}: expected "
                       "the axis one way, thrust_axis_T or the angles shaft_angle_deg and lateral_angle_deg (thrust_axis_T "
                       "would override them)"), message


def test_rig_axis_as_a_vector_is_used(tmp_path):
    rig = load_rig(_rig(tmp_path, thrust_axis_T=[0.0, 2.0, 0.0]))
    np.testing.assert_allclose(rotor_axis_test(rig["rotor_conditions"][1]), [0.0, 1.0, 0.0])


def test_rig_azimuths_not_a_multiple_of_the_blades_are_refused(tmp_path):
    path = _rig(tmp_path, lateral_angle_deg=90.0)
    rig = yaml.safe_load(path.read_text())
    rig["resolution"]["n_psi"] = 40  # the tail rotor has 3 blades
    path.write_text(yaml.safe_dump(rig, sort_keys=False))
    with pytest.raises(ConfigError, match=r"axis_rig.yaml: resolution.n_psi: 40 azimuth steps per revolution, expected a "
                                          r"multiple of 3 \(each of the 3 blades of the rig's rotor 'tail'"):
        load_rig(path)


# ---- through the workflow: snakemake -n study_NAME in a copy of config/ ----

def _dry_run(root: Path, name: str) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(root), "-n", "-j1", f"study_{name}"]
    return subprocess.run(command, capture_output=True, text=True, timeout=600)


@pytest.mark.parametrize("case", ["same_field_twice", "samples_without_kind", "five_blades_at_72_azimuths"])
def test_workflow_refuses_the_study_before_any_job(root, case):
    spec, field, expected = next((s, f, e) for c, s, f, e in REFUSED if c == case)
    write(root, "bad", **spec)
    result = _dry_run(root, "bad")
    lines = [line for line in result.stderr.splitlines() if line.startswith("NPS study configuration error:")]
    assert result.returncode != 0 and "Traceback" not in result.stderr, result.stderr[-3000:]
    assert len(lines) == 1 and lines[0].startswith(f"NPS study configuration error: config/studies/bad.yaml: {field}: "), lines
    assert expected in lines[0] and not (root / "results").exists()


def test_workflow_refuses_the_hundred_thousand_samples_with_size_and_cost(root):
    write(root, "big", fidelity="preview", design={"kind": "latin_hypercube", "samples": 100000},
          variables=[{"path": OMEGA, "range": {"low": 22.4, "high": 29.4}}])
    result = _dry_run(root, "big")
    assert result.returncode != 0 and "Traceback" not in result.stderr, result.stderr[-3000:]
    assert "NPS study configuration error: config/studies/big.yaml: design.samples: 100000 designs × 1 aircraft × 2 " \
           "segments = 200000 cases, estimated" in result.stderr and not (root / "results").exists()


def test_workflow_states_the_size_of_an_accepted_study(root):
    write(root, "pair", variables=[OMEGAS])
    result = _dry_run(root, "pair")
    assert result.returncode == 0, result.stderr[-3000:]
    assert "NPS study config/studies/pair.yaml: 2 designs × 1 aircraft × 2 segments = 4 cases, estimated" in result.stderr
    assert (result.stdout + result.stderr).count("rule case:") == 2
