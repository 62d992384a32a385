"""Lean job start-up (issue 36): a workflow job imports only what its stage runs. No stage module imports numba
(imported by the first kernel call, nps.core.jit) or matplotlib (the figure code imports it); the study's jobs
import no configuration code (the workflow validated the configuration once; the params carry it); a
kernel-free job runs to its end without numba. Fresh interpreters: this process has imported everything."""

import json
import os
import pickle
import subprocess
import sys
from pathlib import Path

from nps.stages import STAGES

REPO = Path(__file__).resolve().parents[2]
# the study's stages (workflow/rules/*.smk of a campaign, rigs and design studies aside)
STUDY_STAGES = ("trim", "loads", "wake", "observers", "acoustics", "hsi", "metrics", "tones", "rotor_figures",
                "hsi_figure", "study_maps", "rotor_maps", "bvi_hotspot", "summary", "results_summary",
                "source_hemisphere", "footprint", "certification")


def _fresh(code: str, *args: str) -> dict:
    """The JSON that ``code`` prints, run by a fresh interpreter on this repository's package."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, (str(REPO), os.environ.get("PYTHONPATH")))))
    done = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, cwd=REPO)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


IMPORTED = """
import importlib, json, sys
import nps.stages.job
for stage in sys.argv[1].split(","):
    importlib.import_module(f"nps.stages.{stage}")
print(json.dumps(sorted(m for m in sys.modules if m.split(".")[0] in ("numba", "matplotlib", "jsonschema", "yaml")
                        or m == "nps.app.config")))
"""


def test_no_stage_module_imports_numba_or_matplotlib():
    """Every stage's job path (nps.stages.job and the stage's module) leaves numba to the first kernel call and
    matplotlib to the figure code."""
    found = _fresh(IMPORTED, ",".join(STAGES))
    assert not [m for m in found if m.split(".")[0] in ("numba", "matplotlib")], found


def test_study_jobs_import_no_configuration_code():
    """The study's jobs read validated params: neither nps.app.config nor its YAML and JSON-schema libraries."""
    assert _fresh(IMPORTED, ",".join(STUDY_STAGES)) == []


JOB = """
import json, pickle, sys
inputs, outputs, params, log = pickle.loads(bytes.fromhex(sys.argv[1]))


class Named(dict):
    def __getitem__(self, key):
        return list(self.values())[key] if isinstance(key, int) else dict.__getitem__(self, key)


class Job:  # what workflow/scripts/stage.py gets from Snakemake
    rule, threads = "trim", 1
    input, output, params, wildcards, log = Named(inputs), Named(outputs), Named(params), Named(), Named(log=log)


from nps.stages.job import run_job

run_job(Job(), "trim")
print(json.dumps(sorted(m for m in sys.modules if m.split(".")[0] in ("numba", "matplotlib", "scipy", "jsonschema"))))
"""


def test_a_kernel_free_job_runs_to_its_end_without_numba(tmp_path, repo_root):
    """A trim job (linear airfoils: no kernel) through nps.stages.job imports neither numba nor scipy, and its log
    gives the start-up and work without a numba import; it writes what the stage writes in this process."""
    from nps.app.config import load_aircraft, load_mission
    from nps.stages import trim

    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    speeds = next(s for s in load_mission(repo_root / "config/missions/demo.yaml")["segments"] if s["id"] == "seg2")
    params = {"aircraft_config": aircraft, "speeds": speeds["aircraft"]["helicopter"], "segment": "seg2",
              "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}, "n_psi": 36,
              "n_r": 10}
    log = tmp_path / "trim.log"
    job = pickle.dumps(({}, {"trim": str(tmp_path / "job.parquet")}, {"job": params}, str(log))).hex()
    assert _fresh(JOB, job) == []
    *_, timing = log.read_text().splitlines()
    assert timing.startswith("timing: start-up ") and "numba" not in timing, timing
    trim.run({}, {"trim": tmp_path / "here.parquet"}, params)
    assert (tmp_path / "job.parquet").read_bytes() == (tmp_path / "here.parquet").read_bytes()
