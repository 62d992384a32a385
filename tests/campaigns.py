"""The tiny campaign of the end-to-end tests: two aircraft, two segments, coarse resolution; and how the tests run
a campaign through the repository's Snakefile (:func:`campaign_workdir`, :func:`snakemake`)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

TINY = {
    # 2 wake revolutions are short of the ~2.5 the seg3 descent needs (docs/reference/validity.md): run with the
    # switch, the warning recorded in the wake and BVI tables' metadata and in the summary CSV
    "campaign": {"mission": "demo", "aircraft": ["helicopter", "coaxial"], "segments": ["seg2", "seg3"],
                 "allow_outside_validity": True},
    "observer_sets": {
        "hemisphere": {"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 4, "n_azimuth": 8, "moving": True},
        "hsi": {"kind": "points_ahead", "radius_R": 10.0, "elevations_deg": [0.0, -26.0], "moving": True, "segments": ["seg2"]},
    },
    "resolution": {"n_psi": 72, "n_r": 16, "wake_revolutions": 2, "samples_per_rev": 256},
    "models": {"bvi": True, "hsi": True, "broadband": True, "absorption": True, "thickness": "dual_compact",
               "bvi_segments": ["seg3"]},
    "figures": {"disk_segments": ["seg3"], "map_segments": ["seg2", "seg3"], "bvi_map_segments": ["seg3"], "hsi_segments": ["seg2"]},
    "wake": {"A": 0.5, "B": 1.0, "C": 1.1, "D": 0.85, "core_radius_chords": 0.5, "core_growth": False},
    "acoustics": {"dual_compact_chord_fractions": [0.13, 0.87], "bvispl_harmonics": [7, 40]},
    "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0},
}


def tiny_manifest():
    """The committed content digests of the tiny campaign for this machine's CPU class (nps.app.digests):
    bit-identity holds within a class; a class without a manifest skips, naming how to make one."""
    import pytest

    from nps.app.digests import cpu_class, manifest_path

    path = manifest_path(Path(__file__).parent / "data" / "manifests", "tiny_campaign")
    if not path.is_file():
        pytest.skip(f"no tiny-campaign manifest for CPU class {cpu_class()}: make {path.name} with "
                    "`python -m nps.app.digests RESULTS_DIR` from the tiny campaign of the code before a change")
    return path


def campaign_workdir(workdir: Path, config: dict) -> Path:
    """``workdir`` with a copy of the repository's config/ whose config.yaml is ``config``: a campaign the
    Snakefile runs in ``workdir`` (:func:`snakemake`)."""
    import yaml

    shutil.copytree(REPO / "config", workdir / "config")
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    return workdir


def snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    """``snakemake`` of the repository's Snakefile in ``workdir`` (``-d``), output captured."""
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args]
    return subprocess.run(command, capture_output=True, text=True, timeout=1200)


def nps_command(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    """``python -m nps ARGS`` of the repository's package run in ``workdir``, output captured."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, (str(REPO), env.get("PYTHONPATH"))))
    return subprocess.run([sys.executable, "-m", "nps", *args], cwd=workdir, capture_output=True, text=True, env=env,
                          timeout=1200)
