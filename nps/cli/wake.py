"""``python -m nps wake``: tip-vortex wake and BVI loads of every rotor of an aircraft (stage nps.stages.wake), with
the params the workflow plans for it (nps.app.plan).

Reads the trim artifact and the loads directory (``{rotor}.parquet`` and ``{rotor}_summary.parquet``);
writes the wake geometry (``{rotor}.parquet`` and a legacy-VTK series ``{rotor}_vtk/``) into
``--wake-dir`` and the BVI disk tables (``{rotor}.parquet``) into ``--bvi-dir``.
"""

from __future__ import annotations

from nps.cli import command_aircraft, fail, option, parser, plan, provenance, run_stage, schema_field
from nps.app.config import ConfigError

# config ``wake`` field -> option; the free-wake block's fields become --free-<field>
WAKE_OPTIONS = {"model": "--model", "A": "--A", "B": "--B", "C": "--C", "D": "--D",
                "core_radius_chords": "--core-radius-chords", "vortex_structure": "--vortex-structure",
                "step_deg": "--step-deg"}
FREE_FIELDS = tuple(schema_field("wake.free")["properties"])


def main(argv: list[str]) -> int:
    ap = parser("wake", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--loads-dir", required=True, help="loads directory (results/.../loads)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    ap.add_argument("--wake-dir", required=True, help="output directory of the wake geometry")
    ap.add_argument("--bvi-dir", required=True, help="output directory of the BVI disk tables")
    for field, flag in WAKE_OPTIONS.items():
        option(ap, flag, f"wake.{field}", dest=field)
    option(ap, "--core-growth", "wake.core_growth", action="store_true", help="Squire core growth with wake age")
    option(ap, "--quasi-steady", "wake.unsteady", dest="unsteady", action="store_false",
           help="no Sears response (thesis lifting line)")
    for field in FREE_FIELDS:
        option(ap, f"--free-{field.replace('_', '-')}", f"wake.free.{field}", dest=f"free_{field}",
               help=f"free wake (--model free): {schema_field(f'wake.free.{field}').get('description', field)} "
                    "(default: nps.wake.free.FreeWakeModel's)".replace("%", "%%"))
    option(ap, "--revolutions", "resolution.wake_revolutions", help="wake age kept")
    option(ap, "--steps-per-rev", "resolution.n_psi", help="vortex segments per revolution")
    args = ap.parse_args(argv)
    try:
        aircraft = command_aircraft(args.aircraft, args.rotor)
        params = plan("wake", ap, args, aircraft)
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"))
    return run_stage("wake", {"trim": args.trim, "loads": args.loads_dir}, {"wake": args.wake_dir, "bvi": args.bvi_dir},
                     params, args.debug, sources={"--aircraft": args.aircraft})
