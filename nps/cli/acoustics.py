"""``python -m nps acoustics``: pressure signals of every rotor of an aircraft at one observer set
(stage nps.stages.acoustics, compact Farassat 1A).

Reads a directory of disk tables (``loads/`` or ``bvi/``: ``{rotor}.parquet``), the trim artifact and an
observer table; writes ``{rotor}.parquet`` signal tables (observer, group, time_s, p_Pa) on the
aircraft's common grid (one revolution of the first rotor) into ``--out-dir``.
"""

from __future__ import annotations

from nps.cli import default, fail, option_problem, parser, provenance, run_stage
from nps.app.config import ConfigError, aircraft_rotor, load_aircraft


def main(argv: list[str]) -> int:
    ap = parser("acoustics", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML: hinge offsets, reference (first) rotor")
    ap.add_argument("--disks", required=True, help="directory of disk tables (results/.../loads or .../bvi)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--observers", required=True, help="observer table (results/.../observers/SET.parquet)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor); the first one listed sets the time grid")
    ap.add_argument("--samples-per-rev", type=int, default=default("resolution.samples_per_rev"),
                    help="samples per reference-rotor revolution (default %(default)s)")
    ap.add_argument("--thickness", default=default("models.thickness"), help="dual_compact or compact_monopole")
    ap.add_argument("--chord-fractions", type=float, nargs=2, default=default("acoustics.dual_compact_chord_fractions"),
                    metavar=("FRONT", "REAR"), help="dual-compact line positions from the leading edge (fractions of chord)")
    ap.add_argument("--variant", choices=("base", "bvi"),
                    help="load variant: base (trimmed loads) or bvi (default: from the disk tables' provenance)")
    ap.add_argument("--out-dir", required=True, help="output directory of the per-rotor signal tables")
    args = ap.parse_args(argv)
    problem = option_problem({"--samples-per-rev": ("resolution.samples_per_rev", args.samples_per_rev),
                              "--thickness": ("models.thickness", args.thickness),
                              "--chord-fractions": ("acoustics.dual_compact_chord_fractions", args.chord_fractions)})
    if problem:
        return fail(problem)
    try:
        aircraft = load_aircraft(args.aircraft)
        names = args.rotor or [r["name"] for r in aircraft["rotors"]]
        hinges = {n: float(aircraft_rotor(aircraft, n, args.aircraft)["hinge_offset_m"]) for n in names}
    except ConfigError as error:
        return fail(str(error))
    params = {"rotors": names, "hinge_offsets_m": hinges, "thickness": args.thickness, "chord_fractions": args.chord_fractions,
              "samples_per_rev": args.samples_per_rev, "aircraft": aircraft["name"],
              "segment": provenance(args.trim, "segment"), "obsset": provenance(args.observers, "obsset"),
              "variant": args.variant or ("bvi" if provenance(f"{args.disks}/{names[0]}.parquet", "stage") == "bvi" else "base")}
    inputs = {"disks": args.disks, "trim": args.trim, "observers": args.observers}
    return run_stage("acoustics", inputs, {"signals": args.out_dir}, params, args.debug, sources={"--aircraft": args.aircraft})
