"""Run a PSU-WOPWOP case with NPS's compact F1A kernel: ``nps wopwop run CASE``.

The case's container tree gives every patch file pair its change-of-base chain (the ancestors' CBs, then its own;
:mod:`nps.wopwop.motion`), the patches become point sources (:mod:`nps.wopwop.sources`), and
:func:`nps.noise.acoustics.radiate_arrays` radiates them to every observer container, with observer time absolute
(t = τ + r/c) on PSU-WOPWOP's grid t_i = tMin + i (tMax − tMin)/(nt − 1).

Two paths, as NPS's own rotors use them (docs/reference/acoustics.md):

* **periodic**: a container whose chain repeats with one period T up to a uniform translation (rotations with
  one |Omega|, time-independent or periodic CBs, translations at constant velocity V), whose data are constant or
  periodic with period T, heard by observers that all move with V: one period of sources, the signal's Fourier
  series evaluated on the observer grid (exact periodicity);
* **direct**: anything else (stationary observers of a moving rotor, aperiodic data, accelerating frames): the
  sources over the source-time span the observer window needs, on the container's key grid.

Sources are grouped by **rotor**: the outermost container whose chain holds a rotation (a CB with a nonzero Omega)
collects every patch below it; patches outside any rotor form groups named after their top-level container.
Thickness and loading are kept apart as PSU-WOPWOP does; a functional-data zone written with ``loadingOutput`` = 1
(format 1.1) adds its loading noise to the thickness output.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from nps.noise.acoustics import LOADING, THICKNESS, AcousticsError, CompactSources, Observers, TimeGrid, radiate_arrays
from nps.wopwop import binary
from nps.wopwop.case import CB, Case, Container
from nps.wopwop.errors import WopwopError
from nps.wopwop.motion import FrameMotion, chain_motion
from nps.wopwop.observers import ObserverGrid, observer_grids
from nps.wopwop.sources import KeyRows, PointSources, is_compact, zone_sources

GROUPS = (THICKNESS, LOADING)
PERIOD_RTOL = 1e-6       # data period against the motion's period (the file holds it in single precision)
MAX_ROWS_PER_CALL = 4_000_000  # source rows (point x step) radiated per kernel call (~0.7 GB packed)
MARGIN_STEPS = 8         # extra source steps on each side of the span a direct window needs


@dataclass(frozen=True)
class PatchFiles:
    """One patch file pair of a container, read: the geometry, the functional data (or None) and their paths."""

    geometry: binary.GeometryFile
    functional: binary.FunctionalFile | None
    geometry_path: str
    functional_path: str | None


@dataclass(frozen=True)
class SourceContainer:
    """A container that holds patch files, with everything its radiation needs.

    ``chain``: its full CB list (ancestors first, PSU-WOPWOP's order); ``rotor``: the name of the source group
    it belongs to; ``d_tau_s``: its source-time step (the effective ContainerIn dTau, or None);
    ``key_offset``: its periodicKeyOffset (key units).
    """

    title: str
    chain: tuple[CB, ...]
    rotor: str
    patches: tuple[PatchFiles, ...]
    d_tau_s: float | None
    key_offset: float


@dataclass(frozen=True)
class ObserverResult:
    """The pressure of one observer container: per source group (rotor) (n_obs, 2, nt), groups (thickness,
    loading), on ``observers.grid``; ``modes``: the path each source container took (periodic / direct)."""

    observers: ObserverGrid
    pressure_pa: dict[str, np.ndarray]
    modes: dict[str, str] = field(default_factory=dict)

    @property
    def total_pa(self) -> np.ndarray:
        """(n_obs, 2, nt): thickness and loading summed over the source groups."""
        return sum(self.pressure_pa.values())


# --------------------------------------------------------------------------- the container tree
def source_containers(case: Case) -> tuple[SourceContainer, ...]:
    """Every container with patch files, depth-first in file order, its patch files read and paired
    (:func:`read_patch_pair`); rotors named after their container's Title (made unique)."""
    out: list[SourceContainer] = []
    names: dict[str, int] = {}
    state = {"d_tau_s": None}

    def walk(container: Container, chain: tuple[CB, ...], rotor: str | None):
        chain = chain + tuple(container.cbs)
        state["d_tau_s"] = _effective_dtau(container, state["d_tau_s"])
        if rotor is None and any(spins(cb) for cb in container.cbs):
            rotor = _unique(container.title or "rotor", names)
        if container.geometry_files:
            pairs = tuple(read_patch_pair(case, g, l) for g, l in zip(container.geometry_files, _loading_files(container)))
            out.append(SourceContainer(container.title, chain, rotor or top, pairs, state["d_tau_s"],
                                       float(container.periodic_key_offset or 0.0)))
        for child in container.children:
            walk(child, chain, rotor)

    for container in case.containers:
        top = _unique(container.title or "sources", names) if not any(spins(cb) for cb in container.cbs) else None
        walk(container, (), None)
    if not out:
        raise WopwopError(f"{case.path}: no container holds a patchGeometryFile: nothing radiates")
    return tuple(out)


def _loading_files(container: Container) -> list[str | None]:
    files = list(container.loading_files) + [None] * (len(container.geometry_files) - len(container.loading_files))
    return [f or None for f in files]


def _effective_dtau(container: Container, carried: float | None) -> float | None:
    """PSU-WOPWOP's source-time step: dTau, or (tauMax − tauMin)/nTau when dTau is 0 and nTau > 0; the values of a
    container carry over to the containers read after it (they are passed by reference)."""
    if container.d_tau_s:
        return float(container.d_tau_s)
    if container.n_tau and container.tau_max_s is not None and container.tau_min_s is not None:
        return (float(container.tau_max_s) - float(container.tau_min_s)) / int(container.n_tau)
    return carried


def spins(cb: CB) -> bool:
    """A CB that turns with time (a rotor's rotation): KnownFunction or Periodic angle with nonzero Omega."""
    return cb.angle_type in ("KnownFunction", "Periodic") and bool(cb.omega_rad_s)


def _unique(name: str, names: dict[str, int]) -> str:
    names[name] = names.get(name, 0) + 1
    return name if names[name] == 1 else f"{name}_{names[name]}"


def read_patch_pair(case: Case, geometry_name: str, loading_name: str | None) -> PatchFiles:
    """Read a container's geometry file and its functional data file (resolved as PSU-WOPWOP does) and check that
    they belong together (:func:`nps.wopwop.binary.check_pair`)."""
    geometry_path = str(case.file(geometry_name))
    geometry = binary.read_geometry(geometry_path)
    if loading_name is None:
        return PatchFiles(geometry, None, geometry_path, None)
    functional_path = str(case.file(loading_name))
    functional = binary.read_functional(functional_path)
    binary.check_pair(geometry, functional, geometry_path, functional_path)
    return PatchFiles(geometry, functional, geometry_path, functional_path)


# --------------------------------------------------------------------------- timing
@dataclass(frozen=True)
class Timing:
    """The time layout of a patch pair: ``kind`` ("constant", "periodic", "aperiodic"), ``period_s`` (periodic),
    the uniform key spacing ``dtau_s`` (None for constant data), the first key time ``t0_s`` (aperiodic) and the
    number of distinct keys ``n_rows`` (periodic: the keys less the repeated end point)."""

    kind: str
    period_s: float | None
    dtau_s: float | None
    t0_s: float
    n_rows: int


def zone_timing(zone, path: str) -> Timing:
    """Timing of one geometry or functional zone (PSU-WOPWOP: periodic key k at (key_k − key_1)/(key_N − key_1)·T,
    the last key one period after the first; aperiodic keys are times, used at a uniform spacing)."""
    keys = np.asarray(zone.keys, dtype=float)
    if keys.size == 0:
        return Timing("constant", None, None, 0.0, 1)
    if keys.size < 2 or np.any(np.diff(keys) <= 0.0):
        raise WopwopError(f"{path}: zone '{zone.name}': keys: expected at least 2 increasing keys, got {keys.size}")
    if zone.period_s is not None:
        if not zone.period_s > 0.0:
            raise WopwopError(f"{path}: zone '{zone.name}': period: expected > 0 s, got {zone.period_s}")
        times = (keys - keys[0]) / (keys[-1] - keys[0]) * float(zone.period_s)
        kind, n_rows = "periodic", keys.size - 1
    else:
        times, kind, n_rows = keys, "aperiodic", keys.size
    step = np.diff(times)
    if not np.allclose(step, step[0], rtol=1e-4, atol=0.0):
        raise WopwopError(f"{path}: zone '{zone.name}': keys: expected uniformly spaced keys (NPS uses them as its "
                          f"source-time grid, as PSU-WOPWOP does), spacing {step.min():.6g} to {step.max():.6g} s")
    return Timing(kind, float(zone.period_s) if zone.period_s is not None else None, float(step.mean()), float(times[0]), n_rows)


def pair_timing(pair: PatchFiles) -> Timing:
    """The one timing of a patch pair: the time-varying file's (geometry first); PSU-WOPWOP refuses a loading
    key spacing other than the geometry's."""
    timings = [(zone_timing(z, pair.geometry_path), pair.geometry_path) for z in pair.geometry.zones]
    if pair.functional is not None:
        timings += [(zone_timing(z, pair.functional_path), pair.functional_path) for z in pair.functional.zones]
    varying = [(t, p) for t, p in timings if t.kind != "constant"]
    if not varying:
        return timings[0][0]
    first, first_path = varying[0]
    for t, path in varying[1:]:
        same = (t.kind == first.kind and t.n_rows == first.n_rows
                and abs(t.dtau_s - first.dtau_s) <= 1e-6 * first.dtau_s and abs(t.t0_s - first.t0_s) <= 1e-6 * first.dtau_s)
        if not same:
            raise WopwopError(f"{path}: keys: {t.kind} data with {t.n_rows} keys every {t.dtau_s:.6g} s, expected the "
                              f"{first.kind} keys of {first_path} ({first.n_rows} every {first.dtau_s:.6g} s): the "
                              "geometry and its data must share one source-time grid")
    return first


def key_shift(container: SourceContainer, timing: Timing, keys: np.ndarray) -> int:
    """PSU-WOPWOP's periodicKeyOffset as a whole number of rows: (offset − keyMin)/(keyMax − keyMin) of the
    period, rounded to the nearest key (0 when the offset is 0)."""
    if not container.key_offset or timing.kind != "periodic":
        return 0
    keys = np.asarray(keys, dtype=float)
    fraction = (container.key_offset - keys[0]) / (keys[-1] - keys[0])
    return int(np.floor(fraction * timing.n_rows + 0.5))


# --------------------------------------------------------------------------- periodicity
def chain_period(chain: tuple[CB, ...]) -> float | None:
    """The period (s) of a chain's turning CBs, 2π/|Omega| (None: nothing turns); refuses turning CBs of
    different speeds that are not whole multiples of the slowest (no common period NPS can use)."""
    omegas = sorted({abs(float(cb.omega_rad_s)) for cb in chain if spins(cb)})
    if not omegas:
        return None
    ratios = np.asarray(omegas) / omegas[0]
    if np.any(np.abs(ratios - np.round(ratios)) > 1e-9 * ratios):
        return None
    return 2.0 * np.pi / omegas[0]


def uniform_velocity(motion: FrameMotion, period_s: float, chain, probe_s: np.ndarray) -> np.ndarray | None:
    """The chain's frame velocity V (m/s, G) when it repeats with ``period_s`` up to the translation V·T (its
    rotation equal after a period, its origin at constant velocity), else None. ``motion``: the chain at
    ``probe_s`` and ``probe_s`` + T stacked (2 n)."""
    n = probe_s.size
    rot, trans = motion.rotation, motion.translation
    scale = max(1.0, float(np.abs(trans[0]).max()))
    same_turn = np.allclose(rot[0, :n], rot[0, n:], rtol=0.0, atol=1e-9)
    velocity = trans[1, 0]
    steady = (np.allclose(trans[1], velocity[None, :], rtol=0.0, atol=1e-9 * max(1.0, float(np.abs(velocity).max())))
              and np.allclose(trans[2], 0.0, rtol=0.0, atol=1e-9 * scale / period_s**2))
    return velocity.copy() if same_turn and steady else None


def periodic_frame(source: SourceContainer, timing: Timing, observers: ObserverGrid, c0: float):
    """(period T, frame velocity V) when the periodic path applies to this patch pair, else None: a chain that
    repeats with T up to a uniform translation V, data constant or periodic with T, every observer moving with V."""
    period = chain_period(source.chain)
    if timing.kind == "aperiodic":
        return None
    if timing.kind == "periodic":
        if period is None:
            period = timing.period_s
        else:  # data over a whole number m of the motion's periods (a common period of several rotors)
            turns = timing.period_s / period
            if abs(turns - round(turns)) > PERIOD_RTOL * turns or round(turns) < 1:
                return None
            period *= round(turns)
    if period is None:
        return None
    probe = np.linspace(0.0, period, 5)
    motion = chain_motion(source.chain, np.concatenate([probe, probe + period]))
    velocity = uniform_velocity(motion, period, source.chain, probe)
    if velocity is None or not np.allclose(observers.velocity_mps, velocity[None, :], rtol=0.0, atol=1e-9 * c0):
        return None
    return period, velocity


# --------------------------------------------------------------------------- source steps
def source_span(source: SourceContainer, reach_m: float, observers: ObserverGrid, c0: float, step_s: float) -> tuple[float, float]:
    """Source-time span (s) the observer window needs from this container: the emission times of its frame
    origin for the first and last observer times (bisection on c(t − τ) = |x(t) − y_o(τ)|), widened by
    2·reach/(c0 − v) and a few steps (reach: the farthest point from the origin, v: the origin's top speed)."""
    t_first = observers.grid.t_start_s
    t_last = observers.grid.t_start_s + (observers.grid.n_samples - 1) * observers.grid.dt_s
    t = np.concatenate([np.full(len(observers.position_m), t_first), np.full(len(observers.position_m), t_last)])
    x = np.concatenate([observers.position_m + t_first * observers.velocity_mps,
                        observers.position_m + t_last * observers.velocity_mps])

    def gap(tau):
        origin = chain_motion(source.chain, tau).translation[0]
        return c0 * (t - tau) - np.linalg.norm(x - origin, axis=1)

    hi = t.copy()
    lo = t - 2.0 * np.linalg.norm(x - chain_motion(source.chain, t).translation[0], axis=1) / c0 - step_s
    for _ in range(60):
        short = gap(lo) <= 0.0
        if not short.any():
            break
        lo = np.where(short, lo - 2.0 * (hi - lo), lo)
    else:
        raise WopwopError(f"container '{source.title}': its frame origin does not stay subsonic (no emission time "
                          "for the observer window)")
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        inside = gap(mid) > 0.0
        lo, hi = np.where(inside, mid, lo), np.where(inside, hi, mid)
    probe = np.linspace(lo.min(), hi.max(), 64)
    speed = float(np.linalg.norm(chain_motion(source.chain, probe).translation[1], axis=1).max())
    if not speed < c0:
        raise WopwopError(f"container '{source.title}': its frame origin moves at {speed:.1f} m/s, not below c = {c0} m/s")
    margin = 2.0 * reach_m / (c0 - speed) + MARGIN_STEPS * step_s
    return float(lo.min() - margin), float(hi.max() + margin)


def key_rows(timing: Timing, steps: np.ndarray, shift: int, varying: bool) -> KeyRows:
    """The rows of a file's zones at the source steps j (τ_j = t0 + j·dτ): periodic rows wrap, aperiodic rows are
    the steps themselves, constant files use row 0."""
    if not varying:
        return KeyRows(np.zeros(steps.size, dtype=np.int64), timing.dtau_s or 1.0, False, 1)
    if timing.kind == "periodic":
        return KeyRows((steps + shift) % timing.n_rows, timing.dtau_s, True, timing.n_rows)
    return KeyRows(steps.astype(np.int64), timing.dtau_s, False, timing.n_rows)


def _varying(file_zones) -> bool:
    return any(np.asarray(z.keys).size for z in file_zones)


def _reach(pair: PatchFiles) -> float:
    """Farthest patch node from the container's frame origin over all keys (m)."""
    return float(max(np.linalg.norm(np.asarray(z.xyz, dtype=float), axis=-1).max() for z in pair.geometry.zones))


# --------------------------------------------------------------------------- radiation
def _steps(source: SourceContainer, pair: PatchFiles, timing: Timing, observers: ObserverGrid, c0: float):
    """(source steps j, source times τ_j, step dτ, (period, frame velocity) or None) of one patch pair."""
    step = timing.dtau_s if timing.kind != "constant" else source.d_tau_s
    frame = periodic_frame(source, timing, observers, c0)
    if step is None or not step > 0.0:
        raise WopwopError(f"container '{source.title}': constant data need a source-time step: set dTau (or tauMin, "
                          "tauMax and nTau) in this container or one read before it, as PSU-WOPWOP requires")
    if frame is not None:
        period = frame[0]
        n = timing.n_rows if timing.kind == "periodic" else max(8, int(round(period / step)))
        steps = np.arange(n)
        return steps, steps * (period / n), period / n, frame
    t0 = timing.t0_s if timing.kind == "aperiodic" else 0.0
    first, last = source_span(source, max(_reach(pair), 0.0), observers, c0, step)
    j_lo, j_hi = int(np.floor((first - t0) / step)), int(np.ceil((last - t0) / step))
    if timing.kind == "aperiodic":
        j_lo, j_hi = max(j_lo, 0), min(j_hi, timing.n_rows - 1)
        if j_hi - j_lo < 3:
            raise WopwopError(f"{pair.geometry_path}: its aperiodic data cover source times [{t0:.6g}, "
                              f"{t0 + (timing.n_rows - 1) * step:.6g}] s, the observer window needs [{first:.6g}, "
                              f"{last:.6g}] s")
    steps = np.arange(j_lo, j_hi + 1)
    return steps, t0 + steps * step, step, None


def pair_points(source: SourceContainer, pair: PatchFiles, steps, tau, timing: Timing, rho0: float):
    """[(PointSources, output group of its loading)] of every zone of a patch pair at the source steps."""
    motion = chain_motion(source.chain, tau)
    varying_zone = next((z for z in (*pair.geometry.zones, *(pair.functional.zones if pair.functional else ()))
                         if np.asarray(z.keys).size), None)
    shift = key_shift(source, timing, varying_zone.keys) if varying_zone is not None else 0
    geometry_rows = key_rows(timing, steps, shift, _varying(pair.geometry.zones))
    data_rows = key_rows(timing, steps, shift, _varying(pair.functional.zones)) if pair.functional else None
    data_of = {z.zone: z for z in pair.functional.zones} if pair.functional else {}
    out = []
    for number, zone in enumerate(pair.geometry.zones, start=1):
        if zone.iblank is not None and np.any(np.asarray(zone.iblank) != 1):
            raise WopwopError(f"{pair.geometry_path}: zone '{zone.name}': iblank: blanked nodes (iblank != 1) are not "
                              "supported by NPS; remove them from the zone")
        data = data_of.get(number)
        if data is None and is_compact(zone):
            continue  # a lifting line without loading radiates nothing (compact zones have no thickness noise)
        try:
            points = zone_sources(zone, data, pair.functional, geometry_rows, data_rows, motion, rho0)
        except WopwopError as error:
            files = pair.geometry_path if data is None else f"{pair.geometry_path}, {pair.functional_path}"
            raise WopwopError(f"{files}: {error}") from None
        group = THICKNESS if data is not None and getattr(data, "loading_output", 2) == 1 else LOADING
        out.append((points, group))
    return out


def _compact_sources(parts, tau, frame, copies: int = 1) -> CompactSources:
    """The kernel's sources of a list of (PointSources, group): points along the node axis; ``copies`` identical
    blades shifted by a period / copies on the periodic path."""
    kin = np.concatenate([p.kinematics for p, _ in parts], axis=2).transpose(2, 1, 0, 3)  # (n_point, n_tau, 4, 3)
    force = np.concatenate([p.force_N for p, _ in parts], axis=1).transpose(1, 0, 2)
    force_rate = np.concatenate([p.force_rate_N_s for p, _ in parts], axis=1).transpose(1, 0, 2)
    zero = [np.zeros(p.force_N.shape[:2]) for p, _ in parts]
    flux = np.concatenate([z if p.mass_flux_kg_s is None else p.mass_flux_kg_s for (p, _), z in zip(parts, zero)], axis=1).T
    flux_rate = np.concatenate([z if p.mass_flux_rate_kg_s2 is None else p.mass_flux_rate_kg_s2
                                for (p, _), z in zip(parts, zero)], axis=1).T
    dipole = np.concatenate([np.full(p.force_N.shape[1], GROUPS.index(g)) for p, g in parts])
    dipole[np.all(force == 0.0, axis=(1, 2)) & np.all(force_rate == 0.0, axis=(1, 2))] = -1
    monopole = np.where(np.any(flux != 0.0, axis=1) | np.any(flux_rate != 0.0, axis=1), GROUPS.index(THICKNESS), -1)
    period, velocity = frame if frame is not None else (None, None)
    return CompactSources(np.asarray(tau, dtype=float), *(np.ascontiguousarray(kin[:, :, k]) for k in range(4)),
                          np.ascontiguousarray(force), np.ascontiguousarray(force_rate), np.zeros(kin.shape[0]), GROUPS,
                          dipole.astype(np.int64), monopole.astype(np.int64), period_s=period, frame_velocity_mps=velocity,
                          copies=copies, mass_flux_kg_s=np.ascontiguousarray(flux), mass_flux_rate_kg_s2=np.ascontiguousarray(flux_rate))


def _point_slice(sources: CompactSources, lo: int, hi: int) -> CompactSources:
    """The points lo…hi−1 of ``sources`` (a chunk radiated in one kernel call)."""
    take = slice(lo, hi)
    return CompactSources(sources.time_s, sources.position_m[take], sources.velocity_mps[take],
                          sources.acceleration_mps2[take], sources.jerk_mps3[take], sources.force_N[take],
                          sources.force_rate_N_s[take], sources.volume_m3[take], sources.groups, sources.dipole_group[take],
                          sources.monopole_group[take], sources.period_s, sources.frame_velocity_mps, sources.copies,
                          sources.mass_flux_kg_s[take], sources.mass_flux_rate_kg_s2[take])


def radiate_pair(source: SourceContainer, pair: PatchFiles, observers: ObserverGrid, rho0: float, c0: float,
                 copies: int = 1):
    """Pressure (Pa, (n_obs, 2, nt): thickness, loading) of one patch pair at one observer container, and the path
    taken ("periodic" or "direct"). ``copies``: on the periodic path, the number of identical blades this container
    stands for (:func:`blade_copies`; 0: a copy, radiated with its reference). Points are radiated in chunks of at
    most MAX_ROWS_PER_CALL source rows."""
    timing = pair_timing(pair)
    steps, tau, _, frame = _steps(source, pair, timing, observers, c0)
    mode = "periodic" if frame is not None else "direct"
    out = np.zeros((len(observers.position_m), len(GROUPS), observers.grid.n_samples))
    if frame is not None and copies == 0:
        return out, "periodic (copy)"
    parts = pair_points(source, pair, steps, tau, timing, rho0)
    if not parts:
        return out, mode
    sources = _compact_sources(parts, tau, frame, max(copies, 1) if frame is not None else 1)
    obs = Observers(observers.position_m, observers.velocity_mps)
    n_point = sources.position_m.shape[0]
    per_call = max(1, MAX_ROWS_PER_CALL // tau.size)
    for lo in range(0, n_point, per_call):
        try:
            out += radiate_arrays(_point_slice(sources, lo, min(lo + per_call, n_point)), obs, observers.grid,
                                  c0_mps=c0, rho0_kg_m3=rho0)
        except AcousticsError as error:
            raise WopwopError(f"{pair.geometry_path} (container '{source.title}') / observers '{observers.title}': "
                              f"{error}") from None
    return out, mode


def run_case(case: Case, sources: tuple[SourceContainer, ...] | None = None) -> tuple[ObserverResult, ...]:
    """Every observer container of ``case``: its pressures per source group (rotor), thickness and loading apart.
    ``sources``: the case's :func:`source_containers` when already read."""
    rho0, c0 = float(case.environment.rho_kg_m3), float(case.environment.c_m_s)
    sources = source_containers(case) if sources is None else sources
    results = []
    for grid in observer_grids(case):
        pressure: dict[str, np.ndarray] = {}
        modes: dict[str, str] = {}
        for source, copies in zip(sources, blade_copies(sources)):
            for pair in source.patches:
                p, mode = radiate_pair(source, pair, grid, rho0, c0, copies)
                pressure[source.rotor] = pressure.get(source.rotor, 0.0) + p
                modes[f"{source.title}: {pair.geometry_path}"] = mode
        results.append(ObserverResult(grid, pressure, modes))
    return tuple(results)


# --------------------------------------------------------------------------- identical blades
def blade_copies(sources: tuple[SourceContainer, ...]) -> list[int]:
    """Per source container: B for the first blade of a rotor whose B blade containers are copies of it shifted by
    T/B (the periodic path radiates it once, summing the harmonics n·B times B, as NPS does for its own rotors),
    0 for the other blades of such a rotor, 1 otherwise. Copies: the same patch files, the same chain but one
    TimeIndependent rotation about the turning CB's axis (only such rotations between the two), blade b's angle
    offset δ_b a whole number of T/B in time (δ_b/Omega), and periodic data over one turn whose
    periodicKeyOffset rows follow the same time shift (constant data need nothing)."""
    out = [1] * len(sources)
    for rotor in dict.fromkeys(s.rotor for s in sources):
        members = [k for k, s in enumerate(sources) if s.rotor == rotor]
        if len(members) > 1 and _copies_of(sources[members[0]], [sources[k] for k in members]):
            out[members[0]] = len(members)
            for k in members[1:]:
                out[k] = 0
    return out


def _copies_of(ref: SourceContainer, group: list[SourceContainer]) -> bool:
    """Whether ``group`` (``ref`` first) are identical blades evenly spaced in time (:func:`blade_copies`)."""
    paths = [[(p.geometry_path, p.functional_path) for p in s.patches] for s in group]
    if any(p != paths[0] for p in paths) or any(len(s.chain) != len(ref.chain) for s in group):
        return False
    differ = sorted({j for s in group for j, (a, b) in enumerate(zip(s.chain, ref.chain)) if a != b})
    spin_at = next((j for j, cb in enumerate(ref.chain) if spins(cb)), None)
    if len(differ) != 1 or spin_at is None or differ[0] <= spin_at:
        return False
    spin, at = ref.chain[spin_at], differ[0]
    axis = np.asarray(spin.axis_value, dtype=float) / np.linalg.norm(spin.axis_value)
    if not all(_turn_about(cb, axis) for cb in ref.chain[spin_at + 1:at]) or not all(_turn_about(s.chain[at], axis) for s in group):
        return False
    period = 2.0 * np.pi / abs(spin.omega_rad_s)
    leads = [((s.chain[at].angle_value - ref.chain[at].angle_value) / spin.omega_rad_s) % period for s in group]
    n = len(group)
    if not np.allclose(np.sort(leads), np.arange(n) * period / n, rtol=0.0, atol=1e-9 * period):
        return False
    return all(_keys_follow(ref, s, pair, lead / period, period) for s, lead in zip(group, leads) for pair in s.patches)


def _turn_about(cb: CB, axis: np.ndarray) -> bool:
    """A TimeIndependent rotation about ``axis`` without translation."""
    if cb.angle_type != "TimeIndependent" or cb.translation_type is not None or cb.axis_value is None:
        return False
    own = np.asarray(cb.axis_value, dtype=float)
    return bool(np.allclose(own / np.linalg.norm(own), axis, rtol=0.0, atol=1e-12))


def _keys_follow(ref: SourceContainer, blade: SourceContainer, pair: PatchFiles, lead: float, period_s: float) -> bool:
    """The blade's periodic data rows lead the reference's by the fraction ``lead`` of one turn, the data being
    periodic over that turn (constant data: always)."""
    timing = pair_timing(pair)
    if timing.kind == "constant":
        return True
    if timing.kind != "periodic" or abs(timing.period_s - period_s) > PERIOD_RTOL * period_s:
        return False
    keys = next(z.keys for z in (*pair.geometry.zones, *(pair.functional.zones if pair.functional else ())) if np.asarray(z.keys).size)
    rows = lead * timing.n_rows
    if abs(rows - round(rows)) > 1e-6:
        return False
    shift = key_shift(blade, timing, keys) - key_shift(ref, timing, keys)
    return (shift - round(rows)) % timing.n_rows == 0
