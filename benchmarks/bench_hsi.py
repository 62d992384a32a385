"""Benchmark of the HSI stage: 1,368-observer hemisphere (19 elevations × 72 azimuths, 10 R), two rotors.

Prints wall times of nps.noise.hsi.process (M_r search, amplification, shear, shock fit, resampling and
table assembly) per rotor and in total, after a warm-up call that compiles the numba kernels.
Target (issue 7): < 2 s for both rotors. Synthetic signals: 1024 samples per revolution, one
thickness-like negative pulse per blade passage whose amplitude falls off out of plane.

    python benchmarks/bench_hsi.py
"""

from __future__ import annotations

import time

import numpy as np
import pandas as pd

from nps.core.frames import observer_direction, rot_x
from nps.noise.hsi import process

C0, RHO = 340.3, 1.225
V = 82.8  # helicopter maximum-speed segment, m/s
N = 1024


def trim_row(name, radius, mtip, n_blades, hub, r_gh, sign):
    row = dict(rotor=name, rotation_sign=sign, n_blades=n_blades, radius_m=radius, omega_rad_s=mtip * C0 / radius,
               hub_x_m=hub[0], hub_y_m=hub[1], hub_z_m=hub[2], vel_x_mps=V, vel_y_mps=0.0, vel_z_mps=0.0,
               density_kg_m3=RHO, speed_of_sound_mps=C0)
    row.update({f"r_gh_{i}{j}": float(r_gh[i, j]) for i in range(3) for j in range(3)})
    return row


def hemisphere(radius_m):
    el, az = np.meshgrid(np.radians(np.linspace(0, -90, 19)), np.radians(np.arange(72) * 5.0), indexing="ij")
    d = observer_direction(az.ravel(), el.ravel()) * radius_m
    n = d.shape[0]
    return pd.DataFrame({"observer": np.arange(n, dtype=np.int32), "x_m": d[:, 0], "y_m": d[:, 1], "z_m": d[:, 2],
                         "vx_mps": V, "vy_mps": 0.0, "vz_mps": 0.0,
                         "elevation_deg": np.degrees(el.ravel()), "azimuth_deg": np.degrees(az.ravel())})


def signals(observers, period, n_blades):
    t = np.arange(N) * period / N
    cos_el = np.cos(np.radians(observers["elevation_deg"].to_numpy()))
    phase = (t[None, :] * n_blades / period) % 1.0
    pulse = -800.0 * cos_el[:, None] ** 4 * np.exp(-(((phase - 0.5) / 0.01) ** 2))
    n_obs = len(observers)
    return pd.DataFrame({"observer": np.repeat(observers["observer"].to_numpy(), N), "group": "thickness",
                         "time_s": np.tile(t, n_obs), "p_Pa": pulse.ravel()})


def main() -> None:
    main_row = trim_row("main", 7.32, 0.64, 4, (0.0, 0.0, 2.0), np.eye(3), 1)
    tail_row = trim_row("tail", 1.3, 0.60, 2, (-9.0, 0.0, 1.5), rot_x(np.pi / 2), -1)
    observers = hemisphere(73.2)
    period = 2 * np.pi / main_row["omega_rad_s"]
    sig = {"main": signals(observers, period, 4), "tail": signals(observers, period, 2)}
    process(sig["main"].head(2 * N), observers, main_row)  # compile (cached after the first run)
    total = 0.0
    for row in (main_row, tail_row):
        start = time.perf_counter()
        res = process(sig[row["rotor"]], observers, row)
        elapsed = time.perf_counter() - start
        total += elapsed
        d = res.diagnostics
        print(f"{row['rotor']}: {len(observers)} observers × {N} samples: {elapsed:.3f} s; "
              f"max M_r {d['mach_r'].max():.3f}, observers with shocks {(d['n_shocks'] > 0).sum()}")
    print(f"HSI stage, 2 rotors: {total:.3f} s (target < 2 s)")


if __name__ == "__main__":
    main()
