"""``python -m nps acoustics``: pressure signals of every rotor of an aircraft at one observer set
(stage nps.stages.acoustics, compact Farassat 1A), with the params the workflow plans for it (nps.app.plan: the
aircraft file's hinge offsets and blade phases).

Reads a directory of disk tables (``loads/`` or ``bvi/``: ``{rotor}.parquet``), the trim artifact and an
observer table; writes ``{rotor}.parquet`` signal tables (observer, group, time_s, p_Pa) on the
aircraft's common grid (one revolution of the first rotor) into ``--out-dir``.
"""

from __future__ import annotations

from nps.cli import command_aircraft, disks_variant, fail, option, parser, plan, provenance, run_stage
from nps.app.config import ConfigError


def main(argv: list[str]) -> int:
    ap = parser("acoustics", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML: hinge offsets, blade phases, reference (first) rotor")
    ap.add_argument("--disks", required=True, help="directory of disk tables (results/.../loads or .../bvi)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--observers", required=True, help="observer table (results/.../observers/SET.parquet)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor); the first one listed sets the time grid")
    option(ap, "--samples-per-rev", "resolution.samples_per_rev",
           help="samples per reference-rotor revolution (default %(default)s)")
    option(ap, "--thickness", "models.thickness", help="thickness source model (default %(default)s)")
    option(ap, "--chord-fractions", "acoustics.dual_compact_chord_fractions", metavar=("FRONT", "REAR"),
           help="dual-compact line positions from the leading edge (fractions of chord)")
    ap.add_argument("--variant", choices=("base", "bvi"),
                    help="load variant: base (trimmed loads) or bvi (default: from the disk tables' provenance)")
    ap.add_argument("--out-dir", required=True, help="output directory of the per-rotor signal tables")
    args = ap.parse_args(argv)
    try:
        aircraft = command_aircraft(args.aircraft, args.rotor)
        params = plan("acoustics", ap, args, aircraft)
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"),
                  obsset=provenance(args.observers, "obsset"), variant=args.variant or disks_variant(args.disks, params["rotors"][0]))
    inputs = {"disks": args.disks, "trim": args.trim, "observers": args.observers}
    return run_stage("acoustics", inputs, {"signals": args.out_dir}, params, args.debug, sources={"--aircraft": args.aircraft})
