"""PSU-WOPWOP observer containers as NPS observers: positions at t = 0 and uniform velocities in G, time grids.

Geometry (PSU-WOPWOP ObserverContainerObject, :mod:`nps.wopwop.case`): a point; a box (x fastest, then y, then z,
n points from min to max, a count of 1 at min — at the middle with debugLevel > 1, as WOPWOP); a sphere x = R cos θ cos ψ, y = R sin θ cos ψ, z = R sin ψ
(θ the azimuth from +x, ψ the elevation; n points from min to max, both included, a count of 1 at min; ψ outer and
θ fastest, θ outer with ``indexSwap``; grid dims (nbTheta, nbPsi)); or a file (list-directed ``nbx nby nbz``, then
all x, all y, all z). The observer's change-of-base chain (its ``nbBase`` CBs; with ``attachedTo``, the frame CBs,
the named container's whole chain, then the local CBs) must keep it at rest or in uniform translation: NPS's
closed-form reception time needs x(t) = x0 + v t. Observer times are PSU-WOPWOP's t_i = tMin + i (tMax − tMin)/(nt − 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.noise.acoustics import TimeGrid
from nps.wopwop.case import Case, ObserverSpec, observer_chain
from nps.wopwop.errors import WopwopError
from nps.wopwop.motion import chain_motion


@dataclass(frozen=True)
class ObserverGrid:
    """One observer container: ``shape`` (dim1, dim2) of its grid, ``position_m`` (n, 3) at t = 0 and
    ``velocity_mps`` (n, 3) in G, observers in PSU-WOPWOP's order, and its observer-time ``grid``."""

    title: str
    shape: tuple[int, int]
    position_m: np.ndarray
    velocity_mps: np.ndarray
    grid: TimeGrid
    spec: ObserverSpec


def _spaced(low: float, high: float, n: int, middle: bool) -> np.ndarray:
    """n values from low to high (both included); n = 1: ``low``, or the middle where ``middle`` (a box axis
    with debugLevel > 1: PSU-WOPWOP shifts it inside its warning's test, :class:`nps.wopwop.case.Box`)."""
    if n == 1:
        return np.array([0.5 * (low + high) if middle else low])
    return low + np.arange(n) * (high - low) / (n - 1)


def local_positions(case: Case, spec: ObserverSpec) -> tuple[tuple[int, int], np.ndarray]:
    """(grid dims, positions (n, 3) in the observer's own frame) of an observer container."""
    if spec.kind == "point":
        return (1, 1), np.asarray(spec.point, dtype=float).reshape(1, 3)
    if spec.kind == "box":
        b = spec.box
        middle = case.environment.debug_level > 1
        x, y, z = (_spaced(lo, hi, n, middle) for lo, hi, n in ((b.x_min_m, b.x_max_m, b.nbx), (b.y_min_m, b.y_max_m, b.nby),
                                                               (b.z_min_m, b.z_max_m, b.nbz)))
        zz, yy, xx = np.meshgrid(z, y, x, indexing="ij")
        return (b.nbx, b.nby * b.nbz), np.stack([xx.ravel(), yy.ravel(), zz.ravel()], axis=1)
    if spec.kind == "sphere":
        s = spec.sphere
        theta = _spaced(s.theta_min_rad, s.theta_max_rad, s.nb_theta, False)
        psi = _spaced(s.psi_min_rad, s.psi_max_rad, s.nb_psi, False)
        outer, inner = (theta, psi) if s.index_swap else (psi, theta)
        oo, ii = np.meshgrid(outer, inner, indexing="ij")
        th, ps = (oo, ii) if s.index_swap else (ii, oo)
        th, ps = th.ravel(), ps.ravel()
        points = s.radius_m * np.stack([np.cos(th) * np.cos(ps), np.sin(th) * np.cos(ps), np.sin(ps)], axis=1)
        return (s.nb_theta, s.nb_psi), points
    return observer_file(case, spec)


def observer_file(case: Case, spec: ObserverSpec) -> tuple[tuple[int, int], np.ndarray]:
    """An observer file: list-directed ``nbx nby nbz``, then the nbx·nby·nbz x, y and z values."""
    path = case.file(spec.file_name)
    try:
        words = path.read_text(encoding="ascii").replace(",", " ").split()
    except (OSError, UnicodeDecodeError) as error:
        raise WopwopError(f"{path}: observer file of '{spec.title}': cannot be read ({error})") from None
    try:
        counts = [int(w) for w in words[:3]]
    except ValueError:
        raise WopwopError(f"{path}: observer file: first line: expected the counts 'nbx nby nbz', got "
                          f"{' '.join(words[:3])!r}") from None
    if len(counts) < 3 or min(counts) < 1:
        raise WopwopError(f"{path}: observer file: counts: expected three counts >= 1, got {counts}")
    n = counts[0] * counts[1] * counts[2]
    if len(words) != 3 + 3 * n:
        raise WopwopError(f"{path}: observer file: expected 3 x {n} coordinates after the counts {counts}, got "
                          f"{len(words) - 3} values")
    try:
        values = np.array([float(w.replace("d", "e").replace("D", "e")) for w in words[3:]])
    except ValueError as error:
        raise WopwopError(f"{path}: observer file: coordinates: expected numbers, got {str(error).split(': ')[-1]}") from None
    if not np.isfinite(values).all():
        raise WopwopError(f"{path}: observer file: coordinates: expected finite numbers, got NaN or inf")
    return (counts[0], counts[1] * counts[2]), values.reshape(3, n).T.copy()


def observer_grid(case: Case, spec: ObserverSpec) -> ObserverGrid:
    """One observer container as positions, velocities and time grid; refuses rotating or accelerating observers."""
    shape, local = local_positions(case, spec)
    if spec.nt < 2 or not spec.t_max_s > spec.t_min_s:
        raise WopwopError(f"{case.path}: &ObserverIn '{spec.title}': nt, tMin, tMax: expected nt >= 2 and tMax > tMin "
                          f"(NPS needs the observer window), got nt {spec.nt}, [{spec.t_min_s}, {spec.t_max_s}] s")
    grid = TimeGrid(float(spec.t_min_s), (spec.t_max_s - spec.t_min_s) * spec.nt / (spec.nt - 1), int(spec.nt))
    chain = observer_chain(case, spec)
    probe = np.linspace(grid.t_start_s, grid.t_start_s + grid.duration_s, 5)
    motion = chain_motion(chain, probe)
    rotation, translation = motion.rotation, motion.translation
    scale = max(1.0, float(np.abs(translation[0]).max()))
    if not (np.allclose(rotation[0], rotation[0, :1], rtol=0.0, atol=1e-12)
            and np.allclose(translation[2], 0.0, rtol=0.0, atol=1e-12 * scale / max(grid.duration_s, 1e-9) ** 2)):
        raise WopwopError(f"{case.path}: &ObserverIn '{spec.title}': its change-of-base chain turns or accelerates the "
                          "observers: NPS radiates to observers at rest or in uniform translation")
    velocity = translation[1, 0]
    origin = translation[0, 0] - probe[0] * velocity
    position = local @ rotation[0, 0].T + origin[None, :]
    return ObserverGrid(spec.title, shape, position, np.repeat(velocity[None, :], len(position), axis=0), grid, spec)


def observer_grids(case: Case) -> tuple[ObserverGrid, ...]:
    """Every observer container of the case."""
    if not case.observers:
        raise WopwopError(f"{case.path}: no &ObserverIn: nothing to radiate to")
    return tuple(observer_grid(case, spec) for spec in case.observers)
