"""NPS cases as PSU-WOPWOP cases: ``nps wopwop export``.

An aircraft in a segment (or a rig) becomes a complete case directory that PSU-WOPWOP runs as it is: ``cases.nam``,
the case namelist, an observer file per observer velocity, and per rotor one compact geometry file and one
periodic functional data file shared by its blades.

Mapping (docs/reference/wopwop.md, "Export"):

* **containers**: the aircraft (``VH`` = its velocity, KnownFunction translation) → each rotor (its hub position
  and hub-frame orientation R_GH, TimeIndependent; its rotation, KnownFunction angle s Ω t + s φ about z_H, s the
  rotation sign, φ the blade phase) → each blade k (a TimeIndependent turn s 2πk/B about z_H, and
  ``periodicKeyOffset``: the rows of its loads, below).
* **lines**: NPS's compact source lines (:func:`nps.noise.sources.blade_lines`) are compact zones (iMax = 1, one
  node per radial station) of the blade frame: the lifting line (loading) and the two dual-compact thickness lines.
  A node's normal is (0, 0, dr): PSU-WOPWOP takes |n| as the span length of a compact node when the first normal
  is not of unit length, so each node carries dr exactly. Components in the blade frame: (e_r, s e_t, z_H) of
  NPS's rotating frame. The geometry is constant when the lines do not move in the rotating frame (no flapping
  or cyclic pitch), periodic otherwise.
* **loads**: loading vectors, patch-fixed frame (3), the force on the blade per unit span, −F/dr of the force on
  the fluid F of each node; periodic over the table's rows (one revolution, or the revolutions of a common
  period) with keys 0 … N (row indices, exact in single precision; the last key repeats row 0, as PSU-WOPWOP
  wants). The thickness lines' zones are written in format 1.1 with ``loadingOutput`` = 1, so that PSU-WOPWOP (and
  ``nps wopwop run``) reports their noise as thickness, as NPS does; every zone id is negative (compact zones
  radiate no thickness of their own).
* **time**: row r of blade k is heard at source time (r − o_k) T/N, o_k = (blade k's row shift) + φ N/2π, the
  ``periodicKeyOffset`` in rows: NPS applies row i + shift_k when blade 0 is at ψ_i = 2πi/N, at τ = (ψ_i − φ)/Ω.
  PSU-WOPWOP shifts periodic data by whole keys only, so a phase must be a whole number of azimuth steps.
* **observers**: the observer table as PSU-WOPWOP observer files (``nbx`` = n), one observer container per
  observer velocity (KnownFunction translation VH), on the signals' grid t_i = i D/N, i < N (tMin = 0,
  tMax = (N − 1) D/N, nt = N).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from nps.core import periods
from nps.noise.acoustics import LOADING, TimeGrid
from nps.noise.sources import COMPACT_MONOPOLE, ThicknessModel, blade_lines
from nps.rotor.geometry import RotorMotion
from nps.wopwop import binary
from nps.wopwop.errors import WopwopError
from nps.wopwop.namelist import Group, format_namelist

CASE_FILE = "case.nam"
OUTPUT_FOLDER = "output/"
LINE_NAMES = {0: "lifting_line", 1: "thickness_front", 2: "thickness_rear"}
UNIT_NORMAL_BAND = (0.999, 1.001)  # PSU-WOPWOP treats a first normal of this length as a unit normal
FILE_FLOAT = np.float32  # PSU-WOPWOP's files hold 4-byte reals (tests set float64 to check the export exactly)


@dataclass(frozen=True)
class RotorCase:
    """One rotor as the exporter needs it: its disk table (one revolution, or the revolutions of a common period),
    trim row, hinge offset (m), blade phase (deg) and the table-row shift of each blade (None: k N/B)."""

    name: str
    disk: pd.DataFrame
    trim_row: dict
    hinge_offset_m: float = 0.0
    phase_deg: float = 0.0
    blade_shift_steps: tuple[int, ...] | None = None


def rotor_files(rotor: RotorCase, thickness: ThicknessModel, comment: str) -> tuple[binary.GeometryFile, binary.FunctionalFile, int]:
    """(geometry file, functional data file, rows N of the period) of one rotor's blade lines (module doc)."""
    if thickness.kind == COMPACT_MONOPOLE:
        raise WopwopError(f"rotor '{rotor.name}': thickness model '{COMPACT_MONOPOLE}': PSU-WOPWOP computes no "
                          "thickness noise on compact patches; export with the dual-compact thickness lines")
    motion = RotorMotion.from_trim_row(rotor.trim_row)
    arrays, lines, _ = blade_lines(rotor.disk, motion, thickness, rotor.hinge_offset_m, float(rotor.trim_row["density_kg_m3"]))
    n_rows = arrays["r_m"].shape[0]
    dr = arrays["dr_m"][0]
    if UNIT_NORMAL_BAND[0] <= dr[0] <= UNIT_NORMAL_BAND[1]:
        raise WopwopError(f"rotor '{rotor.name}': the first radial element is {dr[0]:.6g} m wide: PSU-WOPWOP would take "
                          "a normal of that length for a unit normal; use another n_r")
    s = float(motion.rotation_sign)
    flip = np.array([1.0, s, 1.0])
    positions = [q * flip for q, _, _, _ in lines]
    loads = [-(g * flip) / dr[None, :, None] for _, g, _, _ in lines]
    varying = any(not np.array_equal(p.astype(FILE_FLOAT), np.broadcast_to(p[:1], p.shape).astype(FILE_FLOAT)) for p in positions)
    keys = np.arange(n_rows + 1, dtype=FILE_FLOAT)
    period = FILE_FLOAT(2.0 * np.pi * periods.table_revolutions(arrays["psi_rad"][:, 0]) / motion.omega_rad_s)
    normals = np.zeros((1, dr.size, 3), dtype=FILE_FLOAT)
    normals[0, :, 2] = dr
    geometry_zones, data_zones = [], []
    for k, ((_, _, group, _), pos, load) in enumerate(zip(lines, positions, loads)):
        name = LINE_NAMES[k]
        steps = np.concatenate([pos, pos[:1]]) if varying else pos[:1]
        geometry_zones.append(binary.GeometryZone(name, True, 1, dr.size, (), dr.size, float(period) if varying else None,
                                                  keys if varying else np.zeros(0, FILE_FLOAT), steps.astype(FILE_FLOAT),
                                                  np.repeat(normals, steps.shape[0], axis=0), None))
        data_zones.append(binary.FunctionalZone(k + 1, False, name, True, 1, dr.size, dr.size, float(period), keys,
                                                np.concatenate([load, load[:1]]).astype(FILE_FLOAT),
                                                loading_output=2 if group == LOADING else 1))
    kind = binary.PERIODIC if varying else binary.CONSTANT
    geometry = binary.GeometryFile("m", comment, kind, False, tuple(geometry_zones))
    functional = binary.FunctionalFile(comment, len(lines), True, binary.PERIODIC, False, binary.LOADING_VECTOR,
                                       binary.PATCH_FRAME, tuple(data_zones), minor_version=1)
    return geometry, functional, n_rows



def axis_angle(matrix: np.ndarray) -> tuple[np.ndarray, float]:
    """(unit axis, angle in rad, in [0, π]) of a proper rotation matrix: R = exp(angle [axis]×) (scipy's rotation
    vector, robust near a half turn); no rotation gives the axis (0, 0, 1) and angle 0."""
    from scipy.spatial.transform import Rotation

    vector = Rotation.from_matrix(np.asarray(matrix, dtype=float)).as_rotvec()
    angle = float(np.linalg.norm(vector))
    if angle < 1e-15:
        return np.array([0.0, 0.0, 1.0]), 0.0
    return vector / angle, angle


def _vec(values) -> tuple[float, float, float]:
    return tuple(float(v) for v in values)


def blade_offsets(rotor: RotorCase, n_rows: int) -> list[int]:
    """``periodicKeyOffset`` of each blade in rows: its row shift plus the phase φ N/2π (module doc)."""
    row = rotor.trim_row
    n_blades = int(row["n_blades"])
    n_turn = n_rows // periods.table_revolutions(np.unique(rotor.disk["psi_rad"].to_numpy(float)))
    steps = rotor.phase_deg / 360.0 * n_turn
    if abs(steps - round(steps)) > 1e-9 * max(1.0, abs(steps)):
        raise WopwopError(f"rotor '{rotor.name}': phase_deg {rotor.phase_deg:g}: PSU-WOPWOP shifts periodic data by whole "
                          f"keys, expected a multiple of the azimuth step {360.0 / n_turn:g} deg")
    if rotor.blade_shift_steps is not None:
        shifts = [int(k) for k in rotor.blade_shift_steps]
    elif n_turn % n_blades:
        raise WopwopError(f"rotor '{rotor.name}': {n_turn} azimuths per revolution, expected a multiple of its "
                          f"{n_blades} blades")
    else:
        shifts = [k * n_turn // n_blades for k in range(n_blades)]
    return [(shift + int(round(steps))) % n_rows for shift in shifts]


def rotor_groups(rotor: RotorCase, n_rows: int, geometry_file: str, loading_file: str) -> list[Group]:
    """The namelist groups of one rotor: its container, CBs and one container per blade (module doc)."""
    row = rotor.trim_row
    motion = RotorMotion.from_trim_row(row)
    s = float(motion.rotation_sign)
    axis, angle = axis_angle(motion.r_gh)
    groups = [Group("ContainerIn", {"Title": rotor.name, "nbContainer": int(row["n_blades"]), "nbBase": 3}),
              Group("CB", {"Title": "hub position", "TranslationType": "TimeIndependent",
                           "TranslationValue": _vec(motion.hub_position_m)}),
              Group("CB", {"Title": "hub frame", "AxisType": "TimeIndependent", "AngleType": "TimeIndependent",
                           "AxisValue": _vec(axis), "AngleValue": angle}),
              Group("CB", {"Title": "rotation", "Rotation": True, "AxisType": "TimeIndependent",
                           "AngleType": "KnownFunction", "AxisValue": (0.0, 0.0, 1.0),
                           "Omega": s * float(motion.omega_rad_s), "Psi0": float(s * np.radians(rotor.phase_deg))})]
    n_blades = int(row["n_blades"])
    for k, offset in enumerate(blade_offsets(rotor, n_rows)):
        groups += [Group("ContainerIn", {"Title": f"{rotor.name} blade {k + 1}", "patchGeometryFile": geometry_file,
                                         "patchLoadingFile": loading_file, "periodicKeyOffset": float(offset), "nbBase": 1}),
                   Group("CB", {"Title": "blade azimuth", "AxisType": "TimeIndependent", "AngleType": "TimeIndependent",
                                "AxisValue": (0.0, 0.0, 1.0), "AngleValue": float(s * 2.0 * np.pi * k / n_blades)})]
    return groups


def observer_groups(observers: pd.DataFrame, grid: TimeGrid, title: str) -> tuple[list[Group], dict[str, np.ndarray]]:
    """Observer containers (one per distinct observer velocity) and their observer files (name → (n, 3) positions
    at t = 0): the observer table's rows in ascending id, on the grid t_i = t0 + i D/N."""
    table = observers.sort_values("observer", kind="mergesort")
    velocity = table[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float)
    position = table[["x_m", "y_m", "z_m"]].to_numpy(float)
    distinct, which = np.unique(velocity, axis=0, return_inverse=True)
    t_max = grid.t_start_s + (grid.n_samples - 1) * grid.dt_s
    groups, files = [], {}
    for k, v in enumerate(distinct):
        name = title if len(distinct) == 1 else f"{title}_{k + 1}"
        files[f"{name}.xyz"] = position[np.ravel(which) == k]
        moving = bool(np.any(v != 0.0))
        groups.append(Group("ObserverIn", {"Title": name, "nt": int(grid.n_samples), "tMin": float(grid.t_start_s),
                                           "tMax": float(t_max), "fileName": f"{name}.xyz", "nbBase": int(moving)}))
        if moving:
            groups.append(Group("CB", {"Title": "observer motion", "TranslationType": "KnownFunction", "VH": _vec(v),
                                       "Y0": (0.0, 0.0, 0.0)}))
    return groups, files


def observer_file_text(positions: np.ndarray) -> str:
    """PSU-WOPWOP's observer file: ``nbx nby nbz`` (here n 1 1), then all x, all y, all z (list-directed)."""
    lines = [f"{len(positions)} 1 1"]
    lines += [" ".join(repr(float(v)) for v in positions[:, k]) for k in range(3)]
    return "\n".join(lines) + "\n"


def case_groups(title: str, rotors: list[RotorCase], n_rows: dict[str, int], observer_part: list[Group],
                n_observer_containers: int) -> list[Group]:
    """Every group of the case file: environment, constants, observers, the aircraft container and its rotors."""
    ref = rotors[0].trim_row
    velocity = RotorMotion.from_trim_row(ref).velocity_mps
    flags = ("ASCIIOutputFlag", "OASPLdBFlag", "OASPLdBAFlag", "spectrumFlag", "SPLdBFlag", "SPLdBAFlag",
             "acousticPressureFlag", "thicknessNoiseFlag", "loadingNoiseFlag", "totalNoiseFlag")
    groups = [Group("EnvironmentIn", {"nbSourceContainers": 1, "nbObserverContainers": n_observer_containers,
                                      "pressureFolderName": OUTPUT_FOLDER, "SPLFolderName": OUTPUT_FOLDER,
                                      **dict.fromkeys(flags, True)}),
              Group("EnvironmentConstants", {"rho": float(ref["density_kg_m3"]), "c": float(ref["speed_of_sound_mps"])}),
              *observer_part,
              Group("ContainerIn", {"Title": title, "nbContainer": len(rotors), "nbBase": 1,
                                    "dTau": 2.0 * np.pi / float(ref["omega_rad_s"]) / n_rows[rotors[0].name]}),
              Group("CB", {"Title": "flight", "TranslationType": "KnownFunction", "VH": _vec(velocity),
                           "Y0": (0.0, 0.0, 0.0)})]
    for rotor in rotors:
        groups += rotor_groups(rotor, n_rows[rotor.name], f"{rotor.name}_geometry.dat", f"{rotor.name}_loading.dat")
    return groups


def export_case(rotors: list[RotorCase], observers: pd.DataFrame, grid: TimeGrid, thickness: ThicknessModel,
                directory: str | Path, title: str, observer_title: str, comment: str = "") -> Path:
    """Write the case directory (module doc) atomically: built in a temporary sibling, then renamed into place."""
    import os
    import shutil
    import tempfile

    directory = Path(directory)
    directory.parent.mkdir(parents=True, exist_ok=True)
    files = {rotor.name: rotor_files(rotor, thickness, comment or f"NPS export of {title}") for rotor in rotors}
    observer_part, observer_files = observer_groups(observers, grid, observer_title)
    n_containers = sum(g.name == "ObserverIn" for g in observer_part)
    groups = case_groups(title, rotors, {name: f[2] for name, f in files.items()}, observer_part, n_containers)
    work = Path(tempfile.mkdtemp(prefix=f".{directory.name}.", suffix=".tmp", dir=directory.parent))
    try:
        (work / "cases.nam").write_text(format_namelist([Group("casename", {"globalFolderName": "./",
                                                                            "caseNameFile": CASE_FILE})]))
        (work / CASE_FILE).write_text(format_namelist(groups))
        for name, positions in observer_files.items():
            (work / name).write_text(observer_file_text(positions))
        for name, (geometry, functional, _) in files.items():
            binary.write_geometry(geometry, work / f"{name}_geometry.dat")
            binary.write_functional(functional, work / f"{name}_loading.dat")
        if directory.exists():
            shutil.rmtree(directory)
        os.replace(work, directory)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return directory
