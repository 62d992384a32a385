"""``python -m nps path``: the time history of a flight path (config/paths/NAME.yaml) and the quasi-static trim
states that cover it (stage nps.stages.path, docs/reference/paths.md), with the params the workflow would plan
(nps.app.plan). Writes ``path_history.parquet`` (one row per time step) and ``path_states.parquet`` (one row per
state and rotor: the state's key and fields and its trim table) into ``--out``.
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import fail, option, parser, plan, run_stage, trim_options
from nps.app.config import ConfigError, load_aircraft, load_path

TOLERANCES = ("advance_ratio", "flight_path_deg", "load_factor", "rotor_speed_fraction")


def main(argv: list[str]) -> int:
    ap = parser("path", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--path", required=True, help="flight-path YAML (config/paths/NAME.yaml)")
    option(ap, "--dt-s", "paths.dt_s")
    for name in TOLERANCES:
        option(ap, f"--tolerance-{name.replace('_', '-')}", f"paths.state_tolerances.{name}")
    trim_options(ap)
    ap.add_argument("--out", required=True, help="output directory (path_history.parquet, path_states.parquet)")
    args = ap.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        params = plan("path", ap, args, aircraft)
        path = load_path(args.path, params["paths"]["dt_s"])
        if path["aircraft"] != aircraft["name"]:
            raise ConfigError(f"{args.path}: aircraft: expected the aircraft of --aircraft '{aircraft['name']}', "
                              f"got '{path['aircraft']}'")
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], path_config=path)
    out = Path(args.out)
    outputs = {"history": str(out / "path_history.parquet"), "states": str(out / "path_states.parquet")}
    return run_stage("path", {}, outputs, params, args.debug, sources={"--aircraft": args.aircraft, "--path": args.path})
