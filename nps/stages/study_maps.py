"""Stage ``study_maps``: hemisphere maps of every level family over its segments, one figure per family.

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from nps.app.io import read_table


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """Hemisphere maps of every level family over its segments, one figure per family.

    inputs: segment → hemisphere metrics table. outputs: family (oaspl, dba, bvispl, hsi_oaspl) → PNG.
    params: ``segments`` (family → segments drawn), ``segment_names`` (segment → mission name),
    ``radius_R``, ``radius_m`` (the hemisphere's radius in reference-rotor radii and metres), ``aircraft``.
    """
    from nps.plots.study import study_maps

    tables = {segment: read_table(path) for segment, path in inputs.items()}
    for kind, segments in params["segments"].items():
        study_maps(kind, params["aircraft"], {s: tables[s] for s in segments}, outputs[kind],
                   segment_names=params["segment_names"], radius_R=params["radius_R"], radius_m=params["radius_m"])
    return "\n".join(f"{kind}: segments {segments}" for kind, segments in params["segments"].items())
