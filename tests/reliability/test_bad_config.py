"""Bad campaign configurations (issue 14): refused before the first job, in one line naming the file
and the field (with what was expected).

The workflow validates with ``nps.app.config.load_campaign`` (workflow/rules/common.smk); most cases call
it in process on an edited copy of config/config.yaml. Three cases run ``snakemake -n`` to show the
workflow's behaviour end to end: exit status 1, one ``NPS configuration error`` line, no traceback,
no ``results/``.
"""

from __future__ import annotations

import copy
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from nps.app.config import ConfigError, load_campaign

REPO = Path(__file__).resolve().parents[2]
BUNDLED = yaml.safe_load((REPO / "config/config.yaml").read_text())


def _set(path: str, value):
    """Edit: set the dotted ``path`` of the config (``None`` deletes the key)."""
    def edit(config):
        *parents, key = path.split(".")
        node = config
        for part in parents:
            node = node[part]
        if value is None:
            del node[key]
        else:
            node[key] = value
    return edit


def _add_set(name: str, spec: dict):
    def edit(config):
        config["observer_sets"][name] = spec
    return edit


CASES = {
    "observer_set_typo": (_set("observer_sets.hemisphere.n_azimut", 72), ("observer_sets.hemisphere.n_azimut", "n_azimuth")),
    "observer_set_missing_radius": (_set("observer_sets.hsi.radius_R", None), ("observer_sets.hsi.radius_R", "required")),
    "observer_set_n_elevation_1": (_set("observer_sets.hemisphere.n_elevation", 1), ("n_elevation", ">= 2")),
    "observer_set_field_of_another_kind": (_set("observer_sets.hsi.n_x", 3), ("observer_sets.hsi.n_x", "unknown key")),
    "observer_set_upper_case_name": (_add_set("Ground2", {"kind": "ground_grid", "height_below_m": 1.0, "x_range_m": [0, 1],
                                                         "y_range_m": [0, 1], "n_x": 2, "n_y": 2}),
                                     ("observer_sets.Ground2", "lower-case letter", "wildcards")),
    "observer_set_empty_elevations": (_set("observer_sets.hsi.elevations_deg", []), ("elevations_deg", "minimum 1")),
    "ground_range_reversed": (_set("observer_sets.ground.x_range_m", [300.0, -300.0]), ("ground.x_range_m", "low < high")),
    "empty_campaign_segments": (_set("campaign.segments", []), ("campaign.segments", "minimum 1")),
    "bvispl_harmonics_reversed": (_set("acoustics.bvispl_harmonics", [40, 7]), ("acoustics.bvispl_harmonics", "first < last")),
    "chord_fractions_equal": (_set("acoustics.dual_compact_chord_fractions", [0.5, 0.5]),
                              ("dual_compact_chord_fractions", "front < rear")),
    "switch_not_boolean": (_set("campaign.allow_outside_validity", "yes"), ("campaign.allow_outside_validity", "boolean")),
    "resolution_typo": (_set("resolution.n_phi", 360), ("resolution.n_phi", "unknown key")),
    # YAML 1.1 reads 5e7 (no dot) as text
    "samples_per_rev_5e7": (_set("resolution.samples_per_rev", yaml.safe_load("5e7")), ("resolution.samples_per_rev", "integer")),
    "segment_not_in_mission": (_set("campaign.segments", ["seg1", "seg9"]), ("campaign.segments[1]", "seg9")),
    "aircraft_file_missing": (_set("campaign.aircraft", ["helicopter", "gyrodyne"]), ("campaign.aircraft[1]", "gyrodyne")),
    "isa_delta_minus_300": (_set("atmosphere.isa_delta_K", -300.0), ("atmosphere.isa_delta_K", ">= -60")),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_campaign_error_is_one_line(name):
    edit, expect = CASES[name]
    config = copy.deepcopy(BUNDLED)
    edit(config)
    with pytest.raises(ConfigError) as error:
        load_campaign(config, "config/config.yaml", root=REPO)
    message = str(error.value)
    assert "\n" not in message and message.startswith("config/config.yaml: "), message
    for text in expect:
        assert text in message, (text, message)


def test_bundled_campaign_is_valid():
    assert load_campaign(copy.deepcopy(BUNDLED), "config/config.yaml", root=REPO).segments


def _dry_run(tmp_path: Path, config_text: str) -> subprocess.CompletedProcess:
    shutil.copytree(REPO / "config", tmp_path / "config")
    (tmp_path / "config/config.yaml").write_text(config_text)
    return subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(tmp_path), "-n", "all"],
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("name, text, expect", [
    ("yaml_syntax", (REPO / "config/config.yaml").read_text().replace("n_azimuth: 36", "n_azimuth: [36", 1),
     ("config/config.yaml: line ", "not valid YAML")),
    ("empty_segments", yaml.safe_dump({**BUNDLED, "campaign": {**BUNDLED["campaign"], "segments": []}}),
     ("config/config.yaml: campaign.segments:",)),
    ("observer_set_typo", yaml.safe_dump({**BUNDLED, "observer_sets": {
        **BUNDLED["observer_sets"], "hemisphere": {**BUNDLED["observer_sets"]["hemisphere"], "n_azimut": 72}}}),
     ("observer_sets.hemisphere.n_azimut",)),
], ids=["yaml_syntax", "empty_segments", "observer_set_typo"])
def test_workflow_stops_before_the_first_job(tmp_path, name, text, expect):
    result = _dry_run(tmp_path, text)
    errors = [line for line in result.stderr.splitlines() if line.startswith("NPS configuration error")]
    assert result.returncode != 0
    assert len(errors) == 1, result.stderr[-3000:]
    for fragment in expect:
        assert fragment in errors[0], (fragment, errors[0])
    assert "Traceback" not in result.stderr + result.stdout
    assert not (tmp_path / "results").exists()
