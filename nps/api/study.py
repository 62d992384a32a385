"""A design study (config/studies/*.yaml, nps.app.designs) run in this process."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from nps.api.case import DEFAULT_CACHE
from nps.app.config import ConfigError
from nps.app.designs import DesignStudy, load_study
from nps.app.trade import refused_table, trade_tables
from nps.stages.case import REFUSALS, StageCache, design_rows


@dataclass(frozen=True)
class StudyResult:
    """The trade table (one row per design × aircraft × segment, ``pareto`` marked), the sensitivity per
    aircraft × segment × metric × variable (change per +10 %), its ranking and the refused designs
    (nps.app.trade)."""

    table: pd.DataFrame
    sensitivity: pd.DataFrame
    ranking: pd.DataFrame
    refused: pd.DataFrame


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

    def describe(self) -> str:
        """The study file, its size (designs × aircraft × segments) and estimated cost, in one line."""
        return self.study.describe()

    @property
    def designs(self) -> pd.DataFrame:
        """One row per variant: id and variable values."""
        return pd.DataFrame([{"design": d.id, **d.values} for d in self.study.designs])

    def _segments(self, segments: list[str] | str | None) -> list[str]:
        """The segments to run: the study's, or the subset ``segments`` (a name or a list of names)."""
        if segments is None:
            return self.study.segments
        chosen = [segments] if isinstance(segments, str) else list(segments)
        unknown = [s for s in chosen if s not in self.study.segments]
        if unknown or not chosen or len(set(chosen)) < len(chosen):
            got = f"got {unknown}" if unknown else ("got none" if not chosen else "got one twice")
            raise ConfigError(f"{self.study.file}: Study.run(segments={segments!r}): expected one or more of the study's "
                              f"segments {self.study.segments}, each once; {got}")
        return chosen

    def run(self, segments: list[str] | str | None = None) -> StudyResult:
        """Run every design × aircraft over the study's segments (``segments``: a subset, a name or a list of
        names) with the study's products, as the workflow's case jobs do (:func:`nps.stages.case.design_rows`),
        and make the trade tables; designs the validity envelope or a trim refuses are in ``refused``."""
        spec, rows, refused = self.study.spec, [], []
        segments = self._segments(segments)
        cache = StageCache(self.cache_dir)
        for design in self.study.designs:
            values = {"design": design.id, **design.values}
            for aircraft in self.study.aircraft:
                try:
                    table, _, _ = design_rows(design.campaign, aircraft, segments, values,
                                              spec["observer_sets"], spec["products"], cache)
                except REFUSALS as error:
                    refused.append((values, aircraft, str(error)))
                    continue
                rows.append(table)
        variables = {v.label: v.base_value for v in self.study.variables}
        if not rows:
            raise ValueError(f"study {self.study.name}: every design is refused; first: {refused[0][2]}")
        tables = trade_tables(rows, [d.id for d in self.study.designs], variables, spec.get("pareto"))
        return StudyResult(*tables, refused_table(refused, list(variables)))
