"""``python -m nps wake``: tip-vortex wake and BVI loads of every rotor of an aircraft (stage nps.stages.wake).

Reads the trim artifact and the loads directory (``{rotor}.parquet`` and ``{rotor}_summary.parquet``);
writes the wake geometry (``{rotor}.parquet`` and a legacy-VTK series ``{rotor}_vtk/``) into
``--wake-dir`` and the BVI disk tables (``{rotor}.parquet``) into ``--bvi-dir``.
"""

from __future__ import annotations

from nps.cli import fail, option, option_problem, parser, provenance, run_stage, schema_field
from nps.app.config import ConfigError, aircraft_rotor, load_aircraft

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
    free = {field: getattr(args, f"free_{field}") for field in FREE_FIELDS if getattr(args, f"free_{field}") is not None}
    problem = option_problem({**{flag: (f"wake.{field}", getattr(args, field)) for field, flag in WAKE_OPTIONS.items()},
                              **{f"--free-{k.replace('_', '-')}": (f"wake.free.{k}", v) for k, v in free.items()},
                              "--revolutions": ("resolution.wake_revolutions", args.revolutions),
                              "--steps-per-rev": ("resolution.n_psi", args.steps_per_rev)})
    if problem:
        return fail(problem)
    try:
        aircraft = load_aircraft(args.aircraft)
        names = args.rotor or [r["name"] for r in aircraft["rotors"]]
        rotors = {name: aircraft_rotor(aircraft, name, args.aircraft) for name in names}
    except ConfigError as error:
        return fail(str(error))
    wake = {**{field: getattr(args, field) for field in WAKE_OPTIONS}, "core_growth": args.core_growth,
            "unsteady": args.unsteady, "free": free}
    params = {"rotors": rotors, "wake": wake, "revolutions": args.revolutions, "steps_per_rev": args.steps_per_rev,
              "aircraft": aircraft["name"], "segment": provenance(args.trim, "segment")}
    return run_stage("wake", {"trim": args.trim, "loads": args.loads_dir}, {"wake": args.wake_dir, "bvi": args.bvi_dir},
                     params, args.debug,
                     args.allow_outside_validity, sources={"--aircraft": args.aircraft})
