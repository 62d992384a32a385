"""``python -m nps observers``: one configured observer set of an aircraft in one segment (stage nps.stages.observers),
with the params the workflow plans for it (nps.app.plan).

Reads the trim artifact (hub positions in G at t = 0, aircraft velocity); the set's centre is the mean
hub of the lift rotors and its radii are in first-rotor radii (nps.noise.observers).
"""

from __future__ import annotations

from nps.cli import fail, output_file, parser, plan, provenance, run_stage
from nps.app.config import ConfigError, load_aircraft, load_observer_sets


def main(argv: list[str]) -> int:
    ap = parser("observers", __doc__, validity=True)
    ap.add_argument("--config", required=True, help="campaign config (config/config.yaml) holding observer_sets")
    ap.add_argument("--set", required=True, help="observer set name in observer_sets")
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--out", required=True, type=output_file(".parquet"),
                    help="observer table Parquet (results/.../observers/SET.parquet)")
    args = ap.parse_args(argv)
    try:
        sets = load_observer_sets(args.config)
        if args.set not in sets:
            raise ConfigError(f"{args.config}: observer_sets: no set named '{args.set}'; sets: {list(sets)}")
        aircraft = load_aircraft(args.aircraft)
        params = plan("observers", ap, args, aircraft, {"observer_sets": sets}, obsset=args.set)
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"), obsset=args.set)
    return run_stage("observers", {"trim": args.trim}, {"observers": args.out}, params, args.debug,
                     sources={"--config": args.config, "--aircraft": args.aircraft})
