#!/usr/bin/env bash
# Cluster check (issue 16): a reduced campaign through profiles/slurm on a one-node SLURM cluster
# WITHOUT accounting must give byte-identical Parquet artifacts to the same campaign run locally.
#
#   bash tests/cluster/run_slurm_check.sh        # as root, on Debian; not part of the pytest run
#
# Steps: installs Debian's slurm-wlm and munge and requirements-cluster.txt; starts munged, slurmctld
# and slurmd with their key, socket, ports, spool and state in a temporary directory and
# AccountingStorageType=accounting_storage/none; slurm.conf goes to /etc/slurm/slurm.conf (an
# existing one is put back on exit): the jobstep plugin removes SLURM_CONF from the environment of
# the srun it starts inside each job, so only the default path reaches it; runs the
# helicopter seg3 (wake + BVI) + seg5 (HSI) campaign at coarse resolution through a copy of
# profiles/slurm whose commented `slurm-status-command: squeue` line is uncommented; runs the same
# campaign locally (-j2); compares the sha256 of every Parquet file; prints the SLURM jobs and
# their overhead (tests/cluster/slurm_overhead.py). The daemons it started are stopped on exit.
# Environment: NPS_SLURM_PORT (slurmctld port, default 16817; slurmd uses the next one),
# NPS_KEEP=1 keeps the temporary directory.
set -euo pipefail

REPO="$(cd "$(dirname "$0")/../.." && pwd)"
WORK="$(mktemp -d /tmp/nps-slurm-check.XXXXXX)"
PORT="${NPS_SLURM_PORT:-16817}"
PIDS=()
CONF_WRITTEN=0

cleanup() {
    local status=$?
    if [[ "$CONF_WRITTEN" == 1 ]]; then scancel --user="$(id -un)" 2>/dev/null && sleep 2 || true; fi
    for pid in "${PIDS[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${PIDS[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    done
    if [[ "$CONF_WRITTEN" == 1 ]]; then
        if [[ -e "$WORK/slurm.conf.saved" ]]; then mv "$WORK/slurm.conf.saved" /etc/slurm/slurm.conf; else rm -f /etc/slurm/slurm.conf; fi
    fi
    if [[ "${NPS_KEEP:-0}" == 1 ]]; then echo "kept $WORK"; else rm -rf "$WORK"; fi
    exit "$status"
}
trap cleanup EXIT INT TERM

step() { echo "== $(date -u +%H:%M:%S) $*"; }

step "install slurm-wlm, munge and requirements-cluster.txt"
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge > "$WORK/apt.log"
pip install -q --root-user-action=ignore -r "$REPO/requirements.txt" -r "$REPO/requirements-cluster.txt"
echo "$(slurmctld -V), $(munged -V 2>&1 | awk '{print $1}'), $(pip show snakemake-executor-plugin-slurm | grep ^Version)"

step "start munged"
mkdir -p "$WORK/munge" "$WORK/slurm/state" "$WORK/slurm/spool"
chmod 700 "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
munged --force --key-file="$WORK/munge/munge.key" --socket="$WORK/munge/munge.socket" \
    --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/munge/munged.log" --seed-file="$WORK/munge/munged.seed"
PIDS+=("$(cat "$WORK/munge/munged.pid")")

step "write slurm.conf (no accounting) and start slurmctld, slurmd"
HOST="$(hostname -s)"
# the node as slurmd sees it (CPUs, sockets, cores, memory), at least 4 CPUs: the numba-parallel
# rules ask 4 threads; config_overrides lets a smaller test machine accept the declared node
read -r NODE_HW < <(slurmd -C | head -1 | sed -E 's/^NodeName=[^ ]+ //; s/ *UpTime=.*//')
CPUS="$(sed -E 's/.*CPUs=([0-9]+).*/\1/' <<< "$NODE_HW")"
MEMORY="$(sed -E 's/.*RealMemory=([0-9]+).*/\1/' <<< "$NODE_HW")"
if (( CPUS < 4 )); then
    NODE_HW="CPUs=4 Boards=1 SocketsPerBoard=1 CoresPerSocket=4 ThreadsPerCore=1 RealMemory=$MEMORY"
fi
export SLURM_CONF=/etc/slurm/slurm.conf
if [[ -e "$SLURM_CONF" ]]; then cp -p "$SLURM_CONF" "$WORK/slurm.conf.saved"; fi
CONF_WRITTEN=1
cat > "$SLURM_CONF" <<EOF
ClusterName=npscheck
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
AuthInfo=socket=$WORK/munge/munge.socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$WORK/slurm/state
SlurmdSpoolDir=$WORK/slurm/spool
SlurmctldPidFile=$WORK/slurm/slurmctld.pid
SlurmdPidFile=$WORK/slurm/slurmd.pid
SlurmctldLogFile=$WORK/slurm/slurmctld.log
SlurmdLogFile=$WORK/slurm/slurmd.log
SlurmctldDebug=info
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
MinJobAge=300
NodeName=$HOST NodeAddr=127.0.0.1 $NODE_HW State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF"
for _ in $(seq 100); do [[ -s "$WORK/slurm/slurmctld.pid" ]] && break; sleep 0.1; done
PIDS+=("$(cat "$WORK/slurm/slurmctld.pid")")
slurmd -f "$SLURM_CONF"
for _ in $(seq 100); do [[ -s "$WORK/slurm/slurmd.pid" ]] && break; sleep 0.1; done
PIDS+=("$(cat "$WORK/slurm/slurmd.pid")")
for _ in $(seq 60); do sinfo -h -o %T | grep -qx idle && break; sleep 1; done
sinfo
echo "sacct on this cluster: $(sacct -X -n 2>&1 | head -1)"

step "reduced campaign: helicopter seg3 + seg5, coarse resolution"
python - "$REPO/config" "$WORK" <<'EOF'
import shutil, sys
from pathlib import Path

import yaml

source, work = Path(sys.argv[1]), Path(sys.argv[2])
for run in ("slurm_run", "local_run"):
    shutil.copytree(source, work / run / "config")
    path = work / run / "config" / "config.yaml"
    config = yaml.safe_load(path.read_text())
    config["campaign"].update(aircraft=["helicopter"], segments=["seg3", "seg5"])
    for spec in config["observer_sets"].values():
        spec["segments"] = [s for s in spec["segments"] if s in ("seg3", "seg5")]
    config["observer_sets"]["hemisphere"].update(n_elevation=4, n_azimuth=8)
    config["resolution"].update(n_psi=72, n_r=16, wake_revolutions=2, samples_per_rev=256)
    config["models"].update(bvi_segments=["seg3"], hsi_segments=["seg5"], without_bvi_segments=["seg3"])
    config["figures"] = {"disk_segments": ["seg3"], "map_segments": ["seg3"], "bvi_map_segments": ["seg3"],
                         "hsi_segments": ["seg5"]}
    path.write_text(yaml.safe_dump(config, sort_keys=False))
EOF
cp -r "$REPO/profiles/slurm" "$WORK/profile"
sed -i -E 's/^# *(slurm-status-command: squeue)/\1/' "$WORK/profile/config.v8+.yaml"
grep -x "slurm-status-command: squeue" "$WORK/profile/config.v8+.yaml"

step "SLURM run"
start=$(date +%s%3N)
(cd "$WORK/slurm_run" && timeout 1800 python -m snakemake -s "$REPO/Snakefile" --profile "$WORK/profile" \
    --slurm-keep-successful-logs all) \
    > "$WORK/slurm_run.log" 2>&1 || { tail -60 "$WORK/slurm_run.log"; tail -30 "$WORK/slurm/slurmctld.log"; exit 1; }
slurm_ms=$(( $(date +%s%3N) - start ))

step "local run"
start=$(date +%s%3N)
(cd "$WORK/local_run" && python -m snakemake -s "$REPO/Snakefile" -j2 all) > "$WORK/local_run.log" 2>&1 \
    || { tail -60 "$WORK/local_run.log"; exit 1; }
local_ms=$(( $(date +%s%3N) - start ))

step "compare sha256 of every Parquet artifact"
(cd "$WORK/slurm_run" && find results -name '*.parquet' | sort | xargs sha256sum) > "$WORK/slurm.sha256"
(cd "$WORK/local_run" && find results -name '*.parquet' | sort | xargs sha256sum) > "$WORK/local.sha256"
echo "$(wc -l < "$WORK/slurm.sha256") Parquet files from SLURM, $(wc -l < "$WORK/local.sha256") from the local run"
if ! diff "$WORK/slurm.sha256" "$WORK/local.sha256"; then
    echo "FAIL: the SLURM and local artifacts differ"
    exit 1
fi
echo "wall time: SLURM run $((slurm_ms / 1000)) s, local run (-j2) $((local_ms / 1000)) s"
python "$REPO/tests/cluster/slurm_overhead.py" "$WORK/slurm_run" "$WORK/slurm/slurmctld.log"
echo "PASS: identical Parquet artifacts (SLURM without accounting, squeue status) and local"
