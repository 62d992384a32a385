"""Campaign wall time: the bundled study (config/) run from an empty results/ with `snakemake -j2 all`.

Copies config/ into a temporary working directory, runs the repository's Snakefile there (warm numba
cache: the repository's .numba_cache, unless --cold gives it an empty one), then a second time (the
no-op rerun), and prints both wall times and the per-rule table of benchmarks/campaign_times.py.

    python benchmarks/bench_campaign.py [--cold] [--keep DIR]
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

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

from campaign_times import stage_table  # noqa: E402


def snakemake(workdir: Path, cache: Path, *args: str) -> float:
    """Run the repository's workflow in ``workdir``; wall seconds."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache))
    started = time.perf_counter()
    subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args],
                   check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - started


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cold", action="store_true", help="empty numba cache (first run compiles every kernel)")
    ap.add_argument("--keep", type=Path, help="run in this directory and keep it")
    args = ap.parse_args(argv)
    workdir = args.keep or Path(tempfile.mkdtemp(prefix="nps-campaign-"))
    shutil.rmtree(workdir / "results", ignore_errors=True)
    shutil.rmtree(workdir / ".snakemake", ignore_errors=True)
    shutil.copytree(REPO / "config", workdir / "config", dirs_exist_ok=True)
    cache = Path(tempfile.mkdtemp(prefix="nps-numba-")) if args.cold else REPO / ".numba_cache"
    full = snakemake(workdir, cache, "-j2", "all")
    noop = snakemake(workdir, cache, "-j2", "all")
    table = stage_table(workdir / "results")
    print(table.round(2).to_string())
    print(f"\n{int(table['jobs'].sum())} jobs; campaign {full / 60:.0f} min {full % 60:.0f} s "
          f"({'cold' if args.cold else 'warm'} numba cache); no-op rerun {noop:.1f} s")
    if args.keep is None:
        shutil.rmtree(workdir)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
