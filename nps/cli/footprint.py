"""``python -m nps footprint``: ground footprint of an aircraft flying a mission's flight profile
(stage nps.stages.footprint).

Reads the mission (its ``profile``) and one source-hemisphere product per profile segment; writes the
grid metrics (L_Amax, SEL per leg and mission), the microphones' metrics and L_A/PNLT histories, the
60–80 dB contour areas (Parquet and CSV) and the SEL and L_Amax contour figures into ``--out-dir``.
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import default, fail, ground, ground_options, parser, run_stage
from nps.app.config import ConfigError, load_mission


def _pairs(items, option):
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name or not value:
            raise ConfigError(f"{option} expects NAME=VALUE, got {item!r}")
        out[name] = value
    return out


def main(argv: list[str]) -> int:
    ap = parser("footprint", __doc__)
    ap.add_argument("--mission", required=True, help="mission YAML with a profile")
    ap.add_argument("--aircraft", required=True, help="aircraft name (speeds in the mission)")
    ap.add_argument("--hemisphere", nargs="+", required=True, metavar="SEGMENT=PATH", help="source hemisphere per segment")
    ap.add_argument("--x-range-m", type=float, nargs=2, default=default("footprint.grid.x_range_m"))
    ap.add_argument("--y-range-m", type=float, nargs=2, default=default("footprint.grid.y_range_m"))
    ap.add_argument("--spacing-m", type=float, default=default("footprint.grid.spacing_m"))
    ap.add_argument("--height-m", type=float, default=default("footprint.grid.height_m"))
    ap.add_argument("--microphone", nargs="*", metavar="NAME=X,Y,Z", help="named microphones (m, mission frame)")
    ground_options(ap)
    ap.add_argument("--isa-delta-k", type=float, default=default("atmosphere.isa_delta_K"))
    ap.add_argument("--relative-humidity-pct", type=float, default=default("atmosphere.relative_humidity_pct"))
    ap.add_argument("--no-absorption", action="store_true", help="skip ISO 9613-1 air absorption")
    ap.add_argument("--out-dir", required=True, help="directory of the footprint artifacts")
    args = ap.parse_args(argv)
    try:
        mission = load_mission(args.mission)
        hemis = {f"hemisphere_{k}": v for k, v in _pairs(args.hemisphere, "--hemisphere").items()}
        mics = {k: [float(x) for x in v.split(",")] for k, v in _pairs(args.microphone, "--microphone").items()}
    except (ConfigError, ValueError) as error:
        return fail(str(error))
    out = Path(args.out_dir)
    outputs = {name: str(out / f"{name}.parquet") for name in ("grid", "microphones", "histories", "areas")}
    outputs.update(areas_csv=str(out / "areas.csv"), sel_figure=str(out / "sel.png"), lamax_figure=str(out / "lamax.png"))
    params = {"mission": mission, "aircraft": args.aircraft,
              "grid": {"x_range_m": args.x_range_m, "y_range_m": args.y_range_m, "spacing_m": args.spacing_m,
                       "height_m": args.height_m},
              "microphones": mics, "ground": ground(args), "ground_as_written": ground(args),
              "atmosphere": {"isa_delta_K": args.isa_delta_k, "relative_humidity_pct": args.relative_humidity_pct},
              "absorption": not args.no_absorption}
    return run_stage("footprint", hemis, outputs, params, args.debug, sources={"--mission": args.mission})
