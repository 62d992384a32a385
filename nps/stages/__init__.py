"""Application layer: one function per workflow stage, shared by the workflow, the CLI and the tests.

Every stage is ``run(inputs, outputs, params) -> str``:

* ``inputs``: name → path of the artifacts it reads (files, or per-rotor directories),
* ``outputs``: name → path it writes (written atomically through :func:`nps.app.io.write_table`),
* ``params``: plain values — validated configuration slices, resolution, and the names of the
  aircraft, segment, observer set and variant it works on (they enter the artifacts' metadata),
* the return value is a short report for the job's log.

A stage reads artifacts, calls the physics modules and writes artifacts; it holds no physics
itself. The Snakemake scripts call it through :func:`nps.stages.job.run_job`, ``python -m nps
<stage>`` through its argument parser (``nps/cli/<stage>.py``), and the tests directly. The rule,
the stage and the command carry the same name.
"""

from __future__ import annotations

import importlib
from typing import Callable

# the stages, in workflow order (``radiate``, for tabulated sources, is not in the study workflow;
# ``rig``, the set-up of a rig, ``carpet`` and ``station_loads`` are the rig-only stages, workflow/rules/rig.smk; ``case``, the
# chain of one design-study case in one process, and ``trade``, a study's trade table: designs.smk;
# ``path``, a flight path's history and trim states (command ``nps path``, no rule yet);
# ``results_summary``, the campaign's results page the report opens on: study.smk; ``wopwop_run``,
# ``wopwop_export`` and ``wopwop_read``, the commands ``nps wopwop run | export | read``, the export also a rule:
# wopwop.smk);
# stage X is ``nps.stages.X.run``
STAGES = ("trim", "loads", "wake", "observers", "acoustics", "hsi", "metrics", "tones",
          "rotor_figures", "hsi_figure", "study_maps", "rotor_maps", "bvi_hotspot", "summary", "results_summary",
          "source_hemisphere", "footprint", "certification", "path", "radiate", "rig", "carpet", "station_loads", "case", "trade",
          "wopwop_run", "wopwop_export", "wopwop_read")


def stage_module(stage: str) -> str:
    """Dotted name of the module holding ``stage``."""
    if stage not in STAGES:
        raise KeyError(f"unknown stage '{stage}'; stages: {', '.join(STAGES)}")
    return f"nps.stages.{stage}"


def stage_function(stage: str) -> Callable[..., str]:
    """The ``run(inputs, outputs, params)`` function of ``stage`` (imported on demand)."""
    return importlib.import_module(stage_module(stage)).run
