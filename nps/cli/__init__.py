"""Command-line entry points, one module per stage (``python -m nps <stage>``): argument parsing only.

Each module builds the stage's ``inputs``, ``outputs`` and ``params`` from its options (defaults read
from the configuration schemas, :func:`nps.app.config.schema_default`) and calls the same
``nps.stages.<stage>.run`` the workflow runs. :func:`run_stage` prints the stage's report, and turns
every expected error (bad file, bad field, bad value) into one line on stderr and exit status 2;
``--debug`` shows the traceback instead.
"""

from __future__ import annotations

import argparse
import sys

from nps.app.config import load_schema, schema_default


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
        ap.add_argument("--allow-outside-validity", action="store_true",
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


# config ``footprint.ground`` field -> option of the footprint and certification commands
GROUND_OPTIONS = {"model": "--ground", "flow_resistivity_kPa_s_m2": "--flow-resistivity", "coherent": "--coherent"}


def ground_options(ap: argparse.ArgumentParser) -> None:
    """The ground options (:data:`GROUND_OPTIONS`), dest ``ground_<field>``."""
    for field, flag in GROUND_OPTIONS.items():
        option(ap, flag, f"footprint.ground.{field}", dest=f"ground_{field}")


def ground(args: argparse.Namespace) -> dict:
    """The ``ground`` params slice of the parsed :func:`ground_options`."""
    return {field: getattr(args, f"ground_{field}") for field in GROUND_OPTIONS}


def same_path_problem(inputs: dict, outputs: dict) -> str | None:
    """The first output that would overwrite an input: an output path equal to an input path, or an
    existing output file inside an input directory. ``inputs``/``outputs`` map a name (option or stage
    key) to a path; None values are skipped. Returns the one-line problem or None."""
    from pathlib import Path

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
              allow_outside_validity: bool = False, sources: dict | None = None) -> int:
    """Run ``nps.stages.<stage>.run``; print its report; expected errors → one line and exit status 2.
    ``allow_outside_validity``: the campaign switch, passed to the stage as a param when set.
    ``sources``: option → file the command read itself (configuration files); no output may be an input
    (:func:`same_path_problem`) or one of them."""
    clash = same_path_problem({**inputs, **(sources or {})}, outputs)
    if clash:
        return fail(clash)
    if allow_outside_validity:
        params = {**params, "allow_outside_validity": True}
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


def option_problem(options: dict) -> str | None:
    """First command-line value outside its configuration-schema field: ``options`` maps the option
    (``--isa-delta-k``) to (schema field, value); returns ``"--isa-delta-k: expected ..."`` or None."""
    from nps.app.config import field_problem

    for option, (field, value) in options.items():
        problem = field_problem("config", field, value)
        if problem:
            return f"{option}: {problem}"
    return None


def fail(message: str) -> int:
    """One-line error for a problem found while reading the options (exit status 2)."""
    print(f"error: {message}", file=sys.stderr)
    return 2


def trim_rotors(path: str) -> list[str] | str:
    """The rotor names of a trim artifact, in its order (a command without an aircraft file: a PSU-WOPWOP case's
    rotors, nps.stages.wopwop_run); a one-line problem when it cannot be read."""
    from nps.app.io import read_table

    try:
        return [str(name) for name in read_table(path, required=("rotor",), nonempty=True)["rotor"]]
    except ValueError as error:
        return str(error)


def provenance(path: str, key: str) -> str:
    """The ``nps.<key>`` metadata of an input artifact (e.g. its segment), "" when absent or unreadable
    (the stage then reports the unreadable file itself)."""
    from nps.app.io import read_metadata

    try:
        return str(read_metadata(path).get(key, ""))
    except Exception:  # missing or not a Parquet file: the stage's own read names the problem
        return ""
