"""Stage ``trade``: the trade table of a design study from its cases' rows (nps.stages.case, nps.app.trade).

inputs: one row table per design × aircraft × segment (any names). outputs: ``table`` (Parquet) and ``csv``
(the trade table, rows ordered by design order, aircraft, segment; ``pareto`` marks the front of
``max_dba_db`` against ``power_W`` per aircraft × segment), ``sensitivity`` / ``sensitivity_csv`` (change
per +10 % of each variable per aircraft × segment × metric), ``ranking_csv`` (variables ranked by their
mean change), ``refused_csv`` (the designs a validity check or a trim refused, with the reason: not in the
table), ``html`` (the trade table as an HTML page), ``trends``, ``pareto_figure``,
``sensitivity_figure`` (PNG). params: ``study`` (name), ``variables`` (label → base value, in study
order), ``designs`` (design ids in study order), ``dropped`` (variants a constraint dropped:
[values, constraint]).
"""

from __future__ import annotations

from pathlib import Path

from nps.app.io import read_metadata, read_table, write_table
from nps.app.trade import METRICS, refused_table, trade_tables
from nps.plots.trade import html_table, metrics_against_variables, pareto_figure, sensitivity_figure


def run(inputs: dict, outputs: dict, params: dict) -> str:
    variables = dict(params["variables"])
    rows, refused = {}, []
    for path in inputs.values():
        meta = read_metadata(path)
        if "refused" in meta:
            refused.append((meta["design"], meta["aircraft"], meta["refused"]))
        else:
            rows[path] = read_table(path)
    if not rows:
        raise ValueError(f"study {params['study']}: every design is refused; first: {refused[0][2]}")
    first, columns = next(iter(rows)), list(next(iter(rows.values())).columns)
    for path, row in rows.items():
        if list(row.columns) != columns:
            raise ValueError(f"{path}: columns {sorted(set(row.columns) ^ set(columns))} differ from those of {first}: "
                             "rows of different code or products; rerun the study's case jobs")
    table, per_segment, ranking = trade_tables(list(rows.values()), params["designs"], variables)
    metrics = [m for m in METRICS if m in table.columns]
    meta = {"study": params["study"], "variables": variables, "dropped": params["dropped"]}
    write_table(table, outputs["table"], stage="trade", metadata=meta)
    write_table(per_segment, outputs["sensitivity"], stage="trade", metadata=meta)
    for frame, key in ((table, "csv"), (per_segment, "sensitivity_csv"), (ranking, "ranking_csv"),
                       (refused_table(refused, list(variables)), "refused_csv")):
        Path(outputs[key]).parent.mkdir(parents=True, exist_ok=True)
        frame.to_csv(outputs[key], index=False, float_format="%.6g")
    notes = {"designs": f"{table['design'].nunique()} ({len(params['dropped'])} dropped by constraints, {len(refused)} refused: "
                        "refused.csv)",
             "variables": ", ".join(variables), "Pareto front": "max. OASPL(A) against rotor power, per aircraft x segment"}
    Path(outputs["html"]).write_text(html_table(table.drop(columns="validity_warnings"), f"Design study {params['study']}", notes))
    title = f"design study {params['study']}"
    metrics_against_variables(table, list(variables), metrics, f"{title}: metrics against the design variables", outputs["trends"])
    pareto_figure(table, list(variables)[0], "max_dba_db", f"{title}: noise against power", outputs["pareto_figure"])
    sensitivity_figure(ranking, per_segment, metrics, f"{title}: sensitivity (mean over segments)", outputs["sensitivity_figure"])
    return ranking.to_string(index=False)
