"""``python -m nps certification``: EPNL of an aircraft in the take-off, overflight and approach
reference procedures of 14 CFR 36 Appendix H / ICAO Annex 16 Vol. I Chapter 8, the Chapter 8 limits
for its maximum mass and the margins (stage nps.stages.certification).

Reads the aircraft (maximum mass), the mission (V_y and climb angle from the take-off segment, V_H
from the fastest level segment) and the source hemisphere of each procedure's segment; writes the
summary (Parquet and CSV), the microphone metrics, the PNLT/L_A histories and two figures into
``--out-dir``.
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import fail, ground_options, option, parser, plan, run_stage
from nps.app.config import ConfigError, load_aircraft, load_mission


def main(argv: list[str]) -> int:
    ap = parser("certification", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (gross_weight_kg = maximum mass)")
    ap.add_argument("--mission", required=True, help="mission YAML (reference speeds)")
    for name in ("takeoff", "overflight", "approach"):
        option(ap, f"--{name}-segment", f"certification.segments.{name}", help=f"mission segment flown in the {name} procedure")
        ap.add_argument(f"--{name}-hemisphere", required=True, help=f"source hemisphere of the {name} segment")
    option(ap, "--vne-mps", "certification.vne_mps")
    option(ap, "--approach-min-speed-mps", "certification.approach_min_speed_mps")
    ground_options(ap)
    ap.add_argument("--no-absorption", action="store_true", help="skip ISO 9613-1 air absorption")
    ap.add_argument("--out-dir", required=True, help="directory of the certification artifacts")
    args = ap.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        mission = load_mission(args.mission)
        params = plan("certification", ap, args, aircraft, {"models.absorption": not args.no_absorption}, mission=mission)
    except ConfigError as error:
        return fail(str(error))
    procedures = ("takeoff", "overflight", "approach")
    inputs = {f"hemisphere_{p}": getattr(args, f"{p}_hemisphere") for p in procedures}
    out = Path(args.out_dir)
    outputs = {"summary": str(out / "certification.parquet"), "summary_csv": str(out / "certification.csv"),
               "microphones": str(out / "microphones.parquet"), "histories": str(out / "histories.parquet"),
               "pnlt_figure": str(out / "pnlt.png"), "table_figure": str(out / "certification.png")}
    params["aircraft"] = aircraft["name"]
    return run_stage("certification", inputs, outputs, params, args.debug,
                     sources={"--aircraft": args.aircraft, "--mission": args.mission})
