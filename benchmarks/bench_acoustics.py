"""Acoustics benchmark: compact F1A throughput against the machine's roofline, and a full-hemisphere wall time.

Case: one 4-blade rotor (R = 7.62 m, c = 0.58 m, t/c = 0.09, Ω = 28 rad/s) at 40 m/s with an
analytic 1/rev-varying loading on 50 stations × 360 azimuths, dual-compact thickness (three
lines per blade), 1,368 observers (19 elevations × 72 azimuths, 10 R, moving with the
aircraft), 1,024 samples per revolution: blade 0 over one period, 150 nodes × 360 source steps × 1,368
observers = 73.9 M evaluations of the F1A kernel (``nps.noise.acoustics._radiate_kernel``). Prints

* the kernel's evaluations per second (source node × source time × observer) with one thread and with all
  threads (numba), its CPU time, and the same for ``radiate_arrays`` (packing, kernel, Fourier blade sum);
* the flops of one evaluation (a model count of the formulation: reception, integrand, divided differences,
  cubic per target; 6 divisions and a square root among them), the achieved GFLOP/s and their fraction of
  the machine's peak FP64 rate (cores × SIMD lanes × 2 FMA units × 2 flops × clock, from /proc/cpuinfo) and
  of the divider bound (measured division and square-root throughput: the floor of one evaluation);
* with ``--baseline REV`` (e.g. ``c30d6c6``): the same measured for the ``nps`` of git revision REV (``git
  archive`` into a temporary directory, run in a subprocess with its own numba cache), side by side, and
  whether the kernel outputs and the full hemispheres are bit-identical (``np.array_equal``);
* the wall time of the full hemisphere (source lines + kernel + blade sum and resampling).

Each figure is the best of ``--repeats`` runs (the machine is shared; the best run is the least disturbed);
the load average is printed before and after. Run: ``python benchmarks/bench_acoustics.py [--baseline c30d6c6]``.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np
import pandas as pd

from nps.noise import acoustics
from nps.noise.acoustics import Observers, TimeGrid, periodic_samples, radiate_arrays
from nps.noise.observers import hemisphere
from nps.noise.sources import ThicknessModel, radiate_rotor, rotor_sources
from nps.rotor.geometry import RotorMotion

C0, RHO0 = 340.294, 1.225
REPO = Path(__file__).resolve().parents[1]


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
           "vel_x_mps": speed, "vel_y_mps": 0.0, "vel_z_mps": 0.0, "speed_of_sound_mps": C0, "density_kg_m3": RHO0}
    row.update({f"r_gh_{i}{j}": float(i == j) if (i, j) not in ((0, 0), (1, 1)) else -1.0 for i in range(3) for j in range(3)})
    obs = hemisphere([0.0, 0.0, 1.8], 10 * radius, 19, 72, [speed, 0.0, 0.0])
    observers = Observers(obs[["x_m", "y_m", "z_m"]].to_numpy(), obs[["vx_mps", "vy_mps", "vz_mps"]].to_numpy())
    grid = TimeGrid(0.0, 2 * np.pi / omega, 1024)
    return disk, row, observers, grid


def best_time(function, repeats: int) -> tuple[float, float]:
    """Shortest wall time and shortest CPU time (s) of ``repeats`` calls."""
    wall, cpu = [], []
    for _ in range(repeats):
        start, start_cpu = time.perf_counter(), time.process_time()
        function()
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(wall), min(cpu)


def flops_per_evaluation(n_tau: int, n_out: int) -> dict:
    """Model flop count of one evaluation (one node, one source step, one observer), each +, −, ×, ÷ and √ one
    flop: reception time (s from the quadratic, t = τ + s: 20, one ÷ and one √), radiation vector r = d + v_o s (6),
    F1A dipole integrand (43, two ÷), Newton divided differences of the n_tau + 5 periodic samples (9 per sample,
    three ÷) and the cubic at the n_out/n_tau targets of a source step (t = base + q dt: 2, Newton form: 9,
    accumulation: 1; 13 per target, no ÷)."""
    parts = {"reception": 20.0, "radiation vector": 6.0, "integrand": 43.0,
             "divided differences": 9.0 * (n_tau + 5) / n_tau, "interpolation": 13.0 * n_out / n_tau}
    parts["total"] = sum(parts.values())
    return parts


def _divider_kernels():
    """numba loops of divisions and square roots over arrays that stay in L1 (throughput, not latency)."""
    @numba.njit(error_model="numpy")
    def divide(reps, a, b, out):
        for _ in range(reps):
            for k in range(a.size):
                out[k] = a[k] / b[k]

    @numba.njit(error_model="numpy")
    def root(reps, a, out):
        for _ in range(reps):
            for k in range(a.size):
                out[k] = np.sqrt(a[k])

    return divide, root


def machine(repeats: int) -> dict:
    """Cores, SIMD width, nominal clock and peak FP64 rate from /proc/cpuinfo; measured ÷ and √ throughput."""
    info = Path("/proc/cpuinfo").read_text() if Path("/proc/cpuinfo").exists() else ""
    fields = {key.strip(): value.strip() for key, value in (line.split(":", 1) for line in info.splitlines() if ":" in line)}
    flags = set(fields.get("flags", "").split())
    lanes = 8 if "avx512f" in flags else 4 if "avx2" in flags or "avx" in flags else 2
    if fields.get("vendor_id") == "AuthenticAMD" and int(fields.get("cpu family", "0")) < 26:
        lanes = min(lanes, 4)  # Zen 4 runs AVX-512 on 256-bit pipes: 4 FP64 lanes per FMA per cycle (Zen 5: 8)
    fma_units = 2 if "fma" in flags else 1
    mhz = float(fields.get("cpu MHz") or 0)
    cores = os.cpu_count() or 1
    per_core = lanes * fma_units * 2 * mhz * 1e6
    divide, root = _divider_kernels()
    a, b, out = np.random.default_rng(0).uniform(1.0, 2.0, (3, 1024))
    divide(1, a, b, out)
    root(1, a, out)
    reps = 20000
    t_div = best_time(lambda: divide(reps, a, b, out), repeats)[1] / (reps * a.size)
    t_sqrt = best_time(lambda: root(reps, a, out), repeats)[1] / (reps * a.size)
    return {"model": fields.get("model name", "?"), "cores": cores, "lanes": lanes, "fma_units": fma_units,
            "mhz": mhz, "peak_core": per_core, "peak": per_core * cores, "t_div": t_div, "t_sqrt": t_sqrt,
            "divider_floor": 6 * t_div + t_sqrt}


def measure(repeats: int, save: str | None) -> dict:
    """Kernel and radiate_arrays throughput of the installed ``nps`` on 1 and all threads; the full hemisphere."""
    disk, row, observers, grid = case()
    threads = numba.get_num_threads()
    sources = rotor_sources(disk, RotorMotion.from_trim_row(row), thickness=ThicknessModel(), rho0_kg_m3=RHO0, c0_mps=C0)
    period = float(sources.period_s)
    n_out = periodic_samples(period, grid)
    xo, vo = (np.ascontiguousarray(a, dtype=float) for a in (observers.position_m, observers.velocity_mps))
    packed = acoustics._pack_sources(sources, C0, period)

    def kernel(x=xo, v=vo):
        return acoustics._radiate_kernel(*packed, x, v, C0, RHO0, float(grid.t_start_s), period / n_out, n_out, period)

    kernel(xo[:2], vo[:2])  # compile
    radiate_arrays(sources, Observers(xo[:2], vo[:2]), grid)
    n_node, n_tau = sources.position_m.shape[:2]
    result = {"evaluations": n_node * n_tau * len(xo), "n_tau": n_tau, "n_out": n_out, "threads": {}}
    for n_threads in sorted({1, threads}):
        numba.set_num_threads(n_threads)
        result["threads"][n_threads] = {"kernel": best_time(kernel, repeats),
                                        "radiate_arrays": best_time(lambda: radiate_arrays(sources, observers, grid), repeats)}
    numba.set_num_threads(threads)
    p = radiate_rotor(disk, row, observers, grid)
    result["hemisphere_s"] = best_time(lambda: radiate_rotor(disk, row, observers, grid), repeats)[0]
    result["p_rms_max"] = float(np.sqrt((p.sum(1) ** 2).mean(-1)).max())
    if save:
        np.savez(save, kernel=kernel(), hemisphere=p)
    return result


def baseline(revision: str, repeats: int, save: str) -> dict:
    """:func:`measure` for the ``nps`` of a git revision, in a subprocess (its sources first on sys.path)."""
    tree = Path(tempfile.mkdtemp(prefix="nps_baseline_"))
    archive = subprocess.run(["git", "-C", str(REPO), "archive", revision, "nps"], check=True, capture_output=True).stdout
    subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tree), os.environ.get("PYTHONPATH", "")]),
               NUMBA_CACHE_DIR=str(tree / "numba_cache"))
    done = subprocess.run([sys.executable, __file__, "--measure-only", "--repeats", str(repeats), "--save", save],
                          env=env, cwd=str(tree), check=True, capture_output=True, text=True)
    return json.loads(done.stdout.splitlines()[-1])


def report(label: str, result: dict, hw: dict, flops: float) -> None:
    evals = result["evaluations"]
    for n_threads, times in sorted(result["threads"].items(), key=lambda kv: int(kv[0])):
        wall, cpu = times["kernel"]
        rate = evals / wall
        print(f"{label} kernel, {n_threads} thread(s): {evals / 1e6:.1f} M evaluations in {wall:.3f} s (CPU {cpu:.3f} s) = "
              f"{rate / 1e6:.1f} M/s ({rate / 1e6 / int(n_threads):.1f} M/s per thread); {rate * flops / 1e9:.1f} GFLOP/s = "
              f"{rate * flops / (hw['peak_core'] * int(n_threads)):.1%} of the peak of {n_threads} core(s), "
              f"{rate * hw['divider_floor'] / int(n_threads):.1%} of the divider bound")
        wall, cpu = times["radiate_arrays"]
        print(f"{label} radiate_arrays, {n_threads} thread(s): {wall:.3f} s (CPU {cpu:.3f} s) = {evals / wall / 1e6:.1f} M/s")
    print(f"{label} full hemisphere: {result['hemisphere_s']:.2f} s (p_rms max {result['p_rms_max']:.2f} Pa)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs per figure; the best is reported")
    parser.add_argument("--baseline", help="git revision whose kernel is measured side by side (e.g. c30d6c6)")
    parser.add_argument("--measure-only", action="store_true", help="print the measurement as JSON (baseline subprocess)")
    parser.add_argument("--save", help="write the kernel output and the hemisphere to this .npz")
    args = parser.parse_args()
    if args.measure_only:
        print(json.dumps(measure(args.repeats, args.save)))
        return
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    hw = machine(args.repeats)
    print(f"machine: {hw['model']}, {hw['cores']} cores, {hw['lanes']} FP64 lanes x {hw['fma_units']} FMA units x 2 flops "
          f"x {hw['mhz']:.0f} MHz (cpuinfo) = peak {hw['peak_core'] / 1e9:.1f} GFLOP/s per core, {hw['peak'] / 1e9:.1f} in all; "
          f"measured division {hw['t_div'] * 1e9:.3f} ns and square root {hw['t_sqrt'] * 1e9:.3f} ns per double: "
          f"divider bound {hw['divider_floor'] * 1e9:.2f} ns per evaluation and core ({1e-6 / hw['divider_floor']:.0f} M/s)")
    with tempfile.TemporaryDirectory() as scratch:
        new_file, old_file = os.path.join(scratch, "new.npz"), os.path.join(scratch, "old.npz")
        current = measure(args.repeats, new_file)
        model = flops_per_evaluation(current["n_tau"], current["n_out"])
        print("flops per evaluation (model): " + ", ".join(f"{k} {v:.1f}" for k, v in model.items()))
        report("this tree", current, hw, model["total"])
        if args.baseline:
            old = baseline(args.baseline, args.repeats, old_file)
            report(args.baseline, old, hw, model["total"])
            a, b = np.load(new_file), np.load(old_file)
            print(f"bit-identical to {args.baseline}: kernel output {np.array_equal(a['kernel'], b['kernel'])}, "
                  f"full hemisphere {np.array_equal(a['hemisphere'], b['hemisphere'])}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
