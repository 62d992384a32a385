"""Unit tests of nps.noise.acoustics: derivatives, reception time, resampling, periodic path, CLI."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nps.__main__ import main as nps_main
from nps.noise.acoustics import AcousticsError, Observers, TimeGrid, fourier_resample, time_derivative
from nps.noise.sources import _emission_time, radiate, radiate_rotor
from nps.app.io import read_table, write_table


def test_time_derivative_sixth_order():
    """Derivative of sin on 50 points: error < 1e-8 inside and at the one-sided ends."""
    dt = 0.05
    t = np.arange(50) * dt
    d = time_derivative(np.sin(t)[None, :], dt)[0]
    assert np.abs(d - np.cos(t)).max() < 1e-6
    assert np.abs(d[3:-3] - np.cos(t[3:-3])).max() < 1e-8


@settings(max_examples=50, deadline=None)
@given(st.floats(-50, 50), st.floats(-50, 50), st.floats(-50, 50), st.floats(-200, 200), st.floats(-200, 200), st.floats(-1, 1))
def test_emission_time_closed_form(x, y, z, vx, vy, t):
    """|x_obs(t) − y(τ)| = c (t − τ) and τ ≤ t for a moving observer and a moving point."""
    c0 = 340.0
    x0 = np.array([[x, y, z]])
    v_obs = np.array([[vx, vy, 0.0]])
    y0, v_src = np.array([1.0, -2.0, 0.5]), np.array([60.0, 0.0, -5.0])
    tau = _emission_time(x0, v_obs, t, y0, v_src, c0)[0]
    dist = np.linalg.norm(x0[0] + v_obs[0] * t - (y0 + v_src * tau))
    assert tau <= t
    assert abs(dist - c0 * (t - tau)) < 1e-9 * max(1.0, dist)


def test_fourier_resample_exact_and_blade_sum():
    """A band-limited periodic signal is reproduced on another grid; copies keep harmonics multiple of B."""
    period, m = 0.2, 64
    t = np.arange(m) * period / m
    signal = np.cos(2 * np.pi * 3 * t / period + 0.3) + 0.5 * np.sin(2 * np.pi * 8 * t / period)
    grid = TimeGrid(0.0, 0.35, 91)
    tt = grid.times_s
    exact = np.cos(2 * np.pi * 3 * tt / period + 0.3) + 0.5 * np.sin(2 * np.pi * 8 * tt / period)
    assert np.allclose(fourier_resample(signal, period, grid), exact, atol=1e-12)
    assert np.allclose(fourier_resample(signal, period, grid, copies=4), 4 * 0.5 * np.sin(2 * np.pi * 8 * tt / period), atol=1e-12)


def _row(speed):
    row = {"rotation_sign": -1, "n_blades": 3, "omega_rad_s": 30.0, "hub_x_m": 0.5, "hub_y_m": 0.0, "hub_z_m": 1.5,
           "vel_x_mps": speed, "vel_y_mps": 0.0, "vel_z_mps": -2.0, "speed_of_sound_mps": 340.0, "density_kg_m3": 1.2}
    tilt = 0.1
    r_gh = np.array([[-np.cos(tilt), 0.0, np.sin(tilt)], [0.0, -1.0, 0.0], [np.sin(tilt), 0.0, np.cos(tilt)]])
    row.update({f"r_gh_{i}{j}": r_gh[i, j] for i in range(3) for j in range(3)})
    return row


def _disk(n_psi=120, n_r=8, radius=5.0):
    r = np.linspace(0.3, 0.95, n_r) * radius
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    return pd.DataFrame({"psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": 0.08 * radius, "chord_m": 0.4, "thickness_m": 0.04,
                         "theta_rad": (0.1 + 0.05 * np.cos(pp)).ravel(), "beta_rad": (0.04 + 0.03 * np.sin(pp)).ravel(),
                         "fz_N_per_m": (800 * (rr / radius) ** 2 * (1 + 0.4 * np.sin(pp) + 0.2 * np.cos(2 * pp))).ravel(),
                         "fx_N_per_m": (40 + 10 * np.cos(pp)).ravel()})


def test_periodic_path_equals_all_blade_direct_path():
    """Co-moving observers: one blade + symmetry + Fourier resampling = all blades computed directly (1e-3 of p2p).

    The direct path is forced by giving the observers a velocity differing by 1e-7 m/s (no periodicity used).
    """
    row = _row(30.0)
    velocity = np.array([row["vel_x_mps"], 0.0, row["vel_z_mps"]])
    pos = np.array([[40.0, 10.0, -20.0], [-30.0, -25.0, 5.0], [0.0, 0.0, -45.0]])
    grid = TimeGrid(0.05, 2 * np.pi / 30.0, 256)
    disk = _disk()
    periodic = radiate_rotor(disk, row, Observers(pos, np.tile(velocity, (3, 1))), grid)
    direct = radiate_rotor(disk, row, Observers(pos, np.tile(velocity + [1e-7, 0, 0], (3, 1))), grid)
    scale = np.ptp(direct, axis=-1, keepdims=True)
    assert np.abs(periodic - direct).max(axis=-1).max() < 1e-3 * scale.min()


def _synthetic_tables(n_tau=200):
    tau = np.arange(n_tau) * 1e-3
    omega = 60.0
    src = pd.DataFrame({"node": np.repeat([0, 1], n_tau), "group": "loading", "time_s": np.tile(tau, 2),
                        "x_m": np.concatenate([np.cos(omega * tau), -np.cos(omega * tau)]),
                        "y_m": np.concatenate([np.sin(omega * tau), -np.sin(omega * tau)]), "z_m": 0.0,
                        "fx_N": 0.0, "fy_N": 0.0, "fz_N": -100.0})
    obs = pd.DataFrame({"observer": [0, 1], "x_m": [10.0, 0.0], "y_m": [0.0, 5.0], "z_m": [-5.0, -8.0],
                        "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0})
    return src, obs


def test_cli_round_trip(tmp_path):
    """CLI output equals the Python API and has the documented columns and time grid."""
    src, obs = _synthetic_tables()
    write_table(src, tmp_path / "s.parquet", stage="test")
    write_table(obs, tmp_path / "o.parquet", stage="test")
    code = nps_main(["radiate", "--sources", str(tmp_path / "s.parquet"), "--observers", str(tmp_path / "o.parquet"),
                     "--t-start", "0.05", "--duration", "0.1", "--samples", "100", "--out", str(tmp_path / "p.parquet")])
    assert code == 0
    out = read_table(tmp_path / "p.parquet")
    assert list(out.columns) == ["observer", "group", "time_s", "p_Pa"]
    assert set(out.group) == {"loading", "total"}
    api = radiate(src, obs, 0.05, 0.1, 100)
    assert np.array_equal(out.p_Pa.to_numpy(), api.p_Pa.to_numpy())
    assert np.allclose(out[(out.observer == 0) & (out.group == "total")].time_s, 0.05 + np.arange(100) * 1e-3)


@pytest.mark.parametrize("mutate,message", [
    (lambda s, o: (s.drop(columns="fz_N"), o), "missing column"),
    (lambda s, o: (s.assign(time_s=s.time_s * (1 + 0.01 * (s.time_s > 0.1))), o), "uniform"),
    (lambda s, o: (s.assign(x_m=s.x_m.where(s.index != 7, np.nan)), o), "NaN"),
    (lambda s, o: (s, o.assign(z_m=[-5.0, -500.0])), "observer 1"),
    (lambda s, o: (s, o.drop(columns="vz_mps")), "missing column"),
])
def test_cli_errors(tmp_path, capsys, mutate, message):
    """Bad inputs: exit code 2 and a message naming the field, file or observer; no output written."""
    src, obs = mutate(*_synthetic_tables())
    src.to_csv(tmp_path / "s.csv", index=False)
    obs.to_csv(tmp_path / "o.csv", index=False)
    code = nps_main(["radiate", "--sources", str(tmp_path / "s.csv"), "--observers", str(tmp_path / "o.csv"),
                     "--t-start", "0.05", "--duration", "0.1", "--samples", "100", "--out", str(tmp_path / "p.parquet")])
    err = capsys.readouterr().err
    assert code == 2 and message in err and "s.csv" in err
    assert not (tmp_path / "p.parquet").exists()


def test_uncovered_window_names_interval():
    src, obs = _synthetic_tables()
    with pytest.raises(AcousticsError, match=r"observer 0: the sources cover observer times \["):
        radiate(src, obs, 0.0, 0.1, 100)
