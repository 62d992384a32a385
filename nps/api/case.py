"""One aircraft in one mission under one campaign configuration, run segment by segment."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from nps.app.config import Campaign
from nps.app.designs import campaign_for_files
from nps.stages.case import CaseOutcome, StageCache, evaluate

DEFAULT_CACHE = Path("results/studies/cache")  # the workflow's stage cache, relative to the working directory


@dataclass(frozen=True)
class CaseResult:
    """Tables of one case: ``row`` (the trade-table row: performance and noise maxima, nps.app.trade.case_row),
    ``trim`` (one row per rotor), ``loads`` (rotor → loads summary: quantity, value, unit), ``metrics``
    (observer set → per-observer metrics), ``artifacts`` (stage → output name → path in the stage cache:
    trim, loads, metrics per observer set, nps.stages.case.run_chain) and ``log`` (stage, digest,
    computed/reused, seconds)."""

    row: pd.DataFrame
    trim: pd.DataFrame
    loads: dict
    metrics: dict
    artifacts: dict
    log: list

    @classmethod
    def from_outcome(cls, outcome: CaseOutcome, log: list) -> "CaseResult":
        artifacts = {key: ({k: a.paths for k, a in value.items()} if isinstance(value, dict) else value.paths)
                     for key, value in outcome.chain.items()}
        return cls(outcome.row, outcome.trim, outcome.loads, outcome.metrics, artifacts, list(log))


class Case:
    """An aircraft flying a mission under a campaign configuration (schema-validated like the workflow's).

    ``Case.from_files("my_heli.yaml", "my_mission.yaml", "config/config.yaml").run("seg2")`` trims the
    aircraft in segment ``seg2``, computes its loads (and wake and BVI loads where the configuration asks),
    radiates to the observer sets and returns a :class:`CaseResult`.
    """

    def __init__(self, campaign: Campaign, aircraft: str, cache_dir: str | Path = DEFAULT_CACHE):
        if aircraft not in campaign.aircraft:
            raise KeyError(f"aircraft '{aircraft}' is not in the campaign ({list(campaign.aircraft)})")
        self.campaign, self.aircraft, self.cache_dir = campaign, aircraft, Path(cache_dir)

    @classmethod
    def from_files(cls, aircraft: str | Path, mission: str | Path, config: str | Path = "config/config.yaml",
                   cache_dir: str | Path = DEFAULT_CACHE, resolution: dict | None = None) -> "Case":
        """The case of the aircraft file in the mission file under the campaign configuration file (its
        ``campaign`` section's aircraft and mission replaced by these; ``resolution`` overrides fields of
        its ``resolution`` section, e.g. nps.app.designs.PREVIEW_RESOLUTION). Errors name the file and field."""
        campaign = campaign_for_files(aircraft, mission, config, resolution)
        return cls(campaign, Path(aircraft).stem, cache_dir)

    @property
    def segments(self) -> list[str]:
        return list(self.campaign.segments)

    def run(self, segment: str, observer_sets: tuple[str, ...] = ("hemisphere",), design_values: dict | None = None) -> CaseResult:
        """Run (or reuse from the cache) the chain of ``segment``; ``design_values`` (label → value) lead the row."""
        if segment not in self.campaign.segments:
            raise KeyError(f"segment '{segment}' is not in the mission ({self.campaign.segments})")
        unknown = [s for s in observer_sets if s not in self.campaign.config["observer_sets"]]
        if unknown:
            raise KeyError(f"observer sets {unknown} are not in the configuration ({list(self.campaign.config['observer_sets'])})")
        cache = StageCache(self.cache_dir)
        outcome = evaluate(self.campaign, self.aircraft, segment, dict(design_values or {}), cache, list(observer_sets))
        return CaseResult.from_outcome(outcome, cache.log)
