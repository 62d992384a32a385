"""``python -m nps case``: the whole chain of one aircraft in one or more segments in one process, through the stage
cache (stage nps.stages.case): trim, loads, wake and BVI loads where the configuration asks, observers,
acoustics, HSI, metrics; writes a trade-table row per segment (performance and noise maxima)."""

from __future__ import annotations

import dataclasses

from nps.app.config import ConfigError
from nps.app.designs import campaign_for_files
from nps.cli import fail, output_file, parser, run_stage


def main(argv: list[str]) -> int:
    ap = parser("case", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--mission", required=True, help="mission YAML (config/missions/NAME.yaml)")
    ap.add_argument("--config", required=True, help="campaign configuration YAML (config/config.yaml): resolution, models, observer sets")
    ap.add_argument("--segment", action="append", dest="segments", required=True, help="segment id, e.g. seg3 (repeatable)")
    ap.add_argument("--observer-set", action="append", dest="observer_sets",
                    help="observer set whose maxima enter the row (repeatable; default hemisphere)")
    ap.add_argument("--cache", required=True, help="stage-cache directory (the workflow's: results/studies/cache)")
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="output Parquet (one row per segment)")
    args = ap.parse_args(argv)
    try:
        campaign = campaign_for_files(args.aircraft, args.mission, args.config)
    except ConfigError as error:
        return fail(str(error))
    missing = [s for s in args.segments if s not in campaign.segments]
    if missing:
        return fail(f"--segment: {missing} not in {args.mission} (segments {campaign.segments})")
    sets = args.observer_sets or ["hemisphere"]
    unknown = [s for s in sets if s not in campaign.config["observer_sets"]]
    if unknown:
        return fail(f"--observer-set: {unknown} not in {args.config} observer_sets ({list(campaign.config['observer_sets'])})")
    params = {"campaign": dataclasses.asdict(campaign), "aircraft": next(iter(campaign.aircraft)), "segments": args.segments,
              "design_values": {}, "observer_sets": sets, "products": ["performance", "noise"], "cache_dir": args.cache}
    return run_stage("case", {}, {"rows": args.out}, params, args.debug,
                     sources={"--aircraft": args.aircraft, "--mission": args.mission, "--config": args.config})
