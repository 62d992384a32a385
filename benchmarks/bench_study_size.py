"""Wall time of the answer to a study too large to run: a Latin hypercube of 100,000 samples of the helicopter's
main rotor (speed and radius) at the preview fidelity, in a fresh copy of config/.

The study is refused with its size and estimated cost (docs/reference/studies.md "Size and cost") before any
variant is validated; the script prints the answer and the time it takes, in this process after the imports
(``nps.app.designs.load_study``) and through ``snakemake -n study_big`` (start-up included), against the
target: < 2 s in the process.

    python benchmarks/bench_study_size.py
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

from nps.app.config import ConfigError
from nps.app.designs import load_study

REPO = Path(__file__).resolve().parents[1]
TARGET_S = 2.0
BIG = {
    "name": "big", "description": "100,000 designs of the helicopter's main rotor at the preview fidelity",
    "base": {"aircraft": ["helicopter"]}, "fidelity": "preview",
    "variables": [
        {"path": "aircraft.helicopter.rotors.main.omega_rad_s", "label": "main.omega_rad_s", "range": {"low": 22.4, "high": 29.4}},
        {"path": "aircraft.helicopter.rotors.main.radius_m", "label": "main.radius_m", "range": {"low": 7.0, "high": 8.2}},
    ],
    "design": {"kind": "latin_hypercube", "samples": 100000, "seed": 1},
}


def main() -> int:
    with tempfile.TemporaryDirectory() as directory:
        workdir = Path(directory)
        shutil.copytree(REPO / "config", workdir / "config", ignore=shutil.ignore_patterns("studies"))
        (workdir / "config" / "studies").mkdir()
        (workdir / "config" / "studies" / "big.yaml").write_text(yaml.safe_dump(BIG, sort_keys=False))
        start = time.perf_counter()
        try:
            load_study(workdir / "config" / "studies" / "big.yaml", workdir)
            answer = "accepted (expected a refusal)"
        except ConfigError as error:
            answer = str(error)
        in_process_s = time.perf_counter() - start
        start = time.perf_counter()
        result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), "-n",
                                 "study_big"], capture_output=True, text=True, timeout=600)
        workflow_s = time.perf_counter() - start
    print(answer)
    print(f"in the process: {in_process_s:.2f} s (target < {TARGET_S:.0f} s); snakemake -n study_big: {workflow_s:.1f} s, "
          f"exit {result.returncode}")
    return 0 if in_process_s < TARGET_S and result.returncode != 0 else 1


if __name__ == "__main__":
    sys.exit(main())
