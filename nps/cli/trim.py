"""``python -m nps trim``: aircraft trim of one aircraft in one mission segment (stage nps.stages.trim), with the
params the workflow plans for it (nps.app.plan)."""

from __future__ import annotations

from nps.cli import fail, output_file, parser, plan, run_stage, trim_options
from nps.app.config import ConfigError, load_aircraft, load_mission


def main(argv: list[str]) -> int:
    ap = parser("trim", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--mission", required=True, help="mission YAML (config/missions/NAME.yaml)")
    ap.add_argument("--segment", required=True, help="segment id, e.g. seg3")
    trim_options(ap)
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="output Parquet (one row per rotor)")
    args = ap.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        mission = load_mission(args.mission)
        segment = next((s for s in mission["segments"] if s["id"] == args.segment), None)
        if segment is None:
            raise ConfigError(f"{args.mission}: segments: no segment '{args.segment}'")
        if aircraft["name"] not in segment["aircraft"]:
            raise ConfigError(f"{args.mission}: segments.{args.segment}.aircraft: no speeds for '{aircraft['name']}'")
        params = plan("trim", ap, args, aircraft, speeds=segment["aircraft"][aircraft["name"]])
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=args.segment)
    return run_stage("trim", {}, {"trim": args.out}, params, args.debug,
                     sources={"--aircraft": args.aircraft, "--mission": args.mission})
