"""Stage ``path_footprint``: the noise of an aircraft flying a flight path (nps.mission.path_noise).

The path's time history (stage ``path``) is flown as chords, each radiating the blend of its bracketing trim
states' source hemispheres (stage ``source_hemisphere`` per state, the states run as segments named by their
keys), to the path's receivers: a ground grid (L_Amax, SEL, per leg and for the path; contour areas) and named
microphones (L_A(t), PNLT(t), SEL, L_Amax, EPNL), over flat ground or the path's terrain (``receivers.terrain``:
receivers stand above the local ground, which reflects at its elevation; nps.mission.terrain).

inputs: ``history`` (path_history.parquet), ``hemisphere_<key>`` for every state key of the history.
outputs: ``grid``, ``microphones``, ``histories``, ``areas`` (Parquet, the columns of the mission footprint's:
nps.stages.footprint), ``plan_figure`` (SEL footprint with the track coloured by the loudest A-weighted source level
toward the ground, and the height profile) and ``history_figure`` (L_A(t) at the microphones).
params: ``path_config`` (validated path: receivers), ``atmosphere`` (isa_delta_K, relative_humidity_pct),
``ground`` (model, flow_resistivity_kPa_s_m2, coherent), ``absorption`` (bool), ``aircraft``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from nps.app.io import read_table, write_table
from nps.core.atmosphere import isa
from nps.mission.footprint import GroundGrid
from nps.mission.path_noise import PathSamples, source_level_db, path_footprint, track_grid
from nps.mission.source_hemisphere import hemisphere_from_table
from nps.mission.terrain import Terrain
from nps.stages.footprint import ground_model

HISTORY_COLUMNS = ("time_s", "leg", "x_m", "y_m", "z_m", "heading_rad", "flight_path_rad", "effective_flight_path_rad",
                   "state", "neighbour", "neighbour_weight")


def samples_from_history(history: pd.DataFrame, keys: list[str]) -> PathSamples:
    """:class:`PathSamples` of a path history table with its state keys numbered as in ``keys``."""
    index = {key: i for i, key in enumerate(keys)}
    return PathSamples(history["time_s"].to_numpy(float), history[["x_m", "y_m", "z_m"]].to_numpy(float),
                       history["heading_rad"].to_numpy(float), history["flight_path_rad"].to_numpy(float),
                       history["effective_flight_path_rad"].to_numpy(float), history["leg"].to_numpy(np.int64),
                       history["state"].map(index).to_numpy(np.int64), history["neighbour"].map(index).to_numpy(np.int64),
                       history["neighbour_weight"].to_numpy(float))


def run(inputs: dict, outputs: dict, params: dict) -> str:
    path, aircraft, atm = params["path_config"], params["aircraft"], params["atmosphere"]
    history = read_table(inputs["history"], required=HISTORY_COLUMNS)
    keys = list(dict.fromkeys(history["state"].tolist() + history["neighbour"].tolist()))
    missing = [key for key in keys if f"hemisphere_{key}" not in inputs]
    if missing:
        raise KeyError(f"path_footprint: no source hemisphere for the state(s) {missing} of {inputs['history']}")
    hemispheres = [hemisphere_from_table(read_table(inputs[f"hemisphere_{key}"]), what=str(inputs[f"hemisphere_{key}"]))
                   for key in keys]
    samples = samples_from_history(history, keys)
    receivers = path["receivers"]
    if "grid" in receivers:
        g = receivers["grid"]
        grid = GroundGrid(tuple(g["x_range_m"]), tuple(g["y_range_m"]), float(g["spacing_m"]), float(g["height_m"]))
    else:
        grid = track_grid(samples.position_m, float(receivers["margin_m"]), float(receivers["spacing_m"]))
    c = isa(0.0, atm["isa_delta_K"], atm["relative_humidity_pct"]).speed_of_sound_mps
    legs = [f"leg{k}" for k in range(int(samples.leg.max()) + 1)]
    terrain = Terrain.from_config(receivers["terrain"]) if "terrain" in receivers else None
    fp = path_footprint(samples, legs, hemispheres, grid, {k: tuple(v) for k, v in receivers["microphones"].items()}, c,
                        atm["isa_delta_K"], atm["relative_humidity_pct"], ground_model(params["ground"]),
                        absorption=bool(params["absorption"]), terrain=terrain)
    meta = {"aircraft": aircraft, "path": path["name"], "states": keys, "legs": legs,
            "grid": {"x_range_m": list(grid.x_range_m), "y_range_m": list(grid.y_range_m), "spacing_m": grid.spacing_m,
                     "height_m": grid.height_m},
            "inputs": sorted(str(v) for v in inputs.values())}
    for name in ("grid", "microphones", "histories", "areas"):
        write_table(getattr(fp, name), outputs[name], stage="path_footprint", metadata=meta)
    from nps.plots.path import path_history_figure, path_plan_figure

    path_plan_figure(fp.grid, samples, source_level_db(samples, hemispheres), receivers["microphones"], f"{aircraft}: {path['name']}",
                     outputs["plan_figure"])
    path_history_figure(fp.histories, f"{aircraft}: {path['name']}, L_A(t) at the microphones", outputs["history_figure"])
    return (f"{len(fp.grid)} receivers, {len(fp.microphones)} microphones, {len(keys)} states, {len(legs)} legs\n"
            f"{fp.areas.to_string(index=False)}\n{fp.microphones.to_string(index=False)}")
