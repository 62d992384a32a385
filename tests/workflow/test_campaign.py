"""End-to-end: a tiny campaign through the real Snakefile, then rerun scope and no-op rerun.

The workflow runs from the repository's Snakefile with a temporary working directory holding
a copy of config/ (two aircraft, two segments, coarse resolution), so the numba cache of the
repository is reused.
"""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
import yaml

from campaigns import TINY, tiny_manifest

REPO = Path(__file__).resolve().parents[2]



def _snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=1200)


@pytest.fixture(scope="module")
def campaign_dir(tmp_path_factory):
    workdir = tmp_path_factory.mktemp("campaign")
    import shutil

    shutil.copytree(REPO / "config", workdir / "config")
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(TINY, sort_keys=False))
    result = _snakemake(workdir, "-j2", "all")
    assert result.returncode == 0, result.stderr[-4000:]
    return workdir


def _jobs(dry_run_output: str) -> list[tuple[str, str]]:
    """(rule, wildcards) of each job listed by a dry run."""
    jobs = []
    rule = None
    for line in dry_run_output.splitlines():
        match = re.match(r"^(?:localrule|rule) (\w+):", line.strip())
        if match:
            rule = match.group(1)
            jobs.append((rule, ""))
        elif line.strip().startswith("wildcards:") and jobs:
            jobs[-1] = (rule, line.strip())
    return jobs


def test_campaign_artifacts_are_finite(campaign_dir):
    artifacts = sorted((campaign_dir / "results").rglob("*.parquet"))
    assert artifacts, "no artifacts written"
    for path in artifacts:
        table = pq.read_table(path)
        for name in table.column_names:
            column = table.column(name).to_numpy()
            if column.dtype.kind == "f":
                assert np.isfinite(column).all(), f"{path}:{name}"


def test_campaign_reproduces_the_committed_manifest(campaign_dir):
    """Every artifact of the tiny campaign has the content digest recorded in tests/data/manifests (only a
    deliberate physics change may regenerate it); the seg3 wake and BVI tables carry their validity warning
    (2 wake revolutions, short of the descent's ~2.5), the helicopter's metrics its model-range warnings."""
    from nps.app.digests import compare, digests, read_manifest

    results = campaign_dir / "results"
    manifest = read_manifest(tiny_manifest())
    warned = sorted(n for n in manifest if b"nps.validity_warnings" in (pq.read_schema(results / n).metadata or {}))
    assert warned == sorted(n for n in manifest if re.fullmatch(r"\w+/seg3/(wake|bvi)/\w+\.parquet", n)), warned
    modelled = sorted(n for n in manifest if b"nps.model_warnings" in (pq.read_schema(results / n).metadata or {}))
    assert modelled and all(re.fullmatch(r"\w+/seg\d+/metrics/\w+\.parquet", n) for n in modelled), modelled
    assert any(n.startswith("helicopter/") for n in modelled), modelled
    problems = compare(digests(results), manifest)
    assert not problems, problems[:20]
    summary = (results / "helicopter/summary.csv").read_text()
    assert "rotor 'main': wake_revolutions = 2 is outside the validity limit" in summary


def test_failing_job_writes_its_error_into_its_log(tmp_path):
    """A job that fails on its input (a trim without a solution) leaves its error in its log: file (where
    Snakemake points the user), as one line without a traceback (an expected refusal, nps.stages.job)."""
    import shutil

    shutil.copytree(REPO / "config", tmp_path / "config")
    tiny = dict(TINY, campaign={"mission": "demo", "aircraft": ["helicopter"], "segments": ["seg2"]})
    (tmp_path / "config" / "config.yaml").write_text(yaml.safe_dump(tiny, sort_keys=False))
    aircraft = tmp_path / "config" / "aircraft" / "helicopter.yaml"
    aircraft.write_text(aircraft.read_text().replace("gross_weight_kg: ", "gross_weight_kg: 1.0e+9 #"))
    result = _snakemake(tmp_path, "-j1", "results/helicopter/seg2/trim.parquet")
    assert result.returncode != 0
    log = (tmp_path / "results/logs/trim/helicopter/seg2.log").read_text()
    assert "error: stage 'trim':" in log and "did not converge" in log and "Traceback" not in log


def test_second_run_does_nothing(campaign_dir):
    result = _snakemake(campaign_dir, "-n", "all")
    assert result.returncode == 0, result.stderr[-2000:]
    assert "Nothing to be done" in result.stdout + result.stderr


def _jobs_after_edit(campaign_dir: Path, relative: str, edit) -> list[tuple[str, str]]:
    """Jobs (rule, wildcards; without `all`) a dry run schedules after ``edit`` changed one YAML file of
    the campaign's config/; the file is restored afterwards."""
    path = campaign_dir / "config" / relative
    original = path.read_text()
    data = yaml.safe_load(original)
    edit(data)
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    try:
        result = _snakemake(campaign_dir, "-n", "all")
    finally:
        path.write_text(original)
    assert result.returncode == 0, result.stderr[-2000:]
    return [job for job in _jobs(result.stdout + result.stderr) if job[0] != "all"]


def test_changing_one_segment_reruns_only_that_segment(campaign_dir):
    def faster_seg3(mission):
        mission["segments"][2]["aircraft"]["helicopter"]["forward_speed_mps"] = 27.0
        mission["segments"][2]["aircraft"]["helicopter"].pop("flight_path_deg")

    jobs = _jobs_after_edit(campaign_dir, "missions/demo.yaml", faster_seg3)
    # per-segment jobs: only seg3's; aircraft-level study jobs (maps over segments, summary) and the campaign's
    # results summary read seg3 too
    aircraft_level = {"summary", "study_maps", "rotor_maps", "results_summary"}
    assert all("segment=seg3" in wildcards or rule in aircraft_level for rule, wildcards in jobs), jobs
    assert not any("segment=seg2" in wildcards for _, wildcards in jobs), jobs
    assert any(rule == "trim" for rule, _ in jobs), jobs


def test_changing_one_aircraft_reruns_only_that_aircraft(campaign_dir):
    def heavier_lock(aircraft):
        aircraft["rotors"][0]["lock_number"] = float(aircraft["rotors"][0]["lock_number"]) * 1.05

    jobs = _jobs_after_edit(campaign_dir, "aircraft/coaxial.yaml", heavier_lock)
    assert any(rule == "trim" for rule, _ in jobs), jobs
    assert all("aircraft=coaxial" in wildcards or rule == "results_summary" for rule, wildcards in jobs), jobs


def test_lint_reports_only_environment_findings():
    result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(REPO), "--lint"],
                            capture_output=True, text=True, timeout=300)
    findings = [line.strip() for line in (result.stdout + result.stderr).splitlines() if line.strip().startswith("* ")]
    unexpected = [f for f in findings if "conda environment or container" not in f]
    assert not unexpected, unexpected


def test_bad_configuration_stops_before_any_job(tmp_path):
    """A wrong aircraft file stops `snakemake` at once with the validator's message, no traceback."""
    import shutil

    shutil.copytree(REPO / "config", tmp_path / "config")
    aircraft = tmp_path / "config" / "aircraft" / "helicopter.yaml"
    aircraft.write_text(aircraft.read_text().replace("radius_m: 7.62 ", "radius_m: -7.62 "))
    result = _snakemake(tmp_path, "-n", "all")
    assert result.returncode != 0
    assert "config/aircraft/helicopter.yaml: rotors[0].radius_m: expected a number > 0, got -7.62" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "results").exists()


def test_report_opens_on_the_results_summary(campaign_dir):
    """The results summary holds every aircraft × segment with the levels of the summary tables, and the report's
    front page (the workflow description) inserts it and links the figures; the build reports no docutils error and
    the page holds no system message."""
    import json

    summary = pd.read_csv(campaign_dir / "results/results_summary.csv", keep_default_na=False)
    assert [tuple(p) for p in summary[["aircraft", "segment"]].to_numpy()] == [
        (a, s) for a in TINY["campaign"]["aircraft"] for s in TINY["campaign"]["segments"]]
    for aircraft, rows in summary.groupby("aircraft", sort=False):
        table = pq.read_table(campaign_dir / "results" / aircraft / "summary.parquet").to_pandas()
        for column in ("max_oaspl_db", "max_dba_db", "max_bvispl_db"):
            assert np.allclose(rows[column], table[column], rtol=1e-5, atol=0.0), (aircraft, column)
    result = _snakemake(campaign_dir, "--report", str(campaign_dir / "report.html"))
    assert result.returncode == 0, result.stderr[-2000:]
    page = (campaign_dir / "report.html").read_text()
    front = json.loads(re.search(r"workflow_desc\s*=\s*(\".*?\");\s*\n", page, re.S).group(1))
    assert "NPS results summary" in front and "6 deg descent (BVI)" in front
    assert "System Message" not in front and "ERROR/" not in result.stderr
    assert "showResultInfo('results/helicopter/seg3/figures/hotspot_bvi.png')" in front


def test_wopwop_roundtrip_example_on_the_campaign(campaign_dir, tmp_path, capsys):
    """The worked example examples/wopwop_roundtrip.py as its docstring runs it: the workflow exports the helicopter's
    seg3 BVI case (target results/…/wopwop/hemisphere_bvi), the example runs it with ``nps wopwop run`` and compares
    with the acoustics stage. Through PSU-WOPWOP's single-precision files the signals agree to ≤ 1e-5 of
    peak-to-peak (the float32 floor of tests/validation/test_wopwop_export_run.py; measured on the bundled
    campaign ≤ 3.8e-6)."""
    import importlib.util
    import shutil

    case = "results/helicopter/seg3/wopwop/hemisphere_bvi"
    result = _snakemake(campaign_dir, "-j1", case)
    assert result.returncode == 0, result.stderr[-2000:]
    base = tmp_path / "helicopter" / "seg3"  # a copy: the run's outputs stay out of the campaign's results
    for folder in ("wopwop", "acoustics"):
        shutil.copytree(campaign_dir / "results/helicopter/seg3" / folder / "hemisphere_bvi", base / folder / "hemisphere_bvi")
    spec = importlib.util.spec_from_file_location("wopwop_roundtrip", REPO / "examples" / "wopwop_roundtrip.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    table = example.main([str(base), "hemisphere_bvi"])
    assert sorted(set(table["rotor"])) == ["main", "tail"]
    assert (table["peak_to_peak_pa"] > 0.0).all()
    assert (table["max_error_over_p2p"] < 1e-5).all(), table
    assert "max_error_over_p2p" in capsys.readouterr().out
    assert (base / "wopwop_run" / "hemisphere_bvi" / "nps" / "signals" / "main.parquet").is_file()
