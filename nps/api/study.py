"""A design study (config/studies/*.yaml, nps.app.designs) run in this process."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from nps.api.case import DEFAULT_CACHE, Case
from nps.app.designs import DesignStudy, load_study
from nps.app.trade import trade_tables


@dataclass(frozen=True)
class StudyResult:
    """The trade table (one row per design × aircraft × segment, ``pareto`` marked), the sensitivity per
    aircraft × segment × metric × variable (change per +10 %) and its ranking (nps.app.trade)."""

    table: pd.DataFrame
    sensitivity: pd.DataFrame
    ranking: pd.DataFrame


class Study:
    """``Study.from_file("config/studies/tip_speed_blades.yaml").run()`` runs every variant of the study
    (the same cases and stage cache as ``snakemake study_<name>``, one after the other) and returns a
    :class:`StudyResult`."""

    def __init__(self, study: DesignStudy, cache_dir: str | Path = DEFAULT_CACHE):
        self.study, self.cache_dir = study, Path(cache_dir)

    @classmethod
    def from_file(cls, path: str | Path, root: str | Path = ".", cache_dir: str | Path = DEFAULT_CACHE,
                  resolution: dict | None = None) -> "Study":
        """The validated, expanded study of ``path`` (base configuration paths relative to ``root``;
        ``resolution`` overrides fields of the variants' resolution, :func:`nps.app.designs.load_study`)."""
        return cls(load_study(path, root, resolution), cache_dir)

    @property
    def designs(self) -> pd.DataFrame:
        """One row per variant: id and variable values."""
        return pd.DataFrame([{"design": d.id, **d.values} for d in self.study.designs])

    def run(self, segments: list[str] | None = None) -> StudyResult:
        """Run every design × aircraft × segment (``segments``: a subset) and make the trade tables."""
        spec, rows = self.study.spec, []
        for design in self.study.designs:
            for aircraft in self.study.aircraft:
                case = Case(design.campaign, aircraft, self.cache_dir)
                for segment in segments or self.study.segments:
                    result = case.run(segment, tuple(spec["observer_sets"]), tuple(spec["products"]),
                                      {"design": design.id, **design.values})
                    rows.append(result.row)
        variables = {v.label: v.base_value for v in self.study.variables}
        return StudyResult(*trade_tables(rows, [d.id for d in self.study.designs], variables))
