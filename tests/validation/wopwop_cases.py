"""Small PSU-WOPWOP cases written into a directory, for the validations of ``nps wopwop run``.

Helpers only (no tests): constant structured geometry zones and constant loading-vector zones
(:mod:`nps.wopwop.binary`), the namelist groups of a rotor tree (an optional translating outer container, the
rotor container with a KnownFunction rotation about z, one container per blade turned by 2πk/B) and of observer
containers of points given in an observer file (:mod:`nps.wopwop.namelist`), and :func:`write_case`, which writes
``cases.nam``, the case file and every file it names, and reads the case back with
:func:`nps.wopwop.case.read_case`. SI units throughout; angles in rad.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from nps.wopwop import binary
from nps.wopwop.case import Case, read_case
from nps.wopwop.namelist import Group, format_namelist
from nps.wopwop.run import ObserverResult, run_case

CASE_FILE = "case.nam"
Z_AXIS = (0.0, 0.0, 1.0)


def structured_zone(name: str, xyz: np.ndarray, normals: np.ndarray) -> binary.GeometryZone:
    """A constant, node-centred structured zone from nodes ``xyz`` (j_max, i_max, 3) (i fastest in the file) and
    their ``normals`` of the same shape (unit vectors: a surface; |n| = span length: a compact line)."""
    xyz, normals = np.asarray(xyz, dtype=float), np.asarray(normals, dtype=float)
    j_max, i_max = xyz.shape[:2]
    n = i_max * j_max
    return binary.GeometryZone(name, True, i_max, j_max, (), n, None, np.zeros(0, np.float32),
                               xyz.reshape(1, n, 3).astype(np.float32), normals.reshape(1, n, 3).astype(np.float32), None)


def compact_line(name: str, nodes: np.ndarray, span_m: np.ndarray) -> binary.GeometryZone:
    """A lifting line: structured, iMax = 1, one node per element at ``nodes`` (n, 3), node normals (0, 0, dr)
    so that |n| is the element's span length (non-unit normals: PSU-WOPWOP takes |n| as the span)."""
    normals = np.zeros((len(nodes), 1, 3))
    normals[:, 0, 2] = span_m
    return structured_zone(name, np.asarray(nodes, dtype=float)[:, None, :], normals)


def geometry_file(zones, comment: str = "nps validation") -> binary.GeometryFile:
    """A constant, node-centred geometry file (m) of ``zones``."""
    return binary.GeometryFile("m", comment, binary.CONSTANT, False, tuple(zones))


def loading_file(zones: list[binary.GeometryZone], loads: list[np.ndarray], loading_output: list[int],
                 comment: str = "nps validation") -> binary.FunctionalFile:
    """Format 1.1 constant loading vectors in the patch frame, one (n, 3) array per zone (the force on the blade per
    unit span on a compact zone), every zone id negative (no thickness of its own), ``loading_output`` per zone
    (1: its noise is reported as thickness, 2: as loading)."""
    data = [binary.FunctionalZone(k + 1, False, zone.name, True, zone.i_max, zone.j_max, zone.n_nodes, None,
                                  np.zeros(0, np.float32), np.asarray(load, dtype=np.float32)[None], output)
            for k, (zone, load, output) in enumerate(zip(zones, loads, loading_output))]
    return binary.FunctionalFile(comment, len(zones), True, binary.CONSTANT, False, binary.LOADING_VECTOR,
                                 binary.PATCH_FRAME, tuple(data), minor_version=1)


def turn_cb(title: str, angle_rad: float) -> Group:
    """A TimeIndependent turn about z."""
    return Group("CB", {"Title": title, "AxisType": "TimeIndependent", "AngleType": "TimeIndependent",
                        "AxisValue": Z_AXIS, "AngleValue": float(angle_rad)})


def rotation_cb(omega_rad_s: float) -> Group:
    """The rotor shaft: KnownFunction angle Omega t about z."""
    return Group("CB", {"Title": "rotation", "Rotation": True, "AxisType": "TimeIndependent",
                        "AngleType": "KnownFunction", "AxisValue": Z_AXIS, "Omega": float(omega_rad_s), "Psi0": 0.0})


def translation_cb(title: str, velocity_mps) -> Group:
    """KnownFunction translation Y0 + VH t, Y0 = 0."""
    return Group("CB", {"Title": title, "TranslationType": "KnownFunction", "VH": tuple(float(v) for v in velocity_mps),
                        "Y0": (0.0, 0.0, 0.0)})


def rotor_groups(omega_rad_s: float, n_blades: int, d_tau_s: float, geometry_name: str,
                 loading_name: str | None = None, hub_velocity_mps=None) -> list[Group]:
    """The source tree: [an outer container translating at ``hub_velocity_mps`` →] the rotor (rotation Omega about
    z) → blade k (turned by 2πk/B) holding the patch files; dTau set on the first container (WOPWOP carries it
    over to the containers read after it)."""
    blade = {"patchGeometryFile": geometry_name, "nbBase": 1}
    if loading_name is not None:
        blade["patchLoadingFile"] = loading_name
    outer = [] if hub_velocity_mps is None else [
        Group("ContainerIn", {"Title": "aircraft", "nbContainer": 1, "nbBase": 1, "dTau": float(d_tau_s)}),
        translation_cb("flight", hub_velocity_mps)]
    rotor = {"Title": "rotor", "nbContainer": n_blades, "nbBase": 1}
    if not outer:
        rotor["dTau"] = float(d_tau_s)
    groups = [*outer, Group("ContainerIn", rotor), rotation_cb(omega_rad_s)]
    for k in range(n_blades):
        groups += [Group("ContainerIn", {"Title": f"blade {k + 1}", **blade}),
                   turn_cb("blade azimuth", 2.0 * np.pi * k / n_blades)]
    return groups


def observer_groups(title: str, positions_m, t_min_s: float, t_max_s: float, nt: int,
                    velocity_mps=None) -> tuple[list[Group], dict[str, str]]:
    """One observer container of the points ``positions_m`` (n, 3) (at t = 0) on the grid
    t_i = tMin + i (tMax − tMin)/(nt − 1), at rest or moving with ``velocity_mps`` (a KnownFunction translation
    CB): its groups and its observer file (name → text: ``n 1 1``, then all x, all y, all z)."""
    positions = np.atleast_2d(np.asarray(positions_m, dtype=float))
    name = f"{title}.xyz"
    text = "\n".join([f"{len(positions)} 1 1"] + [" ".join(repr(float(v)) for v in positions[:, k]) for k in range(3)])
    fields = {"Title": title, "nt": int(nt), "tMin": float(t_min_s), "tMax": float(t_max_s), "fileName": name,
              "nbBase": int(velocity_mps is not None)}
    groups = [Group("ObserverIn", fields)]
    if velocity_mps is not None:
        groups.append(translation_cb("observer motion", velocity_mps))
    return groups, {name: text + "\n"}


def write_case(directory, observers: list[tuple[list[Group], dict[str, str]]], sources: list[Group], c0_mps: float,
               rho0_kg_m3: float, patches: dict[str, binary.GeometryFile | binary.FunctionalFile]) -> Case:
    """Write ``cases.nam``, the case file (the observer containers of :func:`observer_groups`, one source tree),
    the observer files and the patch files (name → file) into ``directory``, and read the case back."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    for name, data in patches.items():
        write = binary.write_geometry if isinstance(data, binary.GeometryFile) else binary.write_functional
        write(data, directory / name)
    for _, files in observers:
        for name, text in files.items():
            (directory / name).write_text(text)
    environment = [Group("EnvironmentIn", {"nbSourceContainers": 1, "nbObserverContainers": len(observers),
                                           "acousticPressureFlag": True, "thicknessNoiseFlag": True,
                                           "loadingNoiseFlag": True, "totalNoiseFlag": True}),
                   Group("EnvironmentConstants", {"rho": float(rho0_kg_m3), "c": float(c0_mps)})]
    groups = environment + [g for obs, _ in observers for g in obs] + sources
    (directory / CASE_FILE).write_text(format_namelist(groups))
    (directory / "cases.nam").write_text(format_namelist([Group("casename", {"globalFolderName": "./",
                                                                             "caseNameFile": CASE_FILE})]))
    return read_case(directory / "cases.nam")


def run(case: Case) -> list[ObserverResult]:
    """``nps wopwop run`` on a case: one result per observer container."""
    return list(run_case(case))
