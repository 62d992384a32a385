"""Application infrastructure: configuration and its schemas, the validity envelope, memory estimates,
Parquet artifacts, VTK export and study summaries.

Layer 4: above every physics package; below plots, stages and commands. The face imports nothing, so
that a job reading artifacts through :mod:`nps.app.io` does not depend on the configuration code.

- :mod:`nps.app.config`: configuration files, JSON schemas (``nps/app/schemas``), defaults filled at validation;
  :mod:`nps.app.broadband`: the broadband model a validated configuration names (read by jobs without the
  configuration code).
- :mod:`nps.app.validity`: the models' validity envelope; :mod:`nps.app.resources`: memory estimates.
- :mod:`nps.app.io`: Parquet artifacts (explicit schemas, provenance, atomic writes); :mod:`nps.app.vtk`.
- :mod:`nps.app.study`: per aircraft × segment summaries.
"""
