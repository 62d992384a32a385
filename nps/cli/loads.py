"""``python -m nps loads``: trimmed blade loads of every rotor of an aircraft (stage nps.stages.loads).

Writes, per rotor, ``{rotor}.parquet`` (disk table), ``{rotor}_summary.parquet`` and
``{rotor}_history.parquet`` into ``--out-dir``; ``--rotor`` restricts to named rotors.
"""

from __future__ import annotations

from nps.cli import default, fail, option_problem, parser, provenance, run_stage
from nps.app.config import ConfigError, aircraft_rotor, load_aircraft


def main(argv: list[str]) -> int:
    ap = parser("loads", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    ap.add_argument("--n-psi", type=int, default=default("resolution.n_psi"), help="azimuth stations (default %(default)s)")
    ap.add_argument("--n-r", type=int, default=default("resolution.n_r"), help="radial stations (default %(default)s)")
    ap.add_argument("--out-dir", required=True, help="directory of the per-rotor tables (results/.../loads)")
    args = ap.parse_args(argv)
    problem = option_problem({"--n-psi": ("resolution.n_psi", args.n_psi), "--n-r": ("resolution.n_r", args.n_r)})
    if problem:
        return fail(problem)
    try:
        aircraft = load_aircraft(args.aircraft)
        names = args.rotor or [r["name"] for r in aircraft["rotors"]]
        rotors = {name: aircraft_rotor(aircraft, name, args.aircraft) for name in names}
    except ConfigError as error:
        return fail(str(error))
    params = {"rotors": rotors, "n_psi": args.n_psi, "n_r": args.n_r, "aircraft": aircraft["name"],
              "segment": provenance(args.trim, "segment")}
    return run_stage("loads", {"trim": args.trim}, {"loads": args.out_dir}, params, args.debug,
                     args.allow_outside_validity, sources={"--aircraft": args.aircraft})

