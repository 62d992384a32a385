"""``python -m nps wopwop run | export | read``: PSU-WOPWOP cases (docs/reference/wopwop.md).

``nps wopwop run CASE``: run a PSU-WOPWOP case (a folder holding ``cases.nam``, a ``cases.nam``, or a case file)
with NPS's F1A solver (stage nps.stages.wopwop_run). Writes PSU-WOPWOP's output files where PSU-WOPWOP would (the
case's folder and pressureFolderName) or into ``--out-dir``, and NPS's observer, trim and signal tables in ``nps/``
beside them, ready for ``nps hsi``, ``nps metrics``, ``nps tones``.

``nps wopwop export``: write an aircraft's rotors in a segment as a PSU-WOPWOP case (stage
nps.stages.wopwop_export), from the artifacts the acoustics stage reads (disk tables, trim, observers), with the
stage parameters the workflow gives it (nps.app.plan: the aircraft file's hinge offsets and blade phases, the
campaign configuration's thickness model, chord fractions and samples per revolution).

``nps wopwop read OUTPUTS --case CASE``: PSU-WOPWOP's own output files of a case (pressure, OASPL, spectrum) as
NPS's observer, trim and signal tables and level tables (stage nps.stages.wopwop_read), for ``nps hsi``,
``nps metrics``, ``nps tones`` on PSU-WOPWOP's pressures.
"""

from __future__ import annotations

from nps.cli import disks_variant, fail, parser, provenance, run_stage


def _run(argv: list[str]) -> int:
    ap = parser("wopwop run", __doc__)
    ap.add_argument("case", help="case folder (holding cases.nam), a cases.nam, or a case file")
    ap.add_argument("--out-dir", help="output folder (default: the case's globalFolderName + pressureFolderName, "
                                      "where PSU-WOPWOP writes)")
    ap.add_argument("--case-index", type=int, help="which case of a cases.nam listing several (0-based)")
    args = ap.parse_args(argv)
    out_dir = args.out_dir
    if out_dir is None:
        from nps.stages.wopwop_run import case_file
        from nps.wopwop.case import read_case
        from nps.wopwop.errors import WopwopError

        try:
            case = read_case(case_file(args.case), args.case_index)
        except WopwopError as error:
            return fail(str(error))
        out_dir = str(case.folder / case.environment.pressure_folder)
    params = {} if args.case_index is None else {"case_index": args.case_index}
    return run_stage("wopwop_run", {"case": args.case}, {"out_dir": out_dir}, params, args.debug)


def _export(argv: list[str]) -> int:
    ap = parser("wopwop export", __doc__)
    ap.add_argument("--aircraft", required=True, help="aircraft YAML (hinge offsets, blade phases, rotor order)")
    ap.add_argument("--config", required=True,
                    help="campaign configuration YAML (config/config.yaml): thickness model, chord fractions, samples "
                         "per revolution")
    ap.add_argument("--disks", required=True, help="directory of disk tables (results/.../loads or .../bvi)")
    ap.add_argument("--trim", required=True, help="trim artifact (results/.../trim.parquet)")
    ap.add_argument("--observers", required=True, help="observer table (results/.../observers/SET.parquet)")
    ap.add_argument("--out", required=True, help="case folder to write")
    args = ap.parse_args(argv)
    from nps.app.config import ConfigError, fill_defaults, load_aircraft, load_schema, read_yaml, validate
    from nps.app.plan import CaseConfig, stage_params

    try:
        aircraft = load_aircraft(args.aircraft)
        settings = fill_defaults(validate(read_yaml(args.config), "config", args.config), load_schema("config"))
    except ConfigError as error:
        return fail(str(error))
    params = stage_params("wopwop_export", CaseConfig(aircraft, settings))
    params.update(aircraft=aircraft["name"], segment=provenance(args.trim, "segment"),
                  obsset=provenance(args.observers, "obsset"), variant=disks_variant(args.disks, params["rotors"][0]))
    inputs = {"disks": args.disks, "trim": args.trim, "observers": args.observers}
    return run_stage("wopwop_export", inputs, {"case": args.out}, params, args.debug,
                     sources={"--aircraft": args.aircraft, "--config": args.config})


def _read(argv: list[str]) -> int:
    ap = parser("wopwop read", __doc__)
    ap.add_argument("output_folder", metavar="OUTPUTS", help="folder of PSU-WOPWOP's output files of one observer container (pressure.tec or "
                                    "pressure.fn/.nam/.x; OASPLdB, OASPLdBA, spl_spectrum when present)")
    ap.add_argument("--case", required=True, help="the case they are of (folder holding cases.nam, a cases.nam or a "
                                                  "case file): its observers and rotors")
    ap.add_argument("--case-index", type=int, help="which case of a cases.nam listing several (0-based)")
    ap.add_argument("--observer-container", help="title of the case's observer container (default: its only one)")
    ap.add_argument("--out-dir", required=True, help="folder of the NPS artifacts (observers, trim, signals, levels)")
    args = ap.parse_args(argv)
    params = {key: value for key, value in (("case_index", args.case_index), ("observer_container", args.observer_container))
              if value is not None}
    return run_stage("wopwop_read", {"case": args.case, "outputs": args.output_folder}, {"out_dir": args.out_dir}, params,
                     args.debug)


COMMANDS = {"run": _run, "export": _export, "read": _read}


def main(argv: list[str]) -> int:
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip() + "\n\nusage: python -m nps wopwop {run,export,read} ... (--help of each)")
        return 0 if argv else 2
    if argv[0] not in COMMANDS:
        return fail(f"wopwop: unknown command {argv[0]!r}; expected one of {', '.join(COMMANDS)} (see --help)")
    return COMMANDS[argv[0]](argv[1:])
