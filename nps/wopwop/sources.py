"""PSU-WOPWOP patches as point sources of NPS's F1A kernel (:mod:`nps.noise.acoustics`), in the ground frame.

A patch file pair (geometry zone + optional functional-data zone) becomes, at the source times τ_j of its
container, a set of points carrying a force on the fluid (loading) and, for surfaces, a mass flux Q = ρ0 v·A
(thickness, the panel form of formulation 1A's thickness integrand):

* **compact zones** (lifting lines: structured with iMax = 1 or jMax = 1, unstructured with two faces; PSU-WOPWOP
  surface.f90 ``IsSurfaceCompact``): node-centred data at the nodes, each carrying a span length: |n| of its
  normal, or, when the zone's first normal is of unit length (0.999–1.001) or zero, half the sum of its adjacent
  segment lengths (``CalculateSurfaceAreas``); face-centred data (one value per segment, n − 1 values, as
  FLOWUnsteady writes its lifting lines) at the segment midpoints with the segment lengths. Loading is per
  unit span; compact zones radiate no thickness noise (as in PSU-WOPWOP).
* **surfaces**, structured and node-centred with unit (or zero) normals: face-centred quadrilateral panels,
  centre the mean of the four nodes, area vector A = ½ d1 × d2 (d1, d2 the diagonals), oriented like the mean of
  the four nodes' file normals, data the mean of the four nodes' values (a panel is skipped unless its four
  nodes have iblank 1). Structured with non-unit normals, and unstructured node-centred zones: the nodes, area
  vector = the file normal (PSU-WOPWOP: area = |n|); unstructured face-centred: the faces, centre the mean of
  their nodes, area vector = the face's file normal.
* **data**: surface pressure p (gauge; force on the fluid p A), loading vectors L (the force on the surface per unit
  area — per unit span on compact zones —, force on the fluid −L |A|), in the ground frame (frame 1) or rotated
  by the container's whole change-of-base chain (frames 2 and 3, identical for loading; PSU-WOPWOP
  ``VectorBaseChange``). Flow-parameter data (permeable surfaces) are read but not radiated.

Time: keyed data are used at their key times, as PSU-WOPWOP does (no interpolation between keys): the source
times of a container are its key times (periodic data wrap with the period; ``periodicKeyOffset`` shifts the rows
by whole keys). Local rates of keyed data (a deforming surface, time-varying loads) are 6th-order central
differences over the keys (periodic data wrap; aperiodic data one-sided at the ends; NPS's order, PSU-WOPWOP
uses second-order differences); rigid motion and its rates come analytically from the change-of-base chain
(:mod:`nps.wopwop.motion`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.noise.acoustics import time_derivative
from nps.noise.sources import periodic_dpsi
from nps.wopwop import binary
from nps.wopwop.errors import WopwopError
from nps.wopwop.motion import FrameMotion, apply, rotate_vectors

UNIT_NORMAL_TOLERANCE = 1e-3  # PSU-WOPWOP: a first normal of length 0.999–1.001 marks unit normals
ZERO_NORMAL = 1e-15           # ... and one below 1e-15 "no area given": areas from the geometry


@dataclass(frozen=True)
class KeyRows:
    """Which key row of a keyed zone each source step uses, and the spacing of the keys.

    ``rows`` (n_tau,) int: the row of every source step (constant data: all 0); ``dtau_s``: the key spacing (s),
    the source-time step of the container; ``periodic``: rows wrap over ``n_rows`` distinct keys.
    """

    rows: np.ndarray
    dtau_s: float
    periodic: bool
    n_rows: int


@dataclass(frozen=True)
class PointSources:
    """Point sources of one zone over the source steps, ground frame G, SI.

    ``kinematics`` (4, n_tau, n_point, 3): position, velocity, acceleration, jerk; ``force_N`` and
    ``force_rate_N_s`` (n_tau, n_point, 3): force on the fluid and its rate; ``mass_flux_kg_s`` and
    ``mass_flux_rate_kg_s2`` (n_tau, n_point), or None: no thickness source.
    """

    kinematics: np.ndarray
    force_N: np.ndarray
    force_rate_N_s: np.ndarray
    mass_flux_kg_s: np.ndarray | None
    mass_flux_rate_kg_s2: np.ndarray | None


def is_compact(zone: binary.GeometryZone) -> bool:
    """A lifting line: structured with iMax = 1 or jMax = 1, or unstructured with two faces (PSU-WOPWOP)."""
    if zone.structured:
        return zone.i_max == 1 or zone.j_max == 1
    return len(zone.faces) == 2


def keyed_rates(values: np.ndarray, rows: KeyRows, order: int) -> list[np.ndarray]:
    """``values`` (n_keys, ...) at uniform keys and their first ``order`` τ-derivatives over the distinct rows:
    6th-order central differences, wrapping when periodic (the repeated last key of periodic data dropped),
    one-sided 7-point stencils at the ends otherwise (constant data, one row: zero rates)."""
    values = values[:rows.n_rows] if rows.periodic else values
    dtau_s, periodic = rows.dtau_s, rows.periodic
    out = [values]
    for _ in range(order):
        last = out[-1]
        if last.shape[0] == 1:
            out.append(np.zeros_like(last))
        elif periodic:
            out.append(periodic_dpsi(last, dtau_s))
        else:
            out.append(time_derivative(last, dtau_s, axis=0))
    return out


def _structured_panels(zone: binary.GeometryZone):
    """Node ids (n_panel, 4) of the quadrilaterals of a structured zone (i fastest), counter-clockwise in (i, j)."""
    i, j = np.meshgrid(np.arange(zone.i_max - 1), np.arange(zone.j_max - 1), indexing="xy")
    first = (i + zone.i_max * j).ravel()
    return np.stack([first, first + 1, first + 1 + zone.i_max, first + zone.i_max], axis=1)


def _face_centred_compact(zone: binary.GeometryZone, n_data: int) -> bool:
    """Face-centred data on a compact line: one value per segment (n − 1 values)."""
    return is_compact(zone) and n_data == zone.n_nodes - 1


def _panel_geometry(zone: binary.GeometryZone, xyz: np.ndarray, normals: np.ndarray, face_centred: bool):
    """(averaging matrix (n_point, n_nodes), local area vectors (n_rows, n_point, 3)) of a surface zone.

    The averaging matrix maps node values to the points (panel centres, nodes or faces); xyz and normals are the
    zone's rows (n_rows, n_nodes, 3) and (n_rows, n_normals, 3) as float64.
    """
    n_nodes = zone.n_nodes
    if zone.structured and not face_centred and _unit_or_zero(normals):
        quads = _structured_panels(zone)
        d1 = xyz[:, quads[:, 2]] - xyz[:, quads[:, 0]]
        d2 = xyz[:, quads[:, 3]] - xyz[:, quads[:, 1]]
        area = 0.5 * np.cross(d1, d2)
        orient = normals[:, quads].sum(axis=2)
        area = np.where((np.einsum("rpk,rpk->rp", area, orient) < 0.0)[..., None], -area, area)
        return _mean_matrix(quads, n_nodes), area
    if face_centred:
        if zone.structured:
            raise WopwopError("structured face-centred data: PSU-WOPWOP does not support it (its face centres need "
                              "an unstructured connectivity); write the zone unstructured or node-centred")
        return _mean_matrix(zone.faces, n_nodes), normals
    return np.eye(n_nodes), normals


def _unit_or_zero(normals: np.ndarray) -> bool:
    """PSU-WOPWOP's test on the FIRST normal of a structured zone: unit length or ~zero → areas from the geometry."""
    length = float(np.linalg.norm(normals[0, 0]))
    return abs(length - 1.0) <= UNIT_NORMAL_TOLERANCE or length < ZERO_NORMAL


def _mean_matrix(faces, n_nodes: int) -> np.ndarray:
    """(n_face, n_nodes) matrix averaging each face's nodes."""
    out = np.zeros((len(faces), n_nodes))
    for k, face in enumerate(faces):
        out[k, np.asarray(face)] = 1.0 / len(face)
    return out


def _compact_geometry(zone: binary.GeometryZone, xyz: np.ndarray, normals: np.ndarray, n_data: int):
    """(averaging matrix (n_point, n_nodes), span lengths (n_rows, n_point)) of a compact zone."""
    order = np.arange(zone.n_nodes) if zone.structured else _line_order(zone)
    segment = np.linalg.norm(np.diff(xyz[:, order], axis=1), axis=-1)  # (n_rows, n - 1)
    if _face_centred_compact(zone, n_data):
        mean = np.zeros((zone.n_nodes - 1, zone.n_nodes))
        mean[np.arange(zone.n_nodes - 1), order[:-1]] = 0.5
        mean[np.arange(zone.n_nodes - 1), order[1:]] += 0.5
        return mean, segment
    if _unit_or_zero(normals):
        share = np.zeros(xyz.shape[:2])
        share[:, order[:-1]] += 0.5 * segment
        share[:, order[1:]] += 0.5 * segment
        return np.eye(zone.n_nodes), share
    return np.eye(zone.n_nodes), np.linalg.norm(normals, axis=-1)


def zone_outline(zone: binary.GeometryZone) -> np.ndarray:
    """Points (n, 3) of a zone's first key in its local frame that bound its extent: the nodes, and for a compact
    zone the two ends of the line, each end node pushed outward by half its span length."""
    xyz = np.asarray(zone.xyz[0], dtype=float)
    if not is_compact(zone) or zone.n_nodes < 2:
        return xyz
    _, length = _compact_geometry(zone, xyz[None], np.asarray(zone.normals[:1], dtype=float), zone.n_nodes)
    order = np.arange(zone.n_nodes) if zone.structured else _line_order(zone)
    ends = []
    for end, inner in ((order[0], order[1]), (order[-1], order[-2])):
        direction = xyz[end] - xyz[inner]
        ends.append(xyz[end] + 0.5 * length[0, end] * direction / np.linalg.norm(direction))
    return np.vstack([xyz, ends])


def _line_order(zone: binary.GeometryZone) -> np.ndarray:
    """Node order along an unstructured two-face compact zone (faces as PSU-WOPWOP's line segments)."""
    ids = np.unique(np.concatenate([np.asarray(f) for f in zone.faces]))
    if ids.size != zone.n_nodes:
        raise WopwopError(f"zone '{zone.name}': a two-face compact zone must use all its {zone.n_nodes} nodes")
    return ids


def zone_sources(zone: binary.GeometryZone, data: binary.FunctionalZone | None, functional: binary.FunctionalFile | None,
                 geometry_rows: KeyRows, data_rows: KeyRows | None, motion: FrameMotion, rho0_kg_m3: float) -> PointSources:
    """Point sources of one zone at the source steps of ``motion`` (its container's chain at τ_j).

    ``geometry_rows`` / ``data_rows``: the key row of every source step for the geometry and the functional data
    (None: no data, thickness only). Compact zones carry loading only; surfaces carry thickness when the data
    file lists the zone with a positive id (or has no data for it) and loading when data are given.
    """
    face_centred = functional is not None and functional.face_centred and data is not None
    xyz, normals = (np.asarray(a, dtype=float) for a in (zone.xyz, zone.normals))
    compact = is_compact(zone)
    n_data = data.n_data if data is not None else zone.n_nodes
    if compact:
        mean, length = _compact_geometry(zone, xyz, normals, n_data)
        area_local = None
    else:
        mean, area_local = _panel_geometry(zone, xyz, normals, face_centred)
    points = np.einsum("pn,rnk->rpk", mean, xyz)
    kin_local = keyed_rates(points, geometry_rows, 3)
    kin = apply(motion, None, np.stack([k[geometry_rows.rows] for k in kin_local]))
    force, force_rate = _loads(zone, data, functional, data_rows, geometry_rows, motion, mean, compact,
                               length if compact else area_local)
    thickness = not compact and (data is None or data.thickness)
    flux = flux_rate = None
    if thickness:
        area, area_rate = _ground_vectors(area_local, geometry_rows, motion)
        flux = rho0_kg_m3 * np.einsum("tpk,tpk->tp", kin[1], area)
        flux_rate = rho0_kg_m3 * (np.einsum("tpk,tpk->tp", kin[2], area) + np.einsum("tpk,tpk->tp", kin[1], area_rate))
    return PointSources(kin, force, force_rate, flux, flux_rate)


def _ground_vectors(local: np.ndarray, rows: KeyRows, motion: FrameMotion) -> tuple[np.ndarray, np.ndarray]:
    """Keyed local vectors (n_rows, n_point, 3) at the source steps in G, and their τ-rates (n_tau, n_point, 3)."""
    value, rate = keyed_rates(local, rows, 1)
    rotated = rotate_vectors(motion, value[rows.rows], rate[rows.rows])
    return rotated[0], rotated[1]


def _loads(zone, data, functional, data_rows, geometry_rows, motion, mean, compact, measure):
    """Force on the fluid (n_tau, n_point, 3) and its rate. ``measure``: span lengths (n_rows, n_point) of a
    compact zone, local area vectors (n_rows, n_point, 3) of a surface."""
    n_tau = geometry_rows.rows.size
    n_point = mean.shape[0]
    if data is None:
        zero = np.zeros((n_tau, n_point, 3))
        return zero, zero.copy()
    kind = functional.data_kind
    if kind == binary.FLOW:
        raise WopwopError(f"zone '{zone.name}': flow-parameter data (permeable surfaces) are read but not radiated by "
                          "NPS; give surface pressure or loading vectors")
    values = np.asarray(data.values, dtype=float)
    if values.shape[1] != n_point:  # node data on panels: average to the panel centres
        values = np.einsum("pn,rnc->rpc", mean, values)
    value, value_rate = keyed_rates(values, data_rows, 1)
    value, value_rate = value[data_rows.rows], value_rate[data_rows.rows]
    if compact:
        size, size_rate = (a[geometry_rows.rows] for a in keyed_rates(measure, geometry_rows, 1))
        normal, normal_rate = _compact_normals(zone, mean, geometry_rows, motion) if kind == binary.PRESSURE else (None, None)
    else:
        area, area_rate = _ground_vectors(measure, geometry_rows, motion)
        size = np.linalg.norm(area, axis=-1)
        size_rate = np.einsum("tpk,tpk->tp", area, area_rate) / np.where(size > 0.0, size, 1.0)
        normal, normal_rate = area, area_rate  # p A: pressure times the area vector
    if kind == binary.PRESSURE:
        p, p_rate = value[..., 0], value_rate[..., 0]
        if compact:  # p n̂ times the span length
            return ((p * size)[..., None] * normal,
                    (p_rate * size + p * size_rate)[..., None] * normal + (p * size)[..., None] * normal_rate)
        return p[..., None] * normal, p_rate[..., None] * normal + p[..., None] * normal_rate
    if functional.frame == binary.GROUND_FRAME:
        vec, vec_rate = value, value_rate
    else:
        rotated = rotate_vectors(motion, value, value_rate)
        vec, vec_rate = rotated[0], rotated[1]
    return -vec * size[..., None], -(vec_rate * size[..., None] + vec * size_rate[..., None])


def _compact_normals(zone, mean, geometry_rows: KeyRows, motion: FrameMotion):
    """Unit normals of a compact zone's points in G and their rates (pressure data on a lifting line)."""
    normals = np.einsum("pn,rnk->rpk", mean, np.asarray(zone.normals, dtype=float))
    length = np.linalg.norm(normals, axis=-1, keepdims=True)
    return _ground_vectors(normals / np.where(length > 0.0, length, 1.0), geometry_rows, motion)
