"""Campaign wall time: the bundled study (config/) run from an empty results/ with `snakemake -j2 all`.

Copies config/ into a temporary working directory, runs the repository's Snakefile there (warm numba
cache: nps.core.jit's, shared with the package's commands and tests, unless --cold gives it an empty one),
then a second time (the no-op rerun), and prints both wall times and the per-rule table of
benchmarks/campaign_times.py.
``--study-only`` leaves out the products added after the chapter-7 study (mission footprint and
certification, tone tables), i.e. the campaign whose time issue 16 measured. ``--free-wake`` sets
``wake.model: free`` (free-vortex wakes with rotor–rotor interaction, issue 12). Prints the CPU time of
the two snakemake runs with their children next to the wall time (the machine is shared).

``--wake-threads N`` runs the wake jobs with N threads (the local profile gives them one).
``--without-job-server`` runs every job in its own process (``NPS_JOB_SERVER=off``), as before the job server
(nps.stages.jobserver), for a side-by-side comparison.

    python benchmarks/bench_campaign.py [--cold] [--study-only] [--free-wake] [--wake-threads N]
                                        [--without-job-server] [--keep DIR]
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

REPO = Path(__file__).resolve().parents[1]
from campaign_times import stage_table


def snakemake(workdir: Path, cache: Path | None, *args: str, job_server: bool = True) -> tuple[float, float]:
    """Run the repository's workflow in ``workdir`` with numba's cache in ``cache`` (None: nps.core.jit's default);
    (wall s, CPU s of snakemake and its jobs, the job server's included)."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache)) if cache else dict(os.environ)
    if not job_server:
        env["NPS_JOB_SERVER"] = "off"
    cpu0, started = os.times(), time.perf_counter()
    subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    cpu1 = os.times()
    return time.perf_counter() - started, (cpu1.children_user - cpu0.children_user) + (cpu1.children_system - cpu0.children_system)


def _min_s(seconds: float) -> str:
    minutes, rest = divmod(int(round(seconds)), 60)
    return f"{minutes} min {rest} s"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cold", action="store_true", help="empty numba cache (first run compiles every kernel)")
    ap.add_argument("--study-only", action="store_true", help="without footprint, certification and tone tables")
    ap.add_argument("--free-wake", action="store_true", help="wake.model: free (rotor-rotor interaction)")
    ap.add_argument("--wake-threads", type=int, help="threads of each wake job (default: the profile's)")
    ap.add_argument("--without-job-server", action="store_true", help="every job in its own process")
    ap.add_argument("--keep", type=Path, help="run in this directory and keep it")
    args = ap.parse_args(argv)
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="nps-campaign-"))
    shutil.rmtree(workdir / "results", ignore_errors=True)
    shutil.rmtree(workdir / ".snakemake", ignore_errors=True)
    shutil.copytree(REPO / "config", workdir / "config", dirs_exist_ok=True)
    config_path = workdir / "config" / "config.yaml"
    config = yaml.safe_load(config_path.read_text())
    if args.study_only:
        for section in ("footprint", "certification"):
            config.pop(section, None)
        config.setdefault("outputs", {})["tone_observer_sets"] = []
    if args.free_wake:
        config["wake"]["model"] = "free"
    config_path.write_text(yaml.safe_dump(config, sort_keys=False))
    cache = Path(tempfile.mkdtemp(prefix="nps-numba-")) if args.cold else None
    extra = ["--set-threads", f"wake={args.wake_threads}"] if args.wake_threads else []
    server = not args.without_job_server
    (full, cpu), (noop, _) = (snakemake(workdir, cache, "-j2", "all", *extra, job_server=server),
                              snakemake(workdir, cache, "-j2", "all", *extra, job_server=server))
    table = stage_table(workdir / "results")
    print(table.round(2).to_string())
    print(f"\n{int(table['jobs'].sum())} jobs ({'free' if args.free_wake else config['wake'].get('model', 'beddoes')} "
          f"wake, {'job server' if server else 'a process per job'}); campaign {_min_s(full)} wall, {_min_s(cpu)} CPU "
          f"({'cold' if args.cold else 'warm'} numba cache, load average {os.getloadavg()[0]:.1f} at the end); "
          f"no-op rerun {noop:.1f} s")
    if args.keep is None:
        shutil.rmtree(workdir)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
