"""``python -m nps trim``: aircraft trim of one aircraft in one mission segment (stage nps.stages.trim)."""

from __future__ import annotations

from nps.cli import default, fail, option_problem, parser, run_stage
from nps.app.config import ConfigError, load_aircraft, load_mission


def main(argv: list[str]) -> int:
    ap = parser("trim", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--mission", required=True, help="mission YAML (config/missions/NAME.yaml)")
    ap.add_argument("--segment", required=True, help="segment id, e.g. seg3")
    ap.add_argument("--altitude-m", type=float, default=default("atmosphere.altitude_m"))
    ap.add_argument("--isa-delta-k", type=float, default=default("atmosphere.isa_delta_K"))
    ap.add_argument("--relative-humidity-pct", type=float, default=default("atmosphere.relative_humidity_pct"))
    ap.add_argument("--n-psi", type=int, default=default("resolution.n_psi"),
                    help="azimuth stations of the loads solving rpm-controlled rotor speeds (default %(default)s)")
    ap.add_argument("--n-r", type=int, default=default("resolution.n_r"), help="radial stations (default %(default)s)")
    ap.add_argument("--out", required=True, help="output Parquet (one row per rotor)")
    args = ap.parse_args(argv)
    problem = option_problem({"--altitude-m": ("atmosphere.altitude_m", args.altitude_m),
                              "--isa-delta-k": ("atmosphere.isa_delta_K", args.isa_delta_k),
                              "--relative-humidity-pct": ("atmosphere.relative_humidity_pct", args.relative_humidity_pct)})
    if problem:
        return fail(problem)
    try:
        aircraft = load_aircraft(args.aircraft)
        mission = load_mission(args.mission)
    except ConfigError as error:
        return fail(str(error))
    segment = next((s for s in mission["segments"] if s["id"] == args.segment), None)
    if segment is None:
        return fail(f"{args.mission}: segments: no segment '{args.segment}'")
    if aircraft["name"] not in segment["aircraft"]:
        return fail(f"{args.mission}: segments.{args.segment}.aircraft: no speeds for '{aircraft['name']}'")
    atmosphere = {"altitude_m": args.altitude_m, "isa_delta_K": args.isa_delta_k,
                  "relative_humidity_pct": args.relative_humidity_pct}
    params = {"aircraft_config": aircraft, "speeds": segment["aircraft"][aircraft["name"]], "atmosphere": atmosphere,
              "segment": args.segment, "n_psi": args.n_psi, "n_r": args.n_r}
    return run_stage("trim", {}, {"trim": args.out}, params, args.debug,
                     args.allow_outside_validity, sources={"--aircraft": args.aircraft, "--mission": args.mission})
