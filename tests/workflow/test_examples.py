"""The examples run as documented (examples/notebook_api.py at its coarse --quick resolution)."""

from __future__ import annotations

import importlib.util
import os
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]


def test_notebook_api_example_runs_and_the_sweep_trends_are_physical(tmp_path, monkeypatch, capsys):
    spec = importlib.util.spec_from_file_location("notebook_api", REPO / "examples" / "notebook_api.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    monkeypatch.chdir(REPO)  # the example's paths are relative to the repository root
    table = example.main(["--quick", "--cache", str(tmp_path / "cache")])
    assert "helicopter seg2: main-rotor power" in capsys.readouterr().out
    table = table.sort_values("main.omega_rad_s")
    assert table["main.omega_rad_s"].tolist() == [25.2, 28.0, 29.4]
    # thrust held by the trim: profile power and the rotational noise rise with the rotor speed
    assert np.all(np.diff(table["power_W"]) > 0) and np.all(np.diff(table["max_oaspl_db"]) > 0)
    assert np.allclose(table["main_thrust_N"], table["main_thrust_N"].iloc[0], rtol=0.02)
    assert not any(p.name.startswith(".") and p.suffix == ".tmp" for p in (tmp_path / "cache").rglob("*"))
    assert os.path.isdir(tmp_path / "cache" / "metrics")
