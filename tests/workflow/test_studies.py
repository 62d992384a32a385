"""End-to-end: a two-variable design study through the real Snakefile (workflow/rules/designs.smk).

A temporary working directory holds a copy of config/ with the tiny campaign (tests/campaigns.py) and a
study of the helicopter: main-rotor speed × the seg3 flight speed (2 × 2 designs, segments seg2 and seg3).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pyarrow.parquet as pq
import pytest
import yaml

from campaigns import TINY
from nps.app.io import read_metadata

REPO = Path(__file__).resolve().parents[2]
STUDY = {"name": "pair", "base": {"aircraft": ["helicopter"]},
         "variables": [{"path": "aircraft.helicopter.rotors.main.omega_rad_s", "label": "omega", "values": [26.0, 28.0]},
                       {"path": "mission.seg3.forward_speed_mps", "label": "seg3_speed", "values": [25.7, 30.0]}]}
NOISE = ("max_oaspl_db", "max_dba_db", "max_bvispl_db")


def _snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=1200)


def _write_study(workdir: Path, study: dict) -> None:
    (workdir / "config" / "studies" / "pair.yaml").write_text(yaml.safe_dump(study, sort_keys=False))


@pytest.fixture(scope="module")
def study_dir(tmp_path_factory):
    workdir = tmp_path_factory.mktemp("study")
    shutil.copytree(REPO / "config", workdir / "config", ignore=shutil.ignore_patterns("studies"))
    (workdir / "config" / "studies").mkdir()
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(TINY, sort_keys=False))
    _write_study(workdir, STUDY)
    result = _snakemake(workdir, "-j2", "study_pair")
    assert result.returncode == 0, result.stderr[-4000:]
    return workdir


def _case_jobs(dry_run: str) -> list[str]:
    """Wildcards of the ``case`` jobs a dry run lists."""
    jobs, rule = [], None
    for line in dry_run.splitlines():
        match = re.match(r"^(?:localrule|rule) (\w+):", line.strip())
        if match:
            rule = match.group(1)
        elif rule == "case" and line.strip().startswith("wildcards:"):
            jobs.append(line.strip())
    return jobs


def test_study_expands_to_every_design_and_segment(study_dir):
    table = pd.read_parquet(study_dir / "results/studies/pair/trade.parquet")
    assert len(table) == 8 and table["design"].nunique() == 4
    assert sorted(set(zip(table["omega"], table["seg3_speed"]))) == [(26.0, 25.7), (26.0, 30.0), (28.0, 25.7), (28.0, 30.0)]
    assert set(table["segment"]) == {"seg2", "seg3"}
    assert (table["main_omega_rad_s"] == table["omega"]).all()


def test_a_variable_that_does_not_reach_a_stage_reuses_its_artifacts(study_dir):
    """seg2 does not read the seg3 speed: the two designs of each rotor speed share every seg2 stage job."""
    table = pd.read_parquet(study_dir / "results/studies/pair/trade.parquet")
    digests = {}
    for design, omega, speed in table[["design", "omega", "seg3_speed"]].drop_duplicates().itertuples(index=False):
        digests[(omega, speed)] = read_metadata(study_dir / f"results/studies/pair/{design}/helicopter.parquet")["stage_digests"]
    for omega in (26.0, 28.0):
        assert digests[(omega, 25.7)]["seg2"] == digests[(omega, 30.0)]["seg2"]
        assert digests[(omega, 25.7)]["seg3"]["trim"] != digests[(omega, 30.0)]["seg3"]["trim"]
    cache = study_dir / "results/studies/cache"
    assert len(list((cache / "trim").glob("*/.complete"))) == 6  # seg2: 2 speeds of the rotor, seg3: 4 designs
    seg2_rows = table[(table["segment"] == "seg2")].groupby("omega")[list(NOISE)].nunique()
    assert (seg2_rows == 1).all().all()


def test_new_values_rerun_only_the_new_designs(study_dir):
    study = {**STUDY, "variables": [STUDY["variables"][0], {**STUDY["variables"][1], "values": [25.7, 30.0, 33.0]}]}
    _write_study(study_dir, study)
    try:
        result = _snakemake(study_dir, "-n", "-j2", "study_pair")
        assert result.returncode == 0, result.stderr[-3000:]
        jobs = _case_jobs(result.stdout + result.stderr)
        old = set(pd.read_parquet(study_dir / "results/studies/pair/trade.parquet")["design"])
        assert len(jobs) == 2 and not any(d in job for job in jobs for d in old), jobs  # one job per new design
    finally:
        _write_study(study_dir, STUDY)


def test_trade_noise_columns_equal_the_campaign_summary(study_dir):
    """The base design (28 rad/s, seg3 at 25.7 m/s) is the tiny campaign's helicopter: its trade rows hold the
    campaign summary's hemisphere maxima, computed by the campaign's own rules."""
    result = _snakemake(study_dir, "-j2", "results/helicopter/summary.parquet")
    assert result.returncode == 0, result.stderr[-3000:]
    summary = pq.read_table(study_dir / "results/helicopter/summary.parquet").to_pandas().set_index("segment")
    table = pd.read_parquet(study_dir / "results/studies/pair/trade.parquet")
    base = table[(table["omega"] == 28.0) & (table["seg3_speed"] == 25.7)].set_index("segment")
    for segment in ("seg2", "seg3"):
        for column in NOISE:
            assert base.loc[segment, column] == summary.loc[segment, column], (segment, column)


def test_configfile_on_the_command_line_is_the_campaign(study_dir, tmp_path):
    other = {**TINY, "campaign": {**TINY["campaign"], "aircraft": ["coaxial"], "segments": ["seg2"]}}
    path = tmp_path / "other.yaml"
    path.write_text(yaml.safe_dump(other, sort_keys=False))
    result = _snakemake(study_dir, "-n", "-j2", "all", "--configfile", str(path))  # --configfile takes several files
    assert result.returncode == 0, result.stderr[-3000:]
    listed = result.stdout + result.stderr
    assert "aircraft=coaxial, segment=seg2" in listed and "aircraft=helicopter" not in listed and "segment=seg3" not in listed


def test_unknown_study_is_refused_before_any_job(study_dir):
    result = _snakemake(study_dir, "-n", "all", "--config", "study=nope")  # --config takes several pairs
    assert result.returncode != 0
    assert "study=nope" in result.stderr and "expected one of ['pair']" in result.stderr and "Traceback" not in result.stderr


def test_sensitivity_of_the_study_is_the_hand_computation_on_two_variants(study_dir):
    """seg2 does not see the seg3 speed: its rotor-speed sensitivity is the two-variant slope
    ΔL ln 1.1 / ln(28/26) of either speed's pair of designs."""
    import math

    table = pd.read_parquet(study_dir / "results/studies/pair/trade.parquet")
    sensitivity = pd.read_csv(study_dir / "results/studies/pair/sensitivity.csv")
    seg2 = table[(table["segment"] == "seg2") & (table["seg3_speed"] == 25.7)].set_index("omega")
    for metric in NOISE:
        hand = (seg2.loc[28.0, metric] - seg2.loc[26.0, metric]) * math.log(1.1) / math.log(28.0 / 26.0)
        found = sensitivity.query("segment == 'seg2' and variable == 'omega' and metric == @metric")["change_per_10pct"]
        assert float(found.iloc[0]) == pytest.approx(hand, rel=1e-5, abs=1e-9), metric
