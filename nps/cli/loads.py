"""``python -m nps loads``: trimmed blade loads of every rotor of an aircraft (stage nps.stages.loads), with the
params the workflow plans for it (nps.app.plan).

Writes, per rotor, ``{rotor}.parquet`` (disk table), ``{rotor}_summary.parquet`` and
``{rotor}_history.parquet`` into ``--out-dir``; ``--rotor`` restricts to named rotors.
"""

from __future__ import annotations

from nps.cli import command_aircraft, fail, option, parser, plan, provenance, run_stage
from nps.app.config import ConfigError


def main(argv: list[str]) -> int:
    ap = parser("loads", __doc__, validity=True)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (config/aircraft/NAME.yaml)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    option(ap, "--n-psi", "resolution.n_psi", help="azimuth stations (default %(default)s)")
    option(ap, "--n-r", "resolution.n_r", help="radial stations (default %(default)s)")
    ap.add_argument("--out-dir", required=True, help="directory of the per-rotor tables (results/.../loads)")
    args = ap.parse_args(argv)
    try:
        aircraft = command_aircraft(args.aircraft, args.rotor)
        params = plan("loads", ap, args, aircraft)
    except ConfigError as error:
        return fail(str(error))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"))
    return run_stage("loads", {"trim": args.trim}, {"loads": args.out_dir}, params, args.debug,
                     sources={"--aircraft": args.aircraft})
