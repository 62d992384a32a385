"""Stage ``summary``: one summary row per segment: levels and hotspots, trim state, wall time per stage.

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from nps.app.broadband import broadband_model
from nps.app.io import check_provenance, read_metadata, read_table, rotor_path, write_table
from nps.app.validity import pegg_range_notes
from nps.app.study import STAGES, segment_summary
from nps.rotor.trim import TRIM_STAGES


def stage_wall_times(benchmark_dir: str | Path, aircraft: str, segment: str) -> dict[str, float]:
    """Wall time (s) of each stage's jobs for one aircraft and segment, summed over files.

    Reads Snakemake benchmark files ``<benchmark_dir>/<stage>/<aircraft>/<segment>[/…].tsv``
    (column ``s``); stages without files are absent.
    """
    times = {}
    for stage in STAGES:
        root = Path(benchmark_dir) / stage / aircraft
        files = sorted(root.glob(f"{segment}.tsv")) + sorted(root.glob(f"{segment}/**/*.tsv"))
        if files:
            times[stage] = float(sum(pd.read_csv(f, sep="\t")["s"].iloc[-1] for f in files))
    return times


def validity_warnings(paths, notes=()) -> str:
    """The distinct ``validity_warnings`` messages recorded in the artifacts ``paths`` (metadata), in
    order, then the distinct model-range ``notes`` (:func:`model_range_notes`), joined by " | "; "" when
    there are none."""
    messages = []
    for path in paths:
        for warning in read_metadata(path).get("validity_warnings", []):
            if warning["message"] not in messages:
                messages.append(warning["message"])
    for note in notes:
        if note not in messages:
            messages.append(note)
    return " | ".join(messages)


def model_range_notes(metrics_paths, trim: pd.DataFrame, rotors) -> list[str]:
    """The model-range warnings the metrics jobs of a segment emit (their log; not their metadata, which
    stays that of a run without them): Pegg outside his data range for every rotor of a metrics artifact
    computed with Pegg broadband (its ``broadband`` metadata), :func:`nps.app.validity.pegg_range_notes`."""
    models = [meta["broadband"] for meta in map(read_metadata, metrics_paths) if "broadband" in meta]
    return pegg_range_notes(trim, rotors) if any(broadband_model(m) == "pegg" for m in models) else []


def segment_artifacts(inputs: dict, params: dict, segment: str) -> dict:
    """Artifacts of one segment the summary reads or lists the warnings of (trim, loads summaries,
    wake tables where computed, metrics of each variant) → the provenance each must have."""
    same = {"aircraft": params["aircraft"], "segment": segment}
    artifacts = {inputs[f"trim_{segment}"]: {"stage": TRIM_STAGES, **same}}
    artifacts.update({rotor_path(inputs[f"loads_{segment}"], r, "_summary"): {"stage": "loads", "rotor": r, **same}
                      for r in params["rotors"]})
    if f"wake_{segment}" in inputs:
        artifacts.update({rotor_path(inputs[f"wake_{segment}"], r): {"stage": "wake", "rotor": r, **same} for r in params["rotors"]})
    artifacts.update({inputs[f"metrics_{segment}_{v}"]: {"stage": "metrics", "variant": v, "obsset": "hemisphere", **same}
                      for v in params["variants"][segment]})
    return artifacts


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """One summary row per segment: levels and hotspots, trim state, wall time per stage.

    inputs: ``trim_<segment>``, ``loads_<segment>`` (directory), ``metrics_<segment>_<variant>``.
    outputs: ``table`` (Parquet, without the wall times, so it stays bit-reproducible) and ``csv``
    (with them and the column ``validity_warnings``: the findings the artifacts of the segment recorded
    under ``allow_outside_validity`` and the model-range warnings of its metrics jobs, "" when none). params: ``segments``, ``rotors``, ``variants`` (segment → variants),
    ``benchmarks`` (Snakemake benchmark directory), ``aircraft``.
    """
    aircraft = params["aircraft"]
    rows = []
    for segment in params["segments"]:
        recorded = segment_artifacts(inputs, params, segment)
        for path, expected in recorded.items():
            check_provenance(path, expected)
        trim = read_table(inputs[f"trim_{segment}"])
        loads = {r: read_table(rotor_path(inputs[f"loads_{segment}"], r, "_summary")) for r in params["rotors"]}
        metrics = {v: read_table(inputs[f"metrics_{segment}_{v}"]) for v in params["variants"][segment]}
        notes = model_range_notes([inputs[f"metrics_{segment}_{v}"] for v in params["variants"][segment]], trim,
                                  params["rotors"])
        rows.append({**segment_summary(aircraft, segment, trim, loads, metrics,
                                       stage_wall_times(params["benchmarks"], aircraft, segment)),
                     "validity_warnings": validity_warnings(recorded, notes)})
    table = pd.DataFrame(rows)
    csv_only = [c for c in table.columns if c.startswith("wall_")] + ["validity_warnings"]
    write_table(table.drop(columns=csv_only), outputs["table"], stage="summary", metadata={"aircraft": aircraft})
    table.to_csv(outputs["csv"], index=False, float_format="%.6g")
    return table.to_string()
