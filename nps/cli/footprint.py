"""``python -m nps footprint``: ground footprint of an aircraft flying a mission's flight profile
(stage nps.stages.footprint).

Reads the mission (its ``profile``) and one source-hemisphere product per profile segment; writes the
grid metrics (L_Amax, SEL per leg and mission), the microphones' metrics and L_A/PNLT histories, the
60–80 dB contour areas (Parquet and CSV) and the SEL and L_Amax contour figures into ``--out-dir``.
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import fail, option, pairs, parser, plan, propagation_options, run_stage
from nps.app.config import ConfigError, load_mission


def main(argv: list[str]) -> int:
    ap = parser("footprint", __doc__)
    ap.add_argument("--mission", required=True, help="mission YAML with a profile")
    ap.add_argument("--aircraft", required=True, help="aircraft name (speeds in the mission)")
    ap.add_argument("--hemisphere", nargs="+", required=True, metavar="SEGMENT=PATH", help="source hemisphere per segment")
    for field in ("x_range_m", "y_range_m", "spacing_m", "height_m"):
        option(ap, f"--{field.replace('_', '-')}", f"footprint.grid.{field}")
    ap.add_argument("--microphone", nargs="*", metavar="NAME=X,Y,Z", help="named microphones (m, mission frame)")
    propagation_options(ap)
    ap.add_argument("--out-dir", required=True, help="directory of the footprint artifacts")
    args = ap.parse_args(argv)
    try:
        mission = load_mission(args.mission)
        hemis = {f"hemisphere_{k}": v for k, v in pairs(args.hemisphere, "--hemisphere").items()}
        mics = {k: [float(x) for x in v.split(",")] for k, v in pairs(args.microphone, "--microphone").items()}
        params = plan("footprint", ap, args, {}, {"footprint.microphones": mics, "models.absorption": not args.no_absorption},
                      mission=mission)
    except (ConfigError, ValueError) as error:
        return fail(str(error))
    out = Path(args.out_dir)
    outputs = {name: str(out / f"{name}.parquet") for name in ("grid", "microphones", "histories", "areas")}
    outputs.update(areas_csv=str(out / "areas.csv"), sel_figure=str(out / "sel.png"), lamax_figure=str(out / "lamax.png"))
    params["aircraft"] = args.aircraft
    return run_stage("footprint", hemis, outputs, params, args.debug, sources={"--mission": args.mission})
