"""The notebook API of flight paths (nps.api.FlightPathCase): a short decelerating path flown by the helicopter at a
coarse resolution through the stage cache — the path, each state's chain and the footprint — and reused whole
on a second run; the path's aircraft must be the aircraft file's."""

from pathlib import Path

import numpy as np
import pytest
import yaml

from nps.api import FlightPathCase
from nps.app.config import ConfigError

REPO = Path(__file__).resolve().parents[2]
RESOLUTION = {"n_psi": 72, "n_r": 16, "wake_revolutions": 2, "samples_per_rev": 256}
PATH = {"name": "short_deceleration", "aircraft": "helicopter",
        "start": {"position_m": [-600.0, 0.0], "height_m": 120.0, "heading_deg": 0.0, "speed_mps": 30.0},
        "legs": [{"straight": {"duration_s": 4.0}}, {"straight": {"duration_s": 6.0}, "end_speed_mps": 25.0}],
        "receivers": {"grid": {"x_range_m": [-600.0, 200.0], "y_range_m": [-400.0, 400.0], "spacing_m": 200.0},
                      "microphones": {"under": [-300.0, 0.0, 1.2]}}}


@pytest.fixture
def files(tmp_path):
    config = yaml.safe_load((REPO / "config/config.yaml").read_text())
    config["observer_sets"]["source"].update(n_elevation=4, n_azimuth=8)
    config["campaign"]["allow_outside_validity"] = True  # 2 wake turns at this coarse resolution
    (tmp_path / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    (tmp_path / "short_deceleration.yaml").write_text(yaml.safe_dump(PATH, sort_keys=False))
    return tmp_path


@pytest.mark.slow
def test_a_path_runs_and_is_reused(files):
    """End to end (~10 s with compiled kernels, ~55 s compiling them): slow."""
    case = FlightPathCase.from_files(REPO / "config/aircraft/helicopter.yaml", files / "short_deceleration.yaml",
                                     files / "config.yaml", REPO / "config/missions/demo.yaml", cache_dir=files / "cache",
                                     resolution=RESOLUTION)
    first = case.run()
    keys = case.campaign.path_keys["short_deceleration"]
    assert len(keys) >= 2 and set(first.history["state"]) <= set(keys)
    assert sum(stage == "source_hemisphere" for stage, *_ in first.log) == len(keys)
    assert len(first.grid) == 25 and np.isfinite(first.grid["sel_db"]).all()
    under = first.microphones.set_index("microphone").loc["under"]
    assert 60.0 < under["lamax_db"] < 120.0 and under["sel_db"] > under["lamax_db"] - 10.0
    again = case.run()
    assert all(what == "reused" for _, _, what, _ in again.log)
    assert again.grid.equals(first.grid) and again.microphones.equals(first.microphones)
    assert Path(first.figures["plan_figure"]).is_file()


def test_the_path_must_be_the_aircraft_files(files):
    with pytest.raises(ConfigError, match="short_deceleration.yaml: aircraft: expected the aircraft of .*coaxial"):
        FlightPathCase.from_files(REPO / "config/aircraft/coaxial.yaml", files / "short_deceleration.yaml",
                                  files / "config.yaml", REPO / "config/missions/demo.yaml", cache_dir=files / "cache")
