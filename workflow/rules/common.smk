# Shared definitions: validated campaign, wildcard constraints, config slices and code hashes.
import hashlib
import sys
from pathlib import Path

from nps.config import ConfigError, load_campaign

# Configuration paths are relative to the working directory (`snakemake -d DIR` runs a campaign elsewhere).
# A configuration error stops the run before any job with the validator's message alone.
try:
    CAMPAIGN = load_campaign(config, workflow.configfiles[0] if workflow.configfiles else "config", root=".")
except ConfigError as error:
    sys.stderr.write(f"NPS configuration error: {error}\n")
    raise SystemExit(1)
RESULTS = "results"
ALL_TARGETS = []


wildcard_constraints:
    aircraft="[a-z][a-z0-9_]*",
    segment="seg[0-9]+",
    rotor="[a-z][a-z0-9_]*",
    obsset="[a-z][a-z0-9_]*",
    variant="base|bvi",


def nps_hash(*modules):
    """Hash of the named nps modules (e.g. "bet", "plots/disk"): a param that reruns a job when its code changes."""
    digest = hashlib.sha256()
    for name in sorted(set(modules) | {"io", "config", "rotor", "frames"}):
        digest.update((Path(workflow.basedir) / "nps" / f"{name}.py").read_bytes())
    return digest.hexdigest()[:16]


def aircraft_config(wildcards):
    """The whole validated aircraft configuration."""
    return CAMPAIGN.aircraft[wildcards.aircraft]


def rotor_config(wildcards):
    """The validated configuration of one rotor."""
    return CAMPAIGN.rotor(wildcards.aircraft, wildcards.rotor)


def rotor_config_named(aircraft, rotor):
    return CAMPAIGN.rotor(aircraft, rotor)


def segment_speeds(wildcards):
    """Speeds of one aircraft in one segment (a mission-file slice)."""
    return CAMPAIGN.segment(wildcards.segment)["aircraft"][wildcards.aircraft]


def rotor_names(aircraft):
    return CAMPAIGN.rotor_names(aircraft)


def observer_sets(segment):
    """Observer sets used in a segment."""
    return [name for name, obs in config["observer_sets"].items() if segment in obs.get("segments", CAMPAIGN.segments)]


def bvi_segments():
    """Segments where the wake and BVI loads are computed (all when not listed)."""
    if not config["models"]["bvi"]:
        return []
    return [s for s in CAMPAIGN.segments if s in config["models"].get("bvi_segments", CAMPAIGN.segments)]


def hsi_segments():
    """Segments whose signals get the HSI post-processing (all when not listed)."""
    if not config["models"]["hsi"]:
        return []
    return [s for s in CAMPAIGN.segments if s in config["models"].get("hsi_segments", CAMPAIGN.segments)]


def figure_rotors(aircraft):
    """Rotors drawn in per-rotor figures: all of a one- or two-rotor aircraft, else the first."""
    names = rotor_names(aircraft)
    return names if len(names) <= 2 else names[:1]


def variants(segment):
    """Load variants radiated in a segment: the trimmed loads ("base") and/or the BVI loads ("bvi").

    Outside the BVI segments only "base"; in a BVI segment "bvi", preceded by "base" where the
    comparison without BVI is asked for (models.without_bvi_segments, default every BVI segment).
    """
    if segment not in bvi_segments():
        return ["base"]
    return ["base", "bvi"] if segment in config["models"].get("without_bvi_segments", bvi_segments()) else ["bvi"]


def figure_segments(kind):
    """Campaign segments listed for a figure family in config["figures"]."""
    return [s for s in CAMPAIGN.segments if s in config["figures"][f"{kind}_segments"]]


def campaign_pairs():
    """(aircraft, segment) pairs of the campaign."""
    return [(a, s) for a in CAMPAIGN.aircraft for s in CAMPAIGN.segments]


def log_path(stage, suffix="{aircraft}/{segment}"):
    return f"{RESULTS}/logs/{stage}/{suffix}.log"


def bench_path(stage, suffix="{aircraft}/{segment}"):
    return f"{RESULTS}/benchmarks/{stage}/{suffix}.tsv"


def signals_dir(stage):
    """Directory of the per-rotor signal tables ({rotor}.parquet) of a stage ("acoustics" or "hsi")."""
    return f"{RESULTS}/{{aircraft}}/{{segment}}/{stage}/{{obsset}}_{{variant}}"


# used by acoustics.smk
def acoustics_disk_inputs(wildcards):
    """Disk table of every rotor: trimmed loads (variant base) or BVI loads (variant bvi)."""
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    if wildcards.variant == "bvi":  # the wake job writes the bvi/ directory of every rotor
        return {"bvi_dir": f"{base}/bvi"}
    return {f"disk_{r}": f"{base}/loads/{r}.parquet" for r in rotor_names(wildcards.aircraft)}


# used by metrics.smk
def metrics_signal_inputs(wildcards):
    """Pressure-signal directory of the aircraft (and its HSI-processed version in HSI segments)."""
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    inputs = {"signals": f"{base}/acoustics/{wildcards.obsset}_{wildcards.variant}"}
    if wildcards.segment in hsi_segments():
        inputs["hsi"] = f"{base}/hsi/{wildcards.obsset}_{wildcards.variant}"
    return inputs


# used by metrics.smk
def metrics_solidity(wildcards):
    """Rotor name -> solidity (the only aircraft-configuration slice the metrics depend on)."""
    from nps.metrics import rotor_solidities

    return rotor_solidities(aircraft_config(wildcards))


# used by study.smk
MAP_SEGMENTS = {
    "oaspl": lambda: figure_segments("map"),
    "dba": lambda: figure_segments("bvi_map"),
    "bvispl": lambda: figure_segments("bvi_map"),
    "hsi_oaspl": lambda: [s for s in figure_segments("hsi") if s in hsi_segments()],
}


# used by study.smk
def map_kinds():
    """Map families with at least one segment in the campaign."""
    return [kind for kind, segments in MAP_SEGMENTS.items() if segments()]


# used by study.smk
def map_segments_all():
    """Segments drawn in any map family."""
    return [s for s in CAMPAIGN.segments if any(s in MAP_SEGMENTS[kind]() for kind in map_kinds())]


# used by study.smk
def best_variant(segment):
    return variants(segment)[-1]


# used by study.smk
def hemisphere_metrics(aircraft, segment):
    return f"{RESULTS}/{aircraft}/{segment}/metrics/hemisphere_{best_variant(segment)}.parquet"


# used by study.smk
def antitorque_rotors(aircraft):
    return [r["name"] for r in CAMPAIGN.aircraft[aircraft]["rotors"] if r["role"] == "antitorque"]


# used by wake.smk
def wake_inputs(wildcards):
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    inputs = {"trim": f"{base}/trim.parquet"}
    for r in rotor_names(wildcards.aircraft):
        inputs[f"disk_{r}"] = f"{base}/loads/{r}.parquet"
        inputs[f"summary_{r}"] = f"{base}/loads/{r}_summary.parquet"
    return inputs


# used by figures.smk
def rotor_figure_inputs(wildcards):
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    inputs = {}
    for r in figure_rotors(wildcards.aircraft):
        inputs[f"loads_{r}"] = f"{base}/loads/{r}.parquet"
    if wildcards.segment in bvi_segments():
        inputs.update(wake=f"{base}/wake", bvi=f"{base}/bvi")
    return inputs


# ---- Cluster requests (threads, mem_mb, runtime) of every rule: nps.resources, from the resolution ----
# ---- in config and the observer set / rotors of the job; mem_mb and runtime grow with the attempt.  ----
def job_size(wildcards):
    """nps.resources.JobSize of a job: config resolution, the job's rotors and observer set."""
    from nps.resources import JobSize, observer_count

    if "obsset" in wildcards.keys():
        n_observers = observer_count(config["observer_sets"][wildcards.obsset])
    elif "hemisphere" in config["observer_sets"]:  # the study figures read the hemisphere signals
        n_observers = observer_count(config["observer_sets"]["hemisphere"])
    else:
        n_observers = 0
    n_rotors = 1 if "rotor" in wildcards.keys() else len(rotor_names(wildcards.aircraft))
    resolution = config["resolution"]
    return JobSize(int(resolution["n_psi"]), int(resolution["n_r"]), int(resolution["wake_revolutions"]),
                   int(resolution["samples_per_rev"]), n_rotors, n_observers)


def job_threads(stage):
    from nps.resources import threads

    return lambda wildcards: threads(stage, job_size(wildcards))


def job_mem_mb(stage):
    from nps.resources import memory_mb

    return lambda wildcards, attempt: memory_mb(stage, job_size(wildcards), attempt)


def job_runtime(stage):
    from nps.resources import runtime_min

    return lambda wildcards, attempt: runtime_min(stage, job_size(wildcards), attempt)
