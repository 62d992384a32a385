"""``python -m nps path-footprint``: the noise of an aircraft flying a flight path (stage nps.stages.path_footprint).

Reads the path file (its receivers), the path's history (``path_history.parquet`` of ``python -m nps path``) and
one source-hemisphere product per trim state of the history (``--hemisphere KEY=PATH``, e.g. from
``python -m nps source-hemisphere`` for each state run as a segment); writes the grid metrics (L_Amax, SEL per leg
and path), the microphones' metrics and L_A/PNLT histories, the contour areas and the plan and history figures
into ``--out-dir``.
"""

from __future__ import annotations

from pathlib import Path

from nps.app.config import ConfigError, load_path
from nps.cli import fail, pairs, parser, plan, propagation_options, run_stage


def main(argv: list[str]) -> int:
    ap = parser("path_footprint", __doc__)
    ap.add_argument("--path", required=True, help="flight-path YAML (config/paths/NAME.yaml: its receivers)")
    ap.add_argument("--history", required=True, help="path_history.parquet of the path (python -m nps path)")
    ap.add_argument("--hemisphere", nargs="+", required=True, metavar="KEY=PATH",
                    help="source hemisphere of each trim state (key as in the history's state column)")
    propagation_options(ap)
    ap.add_argument("--out-dir", required=True, help="directory of the path's footprint artifacts")
    args = ap.parse_args(argv)
    try:
        path = load_path(args.path)
        inputs = {f"hemisphere_{k}": v for k, v in pairs(args.hemisphere, "--hemisphere").items()}
        params = plan("path_footprint", ap, args, {}, {"models.absorption": not args.no_absorption})
    except (ConfigError, ValueError) as error:
        return fail(str(error))
    inputs["history"] = args.history
    out = Path(args.out_dir)
    outputs = {name: str(out / f"{name}.parquet") for name in ("grid", "microphones", "histories", "areas")}
    outputs.update(plan_figure=str(out / "plan.png"), history_figure=str(out / "histories.png"))
    params.update(aircraft=path["aircraft"], path_config=path)
    return run_stage("path_footprint", inputs, outputs, params, args.debug,
                     sources={"--path": args.path, "--history": args.history})
