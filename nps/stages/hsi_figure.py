"""Stage ``hsi_figure``: observer time histories with and without HSI, rotors summed.

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from nps.app.io import read_signals, read_table


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """Observer time histories with and without HSI, rotors summed.

    inputs: ``signals``, ``hsi`` (directories), ``observers``. outputs: ``figure``. params: ``rotors``,
    ``aircraft``, ``segment``, ``variant``, ``description`` (the observers, for the title); optional
    ``segment_name`` (the mission's name of the segment, in the title).
    """
    from nps.plots import segment_title
    from nps.noise.hsi import combine_rotors
    from nps.plots.hsi import plot_observer_histories

    rotors = list(params["rotors"])
    raw = combine_rotors(list(read_signals(inputs["signals"], rotors).values()))
    hsi = combine_rotors(list(read_signals(inputs["hsi"], rotors).values()))
    observers = read_table(inputs["observers"], required=("observer", "elevation_deg")).sort_values("observer")
    histories = {}
    for o, el in zip(observers["observer"], observers["elevation_deg"]):
        a, b = raw[raw["observer"] == o], hsi[hsi["observer"] == o]
        histories[f"el {el:.0f}°"] = (a["time_s"].to_numpy(), a["p_Pa"].to_numpy(), b["p_Pa"].to_numpy())
    plot_observer_histories(histories, outputs["figure"],
                            title=f"{params['aircraft']} {segment_title(params['segment'], params.get('segment_name'))}: "
                                  f"{params['description']} "
                                  f"({params['variant']} loads), rotors summed")
    return f"{len(histories)} observers drawn"
