"""Study summaries: per aircraft × segment, the numbers a designer reads first.

Inputs are the stage artifacts of one aircraft and segment (docs/reference/conventions.md): the trim
table, the loads summaries, the metrics tables per observer set and variant, and the wall time of
each stage's jobs (read from the workflow's benchmark files by :mod:`nps.stages.study`).
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import pandas as pd

STAGES = ("trim", "loads", "wake", "observers", "acoustics", "hsi", "metrics")  # stages whose wall time the summary reports


def hotspot(metrics: pd.DataFrame, column: str) -> dict[str, float]:
    """Largest value of ``column`` and where it is (observer, azimuth_deg, elevation_deg).

    Ties go to the lowest observer id, so the answer is deterministic.
    """
    ordered = metrics.sort_values("observer", kind="mergesort")
    index = int(np.argmax(ordered[column].to_numpy()))
    row = ordered.iloc[index]
    return {
        "value": float(row[column]),
        "observer": int(row["observer"]),
        "azimuth_deg": float(row["azimuth_deg"]),
        "elevation_deg": float(row["elevation_deg"]),
    }


def segment_summary(
    aircraft: str,
    segment: str,
    trim: pd.DataFrame,
    loads_summaries: Mapping[str, pd.DataFrame],
    metrics: Mapping[str, pd.DataFrame],
    wall_times_s: Mapping[str, float],
) -> dict[str, object]:
    """One summary row.

    ``metrics`` maps a variant (``base``/``bvi``) to the hemisphere metrics table of that
    variant; the reported levels use the BVI variant where it exists (the physical answer) and
    also give the base-variant maximum for comparison (``without_bvi_computed`` False: only the
    BVI variant was radiated and the column repeats the BVI value). ``loads_summaries`` maps rotor → the
    long ``loads/{rotor}_summary.parquet`` table (quantity, value, unit).
    """
    first = trim.iloc[0]
    row: dict[str, object] = {
        "aircraft": aircraft,
        "segment": segment,
        "pitch_deg": float(np.degrees(first["pitch_rad"])),
        "roll_deg": float(np.degrees(first["roll_rad"])),
        "flight_path_deg": float(np.degrees(first["flight_path_rad"])),
    }
    for rotor, table in loads_summaries.items():
        values = dict(zip(table["quantity"], table["value"]))
        thrust = float(trim.loc[trim["rotor"] == rotor, "thrust_N"].iloc[0])
        row[f"{rotor}_thrust_N"] = thrust
        row[f"{rotor}_mu_x"] = float(trim.loc[trim["rotor"] == rotor, "mu_x"].iloc[0])
        row[f"{rotor}_trim_iterations"] = int(values["trim_iterations"])
        row[f"{rotor}_thrust_error_rel"] = abs(values["thrust_N"] - thrust) / thrust
    variant = "bvi" if "bvi" in metrics else "base"
    table = metrics[variant]
    row["levels_variant"] = variant
    for column, label in (("oaspl_db", "oaspl"), ("oaspl_dba", "dba"), ("bvispl_db", "bvispl")):
        spot = hotspot(table, column)
        row[f"max_{label}_db"] = spot["value"]
        row[f"max_{label}_azimuth_deg"] = spot["azimuth_deg"]
        row[f"max_{label}_elevation_deg"] = spot["elevation_deg"]
    # no NaN in artifacts: where only the BVI loads were radiated the column repeats the BVI value
    # and without_bvi_computed says so
    row["without_bvi_computed"] = "base" in metrics
    row["max_bvispl_without_bvi_db"] = hotspot(metrics["base"] if "base" in metrics else table, "bvispl_db")["value"]
    for stage in STAGES:
        row[f"wall_{stage}_s"] = float(wall_times_s.get(stage, 0.0))
    return row
