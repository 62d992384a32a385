"""The stage cache of design studies and the API (nps.stages.case.StageCache): reuse by content, complete
entries only, no entry from a failed stage, and the same bits when an entry is recomputed."""

from __future__ import annotations

import copy
import shutil
from pathlib import Path

import pytest
import yaml

import nps
from campaigns import TINY

REPO = Path(__file__).resolve().parents[2]


def _case(tmp_path: Path, cache: Path, **resolution) -> "nps.Case":
    config = copy.deepcopy(TINY)
    config["campaign"]["segments"] = ["seg2"]
    config["resolution"] = {**config["resolution"], "n_psi": 36, "n_r": 10, "samples_per_rev": 128, **resolution}
    path = tmp_path / f"config_{len(list(tmp_path.glob('config_*.yaml')))}.yaml"
    path.write_text(yaml.safe_dump(config))
    return nps.Case.from_files(REPO / "config/aircraft/helicopter.yaml", REPO / "config/missions/demo.yaml", path, cache_dir=cache)


def _what(result) -> dict:
    return {stage: what for stage, _, what, _ in result.log}


def test_second_run_reuses_every_stage_and_a_sampling_change_only_the_acoustics(tmp_path):
    cache = tmp_path / "cache"
    first = _case(tmp_path, cache).run("seg2")
    assert set(_what(first).values()) == {"computed"}
    again = _case(tmp_path, cache).run("seg2")
    assert set(_what(again).values()) == {"reused"}
    assert again.row.equals(first.row)
    finer = _case(tmp_path, cache, samples_per_rev=256).run("seg2")
    assert _what(finer) == {"trim": "reused", "loads": "reused", "observers": "reused", "acoustics": "computed",
                            "hsi": "computed", "metrics": "computed"}


def test_an_interrupted_entry_is_recomputed_to_the_same_bits(tmp_path):
    cache = tmp_path / "cache"
    first = _case(tmp_path, cache).run("seg2")
    entry = Path(first.artifacts["metrics"]["hemisphere"]["metrics"]).parent
    before = (entry / "metrics.parquet").read_bytes()
    (entry / ".complete").unlink()  # as if killed before the marker
    (entry / "metrics.parquet").write_bytes(b"half")
    again = _case(tmp_path, cache).run("seg2")
    assert _what(again)["metrics"] == "computed"
    assert (entry / "metrics.parquet").read_bytes() == before


def test_a_failed_stage_leaves_no_entry(tmp_path, monkeypatch):
    import nps.stages.case as case_module

    cache = tmp_path / "cache"
    original = case_module.stage_function

    def failing(stage):
        if stage == "acoustics":
            def broken(inputs, outputs, params):
                Path(outputs["signals"]).mkdir(parents=True, exist_ok=True)
                (Path(outputs["signals"]) / "main.parquet").write_bytes(b"partial")
                raise RuntimeError("disk full")
            return broken
        return original(stage)

    monkeypatch.setattr(case_module, "stage_function", failing)
    with pytest.raises(RuntimeError, match="disk full"):
        _case(tmp_path, cache).run("seg2")
    assert not any((cache / "acoustics").iterdir() if (cache / "acoustics").is_dir() else []) or \
        all(p.suffix == ".lock" for p in (cache / "acoustics").iterdir())
    assert all((entry / ".complete").is_file() for stage in ("trim", "loads") for entry in (cache / stage).iterdir() if entry.is_dir())


def test_a_design_outside_the_envelope_is_recorded_as_refused_not_failed(tmp_path):
    """A rotor too slow for segment 2's speed (advance ratio 0.53 > 0.5): the design job writes no rows and
    the reason, which the trade stage lists in refused.csv."""
    import dataclasses

    from nps.app.io import read_metadata, read_table
    from nps.stages import case as case_stage

    campaign = _case(tmp_path, tmp_path / "cache").campaign
    config = copy.deepcopy(campaign.config)
    config["campaign"]["allow_outside_validity"] = False
    aircraft = copy.deepcopy(campaign.aircraft)
    aircraft["helicopter"]["rotors"][0]["omega_rad_s"] = 10.0
    slow = dataclasses.replace(campaign, config=config, aircraft=aircraft)
    params = {"campaign": dataclasses.asdict(slow), "aircraft": "helicopter", "segments": ["seg2"],
              "design_values": {"design": "d0000000000", "omega": 10.0}, "observer_sets": ["hemisphere"],
              "products": ["performance", "noise"], "cache_dir": str(tmp_path / "cache")}
    out = tmp_path / "rows.parquet"
    case_stage.run({}, {"rows": out}, params)
    assert len(read_table(out)) == 0
    assert "advance ratio" in read_metadata(out)["refused"]
    assert not [p for p in (tmp_path / "cache" / "trim").iterdir() if p.is_dir()]  # the refused trim left no entry
