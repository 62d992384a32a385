"""A flight path flown by its aircraft under a campaign configuration (docs/reference/paths.md)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from nps.api.case import DEFAULT_CACHE
from nps.app.config import Campaign, ConfigError, load_path
from nps.app.designs import campaign_for_files
from nps.app.io import read_table
from nps.stages.case import StageCache, path_product


@dataclass(frozen=True)
class PathResult:
    """Tables of a flown path: ``history`` (one row per time step, its states and weights), ``states`` (one row
    per state × rotor: the state's trim), ``grid`` (L_Amax, SEL per receiver and leg), ``microphones`` (SEL,
    L_Amax, EPNL …), ``histories`` (L_A(t), PNLT(t) per microphone), ``areas`` (contour areas), ``figures``
    (name → PNG path in the stage cache) and ``log`` (stage, digest, computed/reused, seconds)."""

    history: pd.DataFrame
    states: pd.DataFrame
    grid: pd.DataFrame
    microphones: pd.DataFrame
    histories: pd.DataFrame
    areas: pd.DataFrame
    figures: dict
    log: list


class FlightPathCase:
    """A path file's aircraft flying it under a campaign configuration (schema-validated like the workflow's).

    ``FlightPathCase.from_files("config/aircraft/helicopter.yaml", "config/paths/my_approach.yaml").run()``
    plans the path's quasi-static trim states, runs each state's chain to its source hemisphere and flies the path
    to its receivers, through the workflow's stage functions and the stage cache (a state computed for another path
    or procedure is reused)."""

    def __init__(self, campaign: Campaign, path: str, cache_dir: str | Path = DEFAULT_CACHE):
        if path not in campaign.paths:
            raise KeyError(f"path '{path}' is not planned in the campaign ({list(campaign.paths)})")
        self.campaign, self.path, self.cache_dir = campaign, path, Path(cache_dir)

    @classmethod
    def from_files(cls, aircraft: str | Path, path: str | Path, config: str | Path = "config/config.yaml",
                   mission: str | Path = "config/missions/demo.yaml", cache_dir: str | Path = DEFAULT_CACHE,
                   resolution: dict | None = None) -> "FlightPathCase":
        """The path file flown by the aircraft file under the configuration file (``mission`` only completes the
        campaign; ``resolution`` overrides fields of its ``resolution`` section). Errors name the file and field;
        the path's ``aircraft`` must be the aircraft file's name."""
        campaign = campaign_for_files(aircraft, mission, config, resolution)
        spec = load_path(path, campaign.config["paths"]["dt_s"])
        if spec["aircraft"] not in campaign.aircraft:
            raise ConfigError(f"{path}: aircraft: expected the aircraft of {aircraft} ('{Path(aircraft).stem}'), "
                              f"got '{spec['aircraft']}'")
        return cls(campaign.with_paths({spec["name"]: spec}), spec["name"], cache_dir)

    def run(self) -> PathResult:
        """Run (or reuse from the cache) the path, its states and its footprint."""
        cache = StageCache(self.cache_dir)
        product = path_product(self.campaign, self.path, cache)
        path, footprint = product["path"].paths, product["footprint"].paths
        return PathResult(read_table(path["history"]), read_table(path["states"]),
                          *(read_table(footprint[name]) for name in ("grid", "microphones", "histories", "areas")),
                          {name: footprint[name] for name in ("plan_figure", "history_figure")}, list(cache.log))
