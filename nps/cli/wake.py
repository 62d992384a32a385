"""``python -m nps wake``: tip-vortex wake and BVI loads of every rotor of an aircraft (stage nps.stages.wake).

Reads the trim artifact and the loads directory (``{rotor}.parquet`` and ``{rotor}_summary.parquet``);
writes the wake geometry (``{rotor}.parquet`` and a legacy-VTK series ``{rotor}_vtk/``) into
``--wake-dir`` and the BVI disk tables (``{rotor}.parquet``) into ``--bvi-dir``.
"""

from __future__ import annotations

from nps.cli import default, fail, option_problem, parser, provenance, run_stage
from nps.app.config import ConfigError, aircraft_rotor, load_aircraft


def main(argv: list[str]) -> int:
    ap = parser("wake", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--loads-dir", required=True, help="loads directory (results/.../loads)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    ap.add_argument("--wake-dir", required=True, help="output directory of the wake geometry")
    ap.add_argument("--bvi-dir", required=True, help="output directory of the BVI disk tables")
    ap.add_argument("--model", choices=("beddoes", "free"), default=default("wake.model"),
                    help="beddoes (prescribed, per rotor) or free (free-vortex wakes of all rotors, interaction)")
    ap.add_argument("--A", type=float, default=default("wake.A"), help="Beddoes skew coefficient A")
    ap.add_argument("--B", type=float, default=default("wake.B"), help="Beddoes lateral coefficient B")
    ap.add_argument("--C", type=float, default=default("wake.C"), help="Beddoes mean-inflow coefficient C")
    ap.add_argument("--D", type=float, default=default("wake.D"), help="Landgrebe contraction D")
    ap.add_argument("--core-radius-chords", type=float, default=default("wake.core_radius_chords"), help="r_c / c")
    ap.add_argument("--core-growth", action="store_true", default=default("wake.core_growth"),
                    help="Squire core growth with wake age")
    ap.add_argument("--vortex-structure", choices=("betz", "point"), default=default("wake.vortex_structure"),
                    help="betz (circulation spread as Betz's roll-up of the trailed sheet) or point (thesis)")
    ap.add_argument("--revolutions", type=float, default=default("resolution.wake_revolutions"), help="wake age kept")
    ap.add_argument("--steps-per-rev", type=int, default=default("resolution.n_psi"), help="vortex segments per revolution")
    ap.add_argument("--step-deg", type=float, default=5.0, help="wake snapshot spacing over one blade passage (deg)")
    ap.add_argument("--quasi-steady", action="store_true", help="no Sears response (thesis lifting line)")
    args = ap.parse_args(argv)
    problem = option_problem({**{f"--{k}": (f"wake.{k}", getattr(args, k)) for k in ("A", "B", "C", "D")},
                              "--core-radius-chords": ("wake.core_radius_chords", args.core_radius_chords),
                              "--revolutions": ("resolution.wake_revolutions", args.revolutions),
                              "--steps-per-rev": ("resolution.n_psi", args.steps_per_rev)})
    if problem:
        return fail(problem)
    if not 0.0 < args.step_deg <= 360.0:
        return fail(f"--step-deg: expected a number in (0, 360], got {args.step_deg}")
    try:
        aircraft = load_aircraft(args.aircraft)
        names = args.rotor or [r["name"] for r in aircraft["rotors"]]
        rotors = {name: aircraft_rotor(aircraft, name, args.aircraft) for name in names}
    except ConfigError as error:
        return fail(str(error))
    wake = {"model": args.model, "A": args.A, "B": args.B, "C": args.C, "D": args.D, "core_radius_chords": args.core_radius_chords,
            "core_growth": args.core_growth, "vortex_structure": args.vortex_structure}
    params = {"rotors": rotors, "wake": wake, "revolutions": args.revolutions, "steps_per_rev": args.steps_per_rev,
              "step_deg": args.step_deg, "unsteady": not args.quasi_steady, "aircraft": aircraft["name"],
              "segment": provenance(args.trim, "segment")}
    return run_stage("wake", {"trim": args.trim, "loads": args.loads_dir}, {"wake": args.wake_dir, "bvi": args.bvi_dir},
                     params, args.debug,
                     args.allow_outside_validity)
