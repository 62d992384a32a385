"""End-to-end: the bundled rotor test studies (config/tests/) through the command and the Snakefile."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from nps.cli.rotor import main as rotor_command
from nps.io import read_table

REPO = Path(__file__).resolve().parents[2]


def test_itr_hover_through_the_rotor_command(tmp_path):
    """The ideally twisted rotor in hover (fixed pitch and speed) through set-up, loads and acoustics: the
    BPF tone falls monotonically from the rotor plane to the axis, where the steady axisymmetric loads
    radiate no tone at all."""
    assert rotor_command(["--test", str(REPO / "config/tests/itr_hover.yaml"), "--out-dir", str(tmp_path)]) == 0
    levels = pd.read_csv(tmp_path / "levels.csv")
    bpf1 = levels["bpf1_db"].to_numpy()
    assert np.all(np.diff(bpf1) < 0.0) and bpf1[-1] < 0.0 < bpf1[0]
    row = read_table(tmp_path / "trim.parquet").iloc[0]
    assert row["omega_rad_s"] == pytest.approx(5465.0 * np.pi / 30.0, rel=1e-12) and row["thrust_N"] > 0.0


@pytest.mark.slow
def test_rotor_test_studies_run_from_the_snakefile(tmp_path):
    """`snakemake rotor_tests` in a copy of config/: both studies, metrics finite, the HART-II carpet drawn,
    and its BVISPL maximum under the advancing side (y_T > 0), as the HART-II measurements have it."""
    shutil.copytree(REPO / "config", tmp_path / "config")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(REPO / ".numba_cache"))
    result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(tmp_path),
                             "-j2", "rotor_tests"], capture_output=True, text=True, env=env, timeout=1800)
    assert result.returncode == 0, result.stderr[-4000:]
    base = tmp_path / "results" / "tests"
    assert (base / "hart_ii_bl" / "carpet.png").stat().st_size > 20_000
    for test in ("hart_ii_bl", "itr_hover"):
        metrics = read_table(base / test / "metrics.parquet")
        assert np.isfinite(metrics.select_dtypes("number").to_numpy()).all()
    carpet = read_table(base / "hart_ii_bl" / "microphones.parquet").merge(read_table(base / "hart_ii_bl" / "metrics.parquet"),
                                                                         on="observer")
    assert carpet.loc[carpet["bvispl_db"].idxmax(), "y_T_m"] > 0.0
