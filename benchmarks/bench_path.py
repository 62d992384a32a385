"""Benchmark of the noise along a flight path (issue 37): a 3-minute helicopter approach with a turn (level leg,
a 180° descending turn, a decelerating 6° final; nps.mission.paths at 0.5 s, 361 samples), 100 synthetic
directional source hemispheres (10 × 36 directions, 31 bands) standing for 100 trim states, each chord blending
two of them, over 16,000 ground receivers (160 × 100 at 50 m) plus five microphones, hard ground, ISO 9613-1
absorption. Prints the plan time, the propagation time (what dominates), the peak memory and the states' reuse
between two procedures that share a leg.

    python benchmarks/bench_path.py

The states' own chains (trim, loads, wake, BVI, acoustics, source hemisphere) are workflow jobs, timed by the
campaign's benchmark files (results/benchmarks/*/<aircraft>/<key>.tsv) and summed by benchmarks/campaign_times.py."""

from __future__ import annotations

import resource
import time

import numpy as np

from nps.app.config import load_aircraft, load_path
from nps.core.atmosphere import isa
from nps.mission.footprint import GroundGrid
from nps.mission.path_noise import PathSamples, path_footprint
from nps.mission.path_states import plan_path
from nps.mission.propagation import Ground, Hemisphere

C = 340.29
PATH = {
    "name": "bench_path", "aircraft": "helicopter",
    "start": {"position_m": [-4000.0, 0.0], "height_m": 300.0, "heading_deg": 0.0, "speed_mps": 35.0},
    "legs": [{"straight": {"distance_m": 2000.0}},
             {"turn": {"heading_change_deg": 180.0, "radius_m": 600.0}, "height_change_m": -100.0},
             {"straight": {"distance_m": 1800.0}, "flight_path_deg": -6.0, "end_speed_mps": 20.0}],
}
SETTINGS = {"dt_s": 0.5, "state_tolerances": {"advance_ratio": 0.01, "flight_path_deg": 1.0, "load_factor": 0.05,
                                              "rotor_speed_fraction": 0.02}}


def hemispheres(n: int) -> list[Hemisphere]:
    el, az, bands = np.linspace(-90.0, 0.0, 10), np.arange(36) * 10.0, np.arange(-20, 11)
    e, a, b = np.meshgrid(np.radians(el), np.radians(az), bands, indexing="ij")
    return [Hemisphere(el, az, bands, 76.0 + 4.0 * np.cos(a + 0.05 * k) * np.cos(e) + 3.0 * np.sin(e) ** 2
                       - 0.04 * (b + 5) ** 2 + 0.05 * k, 76.2, np.array([30.0, 0.0, -2.0]), C) for k in range(n)]


def main():
    aircraft = load_aircraft("config/aircraft/helicopter.yaml")
    import tempfile, yaml, os  # noqa: E401 - the path is written as a user would
    with tempfile.TemporaryDirectory() as folder:
        file = os.path.join(folder, "bench_path.yaml")
        with open(file, "w") as handle:
            yaml.safe_dump(PATH, handle)
        path = load_path(file, SETTINGS["dt_s"])
    t0 = time.perf_counter()
    plan = plan_path(aircraft, path, SETTINGS, isa(0.0, 0.0, 70.0))
    t_plan = time.perf_counter() - t0
    h = plan.history
    n = h.time_s.size
    # 100 states: the path's own bracketing pattern spread over 100 hemispheres (each chord blends two)
    state = (np.arange(n) * 100) // n
    neighbour = np.minimum(state + 1, 99)
    weight = ((np.arange(n) * 100) % n) / n
    gamma_e = np.arcsin(np.clip(h.tangential_g, -1.0, 1.0))
    samples = PathSamples(h.time_s, h.position_m, h.heading_rad, h.flight_path_rad, gamma_e, h.leg, state, neighbour,
                          weight)
    hemis = hemispheres(100)
    mics = {f"m{i}": (-3000.0 + 800.0 * i, 200.0 * (i % 3 - 1), 1.2) for i in range(5)}
    small = GroundGrid((-1000.0, 0.0), (-500.0, 500.0), 500.0)
    path_footprint(samples, [f"leg{k}" for k in range(3)], hemis, small, mics, C, ground=Ground("hard"))  # compile
    grid = GroundGrid((-5000.0, 2950.0), (-2000.0, 2950.0), 50.0)
    t1 = time.perf_counter()
    fp = path_footprint(samples, [f"leg{k}" for k in range(3)], hemis, grid, mics, C, ground=Ground("hard"))
    t_prop = time.perf_counter() - t1
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"path: {h.time_s[-1]:.0f} s, {n} samples, {len(set(plan.keys))} states of its own (tolerances of the "
          f"campaign), plan {t_plan * 1e3:.0f} ms")
    print(f"propagation: {len(fp.grid)} receivers + {len(mics)} microphones, 100 states blended per chord: "
          f"{t_prop:.1f} s wall; peak resident memory {peak_mb:.0f} MB")
    # reuse: a second procedure sharing the first leg (same speed, height) reuses its states' keys
    other = {**PATH, "legs": [PATH["legs"][0], {"straight": {"distance_m": 1500.0}, "flight_path_deg": -9.0}]}
    with tempfile.TemporaryDirectory() as folder:
        file = os.path.join(folder, "bench_path.yaml")
        with open(file, "w") as handle:
            yaml.safe_dump(other, handle)
        second = plan_path(aircraft, load_path(file, SETTINGS["dt_s"]), SETTINGS, isa(0.0, 0.0, 70.0))
    shared = set(plan.keys) & set(second.keys)
    print(f"second procedure: {len(set(second.keys))} states, {len(shared)} shared with the first (computed once)")


if __name__ == "__main__":
    main()
