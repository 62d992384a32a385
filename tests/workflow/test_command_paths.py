"""One aircraft, one answer on every path (issue 34): the per-stage commands (``python -m nps`` trim → loads →
observers → acoustics → metrics → tones) write the workflow's artifacts bit for bit, for the bundled hexacopter
(``tone_sum: incoherent``) and a coaxial whose rotors have non-zero blade phases (``phase_deg``).

The workflow runs a tiny campaign (tests/campaigns.py) of both aircraft in one segment; its results are moved
aside and the commands run the same chain in the same directory, on the same configuration files, into the same
paths (the artifacts' metadata records their inputs' paths), with the options a user gives for the campaign's
resolution and nothing else: every other option at its default is the campaign's (schema) default.
"""

import copy
from pathlib import Path

import pyarrow.parquet as pq
import pytest
import yaml

from campaigns import REPO, TINY, campaign_workdir, nps_command, snakemake
from nps.app.io import read_metadata

SEGMENT = "seg2"
AIRCRAFT = ("hexacopter", "coaxial")
PHASES_DEG = {"upper": 20.0, "lower": 50.0}  # the coaxial's blade phases
N_PSI, N_R, SAMPLES_PER_REV = 36, 10, 128
CONFIG = {**copy.deepcopy(TINY),
          "campaign": {"mission": "demo", "aircraft": list(AIRCRAFT), "segments": [SEGMENT]},
          "observer_sets": {"hemisphere": {"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 3, "n_azimuth": 6,
                                           "moving": True}},
          "resolution": {"n_psi": N_PSI, "n_r": N_R, "wake_revolutions": 2, "samples_per_rev": SAMPLES_PER_REV},
          "models": {"bvi": False, "hsi": False, "broadband": "pegg", "absorption": True, "thickness": "dual_compact"}}
SET = "hemisphere_base"  # observer set and load variant of the signals, metrics and tones


def _targets(aircraft: str) -> list[str]:
    base = f"results/{aircraft}/{SEGMENT}"
    return [f"{base}/metrics/{SET}.parquet", f"{base}/tones/{SET}.parquet"]


def _commands(aircraft: str) -> list[list[str]]:
    """The chain of commands of ``aircraft`` the workflow's jobs of :func:`_targets` run, as a user writes it."""
    plane, base = f"config/aircraft/{aircraft}.yaml", f"results/{aircraft}/{SEGMENT}"
    trim, observers, signals = f"{base}/trim.parquet", f"{base}/observers/hemisphere.parquet", f"{base}/acoustics/{SET}"
    resolution = ["--n-psi", str(N_PSI), "--n-r", str(N_R)]
    return [
        ["trim", "--aircraft", plane, "--mission", "config/missions/demo.yaml", "--segment", SEGMENT, *resolution,
         "--out", trim],
        ["loads", "--aircraft", plane, "--trim", trim, *resolution, "--out-dir", f"{base}/loads"],
        ["observers", "--config", "config/config.yaml", "--set", "hemisphere", "--aircraft", plane, "--trim", trim,
         "--out", observers],
        ["acoustics", "--aircraft", plane, "--disks", f"{base}/loads", "--trim", trim, "--observers", observers,
         "--samples-per-rev", str(SAMPLES_PER_REV), "--out-dir", signals],
        ["metrics", "--aircraft", plane, "--trim", trim, "--observers", observers, "--signals", signals,
         "--out", f"{base}/metrics/{SET}.parquet", "--bands-out", f"{base}/metrics/{SET}_bands.parquet",
         "--figure", f"{base}/metrics/{SET}_spectrum.png"],
        ["tones", "--aircraft", plane, "--trim", trim, "--signals", signals, "--out", f"{base}/tones/{SET}.parquet",
         "--csv", f"{base}/tones/{SET}_selected.csv", "--spectra-out", f"{base}/tones/{SET}_spectra.parquet"],
    ]


@pytest.fixture(scope="module")
def campaign(tmp_path_factory) -> Path:
    """The campaign directory: the workflow's artifacts in ``workflow/``, the commands' in ``results/``."""
    workdir = campaign_workdir(tmp_path_factory.mktemp("paths"), CONFIG)
    coaxial = workdir / "config" / "aircraft" / "coaxial.yaml"
    document = yaml.safe_load(coaxial.read_text())
    for rotor in document["rotors"]:
        rotor["phase_deg"] = PHASES_DEG[rotor["name"]]
    coaxial.write_text(yaml.safe_dump(document, sort_keys=False))
    result = snakemake(workdir, "-j2", *(t for a in AIRCRAFT for t in _targets(a)))
    assert result.returncode == 0, result.stderr[-4000:]
    (workdir / "results").rename(workdir / "workflow")
    for aircraft in AIRCRAFT:
        for command in _commands(aircraft):
            run = nps_command(workdir, *command)
            assert run.returncode == 0, (command, run.stderr[-2000:])
    return workdir


def _difference(workflow: Path, command: Path) -> str:
    """What differs between two Parquet artifacts: the data, or the metadata keys."""
    ours, theirs = pq.read_table(workflow), pq.read_table(command)
    if not ours.equals(theirs):
        return "data"
    a, b = ours.schema.metadata or {}, theirs.schema.metadata or {}
    return "metadata " + ", ".join(sorted(key.decode() for key in set(a) | set(b) if a.get(key) != b.get(key)))


@pytest.mark.parametrize("aircraft", AIRCRAFT)
def test_the_commands_write_the_workflows_artifacts_bit_for_bit(campaign, aircraft):
    """Every table (Parquet and CSV) of the chain: the same files, the same bytes (data and metadata)."""
    def tables(root: Path) -> list[str]:
        return sorted(str(p.relative_to(root)) for p in (root / aircraft).rglob("*") if p.suffix in (".parquet", ".csv"))

    workflow, commands = campaign / "workflow", campaign / "results"
    assert tables(workflow) == tables(commands)
    assert len(tables(workflow)) >= 10, tables(workflow)
    different = {name: _difference(workflow / name, commands / name) if name.endswith(".parquet") else "text"
                 for name in tables(workflow) if (workflow / name).read_bytes() != (commands / name).read_bytes()}
    assert not different, different


def test_the_paths_carry_the_blade_phases_and_the_incoherent_sum(campaign):
    """What the commands once dropped is in both paths' artifacts: the coaxial's phases in its signals, the
    hexacopter's incoherent sum (its bundled file's) in its metrics and tones."""
    assert yaml.safe_load((REPO / "config/aircraft/hexacopter.yaml").read_text())["tone_sum"] == "incoherent"
    for root in ("workflow", "results"):
        signals = campaign / root / "coaxial" / SEGMENT / "acoustics" / SET
        assert {name: read_metadata(signals / f"{name}.parquet")["phase_deg"] for name in PHASES_DEG} == PHASES_DEG
        hexacopter = campaign / root / "hexacopter" / SEGMENT
        for table in (f"metrics/{SET}.parquet", f"tones/{SET}.parquet"):
            assert read_metadata(hexacopter / table)["tone_sum"] == "incoherent", (root, table)
