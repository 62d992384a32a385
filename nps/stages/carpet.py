"""Stage ``carpet``: level carpet of a rig's plane microphone group (NPS prediction only).

inputs: ``metrics`` (metrics table of the rig's microphones), ``observers`` (with ``x_T_m``,
``y_T_m``, ``group``). outputs: ``figure`` (PNG). params: ``groups`` (indices of the plane groups
drawn, one panel each), ``level`` (metrics column, e.g. ``bvispl_db``), ``label`` (colour-bar text),
``title``.
"""

from __future__ import annotations

from nps.app.io import read_table


def run(inputs: dict, outputs: dict, params: dict) -> str:
    from nps.plots.carpet import carpet_figure

    metrics, observers = read_table(inputs["metrics"]), read_table(inputs["observers"])
    table = observers.merge(metrics[["observer", params["level"]]], on="observer", validate="one_to_one")
    report = []
    for group in params["groups"]:
        part = table[table["group"] == int(group)]
        if part.empty:
            raise ValueError(f"{inputs['observers']}: group {group}: no microphones")
        peak = part.loc[part[params["level"]].idxmax()]
        report.append(f"group {group}: {params['level']} max {peak[params['level']]:.2f} dB at "
                      f"x_T {peak['x_T_m']:.3g} m, y_T {peak['y_T_m']:.3g} m; min {part[params['level']].min():.2f} dB")
    carpet_figure([table[table["group"] == int(g)] for g in params["groups"]], params["level"], params["label"],
                  params["title"], outputs["figure"])
    return "\n".join(report)
