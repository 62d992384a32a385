"""Stage ``case``: the whole chain of one aircraft in one segment in one process, through a stage cache.

The design studies' jobs (workflow/rules/designs.smk) and the Python API (:class:`nps.api.Case`) run the
same stage functions as the campaign's rules (``nps.stages.<stage>.run`` with
:func:`nps.app.plan.stage_params`): trim → loads → wake and BVI loads (BVI segments) → observers →
acoustics → HSI (HSI segments) → metrics, for the load variant of the product (with BVI wherever it is
computed); with the ``certification`` and ``footprint`` products, the source hemispheres of the procedures'
(or the mission profile's) segments and the aircraft's Chapter 8 certification (or mission footprint).

Stage cache: every stage job is stored under ``<cache>/<stage>/<digest>/`` where the digest
(:func:`nps.app.plan.job_digest`) covers the stage's code, its params and its inputs' digests. A job whose
digest is there is not run again, so variants that differ in a field the stage does not read (a segment
speed for another segment, the observer sampling for the loads) share its artifacts. An entry counts once
its marker file ``.complete`` is written, after the stage returned: a failed job's entry is removed, an
interrupted one's is found without its marker and computed again. A file lock per entry lets concurrent
jobs wait for each other instead of computing it twice.

One job runs every segment of a design's aircraft (a process start-up per design and aircraft, not per
stage or segment).

inputs: none. outputs: ``rows`` (the trade-table rows of the aircraft in ``segments``, in that order,
:func:`nps.app.trade.case_row`; metadata ``stage_digests``: segment → stage → digest of the cache entry
used; a design that a validity check or a trim refuses in any segment (:data:`REFUSALS`) gets no rows and
the message as metadata ``refused``). params: ``campaign`` (the validated campaign of the design as plain values: config, aircraft,
mission, segments, written), ``aircraft``, ``segments``, ``design_values`` (design id and variable label →
value), ``observer_sets`` (sets whose maxima enter the rows), ``products``, ``cache_dir``.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from nps.app.config import Campaign
from nps.app.io import read_metadata, read_table, rotor_path, write_table
from nps.app.plan import CaseConfig, job_digest, metrics_reads_disks, stage_params
from nps.app.trade import case_row, certification_columns, footprint_columns
from nps.app.trade import procedure_row as trade_procedure_row
from nps.app.validity import ValidityError
from nps.rotor.bet import TrimError
from nps.rotor.trim import AircraftTrimError
from nps.stages import stage_function
from nps.stages.code import stage_digest

COMPLETE = ".complete"  # written last into a cache entry: the entry is whole
# what refuses a design (outside the models' validity envelope, or a trim that has no solution): the design is
# listed with the message in the study's refused.csv and left out of its trade table
REFUSALS = (ValidityError, TrimError, AircraftTrimError)

# file and directory names of each stage's outputs inside its cache entry
OUTPUTS = {
    "trim": {"trim": "trim.parquet"},
    "loads": {"loads": "loads"},
    "wake": {"wake": "wake", "bvi": "bvi"},
    "observers": {"observers": "observers.parquet"},
    "acoustics": {"signals": "signals"},
    "hsi": {"hsi": "hsi"},
    "metrics": {"metrics": "metrics.parquet", "bands": "bands.parquet"},
    "source_hemisphere": {"hemisphere": "source_hemisphere.parquet"},
    "certification": {"summary": "certification.parquet", "summary_csv": "certification.csv",
                      "microphones": "microphones.parquet", "histories": "histories.parquet",
                      "pnlt_figure": "pnlt.png", "table_figure": "certification.png"},
    "footprint": {"grid": "grid.parquet", "microphones": "microphones.parquet", "histories": "histories.parquet",
                  "areas": "areas.parquet", "areas_csv": "areas.csv", "sel_figure": "sel.png", "lamax_figure": "lamax.png"},
    "path": {"history": "path_history.parquet", "states": "path_states.parquet"},
    "path_footprint": {"grid": "grid.parquet", "microphones": "microphones.parquet", "histories": "histories.parquet",
                       "areas": "areas.parquet", "plan_figure": "plan.png", "history_figure": "histories.png"},
}


@dataclass(frozen=True)
class Artifact:
    """A cached stage job: its digest and output name → path."""

    digest: str
    paths: dict


@dataclass
class StageCache:
    """Content-addressed stage artifacts under ``root`` (see the module docstring); ``log`` lists what each
    :meth:`run` did (stage, digest, ``computed`` or ``reused``, seconds)."""

    root: Path
    log: list = field(default_factory=list)

    @contextmanager
    def _locked(self, stage: str, digest: str):
        folder = self.root / stage
        folder.mkdir(parents=True, exist_ok=True)
        with open(folder / f"{digest}.lock", "w") as handle:
            fcntl.flock(handle, fcntl.LOCK_EX)
            try:
                yield folder / digest
            finally:
                fcntl.flock(handle, fcntl.LOCK_UN)

    def run(self, stage: str, inputs: dict[str, tuple[Artifact, str]], params: dict) -> Artifact:
        """Run ``stage`` on ``inputs`` (input name → (artifact, its output name)) with ``params`` (wildcards
        included), or reuse the cached result."""
        digests = {name: artifact.digest for name, (artifact, _) in inputs.items()}
        digest = job_digest(stage, stage_digest(stage), params, digests)
        started = time.perf_counter()
        with self._locked(stage, digest) as final:
            paths = {name: final / leaf for name, leaf in OUTPUTS[stage].items()}
            if (final / COMPLETE).is_file():
                self.log.append((stage, digest, "reused", time.perf_counter() - started))
                return Artifact(digest, paths)
            shutil.rmtree(final, ignore_errors=True)  # an interrupted job's remains
            final.mkdir()
            try:
                stage_function(stage)({name: artifact.paths[key] for name, (artifact, key) in inputs.items()}, paths, params)
            except BaseException:
                shutil.rmtree(final, ignore_errors=True)
                raise
            (final / COMPLETE).write_text(f"{stage} {digest}\n")
        self.log.append((stage, digest, "computed", time.perf_counter() - started))
        return Artifact(digest, paths)


def campaign_from_params(values: dict) -> Campaign:
    """The :class:`Campaign` a ``campaign`` param holds (its fields as plain values)."""
    return Campaign(**values)


def run_chain(campaign: Campaign, aircraft: str, segment: str, cache: StageCache, observer_sets: list[str],
              source_set: bool = False) -> dict:
    """Run (or reuse) every stage of ``aircraft`` in ``segment`` for the product variant; returns
    ``{"trim": Artifact, "loads": Artifact, "acoustics": {obsset: Artifact}, "metrics": {obsset: Artifact},
    "source_hemisphere": Artifact}``
    (the last with ``source_set``)."""
    case = CaseConfig.from_campaign(campaign, aircraft, segment)
    same = {"aircraft": aircraft, "segment": segment}
    variant = campaign.variants(segment)[-1]
    trim = cache.run("trim", {}, {**stage_params("trim", case), **same})
    loads = cache.run("loads", {"trim": (trim, "trim")}, {**stage_params("loads", case), **same})
    disks = (loads, "loads")
    if variant == "bvi":
        wake = cache.run("wake", {"trim": (trim, "trim"), "loads": disks}, {**stage_params("wake", case), **same})
        disks = (wake, "bvi")
    hsi_segment = segment in campaign.hsi_segments()
    bpm = metrics_reads_disks(campaign.config)
    result = {"trim": trim, "loads": loads, "acoustics": {}, "metrics": {}}
    sets = list(observer_sets) + ([campaign.config["footprint"]["source_set"]] if source_set else [])
    for obsset in dict.fromkeys(sets):
        where = {**same, "obsset": obsset}
        observers = cache.run("observers", {"trim": (trim, "trim")}, {**stage_params("observers", case, obsset), **where})
        base = {"trim": (trim, "trim"), "observers": (observers, "observers")}
        where = {**where, "variant": variant}
        signals = cache.run("acoustics", {"disks": disks, **base}, {**stage_params("acoustics", case), **where})
        result["acoustics"][obsset] = signals
        inputs = {"signals": (signals, "signals"), **base}
        if hsi_segment:
            inputs["hsi"] = (cache.run("hsi", {"signals": (signals, "signals"), **base},
                                       {**stage_params("hsi", case), **where}), "hsi")
        inputs.update({"disks": disks} if bpm else {})
        if obsset in observer_sets:
            result["metrics"][obsset] = cache.run("metrics", inputs, {**stage_params("metrics", case), **where})
        if source_set and obsset == sets[-1]:
            result["source_hemisphere"] = cache.run("source_hemisphere", inputs,
                                                    {**stage_params("source_hemisphere", case), **same})
    return result


def warnings_of(artifacts: list[Artifact]) -> list[str]:
    """The warnings recorded in the metadata of the artifacts' Parquet files (sorted, unique): validity
    findings run under ``allow_outside_validity`` and model-range notes (``model_warnings``)."""
    found = set()
    for artifact in artifacts:
        for path in artifact.paths.values():
            files = sorted(Path(path).glob("*.parquet")) if Path(path).is_dir() else [Path(path)]
            for meta in map(read_metadata, (f for f in files if f.suffix == ".parquet")):
                found.update(w["message"] for w in (meta["validity_warnings"] if "validity_warnings" in meta else []))
                found.update(str(w) for w in (meta["model_warnings"] if "model_warnings" in meta else []))
    return sorted(found)


@dataclass(frozen=True)
class CaseOutcome:
    """What a case produced: its trade-table ``row``, the ``trim`` table, the rotors' loads summaries
    (rotor → table), the metrics tables (observer set → table) and the ``chain`` of artifacts
    (:func:`run_chain`)."""

    row: pd.DataFrame
    trim: pd.DataFrame
    loads: dict
    metrics: dict
    chain: dict


def evaluate(campaign: Campaign, aircraft: str, segment: str, design_values: dict, cache: StageCache,
             observer_sets: list[str]) -> CaseOutcome:
    """Run (or reuse) the chain of a case and make its trade-table row (:func:`nps.app.trade.case_row`)."""
    chain = run_chain(campaign, aircraft, segment, cache, list(observer_sets))
    trim = read_table(chain["trim"].paths["trim"])
    loads = {name: read_table(rotor_path(chain["loads"].paths["loads"], name, "_summary"))
             for name in campaign.rotor_names(aircraft)}
    metrics = {obsset: read_table(artifact.paths["metrics"]) for obsset, artifact in chain["metrics"].items()}
    row = case_row(campaign, aircraft, segment, design_values, trim, loads, metrics,
                   warnings_of([chain["trim"], chain["loads"], *chain["metrics"].values()]))
    return CaseOutcome(row, trim, loads, metrics, chain)


def mission_product(stage: str, campaign: Campaign, aircraft: str, cache: StageCache) -> Artifact:
    """An aircraft-level product from source hemispheres: ``certification`` (Chapter 8, the procedures'
    segments ``certification.segments``, inputs ``hemisphere_<procedure>``) or ``footprint`` (the mission
    profile's segments, inputs ``hemisphere_<segment>``); each hemisphere through :func:`run_chain`."""
    if stage == "certification":
        segments = dict(campaign.config["certification"]["segments"])
    else:
        segments = {leg["segment"]: leg["segment"] for leg in campaign.mission["profile"]}
    hemispheres = {}
    for name, segment in segments.items():
        chain = run_chain(campaign, aircraft, segment, cache, [], source_set=True)
        hemispheres[f"hemisphere_{name}"] = (chain["source_hemisphere"], "hemisphere")
    case = CaseConfig.from_campaign(campaign, aircraft)
    return cache.run(stage, hemispheres, {**stage_params(stage, case), "aircraft": aircraft})


def path_product(campaign: Campaign, path: str, cache: StageCache) -> dict:
    """The noise of ``path`` (a path of ``campaign.paths``, :meth:`nps.app.config.Campaign.with_paths`): the
    ``path`` stage, every state's chain with its source hemisphere (:func:`run_chain`, the state key as the
    segment) and ``path_footprint``, with the workflow's params (rules path and path_footprint). Returns
    ``{"path": Artifact, "footprint": Artifact, "chains": {state key: chain}}``."""
    spec = campaign.paths[path]
    aircraft = spec["aircraft"]
    case = CaseConfig.from_campaign(campaign, aircraft)
    named = {"aircraft": aircraft, "path_config": spec, "path": path}
    history = cache.run("path", {}, {**stage_params("path", case), **named})
    chains = {key: run_chain(campaign, aircraft, key, cache, [], source_set=True) for key in campaign.path_keys[path]}
    hemispheres = {f"hemisphere_{key}": (chain["source_hemisphere"], "hemisphere") for key, chain in chains.items()}
    footprint = cache.run("path_footprint", {"history": (history, "history"), **hemispheres},
                          {**stage_params("path_footprint", case), **named})
    return {"path": history, "footprint": footprint, "chains": chains}


def procedure_row(campaign: Campaign, path: str, design_values: dict, cache: StageCache) -> pd.DataFrame:
    """The trade-table row of a flown path (:func:`path_product`, :func:`nps.app.trade.procedure_row`): the
    states' rotor power from their loads summaries, the path's duration and distance from its legs."""
    from nps.mission.paths import flight_path_history, path_spec

    spec = campaign.paths[path]
    product = path_product(campaign, path, cache)
    rotors = campaign.rotor_names(spec["aircraft"])
    power = {key: sum(float(table.loc[table["quantity"] == "power_W", "value"].iloc[0])
                      for table in (read_table(rotor_path(chain["loads"].paths["loads"], rotor, "_summary")) for rotor in rotors))
             for key, chain in product["chains"].items()}
    legs, _ = flight_path_history(path_spec(spec), campaign.config["paths"]["dt_s"])
    duration = legs[-1].t0_s + legs[-1].duration_s
    distance = sum(leg.speed0_mps * leg.duration_s + 0.5 * leg.accel_mps2 * leg.duration_s**2 for leg in legs)
    footprint = product["footprint"].paths
    artifacts = [product["path"], *(artifact for chain in product["chains"].values() for artifact in (chain["trim"], chain["loads"]))]
    return trade_procedure_row(spec, design_values, read_table(product["path"].paths["history"]), power, duration, distance,
                               read_table(footprint["microphones"]), read_table(footprint["areas"]), warnings_of(artifacts))


def _logged(cache: StageCache, start: int, prefix: str) -> tuple[dict, list[str]]:
    """Stage → digest of the cache entries used since ``start`` (a stage run more than once, as per path state:
    the list of its digests), and their report lines."""
    entries = cache.log[start:]
    used: dict = {}
    for stage, digest, _, _ in entries:
        used.setdefault(stage, []).append(digest)
    return ({stage: digests[0] if len(digests) == 1 else digests for stage, digests in used.items()},
            [f"{prefix} {stage:18s} {digest} {what:8s} {seconds:7.2f} s" for stage, digest, what, seconds in entries])


def design_rows(campaign: Campaign, aircraft: str, segments: list[str], design_values: dict, observer_sets: list[str],
                products: list[str], cache: StageCache) -> tuple[pd.DataFrame, dict, list[str]]:
    """The trade-table rows of a design's aircraft in ``segments``, with the aircraft-level ``products``
    (certification, footprint), or with the ``procedure`` product one row per path of the campaign the aircraft
    flies (:func:`procedure_row`); the stage digests (part → stage → digest) and the report lines. Raises one
    of :data:`REFUSALS` for a design the validity envelope or a trim refuses."""
    rows, digests, report = [], {}, []
    if "procedure" in products:  # a procedure study: a row per path the aircraft flies
        for path in (name for name, spec in campaign.paths.items() if spec["aircraft"] == aircraft):
            start = len(cache.log)
            rows.append(procedure_row(campaign, path, design_values, cache))
            digests[path], lines = _logged(cache, start, path)
            report += lines
        return pd.concat(rows, ignore_index=True), digests, report
    for segment in segments:
        start = len(cache.log)
        outcome = evaluate(campaign, aircraft, segment, design_values, cache, observer_sets)
        rows.append(outcome.row)
        digests[segment], lines = _logged(cache, start, segment)
        report += lines
    table = pd.concat(rows, ignore_index=True)
    for product, columns in (("certification", certification_columns), ("footprint", footprint_columns)):
        if product in products:
            start = len(cache.log)
            artifact = mission_product(product, campaign, aircraft, cache)
            table = columns(table, read_table(artifact.paths["summary" if product == "certification" else "areas"]))
            digests[product], lines = _logged(cache, start, product)
            report += lines
    return table, digests, report


def run(inputs: dict, outputs: dict, params: dict) -> str:
    campaign, cache = campaign_from_params(params["campaign"]), StageCache(Path(params["cache_dir"]))
    meta = {"aircraft": params["aircraft"], "design": params["design_values"]}
    try:
        table, digests, report = design_rows(campaign, params["aircraft"], params["segments"], params["design_values"],
                                             params["observer_sets"], params["products"], cache)
    except REFUSALS as error:  # a design outside the envelope: recorded, not a failed job
        table, digests, report = pd.DataFrame({"design": pd.Series([], dtype=str)}), {}, [f"refused: {error}"]
        meta["refused"] = str(error)
    write_table(table, outputs["rows"], stage="case", metadata={**meta, "stage_digests": digests})
    return "\n".join(report)
