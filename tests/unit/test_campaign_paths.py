"""Flight paths in the campaign (nps.app.config.Campaign.with_paths): states as segments, shared keys, the load
variant by advance ratio, and the aircraft check."""

import pytest

from nps.app.config import ConfigError, load_campaign, load_path, read_yaml

PATHS = ("helicopter_approach_6deg", "helicopter_approach_9deg", "hexacopter_transition")


@pytest.fixture(scope="module")
def campaign():
    base = load_campaign(read_yaml("config/config.yaml"), "config/config.yaml", root=".")
    return base.with_paths({name: load_path(f"config/paths/{name}.yaml") for name in PATHS})


def test_states_are_segments_with_the_speeds_of_their_aircraft(campaign):
    key = campaign.path_keys["helicopter_approach_6deg"][0]
    segment = campaign.segment(key)
    assert segment["id"] == key and list(segment["aircraft"]) == ["helicopter"]
    speeds = segment["aircraft"]["helicopter"]
    assert speeds["forward_speed_mps"] == pytest.approx(25.8, abs=0.2) and "acceleration_mps2" in speeds
    # the level flight at 25.8 m/s opens both helicopter approaches: one state, one key
    assert key in campaign.path_keys["helicopter_approach_9deg"]


def test_slow_states_radiate_the_trimmed_loads(campaign):
    """Path states below paths.bvi_min_advance_ratio (0.08) radiate the trimmed loads, the others the BVI loads."""
    threshold = campaign.config["paths"]["bvi_min_advance_ratio"]
    variants = {key: campaign.variants(key) for key in campaign.path_keys["hexacopter_transition"]}
    slow = [k for k in variants if campaign.path_states[k]["advance_ratio"] < threshold]
    fast = [k for k in variants if k not in slow]
    assert slow and fast
    assert all(variants[k] == ["base"] for k in slow) and all(variants[k] == ["bvi"] for k in fast)


def test_a_path_of_an_aircraft_outside_the_campaign_is_refused():
    base = load_campaign(read_yaml("config/config.yaml"), "config/config.yaml", root=".")
    path = dict(load_path("config/paths/helicopter_approach_6deg.yaml"), aircraft="gyrocopter")
    with pytest.raises(ConfigError, match="helicopter_approach_6deg.yaml: aircraft: expected an aircraft of the campaign"):
        base.with_paths({"helicopter_approach_6deg": path})
