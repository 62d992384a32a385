"""Observer-set stage: set centre, directions of any set, artifact and CLI errors (nps.noise.observers, nps.stages.observers)."""

from nps.app.config import load_aircraft
import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.__main__ import main as nps_main
from nps.noise.observers import ObserverError, lift_rotors, observer_centre, rotor_roles, with_directions
from nps.stages.observers import run as run_observers
from nps.core.frames import observer_direction
from nps.app.io import read_metadata, read_table, write_table
from tests.trim_tables import complete_trim


def trim_table(hubs: dict, velocity=(30.0, 0.0, -2.0)) -> pd.DataFrame:
    return pd.DataFrame({
        "rotor": list(hubs),
        **{f"hub_{a}_m": [h[i] for h in hubs.values()] for i, a in enumerate("xyz")},
        **{f"vel_{a}_mps": [velocity[i]] * len(hubs) for i, a in enumerate("xyz")},
    })


def test_centre_is_main_hub_for_helicopter_and_midpoint_for_tandem():
    """Helicopter: the antitorque rotor is not a lift rotor, centre = main hub; tandem: midpoint of the hubs."""
    heli = rotor_roles({"rotors": [{"name": "main", "role": "lift"}, {"name": "tail", "role": "antitorque"}]})
    trim = trim_table({"main": (0.1, 0.0, 1.8), "tail": (-9.9, 0.0, 1.9)})
    assert lift_rotors(heli) == ["main"]
    assert np.allclose(observer_centre(trim, lift_rotors(heli)), [0.1, 0.0, 1.8])
    tandem = trim_table({"front": (5.67, 0.0, 1.6), "rear": (-6.27, 0.0, 2.6)})
    assert np.allclose(observer_centre(tandem, ["front", "rear"]), [-0.3, 0.0, 2.1])
    with pytest.raises(ObserverError, match="rotor"):
        observer_centre(tandem, ["main"])


@settings(max_examples=50, deadline=None)
@given(st.floats(0.0, 359.0), st.floats(-89.0, 89.0), st.floats(1.0, 500.0))
def test_directions_invert_the_map_convention(az, el, dist):
    """azimuth/elevation recovered from positions (d = (−cos az cos el, −sin az cos el, sin el)) to 1e-9 deg."""
    centre = np.array([3.0, -1.0, 2.0])
    pos = centre + dist * observer_direction(np.radians(az), np.radians(el))
    table = with_directions(pd.DataFrame({"x_m": [pos[0]], "y_m": [pos[1]], "z_m": [pos[2]]}), centre)
    assert table["elevation_deg"].iloc[0] == pytest.approx(el, abs=1e-9)
    assert (table["azimuth_deg"].iloc[0] - az + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=1e-9)


def test_run_writes_every_set_kind_with_directions(tmp_path):
    """Hemisphere about the main hub at 10 R moving with the aircraft; ground grid gets directions too."""
    trim_path = tmp_path / "trim.parquet"
    write_table(complete_trim(trim_table({"main": (0.0, 0.0, 1.8), "tail": (-9.9, 0.0, 1.9)})), trim_path, stage="trim")

    def run(spec, roles, out):
        params = {"spec": spec, "rotor_roles": roles, "reference_radius_m": 7.62, "aircraft": "x", "segment": "seg1",
                  "obsset": out.stem, "rotors": {r["name"]: r for r in load_aircraft("config/aircraft/helicopter.yaml")["rotors"]}}
        run_observers({"trim": trim_path}, {"observers": out}, params)
        return read_table(out)

    hemi = run({"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 3, "n_azimuth": 4}, {"main": "lift", "tail": "antitorque"},
               tmp_path / "hemi.parquet")
    rel = hemi[["x_m", "y_m", "z_m"]].to_numpy() - [0.0, 0.0, 1.8]
    assert np.allclose(np.linalg.norm(rel, axis=1), 76.2) and (hemi["vx_mps"] == 30.0).all()
    assert read_metadata(tmp_path / "hemi.parquet")["centre_rotors"] == ["main"]
    grid = run({"kind": "ground_grid", "height_below_m": 150.0, "x_range_m": [-300.0, 300.0], "y_range_m": [-300.0, 300.0],
                "n_x": 3, "n_y": 3, "moving": False}, {"main": "lift"}, tmp_path / "ground.parquet")
    below = read_table(tmp_path / "ground.parquet").set_index(["grid_x_m", "grid_y_m"])
    assert below.loc[(0.0, 0.0), "elevation_deg"] == pytest.approx(-90.0)
    # ahead of and to starboard of the hub: azimuth 180 deg and 90 deg
    assert below.loc[(300.0, 0.0), "azimuth_deg"] == pytest.approx(180.0)
    assert below.loc[(0.0, -300.0), "azimuth_deg"] == pytest.approx(90.0)
    assert (grid[["vx_mps", "vy_mps", "vz_mps"]].to_numpy() == 0.0).all()


def test_cli_names_a_missing_set(tmp_path, capsys):
    config = tmp_path / "config.yaml"
    config.write_text("observer_sets:\n  hemisphere: {kind: hemisphere, radius_R: 10.0, n_elevation: 3, n_azimuth: 4}\n")
    code = nps_main(["observers", "--config", str(config), "--set", "carpet", "--aircraft", "config/aircraft/helicopter.yaml",
                     "--trim", str(tmp_path / "trim.parquet"), "--out", str(tmp_path / "o.parquet")])
    assert code == 2 and "no set named 'carpet'" in capsys.readouterr().err
