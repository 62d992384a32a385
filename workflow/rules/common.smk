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
    """Load variants radiated in a segment: the trimmed loads, plus BVI loads where BVI is on."""
    return ["base", "bvi"] if segment in bvi_segments() else ["base"]


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


# used by hsi.smk
def hsi_figure_inputs(wildcards):
    """Unprocessed and HSI signals of every rotor of the aircraft for one observer set."""
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    rotors = rotor_names(wildcards.aircraft)
    inputs = {f"signal_{r}": f"{base}/acoustics/{wildcards.obsset}/{r}_{wildcards.variant}.parquet" for r in rotors}
    inputs.update({f"hsi_{r}": f"{base}/hsi/{wildcards.obsset}/{r}_{wildcards.variant}.parquet" for r in rotors})
    return inputs


# used by metrics.smk
def metrics_signal_inputs(wildcards):
    """Pressure signals of every rotor of the aircraft (and their HSI-processed versions)."""
    base = f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}"
    rotors = rotor_names(wildcards.aircraft)
    inputs = {
        f"signal_{r}": f"{base}/acoustics/{wildcards.obsset}/{r}_{wildcards.variant}.parquet" for r in rotors
    }
    if wildcards.segment in hsi_segments():
        inputs.update({f"hsi_{r}": f"{base}/hsi/{wildcards.obsset}/{r}_{wildcards.variant}.parquet" for r in rotors})
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
wildcard_constraints:
    kind="oaspl|dba|bvispl|hsi_oaspl",


# used by study.smk
def best_variant(segment):
    return variants(segment)[-1]


# used by study.smk
def hemisphere_metrics(aircraft, segment):
    return f"{RESULTS}/{aircraft}/{segment}/metrics/hemisphere_{best_variant(segment)}.parquet"


# used by study.smk
def antitorque_rotors(aircraft):
    return [r["name"] for r in CAMPAIGN.aircraft[aircraft]["rotors"] if r["role"] == "antitorque"]
