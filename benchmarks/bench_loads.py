"""Benchmark: time to trim one 360 × 50 rotor (issue 3 target: < 1 s on the 2-core machine).

Demonstration helicopter main rotor (B = 4, R = 7.62 m, c = 0.58 m, Ω = 28 rad/s) at hover,
100 kt (μ 0.24) and segment 5 (μ 0.38). Prints the best and median of 5 runs per case and the
number of inner (inflow + flapping) Newton iterations. Run: ``python benchmarks/bench_loads.py``.
"""

import math
import statistics
import time

from nps.rotor.bet import DiskGrid, trim_rotor
from nps.rotor.geometry import OperatingPoint, RotorGeometry

R = 7.62
GEOM = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.15 * R,
                     twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0, hinge_offset_m=0.381)
CASES = {"hover": (0.0, 0.0), "100 kt (mu 0.24)": (0.241, 0.0126), "seg5 (mu 0.38)": (0.3827, 0.0643)}


def main() -> None:
    grid = DiskGrid(360, 50)
    print(f"{'case':<20}{'best s':>9}{'median s':>10}{'outer':>7}{'inner':>7}")
    for name, (mu_x, mu_z) in CASES.items():
        op = OperatingPoint(28.0, mu_x, 0.0, mu_z, 1.225, 340.3, 5140.1 * 9.80665)
        times = []
        for _ in range(5):
            start = time.perf_counter()
            result = trim_rotor(GEOM, op, grid)
            times.append(time.perf_counter() - start)
        evals = int(result.history["inner_iterations"].sum())
        print(f"{name:<20}{min(times):>9.3f}{statistics.median(times):>10.3f}{result.iterations:>7d}{evals:>7d}")


if __name__ == "__main__":
    main()
