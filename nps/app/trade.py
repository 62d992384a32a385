"""Trade tables of design studies (docs/reference/studies.md): one row per design × aircraft × segment with
the design variables, rotor performance and noise maxima, the Pareto front of noise against power, and the
sensitivity of each metric to each variable.

Performance is the blade-element solution at trim (``loads/{rotor}_summary``): thrust, torque, power,
C_T and C_T/σ; the tip Mach number is the hover tip Mach number Ω R / a of the trim table. Noise is the
maximum over an observer set of OASPL, A-weighted OASPL and BVISPL of the load variant with BVI wherever it
is computed (as the campaign summary, :func:`nps.app.study.segment_summary`).
"""

from __future__ import annotations

import math
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.app.broadband import rotor_broadband_models
from nps.app.config import Campaign
from nps.app.study import hotspot
from nps.noise.metrics import rotor_solidities

NOISE_METRICS = {"oaspl_db": "max_oaspl_db", "oaspl_dba": "max_dba_db", "bvispl_db": "max_bvispl_db"}
SOURCE_LEVELS = ("thickness", "loading", "broadband")  # per-source OASPL of the metrics (oaspl_<source>_db)
TEN_PERCENT = math.log(1.1)


def noise_column(obsset: str, column: str) -> str:
    """Trade-table column of an observer set's maximum: ``max_dba_db`` (hemisphere), ``<set>_max_dba_db`` else."""
    name = NOISE_METRICS[column]
    return name if obsset == "hemisphere" else f"{obsset}_{name}"


def case_row(campaign: Campaign, aircraft: str, segment: str, design: Mapping, trim: pd.DataFrame,
             loads_summaries: Mapping[str, pd.DataFrame], metrics: Mapping[str, pd.DataFrame],
             warnings: Sequence[str]) -> pd.DataFrame:
    """The one-row trade table of a case: ``design`` (label → value) first, then aircraft, segment and its
    name, per rotor ``<rotor>_{thrust_N, torque_Nm, power_W, ct, ct_sigma, omega_rad_s, tip_speed_mps,
    tip_mach}`` and ``<rotor>_broadband`` (the model its broadband came from: ``pegg``, ``bpm`` or ``none``;
    ``auto`` may choose differently from design to design), ``power_W`` (all rotors), per observer set the maxima (:func:`noise_column`) with the
    azimuth and elevation of the loudest observer, the maxima of the per-source OASPL
    (``max_{thickness,loading,broadband}_db``) and of the thickness OASPL in the hub plane (elevation 0,
    ``in_plane_max_thickness_db``) where the set has such observers, and ``validity_warnings`` ("; "-joined)."""
    row: dict[str, object] = {}
    row.update(aircraft=aircraft, segment=segment, segment_name=campaign.segment(segment)["name"])
    solidity = rotor_solidities(campaign.aircraft[aircraft])
    total = 0.0
    broadband = rotor_broadband_models(campaign.config["models"]["broadband"], trim, list(loads_summaries))
    for name, table in loads_summaries.items():
        values = dict(zip(table["quantity"], table["value"]))
        state = trim.loc[trim["rotor"] == name].iloc[0]
        row[f"{name}_thrust_N"] = float(values["thrust_N"])
        row[f"{name}_torque_Nm"] = float(values["torque_Nm"])
        row[f"{name}_power_W"] = float(values["power_W"])
        row[f"{name}_ct"] = float(values["ct"])
        row[f"{name}_ct_sigma"] = float(values["ct"]) / solidity[name]
        row[f"{name}_omega_rad_s"] = float(state["omega_rad_s"])
        row[f"{name}_tip_speed_mps"] = float(state["omega_rad_s"] * state["radius_m"])
        row[f"{name}_tip_mach"] = float(state["tip_mach"])
        row[f"{name}_broadband"] = broadband[name]
        total += float(values["power_W"])
    row["power_W"] = total
    for obsset, table in metrics.items():
        prefix = "" if obsset == "hemisphere" else f"{obsset}_"
        for source in SOURCE_LEVELS:  # broadband: where a broadband model is on
            if f"oaspl_{source}_db" in table:
                row[f"{prefix}max_{source}_db"] = float(table[f"oaspl_{source}_db"].max())
        in_plane = table["elevation_deg"].abs() < 1e-9
        if in_plane.any():
            row[f"{prefix}in_plane_max_thickness_db"] = float(table.loc[in_plane, "oaspl_thickness_db"].max())
        for column in NOISE_METRICS:
            spot = hotspot(table, column)
            name = noise_column(obsset, column)
            row[name] = spot["value"]
            row[f"{name[:-3]}_azimuth_deg"] = spot["azimuth_deg"]
            row[f"{name[:-3]}_elevation_deg"] = spot["elevation_deg"]
    row["validity_warnings"] = "; ".join(warnings)
    clashes = sorted(set(design) & set(row))
    if clashes:
        raise ValueError(f"design-variable labels {clashes} are trade-table columns; choose other labels")
    return pd.DataFrame([{**design, **row}])


def certification_columns(table: pd.DataFrame, summary: pd.DataFrame) -> pd.DataFrame:
    """``table`` (one aircraft's rows) with its certification (nps.stages.certification summary) on every
    row: ``epnl_<procedure>_db`` (mean of the three microphones), ``margin_<procedure>_db`` (limit − EPNL,
    positive: below the limit) and ``min_margin_db``."""
    table = table.copy()
    for procedure, epnl, margin in summary[["procedure", "epnl_db", "margin_db"]].itertuples(index=False):
        table[f"epnl_{procedure}_db"] = float(epnl)
        table[f"margin_{procedure}_db"] = float(margin)
    table["min_margin_db"] = float(summary["margin_db"].min())
    return table


def footprint_columns(table: pd.DataFrame, areas: pd.DataFrame) -> pd.DataFrame:
    """``table`` (one aircraft's rows) with its mission footprint's contour areas (nps.stages.footprint
    ``areas``) on every row: ``<metric>_<level>db_area_km2`` (e.g. ``sel_db_80db_area_km2``; a contour that
    reaches the grid edge is a lower bound, ``footprint_open`` lists those)."""
    table = table.copy()
    for metric, level, area in areas[["metric", "level_db", "area_km2"]].itertuples(index=False):
        table[f"{metric}_{level:g}db_area_km2"] = float(area)
    opened = areas[areas["open"]]
    table["footprint_open"] = "; ".join(f"{m} {l:g} dB" for m, l in opened[["metric", "level_db"]].itertuples(index=False))
    return table


def state_power_history_W(history: pd.DataFrame, power_W: Mapping[str, float]) -> np.ndarray:
    """Rotor power (W) along a path history (stage ``path``): each sample's blend of its bracketing states'
    powers, (1 − w) P(state) + w P(neighbour), the weights that blend their source hemispheres."""
    weight = history["neighbour_weight"].to_numpy(float)
    own = history["state"].map(power_W).to_numpy(float)
    neighbour = history["neighbour"].map(power_W).to_numpy(float)
    return (1.0 - weight) * own + weight * neighbour


def path_energy_J(time_s: np.ndarray, power_W: np.ndarray, duration_s: float) -> float:
    """Energy (J) the rotors take over a path: the trapezoidal integral of the sampled power, the last sample's
    power held to the path's end ``duration_s`` (the samples are k Δt, the end between two)."""
    time_s, power_W = np.asarray(time_s, float), np.asarray(power_W, float)
    inner = float(np.sum(0.5 * (power_W[1:] + power_W[:-1]) * np.diff(time_s)))
    return inner + float(power_W[-1]) * max(duration_s - float(time_s[-1]), 0.0)


PROCEDURE_METRICS = ("sel", "lamax", "epnl")  # per microphone: sel_<mic>_db, ... and their maxima max_sel_db, ...


def procedure_row(path: Mapping, design: Mapping, history: pd.DataFrame, power_W: Mapping[str, float],
                  duration_s: float, distance_m: float, microphones: pd.DataFrame, areas: pd.DataFrame,
                  warnings: Sequence[str]) -> pd.DataFrame:
    """The one-row trade table of a flown path (a procedure study, docs/reference/studies.md): ``design`` (label →
    value) first, then aircraft, ``path`` and ``path_description``, ``duration_s``, ``distance_m`` (along the
    path), ``energy_J`` (:func:`path_energy_J` of the states' rotor power ``power_W``, state key → W, blended as
    the hemispheres are), ``n_states``; per microphone ``sel_<mic>_db``, ``lamax_<mic>_db``, ``epnl_<mic>_db`` and
    their maxima ``max_sel_db``, ``max_lamax_db``, ``max_epnl_db``; the contour areas (:func:`footprint_columns`)
    and ``validity_warnings``."""
    power = state_power_history_W(history, power_W)
    row: dict[str, object] = {"aircraft": path["aircraft"], "path": path["name"],
                              "path_description": path.get("description", ""), "duration_s": float(duration_s),
                              "distance_m": float(distance_m),
                              "energy_J": path_energy_J(history["time_s"].to_numpy(float), power, duration_s),
                              "n_states": len(set(history["state"]) | set(history["neighbour"]))}
    for metric in PROCEDURE_METRICS:
        values = dict(zip(microphones["microphone"], microphones[f"{metric}_db"].astype(float)))
        row.update({f"{metric}_{name}_db": value for name, value in values.items()})
        row[f"max_{metric}_db"] = max(values.values())
    clashes = sorted(set(design) & set(row))
    if clashes:
        raise ValueError(f"design-variable labels {clashes} are trade-table columns; choose other labels")
    table = footprint_columns(pd.DataFrame([{**design, **row}]), areas)
    table["validity_warnings"] = "; ".join(warnings)
    return table


def trade_columns(products: Sequence[str], campaign: Campaign, observer_sets: Sequence[str]) -> set[str]:
    """The numeric trade-table columns of a study's products for ``campaign`` (the choices of its Pareto front):
    a procedure study's :func:`procedure_row` columns (its paths' microphones, the contour levels), else power,
    each rotor's performance and the observer sets' maxima (:func:`case_row`) and the Chapter 8 EPNLs."""
    from nps.mission.footprint import CONTOUR_LEVELS_DB

    if "procedure" in products:
        microphones = next(iter(campaign.paths.values()))["receivers"]["microphones"]
        columns = {"duration_s", "distance_m", "energy_J", *(f"max_{m}_db" for m in PROCEDURE_METRICS)}
        columns |= {f"{m}_{name}_db" for m in PROCEDURE_METRICS for name in microphones}
        return columns | {f"{metric}_{level:g}db_area_km2" for metric in ("sel_db", "lamax_db") for level in CONTOUR_LEVELS_DB}
    columns = {"power_W", *(noise_column(obsset, column) for obsset in observer_sets for column in NOISE_METRICS)}
    columns |= {f"{rotor['name']}_{quantity}" for aircraft in campaign.aircraft.values() for rotor in aircraft["rotors"]
                for quantity in ("thrust_N", "torque_Nm", "power_W", "ct", "ct_sigma", "tip_mach")}
    if "certification" in products:
        columns |= {f"epnl_{procedure}_db" for procedure in campaign.config["certification"]["segments"]}
    return columns


def case_columns(table: pd.DataFrame) -> tuple[str, str]:
    """(key, name) columns of a trade table's cases within an aircraft: ("path", "path_description") for the
    rows of a procedure study, ("segment", "segment_name") else."""
    return ("path", "path_description") if "path" in table.columns else ("segment", "segment_name")


def refused_table(refused: Sequence[tuple[Mapping, str, str]], variables: Sequence[str]) -> pd.DataFrame:
    """The designs a validity check or a trim refused: one row per (design values with ``design``, aircraft,
    reason), columns design, the variables, aircraft, reason."""
    rows = [{**values, "aircraft": aircraft, "reason": reason} for values, aircraft, reason in refused]
    return pd.DataFrame(rows, columns=["design", *variables, "aircraft", "reason"])


def pareto_front(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Boolean mask of the points no other point beats in both ``x`` and ``y`` (lower is better; a point
    equal in one and lower in the other beats it)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    better_or_equal = (x[None, :] <= x[:, None]) & (y[None, :] <= y[:, None])
    strictly = (x[None, :] < x[:, None]) | (y[None, :] < y[:, None])
    return ~np.any(better_or_equal & strictly, axis=1)


def pareto_columns(table: pd.DataFrame, pareto: Mapping[str, str] | None = None) -> tuple[str, str]:
    """(noise, cost) of a trade table's Pareto front: the study's ``pareto`` section, its defaults max_dba_db
    against power_W, for a procedure study's rows max_sel_db against energy_J."""
    given = dict(pareto or {})
    defaults = ("max_sel_db", "energy_J") if "path" in table.columns else ("max_dba_db", "power_W")
    return given.get("noise", defaults[0]), given.get("cost", defaults[1])


def mark_pareto(table: pd.DataFrame, noise: str = "max_dba_db", cost: str = "power_W") -> pd.DataFrame:
    """``table`` with a ``pareto`` column: on the front of ``noise`` against ``cost`` within each aircraft
    × segment (× path: :func:`case_columns`)."""
    table = table.copy()
    table["pareto"] = False
    for _, group in table.groupby(["aircraft", case_columns(table)[0]], sort=False):
        table.loc[group.index, "pareto"] = pareto_front(group[cost].to_numpy(), group[noise].to_numpy())
    return table


def _relative(values: pd.Series, base) -> bool:
    """Whether a variable's ``values`` change relative to its ``base`` value: numbers (not booleans or text) of the
    base value's sign, not all equal."""
    numeric = pd.api.types.is_numeric_dtype(values) and not pd.api.types.is_bool_dtype(values)
    return (numeric and isinstance(base, (int, float)) and not isinstance(base, bool) and base != 0
            and bool((values / base > 0).all()) and values.nunique() > 1)


RELATIVE_METRICS = ("power_W", "energy_J", "duration_s", "distance_m")  # fitted as logarithms, changes in percent


def sensitivity(table: pd.DataFrame, variables: Mapping[str, float], metrics: Sequence[str]) -> pd.DataFrame:
    """Change of each metric per +10 % of each variable, per aircraft × segment (× path: :func:`case_columns`):
    least squares of the metric on ln(variable / base value) over the designs (all variables at once: the main
    effects of a factorial), times ln 1.1. Levels in dB change by that many dB; :data:`RELATIVE_METRICS`
    (power, energy, time, distance) are fitted as logarithms and reported in percent. ``variables``: label →
    base value (variables with values of both signs, booleans and text are skipped: no relative change).
    Columns: aircraft, segment (path), metric, variable, change_per_10pct, unit."""
    usable = [v for v, base in variables.items() if _relative(table[v], base)]
    key = case_columns(table)[0]
    rows = []
    for (aircraft, case), group in table.groupby(["aircraft", key], sort=False):
        design = np.column_stack([np.ones(len(group))] + [np.log(group[v].to_numpy(float) / variables[v]) for v in usable])
        for metric in metrics:
            relative = metric in RELATIVE_METRICS
            values = group[metric].to_numpy(float)
            coefficients = np.linalg.lstsq(design, np.log(values) if relative else values, rcond=None)[0]
            for variable, slope in zip(usable, coefficients[1:]):
                change = 100.0 * (math.exp(slope * TEN_PERCENT) - 1.0) if relative else slope * TEN_PERCENT
                rows.append({"aircraft": aircraft, key: case, "metric": metric, "variable": variable,
                             "change_per_10pct": float(change), "unit": "%" if relative else "dB"})
    return pd.DataFrame(rows, columns=["aircraft", key, "metric", "variable", "change_per_10pct", "unit"])


def sensitivity_ranking(sensitivities: pd.DataFrame) -> pd.DataFrame:
    """Variables ranked per aircraft × metric by the mean over segments of their change per +10 % (sign
    kept), largest magnitude first; ``rank`` starts at 1."""
    mean = (sensitivities.groupby(["aircraft", "metric", "variable", "unit"], sort=False)["change_per_10pct"]
            .mean().reset_index())
    mean["magnitude"] = mean["change_per_10pct"].abs()
    mean = mean.sort_values(["aircraft", "metric", "magnitude"], ascending=[True, True, False], kind="mergesort")
    mean["rank"] = mean.groupby(["aircraft", "metric"]).cumcount() + 1
    return mean.drop(columns="magnitude").reset_index(drop=True)


METRICS = ("max_dba_db", "max_oaspl_db", "max_bvispl_db", "power_W")


def study_metrics(table: pd.DataFrame) -> list[str]:
    """The metrics a trade table's sensitivities and trends show: :data:`METRICS` present, or for a procedure
    study the SEL at each microphone, the rotor energy and the duration."""
    if "path" in table.columns:
        return [c for c in table.columns if c.startswith("sel_") and c.endswith("_db")] + ["energy_J", "duration_s"]
    return [m for m in METRICS if m in table.columns]


def trade_tables(rows: Sequence[pd.DataFrame], designs: Sequence[str], variables: Mapping[str, float],
                 pareto: Mapping[str, str] | None = None) -> tuple[pd.DataFrame, pd.DataFrame, pd.DataFrame]:
    """(trade table, sensitivity per aircraft × segment or path, ranking) from the cases' rows: rows ordered by
    ``designs`` (ids in study order), aircraft and segment (path), with the Pareto front of the study's
    ``pareto`` section marked (:func:`pareto_columns`, :func:`mark_pareto`); sensitivities of
    :func:`study_metrics` (:func:`sensitivity`)."""
    table = pd.concat(list(rows), ignore_index=True)
    order = {design: index for index, design in enumerate(designs)}
    table = table.sort_values(["aircraft", case_columns(table)[0]], kind="mergesort")
    table = table.iloc[table["design"].map(order).argsort(kind="stable")].reset_index(drop=True)
    table = mark_pareto(table, *pareto_columns(table, pareto))
    per_case = sensitivity(table, variables, study_metrics(table))
    return table, per_case, sensitivity_ranking(per_case)
