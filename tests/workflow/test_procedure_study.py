"""End-to-end: a procedure study (config/studies with base.paths, products [procedure]) through the real Snakefile.

A temporary working directory holds config/ with the tiny campaign and the footprint section paths need, a short
decelerating path of the helicopter and a study of its end speed (two designs). The trade table has one row per
design × path with the duration of the closed form; the notebook API flying the same variant reuses every stage of
the study's cache (one answer on every entry path); a new value reruns only its design.
"""

from __future__ import annotations

import pytest
import yaml

from test_paths_workflow import TINY_PATHS
from test_studies import REPO, _case_jobs, _snakemake

from nps.api.path import FlightPathCase
from nps.app.io import read_table

PATH = {"name": "helicopter_short_approach", "description": "300 m decelerating from 30 m/s at 100 m",
        "aircraft": "helicopter", "start": {"position_m": [-600.0, 0.0], "height_m": 100.0, "heading_deg": 0.0, "speed_mps": 30.0},
        "legs": [{"straight": {"distance_m": 300.0}, "end_speed_mps": 26.0}],
        "receivers": {"grid": {"x_range_m": [-800.0, 200.0], "y_range_m": [-300.0, 300.0], "spacing_m": 100.0},
                      "microphones": {"below": [-450.0, 0.0, 1.2], "side": [-450.0, 200.0, 1.2]}}}
END_SPEED = "paths.helicopter_short_approach.legs.0.end_speed_mps"
STUDY = {"name": "procs", "base": {"aircraft": ["helicopter"], "paths": ["helicopter_short_approach"]},
         "variables": [{"path": END_SPEED, "label": "end.speed_mps", "values": [26.0, 22.0]}],
         "products": ["procedure"], "pareto": {"noise": "sel_below_db", "cost": "duration_s"}}


def _write(workdir, study):
    (workdir / "config" / "studies" / "procs.yaml").write_text(yaml.safe_dump(study, sort_keys=False))


def _workdir(workdir):
    import shutil

    shutil.copytree(REPO / "config", workdir / "config", ignore=shutil.ignore_patterns("studies"))
    (workdir / "config" / "studies").mkdir()
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(TINY_PATHS, sort_keys=False))
    (workdir / "config" / "paths" / "helicopter_short_approach.yaml").write_text(yaml.safe_dump(PATH, sort_keys=False))
    _write(workdir, STUDY)
    return workdir


def test_a_procedure_study_is_a_case_job_per_design_and_a_trade_table(tmp_path):
    result = _snakemake(_workdir(tmp_path), "-n", "study_procs")
    assert result.returncode == 0, result.stderr[-3000:]
    assert len(_case_jobs(result.stdout + result.stderr)) == 2
    assert "NPS study config/studies/procs.yaml: 2 designs × 1 paths = 2 procedures" in result.stderr


@pytest.fixture(scope="module")
def procedure_dir(tmp_path_factory):
    workdir = _workdir(tmp_path_factory.mktemp("procedures"))
    result = _snakemake(workdir, "-j2", "study_procs")
    assert result.returncode == 0, result.stderr[-4000:]
    return workdir


@pytest.mark.slow
def test_procedure_study_has_a_row_per_design_and_path(procedure_dir):
    """Duration of a straight leg at constant deceleration: T = 2 L / (V0 + V1); the energy between the
    slowest and fastest state's power over that time; the front of SEL below the path against duration."""
    table = read_table(procedure_dir / "results/studies/procs/trade.parquet")
    assert table["path"].tolist() == ["helicopter_short_approach"] * 2
    assert table["end.speed_mps"].tolist() == [26.0, 22.0]
    assert table["duration_s"].to_numpy() == pytest.approx([600.0 / 56.0, 600.0 / 52.0], rel=1e-12)
    assert table["distance_m"].to_numpy() == pytest.approx([300.0, 300.0], rel=1e-12)
    assert (table["energy_J"] > 0).all() and (table["n_states"] >= 2).all()
    assert {"sel_below_db", "sel_side_db", "lamax_below_db", "epnl_side_db", "max_sel_db"} <= set(table.columns)
    assert (table["sel_below_db"] > table["sel_side_db"]).all()  # under the track is closer
    assert table["pareto"].any()


@pytest.mark.slow
def test_the_notebook_api_flies_the_variant_from_the_study_cache(procedure_dir, tmp_path):
    """FlightPathCase of the 22 m/s variant written as a path file, under the same configuration and cache:
    every stage is reused and the microphones' SEL equal the study's row bit for bit."""
    variant = {**PATH, "legs": [{"straight": {"distance_m": 300.0}, "end_speed_mps": 22.0}]}
    path_file = tmp_path / "helicopter_short_approach.yaml"
    path_file.write_text(yaml.safe_dump(variant, sort_keys=False))
    case = FlightPathCase.from_files(procedure_dir / "config/aircraft/helicopter.yaml", path_file,
                                     procedure_dir / "config/config.yaml", procedure_dir / "config/missions/demo.yaml",
                                     cache_dir=procedure_dir / "results/studies/cache")
    result = case.run()
    assert {what for _, _, what, _ in result.log} == {"reused"}, result.log
    row = read_table(procedure_dir / "results/studies/procs/trade.parquet").iloc[1]
    sel = dict(zip(result.microphones["microphone"], result.microphones["sel_db"]))
    assert (sel["below"], sel["side"]) == (row["sel_below_db"], row["sel_side_db"])


@pytest.mark.slow
def test_a_new_value_reruns_only_its_design(procedure_dir):
    _write(procedure_dir, {**STUDY, "variables": [{"path": END_SPEED, "label": "end.speed_mps", "values": [26.0, 22.0, 18.0]}]})
    try:
        result = _snakemake(procedure_dir, "-n", "study_procs")
    finally:
        _write(procedure_dir, STUDY)
    assert result.returncode == 0, result.stderr[-3000:]
    assert len(_case_jobs(result.stdout + result.stderr)) == 1
