"""Start-up of the workflow's jobs, per stage: what a Snakemake ``script:`` job spends before its stage works.

Each measurement is a fresh interpreter that does what a job of the stage does before the stage function is
entered: Snakemake's script preamble (unpickling the job's ``snakemake`` object, which imports Snakemake's
script support), then workflow/scripts/stage.py's path — ``nps.stages.job`` and the stage's module
(``nps.stages.stage_function``). Printed per stage, medians of ``--runs`` interpreters:

* ``import``: the job path's imports in the interpreter (``nps.stages.job`` and the stage's module),
* ``start-up``: process start to the stage function imported: the time to the stage's first line of work,
  which the job's log reports as ``start-up`` (interpreter, site, Snakemake's preamble, the imports),
* ``+ numba``: for the stages whose jobs run a numba kernel (:data:`KERNEL_STAGES`), the start-up plus the
  import of numba that the first kernel call makes (nps.core.jit; code that imports numba with the stage's
  module pays it in ``start-up`` already).

``--before DIR`` measures the tree ``DIR`` (a directory holding an ``nps`` package, e.g. ``git worktree add
/tmp/nps_head HEAD``) beside this repository's, runs interleaved, and prints both. ``--bytecode``
lets Python cache the modules' bytecode (in a temporary ``PYTHONPYCACHEPREFIX``, after one warm-up run):
with ``PYTHONDONTWRITEBYTECODE`` set, as on the project's shared machine, every job compiles the ``nps``
modules it imports.

    python benchmarks/bench_startup.py [--runs 5] [--stages trim,acoustics] [--before DIR] [--bytecode]
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
# the stages whose jobs call a numba kernel (the job log's "numba import"): F1A radiation (acoustics, radiate,
# wopwop_run), HSI, the wakes and BVI loads, BPM broadband (metrics and source_hemisphere with models.broadband
# bpm, or auto on a rotor outside Pegg's range), the ground propagation (footprint, certification), a design
# case's chain, and the airfoil-table lookups of rotors with C81 or polar tables (rig; trim and loads of such
# aircraft, none in the bundled campaign)
KERNEL_STAGES = ("wake", "acoustics", "hsi", "metrics", "source_hemisphere", "footprint", "certification", "radiate",
                 "rig", "case", "wopwop_run")
HEAVY = ("numba", "pandas", "pyarrow", "scipy", "matplotlib", "yaml", "jsonschema")
# reference rows: a job's interpreter and Snakemake's preamble alone, and with the libraries of every table job
PREAMBLE, FLOOR = "(interpreter and Snakemake preamble)", "(+ numpy, pandas, pyarrow.parquet)"

CHILD = f"""
import json, pickle, sys, time
blob, stage, kernel = pickle.loads(bytes.fromhex(sys.argv[1])), sys.argv[2], sys.argv[3] == "1"
sys.path.extend(blob["searchpaths"])  # Snakemake's script preamble
snakemake = pickle.loads(blob["snakemake"])
from snakemake.logging import logger
from snakemake.iocontainers import Snakemake
started = time.perf_counter()
if stage == {FLOOR!r}:
    import numpy, pandas, pyarrow.parquet
elif stage != {PREAMBLE!r}:
    from nps.stages.job import run_job  # workflow/scripts/stage.py
    from nps.stages import stage_function
    run = stage_function(stage)
ready, imported = time.time(), time.perf_counter() - started
heavy = sorted(m for m in sys.modules if m in {HEAVY!r})
numba_s = 0.0
if kernel:  # the first kernel call of the job
    import nps.core.jit as jit
    if hasattr(jit, "numba_module"):  # else numba came with the stage's module
        started = time.perf_counter()
        jit.numba_module()
        numba_s = time.perf_counter() - started
print(json.dumps({{"ready": ready, "import": imported, "numba": numba_s, "heavy": heavy}}))
"""


def job_blob(root: Path, stage: str) -> str:
    """The pickled ``snakemake`` object of a job of ``stage`` and the preamble's search paths (Snakemake's own and
    ``root``, the workflow's directory), hex-encoded for the child's command line."""
    from snakemake.iocontainers import InputFiles, Log, OutputFiles, Params, ResourceList, Snakemake, Wildcards

    job = Snakemake(InputFiles(["results/x/seg2/trim.parquet"]), OutputFiles(["results/x/seg2/out.parquet"]),
                    Params(fromdict={"code": "0" * 16, "job": {"aircraft": "x", "segment": "seg2"}}),
                    Wildcards(fromdict={"aircraft": "x", "segment": "seg2"}), 1, ResourceList(fromdict={"_cores": 1}),
                    Log(["results/logs/x.log"]), {}, stage, None, str(root / "workflow" / "scripts"))
    searchpaths = [str(Path(sys.modules["snakemake"].__file__).parents[1]), str(root)]
    return pickle.dumps({"snakemake": pickle.dumps(job, protocol=4), "searchpaths": searchpaths}).hex()


def environment(root: Path, pycache: str | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
    env.update(PYTHONPATH=str(root), MPLBACKEND="Agg", NUMBA_CACHE_DIR=str(Path(tempfile.gettempdir()) / "nps_bench_startup_numba"))
    if pycache:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = pycache
    return env


def measure(root: Path, stage: str, env: dict) -> dict:
    """One fresh interpreter running a job's start-up of ``stage`` from the tree ``root``."""
    blob = job_blob(root, stage)
    spawned = time.time()
    done = subprocess.run([sys.executable, "-c", CHILD, blob, stage, "1" if stage in KERNEL_STAGES else "0"],
                          cwd=tempfile.gettempdir(), env=env, capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"{root}: stage {stage}: {done.stderr.strip().splitlines()[-1]}")
    found = json.loads(done.stdout.strip().splitlines()[-1])
    return {"import": found["import"], "start_up": found["ready"] - spawned, "numba": found["numba"],
            "heavy": found["heavy"]}


def stages_of(root: Path) -> list[str]:
    out = subprocess.run([sys.executable, "-c", "from nps.stages import STAGES; print(' '.join(STAGES))"],
                         env=environment(root, None), cwd=tempfile.gettempdir(), capture_output=True, text=True, check=True)
    return out.stdout.split()


def median_row(runs: list[dict]) -> dict:
    return {key: statistics.median(r[key] for r in runs) for key in ("import", "start_up", "numba")} | {"heavy": runs[-1]["heavy"]}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=5, help="fresh interpreters per stage and tree (median)")
    ap.add_argument("--stages", help="comma-separated stages (default: every stage)")
    ap.add_argument("--before", type=Path, help="a tree with the code to compare with (e.g. a git worktree of HEAD)")
    ap.add_argument("--bytecode", action="store_true", help="cache bytecode (temporary PYTHONPYCACHEPREFIX)")
    args = ap.parse_args(argv)
    trees = {"after": REPO, **({"before": args.before.resolve()} if args.before else {})}
    stages = [PREAMBLE, FLOOR] + (args.stages.split(",") if args.stages else stages_of(REPO))
    with tempfile.TemporaryDirectory() as pycache:
        envs = {name: environment(root, pycache if args.bytecode else None) for name, root in trees.items()}
        if args.bytecode:  # one run to write the bytecode
            for name, root in trees.items():
                for stage in stages:
                    measure(root, stage, envs[name])
        runs: dict[tuple[str, str], list[dict]] = {}
        for _ in range(args.runs):
            for stage in stages:
                for name, root in trees.items():  # interleaved: the machine's load falls on both alike
                    runs.setdefault((name, stage), []).append(measure(root, stage, envs[name]))
    load = os.getloadavg()[0]
    print(f"job start-up per stage, median of {args.runs} fresh interpreters, s; load average {load:.1f}; "
          f"bytecode {'cached' if args.bytecode else 'as the environment has it'} "
          f"(PYTHONDONTWRITEBYTECODE={os.environ.get('PYTHONDONTWRITEBYTECODE', '')!s})")
    names = list(trees)[::-1]
    head = ["stage"] + [f"{col} {name}" for col in ("import", "start-up") for name in names] + ["+ numba after", "imported by the stage module (after)"]
    print("| " + " | ".join(head) + " |")
    print("|" + " --- |" * len(head))
    for stage in stages:
        rows = {name: median_row(runs[(name, stage)]) for name in names}
        after = rows["after"]
        cells = [stage] + [f"{rows[n]['import']:.2f}" for n in names] + [f"{rows[n]['start_up']:.2f}" for n in names]
        cells.append(f"{after['start_up'] + after['numba']:.2f}" if stage in KERNEL_STAGES else "")
        cells.append(" ".join(after["heavy"]))
        print("| " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
