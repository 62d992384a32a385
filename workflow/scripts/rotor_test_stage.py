"""Snakemake script of the rotor-test rules ``rotor_test_<stage>``: runs ``nps.stages.<stage>.run``, the
stage the study workflow runs (nps.stages.job)."""

from nps.stages.job import run_job

run_job(snakemake, snakemake.rule.removeprefix("rotor_test_"))
