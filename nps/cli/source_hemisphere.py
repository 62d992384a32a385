"""``python -m nps source_hemisphere``: the source-hemisphere product of an aircraft in one segment
(stage nps.stages.source_hemisphere), with the params the workflow plans for it (nps.app.plan: the aircraft
file's rotors and tone sum).

Reads the acoustics directory (and optionally the HSI directory) of a hemisphere observer set moving
with the aircraft, its observer table and the trim artifact; writes one row per observer × source ×
1/3-octave band (10 Hz–10 kHz), unabsorbed, referred to ``--reference-radius-R`` (default 10 R of the
first rotor) by spherical spreading; broadband as the metrics command (``--broadband``, ``--disks``). Schema: nps.mission.source_hemisphere.
"""

from __future__ import annotations

from nps.cli import fail, option, output_file, parser, plan, provenance, run_stage, signals_variant
from nps.app.broadband import BROADBAND_MODELS
from nps.app.config import ConfigError, load_aircraft


def main(argv: list[str]) -> int:
    ap = parser("source_hemisphere", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (rotor solidities, first-rotor radius, tone sum)")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--observers", required=True, help="observers/{obsset}.parquet of a moving hemisphere")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals at that set")
    ap.add_argument("--hsi", help="HSI directory (its tonal total replaces thickness + loading)")
    option(ap, "--broadband", "models.broadband", choices=BROADBAND_MODELS,
           help="broadband source: Pegg's method, BPM blade self-noise (needs --disks), none, or auto: per rotor, "
                "BPM outside Pegg's data range and Pegg inside (needs --disks) (default %(default)s)")
    ap.add_argument("--disks", help="directory of the rotors' disk tables the signals were radiated from (BPM broadband)")
    option(ap, "--reference-radius-R", "footprint.reference_radius_R", dest="reference_radius_R",
           help="reference radius of the levels, first-rotor radii (default %(default)s)")
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="source-hemisphere Parquet")
    args = ap.parse_args(argv)
    if args.broadband in ("bpm", "auto") and not args.disks:
        return fail(f"--broadband {args.broadband} needs --disks (the loads or bvi directory of the rotors' disk tables)")
    try:
        aircraft = load_aircraft(args.aircraft)
        params = plan("source_hemisphere", ap, args, aircraft)
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"),
                  obsset=provenance(args.observers, "obsset"), variant=signals_variant(args.signals, params["rotors"][0]))
    inputs = {"signals": args.signals, "trim": args.trim, "observers": args.observers, **({"hsi": args.hsi} if args.hsi else {}),
              **({"disks": args.disks} if args.disks else {})}
    return run_stage("source_hemisphere", inputs, {"hemisphere": args.out}, params, args.debug,
                     sources={"--aircraft": args.aircraft})
