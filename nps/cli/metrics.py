"""``python -m nps metrics``: noise metrics and 1/3-octave bands of an aircraft at one observer set
(stage nps.stages.metrics), with the params the workflow plans for it (nps.app.plan: the aircraft file's rotors
and tone sum).

Reads the acoustics directory (and optionally the HSI directory) of every rotor, the observer table
and the trim artifact; writes the metrics table (one row per observer), the band table
(observer × source × band) and, with ``--figure``, the spectrum of the loudest observer. Broadband:
Pegg's method (default), BPM blade self-noise from the rotors' disk tables (``--broadband bpm --disks DIR``),
none, or per rotor BPM outside Pegg's data range and Pegg inside (``--broadband auto --disks DIR``).
"""

from __future__ import annotations

from nps.cli import command_rotors, fail, option, output_file, parser, plan, provenance, run_stage, signals_variant
from nps.app.broadband import BROADBAND_MODELS


def main(argv: list[str]) -> int:
    ap = parser("metrics", __doc__, validity=True)
    ap.add_argument("--aircraft", help="aircraft YAML (rotor solidities, tone sum); without it (a PSU-WOPWOP case's trim "
                                       "artifact) the rotors are the trim artifact's and --broadband must be none")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--observers", required=True, help="observers/{obsset}.parquet")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals")
    ap.add_argument("--hsi", help="HSI directory of the rotors' processed signals (used instead of --signals' totals)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    option(ap, "--altitude-m", "atmosphere.altitude_m")
    option(ap, "--isa-delta-k", "atmosphere.isa_delta_K")
    option(ap, "--relative-humidity-pct", "atmosphere.relative_humidity_pct")
    ap.add_argument("--no-absorption", action="store_true", help="skip ISO 9613-1 air absorption")
    option(ap, "--broadband", "models.broadband", choices=BROADBAND_MODELS,
           help="broadband source: Pegg's method, BPM blade self-noise (needs --disks), none, or auto: per rotor, "
                "BPM outside Pegg's data range and Pegg inside (needs --disks) (default %(default)s)")
    ap.add_argument("--disks", help="directory of the rotors' disk tables the signals were radiated from (BPM broadband)")
    option(ap, "--bvispl-harmonics", "acoustics.bvispl_harmonics", metavar=("FIRST", "LAST"))
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="metrics Parquet (one row per observer)")
    ap.add_argument("--bands-out", required=True, type=output_file(".parquet"), help="1/3-octave band Parquet")
    ap.add_argument("--figure", help="spectrum figure (PNG) of the loudest observer")
    args = ap.parse_args(argv)
    if args.broadband in ("bpm", "auto") and not args.disks:
        return fail(f"--broadband {args.broadband} needs --disks (the loads or bvi directory of the rotors' disk tables)")
    if not args.aircraft and args.broadband != "none":
        return fail(f"--broadband {args.broadband} needs --aircraft (the rotors' solidities and sections); without an "
                    "aircraft file use --broadband none")
    try:
        aircraft, rotors = command_rotors(args.aircraft, args.rotor, args.trim)
        params = plan("metrics", ap, args, aircraft, {"models.absorption": not args.no_absorption})
    except ValueError as error:  # a bad file or field (ConfigError), an unreadable trim artifact
        return fail(str(error))
    params.update(rotors=rotors or params["rotors"], aircraft=aircraft["name"], segment=provenance(args.trim, "segment"),
                  obsset=provenance(args.observers, "obsset"))
    params["variant"] = signals_variant(args.signals, params["rotors"][0])
    inputs = {"signals": args.signals, "trim": args.trim, "observers": args.observers, **({"hsi": args.hsi} if args.hsi else {}),
              **({"disks": args.disks} if args.disks else {})}
    outputs = {"metrics": args.out, "bands": args.bands_out, **({"figure": args.figure} if args.figure else {})}
    return run_stage("metrics", inputs, outputs, params, args.debug,
                     sources={"--aircraft": args.aircraft} if args.aircraft else None)
