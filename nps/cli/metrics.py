"""``python -m nps metrics``: noise metrics and 1/3-octave bands of an aircraft at one observer set
(stage nps.stages.metrics).

Reads the acoustics directory (and optionally the HSI directory) of every rotor, the observer table
and the trim artifact; writes the metrics table (one row per observer), the band table
(observer × source × band) and, with ``--figure``, the spectrum of the loudest observer. Broadband:
Pegg's method (default), BPM blade self-noise from the rotors' disk tables (``--broadband bpm --disks DIR``),
none, or per rotor BPM outside Pegg's data range and Pegg inside (``--broadband auto --disks DIR``).
"""

from __future__ import annotations

from nps.cli import default, fail, option_problem, parser, provenance, run_stage, trim_rotors
from nps.app.config import BROADBAND_MODELS, ConfigError, load_aircraft
from nps.noise.metrics import rotor_solidities


def main(argv: list[str]) -> int:
    ap = parser("metrics", __doc__, validity=True)
    ap.add_argument("--aircraft", help="aircraft YAML (rotor solidities); without it (a PSU-WOPWOP case's trim artifact) "
                                       "the rotors are the trim artifact's and --broadband must be none")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--observers", required=True, help="observers/{obsset}.parquet")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals")
    ap.add_argument("--hsi", help="HSI directory of the rotors' processed signals (used instead of --signals' totals)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    ap.add_argument("--altitude-m", type=float, default=default("atmosphere.altitude_m"))
    ap.add_argument("--isa-delta-k", type=float, default=default("atmosphere.isa_delta_K"))
    ap.add_argument("--relative-humidity-pct", type=float, default=default("atmosphere.relative_humidity_pct"))
    ap.add_argument("--no-absorption", action="store_true", help="skip ISO 9613-1 air absorption")
    ap.add_argument("--broadband", choices=BROADBAND_MODELS, default=default("models.broadband"),
                    help="broadband source: Pegg's method, BPM blade self-noise (needs --disks), none, or auto: per rotor, "
                         "BPM outside Pegg's data range and Pegg inside (needs --disks) (default %(default)s)")
    ap.add_argument("--disks", help="directory of the rotors' disk tables the signals were radiated from (BPM broadband)")
    ap.add_argument("--bvispl-harmonics", type=int, nargs=2, default=default("acoustics.bvispl_harmonics"),
                    metavar=("FIRST", "LAST"))
    ap.add_argument("--out", required=True, help="metrics Parquet (one row per observer)")
    ap.add_argument("--bands-out", required=True, help="1/3-octave band Parquet")
    ap.add_argument("--figure", help="spectrum figure (PNG) of the loudest observer")
    args = ap.parse_args(argv)
    if args.broadband in ("bpm", "auto") and not args.disks:
        return fail(f"--broadband {args.broadband} needs --disks (the loads or bvi directory of the rotors' disk tables)")
    problem = option_problem({"--altitude-m": ("atmosphere.altitude_m", args.altitude_m),
                              "--isa-delta-k": ("atmosphere.isa_delta_K", args.isa_delta_k),
                              "--relative-humidity-pct": ("atmosphere.relative_humidity_pct", args.relative_humidity_pct),
                              "--bvispl-harmonics": ("acoustics.bvispl_harmonics", args.bvispl_harmonics)})
    if problem:
        return fail(problem)
    if not args.aircraft:
        if args.broadband != "none":
            return fail(f"--broadband {args.broadband} needs --aircraft (the rotors' solidities and sections); without an "
                        "aircraft file use --broadband none")
        names = trim_rotors(args.trim)
        if isinstance(names, str):
            return fail(names)
        aircraft = {"name": provenance(args.trim, "aircraft"), "rotors": [{"name": n} for n in names]}
    else:
        try:
            aircraft = load_aircraft(args.aircraft)
        except ConfigError as error:
            return fail(str(error))
    atmosphere = {"altitude_m": args.altitude_m, "isa_delta_K": args.isa_delta_k,
                  "relative_humidity_pct": args.relative_humidity_pct}
    names = args.rotor or [r["name"] for r in aircraft["rotors"]]
    params = {"rotors": names, "solidity": rotor_solidities(aircraft) if args.aircraft else {},
              "rotor_configs": {r["name"]: r for r in aircraft["rotors"]} if args.aircraft else {},
              "atmosphere": atmosphere, "broadband": args.broadband, "absorption": not args.no_absorption,
              "harmonics": args.bvispl_harmonics, "aircraft": aircraft["name"], "segment": provenance(args.trim, "segment"),
              "obsset": provenance(args.observers, "obsset"), "variant": provenance(f"{args.signals}/{names[0]}.parquet", "variant") or "base"}
    inputs = {"signals": args.signals, "trim": args.trim, "observers": args.observers, **({"hsi": args.hsi} if args.hsi else {}),
              **({"disks": args.disks} if args.disks else {})}
    outputs = {"metrics": args.out, "bands": args.bands_out, **({"figure": args.figure} if args.figure else {})}
    return run_stage("metrics", inputs, outputs, params, args.debug,
                     args.allow_outside_validity, sources={"--aircraft": args.aircraft} if args.aircraft else None)
