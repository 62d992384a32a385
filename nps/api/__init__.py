"""Python API for notebooks and scripts: :class:`Case` (one aircraft, mission and configuration; run a
segment), :class:`Study` (a design study file; run its variants) and :class:`FlightPathCase` (a flight path
flown by its aircraft), returning pandas DataFrames.

Both run the workflow's own stage functions (``nps.stages.<stage>.run`` with the parameters of
:mod:`nps.app.plan`) through the stage cache of :mod:`nps.stages.case`, so a case computed by the
workflow, a study or a notebook is computed once. Example: examples/tip_speed_sweep.py.
"""

from nps.api.case import Case, CaseResult
from nps.api.path import FlightPathCase, PathResult
from nps.api.study import Study, StudyResult

__all__ = ["Case", "CaseResult", "FlightPathCase", "PathResult", "Study", "StudyResult"]
