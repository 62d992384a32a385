"""``python -m nps source_hemisphere``: the source-hemisphere product of an aircraft in one segment
(stage nps.stages.source_hemisphere).

Reads the acoustics directory (and optionally the HSI directory) of a hemisphere observer set moving
with the aircraft, its observer table and the trim artifact; writes one row per observer × source ×
1/3-octave band (10 Hz–10 kHz), unabsorbed, referred to ``--reference-radius-m`` (default 10 R of the
first rotor) by spherical spreading. Schema: nps.mission.source_hemisphere.
"""

from __future__ import annotations

from nps.cli import fail, option, parser, provenance, run_stage
from nps.app.config import ConfigError, load_aircraft
from nps.app.io import rotor_path
from nps.noise.metrics import rotor_solidities


def main(argv: list[str]) -> int:
    ap = parser("source_hemisphere", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (rotor solidities, first-rotor radius)")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--observers", required=True, help="observers/{obsset}.parquet of a moving hemisphere")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals at that set")
    ap.add_argument("--hsi", help="HSI directory (its tonal total replaces thickness + loading)")
    ap.add_argument("--no-broadband", action="store_true", help="skip the broadband source")
    option(ap, "--reference-radius-R", "footprint.reference_radius_R", dest="reference_radius_R",
           help="reference radius of the levels, first-rotor radii (default %(default)s)")
    ap.add_argument("--out", required=True, help="source-hemisphere Parquet")
    args = ap.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
    except ConfigError as error:
        return fail(str(error))
    radius = args.reference_radius_R * aircraft["rotors"][0]["radius_m"]
    rotors = [r["name"] for r in aircraft["rotors"]]
    params = {"rotors": rotors, "solidity": rotor_solidities(aircraft), "broadband": not args.no_broadband,
              "reference_radius_m": radius, "aircraft": aircraft["name"], "segment": provenance(args.trim, "segment"),
              "obsset": provenance(args.observers, "obsset"),
              "variant": provenance(str(rotor_path(args.signals, rotors[0])), "variant") or "base"}
    inputs = {"signals": args.signals, "trim": args.trim, "observers": args.observers, **({"hsi": args.hsi} if args.hsi else {})}
    return run_stage("source_hemisphere", inputs, {"hemisphere": args.out}, params, args.debug,
                     sources={"--aircraft": args.aircraft})
