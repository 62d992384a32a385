"""Design-study figures from the trade table (nps.app.trade): each metric against each variable, noise
against power with the Pareto front, and the sensitivity ranking."""

from __future__ import annotations

from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.plots import save_figure

MAX_LEVELS = 8  # values of a variable up to which the trends figure draws main-effect lines
LABELS = {"max_dba_db": "max. OASPL(A) (dBA)", "max_oaspl_db": "max. OASPL (dB)", "max_bvispl_db": "max. BVISPL (dB)",
          "power_W": "rotor power (kW)"}


def _label(metric: str) -> str:
    return LABELS.get(metric, metric)


def _values(table: pd.DataFrame, metric: str) -> np.ndarray:
    values = table[metric].to_numpy(float)
    return values / 1e3 if metric == "power_W" else values


def _case_label(aircraft: str, segment: str, name: str, n_aircraft: int) -> str:
    return f"{aircraft} {segment} ({name})" if n_aircraft > 1 else f"{segment} ({name})"


def metrics_against_variables(table: pd.DataFrame, variables: Sequence[str], metrics: Sequence[str], title: str, path) -> None:
    """Grid of panels, one row per metric and one column per variable: the metric's mean over the other
    variables at each value of the variable (its main effect), one line per aircraft × segment; a variable
    with more than :data:`MAX_LEVELS` values (a Latin hypercube) shows every design as a point instead."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(metrics), len(variables), figsize=(4.2 * len(variables) + 2.5, 2.8 * len(metrics)),
                             squeeze=False, sharex="col")
    colours = plt.get_cmap("tab10")
    cases = list(table.groupby(["aircraft", "segment"], sort=False))
    n_aircraft = table["aircraft"].nunique()
    for i, metric in enumerate(metrics):
        for j, variable in enumerate(variables):
            ax = axes[i, j]
            for k, ((aircraft, segment), group) in enumerate(cases):
                label = _case_label(aircraft, segment, group["segment_name"].iloc[0], n_aircraft)
                if group[variable].nunique() > MAX_LEVELS:  # a sampled design: every design, no main effect
                    ax.plot(group[variable].to_numpy(float), _values(group, metric), ".", color=colours(k % 10), ms=4, label=label)
                    continue
                means = group.assign(_m=_values(group, metric)).groupby(variable, sort=True)["_m"].mean()
                ax.plot(means.index.to_numpy(), means.to_numpy(), "o-", color=colours(k % 10), ms=3.5, lw=1.4, label=label)
            ax.grid(alpha=0.3)
            if j == 0:
                ax.set_ylabel(_label(metric))
            if i == len(metrics) - 1:
                ax.set_xlabel(variable)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0, 0.8, 0.97))
    save_figure(fig, path)


def pareto_figure(table: pd.DataFrame, colour_by: str, noise: str, title: str, path) -> None:
    """Noise against power, one panel per aircraft × segment; designs coloured by ``colour_by``, the Pareto
    front (``pareto`` column) joined and ringed."""
    import matplotlib.pyplot as plt

    cases = list(table.groupby(["aircraft", "segment"], sort=False))
    ncols = min(3, len(cases))
    nrows = int(np.ceil(len(cases) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.8 * ncols + 1.0, 3.8 * nrows), squeeze=False, layout="constrained")
    n_aircraft = table["aircraft"].nunique()
    colour_values = table[colour_by].to_numpy(float)
    norm = plt.Normalize(colour_values.min(), colour_values.max())
    scatter = None
    for ax, ((aircraft, segment), group) in zip(axes.flat, cases):
        power, level = _values(group, "power_W"), group[noise].to_numpy(float)
        scatter = ax.scatter(power, level, c=group[colour_by].to_numpy(float), cmap="viridis", norm=norm, s=22)
        front = group["pareto"].to_numpy(bool)
        order = np.argsort(power[front])
        ax.plot(power[front][order], level[front][order], "-", color="crimson", lw=1.2, label="Pareto front")
        ax.scatter(power[front], level[front], facecolors="none", edgecolors="crimson", s=70, lw=1.2)
        ax.set_title(_case_label(aircraft, segment, group["segment_name"].iloc[0], n_aircraft), fontsize=9)
        ax.set_xlabel(_label("power_W"))
        ax.set_ylabel(_label(noise))
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(cases):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=8, loc="best")
    fig.colorbar(scatter, ax=axes, label=colour_by, shrink=0.8)
    fig.suptitle(title)
    save_figure(fig, path)


def sensitivity_figure(ranking: pd.DataFrame, per_segment: pd.DataFrame, metrics: Sequence[str], title: str, path) -> None:
    """One panel per metric: each variable's change per +10 % (bar: mean over segments; dots: segments),
    variables in ranking order (largest magnitude on top)."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(metrics), figsize=(3.8 * len(metrics) + 1.0, 0.6 * ranking["variable"].nunique() + 2.2),
                             squeeze=False)
    for ax, metric in zip(axes[0], metrics):
        rows = ranking[ranking["metric"] == metric].groupby("variable", sort=False)["change_per_10pct"].mean()
        rows = rows.iloc[np.argsort(-np.abs(rows.to_numpy()), kind="stable")][::-1]
        positions = np.arange(len(rows))
        ax.barh(positions, rows.to_numpy(), color=np.where(rows.to_numpy() >= 0, "tab:red", "tab:blue"), alpha=0.7)
        for y, variable in zip(positions, rows.index):
            dots = per_segment[(per_segment["metric"] == metric) & (per_segment["variable"] == variable)]["change_per_10pct"]
            ax.plot(dots.to_numpy(), np.full(len(dots), y), "k.", ms=4)
        ax.set_yticks(positions, rows.index)
        ax.axvline(0.0, color="k", lw=0.8)
        unit = "%" if metric == "power_W" else "dB"
        ax.set_xlabel(f"change per +10 % ({unit})")
        ax.set_title(_label(metric), fontsize=9)
        ax.grid(axis="x", alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    save_figure(fig, path)


def html_table(table: pd.DataFrame, title: str, notes: Mapping[str, str] | None = None) -> str:
    """A self-contained HTML page of ``table`` (numbers to 4 significant digits) for the report."""
    body = table.to_html(index=False, float_format=lambda v: f"{v:.4g}", border=0, classes="trade")
    items = "".join(f"<li><b>{key}</b>: {value}</li>" for key, value in (notes or {}).items())
    style = ("<style>table.trade{border-collapse:collapse;font:12px sans-serif}"
             "table.trade td,table.trade th{padding:2px 6px;border-bottom:1px solid #ddd;text-align:right}</style>")
    return f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{title}</title>{style}</head><body>" \
           f"<h2>{title}</h2><ul>{items}</ul>{body}</body></html>\n"
