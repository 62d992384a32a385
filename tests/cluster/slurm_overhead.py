"""Per-job SLURM overhead of a finished run (used by run_slurm_check.sh; not a pytest module).

    python tests/cluster/slurm_overhead.py WORKDIR SLURMCTLD_LOG

For each SLURM job: allocated (slurmctld "sched: Allocate JobId=N"), completed ("_job_complete:
JobId=N done"), seen finished by Snakemake (latest "Finished jobid" of its rule jobs in the
run's output, saved as WORKDIR.log) and its work: the summed benchmark seconds of the rule jobs it
ran (listed in the job's log under WORKDIR/.snakemake/slurm_logs, kept with
--slurm-keep-successful-logs). Overhead = (seen finished -
allocated) - work: Snakemake and srun start-up inside the job plus the status-query delay; queue
waiting before the allocation is not counted.
"""

from __future__ import annotations

import re
import sys
from datetime import datetime
from pathlib import Path

STAMP = re.compile(r"^\s*\[(\w{3} \w{3} +\d+ \d\d:\d\d:\d\d \d{4})\]")
CTLD = re.compile(r"^\[(\S+)\] (?:sched: Allocate JobId=(\d+) |_job_complete: JobId=(\d+) done)")


def _blocks(log: Path) -> tuple[dict[str, str], dict[str, datetime]]:
    """Benchmark path -> Snakemake jobid of every job block, and jobid -> time it was seen finished."""
    bench_job, finished = {}, {}
    jobid, when = None, None
    for line in log.read_text().splitlines():
        stamp = STAMP.match(line)
        if stamp:
            when = datetime.strptime(stamp.group(1), "%a %b %d %H:%M:%S %Y")
        text = line.strip()
        if text.startswith("jobid: "):
            jobid = text.split()[1]
        elif text.startswith("benchmark: ") and jobid is not None:
            bench_job[text.split()[1]] = jobid
        elif text.startswith("Finished jobid: "):
            finished[text.split()[2]] = when
    return bench_job, finished


def _members(slurm_log: Path) -> set[str]:
    """Benchmark paths of the rule jobs a SLURM job ran (its log prints each job block twice)."""
    return {line.strip().split()[1] for line in slurm_log.read_text().splitlines() if line.strip().startswith("benchmark: ")}


def _work_s(workdir: Path, benchmark: str) -> float:
    return float((workdir / benchmark).read_text().splitlines()[1].split("\t")[0])


def main(workdir: Path, ctld_log: Path) -> None:
    allocated, completed = {}, {}
    for line in ctld_log.read_text().splitlines():
        match = CTLD.match(line)
        if match:
            when = datetime.fromisoformat(match.group(1))
            if match.group(2):
                allocated[match.group(2)] = when
            else:
                completed[match.group(3)] = when
    bench_job, finished = _blocks(workdir.parent / f"{workdir.name}.log")
    rows = []
    for slurm_log in sorted(workdir.glob(".snakemake/slurm_logs/**/*.log"), key=lambda p: int(p.stem)):
        job = slurm_log.stem
        benchmarks = _members(slurm_log)
        if job not in allocated or job not in completed or not benchmarks:
            continue
        seen = max(finished[bench_job[b]] for b in benchmarks)
        work = sum(_work_s(workdir, b) for b in benchmarks)
        in_job = (completed[job] - allocated[job]).total_seconds() - work
        poll = (seen - completed[job]).total_seconds()
        name = slurm_log.parent.relative_to(workdir / ".snakemake" / "slurm_logs").as_posix()
        rows.append((job, name, len(benchmarks), work, in_job, poll))
    print(f"{'SLURM job':>9}  {'rule or group / wildcards':<60} {'jobs':>4} {'work s':>7} {'in-job s':>8} {'status s':>8}")
    for job, name, n, work, in_job, poll in rows:
        print(f"{job:>9}  {name:<60} {n:>4} {work:7.1f} {in_job:8.1f} {poll:8.1f}")
    n_slurm, n_rules = len(rows), sum(r[2] for r in rows)
    total = sum(r[4] + r[5] for r in rows)
    print(f"{n_slurm} SLURM jobs for {n_rules} rule jobs; work {sum(r[3] for r in rows):.1f} s; overhead "
          f"{total:.1f} s = {total / n_slurm:.1f} s per SLURM job (in-job {sum(r[4] for r in rows) / n_slurm:.1f} s, "
          f"status query {sum(r[5] for r in rows) / n_slurm:.1f} s), {total / n_rules:.1f} s per rule job")


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]))
