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

from nps.app.config import schema_default


class _Parser(argparse.ArgumentParser):
    """Argument parser whose usage errors are one line on stderr, exit status 2."""

    def error(self, message: str):
        self.exit(2, f"error: {self.prog}: {message} (see --help)\n")


def parser(stage: str, description: str, validity: bool = False) -> argparse.ArgumentParser:
    """Argument parser of ``python -m nps <stage>`` with the common ``--debug`` option (and, for a stage
    with validity checks, ``--allow-outside-validity``, the campaign switch of docs/models/validity.md)."""
    ap = _Parser(prog=f"python -m nps {stage}", description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--debug", action="store_true", help="show the traceback of an error")
    if validity:
        ap.add_argument("--allow-outside-validity", action="store_true",
                        help="run outside the models' validity envelope with a warning in the output's metadata")
    return ap


def default(field: str):
    """Default of a campaign-configuration field (``config`` schema), e.g. ``resolution.n_psi``."""
    return schema_default("config", field)


def run_stage(stage: str, inputs: dict, outputs: dict, params: dict, debug: bool = False,
              allow_outside_validity: bool = False) -> int:
    """Run ``nps.stages.<stage>.run``; print its report; expected errors → one line and exit status 2.
    ``allow_outside_validity``: the campaign switch, passed to the stage as a param when set."""
    if allow_outside_validity:
        params = {**params, "allow_outside_validity": True}
    from nps.stages import stage_function

    from nps.rotor.bet import TrimError
    from nps.app.resources import ResourceError
    from nps.rotor.trim import AircraftTrimError

    try:
        report = stage_function(stage)(inputs, outputs, params)
    except (ValueError, KeyError, OSError, ResourceError, TrimError, AircraftTrimError) as error:
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


def provenance(path: str, key: str) -> str:
    """The ``nps.<key>`` metadata of an input artifact (e.g. its segment), "" when absent or unreadable
    (the stage then reports the unreadable file itself)."""
    from nps.app.io import read_metadata

    try:
        return str(read_metadata(path).get(key, ""))
    except Exception:  # missing or not a Parquet file: the stage's own read names the problem
        return ""
