"""Benchmark of the rotor BPM broadband (blade self-noise, nps.noise.broadband.rotor) as the metrics stage runs it.

The bundled campaign (config/) under ``models.broadband: auto`` gives BPM to the hexacopter's six rotors and the
helicopter's tail rotor. For one segment (default seg2) at the 360-observer hemisphere this times
``trimmed_rotor_broadband_msp``, the call nps.stages.metrics makes per BPM rotor, on the rotors' loads disk tables
(in a BVI segment the metrics stage reads the BVI loads, tables of the same shape). Prints wall (CPU) seconds per rotor
and per aircraft (best of --repeat runs, after one warm-up call that loads or compiles the kernels).

The inputs (trim, loads, observers) come from the stage functions through the stage cache
(nps.stages.case.StageCache), in a temporary directory or in ``--cache DIR`` (kept: a second run reuses them).
``--before REV`` also times the rotor BPM of the git revision REV (its ``nps`` package extracted with
``git archive`` and run in a subprocess on the same inputs; c30d6c6 is the code before the compiled rotation
average) and prints the speed-up and the largest difference of the band levels in dB. ``--threads N`` runs the
kernels on N threads (default numba's, the number of cores; a metrics job of the local workflow profile has one).
``--profile`` prints the cProfile of one rotor.

    python benchmarks/bench_bpm.py [--segment seg2] [--cache DIR] [--repeat 3] [--threads N] [--before c30d6c6]
                                   [--profile]
"""

from __future__ import annotations

import argparse
import cProfile
import os
import pickle
import pstats
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
AIRCRAFT = ("hexacopter", "helicopter")


def bpm_cases(segment: str, cache_dir: Path) -> list[dict]:
    """The BPM rotors of AIRCRAFT in ``segment``: aircraft, rotor, disk table, rotor configuration, trim row,
    observer positions (G, ascending ids) and the medium's c0 and ν, as the metrics stage reads them."""
    from nps.app.broadband import rotor_broadband_models
    from nps.app.config import load_campaign, read_yaml
    from nps.app.io import read_table, rotor_path
    from nps.app.plan import CaseConfig, stage_params
    from nps.core.atmosphere import isa
    from nps.noise.broadband.rotor import DISK_INPUT_COLUMNS, medium_from_atmosphere
    from nps.rotor.trim import trim_row
    from nps.stages.case import StageCache

    config = REPO / "config" / "config.yaml"
    campaign = load_campaign(read_yaml(config), config, root=REPO)
    cache = StageCache(cache_dir)
    cases = []
    for aircraft in AIRCRAFT:
        case = CaseConfig.from_campaign(campaign, aircraft, segment)
        same = {"aircraft": aircraft, "segment": segment}
        trim = cache.run("trim", {}, {**stage_params("trim", case), **same})
        loads = cache.run("loads", {"trim": (trim, "trim")}, {**stage_params("loads", case), **same})
        observers = cache.run("observers", {"trim": (trim, "trim")},
                              {**stage_params("observers", case, "hemisphere"), **same, "obsset": "hemisphere"})
        params = stage_params("metrics", case)
        trim_table = read_table(trim.paths["trim"])
        models = rotor_broadband_models(params["broadband"], trim_table, params["rotors"])
        table = read_table(observers.paths["observers"])
        positions = table.sort_values("observer", kind="mergesort")[["x_m", "y_m", "z_m"]].to_numpy(dtype=float)
        atm = params["atmosphere"]
        medium = medium_from_atmosphere(isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"]))
        for name in [name for name, model in models.items() if model == "bpm"]:
            cases.append({"aircraft": aircraft, "rotor": name,
                          "disk": read_table(rotor_path(loads.paths["loads"], name), required=DISK_INPUT_COLUMNS),
                          "rotor_config": params["rotor_configs"][name],
                          "trim_row": trim_row(trim_table, name, str(trim.paths["trim"])), "positions": positions,
                          "medium": (medium.speed_of_sound_mps, medium.kinematic_viscosity_m2_s)})
    return cases


def time_cases(cases: list[dict], repeat: int) -> tuple[list[tuple[float, float]], list[np.ndarray]]:
    """Best-of-``repeat`` (wall, CPU) seconds and band MSP (n_obs, n_band) of ``trimmed_rotor_broadband_msp`` per
    case, with the ``nps`` package found first on the path (the working tree's, or a revision's in the subprocess).
    The CPU time (all threads) is the steadier figure on a shared machine."""
    from nps.noise.broadband.bpm import Medium
    from nps.noise.broadband.rotor import trimmed_rotor_broadband_msp
    from nps.noise.metrics import STUDY_BANDS

    def run(case, positions):
        return trimmed_rotor_broadband_msp(case["disk"], case["rotor_config"], case["trim_row"], positions,
                                           Medium(*case["medium"]), STUDY_BANDS)

    run(cases[0], cases[0]["positions"][:1])  # load (or compile) the kernels
    seconds, results = [], []
    for case in cases:
        wall = cpu = np.inf
        for _ in range(repeat):
            start, start_cpu = time.perf_counter(), time.process_time()
            result = run(case, case["positions"])
            wall, cpu = min(wall, time.perf_counter() - start), min(cpu, time.process_time() - start_cpu)
        seconds.append((wall, cpu))
        results.append(result)
    return seconds, results


def time_revision(cases: list[dict], revision: str, repeat: int, threads: int,
                  workdir: Path) -> tuple[list[float], list[np.ndarray]]:
    """:func:`time_cases` run by the ``nps`` package of git ``revision`` (extracted into ``workdir``) on
    ``threads`` numba threads."""
    package = workdir / f"nps-{revision}"
    package.mkdir()
    archive = subprocess.run(["git", "-C", str(REPO), "archive", revision, "nps"], check=True, capture_output=True)
    subprocess.run(["tar", "-x", "-C", str(package)], input=archive.stdout, check=True)
    saved, answer = workdir / "cases.pkl", workdir / "before.pkl"
    saved.write_bytes(pickle.dumps(cases))
    env = dict(os.environ, PYTHONPATH=str(package), NUMBA_CACHE_DIR=str(workdir / "numba"),
               NUMBA_NUM_THREADS=str(threads))
    subprocess.run([sys.executable, __file__, "--run-saved", str(saved), str(answer), "--repeat", str(repeat)],
                   check=True, env=env, cwd=workdir)
    return pickle.loads(answer.read_bytes())


def report(cases: list[dict], seconds: list, results: list, revision: str | None, before: tuple | None) -> None:
    """Print per rotor and per aircraft the wall (CPU) seconds now and, with ``before`` (seconds, results of
    ``revision``), then, the speed-up of the wall time and the largest difference of the band levels (dB)."""
    def cell(wall_cpu) -> str:
        return f"{wall_cpu[0]:>9.3f} ({wall_cpu[1]:.3f})"

    print(f"{'aircraft':<12}{'rotor':<13}{'disk':>8}{'now':>18}"
          + (f"{revision:>18}{'speed-up':>10}{'max |dB|':>10}" if before else ""))
    for i, case in enumerate(cases):
        n_psi = case["disk"]["psi_rad"].nunique()
        disk = f"{n_psi}x{len(case['disk']) // n_psi}"
        line = f"{case['aircraft']:<12}{case['rotor']:<13}{disk:>8}{cell(seconds[i])}"
        if before:
            diff = np.max(np.abs(10.0 * np.log10(results[i] / before[1][i])))
            line += f"{cell(before[0][i])}{before[0][i][0] / seconds[i][0]:>9.1f}x{diff:>10.1e}"
        print(line)
    for aircraft in AIRCRAFT:
        rows = [i for i, case in enumerate(cases) if case["aircraft"] == aircraft]
        total = tuple(sum(seconds[i][j] for i in rows) for j in range(2))
        line = f"{aircraft:<12}{f'{len(rows)} rotor(s)':<13}{'':>8}{cell(total)}"
        if before:
            old = tuple(sum(before[0][i][j] for i in rows) for j in range(2))
            equal = all(np.array_equal(results[i], before[1][i]) for i in rows)
            line += f"{cell(old)}{old[0] / total[0]:>9.1f}x{'  bit-identical' if equal else ''}"
        print(line)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--segment", default="seg2", help="mission segment (default seg2)")
    ap.add_argument("--cache", type=Path, help="stage cache directory of the inputs (default: a temporary one)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per rotor, the best one counts (default 3)")
    ap.add_argument("--threads", type=int, help="numba threads of the kernels (default: numba's)")
    ap.add_argument("--before", metavar="REV", help="also time the rotor BPM of this git revision (e.g. c30d6c6)")
    ap.add_argument("--profile", action="store_true", help="print the cProfile of the first rotor")
    ap.add_argument("--run-saved", nargs=2, type=Path, help=argparse.SUPPRESS)  # the --before subprocess
    args = ap.parse_args(argv)
    if args.run_saved:
        saved, answer = args.run_saved
        answer.write_bytes(pickle.dumps(time_cases(pickle.loads(saved.read_bytes()), args.repeat)))
        return
    import numba

    if args.threads:
        numba.set_num_threads(args.threads)
    with tempfile.TemporaryDirectory(prefix="nps-bench-bpm-") as tmp:
        cases = bpm_cases(args.segment, args.cache or Path(tmp) / "cache")
        seconds, results = time_cases(cases, args.repeat)
        before = (time_revision(cases, args.before, args.repeat, numba.get_num_threads(), Path(tmp)) if args.before
                  else None)
    print(f"BPM broadband, {args.segment}, {len(cases[0]['positions'])} observers, {numba.get_num_threads()} numba "
          f"thread(s), best of {args.repeat}: wall (CPU) s")
    report(cases, seconds, results, args.before, before)
    if args.profile:
        from nps.noise.broadband.bpm import Medium
        from nps.noise.broadband.rotor import trimmed_rotor_broadband_msp
        from nps.noise.metrics import STUDY_BANDS

        case = cases[0]
        profile = cProfile.Profile()
        profile.runcall(trimmed_rotor_broadband_msp, case["disk"], case["rotor_config"], case["trim_row"],
                        case["positions"], Medium(*case["medium"]), STUDY_BANDS)
        pstats.Stats(profile).sort_stats("tottime").print_stats(12)


if __name__ == "__main__":
    main()
