# Shared definitions: validated campaign, wildcard constraints, paths and the code digest of each stage.
# Every job runs workflow/scripts/stage.py, which calls nps.stages.<name of the rule>.run (rule name = stage name).
import dataclasses
import sys
from functools import lru_cache
from pathlib import Path

from nps.app.config import ConfigError, load_campaign, load_path, load_rig
from nps.app.designs import load_study
from nps.app.plan import CaseConfig, metrics_reads_disks, stage_params
from nps.rig import RIG_AIRCRAFT
from nps.rig.case import station_params
from nps.stages.code import stage_digest
from nps.noise.metrics import rotor_solidities
import nps.app.resources as nps_resources



# Configuration paths are relative to the working directory (`snakemake -d DIR` runs a campaign elsewhere).
# A configuration error stops the run before any job with the validator's message alone.
try:
    CAMPAIGN = load_campaign(config, CONFIG_FILE, root=".")
except ConfigError as error:
    sys.stderr.write(f"NPS configuration error: {error}\n")
    raise SystemExit(1)
# the rules read the validated config with every schema default filled (nps.app.config.fill_defaults)
config.update(CAMPAIGN.config)
# campaign switch: findings outside the models' validity envelope become warnings (nps.app.validity)
ALLOW_OUTSIDE_VALIDITY = config["campaign"]["allow_outside_validity"]
RESULTS = "results"
ALL_TARGETS = []
STAGE_SCRIPT = "../scripts/stage.py"
BASE = f"{RESULTS}/{{aircraft}}/{{segment}}"  # per aircraft x segment artifacts

# Rigs (config/rigs/*.yaml, nps.rig.case; rules in rig.smk), validated before any job: the study rules run a
# rig as aircraft "rigs" (RIG_AIRCRAFT), segment NAME, so its artifacts are results/rigs/NAME/. Its jobs
# read the rig's own settings (rule params through setting(), nps.app.config.rig_settings), never the
# campaign's; rig.smk adds the set-up (trim and microphones) and the carpet.
RIGS_DIR = Path("config/rigs")
try:
    RIGS = {p.stem: load_rig(p) for p in sorted(RIGS_DIR.glob("*.yaml"))}
except ConfigError as error:
    sys.stderr.write(f"NPS rig configuration error: {error}\n")
    raise SystemExit(1)
if RIG_AIRCRAFT in CAMPAIGN.aircraft:
    sys.stderr.write(f"NPS configuration error: aircraft name '{RIG_AIRCRAFT}' is the rigs' (results/{RIG_AIRCRAFT}/)\n")
    raise SystemExit(1)

# Flight paths (config/paths/*.yaml of the campaign's aircraft, nps.mission.paths; rules in path.smk), validated
# and planned before any job: a path's quasi-static trim states run the study's per-segment rules as segments
# named by their keys (results/<aircraft>/<key>/, shared by every path through the same state), and its
# products are results/paths/<path>/. Paths of aircraft outside the campaign are not planned, nor any path without
# the `footprint` section (its source set and ground make the states' hemispheres and the propagation).
PATHS_DIR = Path("config/paths")
PATHS_RESULTS = f"{RESULTS}/paths"
try:
    _paths = {p.stem: load_path(p, config["paths"]["dt_s"]) for p in sorted(PATHS_DIR.glob("*.yaml"))}
    if "footprint" in config:
        CAMPAIGN = CAMPAIGN.with_paths({name: p for name, p in _paths.items() if p["aircraft"] in CAMPAIGN.aircraft})
except ConfigError as error:
    sys.stderr.write(f"NPS flight-path configuration error: {error}\n")
    raise SystemExit(1)
if "paths" in CAMPAIGN.aircraft:
    sys.stderr.write(f"NPS configuration error: aircraft name 'paths' is the flight paths' ({PATHS_RESULTS}/)\n")
    raise SystemExit(1)


wildcard_constraints:
    aircraft="[a-z][a-z0-9_]*",
    segment="|".join(["seg[0-9]+", *RIGS, "s[0-9a-f]{12}"]),
    path="[a-z][a-z0-9_]*",
    rotor="[a-z][a-z0-9_]*",
    obsset="[a-z][a-z0-9_]*",
    variant="base|bvi",


def code(stage):
    """Digest of every nps module the stage's jobs run (nps.stages.code): a param that reruns the jobs when
    any of that code changes, and only then."""
    return stage_digest(stage)


def log_path(stage, suffix="{aircraft}/{segment}"):
    return f"{RESULTS}/logs/{stage}/{suffix}.log"


def bench_path(stage, suffix="{aircraft}/{segment}"):
    return f"{RESULTS}/benchmarks/{stage}/{suffix}.tsv"


def signals_dir(stage):
    """Directory of the per-rotor signal tables ({rotor}.parquet) of a stage ("acoustics" or "hsi")."""
    return f"{BASE}/{stage}/{{obsset}}_{{variant}}"


def is_rig(wildcards):
    """Whether a job of the study rules is a rig's (aircraft "rigs", segment the rig's name)."""
    return wildcards.aircraft == RIG_AIRCRAFT


def settings(wildcards):
    """The configuration a job reads: the rig's settings (resolution, models, wake, acoustics, atmosphere,
    campaign.allow_outside_validity) for a rig, else the campaign's config."""
    return RIGS[wildcards.segment]["settings"] if is_rig(wildcards) else config


def setting(section, key=None):
    """Rule param: ``settings(wildcards)[section]`` (or its ``[key]``), the campaign's or the rig's."""
    return lambda wildcards: settings(wildcards)[section] if key is None else settings(wildcards)[section][key]


def aircraft_config(wildcards):
    """The whole validated aircraft configuration (a rig's: its rotors)."""
    if is_rig(wildcards):
        return {"rotors": RIGS[wildcards.segment]["rotor_configs"]}
    return CAMPAIGN.aircraft[wildcards.aircraft]


def case_config(wildcards):
    """The job's case (nps.app.plan.CaseConfig): a rig's rotor and settings, or the campaign's aircraft in the
    job's segment (none for an aircraft-level job)."""
    if is_rig(wildcards):
        return CaseConfig(aircraft_config(wildcards), settings(wildcards))
    return CaseConfig.from_campaign(CAMPAIGN, wildcards.aircraft, wildcards.get("segment"))


def plan(stage):
    """Rule param ``job``: the stage's params (nps.app.plan.stage_params), which the job adapter passes on
    with the wildcards (nps.stages.job)."""
    return lambda wildcards: stage_params(stage, case_config(wildcards), wildcards.get("obsset"))


def rotor_names(aircraft):
    return CAMPAIGN.rotor_names(aircraft)


def rotor_configs(wildcards):
    """Rotor name -> validated rotor configuration, in aircraft order."""
    return {r["name"]: r for r in aircraft_config(wildcards)["rotors"]}


def job_rotors(wildcards):
    """Rotor names of a job's aircraft (or rig), in aircraft order."""
    return list(rotor_configs(wildcards))


def figure_rotors(aircraft):
    """Rotors drawn in per-rotor figures: all of a one- or two-rotor aircraft, else the first."""
    names = rotor_names(aircraft)
    return names if len(names) <= 2 else names[:1]


def campaign_pairs():
    """(aircraft, segment) pairs of the campaign."""
    return [(a, s) for a in CAMPAIGN.aircraft for s in CAMPAIGN.segments]


def hemisphere_radius_R():
    """Radius of the hemisphere observer set in rotor radii (figure captions and titles)."""
    return config["observer_sets"]["hemisphere"]["radius_R"]


# used by study.smk
MAP_SEGMENTS = {
    "oaspl": lambda: CAMPAIGN.figure_segments("map"),
    "dba": lambda: CAMPAIGN.figure_segments("bvi_map"),
    "bvispl": lambda: CAMPAIGN.figure_segments("bvi_map"),
    "hsi_oaspl": lambda: [s for s in CAMPAIGN.figure_segments("hsi") if s in CAMPAIGN.hsi_segments()],
}


def map_kinds():
    """Map families with at least one segment in the campaign."""
    return [kind for kind, segments in MAP_SEGMENTS.items() if segments()]


def map_segments_all():
    """Segments drawn in any map family."""
    return [s for s in CAMPAIGN.segments if any(s in MAP_SEGMENTS[kind]() for kind in map_kinds())]


def hemisphere_metrics(aircraft, segment):
    """Hemisphere metrics of the variant with BVI wherever it was computed."""
    return f"{RESULTS}/{aircraft}/{segment}/metrics/hemisphere_{CAMPAIGN.variants(segment)[-1]}.parquet"


def antitorque_rotors(aircraft):
    return [r["name"] for r in CAMPAIGN.aircraft[aircraft]["rotors"] if r["role"] == "antitorque"]


# used by metrics.smk
def metrics_signal_inputs(wildcards):
    """Pressure-signal directory of the aircraft (and its HSI-processed version in HSI segments; the disk
    tables the signals were radiated from with BPM broadband, or ``auto``: BPM for the rotors outside Pegg's range)."""
    inputs = {"signals": signals_dir("acoustics").format(**wildcards)}
    if not is_rig(wildcards) and wildcards.segment in CAMPAIGN.hsi_segments():
        inputs["hsi"] = signals_dir("hsi").format(**wildcards)
    if metrics_reads_disks(settings(wildcards)):
        inputs["disks"] = variant_disks(wildcards)
    return inputs


# used by acoustics.smk and metrics.smk
def variant_disks(wildcards, variant=None):
    """Disk-table directory of a load variant (the job's, or ``variant``): the trimmed loads (base) or the loads with
    the wake's induced velocity (bvi)."""
    variant = variant or wildcards.variant
    return f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}/{'bvi' if variant == 'bvi' else 'loads'}"


# used by figures.smk
def rotor_figure_inputs(wildcards):
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    inputs = {"loads": f"{base}/loads"}
    if wildcards.segment in CAMPAIGN.bvi_segments():
        inputs.update(wake=f"{base}/wake", bvi=f"{base}/bvi")
    return inputs


# ---- Cluster requests of every job (nps.app.resources): threads, and mem_mb / runtime from the resolution ----
# ---- in config, the job's rotors and observer set, growing with the attempt (profiles/slurm retries). ----
def _job_load(wildcards):
    """(observers, rotors, HSI signals read) of a job; jobs without an observer set read the hemisphere's
    (a rig's: its microphones)."""
    if is_rig(wildcards):
        return len(RIGS[wildcards.segment]["microphones_T"]), len(rotor_configs(wildcards)), False
    obsset = wildcards.get("obsset", "hemisphere")
    spec = config["observer_sets"].get(obsset)
    n_observers = nps_resources.observer_count(spec) if spec else 1
    n_rotors = len(rotor_names(wildcards.aircraft))
    return n_observers, n_rotors, wildcards.get("segment") in CAMPAIGN.hsi_segments()


def job_threads(stage):
    return lambda wildcards: nps_resources.job_threads(stage, _job_load(wildcards)[0])


def job_mem_mb(stage):
    return lambda wildcards, attempt: nps_resources.job_mem_mb(stage, settings(wildcards)["resolution"], *_job_load(wildcards), attempt)


def job_runtime(stage):
    return lambda wildcards, attempt: nps_resources.job_runtime_min(stage, settings(wildcards)["resolution"], *_job_load(wildcards)[:2], attempt)


# used by study.smk
def summary_inputs(wildcards):
    """Per segment: trim, loads directory and hemisphere metrics of each variant; the wake directories are
    not read but make the wake jobs finish first, so their wall times are in the table."""
    base = f"{RESULTS}/{wildcards.aircraft}"
    inputs = {}
    for s in CAMPAIGN.segments:
        inputs.update({f"trim_{s}": f"{base}/{s}/trim.parquet", f"loads_{s}": f"{base}/{s}/loads"})
        inputs.update({f"metrics_{s}_{v}": f"{base}/{s}/metrics/hemisphere_{v}.parquet" for v in CAMPAIGN.variants(s)})
    inputs.update({f"wake_{s}": f"{base}/{s}/wake" for s in CAMPAIGN.bvi_segments()})
    return inputs


# used by footprint.smk and certification.smk
def source_set():
    return config["footprint"]["source_set"]


def product_variant(segment):
    """The load variant of the product: with BVI wherever it is computed (as the summary)."""
    return CAMPAIGN.variants(segment)[-1]


def source_hemisphere_inputs(wildcards):
    variant = product_variant(wildcards.segment)
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    inputs = {"signals": f"{base}/acoustics/{source_set()}_{variant}", "trim": f"{base}/trim.parquet",
              "observers": f"{base}/observers/{source_set()}.parquet"}
    if wildcards.segment in CAMPAIGN.hsi_segments():
        inputs["hsi"] = f"{base}/hsi/{source_set()}_{variant}"
    if metrics_reads_disks(config):  # BPM broadband (bpm, or auto), as the metrics
        inputs["disks"] = variant_disks(wildcards, variant)
    return inputs


def profile_segments():
    return list(dict.fromkeys(leg["segment"] for leg in CAMPAIGN.mission.get("profile", [])))


def footprint_inputs(wildcards):
    return {f"hemisphere_{s}": f"{RESULTS}/{wildcards.aircraft}/{s}/source_hemisphere.parquet" for s in profile_segments()}


# used by rig.smk
def rig_variant(rig):
    """Load variant a rig radiates: with the wake's induced velocity (bvi) where models.bvi, else base."""
    return "bvi" if RIGS[rig]["models"]["bvi"] else "base"


def rig_targets(rig):
    """A rig's products: its microphones' metrics and, where asked, the carpet and the loads at its stations
    (stations_r_over_R of the rig or its rotors: of the trimmed loads, and of the BVI loads where models.bvi).
    With loads_only: the loads (and the wake's BVI loads where models.bvi) and the station loads, no acoustics."""
    base = f"{RESULTS}/{RIG_AIRCRAFT}/{rig}"
    stations = [f"{base}/station_loads/{v}.parquet" for v in dict.fromkeys(("base", rig_variant(rig)))]
    stations = stations if RIGS[rig]["rotor_stations"] else []
    if RIGS[rig]["loads_only"]:
        return [f"{base}/loads"] + ([f"{base}/bvi"] if RIGS[rig]["models"]["bvi"] else []) + stations
    return ([f"{base}/metrics/microphones_{rig_variant(rig)}.parquet"] + ([f"{base}/carpet.png"] if RIGS[rig]["carpet"] else [])
            + stations)


# ---- resources: mem_mb of the jobs whose arrays scale with the resolution (nps.app.resources) ----


# used by study.smk
def segment_names():
    """Segment id -> the mission's name of it, for the campaign's segments."""
    return {s: CAMPAIGN.segment(s)["name"] for s in CAMPAIGN.segments}


def hemisphere_radius_m(aircraft):
    """Radius (m) of the hemisphere observer set: radius_R times the reference (first) rotor's radius."""
    return config["observer_sets"]["hemisphere"]["radius_R"] * CAMPAIGN.aircraft[aircraft]["rotors"][0]["radius_m"]


SUMMARY_CATEGORY = "1. Results summary"


def results_summary_inputs(wildcards):
    inputs = {}
    for a in CAMPAIGN.aircraft:
        inputs[f"summary_{a}"] = f"{RESULTS}/{a}/summary.parquet"
        inputs[f"summary_csv_{a}"] = f"{RESULTS}/{a}/summary.csv"
        if "certification" in config:
            inputs[f"certification_{a}"] = f"{RESULTS}/{a}/certification/certification.parquet"
        for s in CAMPAIGN.segments:
            inputs[f"trim_{a}_{s}"] = f"{RESULTS}/{a}/{s}/trim.parquet"
            inputs[f"loads_{a}_{s}"] = f"{RESULTS}/{a}/{s}/loads"
            inputs[f"metrics_{a}_{s}"] = hemisphere_metrics(a, s)
    inputs["targets"] = [t for t in ALL_TARGETS if any(t.startswith(f"{RESULTS}/{a}/") for a in CAMPAIGN.aircraft)]
    return inputs


# used by designs.smk: design studies (config/studies/NAME.yaml, nps.app.designs)
STUDIES_DIR = Path("config/studies")
STUDY_NAMES = sorted(p.stem for p in STUDIES_DIR.glob("*.yaml"))
STUDY_CACHE = f"{RESULTS}/studies/cache"


@lru_cache(maxsize=None)
def design_study(name):
    """The validated, expanded study (nps.app.designs.DesignStudy), its size and estimated cost on stderr; a
    configuration error (or a study estimated above its max_cost_core_h) stops the run."""
    try:
        study = load_study(STUDIES_DIR / f"{name}.yaml", root=".")
    except ConfigError as error:
        sys.stderr.write(f"NPS study configuration error: {error}\n")
        raise SystemExit(1)
    sys.stderr.write(f"NPS study {study.describe()}\n")
    return study


def study_dir(name):
    return f"{RESULTS}/studies/{name}"


def study_rows(wildcards):
    """The case rows of a study: one table per design x aircraft (a row per segment)."""
    study = design_study(wildcards.study)
    return {f"{d.id}_{a}": f"{study_dir(study.name)}/{d.id}/{a}.parquet" for d in study.designs for a in study.aircraft}


def case_params(wildcards):
    study = design_study(wildcards.study)
    design = study.design(wildcards.design)
    return {"campaign": dataclasses.asdict(design.campaign), "segments": study.segments,
            "design_values": {"design": design.id, **design.values},
            "observer_sets": study.spec["observer_sets"], "products": study.spec["products"], "cache_dir": STUDY_CACHE}


CASE_STAGES = ("trim", "loads", "wake", "observers", "acoustics", "hsi", "metrics")


def case_mem_mb(wildcards, attempt):
    """The largest of the chain's stage requests (the stages run one after the other)."""
    return max(job_mem_mb(stage)(wildcards, attempt) for stage in CASE_STAGES)


def case_runtime(wildcards, attempt):
    """The chain's stage requests summed over the study's segments."""
    n_segments = len(design_study(wildcards.study).segments)
    return n_segments * sum(job_runtime(stage)(wildcards, attempt) for stage in CASE_STAGES)


def study_targets(name):
    return [f"{study_dir(name)}/trade.parquet"]


# used by path.smk
def path_job(stage):
    """Rule param ``job`` of a path's stage: the stage's params planned for the path's aircraft
    (nps.app.plan.stage_params) with the aircraft's name and the validated path."""
    def job(wildcards):
        path = CAMPAIGN.paths[wildcards.path]
        case = CaseConfig.from_campaign(CAMPAIGN, path["aircraft"])
        return {**stage_params(stage, case), "aircraft": path["aircraft"], "path_config": path}
    return job


def path_footprint_inputs(wildcards):
    """The path's history and the source hemisphere of every trim state it passes."""
    aircraft = CAMPAIGN.paths[wildcards.path]["aircraft"]
    inputs = {"history": f"{PATHS_RESULTS}/{wildcards.path}/path_history.parquet"}
    inputs.update({f"hemisphere_{key}": f"{RESULTS}/{aircraft}/{key}/source_hemisphere.parquet"
                   for key in CAMPAIGN.path_keys[wildcards.path]})
    return inputs
