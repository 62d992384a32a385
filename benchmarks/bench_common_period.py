"""Benchmark: free wake and BVI loads over the common period of rotors at different speeds (issue 26 target on
the 2-core machine: under 30 s each).

1. The bundled main + tail rotor rig (``config/rigs/main_tail_rig.yaml``, tail rotor at 5× the main rotor's
   speed) at the campaign resolution (``config/config.yaml`` ``resolution``: n_psi × n_r disk, wake age) with the
   free wake's defaults and ``common_period: true``: the set-up, loads and wake jobs through the Snakefile in a
   scratch directory; the wake job's time from its benchmark file (relaxation over the period, every rotor's
   loads over it, re-trim).
2. The helicopter in segment 3 (main rotor 4 blades, tail rotor at 116/28 = 29/7 of its speed: a common period
   of 7 main-rotor revolutions) at the campaign resolution: :func:`nps.wake.interaction.aircraft_bvi_loads`
   with ``FreeWakeModel(common_period=True)``, inputs as ``benchmarks/bench_freewake.py`` makes them; first call
   (numba cache load or compilation) and best of 2.

Prints the times, the common period, the relaxation iterations and each rotor's table size.
Run from the repository root: ``python benchmarks/bench_common_period.py [--skip-rig] [--skip-helicopter]``.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import yaml

from bench_freewake import segment_inputs
from nps.app.io import read_metadata
from nps.wake import free as freewake
from nps.wake import interaction

REPO = Path(__file__).resolve().parents[1]
RIG = "main_tail_rig"


def rig_wake_time() -> None:
    """Rig through the Snakefile at the campaign resolution; prints the wake job's benchmark row."""
    campaign = yaml.safe_load(open(REPO / "config" / "config.yaml"))["resolution"]
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        shutil.copytree(REPO / "config", work / "config")
        for path in (work / "config" / "rigs").glob("*.yaml"):
            if path.stem != RIG:
                path.unlink()
        rig_file = work / "config" / "rigs" / f"{RIG}.yaml"
        rig = yaml.safe_load(open(rig_file))
        rig["resolution"] = {**rig["resolution"], **{k: campaign[k] for k in ("n_psi", "n_r", "wake_revolutions")}}
        rig["wake"]["free"] = {"common_period": True}
        yaml.safe_dump(rig, open(rig_file, "w"), sort_keys=False)
        start = time.perf_counter()
        run = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(work), "-j2",
                              f"results/rigs/{RIG}/wake"], capture_output=True, text=True)
        if run.returncode:
            raise SystemExit(run.stderr[-3000:])
        total = time.perf_counter() - start
        bench = (work / "results" / "benchmarks" / "wake" / "rigs" / f"{RIG}.tsv").read_text().splitlines()
        wake_s = float(bench[1].split("\t")[0])
        log = (work / "results" / "logs" / "wake" / "rigs" / f"{RIG}.log").read_text().splitlines()
        period = [line for line in log if line.startswith("common period")]
        tables = {r: read_metadata(work / "results" / "rigs" / RIG / "bvi" / f"{r}.parquet").get("revolutions", 1)
                  for r in ("main", "tail")}
        print(f"{RIG} at n_psi {campaign['n_psi']} x n_r {campaign['n_r']}, {campaign['wake_revolutions']} wake "
              f"revolutions: wake job {wake_s:.1f} s (set-up + loads + wake {total:.1f} s); {'; '.join(period)}; "
              f"table revolutions {tables}")


def helicopter_time() -> None:
    inputs = segment_inputs("helicopter")
    model = freewake.FreeWakeModel(common_period=True)
    start = time.perf_counter()
    done = interaction.aircraft_bvi_loads(*inputs, model)
    first = time.perf_counter() - start
    best = []
    for _ in range(2):
        cpu0, start = os.times(), time.perf_counter()
        interaction.aircraft_bvi_loads(*inputs, model)
        cpu1 = os.times()
        best.append((time.perf_counter() - start, cpu1.user - cpu0.user + cpu1.system - cpu0.system))
    wall, cpu = min(best)
    timing = done.solution.timing
    rows = {name: len(result.disk) for name, result in done.results.items()}
    print(f"helicopter seg3, common period: first {first:.1f} s, best {wall:.1f} s wall ({cpu:.1f} s CPU); "
          f"{timing.periods[0].describe()}; {done.solution.iterations} iterations; disk rows {rows}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--skip-rig", action="store_true")
    ap.add_argument("--skip-helicopter", action="store_true")
    args = ap.parse_args(argv)
    print(f"numba threads: {numba.get_num_threads()}, load average {os.getloadavg()[0]:.1f}")
    if not args.skip_rig:
        rig_wake_time()
    if not args.skip_helicopter:
        helicopter_time()


if __name__ == "__main__":
    main()
