"""Benchmark: wake + induced velocity for a 4-blade, 360 × 50 disk with a 4-revolution wake at
1° resolution (issue 4 target: < 3 s on the 2-core machine).

That is 18,000 blade stations × 4 blades × 1,440 vortex segments ≈ 1.04e8 segment
evaluations (``nps.wake.prescribed.disk_induced_velocity``: every azimuth row builds its own wake
snapshot and rows run in parallel). Also times the whole BVI step (``nps.wake.bvi.bvi_loads``:
kernel + Sears filter + section loads). Case: demonstration helicopter main rotor at the
thesis Table 5.2 condition (μ_x = 0.23, 6° descent, C_T = 0.0095). Prints the first call
(including numba's cache load or compilation), then best and median of 5 runs.

Roofline of the Biot–Savart sum (issue 36, part 4): the sweep's evaluations per second on 1 and all threads, for
the Betz structure (the default) and the point vortex, against the flops of one segment-point evaluation (a model
count of ``nps.wake.vortex._sweep`` and ``segment_velocity`` with n = 2, :data:`FLOPS`), the machine's peak FP64
rate and the bound that its divisions and square roots set (measured throughput per double,
``bench_acoustics.machine``).
Run from the repository root: ``python benchmarks/bench_wake.py``.
"""

import math
import statistics
import time

import numba

from nps.rotor import bet

from nps.wake import bvi

from nps.wake import prescribed as wake
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.wake.vortex import VortexModel

from bench_acoustics import machine

R, OMEGA, MU_X, CT = 7.62, 28.0, 0.23, 0.0095
GEOM = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.15 * R,
                     twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0, hinge_offset_m=0.381)


# flops per segment-point evaluation (+, −, ×, ÷ and √ one flop each; loop-invariant terms of a segment left
# out): the new end point's vector and norm 9 (one √), r0 3, r1×r2 9, |r0|² 5, |r1×r2|² 5, the projection
# difference 13, the n = 2 Vatistas denominator 6 (one √), the point-vortex factor 4 (one ÷), the velocity and its
# sum 6; the Betz structure factor adds u 3 (one ÷), x 3, the degree-10 polynomial 20 and Γ·T 1.
FLOPS = {"point": {"flops": 60, "div": 1, "sqrt": 2}, "betz": {"flops": 87, "div": 2, "sqrt": 2}}


def timed(fn, repeats=5):
    start = time.perf_counter()
    fn()
    first = time.perf_counter() - start
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return first, min(times), statistics.median(times)


def main() -> None:
    mu_z = -MU_X * math.tan(math.radians(6.0))
    thrust = CT * 1.225 * math.pi * R**2 * (OMEGA * R) ** 2
    op = OperatingPoint(OMEGA, MU_X, 0.0, mu_z, 1.225, 340.3, thrust)
    trim = bet.trim_rotor(GEOM, op, bet.DiskGrid(360, 50))
    row = dict(n_blades=4, radius_m=R, omega_rad_s=OMEGA, rotation_sign=1, mu_x=MU_X, mu_y=0.0, mu_z=mu_z,
               density_kg_m3=1.225, speed_of_sound_mps=340.3)
    state = bvi.wake_state(trim.disk, row, trim.totals.ct)
    model = wake.WakeModel(revolutions=4.0, steps_per_rev=360)
    grid = bvi.disk_grid(trim.disk)
    beta = trim.disk["beta_rad"].to_numpy().reshape(grid.shape)
    evaluations = grid.shape[0] * grid.shape[1] * state.n_blades * model.n_age
    print(f"numba threads: {numba.get_num_threads()}; segment evaluations per call: {evaluations:.3g}")
    print(f"{'step':<34}{'first s':>9}{'best s':>9}{'median s':>10}{'ns/eval':>9}")
    first, best, median = timed(lambda: wake.disk_induced_velocity(state, model, grid.psi_rad, grid.r_m, beta))
    print(f"{'wake + induced velocity':<34}{first:>9.3f}{best:>9.3f}{median:>10.3f}{best / evaluations * 1e9:>9.2f}")
    roofline(state, grid, beta, evaluations)
    first, best, median = timed(lambda: bvi.bvi_loads(trim.disk, row, GEOM, trim.totals.ct, model))
    print(f"{'BVI loads (kernel+Sears+BET)':<34}{first:>9.3f}{best:>9.3f}{median:>10.3f}{'':>9}")
    print(f"target < 3 s: {'met' if best < 3.0 else 'NOT met'}")


def roofline(state, grid, beta, evaluations) -> None:
    """Evaluations per second of the sweep on 1 and all threads, Betz and point vortex, against the peak and
    the division/square-root bound of this machine."""
    hw = machine(5)
    threads = numba.get_num_threads()
    print(f"machine: {hw['model']}, peak {hw['peak_core'] / 1e9:.1f} GFLOP/s per core (cpuinfo clock); division "
          f"{hw['t_div'] * 1e9:.3f} ns, square root {hw['t_sqrt'] * 1e9:.3f} ns per double")
    for structure, count in FLOPS.items():
        model = wake.WakeModel(revolutions=4.0, steps_per_rev=360, vortex=VortexModel(vortex_structure=structure))
        floor = count["div"] * hw["t_div"] + count["sqrt"] * hw["t_sqrt"]
        for n in sorted({1, threads}):
            numba.set_num_threads(n)
            _, best, _ = timed(lambda: wake.disk_induced_velocity(state, model, grid.psi_rad, grid.r_m, beta), 3)
            rate = evaluations / best
            print(f"{structure:>5} vortex, {n} thread(s): {best:.3f} s, {rate / 1e6:.0f} M evaluations/s; "
                  f"{count['flops']} flops each = {rate * count['flops'] / 1e9:.1f} GFLOP/s, "
                  f"{rate * count['flops'] / (hw['peak_core'] * n):.0%} of the peak, "
                  f"{rate * floor / n:.0%} of the ÷/√ bound ({n / floor / 1e6:.0f} M/s)")
        numba.set_num_threads(threads)


if __name__ == "__main__":
    main()
