"""Stage ``certification``: EPNL of an aircraft in the three Chapter 8 / Appendix H procedures.

Each reference procedure (take-off, overflight, approach; nps.mission.trajectory) flies the source
hemisphere of its configured mission segment in the reference atmosphere (25 °C, 70 %);
nps.mission.certification evaluates EPNL at the centre and the two 150 m sideline microphones (14 CFR 36
A36.4 via nps.noise.metrics), their mean, the Stage 3 / Chapter 8 limit for the maximum mass and the
margin.

inputs: ``hemisphere_takeoff``, ``hemisphere_overflight``, ``hemisphere_approach`` (source-hemisphere
products of the procedures' segments).
outputs: ``summary`` (Parquet) and ``summary_csv`` (one row per procedure: EPNL per microphone and
mean, limit, margin), ``microphones`` (procedure × microphone: EPNL, PNLTM, 10-dB-down duration,
SEL, L_Amax, truncated), ``histories`` (procedure × microphone × record: time_s, pnlt_db, la_db),
``pnlt_figure``, ``table_figure``.
params: ``mission`` (validated mission: V_y, climb angle and V_H come from its segments),
``max_mass_kg``, ``segments`` (procedure → mission segment), ``vne_mps``, ``approach_min_speed_mps``
(null when not given), ``ground`` (as in nps.stages.footprint), ``ground_as_written`` (recorded in the
metadata), ``absorption`` (bool), ``aircraft``.
"""

from __future__ import annotations

import pandas as pd

from nps.mission.certification import certify, histories_table, summary_table
from nps.app.io import read_table, write_table
from nps.mission.source_hemisphere import hemisphere_from_table
from nps.stages.footprint import ground_model
from nps.mission.trajectory import PROCEDURES, certification_procedure, reference_parameters


def run(inputs: dict, outputs: dict, params: dict) -> str:
    aircraft = params["aircraft"]
    segments = dict(params["segments"])
    reference = reference_parameters(params["mission"], aircraft, segments, params["vne_mps"],
                                     params["approach_min_speed_mps"])
    ground = ground_model(params["ground"])
    results = []
    for name in PROCEDURES:
        key = f"hemisphere_{name}"
        hemisphere = hemisphere_from_table(read_table(inputs[key]), what=str(inputs[key]))
        procedure = certification_procedure(name, segments[name], reference)
        results.append(certify(procedure, hemisphere, float(params["max_mass_kg"]), ground, bool(params["absorption"])))
    summary = summary_table(aircraft, float(params["max_mass_kg"]), results)
    summary["segment"] = [segments[r.name] for r in results]
    mics = pd.concat([r.microphones.assign(procedure=r.name) for r in results], ignore_index=True)
    meta = {"aircraft": aircraft, "segments": segments, "reference": reference, "ground": dict(params["ground_as_written"]),
            "limits": "ICAO Annex 16 Vol. I Chapter 8 (8.4.2) / 14 CFR 36 Appendix H Stage 3",
            "inputs": sorted(str(v) for v in inputs.values())}
    write_table(summary, outputs["summary"], stage="certification", metadata=meta)
    summary.to_csv(outputs["summary_csv"], index=False, float_format="%.2f")
    write_table(mics, outputs["microphones"], stage="certification", metadata=meta)
    write_table(histories_table(results), outputs["histories"], stage="certification", metadata=meta)
    from nps.plots.footprint import certification_figure, pnlt_figure

    pnlt_figure(histories_table(results), f"{aircraft}: PNLT at the certification microphones", outputs["pnlt_figure"])
    certification_figure(summary, f"{aircraft} (max. mass {float(params['max_mass_kg']):.0f} kg)", outputs["table_figure"])
    return f"{summary.round(2).to_string(index=False)}\n{mics.round(2).to_string(index=False)}"
