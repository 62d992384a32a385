"""Flight paths in the workflow (workflow/rules/path.smk): a path's trim states run the per-segment rules as
segments named by their keys, states shared between paths run once, and editing one path reruns only it."""

import re

import yaml

from campaigns import TINY
from test_campaign import REPO, _jobs, _snakemake

from nps.app.config import load_campaign, load_path


# the tiny campaign with the footprint section paths need (the source set and the ground)
TINY_PATHS = {**TINY, "footprint": {"source_set": "hemisphere", "grid": {"x_range_m": [0.0, 1000.0],
                                                                           "y_range_m": [-500.0, 500.0], "spacing_m": 250.0}}}


def _campaign_with_paths(workdir):
    import shutil

    shutil.copytree(REPO / "config", workdir / "config")
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(TINY_PATHS, sort_keys=False))
    campaign = load_campaign(TINY_PATHS, workdir / "config" / "config.yaml", root=workdir)
    paths = {p.stem: load_path(p, campaign.config["paths"]["dt_s"]) for p in sorted((workdir / "config/paths").glob("*.yaml"))}
    return campaign.with_paths({n: p for n, p in paths.items() if p["aircraft"] in campaign.aircraft})


def test_path_target_runs_each_state_as_a_segment_once(tmp_path):
    """`snakemake -n path_A path_B`: one path job per path, every state key of either path trimmed once (as segment
    <key> of the path's aircraft), and the footprint of each path reading its states' hemispheres."""
    campaign = _campaign_with_paths(tmp_path)
    names = ["helicopter_approach_6deg", "helicopter_approach_9deg"]
    assert all(name in campaign.paths for name in names), list(campaign.paths)
    result = _snakemake(tmp_path, "-n", *[f"path_{name}" for name in names])
    assert result.returncode == 0, result.stderr[-3000:]
    jobs = _jobs(result.stdout + result.stderr)
    trimmed = sorted(re.search(r"segment=(\w+)", w).group(1) for rule, w in jobs if rule == "trim")
    keys = sorted(set(campaign.path_keys[names[0]]) | set(campaign.path_keys[names[1]]))
    assert trimmed == keys  # shared states (the level flight at 25.8 m/s) once
    assert len(keys) < len(campaign.path_keys[names[0]]) + len(campaign.path_keys[names[1]])
    assert sum(rule == "source_hemisphere" for rule, _ in jobs) == len(keys)
    assert sorted(w for rule, w in jobs if rule == "path") == sorted(f"wildcards: path={n}" for n in names)
    assert sum(rule == "path_footprint" for rule, _ in jobs) == 2
    assert not any(rule in ("footprint", "certification", "summary") for rule, _ in jobs)


def test_a_bad_path_file_stops_before_any_job(tmp_path):
    _campaign_with_paths(tmp_path)
    path = tmp_path / "config" / "paths" / "helicopter_approach_6deg.yaml"
    path.write_text(path.read_text().replace("village: [-1600.0, 0.0, 1.2]", "village: [-1600.0, 0.0, -1.2]"))
    result = _snakemake(tmp_path, "-n", "all")
    assert result.returncode != 0
    assert ("config/paths/helicopter_approach_6deg.yaml: receivers.microphones.village: expected a height z >= 0 "
            "above the ground, got -1.2") in result.stderr
    assert "Traceback" not in result.stderr
