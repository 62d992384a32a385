"""Snakemake script of every rule: runs the stage named like the rule, ``nps.stages.<rule>.run``,
with the job's inputs, outputs, params, threads and log (nps.stages.job)."""

from nps.stages.job import run_job

run_job(snakemake, snakemake.rule)
