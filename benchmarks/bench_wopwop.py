"""Benchmark of ``nps wopwop run`` (:func:`nps.wopwop.run.run_case`) on surface panels against NPS's compact solver.

Case (issue 33 acceptance): a 4-blade rotor, R = 7.62 m, root cut-out 0.15 R, chord 0.58 m, untwisted NACA 0012
(closed trailing edge), collective 8 deg about the quarter chord, Ω = 28 rad/s (M_tip 0.63), ρ0 = 1.225 kg/m³,
c0 = 340.294 m/s. Each blade is one PSU-WOPWOP container whose constant, structured, node-centred geometry file
holds two zones in the blade frame:

* the blade surface as ONE WRAP of 26 × 51 nodes (i: trailing edge → lower side → leading edge → upper side →
  trailing edge on a cosine spacing, the two trailing-edge rows coincide; j: 51 radii from root to tip), unit
  outward normals: 25 × 50 = 1,250 face-centred panels, thickness noise only (the open root and tip ends are not
  closed, as in PSU-WOPWOP);
* a compact lifting line (iMax = 1) at the quarter chord, 50 nodes at the strip mid-radii, normals (0, 0, dr),
  with a periodic loading-vector file (frame 3, keys 0 … N, a steady thrust 900 (r/R)² N/m and drag 60 r/R N/m).

Observers: a sphere (``&ObserverIn`` radius 10 R, nbTheta 40 over 0 … 351 deg, nbPsi 25 over −60 … +60 deg:
1,000 observers) around the hub; one revolution, nt = 1,024 samples (tMin 0, tMax = 1023 T/1024); source step
dTau = T/256 (the compact solver's thickness and loading at 256 steps are within 3e-6 (rms) of 1,024 steps). Two
variants: (a) hover (no translation, observers at rest: run_case's periodic path, where the four identical blades
are radiated once as copies, as NPS does), (b) forward flight at 40 m/s (a KnownFunction translation CB, observers at
rest: the direct path, every blade over the 424 source steps the window needs).

Reference: NPS's compact solver on the same rotor (:func:`nps.noise.sources.radiate_rotor`, disk table built here,
dual-compact thickness with the area of the paneled section, the same lifting line), at the same observers and
grid. Each of the four runs (wopwop / compact × hover / forward) is a fresh process with NUMBA_NUM_THREADS set
(default 2): the case is written first (excluded from the time), then the run is made twice, the first reported,
the second timed (numba cache warm; for wopwop the case reading is inside the time; a '*' marks a first run that
compiled kernels: the cache is keyed by a hash of every nps source, so any edit of nps/ makes it cold). Printed per
run: case size (points, source steps, observers, samples, kernel evaluations = points × source steps × observers),
the time and the kernel's share (radiate_arrays), evaluations per second, the peak RSS of the timed run (VmHWM,
reset before it) and its RSS at start, the process's max RSS (ru_maxrss, first run included), the ratio
wopwop / compact, and the difference of the two pressures (loading: the same lifting line, expected to agree to
float32 rounding, checked below 1e-3; thickness: panels against dual-compact lines). The load average is printed:
on a shared machine the times scale with it.

    python benchmarks/bench_wopwop.py [--quick] [--threads N] [--trace]

``--quick``: a small case (14 × 11 nodes, 10 × 5 observers, 64 steps, 256 samples; ~8 s); ``--trace``: a third
run with tracemalloc (the traced peak of Python and numpy allocations; numba's own allocations are not traced).

Measured (2 threads, load average 0.5–1.4, warm cache, 95 s in all): hover wopwop 5.5 s (0.33 G evaluations, 60 M/s,
peak RSS 443 MB) against compact 0.59 s (0.038 G, 65 M/s, 309 MB); forward wopwop 35.0 s (2.2 G, 63 M/s, 586 MB;
26.4 s in the kernel, ~4.3 s in run.source_span) against compact 2.78 s (0.26 G, 94 M/s, 340 MB). Loading
agrees to 2.6e-8 (rms); thickness, panels against dual-compact lines: 4.5 % rms hover, 8.9 % forward (the same with
a 51-node wrap: the dual-compact model's error; the runner's forward-flight panels agree with a numpy panel sum to
1e-5 of the peak-to-peak).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

RADIUS, ROOT, CHORD, THICKNESS_RATIO = 7.62, 0.15 * 7.62, 0.58, 0.12
OMEGA, N_BLADES, PITCH = 28.0, 4, np.radians(8.0)
C0, RHO0, SPEED = 340.294, 1.225, 40.0
FZ_TIP, FX_TIP = 900.0, 60.0  # N/m at the tip: fz (r/R)², fx r/R
PSI_RANGE = np.radians(60.0)  # observer elevations −60 … +60 deg
LOADING_TOLERANCE = 1e-3  # relative rms difference of the loading pressures (the same lifting line in both)
VARIANTS = ("hover", "forward")


@dataclass(frozen=True)
class Size:
    """Grid sizes: blade nodes (chordwise wrap × spanwise), observer sphere, source steps and samples per rev."""

    n_wrap: int = 26
    n_span: int = 51
    n_theta: int = 40
    n_psi: int = 25
    n_steps: int = 256
    n_samples: int = 1024


QUICK = Size(14, 11, 10, 5, 64, 256)


# --------------------------------------------------------------------------- the blade
def half_thickness(x):
    """NACA 0012 half thickness / c at x/c (closed trailing edge: coefficient −0.1036)."""
    return 5 * THICKNESS_RATIO * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)


def section(n_wrap: int):
    """The wrap in section coordinates (chord offset d toward the leading edge from the quarter chord, thickness
    offset h), m, and outward unit normals (n_d, n_h): TE → lower side → LE → upper side → TE, cosine spaced."""
    phi = 2.0 * np.pi * np.arange(n_wrap) / (n_wrap - 1)
    x = 0.5 * (1.0 + np.cos(phi))
    d = (0.25 - x) * CHORD
    h = -np.sign(np.round(np.sin(phi), 12)) * half_thickness(x) * CHORD
    tangent = np.stack([np.gradient(d), np.gradient(h)], axis=-1)
    normal = np.stack([tangent[:, 1], -tangent[:, 0]], axis=-1)  # the wrap turns counter-clockwise: right = outward
    return d, h, normal / np.linalg.norm(normal, axis=-1, keepdims=True)


def section_area_factor(n_wrap: int) -> float:
    """Area of the paneled section (polygon of the wrap) / (t c): the compact lines carry the same volume."""
    d, h, _ = section(n_wrap)
    return float(0.5 * abs(np.dot(d, np.roll(h, -1)) - np.dot(h, np.roll(d, -1))) / (THICKNESS_RATIO * CHORD**2))


def span_edges(n_span: int) -> np.ndarray:
    return np.linspace(ROOT, RADIUS, n_span)


def blade_surface(size: Size):
    """Surface nodes and unit normals in the blade frame (e_r, e_t, z), i (wrap) fastest: (n_wrap·n_span, 3)."""
    d, h, normal = section(size.n_wrap)
    c, s = np.cos(PITCH), np.sin(PITCH)
    r = span_edges(size.n_span)
    rr, dd = np.meshgrid(r, d, indexing="ij")
    hh = np.broadcast_to(h, rr.shape)
    xyz = np.stack([rr, dd * c - hh * s, dd * s + hh * c], axis=-1).reshape(-1, 3)
    nd, nh = (np.broadcast_to(normal[:, k], rr.shape) for k in range(2))
    normals = np.stack([np.zeros_like(rr), nd * c - nh * s, nd * s + nh * c], axis=-1).reshape(-1, 3)
    return xyz, normals


def stations(size: Size) -> tuple[np.ndarray, np.ndarray]:
    """Strip mid-radii and widths (m) of the lifting line and of the compact solver's disk table."""
    edges = span_edges(size.n_span)
    return 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)


def loads(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Steady thrust and drag per unit span (N/m) on the blade."""
    return FZ_TIP * (r / RADIUS) ** 2, FX_TIP * r / RADIUS


# --------------------------------------------------------------------------- the PSU-WOPWOP case
def blade_files(size: Size):
    """(geometry file, functional file): the surface and the lifting line (constant), the line's periodic loads."""
    from nps.wopwop import binary

    xyz, normals = blade_surface(size)
    r, dr = stations(size)
    n_r = r.size
    line = np.stack([r, np.zeros(n_r), np.zeros(n_r)], axis=-1)
    line_normals = np.stack([np.zeros(n_r), np.zeros(n_r), dr], axis=-1)
    none = np.zeros(0, np.float32)
    zones = (binary.GeometryZone("blade surface", True, size.n_wrap, size.n_span, (), xyz.shape[0], None, none,
                                 xyz[None].astype(np.float32), normals[None].astype(np.float32), None),
             binary.GeometryZone("lifting line", True, 1, n_r, (), n_r, None, none, line[None].astype(np.float32),
                                 line_normals[None].astype(np.float32), None))
    geometry = binary.GeometryFile("m", "bench_wopwop blade", binary.CONSTANT, False, zones)
    fz, fx = loads(r)
    keys = np.arange(size.n_steps + 1, dtype=np.float32)
    per_span = np.broadcast_to(np.stack([np.zeros(n_r), -fx, fz], axis=-1), (keys.size, n_r, 3)).astype(np.float32)
    data = binary.FunctionalZone(2, False, "lifting line", True, 1, n_r, n_r, float(np.float32(2 * np.pi / OMEGA)),
                                 keys, per_span)
    functional = binary.FunctionalFile("bench_wopwop loads", 2, True, binary.PERIODIC, False, binary.LOADING_VECTOR,
                                       binary.PATCH_FRAME, (data,))
    return geometry, functional


def case_groups(size: Size, variant: str):
    """The case file's namelist groups: environment, the observer sphere, the rotor and its four blades (floats as
    Python floats: nps.wopwop.namelist.format_value writes a numpy float64 as 'np.float64(...)', which no reader
    takes)."""
    from nps.wopwop.namelist import Group

    period = 2 * np.pi / OMEGA
    rotor_cbs = [Group("CB", {"Title": "rotation", "Rotation": True, "AxisType": "TimeIndependent",
                              "AngleType": "KnownFunction", "AxisValue": (0.0, 0.0, 1.0), "Omega": OMEGA, "Psi0": 0.0})]
    if variant == "forward":
        rotor_cbs.insert(0, Group("CB", {"Title": "flight", "TranslationType": "KnownFunction",
                                         "VH": (SPEED, 0.0, 0.0), "Y0": (0.0, 0.0, 0.0)}))
    groups = [Group("EnvironmentIn", {"nbSourceContainers": 1, "nbObserverContainers": 1, "acousticPressureFlag": True,
                                      "thicknessNoiseFlag": True, "loadingNoiseFlag": True, "totalNoiseFlag": True}),
              Group("EnvironmentConstants", {"rho": RHO0, "c": C0}),
              Group("ObserverIn", {"Title": "sphere", "nt": size.n_samples, "tMin": 0.0,
                                   "tMax": float((size.n_samples - 1) * period / size.n_samples), "radius": 10 * RADIUS,
                                   "nbTheta": size.n_theta, "nbPsi": size.n_psi, "thetaMin": 0.0,
                                   "thetaMax": float(2 * np.pi * (size.n_theta - 1) / size.n_theta),
                                   "psiMin": float(-PSI_RANGE), "psiMax": float(PSI_RANGE)}),
              Group("ContainerIn", {"Title": "rotor", "nbContainer": N_BLADES, "nbBase": len(rotor_cbs),
                                    "dTau": float(period / size.n_steps)}),
              *rotor_cbs]
    for k in range(N_BLADES):
        groups += [Group("ContainerIn", {"Title": f"blade {k + 1}", "patchGeometryFile": "blade_geometry.dat",
                                         "patchLoadingFile": "blade_loading.dat", "nbBase": 1,
                                         "periodicKeyOffset": float(k * size.n_steps // N_BLADES)}),
                   Group("CB", {"Title": "blade azimuth", "AxisType": "TimeIndependent", "AngleType": "TimeIndependent",
                                "AxisValue": (0.0, 0.0, 1.0), "AngleValue": float(2 * np.pi * k / N_BLADES)})]
    return groups


def write_case(size: Size, variant: str, directory: Path) -> Path:
    """Write ``cases.nam``, the case file and the blade's two binary files; returns the ``cases.nam`` path."""
    from nps.wopwop import binary
    from nps.wopwop.namelist import Group, format_namelist

    directory.mkdir(parents=True)
    geometry, functional = blade_files(size)
    binary.write_geometry(geometry, directory / "blade_geometry.dat")
    binary.write_functional(functional, directory / "blade_loading.dat")
    (directory / "case.nam").write_text(format_namelist(case_groups(size, variant)))
    cases = directory / "cases.nam"
    cases.write_text(format_namelist([Group("casename", {"globalFolderName": "./", "caseNameFile": "case.nam"})]))
    return cases


# --------------------------------------------------------------------------- the compact reference
def sphere(size: Size) -> np.ndarray:
    """The observer sphere (n, 3), m, in PSU-WOPWOP's order (elevation outer, azimuth fastest)."""
    theta = 2 * np.pi * np.arange(size.n_theta) / size.n_theta
    psi = np.linspace(-PSI_RANGE, PSI_RANGE, size.n_psi)
    pp, tt = np.meshgrid(psi, theta, indexing="ij")
    pp, tt = pp.ravel(), tt.ravel()
    return 10 * RADIUS * np.stack([np.cos(tt) * np.cos(pp), np.sin(tt) * np.cos(pp), np.sin(pp)], axis=-1)


def compact_inputs(size: Size, variant: str):
    """(disk table, trim row, thickness model, observers, grid) of the same rotor for the compact solver."""
    import pandas as pd

    from nps.noise.acoustics import Observers, TimeGrid
    from nps.noise.sources import ThicknessModel

    r, dr = stations(size)
    psi = 2 * np.pi * np.arange(size.n_steps) / size.n_steps
    pp, rr = np.meshgrid(psi, r, indexing="ij")
    fz, fx = loads(rr)
    disk = pd.DataFrame({"psi_rad": pp.ravel(), "r_m": rr.ravel(), "dr_m": np.broadcast_to(dr, rr.shape).ravel(),
                         "chord_m": CHORD, "thickness_m": THICKNESS_RATIO * CHORD, "theta_rad": PITCH, "beta_rad": 0.0,
                         "fz_N_per_m": fz.ravel(), "fx_N_per_m": fx.ravel()})
    row = {"rotation_sign": 1, "n_blades": N_BLADES, "omega_rad_s": OMEGA, "hub_x_m": 0.0, "hub_y_m": 0.0,
           "hub_z_m": 0.0, "vel_x_mps": SPEED if variant == "forward" else 0.0, "vel_y_mps": 0.0, "vel_z_mps": 0.0,
           "speed_of_sound_mps": C0, "density_kg_m3": RHO0}
    row.update({f"r_gh_{i}{j}": float(i == j) for i in range(3) for j in range(3)})
    thickness = ThicknessModel(area_factor=section_area_factor(size.n_wrap))
    position = sphere(size)
    return disk, row, thickness, Observers(position, np.zeros_like(position)), TimeGrid(0.0, 2 * np.pi / OMEGA,
                                                                                          size.n_samples)


# --------------------------------------------------------------------------- measuring (worker process)
class KernelCalls:
    """Wraps ``module.radiate_arrays``: counts kernel evaluations (points × source steps × observers), points,
    source steps and the time spent in it."""

    def __init__(self, module):
        self.original = module.radiate_arrays
        module.radiate_arrays = self
        self.reset()

    def reset(self):
        self.seconds, self.evaluations, self.points, self.steps, self.calls = 0.0, 0, 0, 0, 0

    def __call__(self, sources, observers, grid, **kwargs):
        start = time.perf_counter()
        out = self.original(sources, observers, grid, **kwargs)
        self.seconds += time.perf_counter() - start
        n_point, n_tau = sources.position_m.shape[:2]
        self.evaluations += n_point * n_tau * len(observers.position_m)
        self.points += n_point
        self.steps = max(self.steps, n_tau)
        self.calls += 1
        return out


def kernels_compiled() -> int:
    """numba kernels of the loaded nps modules compiled so far in this process (cache misses): a first run that
    compiled was not on a warm cache (the cache is keyed by a hash of every nps source: any edit makes it cold)."""
    from numba.core.registry import CPUDispatcher

    dispatchers = {id(v): v for name, module in list(sys.modules.items()) if name.startswith("nps.")
                   for v in vars(module).values() if isinstance(v, CPUDispatcher)}
    return sum(sum(d.stats.cache_misses.values()) for d in dispatchers.values())


def status_mb(field: str) -> float:
    """A memory field of /proc/self/status (VmRSS, VmHWM), MB."""
    with open("/proc/self/status") as f:
        line = next(line for line in f if line.startswith(field + ":"))
    return int(line.split()[1]) / 1024


def reset_peak_rss() -> None:
    """Reset VmHWM to the current RSS (Linux: '5' to /proc/self/clear_refs)."""
    with open("/proc/self/clear_refs", "w") as f:
        f.write("5")


def wopwop_runner(case_path: Path):
    """(run function → (n_obs, 2, nt) thickness, loading; KernelCalls; path taken)."""
    import nps.wopwop.run as run
    from nps.wopwop.case import read_case

    calls = KernelCalls(run)
    modes = set()

    def go():
        result = run.run_case(read_case(case_path))[0]
        modes.update(result.modes.values())
        return result.pressure_pa["rotor"]

    return go, calls, modes


def compact_runner(size: Size, variant: str):
    """(run function → (n_obs, 2, nt) thickness, loading; KernelCalls; path taken) of the compact solver."""
    import nps.noise.sources as sources

    disk, row, thickness, observers, grid = compact_inputs(size, variant)
    calls = KernelCalls(sources)

    def go():
        p = sources.radiate_rotor(disk, row, observers, grid, thickness=thickness)
        return p[:, [p_index("thickness"), p_index("loading")]]

    modes = {"periodic" if variant == "hover" else "direct"}
    return go, calls, modes


def p_index(group: str) -> int:
    """Index of a group in radiate_rotor's output (loading, thickness)."""
    return ("loading", "thickness").index(group)


def worker(args) -> None:
    """Run one solver on one variant twice (first, then timed), print a JSON line, save the pressure (.npy)."""
    import numba

    size = QUICK if args.quick else Size()
    out_dir = Path(args.dir)
    if args.worker == "wopwop":
        go, calls, modes = wopwop_runner(out_dir / args.variant / "cases.nam")
    else:
        go, calls, modes = compact_runner(size, args.variant)
    start = time.perf_counter()
    go()
    first = time.perf_counter() - start
    compiled = kernels_compiled()
    calls.reset()
    reset_peak_rss()
    rss_start = status_mb("VmRSS")
    start = time.perf_counter()
    p = go()
    elapsed = time.perf_counter() - start
    report = dict(first_s=first, compiled=compiled, time_s=elapsed, kernel_s=calls.seconds,
                  evaluations=calls.evaluations, points=calls.points, steps=calls.steps, calls=calls.calls,
                  observers=p.shape[0], samples=p.shape[2],
                  peak_rss_mb=status_mb("VmHWM"), rss_start_mb=rss_start,
                  max_rss_mb=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
                  threads=numba.get_num_threads(), modes=sorted(modes))
    if args.trace:
        report["traced_peak_mb"] = traced_peak(go)
    np.save(out_dir / f"{args.worker}_{args.variant}.npy", p)
    print(json.dumps(report))


def traced_peak(go) -> float:
    """Peak of Python and numpy allocations (MB, tracemalloc) during one more run."""
    import tracemalloc

    tracemalloc.start()
    go()
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak / 2**20


# --------------------------------------------------------------------------- the driver
def spawn(kind: str, variant: str, directory: Path, args) -> dict:
    """Run a worker process with NUMBA_NUM_THREADS set; its JSON report."""
    command = [sys.executable, __file__, "--worker", kind, "--variant", variant, "--dir", str(directory)]
    command += ["--quick"] * args.quick + ["--trace"] * args.trace
    env = dict(os.environ, NUMBA_NUM_THREADS=str(args.threads))
    done = subprocess.run(command, env=env, capture_output=True, text=True, cwd=Path(__file__).resolve().parent.parent)
    if done.returncode:
        raise SystemExit(f"{kind} {variant} failed:\n{done.stderr[-4000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def path_label(modes: list[str]) -> str:
    """The paths run_case took ("periodic", "direct"), "+copies" when blades were radiated as copies of one."""
    paths = "/".join(sorted({m.split(" ")[0] for m in modes}))
    return paths + ("+copies" if any("copy" in m for m in modes) else "")


def print_run(label: str, r: dict) -> None:
    """One table row of a worker's report."""
    rate = r["evaluations"] / r["time_s"] / 1e6
    traced = f", traced peak {r['traced_peak_mb']:.0f} MB" if "traced_peak_mb" in r else ""
    first = f"{r['first_s']:>6.2f}{'*' if r['compiled'] else ' '}"
    print(f"  {label:<22} {path_label(r['modes']):<15} {r['points']:>7,} {r['steps']:>6} {r['observers']:>6,} "
          f"{r['samples']:>6} {r['evaluations'] / 1e9:>8.3f} G {first:>8} {r['time_s']:>8.2f} {r['kernel_s']:>8.2f} "
          f"{rate:>8.1f} {r['peak_rss_mb']:>7.0f} ({r['rss_start_mb']:>4.0f}) {r['max_rss_mb']:>7.0f}{traced}")


def print_ratio(variant: str, w: dict, c: dict) -> None:
    """wopwop run / compact: time, evaluations, evaluation rate, peak RSS and its rise above the run's start (the
    compact's rise taken as at least 1 MB)."""
    rate = (w["evaluations"] / w["time_s"]) / (c["evaluations"] / c["time_s"])
    rise = (w["peak_rss_mb"] - w["rss_start_mb"]) / max(c["peak_rss_mb"] - c["rss_start_mb"], 1.0)
    print(f"  ratio wopwop/compact, {variant}: time {w['time_s'] / c['time_s']:.1f}x, evaluations "
          f"{w['evaluations'] / c['evaluations']:.1f}x, M eval/s {rate:.2f}x, peak RSS "
          f"{w['peak_rss_mb'] / c['peak_rss_mb']:.1f}x ({rise:.1f}x above start)")


def differences(directory: Path, variant: str) -> dict[str, tuple[float, float]]:
    """Per group: (relative rms difference over all observers and samples, largest |Δp| / largest |p|), wopwop run
    against the compact solver."""
    w = np.load(directory / f"wopwop_{variant}.npy")
    c = np.load(directory / f"compact_{variant}.npy")
    out = {}
    for k, group in enumerate(("thickness", "loading")):
        delta = w[:, k] - c[:, k]
        out[group] = (float(np.sqrt((delta**2).sum() / (c[:, k] ** 2).sum())),
                      float(np.abs(delta).max() / np.abs(c[:, k]).max()))
    return out


def load_average() -> str:
    return " ".join(f"{v:.1f}" for v in os.getloadavg())


def main(args) -> None:
    size = QUICK if args.quick else Size()
    panels = (size.n_wrap - 1) * (size.n_span - 1)
    print(f"bench_wopwop ({'quick' if args.quick else 'full'}): NUMBA_NUM_THREADS={args.threads}; {N_BLADES} blades "
          f"x ({size.n_wrap - 1} x {size.n_span - 1} = {panels:,} panels, one wrap of {size.n_wrap} x {size.n_span} "
          f"nodes, "
          f"+ {size.n_span - 1}-node lifting line); {size.n_theta * size.n_psi:,} observers ({size.n_theta} x "
          f"{size.n_psi} sphere, {10 * RADIUS:.1f} m); {size.n_samples} samples/rev; {size.n_steps} source steps/rev; "
          f"section area {section_area_factor(size.n_wrap):.5f} t c; load average {load_average()}")
    total = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="bench_wopwop_") as tmp:
        directory = Path(tmp)
        start = time.perf_counter()
        for variant in VARIANTS:
            write_case(size, variant, directory / variant)
        print(f"case writing (excluded): {time.perf_counter() - start:.2f} s for both variants")
        print(f"  {'run':<22} {'path':<15} {'points':>7} {'steps':>6} {'obs':>6} {'nt':>6} {'evals':>10} "
              f"{'first s':>8} {'time s':>8} {'kernel s':>8} {'M eval/s':>8} {'peak MB':>7} (start) {'max RSS':>7}")
        failures = []
        for variant in VARIANTS:
            runs = {kind: spawn(kind, variant, directory, args) for kind in ("wopwop", "compact")}
            for kind, label in (("wopwop", "wopwop run"), ("compact", "NPS compact")):
                print_run(f"{label}, {variant}", runs[kind])
            print_ratio(variant, runs["wopwop"], runs["compact"])
            diff = differences(directory, variant)
            print("  wopwop vs compact, " + variant + ": " + "; ".join(
                f"{g} rms {a:.2e}, max |dp|/max|p| {b:.2e}" for g, (a, b) in diff.items()))
            if not diff["loading"][0] < LOADING_TOLERANCE:
                failures.append(f"{variant}: loading differs by {diff['loading'][0]:.2e} (rms) > {LOADING_TOLERANCE}")
    print(f"total wall time {time.perf_counter() - total:.1f} s; load average {load_average()}")
    if failures:
        raise SystemExit("the same lifting line disagrees: " + "; ".join(failures))


def parse(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a small case")
    parser.add_argument("--threads", type=int, default=2, help="NUMBA_NUM_THREADS of the runs (default 2)")
    parser.add_argument("--trace", action="store_true", help="a third run with tracemalloc")
    parser.add_argument("--worker", choices=("wopwop", "compact"), help=argparse.SUPPRESS)
    parser.add_argument("--variant", choices=VARIANTS, help=argparse.SUPPRESS)
    parser.add_argument("--dir", help=argparse.SUPPRESS)
    return parser.parse_args(argv)


if __name__ == "__main__":
    arguments = parse()
    if arguments.worker:
        worker(arguments)
    else:
        main(arguments)
