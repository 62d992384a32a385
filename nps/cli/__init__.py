"""Command-line entry points, one module per stage (``python -m nps <stage>``): argument parsing only.

Each module builds the stage's ``inputs`` and ``outputs`` from its options and calls the same
``nps.stages.<stage>.run`` the workflow runs. A command that reads an aircraft file plans its ``params`` as the
workflow does (:func:`plan`, nps.app.plan.stage_params): from the aircraft and the campaign configuration its
options make (:func:`settings`: the config schema's defaults with the options written in), so a command at its
defaults gives the workflow's params for a campaign at the schema's defaults. :func:`run_stage` prints the
stage's report, and turns every expected error (bad file, bad field, bad value) into one line on stderr and exit
status 2; ``--debug`` shows the traceback instead. An output file named with a suffix other than its format's
(:func:`output_file`) is a usage error.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from nps.app.config import ConfigError, aircraft_rotor, field_problem, load_aircraft, load_schema, schema_default, schema_defaults


class _Parser(argparse.ArgumentParser):
    """Argument parser whose usage errors are one line on stderr, exit status 2."""

    def error(self, message: str):
        self.exit(2, f"error: {self.prog}: {message} (see --help)\n")


def parser(stage: str, description: str, validity: bool = False) -> argparse.ArgumentParser:
    """Argument parser of ``python -m nps <stage>`` with the common ``--debug`` option (and, for a stage
    with validity checks, ``--allow-outside-validity``, the campaign switch of docs/reference/validity.md)."""
    ap = _Parser(prog=f"python -m nps {stage}", description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--debug", action="store_true", help="show the traceback of an error")
    if validity:
        option(ap, "--allow-outside-validity", "campaign.allow_outside_validity", action="store_true",
               help="run outside the models' validity envelope with a warning in the output's metadata")
    return ap


def default(field: str):
    """Default of a campaign-configuration field (``config`` schema), e.g. ``resolution.n_psi``."""
    return schema_default("config", field)


def boolean(text: str) -> bool:
    """``true`` / ``false`` (any case) of a boolean option."""
    if text.lower() not in ("true", "false"):
        raise argparse.ArgumentTypeError(f"expected true or false, got {text!r}")
    return text.lower() == "true"


def schema_field(field: str, schema: str = "config") -> dict:
    """The node of a dotted field of a schema (``config`` or ``rig``), e.g. ``wake.free.relaxation``."""
    node = load_schema(schema)
    for part in field.split("."):
        node = node["properties"][part]
    return node


def option(ap: argparse.ArgumentParser, flag: str, field: str, *, schema: str = "config", **kwargs) -> argparse.Action:
    """``ap.add_argument(flag, ...)`` for a field of ``schema`` (``config`` or ``rig``): default (None without
    one), type, choices and fixed list length from the schema; ``kwargs`` add to or override them. The action
    keeps the field as ``schema_field`` and the schema as ``schema_name`` (tests/unit/test_defaults.py checks
    the defaults against the schema)."""
    node = schema_field(field, schema)
    spec = {"default": node.get("default"), "help": node.get("description", field.rsplit(".", 1)[-1]).replace("%", "%%")}
    if "action" not in kwargs:
        items = node.get("items", node) if node.get("type") == "array" else node
        kind = items.get("type")
        kind = next(k for k in kind if k != "null") if isinstance(kind, list) else kind
        spec["type"] = {"integer": int, "number": float, "boolean": boolean}.get(kind, str)
        if "enum" in items:
            spec["choices"] = items["enum"]
        if node.get("type") == "array":
            fixed = node.get("minItems") is not None and node.get("minItems") == node.get("maxItems")
            spec["nargs"] = node["minItems"] if fixed else "*"
    action = ap.add_argument(flag, **{**spec, **kwargs})
    action.schema_field, action.schema_name = field, schema
    return action


def trim_options(ap: argparse.ArgumentParser) -> None:
    """The options of an aircraft trim (commands trim and path): atmosphere and the disk resolution of the loads
    that solve rpm-controlled rotor speeds."""
    option(ap, "--altitude-m", "atmosphere.altitude_m")
    option(ap, "--isa-delta-k", "atmosphere.isa_delta_K")
    option(ap, "--relative-humidity-pct", "atmosphere.relative_humidity_pct")
    option(ap, "--n-psi", "resolution.n_psi",
           help="azimuth stations of the loads solving rpm-controlled rotor speeds (default %(default)s)")
    option(ap, "--n-r", "resolution.n_r", help="radial stations (default %(default)s)")


# config ``footprint.ground`` field -> option of the footprint and certification commands
GROUND_OPTIONS = {"model": "--ground", "flow_resistivity_kPa_s_m2": "--flow-resistivity", "coherent": "--coherent"}


def ground_options(ap: argparse.ArgumentParser) -> None:
    """The ground options (:data:`GROUND_OPTIONS`), dest ``ground_<field>``."""
    for field, flag in GROUND_OPTIONS.items():
        option(ap, flag, f"footprint.ground.{field}", dest=f"ground_{field}")


# the formats an output file option may name, by suffix
FORMATS = {".parquet": "Parquet table", ".csv": "CSV table"}


def output_file(suffix: str):
    """argparse ``type`` of an output file written in the format of ``suffix`` (:data:`FORMATS`): a path with
    another suffix is a usage error naming the option and the suffix, before anything is read or written."""
    def path(text: str) -> str:
        if Path(text).suffix.lower() != suffix:
            raise argparse.ArgumentTypeError(f"expected a path ending in {suffix} (a {FORMATS[suffix]} is written "
                                             f"there), got {text!r}")
        return text

    return path


def _put(config: dict, field: str, value) -> None:
    *sections, key = field.split(".")
    for section in sections:
        config = config.setdefault(section, {})
    config[key] = value


def settings(ap: argparse.ArgumentParser, args: argparse.Namespace, fields: dict | None = None) -> dict:
    """The campaign configuration a command plans its stage params from: the config schema's defaults
    (:func:`nps.app.config.schema_defaults`) with the value of every option of a config field (:func:`option`;
    None: not given, the schema's) written in, then ``fields`` (dotted field → value) for what no option names
    itself (``--no-absorption``, an observer-set file). ConfigError ``"--option: expected ..."`` for a value
    outside its field."""
    config = schema_defaults("config")
    for action in ap._actions:
        value = getattr(args, action.dest, None)
        if getattr(action, "schema_name", None) != "config" or value is None:
            continue
        problem = field_problem("config", action.schema_field, value)
        if problem:
            raise ConfigError(f"{action.option_strings[0]}: {problem}")
        _put(config, action.schema_field, value)
    for field, value in (fields or {}).items():
        _put(config, field, value)
    return config


def command_aircraft(path: str, rotors: list[str] | None = None) -> dict:
    """The validated aircraft file ``path``; with ``rotors`` (``--rotor``) those only, in that order (the first
    the reference rotor). ConfigError naming the file for a rotor it does not have."""
    aircraft = load_aircraft(path)
    if rotors:
        aircraft = {**aircraft, "rotors": [aircraft_rotor(aircraft, name, path) for name in rotors]}
    return aircraft


def plan(stage: str, ap: argparse.ArgumentParser, args: argparse.Namespace, aircraft: dict, fields: dict | None = None,
         obsset: str | None = None, **case) -> dict:
    """The params the workflow gives a ``stage`` job of ``aircraft`` (:func:`nps.app.plan.stage_params`) with the
    configuration of the command's options (:func:`settings`, ``fields``); ``case``: the other
    :class:`nps.app.plan.CaseConfig` fields (speeds, mission). The ground recorded as written is the options' (every
    field: an option at its default writes it too). The command adds the job's names (aircraft, segment, observer
    set, variant). ConfigError for an option outside its field."""
    from nps.app.plan import CaseConfig, stage_params

    config = settings(ap, args, fields)
    return stage_params(stage, CaseConfig(aircraft, config, ground_as_written=config["footprint"]["ground"], **case), obsset)


def same_path_problem(inputs: dict, outputs: dict) -> str | None:
    """The first output that would overwrite an input: an output path equal to an input path, or an
    existing output file inside an input directory. ``inputs``/``outputs`` map a name (option or stage
    key) to a path; None values are skipped. Returns the one-line problem or None."""
    read = {name: Path(path).resolve() for name, path in inputs.items() if path is not None}
    for out_name, out_path in outputs.items():
        if out_path is None:
            continue
        target = Path(out_path).resolve()
        for in_name, source in read.items():
            if target == source:
                return (f"{out_name} {out_path}: is the input {in_name} {inputs[in_name]}: expected an output path "
                        f"that is no input (writing would overwrite it)")
            if target.is_file() and source.is_dir() and source in target.parents:
                return (f"{out_name} {out_path}: lies in the input directory {in_name} {inputs[in_name]} and exists: "
                        f"expected an output path outside the inputs (writing would overwrite an input)")
    return None


def run_stage(stage: str, inputs: dict, outputs: dict, params: dict, debug: bool = False,
              sources: dict | None = None) -> int:
    """Run ``nps.stages.<stage>.run``; print its report; expected errors → one line and exit status 2.
    ``sources``: option → file the command read itself (configuration files); no output may be an input
    (:func:`same_path_problem`) or one of them."""
    clash = same_path_problem({**inputs, **(sources or {})}, outputs)
    if clash:
        return fail(clash)
    from nps.stages import stage_function
    from nps.stages.job import expected_errors

    try:
        report = stage_function(stage)(inputs, outputs, params)
    except expected_errors() as error:
        if debug:
            raise
        message = error.args[0] if isinstance(error, KeyError) and error.args else error
        if isinstance(error, OSError) and error.filename:
            blocked = " (a file is where an output directory must go)" if isinstance(error, (FileExistsError, NotADirectoryError)) else ""
            message = f"{error.filename}: {error.strerror}{blocked}"
        print(f"error: {message}", file=sys.stderr)
        return 2
    print(report)
    return 0


def fail(message: str) -> int:
    """One-line error for a problem found while reading the options (exit status 2)."""
    print(f"error: {message}", file=sys.stderr)
    return 2


def trim_rotors(path: str) -> list[str]:
    """The rotor names of a trim artifact, in its order (a command without an aircraft file: a PSU-WOPWOP case's
    rotors, nps.stages.wopwop_run); ValueError naming the file when it cannot be read."""
    from nps.app.io import read_table

    return [str(name) for name in read_table(path, required=("rotor",), nonempty=True)["rotor"]]


def command_rotors(path: str | None, rotors: list[str] | None, trim: str) -> tuple[dict, list[str] | None]:
    """The aircraft a command with an optional ``--aircraft`` plans for, and the rotors that replace the planned
    params' (None: keep them): the aircraft file (:func:`command_aircraft`) and None; without one (a PSU-WOPWOP
    case's artifacts) the trim artifact's aircraft name with no rotor configuration, and ``rotors`` or the trim
    artifact's (:func:`trim_rotors`)."""
    if path:
        return command_aircraft(path, rotors), None
    return {"name": provenance(trim, "aircraft"), "rotors": []}, rotors or trim_rotors(trim)


def disks_variant(disks: str, rotor: str) -> str:
    """The load variant of a disk-table directory, from ``rotor``'s table: "bvi" for the wake stage's BVI loads,
    else "base"."""
    from nps.app.io import rotor_path

    return "bvi" if provenance(str(rotor_path(disks, rotor)), "stage") == "bvi" else "base"


def signals_variant(signals: str, rotor: str) -> str:
    """The load variant of a signals directory, from ``rotor``'s table ("base" when it records none)."""
    from nps.app.io import rotor_path

    return provenance(str(rotor_path(signals, rotor)), "variant") or "base"


def provenance(path: str, key: str) -> str:
    """The ``nps.<key>`` metadata of an input artifact (e.g. its segment), "" when absent or unreadable
    (the stage then reports the unreadable file itself)."""
    from nps.app.io import read_metadata

    try:
        return str(read_metadata(path).get(key, ""))
    except Exception:  # missing or not a Parquet file: the stage's own read names the problem
        return ""
