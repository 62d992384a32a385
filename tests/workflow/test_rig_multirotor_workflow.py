"""End-to-end: the bundled main + tail rotor rig (config/rigs/main_tail_rig.yaml) through the Snakefile: set-up
(two rows), loads, the free wake of both rotors over their common period (the tail rotor's loads over its five
turns in one main-rotor turn) with each rotor's own control in the re-trim, acoustics, metrics and the loads at its
stations (station_loads, base and bvi); a dry run of the rig targets."""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from nps.app.io import read_metadata, read_table

REPO = Path(__file__).resolve().parents[2]
RIG = "main_tail_rig"


def _snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args],
                          capture_output=True, text=True, timeout=900)


def _work(tmp_path: Path, keep=(RIG,)) -> Path:
    root = tmp_path / "work"
    shutil.copytree(REPO / "config", root / "config")
    for path in (root / "config" / "rigs").glob("*.yaml"):
        if path.stem not in keep:
            path.unlink()
    return root


def test_dry_run_lists_the_station_loads_jobs(tmp_path):
    """The rig's targets: metrics of the BVI variant and the station loads of both variants; a rig without
    stations_r_over_R (the HART-II baseline) keeps its targets (no station_loads job)."""
    root = _work(tmp_path, keep=(RIG, "hart_ii_bl"))
    dry = _snakemake(root, "-n", RIG)
    assert dry.returncode == 0, dry.stderr[-4000:]
    jobs = re.findall(r"^(?:localrule|rule) (\w+):", dry.stdout, flags=re.M)
    assert sorted(jobs) == sorted(["rig", "loads", "wake", "acoustics", "metrics", "station_loads", "station_loads", RIG])
    for variant in ("base", "bvi"):
        assert f"results/rigs/{RIG}/station_loads/{variant}.parquet" in dry.stdout
    other = _snakemake(root, "-n", "hart_ii_bl")
    assert other.returncode == 0 and "station_loads" not in other.stdout, other.stderr[-2000:]


def test_loads_only_rig_stops_before_the_acoustics_with_per_rotor_stations(tmp_path):
    """loads_only: the dry run lists the set-up, loads, wake (BVI loads) and station loads, no acoustics or metrics;
    the tail rotor's own stations_r_over_R go to the station_loads jobs' params, the main rotor keeps the rig's."""
    from nps.app.config import load_rig
    from nps.rig.case import station_params

    root = _work(tmp_path)
    path = root / "config" / "rigs" / f"{RIG}.yaml"
    text = path.read_text()
    old = "    pitch_deg: 6.0\n"
    assert old in text
    path.write_text(text.replace(old, old + "    stations_r_over_R: [0.5, 0.7]\n") + "loads_only: true\n")
    dry = _snakemake(root, "-n", RIG)
    assert dry.returncode == 0, dry.stderr[-4000:]
    jobs = re.findall(r"^(?:localrule|rule) (\w+):", dry.stdout, flags=re.M)
    assert sorted(jobs) == sorted(["rig", "loads", "wake", "station_loads", "station_loads", RIG])
    assert station_params(load_rig(path)) == {"stations": {"main": [0.75, 0.87], "tail": [0.5, 0.7]},
                                              "rotors": ["main", "tail"]}


@pytest.mark.slow  # ~80 s: the main + tail rig through snakemake; its stages run in tests/unit/test_rig_multirotor.py
def test_main_tail_rig_end_to_end(tmp_path):
    root = _work(tmp_path)
    result = _snakemake(root, "-j2", RIG)
    assert result.returncode == 0, result.stderr[-4000:]
    base = root / "results" / "rigs" / RIG
    trim = read_table(base / "trim.parquet")
    assert list(trim["rotor"]) == ["main", "tail"] and trim["omega_rad_s"].iloc[1] == 5 * trim["omega_rad_s"].iloc[0]
    summary = read_table(base / "wake" / "interaction.parquet")
    retrimmed = summary.groupby("rotor")["retrimmed"].first()
    assert not retrimmed["tail"]  # fixed pitch: its thrust is the answer, never re-trimmed
    # common period (wake.free.common_period): one main-rotor turn, five of the tail rotor
    assert read_metadata(base / "wake" / "interaction.parquet")["common_periods"] == [
        "common period 0.0628319 s: 'main' 1 rev, 'tail' 5 rev"]
    tail_meta = read_metadata(base / "bvi" / "tail.parquet")
    assert tail_meta["revolutions"] == 5 and "revolutions" not in read_metadata(base / "bvi" / "main.parquet")
    for variant, tail_turns in (("base", 1), ("bvi", 5)):
        table = read_table(base / "station_loads" / f"{variant}.parquet")
        assert list(table.columns) == ["rotor", "r_over_R", "psi_rad", "cn", "m2cn"]
        assert len(table) == 2 * 36 * (1 + tail_turns) and np.isfinite(table[["cn", "m2cn"]].to_numpy()).all()
        assert read_metadata(base / "station_loads" / f"{variant}.parquet")["stage"] == "station_loads"
    base_loads = read_table(base / "station_loads" / "base.parquet")
    bvi_loads = read_table(base / "station_loads" / "bvi.parquet")
    main_bvi = bvi_loads[bvi_loads["rotor"] == "main"]["m2cn"].to_numpy()
    assert not np.allclose(base_loads[base_loads["rotor"] == "main"]["m2cn"], main_bvi)  # the wakes change the loads
    # the tail rotor's loads over the period: each of its five turns differs from the others (the main rotor's
    # blades pass at 4/5 per tail turn), by far more than numerical noise, and far less than the loads themselves
    tail = bvi_loads[(bvi_loads["rotor"] == "tail") & (bvi_loads["r_over_R"] == 0.87)].sort_values("psi_rad")
    turns = tail["m2cn"].to_numpy().reshape(5, 36)
    spread = np.abs(turns - turns.mean(axis=0)).max(axis=1) / np.ptp(turns)
    assert np.all(spread > 1e-3) and np.all(spread < 0.2), spread
    metrics = read_table(base / "metrics" / "microphones_bvi.parquet")
    assert len(metrics) == 5 and np.isfinite(metrics["oaspl_db"]).all()
    for stage in ("station_loads",):
        assert (root / "results" / "logs" / stage / "rigs" / f"{RIG}_bvi.log").is_file()
        assert (root / "results" / "benchmarks" / stage / "rigs" / f"{RIG}_bvi.tsv").is_file()
