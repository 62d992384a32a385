"""Export an NPS case to PSU-WOPWOP, run the exported case with ``nps wopwop run``, compare with NPS's own signals.

With the bundled campaign's results (or any campaign's):

    snakemake -j2 results/helicopter/seg3/acoustics/hemisphere_bvi results/helicopter/seg3/wopwop/hemisphere_bvi
    python examples/wopwop_roundtrip.py results/helicopter/seg3 hemisphere_bvi

runs the exported case (``results/helicopter/seg3/wopwop/hemisphere_bvi``, a folder PSU-WOPWOP itself runs) with NPS's
F1A solver into ``results/helicopter/seg3/wopwop_run/hemisphere_bvi`` (PSU-WOPWOP's output files, and NPS's tables in
``nps/``) and prints, per rotor, the largest difference from the acoustics stage's signals over their peak-to-peak.
``--quick`` first makes those results in a temporary workflow at the tests' tiny resolution (about two minutes on
two cores) for the bundled helicopter in seg3 with BVI loads. The same from the command line:

    nps wopwop run results/helicopter/seg3/wopwop/hemisphere_bvi --out-dir out/roundtrip
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

REPO = Path(__file__).resolve().parents[1]


def compare(base: Path, name: str) -> pd.DataFrame:
    """Run ``base/wopwop/name`` and compare with ``base/acoustics/name``: one row per rotor and signal group, the
    largest |difference| over the acoustics stage's peak-to-peak."""
    from nps.app.io import read_table, rotor_path
    from nps.noise.signals import signal_arrays
    from nps.stages import wopwop_run

    out = base / "wopwop_run" / name
    print(wopwop_run.run({"case": base / "wopwop" / name}, {"out_dir": out}, {}))
    rows = []
    for table in sorted((out / "nps" / "signals").glob("*.parquet")):
        _, _, ref = signal_arrays(read_table(rotor_path(base / "acoustics" / name, table.stem)))
        _, _, got = signal_arrays(read_table(table))
        ref["total"], got["total"] = ref["loading"] + ref["thickness"], got["loading"] + got["thickness"]
        rows += [{"rotor": table.stem, "group": group, "peak_to_peak_pa": float(np.ptp(ref[group])),
                  "max_error_over_p2p": float(np.abs(ref[group] - got[group]).max() / np.ptp(ref[group]))}
                 for group in ("loading", "thickness", "total")]
    return pd.DataFrame(rows)


def quick_results(workdir: Path) -> Path:
    """The tiny campaign's helicopter seg3 acoustics and export (BVI loads, moving hemisphere) in ``workdir``."""
    import shutil

    import yaml

    sys.path.insert(0, str(REPO / "tests"))
    from campaigns import TINY

    shutil.copytree(REPO / "config", workdir / "config", dirs_exist_ok=True)
    config = {**TINY, "campaign": {**TINY["campaign"], "aircraft": ["helicopter"], "segments": ["seg3"]}}
    (workdir / "config" / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    base = "results/helicopter/seg3"
    command = [sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), "-j2",
               f"{base}/acoustics/hemisphere_bvi", f"{base}/wopwop/hemisphere_bvi"]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode:
        raise RuntimeError(done.stderr[-3000:])
    return workdir / base


def main(argv: list[str] | None = None) -> pd.DataFrame:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("base", nargs="?", help="results/{aircraft}/{segment} (or results/rigs/{rig})")
    ap.add_argument("name", nargs="?", default="hemisphere_bvi", help="{obsset}_{variant} (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="make the results first in a temporary tiny workflow")
    ap.add_argument("--workdir", help="working folder of --quick (default: a temporary one)")
    args = ap.parse_args(argv)
    if args.quick:
        workdir = Path(args.workdir or tempfile.mkdtemp(prefix="nps_wopwop_"))
        base = quick_results(workdir)
    elif args.base:
        base = Path(args.base)
    else:
        ap.error("give results/{aircraft}/{segment} or --quick")
    table = compare(base, args.name)
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    return table


if __name__ == "__main__":
    main()
