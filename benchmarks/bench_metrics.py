"""Benchmark of the metrics stage: a hemisphere observer set (19 x 72 = 1368 observers), two rotors,
1024 samples per revolution, HSI signals, broadband and absorption on. Prints timings (s)."""

import time

import numpy as np
import pandas as pd

from nps.noise import metrics

from nps.noise import spectra
from nps.core.atmosphere import isa


def _case(n_obs=1368, n=1024, seed=0):
    rng = np.random.default_rng(seed)
    period = 2 * np.pi / 28.0
    t = np.arange(n) * period / n
    eye = np.eye(3)
    trim = pd.DataFrame([
        {"rotor": name, "n_blades": 4, "radius_m": radius, "omega_rad_s": omega, "thrust_N": thrust, "ct": 0.005,
         "hub_x_m": hx, "hub_y_m": 0.0, "hub_z_m": 0.0, "speed_of_sound_mps": 340.29,
         **{f"r_gh_{i}{j}": eye[i, j] for i in range(3) for j in range(3)}}
        for name, radius, omega, thrust, hx in (("main", 7.62, 28.0, 5.0e4, 0.0), ("tail", 1.7, 140.0, 3.0e3, -9.9))
    ])
    el = np.radians(rng.uniform(-90, 0, n_obs))
    az = np.radians(rng.uniform(0, 360, n_obs))
    d = 76.2 * np.stack([-np.cos(az) * np.cos(el), -np.sin(az) * np.cos(el), np.sin(el)], 1)
    observers = pd.DataFrame({"observer": np.arange(n_obs, dtype=np.int32), "x_m": d[:, 0], "y_m": d[:, 1],
                              "z_m": d[:, 2], "elevation_deg": np.degrees(el), "azimuth_deg": np.degrees(az)})

    def table(groups):
        rows = len(groups) * n_obs * n
        return pd.DataFrame({
            "observer": np.tile(np.repeat(np.arange(n_obs, dtype=np.int32), n), len(groups)),
            "group": np.repeat(groups, n_obs * n),
            "time_s": np.tile(t, len(groups) * n_obs),
            "p_Pa": rng.normal(0, 5, rows),
        })

    signals = {r: table(["thickness", "loading"]) for r in ("main", "tail")}
    hsi = {r: table(["hsi"]) for r in ("main", "tail")}
    return signals, hsi, observers, trim


def main():
    signals, hsi, observers, trim = _case()
    t0 = time.perf_counter()
    metrics.metrics_tables(signals, observers, trim, {"main": 0.097, "tail": 0.1}, isa(0.0), hsi, True)
    t1 = time.perf_counter()
    p = np.random.default_rng(1).normal(size=(1368, 1024))
    f, msp = spectra.narrowband_msp(p, 1e-4)
    t2 = time.perf_counter()
    spectra.band_msp(f, msp, metrics.STUDY_BANDS)
    t3 = time.perf_counter()
    metrics.pnlt(np.random.default_rng(2).uniform(40, 90, (1368, 24)))
    t4 = time.perf_counter()
    print(f"metrics_tables, 1368 observers x 2 rotors x 1024 samples (+HSI, broadband, absorption): {t1 - t0:.2f} s")
    print(f"narrowband_msp 1368 x 1024: {t2 - t1:.3f} s; band_msp: {t3 - t2:.3f} s; pnlt 1368 spectra: {t4 - t3:.3f} s")


if __name__ == "__main__":
    main()
