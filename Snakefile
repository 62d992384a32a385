# NPS study workflow: trim -> loads -> wake (+ BVI loads) -> acoustics -> hsi -> metrics -> figures.
# `snakemake -j2 all` runs the campaign of config/config.yaml (or of `--configfile FILE`); `snakemake -j2 rigs`
# the rigs of config/rigs/ (rig.smk); `snakemake -j2 study_NAME` the design study config/studies/NAME.yaml
# (designs.smk); `snakemake -j2 wopwop` exports every case as a PSU-WOPWOP case (wopwop.smk); `snakemake --report
# report.html` builds the HTML report. Rules live in workflow/rules/, one file per stage.
import os
import sys

# nps is an installed package (pip install -r requirements.txt installs it editable). numba's on-disk cache is
# nps.core.jit's (NUMBA_CACHE_DIR if set, else nps/__pycache__/numba, per source version): one cache for the
# jobs, the `python -m nps` commands, the Python API and the tests, so a kernel compiles once on a machine.
os.environ.update(MPLBACKEND="Agg")

# The campaign file: config/config.yaml, or the one `--configfile FILE` names (then it alone, not merged
# with the bundled one). A YAML syntax error stops here with the file, line and column and no traceback
# (Snakemake's own parser names neither); the content is validated in common.smk.
CLI_CONFIG_FILES = [str(f) for f in workflow.overwrite_configfiles or []]
CONFIG_FILE = CLI_CONFIG_FILES[-1] if CLI_CONFIG_FILES else "config/config.yaml"
if os.path.exists(CONFIG_FILE):
    from nps.app.config import ConfigError, read_yaml

    try:
        read_yaml(CONFIG_FILE)
    except ConfigError as error:
        sys.stderr.write(f"NPS configuration error: {error}\n")
        raise SystemExit(1)


if not CLI_CONFIG_FILES:

    configfile: CONFIG_FILE


# `--config study=NAME` adds the design study config/studies/NAME.yaml to the targets of `all` (designs.smk);
# it is not a campaign field
REQUESTED_STUDY = config.pop("study", None)


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"


rule all:
    input:
        lambda wildcards: ALL_TARGETS,
    default_target: True


# A local run forks its jobs from one server process that imported NPS once (nps.stages.jobserver; environment
# NPS_JOB_SERVER=off: every job in its own process). Dry runs and cluster runs (an executor plugin) start none.
from nps.stages import jobserver

JOB_SERVER = None


onstart:
    global JOB_SERVER
    if workflow.local_exec:
        JOB_SERVER = jobserver.start(os.getpid(), os.path.join(".snakemake", "nps-jobserver.log"))


onsuccess:
    jobserver.stop(JOB_SERVER)


onerror:
    jobserver.stop(JOB_SERVER)


include: "workflow/rules/trim.smk"
include: "workflow/rules/loads.smk"
include: "workflow/rules/wake.smk"
include: "workflow/rules/acoustics.smk"
include: "workflow/rules/hsi.smk"
include: "workflow/rules/metrics.smk"
include: "workflow/rules/tones.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/study.smk"
include: "workflow/rules/footprint.smk"
include: "workflow/rules/certification.smk"
include: "workflow/rules/path.smk"
include: "workflow/rules/rig.smk"
include: "workflow/rules/designs.smk"
include: "workflow/rules/wopwop.smk"
