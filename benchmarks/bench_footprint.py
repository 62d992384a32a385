"""Benchmark of a mission footprint: the demo mission's six-segment flight profile (helicopter
speeds, 11.5 km of track, 262 s), six 10 R source hemispheres (10 x 36 directions, 31 bands,
directional synthetic levels), a ground grid of 222 x 72 = 15,984 receivers at 70 m spacing plus
three microphones, hard ground, ISO 9613-1 absorption. Prints the wall time per aircraft (target
< 30 s on the project's 2-core machine) after a small warm-up run that compiles the kernels."""

import time

import numpy as np

from nps.app.config import load_mission
from nps.mission.footprint import GroundGrid, mission_footprint
from nps.mission.propagation import Ground, Hemisphere
from nps.mission.trajectory import mission_path

C = 340.29


def hemispheres(mission, aircraft):
    el = np.linspace(-90.0, 0.0, 10)
    az = np.arange(36) * 10.0
    bands = np.arange(-20, 11)
    e, a, b = np.meshgrid(np.radians(el), np.radians(az), bands, indexing="ij")
    out = {}
    for k, seg in enumerate(mission["segments"]):
        v = seg["aircraft"][aircraft]
        levels = 76.0 + 4.0 * np.cos(a) * np.cos(e) + 3.0 * np.sin(e) ** 2 - 0.4 * (b + 5) ** 2 / 10.0 + k
        out[seg["id"]] = Hemisphere(el, az, bands, levels, 76.2, np.array([v["forward_speed_mps"], 0.0, v["climb_speed_mps"]]), C)
    return out


def main():
    mission = load_mission("config/missions/demo.yaml")
    path = mission_path(mission, "helicopter")
    hemis = hemispheres(mission, "helicopter")
    mics = {"m1": (1000.0, 0.0, 1.2), "m2": (5000.0, 150.0, 1.2), "m3": (10500.0, -150.0, 1.2)}
    t0 = time.perf_counter()
    mission_footprint(path, hemis, GroundGrid((0.0, 2000.0), (-500.0, 500.0), 500.0), mics, C, ground=Ground("hard"))
    t1 = time.perf_counter()
    grid = GroundGrid((-2000.0, 13540.0), (-2485.0, 2485.0), 70.0)
    fp = mission_footprint(path, hemis, grid, mics, C, ground=Ground("hard"))
    t2 = time.perf_counter()
    n_times = fp.histories["time_s"].nunique()
    print(f"warm-up (compiles on a fresh cache): {t1 - t0:.1f} s")
    print(f"footprint: {len(fp.grid)} receivers + {len(mics)} microphones x {n_times} half-second records, "
          f"{len(path.legs)} legs: {t2 - t1:.1f} s")
    print(fp.areas.to_string(index=False))


if __name__ == "__main__":
    main()
