"""Stage ``trade``: the trade table of a design study from its cases' rows (nps.stages.case, nps.app.trade).

inputs: one row table per design × aircraft × segment (any names). outputs: ``table`` (Parquet) and ``csv``
(the trade table, rows ordered by design order, aircraft, segment or path; ``pareto`` marks the front of
the study's ``pareto`` columns, default ``max_dba_db`` against ``power_W`` per aircraft × segment, a procedure
study's ``max_sel_db`` against ``energy_J`` per aircraft × path: nps.app.trade.pareto_columns), ``sensitivity`` / ``sensitivity_csv`` (change
per +10 % of each variable per aircraft × segment × metric), ``ranking_csv`` (variables ranked by their
mean change), ``refused_csv`` (the designs a validity check or a trim refused, with the reason: not in the
table), ``html`` (the trade table as an HTML page), ``trends``, ``pareto_figure``,
``sensitivity_figure`` (PNG). params: ``study`` (name), ``variables`` (label → base value, in study
order), ``designs`` (design ids in study order), ``dropped`` (variants a constraint dropped:
[values, constraint]), ``pareto`` (the study's pareto section: noise, cost; may be empty).
"""

from __future__ import annotations

from pathlib import Path

from nps.app.io import read_metadata, read_table, write_table
from nps.app.trade import case_columns, pareto_columns, refused_table, study_metrics, trade_tables
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
    table, per_segment, ranking = trade_tables(list(rows.values()), params["designs"], variables, params["pareto"])
    metrics, (noise, cost), case = study_metrics(table), pareto_columns(table, params["pareto"]), case_columns(table)[0]
    meta = {"study": params["study"], "variables": variables, "dropped": params["dropped"]}
    write_table(table, outputs["table"], stage="trade", metadata=meta)
    write_table(per_segment, outputs["sensitivity"], stage="trade", metadata=meta)
    for frame, key in ((table, "csv"), (per_segment, "sensitivity_csv"), (ranking, "ranking_csv"),
                       (refused_table(refused, list(variables)), "refused_csv")):
        Path(outputs[key]).parent.mkdir(parents=True, exist_ok=True)
        frame.to_csv(outputs[key], index=False, float_format="%.6g")
    notes = {"designs": f"{table['design'].nunique()} ({len(params['dropped'])} dropped by constraints, {len(refused)} refused: "
                        "refused.csv)",
             "variables": ", ".join(variables), "Pareto front": f"{noise} against {cost}, per aircraft x {case}"}
    Path(outputs["html"]).write_text(html_table(table.drop(columns="validity_warnings"), f"Design study {params['study']}", notes))
    title = f"design study {params['study']}"
    metrics_against_variables(table, list(variables), metrics, f"{title}: metrics against the design variables", outputs["trends"])
    pareto_figure(table, list(variables)[0], noise, cost, f"{title}: {noise} against {cost}", outputs["pareto_figure"])
    sensitivity_figure(ranking, per_segment, metrics, f"{title}: sensitivity (mean over {case}s)", outputs["sensitivity_figure"])
    return ranking.to_string(index=False)
