"""Command line: ``python -m nps <stage> [options]`` (``python -m nps <stage> --help``).

Every stage of the workflow is usable on its own: ``nps/cli/<stage>.py`` parses the options
(``main(argv) -> int``) and runs ``nps.stages.<stage>.run``, the function the workflow runs.
"""

from __future__ import annotations

import os

# Deterministic results: a multi-threaded BLAS may sum the spectra's matrix products in another order
# (last-bit differences); set before numpy loads. The workflow's jobs get the same from nps.stages.job.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import importlib  # noqa: E402
import pkgutil  # noqa: E402
import sys  # noqa: E402

import nps.cli  # noqa: E402


def stages() -> list[str]:
    """Names of the available stages (modules of ``nps.cli``)."""
    return sorted(m.name for m in pkgutil.iter_modules(nps.cli.__path__) if not m.name.startswith("_"))


def main(argv: list[str] | None = None) -> int:
    """Run ``python -m nps <stage> [options]``; returns the exit status (option errors: 2, one line)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    available = stages()
    if argv and argv[0].replace("-", "_") in available:  # station-loads: the module station_loads
        argv[0] = argv[0].replace("-", "_")
    if not argv or argv[0] in ("-h", "--help"):
        print("usage: python -m nps <stage> [options]\nstages: " + ", ".join(available), file=sys.stderr)
        return 0 if argv else 2
    if argv[0] not in available:
        print(f"error: unknown stage '{argv[0]}'; stages: {', '.join(available)}", file=sys.stderr)
        return 2
    module = importlib.import_module(f"nps.cli.{argv[0]}")
    try:
        return int(module.main(argv[1:]) or 0)
    except SystemExit as stop:  # the option parser's --help (0) and usage errors (2)
        return stop.code if isinstance(stop.code, int) else 2


if __name__ == "__main__":
    sys.exit(main())
