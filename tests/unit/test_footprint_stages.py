"""Stages ``footprint`` and ``certification`` and their commands on synthetic source hemispheres."""

import numpy as np
import pandas as pd
import pytest

from nps.__main__ import main as nps_main
from nps.app.io import read_metadata, read_table, write_table
from nps.mission.source_hemisphere import COLUMNS
from nps.stages import stage_function
from nps.noise.spectra import third_octave_bands
from tests.unit.test_footprint import omnidirectional

# the hard ground of the footprint section, defaults filled (nps.app.config.fill_defaults)
GROUND = {"model": "hard", "flow_resistivity_kPa_s_m2": 200.0, "coherent": True}

MISSION = {
    "name": "mini",
    "segments": [
        {"id": "seg1", "aircraft": {"heli": {"forward_speed_mps": 40.0, "climb_speed_mps": 4.0}}},
        {"id": "seg2", "aircraft": {"heli": {"forward_speed_mps": 45.0, "climb_speed_mps": 0.0}}},
        {"id": "seg3", "aircraft": {"heli": {"forward_speed_mps": 25.0, "climb_speed_mps": -2.63}}},
    ],
    "profile": [{"segment": "seg1", "distance_m": 1000.0, "start_altitude_m": 100.0},
                {"segment": "seg2", "distance_m": 1500.0}],
}


def product(level_db, velocity, path):
    """A source-hemisphere product file of an omnidirectional 1 kHz source (columns of the schema)."""
    h = omnidirectional(level_db, velocity)
    el, az, band = np.meshgrid(h.elevation_deg, h.azimuth_deg, h.band_numbers, indexing="ij")
    n_obs = el.shape[0] * el.shape[1]
    table = pd.DataFrame({
        "observer": np.repeat(np.arange(n_obs, dtype=np.int32), h.band_numbers.size),
        "azimuth_deg": az.ravel(), "elevation_deg": el.ravel(), "source": "total", "band": band.ravel().astype(np.int32),
        "center_hz": third_octave_bands(band.ravel())["center_hz"], "level_db": h.levels_db.ravel(),
        "radius_m": h.radius_m, "vel_x_mps": velocity[0], "vel_z_mps": velocity[2], "speed_of_sound_mps": 340.0,
    })[list(COLUMNS)]
    write_table(table, path, stage="source_hemisphere")
    return str(path)


@pytest.fixture
def hemispheres(tmp_path):
    return {s["id"]: product(95.0 - 3.0 * i, (s["aircraft"]["heli"]["forward_speed_mps"], 0.0, s["aircraft"]["heli"]["climb_speed_mps"]),
                             tmp_path / f"{s['id']}.parquet") for i, s in enumerate(MISSION["segments"])}


def test_footprint_stage(tmp_path, hemispheres):
    """The stage writes every artifact; the grid is left-right symmetric; leg SELs add up to the
    mission SEL; a missing profile hemisphere is named."""
    out = {k: str(tmp_path / f"fp_{k}.parquet") for k in ("grid", "microphones", "histories", "areas")}
    out.update(areas_csv=str(tmp_path / "areas.csv"), sel_figure=str(tmp_path / "sel.png"), lamax_figure=str(tmp_path / "lamax.png"))
    params = {"mission": MISSION, "aircraft": "heli",
              "grid": {"x_range_m": [-500.0, 3000.0], "y_range_m": [-1000.0, 1000.0], "spacing_m": 250.0, "height_m": 1.2},
              "microphones": {"m": [500.0, 0.0, 1.2]}, "ground": GROUND, "ground_as_written": {"model": "hard"},
              "atmosphere": {"isa_delta_K": 0.0, "relative_humidity_pct": 70.0}, "absorption": True}
    inputs = {"hemisphere_seg1": hemispheres["seg1"], "hemisphere_seg2": hemispheres["seg2"]}
    report = stage_function("footprint")(inputs, out, params)
    assert "legs ['seg1', 'seg2']" in report
    grid = read_table(out["grid"])
    sel = grid.set_index(["x_m", "y_m"])["sel_db"]
    assert np.abs(sel.to_numpy() - sel.reindex(list(zip(grid["x_m"], -grid["y_m"]))).to_numpy()).max() < 1e-9
    legs = 10 * np.log10(10 ** (grid["leg0_sel_db"] / 10) + 10 ** (grid["leg1_sel_db"] / 10))
    assert np.abs(legs - grid["sel_db"]).max() < 1e-9
    assert read_metadata(out["grid"])["legs"] == ["seg1", "seg2"]
    assert list(pd.read_csv(out["areas_csv"]).columns) == ["metric", "level_db", "area_km2", "open"]
    with pytest.raises(KeyError, match="hemisphere_seg2"):
        stage_function("footprint")({"hemisphere_seg1": hemispheres["seg1"]}, out, params)


def test_certification_stage_and_command(tmp_path, hemispheres):
    """Stage: three procedures, margin = limit − EPNL, sidelines equal for a symmetric source. The
    command runs the same stage and reports a bad segment name as one error line (exit 2)."""
    out_dir = tmp_path / "cert"
    mission_file = tmp_path / "mini.yaml"
    import yaml

    mission_file.write_text(yaml.safe_dump(MISSION))
    aircraft_file = tmp_path / "heli.yaml"
    argv = ["certification", "--aircraft", str(aircraft_file), "--mission", str(mission_file),
            "--takeoff-hemisphere", hemispheres["seg1"], "--overflight-hemisphere", hemispheres["seg2"],
            "--approach-hemisphere", hemispheres["seg3"], "--out-dir", str(out_dir)]
    inputs = {"hemisphere_takeoff": hemispheres["seg1"], "hemisphere_overflight": hemispheres["seg2"],
              "hemisphere_approach": hemispheres["seg3"]}
    outputs = {"summary": str(out_dir / "c.parquet"), "summary_csv": str(out_dir / "c.csv"),
               "microphones": str(out_dir / "m.parquet"), "histories": str(out_dir / "h.parquet"),
               "pnlt_figure": str(out_dir / "p.png"), "table_figure": str(out_dir / "t.png")}
    params = {"mission": MISSION, "aircraft": "heli", "max_mass_kg": 5000.0,
              "segments": {"takeoff": "seg1", "overflight": "seg2", "approach": "seg3"}, "vne_mps": None,
              "approach_min_speed_mps": None, "ground": GROUND, "ground_as_written": {"model": "hard"},
              "absorption": True}
    stage_function("certification")(inputs, outputs, params)
    summary = read_table(outputs["summary"])
    assert list(summary["procedure"]) == ["takeoff", "overflight", "approach"]
    assert np.allclose(summary["margin_db"], summary["limit_db"] - summary["epnl_db"])
    assert np.allclose(summary["epnl_port_db"], summary["epnl_starboard_db"], atol=1e-9)
    hist = read_table(outputs["histories"])
    assert set(hist["microphone"]) == {"centre", "port", "starboard"}
    assert nps_main(argv) == 2  # the aircraft file does not exist: one error line, no traceback
