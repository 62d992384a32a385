"""Acoustics benchmark: compact F1A throughput and a full-hemisphere wall time.

Case: one 4-blade rotor (R = 7.62 m, c = 0.58 m, t/c = 0.09, Ω = 28 rad/s) at 40 m/s with an
analytic 1/rev-varying loading on 50 stations × 360 azimuths, dual-compact thickness (three
lines per blade), 1,368 observers (19 elevations × 72 azimuths, 10 R, moving with the
aircraft), 1,024 samples per revolution. Prints
* evaluations per second (source node × source time × observer) of the kernel, with one thread
  and with all threads (numba), and per core;
* the wall time of the full hemisphere (source lines + kernel + blade sum and resampling).
Each figure is the best of ``REPEATS`` runs (the machine is shared; the best run is the least
disturbed one). Run: ``python benchmarks/bench_acoustics.py``.
"""

import time

import numba
import numpy as np
import pandas as pd

from nps.noise.acoustics import Observers, TimeGrid, radiate_arrays
from nps.noise.sources import radiate_rotor
from nps.noise.observers import hemisphere
from nps.rotor.geometry import RotorMotion
from nps.noise.sources import ThicknessModel, rotor_sources

REPEATS = 3


def best_time(function) -> float:
    """Shortest wall time (s) of REPEATS calls."""
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def case():
    n_psi, n_r, radius, chord, omega, speed = 360, 50, 7.62, 0.58, 28.0, 40.0
    edges = np.linspace(0.15 * radius, radius, n_r + 1)
    r = 0.5 * (edges[1:] + edges[:-1])
    psi = 2 * np.pi * np.arange(n_psi) / n_psi
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    disk = pd.DataFrame({
        "psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": np.diff(edges)[0], "chord_m": chord, "thickness_m": 0.09 * chord,
        "theta_rad": (0.15 - 0.05 * np.sin(pp)).ravel(), "beta_rad": (0.05 - 0.02 * np.cos(pp)).ravel(),
        "fz_N_per_m": (900.0 * (rr / radius) ** 2 * (1 + 0.3 * np.sin(pp))).ravel(), "fx_N_per_m": (60.0 * rr / radius).ravel(),
    })
    row = {"rotation_sign": 1, "n_blades": 4, "omega_rad_s": omega, "hub_x_m": 0.0, "hub_y_m": 0.0, "hub_z_m": 1.8,
           "vel_x_mps": speed, "vel_y_mps": 0.0, "vel_z_mps": 0.0, "speed_of_sound_mps": 340.294, "density_kg_m3": 1.225}
    row.update({f"r_gh_{i}{j}": float(i == j) if (i, j) not in ((0, 0), (1, 1)) else -1.0 for i in range(3) for j in range(3)})
    obs = hemisphere([0.0, 0.0, 1.8], 10 * radius, 19, 72, [speed, 0.0, 0.0])
    observers = Observers(obs[["x_m", "y_m", "z_m"]].to_numpy(), obs[["vx_mps", "vy_mps", "vz_mps"]].to_numpy())
    grid = TimeGrid(0.0, 2 * np.pi / omega, 1024)
    return disk, row, observers, grid


def main():
    disk, row, observers, grid = case()
    threads = numba.get_num_threads()
    sources = rotor_sources(disk, RotorMotion.from_trim_row(row), thickness=ThicknessModel(), rho0_kg_m3=1.225, c0_mps=340.294)
    radiate_arrays(sources, Observers(observers.position_m[:2], observers.velocity_mps[:2]), grid)  # compile
    n_node, n_tau = sources.position_m.shape[:2]
    for n_threads in sorted({1, threads}):
        numba.set_num_threads(n_threads)
        elapsed = best_time(lambda: radiate_arrays(sources, observers, grid))
        evals = n_node * n_tau * len(observers.position_m)
        print(f"kernel, {n_threads} thread(s): {evals / 1e6:.1f} M evaluations in {elapsed:.3f} s = "
              f"{evals / elapsed / 1e6:.1f} M/s ({evals / elapsed / 1e6 / n_threads:.1f} M/s per core)")
    numba.set_num_threads(threads)
    p = radiate_rotor(disk, row, observers, grid)
    elapsed = best_time(lambda: radiate_rotor(disk, row, observers, grid))
    print(f"full hemisphere: {len(observers.position_m)} observers x 4 blades x 50 stations x 360 steps, "
          f"thickness + loading, {threads} thread(s): {elapsed:.2f} s (p_rms max {np.sqrt((p.sum(1) ** 2).mean(-1)).max():.2f} Pa)")


if __name__ == "__main__":
    main()
