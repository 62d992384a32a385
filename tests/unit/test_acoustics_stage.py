"""Acoustics stage: the common time grid of an aircraft's rotors, errors and the command (nps.stages.acoustics)."""

import numpy as np
import pandas as pd
import pytest

from nps.__main__ import main as nps_main
from nps.noise.acoustics import AcousticsError
from nps.noise.acoustics import Observers
from nps.app.io import ArtifactError, read_table, rotor_path, write_table
from nps.noise.signals import signals_table
from nps.noise.sources import common_grid, radiate_rotor
from nps.stages.acoustics import run
from nps.rotor.trim import trim_row
from tests.trim_tables import complete_trim
from nps.noise.observers import points
from nps.noise.sources import ThicknessModel

RADIUS = 2.0


def hover_disk(n_psi=72, n_r=8) -> pd.DataFrame:
    edges = np.linspace(0.2 * RADIUS, RADIUS, n_r + 1)
    r = 0.5 * (edges[1:] + edges[:-1])
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    return pd.DataFrame({
        "psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": edges[1] - edges[0], "chord_m": 0.15, "thickness_m": 0.018,
        "theta_rad": 0.1, "beta_rad": 0.02, "fz_N_per_m": (300.0 * (rr / RADIUS) ** 2).ravel(), "fx_N_per_m": 20.0,
    })


def trim_rows() -> pd.DataFrame:
    """Hovering aircraft: 'main' (Ω = 28 rad/s) and 'aux' turning exactly 3 times faster, another hub."""
    rows = []
    for name, omega, hub in (("main", 28.0, (0.0, 0.0, 1.8)), ("aux", 84.0, (-6.0, 0.0, 1.5))):
        row = {"rotor": name, "rotation_sign": 1, "n_blades": 4, "omega_rad_s": omega, "hub_x_m": hub[0], "hub_y_m": hub[1],
               "hub_z_m": hub[2], "vel_x_mps": 0.0, "vel_y_mps": 0.0, "vel_z_mps": 0.0, "density_kg_m3": 1.225,
               "speed_of_sound_mps": 340.294}
        row.update({f"r_gh_{i}{j}": (-1.0 if i == j < 2 else float(i == j)) for i in range(3) for j in range(3)})
        rows.append(row)
    return pd.DataFrame(rows)


def observers() -> pd.DataFrame:
    return points([[30.0, 5.0, -3.0], [-10.0, -25.0, -8.0], [0.0, 0.0, -20.0]])


def rotor_signals(disk, trim, obs_table, rotor, reference, samples, thickness, hinge_offset_m) -> pd.DataFrame:
    """Signal table of one rotor on the reference rotor's grid, as the acoustics stage computes it."""
    grid = common_grid(trim_row(trim, reference), samples)
    obs = Observers(obs_table[["x_m", "y_m", "z_m"]].to_numpy(float), obs_table[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float))
    pressure = radiate_rotor(disk, trim_row(trim, rotor), obs, grid, thickness=thickness, hinge_offset_m=hinge_offset_m)
    return signals_table(obs_table["observer"].to_numpy(), ("loading", "thickness"), pressure, grid, total=False)


def test_faster_rotor_lands_on_reference_grid_at_its_own_harmonics():
    """A rotor turning 3× faster, on the reference (first) rotor's revolution: only harmonics 12k (its
    4-blade passage) carry energy (outside: < 1e-20 of the total; its first one > 5 %), the grid is [0, T_ref)
    with N samples."""
    table = rotor_signals(hover_disk(), trim_rows(), observers(), "aux", "main", 256, ThicknessModel(), 0.0)
    assert set(table["group"]) == {"thickness", "loading"}
    t = np.sort(table["time_s"].unique())
    assert t.size == 256 and t[0] == 0.0 and t[-1] + t[1] == pytest.approx(2 * np.pi / 28.0)
    p = table.groupby(["observer", "time_s"])["p_Pa"].sum().unstack().to_numpy()
    power = np.abs(np.fft.rfft(p, axis=1)) ** 2
    harmonic = np.arange(power.shape[1])
    assert power[:, harmonic % 12 != 0].sum() < 1e-20 * power.sum()
    assert power[:, 12].sum() > 0.05 * power.sum()


def test_reference_rotor_signal_has_blade_passage_harmonics_only():
    """The 4-blade reference rotor in hover: harmonics 4k of its revolution only."""
    table = rotor_signals(hover_disk(), trim_rows(), observers(), "main", "main", 128, ThicknessModel("compact_monopole"), 0.1)
    p = table.groupby(["observer", "time_s"])["p_Pa"].sum().unstack().to_numpy()
    power = np.abs(np.fft.rfft(p, axis=1)) ** 2
    assert power[:, np.arange(power.shape[1]) % 4 != 0].sum() < 1e-20 * power.sum()


def test_errors_name_the_rotor_file_and_field(tmp_path):
    with pytest.raises(ValueError, match="rotor 'tail'"):
        rotor_signals(hover_disk(), trim_rows(), observers(), "tail", "main", 64, ThicknessModel(), 0.0)
    with pytest.raises(AcousticsError, match="samples_per_rev"):
        common_grid(trim_row(trim_rows(), "main"), 4)
    write_table(hover_disk().drop(columns="thickness_m"), tmp_path / "disks" / "main.parquet", stage="loads")
    write_table(complete_trim(trim_rows()), tmp_path / "trim.parquet", stage="trim")
    write_table(observers(), tmp_path / "obs.parquet", stage="observers")
    params = {"rotors": ["main"], "hinge_offsets_m": {"main": 0.0}, "thickness": "dual_compact", "chord_fractions": [0.13, 0.87],
              "samples_per_rev": 64, "aircraft": "x", "segment": "seg1", "obsset": "obs", "variant": "base"}
    with pytest.raises(ArtifactError, match="thickness_m"):
        run({"disks": tmp_path / "disks", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"},
            {"signals": tmp_path / "out"}, params)
    assert not rotor_path(tmp_path / "out", "main").exists()


def test_cli_round_trip(tmp_path, capsys):
    """``python -m nps acoustics`` writes the contract's columns; a bad rotor name exits 2 with one line."""
    write_table(hover_disk(), tmp_path / "disks" / "main.parquet", stage="loads")
    write_table(complete_trim(trim_rows()), tmp_path / "trim.parquet", stage="trim")
    write_table(observers(), tmp_path / "obs.parquet", stage="observers")
    args = ["acoustics", "--disks", str(tmp_path / "disks"), "--trim", str(tmp_path / "trim.parquet"),
            "--observers", str(tmp_path / "obs.parquet"), "--aircraft", "config/aircraft/helicopter.yaml",
            "--samples-per-rev", "64", "--out-dir", str(tmp_path / "p")]
    assert nps_main(args + ["--rotor", "main"]) == 0
    out = read_table(tmp_path / "p" / "main.parquet")
    assert list(out.columns) == ["observer", "group", "time_s", "p_Pa"] and len(out) == 3 * 2 * 64
    assert np.isfinite(out["p_Pa"]).all() and out["p_Pa"].abs().max() > 0
    assert nps_main(args + ["--rotor", "rotor9"]) == 2
    assert "no rotor named 'rotor9'" in capsys.readouterr().err
