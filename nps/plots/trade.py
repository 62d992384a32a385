"""Design-study figures from the trade table (nps.app.trade): each metric against each variable, noise
against power with the Pareto front, and the sensitivity ranking."""

from __future__ import annotations

import re
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.app.trade import RELATIVE_METRICS, case_columns
from nps.plots import save_figure

MAX_LEVELS = 8  # values of a variable up to which the trends figure draws main-effect lines
LABELS = {"max_dba_db": "max. OASPL(A) (dBA)", "max_oaspl_db": "max. OASPL (dB)", "max_bvispl_db": "max. BVISPL (dB)",
          "power_W": "rotor power (kW)", "energy_J": "rotor energy (MJ)", "duration_s": "duration (s)",
          "max_sel_db": "max. SEL at the microphones (dBA)"}
SCALES = {"power_W": 1e-3, "energy_J": 1e-6}  # to the units of LABELS


def _label(metric: str) -> str:
    """Axis label of a trade-table column: :data:`LABELS`, a procedure's per-microphone level, or the column."""
    at = re.fullmatch(r"(sel|lamax|epnl)_(\w+)_db", metric)
    if metric not in LABELS and at:
        name, unit = {"sel": ("SEL", "dBA"), "lamax": ("L_Amax", "dBA"), "epnl": ("EPNL", "EPNdB")}[at.group(1)]
        return f"{name} at {at.group(2)} ({unit})"
    return LABELS.get(metric, metric)


def _values(table: pd.DataFrame, metric: str) -> np.ndarray:
    return table[metric].to_numpy(float) * SCALES.get(metric, 1.0)


def _broadband_switched(group: pd.DataFrame) -> pd.Series:
    """Per row of one aircraft × segment: whether its rotors' broadband models (``<rotor>_broadband``) differ
    from the case's most frequent combination (``models.broadband: auto`` chooses by the operating point)."""
    columns = [c for c in group.columns if c.endswith("_broadband") and not pd.api.types.is_numeric_dtype(group[c])]
    if not columns:
        return pd.Series(False, index=group.index)
    combination = group[columns].astype(str).agg("/".join, axis=1)
    return combination != combination.mode().iloc[0]


def _case_label(aircraft: str, case: str, name: str, n_aircraft: int) -> str:
    """A case's label: the segment with its mission name, or the path's name alone (its description is a sentence)."""
    text = f"{case} ({name})" if case != name else case
    return f"{aircraft} {text}" if n_aircraft > 1 else text


def metrics_against_variables(table: pd.DataFrame, variables: Sequence[str], metrics: Sequence[str], title: str, path) -> None:
    """Grid of panels, one row per metric and one column per variable: the metric's mean over the other
    variables at each value of the variable (its main effect), one line per aircraft × segment; a variable
    with more than :data:`MAX_LEVELS` values (a Latin hypercube) shows every design as a point instead. Points whose
    rotors' broadband models differ from the case's other designs (:func:`_broadband_switched`) are drawn open,
    with a note; a whole-number variable gets whole-number ticks."""
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator

    fig, axes = plt.subplots(len(metrics), len(variables), figsize=(4.2 * len(variables) + 2.5, 2.8 * len(metrics)),
                             squeeze=False, sharex="col")
    colours = plt.get_cmap("tab10")
    key, name = case_columns(table)
    cases = list(table.groupby(["aircraft", key], sort=False))
    n_aircraft = table["aircraft"].nunique()
    any_switch = False
    for i, metric in enumerate(metrics):
        for j, variable in enumerate(variables):
            ax = axes[i, j]
            for k, ((aircraft, segment), group) in enumerate(cases):
                label = _case_label(aircraft, segment, group[name].iloc[0] if key == "segment" else segment, n_aircraft)
                switched = _broadband_switched(group)
                any_switch |= bool(switched.any())
                if group[variable].nunique() > MAX_LEVELS:  # a sampled design: every design, no main effect
                    x, y = group[variable].to_numpy(float), _values(group, metric)
                    ax.plot(x, y, ".", color=colours(k % 10), ms=4, label=label)
                else:
                    means = group.assign(_m=_values(group, metric)).groupby(variable, sort=True)["_m"].mean()
                    x, y = means.index.to_numpy(), means.to_numpy()
                    ax.plot(x, y, "o-", color=colours(k % 10), ms=3.5, lw=1.4, label=label)
                    switched = switched.groupby(group[variable]).any().reindex(means.index)
                open_ = switched.to_numpy(bool)
                ax.plot(x[open_], y[open_], "o", mfc="white", mec=colours(k % 10), ms=5.5, zorder=3)
            if _integer_valued(table[variable]):
                ax.xaxis.set_major_locator(MaxNLocator(integer=True))
            ax.grid(alpha=0.3)
            ax.ticklabel_format(axis="y", useOffset=False)
            if j == 0:
                ax.set_ylabel(_label(metric))
            if i == len(metrics) - 1:
                ax.set_xlabel(variable)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8, frameon=False)
    fig.suptitle(title)
    if any_switch:
        fig.text(0.01, 0.005, "open markers: the point is or includes designs whose broadband model differs from the "
                 "case's other designs (trade-table columns <rotor>_broadband):\nmodels.broadband auto chooses Pegg or "
                 "BPM per rotor by its operating point, so a step there is the change of model, not a trend",
                 fontsize=8, ha="left", va="bottom")
    fig.tight_layout(rect=(0, 0.045 if any_switch else 0, 0.8, 0.97))
    save_figure(fig, path)


def _integer_valued(values: pd.Series) -> bool:
    """Whether a design variable takes whole numbers only (a blade count): integer axis ticks."""
    if not pd.api.types.is_numeric_dtype(values) or pd.api.types.is_bool_dtype(values):
        return False
    numbers = values.to_numpy(float)
    return bool(np.all(numbers == np.round(numbers)))


def pareto_figure(table: pd.DataFrame, colour_by: str, noise: str, cost: str, title: str, path) -> None:
    """``noise`` against ``cost``, one panel per aircraft × segment (× path); designs coloured by ``colour_by``,
    the Pareto front (``pareto`` column) joined and ringed."""
    import matplotlib.pyplot as plt

    key, name = case_columns(table)
    cases = list(table.groupby(["aircraft", key], sort=False))
    ncols = min(3, len(cases))
    nrows = int(np.ceil(len(cases) / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.8 * ncols + 1.0, 3.8 * nrows), squeeze=False, layout="constrained")
    n_aircraft = table["aircraft"].nunique()
    numeric = pd.api.types.is_numeric_dtype(table[colour_by]) and not pd.api.types.is_bool_dtype(table[colour_by])
    codes, levels = (table[colour_by].to_numpy(float), None) if numeric else pd.factorize(table[colour_by], sort=True)
    colour_values = pd.Series(np.asarray(codes, float), index=table.index)  # text and booleans: their sorted levels
    norm = plt.Normalize(colour_values.min(), colour_values.max())
    scatter = None
    for ax, ((aircraft, case), group) in zip(axes.flat, cases):
        x, level = _values(group, cost), group[noise].to_numpy(float)
        scatter = ax.scatter(x, level, c=colour_values[group.index].to_numpy(), cmap="viridis", norm=norm, s=22)
        front = group["pareto"].to_numpy(bool)
        order = np.argsort(x[front])
        ax.plot(x[front][order], level[front][order], "-", color="crimson", lw=1.2, label="Pareto front")
        ax.scatter(x[front], level[front], facecolors="none", edgecolors="crimson", s=70, lw=1.2)
        ax.set_title(_case_label(aircraft, case, group[name].iloc[0] if key == "segment" else case, n_aircraft), fontsize=9)
        ax.set_xlabel(_label(cost))
        ax.set_ylabel(_label(noise))
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(cases):]:
        ax.set_visible(False)
    axes.flat[0].legend(fontsize=8, loc="best")
    bar = fig.colorbar(scatter, ax=axes, label=colour_by, shrink=0.8)
    if levels is not None:
        bar.set_ticks(range(len(levels)), labels=[str(level) for level in levels])
    fig.suptitle(title)
    save_figure(fig, path)


def sensitivity_figure(ranking: pd.DataFrame, per_segment: pd.DataFrame, metrics: Sequence[str], title: str, path) -> None:
    """One panel per metric: each variable's change per +10 % (bar: mean over segments or paths; dots: each),
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
        unit = "%" if metric in RELATIVE_METRICS else "dB"
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
