"""NPS: noise prediction system for the conceptual design of rotorcraft.

Frames, units and artifact columns are defined in ``docs/reference/conventions.md``. ``nps.Case``,
``nps.Study`` and ``nps.FlightPathCase`` (the notebook API, :mod:`nps.api`) are imported on first use, so that the stage jobs, which
never use them, neither load them nor depend on them (their code digests, nps.stages.code).
"""

import importlib

__version__ = "0.1.0"

_API = ("Case", "CaseResult", "FlightPathCase", "PathResult", "Study", "StudyResult")


def __getattr__(name: str):
    if name in _API:
        return getattr(importlib.import_module("nps.api"), name)
    raise AttributeError(f"module 'nps' has no attribute '{name}'")


def __dir__():
    return sorted([*globals(), *_API])
