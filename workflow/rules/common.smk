# Shared definitions: validated campaign, wildcard constraints, paths and the code digest of each stage.
# Every job runs workflow/scripts/stage.py, which calls nps.stages.<name of the rule>.run (rule name = stage name).
import sys

from pathlib import Path

from nps.app.config import ConfigError, load_campaign, load_rotor_test
from nps.stages.code import stage_digest
from nps.noise.metrics import rotor_solidities
import nps.app.resources as nps_resources



# Configuration paths are relative to the working directory (`snakemake -d DIR` runs a campaign elsewhere).
# A configuration error stops the run before any job with the validator's message alone.
try:
    CAMPAIGN = load_campaign(config, workflow.configfiles[0] if workflow.configfiles else "config", root=".")
except ConfigError as error:
    sys.stderr.write(f"NPS configuration error: {error}\n")
    raise SystemExit(1)
# campaign switch: findings outside the models' validity envelope become warnings (nps.app.validity)
ALLOW_OUTSIDE_VALIDITY = config["campaign"].get("allow_outside_validity", False)
RESULTS = "results"
ALL_TARGETS = []
STAGE_SCRIPT = "../scripts/stage.py"
BASE = f"{RESULTS}/{{aircraft}}/{{segment}}"  # per aircraft x segment artifacts


wildcard_constraints:
    aircraft="[a-z][a-z0-9_]*",
    segment="seg[0-9]+",
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


def aircraft_config(wildcards):
    """The whole validated aircraft configuration."""
    return CAMPAIGN.aircraft[wildcards.aircraft]


def rotor_names(aircraft):
    return CAMPAIGN.rotor_names(aircraft)


def rotor_configs(wildcards):
    """Rotor name -> validated rotor configuration, in aircraft order."""
    return {r["name"]: r for r in aircraft_config(wildcards)["rotors"]}


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
    tables the signals were radiated from with BPM broadband)."""
    inputs = {"signals": signals_dir("acoustics").format(**wildcards)}
    if wildcards.segment in CAMPAIGN.hsi_segments():
        inputs["hsi"] = signals_dir("hsi").format(**wildcards)
    if CAMPAIGN.broadband_model() == "bpm":
        inputs["disks"] = variant_disks(wildcards)
    return inputs


# used by acoustics.smk and metrics.smk
def variant_disks(wildcards):
    """Disk-table directory of a load variant: the trimmed loads (base) or the loads with the wake's induced velocity (bvi)."""
    return f"{RESULTS}/{wildcards.aircraft}/{wildcards.segment}/{'bvi' if wildcards.variant == 'bvi' else 'loads'}"


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
    """(observers, rotors, HSI signals read) of a job; jobs without an observer set read the hemisphere's."""
    obsset = wildcards.get("obsset", "hemisphere")
    spec = config["observer_sets"].get(obsset)
    n_observers = nps_resources.observer_count(spec) if spec else 1
    n_rotors = len(rotor_names(wildcards.aircraft))
    return n_observers, n_rotors, wildcards.get("segment") in CAMPAIGN.hsi_segments()


def job_threads(stage):
    return lambda wildcards: nps_resources.job_threads(stage, _job_load(wildcards)[0])


def job_mem_mb(stage):
    return lambda wildcards, attempt: nps_resources.job_mem_mb(stage, config["resolution"], *_job_load(wildcards), attempt)


def job_runtime(stage):
    return lambda wildcards, attempt: nps_resources.job_runtime_min(stage, config["resolution"], *_job_load(wildcards)[:2], attempt)


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
    return inputs


def profile_segments():
    return list(dict.fromkeys(leg["segment"] for leg in CAMPAIGN.mission.get("profile", [])))


def footprint_inputs(wildcards):
    return {f"hemisphere_{s}": f"{RESULTS}/{wildcards.aircraft}/{s}/source_hemisphere.parquet" for s in profile_segments()}


# used by tests.smk: the rotor test cases of config/tests/ (nps.rig.case), validated before any job
TESTS_DIR = Path("config/tests")
TEST_RESULTS = f"{RESULTS}/tests/{{test}}"
TEST_SCRIPT = "../scripts/rotor_test_stage.py"
try:
    ROTOR_TESTS = {p.stem: load_rotor_test(p) for p in sorted(TESTS_DIR.glob("*.yaml"))}
except ConfigError as error:
    sys.stderr.write(f"NPS rotor-test configuration error: {error}\n")
    raise SystemExit(1)


wildcard_constraints:
    test="|".join(ROTOR_TESTS) or "^$",


def test_variant(test):
    return "bvi" if ROTOR_TESTS[test]["models"]["bvi"] else "base"


def rotor_test_rotors(wildcards):
    rotor = ROTOR_TESTS[wildcards.test]["rotor_config"]
    return {rotor["name"]: rotor}


def test_targets(test):
    base = f"{RESULTS}/tests/{test}"
    out = [f"{base}/metrics.parquet"]
    if ROTOR_TESTS[test]["metrics"]["carpet"]:
        out.append(f"{base}/carpet.png")
    return out


# ---- resources: mem_mb of the jobs whose arrays scale with the resolution (nps.app.resources) ----
