"""Stage ``rotor_maps``: OASPL maps of one rotor alone (e.g. the tail rotor) over its segments.

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from nps.app.io import read_signals, read_table


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """OASPL maps of one rotor alone (e.g. the tail rotor) over its segments.

    inputs: ``signals_<segment>`` (hemisphere acoustics directory of each segment), ``observers``.
    outputs: ``figure``. params: ``segments``, ``segment_names`` (segment → mission name), ``radius_R``,
    ``radius_m`` (the hemisphere's radius), ``rotor``, ``aircraft``.
    """
    from nps.plots.study import rotor_maps, rotor_oaspl

    rotor = params["rotor"]
    levels = {s: rotor_oaspl(read_signals(inputs[f"signals_{s}"], [rotor])[rotor]) for s in params["segments"]}
    rotor_maps(params["aircraft"], rotor, levels, read_table(inputs["observers"]), outputs["figure"],
               segment_names=params["segment_names"], radius_R=params["radius_R"], radius_m=params["radius_m"])
    return f"rotor {rotor}: segments {list(params['segments'])}"
