"""Stage parameters (nps.app.plan): one plan for rules, studies and the API; job digests."""

from __future__ import annotations

from pathlib import Path

import pytest
import yaml

from nps.app.config import load_campaign
from nps.app.plan import PARAMS, CaseConfig, job_digest, stage_params

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def campaign():
    return load_campaign(yaml.safe_load((REPO / "config/config.yaml").read_text()), REPO / "config/config.yaml", REPO)


def test_job_digest_is_canonical_and_covers_code_params_and_inputs():
    params = {"n_psi": 360, "rotors": {"main": {"radius_m": 7.62}}}
    reordered = {"rotors": {"main": {"radius_m": 7.62}}, "n_psi": 360}
    base = job_digest("loads", "abc", params, {"trim": "t1"})
    assert base == job_digest("loads", "abc", reordered, {"trim": "t1"})
    assert base != job_digest("loads", "abd", params, {"trim": "t1"})
    assert base != job_digest("loads", "abc", {**params, "n_psi": 361}, {"trim": "t1"})
    assert base != job_digest("loads", "abc", params, {"trim": "t2"})
    assert base != job_digest("loads", "abc", {**params, "rotors": {"main": {"radius_m": 7.620000000001}}}, {"trim": "t1"})


def test_a_segment_speed_reaches_the_trim_only_through_its_own_segment(campaign):
    seg2, seg3 = (CaseConfig.from_campaign(campaign, "helicopter", s) for s in ("seg2", "seg3"))
    assert stage_params("trim", seg2)["speeds"] != stage_params("trim", seg3)["speeds"]
    for stage in ("loads", "wake", "acoustics", "hsi", "metrics"):
        assert stage_params(stage, seg2) == stage_params(stage, seg3)  # the segment enters through the inputs


def test_observer_sampling_reaches_no_stage_before_the_acoustics(campaign):
    import copy
    import dataclasses

    config = copy.deepcopy(campaign.config)
    config["resolution"]["samples_per_rev"] = 512
    finer = dataclasses.replace(campaign, config=config)
    a, b = (CaseConfig.from_campaign(c, "helicopter", "seg3") for c in (campaign, finer))
    for stage in ("trim", "loads", "wake"):
        assert stage_params(stage, a) == stage_params(stage, b)
    assert stage_params("acoustics", a) != stage_params("acoustics", b)


def test_incoherent_aircraft_pass_the_tone_sum_and_coherent_ones_nothing(campaign):
    hexa = CaseConfig.from_campaign(campaign, "hexacopter", "seg2")
    heli = CaseConfig.from_campaign(campaign, "helicopter", "seg2")
    assert stage_params("metrics", hexa)["tone_sum"] == "incoherent" and "tone_sum" in stage_params("tones", hexa)
    assert stage_params("source_hemisphere", hexa)["tone_sum"] == "incoherent"  # footprints and certification too
    assert "tone_sum" not in stage_params("metrics", heli) and "phases_deg" not in stage_params("acoustics", heli)


def test_unknown_stage_is_refused(campaign):
    with pytest.raises(KeyError, match="no parameter plan for stage 'nope'"):
        stage_params("nope", CaseConfig.from_campaign(campaign, "helicopter", "seg2"))
    assert {"trim", "loads", "wake", "observers", "acoustics", "hsi", "metrics", "tones"} <= set(PARAMS)
