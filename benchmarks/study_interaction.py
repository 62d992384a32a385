"""The study with rotor–rotor interaction next to the isolated-rotor study: the tables of docs/findings/study.md,
"With rotor–rotor interaction (`wake.model: free`)".

Reads two finished study campaigns — isolated Beddoes wakes (the default) and ``wake.model: free`` —
and prints, per aircraft × BVI segment, the hemisphere maxima of both (BVISPL with its hotspot,
OASPL, dBA; ``results/{aircraft}/summary.csv``) and, per rotor, what the free wake's interaction
summary says (``results/{aircraft}/{segment}/wake/interaction.parquet``): the rotor whose wake gives
the largest share of the rotor's ≥ 2/rev BVI increment, the mean ΔU_P that the other rotors' wakes
induce on it, and the thrust change they cause before the re-trim (nps.wake.interaction).

Without result directories it runs both campaigns first (benchmarks/bench_campaign.py --study-only,
with and without --free-wake; about 3 + 5 min on the 2-core machine) and prints their wall and CPU
times. ``--update docs/findings/study.md`` rewrites the tables between the markers
``<!-- interaction tables -->`` and ``<!-- end interaction tables -->``.

    python benchmarks/study_interaction.py [--beddoes RESULTS --free RESULTS] [--update docs/findings/study.md]
"""

from __future__ import annotations

import argparse
import re
import sys
import tempfile
from pathlib import Path

import pandas as pd

import bench_campaign

START, END = "<!-- interaction tables -->", "<!-- end interaction tables -->"
# What thesis chapter 7 reports for the BVI segments (isolated Beddoes wakes; its Figs. 7.10, 7.16,
# 7.27, 7.42 and text; azimuth and elevation in the map convention of docs/findings/study.md)
THESIS = {
    ("helicopter", "seg3"): "max BVISPL at (87°, −39°), advancing side",
    ("helicopter", "seg4"): "max BVISPL > 10 dB below seg3",
    ("tandem", "seg3"): "max at (223°, −26°), rear rotor dominates",
    ("tandem", "seg4"): "max 66 dB, no significant BVI",
    ("coaxial", "seg3"): "max at (78°, −64°)",
    ("coaxial", "seg4"): "max 57 dB, > 22 dB below seg3",
    ("hexacopter", "seg3"): "no significant BVI",
    ("hexacopter", "seg4"): "no significant BVI",
}


AIRCRAFT_ORDER = ("helicopter", "tandem", "coaxial", "hexacopter")  # as the study's tables


def _spot(row: pd.Series, label: str) -> str:
    return (f"{row[f'max_{label}_db']:.1f} ({row[f'max_{label}_azimuth_deg']:.0f}°, "
            f"{row[f'max_{label}_elevation_deg']:.0f}°)").replace("-", "−")


def _signed(value: float, digits: int) -> str:
    return f"{value:+.{digits}f}".replace("-", "−")


def _aircraft(results: Path) -> list[str]:
    """Aircraft with a summary.csv, in the study's order."""
    names = [p.parent.name for p in results.glob("*/summary.csv")]
    return sorted(names, key=lambda n: (AIRCRAFT_ORDER.index(n) if n in AIRCRAFT_ORDER else len(AIRCRAFT_ORDER), n))


def level_table(beddoes: Path, free: Path, segments: list[str]) -> str:
    """Markdown: per aircraft × segment, BVISPL, OASPL and dBA maxima (hotspot az, el), free | Beddoes,
    and the thesis' statement (:data:`THESIS`)."""
    lines = ["| aircraft | seg | BVISPL free | BVISPL Beddoes | Δ BVISPL | OASPL free / Beddoes | dBA free / Beddoes | thesis |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for aircraft in _aircraft(free):
        f = pd.read_csv(free / aircraft / "summary.csv").set_index("segment")
        b = pd.read_csv(beddoes / aircraft / "summary.csv").set_index("segment")
        for segment in segments:
            fr, br = f.loc[segment], b.loc[segment]
            lines.append(f"| {aircraft} | {segment[3:]} | {_spot(fr, 'bvispl')} | {_spot(br, 'bvispl')} | "
                         f"{_signed(fr['max_bvispl_db'] - br['max_bvispl_db'], 1)} | "
                         f"{fr['max_oaspl_db']:.1f} / {br['max_oaspl_db']:.1f} | "
                         f"{fr['max_dba_db']:.1f} / {br['max_dba_db']:.1f} | {THESIS.get((aircraft, segment), '–')} |")
    return "\n".join(lines)


def interaction_table(free: Path, segments: list[str]) -> str:
    """Markdown: per aircraft × segment × rotor, the dominant wake of its BVI increment (share), the
    own wake's share, the mean ΔU_P from the other rotors' wakes and the thrust change before the
    re-trim."""
    lines = ["| aircraft | seg | rotor | dominant wake (share) | own-wake share | mean ΔU_P from other wakes (m/s) | "
             "thrust change before re-trim |", "| --- | --- | --- | --- | --- | --- | --- |"]
    for aircraft in _aircraft(free):
        for segment in segments:
            table = pd.read_parquet(free / aircraft / segment / "wake" / "interaction.parquet")
            for rotor, rows in table.groupby("rotor", sort=False):
                dominant = rows[rows["dominant"]].iloc[0]
                own = rows[rows["source_rotor"] == rotor].iloc[0]
                others = rows[rows["source_rotor"] != rotor]
                lines.append(
                    f"| {aircraft} | {segment[3:]} | {rotor} | {dominant['source_rotor']} ({dominant['bvi_share']:.2f}) | "
                    f"{own['bvi_share']:.2f} | {_signed(others['mean_dup_mps'].sum(), 2)} | "
                    f"{_signed(100.0 * own['thrust_change_before_retrim'], 1)} %{' (re-trimmed)' if own['retrimmed'] else ''} |")
    return "\n".join(lines)


def _bvi_segments(results: Path) -> list[str]:
    """Segments that have a wake directory (models.bvi_segments of the campaign), in order."""
    return sorted({p.parent.parent.name for p in results.glob("*/*/wake/interaction.parquet")})


def _run(free_wake: bool, keep: Path) -> Path:
    bench_campaign.main(["--study-only", "--keep", str(keep)] + (["--free-wake"] if free_wake else []))
    return keep / "results"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--beddoes", type=Path, help="results/ of the default (Beddoes) study")
    ap.add_argument("--free", type=Path, help="results/ of the study with wake.model: free")
    ap.add_argument("--update", type=Path, help="rewrite the tables in this markdown file (docs/findings/study.md)")
    args = ap.parse_args(argv)
    if (args.beddoes is None) != (args.free is None):
        ap.error("give both --beddoes and --free, or neither (then both studies are run)")
    if args.beddoes is None:
        root = Path(tempfile.mkdtemp(prefix="nps-interaction-"))
        args.beddoes, args.free = _run(False, root / "beddoes"), _run(True, root / "free")
    segments = _bvi_segments(args.free)
    if not segments:
        raise SystemExit(f"{args.free}: no wake/interaction.parquet (not a wake.model: free study)")
    text = (f"{START}\n{level_table(args.beddoes, args.free, segments)}\n\n"
            f"{interaction_table(args.free, segments)}\n{END}")
    print(text)
    if args.update:
        doc = args.update.read_text()
        if START not in doc or END not in doc:
            raise SystemExit(f"{args.update}: markers {START} / {END} not found")
        args.update.write_text(re.sub(re.escape(START) + ".*?" + re.escape(END), lambda _: text, doc, flags=re.S))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
