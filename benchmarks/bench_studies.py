"""Wall time of design studies on this machine, 2 parallel jobs, warm numba cache, cold stage cache.

Each study runs with ``snakemake -j2 study_NAME`` in a fresh working directory holding a copy of config/
(so nothing is reused from an earlier run; the numba cache of the repository is), and the script prints the
elapsed time, the cases, the mean case cost (job wall time, its start-up, and the stage the case spends most
in, from the case logs) against the targets:

* the bundled example (config/studies/tip_speed_blades*.yaml, 18 designs × 6 segments = 108 cases) at the
  preview fidelity: < 4 min; at the campaign resolution: < 12 min;
* 100 designs × 6 segments at the preview fidelity (a seeded Latin hypercube of the main rotor's speed,
  radius and blade count): < 20 min.

    python benchmarks/bench_studies.py [preview campaign hundred]   (default: all three)
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

import pandas as pd
import yaml

from nps.app.designs import load_study

REPO = Path(__file__).resolve().parents[1]
HUNDRED = {
    "name": "hundred", "description": "100 designs of the helicopter's main rotor at the preview fidelity",
    "base": {"aircraft": ["helicopter"]}, "fidelity": "preview",
    "variables": [
        {"path": "aircraft.helicopter.rotors.main.omega_rad_s", "label": "main.omega_rad_s", "range": {"low": 22.4, "high": 29.4}},
        {"path": "aircraft.helicopter.rotors.main.radius_m", "label": "main.radius_m", "range": {"low": 7.0, "high": 8.2}},
        {"path": "aircraft.helicopter.rotors.main.n_blades", "label": "main.n_blades", "values": [3, 4, 5]},
    ],
    "design": {"kind": "latin_hypercube", "samples": 100, "seed": 1},
}
RUNS = {"preview": ("tip_speed_blades_preview", 4.0), "campaign": ("tip_speed_blades", 12.0), "hundred": ("hundred", 20.0)}


def case_costs(workdir: Path, study: str) -> tuple[int, float, float, dict]:
    """(jobs, mean job wall s, mean start-up s, mean seconds per job in each stage) from the case jobs' logs
    (one job per design × aircraft, every segment) and benchmark files."""
    walls = [float(p.read_text().splitlines()[-1].split("\t")[0])
             for p in (workdir / "results/benchmarks/case" / study).rglob("*.tsv")]
    stages, start_ups = defaultdict(float), []
    for log in (workdir / "results/logs/case" / study).rglob("*.log"):
        for line in log.read_text().splitlines():
            match = re.match(r"^\w+ (\w+)\s+[0-9a-f]{20} (computed|reused)\s+([0-9.]+) s$", line)
            if match:
                stages[match.group(1)] += float(match.group(3))
            elif line.startswith("timing: start-up "):
                start_ups.append(float(line.split()[2]))
    n = max(1, len(walls))
    return len(walls), sum(walls) / n, sum(start_ups) / max(1, len(start_ups)), {k: v / n for k, v in stages.items()}


def run(name: str) -> None:
    study, target_min = RUNS[name]
    with tempfile.TemporaryDirectory(prefix="nps_bench_") as tmp:
        workdir = Path(tmp)
        shutil.copytree(REPO / "config", workdir / "config", ignore=shutil.ignore_patterns("rigs"))
        (workdir / "config/rigs").mkdir()
        if name == "hundred":
            (workdir / "config/studies/hundred.yaml").write_text(yaml.safe_dump(HUNDRED, sort_keys=False))
        started = time.perf_counter()
        result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir),
                                 "-j2", f"study_{study}"], capture_output=True, text=True)
        elapsed_min = (time.perf_counter() - started) / 60.0
        if result.returncode != 0:
            raise SystemExit(result.stderr[-3000:])
        jobs, wall_s, start_up_s, stages = case_costs(workdir, study)
        segments = len(load_study(workdir / f"config/studies/{study}.yaml", workdir).segments)
        refused = len(pd.read_csv(workdir / f"results/studies/{study}/refused.csv"))
        dominant = ", ".join(f"{k} {v / segments:.2f} s" for k, v in sorted(stages.items(), key=lambda kv: -kv[1])[:4])
        verdict = "met" if elapsed_min < target_min else "NOT met"
        print(f"{name:9s} {study:26s} {jobs:4d} jobs x {segments} segments  {elapsed_min:6.2f} min (target < {target_min:g} min: "
              f"{verdict})  per case (design x aircraft x segment): {wall_s / segments:.2f} s of job time, start-up "
              f"{start_up_s / segments:.2f} s; stages: {dominant}; {refused} designs refused", flush=True)


if __name__ == "__main__":
    for run_name in sys.argv[1:] or list(RUNS):
        run(run_name)
