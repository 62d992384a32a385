"""Stage ``footprint``: ground footprint of an aircraft flying the mission's flight profile.

The profile's legs (nps.mission.trajectory) fly each segment's source hemisphere; nps.mission.footprint propagates
them to the ground grid and the named microphones (nps.mission.propagation) and reduces L_A(t) to L_Amax
and SEL per leg and for the mission, the microphones also to PNLT(t) and EPNL, and the grid to
the 60–80 dB contour areas.

inputs: ``hemisphere_<segment>`` for every segment of the profile (source-hemisphere products).
outputs: ``grid`` (one row per receiver: x_m, y_m, z_m, lamax_db, sel_db, leg<k>_lamax_db,
leg<k>_sel_db), ``microphones`` (one row per microphone), ``histories`` (microphone × half-second
record: time_s, la_db, pnlt_db, leg), ``areas`` (Parquet) and ``areas_csv`` (metric, level_db,
area_km2, open), ``sel_figure`` and ``lamax_figure`` (contours with track and altitude profile).
params: ``mission`` (validated mission with its ``profile``), ``grid`` (x_range_m, y_range_m,
spacing_m, height_m), ``microphones`` (name → [x, y, z] m), ``ground`` (model,
flow_resistivity_kPa_s_m2, coherent), ``ground_as_written`` (the ``ground`` slice as the configuration
writes it, recorded in the metadata), ``atmosphere`` (isa_delta_K, relative_humidity_pct),
``absorption`` (bool), ``aircraft``.
"""

from __future__ import annotations

from nps.core.atmosphere import isa
from nps.mission.footprint import GroundGrid, mission_footprint
from nps.app.io import read_table, write_table
from nps.mission.propagation import Ground
from nps.mission.source_hemisphere import hemisphere_from_table
from nps.mission.trajectory import mission_path


def ground_model(spec: dict) -> Ground:
    """:class:`nps.mission.propagation.Ground` from the ``ground`` configuration slice (defaults filled)."""
    return Ground(spec["model"], float(spec["flow_resistivity_kPa_s_m2"]), bool(spec["coherent"]))


def run(inputs: dict, outputs: dict, params: dict) -> str:
    aircraft = params["aircraft"]
    path = mission_path(params["mission"], aircraft)
    hemispheres = {}
    for segment in dict.fromkeys(path.segments):
        key = f"hemisphere_{segment}"
        if key not in inputs:
            raise KeyError(f"footprint: input '{key}' (the source hemisphere of profile segment {segment}) is missing")
        hemispheres[segment] = hemisphere_from_table(read_table(inputs[key]), what=str(inputs[key]))
    g = params["grid"]
    grid = GroundGrid(tuple(g["x_range_m"]), tuple(g["y_range_m"]), float(g["spacing_m"]), float(g["height_m"]))
    atm = params["atmosphere"]
    c = isa(0.0, atm["isa_delta_K"], atm["relative_humidity_pct"]).speed_of_sound_mps
    fp = mission_footprint(path, hemispheres, grid, {k: tuple(v) for k, v in params["microphones"].items()}, c,
                           atm["isa_delta_K"], atm["relative_humidity_pct"], ground_model(params["ground"]),
                           absorption=bool(params["absorption"]))
    meta = {"aircraft": aircraft, "mission": params["mission"]["name"], "legs": fp.segments,
            "knots_m": path.knot_position_m.tolist(), "knot_time_s": path.knot_time_s.tolist(),
            "ground": dict(params["ground_as_written"]), "grid": dict(g), "inputs": sorted(str(v) for v in inputs.values())}
    write_table(fp.grid, outputs["grid"], stage="footprint", metadata=meta)
    write_table(fp.microphones, outputs["microphones"], stage="footprint", metadata=meta)
    write_table(fp.histories, outputs["histories"], stage="footprint", metadata=meta)
    write_table(fp.areas, outputs["areas"], stage="footprint", metadata=meta)
    fp.areas.to_csv(outputs["areas_csv"], index=False, float_format="%.3f")
    from nps.plots.footprint import footprint_figure

    for metric, key, name in (("sel_db", "sel_figure", "SEL"), ("lamax_db", "lamax_figure", "L_Amax")):
        footprint_figure(fp.grid, path.knot_position_m, fp.segments, metric,
                         f"{aircraft}: {params['mission']['name']} mission {name}", outputs[key],
                         segment_names={segment["id"]: segment["name"] for segment in params["mission"]["segments"]
                                        if "name" in segment})
    return (f"{len(fp.grid)} receivers, {len(fp.microphones)} microphones, legs {fp.segments}\n"
            f"{fp.areas.to_string(index=False)}\n{fp.microphones.to_string(index=False)}")
