"""PSU-WOPWOP cases written byte for byte in the layouts of two public tools, run with nps.wopwop.run.run_case and
checked against independent computations.

(a) FLOWUnsteady + FLOWNoise (byuflowlab; FLOWUnsteady src/FLOWUnsteady_noise_wopwop.jl run_noise_wopwop and
generate_wopwoploading, FLOWNoise src/FLOWNoise_wopwop.jl vtk2wopwop with compact=true, GeometricTools
generatePLOT3D with trickwopwop=true for the observer grid). Per blade one geometry file: structured 1 x n,
node-centred, the lifting line in the GROUND frame moving with time, periodic (period = tMax, keys = times 0 … tMax,
nt + 1 steps) or aperiodic (keys = times), node "normals" the sum of the half segment vectors, strings space-padded,
units "N/m^2", zone "vtkcompactpatch"; and one loading file: unstructured, face-centred (n − 1 values, one per
segment), loading vectors per unit length, ground frame (1), zone list (1, −1), zone "liftinglineloading", keys
t0 + i dt. The case: ``nbContainer=1`` in &EnvironmentIn, an observer ``fileName="observergrid.xyz"`` or
``xLoc``/``yLoc``/``zLoc``, ``tMin = 0``, ``tMax`` = revolutions x T, ``nt`` = revolutions x steps per revolution,
an optional observer translation CB (``iB=1``, ``Y0``, ``VH``), then ``&ContainerIn dTau, nbBase=0, nbContainer``
holding one container per blade (no CBs: the geometry already moves).

(b) VSP2WOPWOP (DanWeitsman/VSP2WOPWOP: VSP2WOPWOP/GeomPatchFileWrite.py, PeriodicLoadingPatchFileWrite.py,
nmlWrite.py, CaseFileWrite.py, NodeCenteredNorms.py, GeomProcess.py, functions/loadingFF.py; the example
TestCase/BoeingModel360/.../Model360.nam). A constant geometry file of two structured node-centred zones, "Blade"
(iMax = points per section, TE → lower surface → LE → upper surface → TE, jMax = sections along +y; node
normals the mean of the adjacent cross products over the mean of their magnitudes: the first, a corner, is a unit
vector)
and "Lifting Line" (1 x n at the quarter chord, unit normals (sin twist, 0, cos twist)), NUL-padded strings; a
periodic loading file for zone −2 only (patch frame 3, node-centred, keys φ = 0 … 2π in radians with the last key
2π, 361 keys, period 60/RPM s); the namelist ``name = value`` one a line, lower-case group names, lists written
``0, 0, 1``, ``'Timeindependent'``: an aircraft container (KnownFunction translation, disk tilt), a rotor container
(KnownFunction rotation Omega = 2π RPM/60, then −π/2 about z to align the blades) and four blade containers with
periodicKeyOffset 2πk/4 and TimeIndependent azimuth (2πk/4) and pitch CBs; a sphere observer with an observer-motion
CB.

References, none of them nps.wopwop: the same moving sources built in numpy (closed-form kinematics, the loads of
tests/wopwop_builders.py) and radiated with nps.noise.acoustics.radiate_arrays (loading), and the full-surface
thickness integral of tests/validation/test_acoustics_thickness_surface.py (full_surface_pressure, numpy) for the
VSP2WOPWOP blade surface (the UH-1H model blade of that test, 4 blades); the blade-passage harmonic content (only
multiples of B = 4) as a closed-form check. Features these tools write that NPS refuses are refused in one line
naming the file and the field.
"""

from __future__ import annotations

import numpy as np
import pytest

from nps.wopwop.case import read_case
from nps.wopwop.errors import WopwopError
from nps.wopwop.run import GROUPS, run_case
from tests.validation.test_acoustics_thickness_surface import (CHORD, N_OUT, RADIUS, ROOT, _half_thickness,
                                                               full_surface_pressure)
from tests.wopwop_builders import (C0_M_S, RHO0_KG_M3, blade_loads, blocks, ground_loads, harmonic_leak, ints,
                                   observer_grid, reals, reference_pressure, relative_error, spin, text,
                                   write_case_dir)

THICKNESS, LOADING = GROUPS.index("thickness"), GROUPS.index("loading")

# ------------------------------------------------------------------------------------------ (a) FLOWUnsteady
RPM = 1920.0                           # T = 31.25 ms (exact in float32), tip Mach 0.44
PERIOD = 60.0 / RPM
OMEGA = 2.0 * np.pi / PERIOD
STEPS = 72                             # FLOWUnsteady steps per revolution
NODES_R = np.linspace(0.15, 0.75, 9)   # lifting-line nodes (m): 8 horseshoes
MID_R, SEGMENT = 0.5 * (NODES_R[1:] + NODES_R[:-1]), np.diff(NODES_R)
BLADES = 2
FLOW_COMMENT = ("Geometry input file for PSU-WOPWOP (Format v1.0)\n------------------------------------------------\n"
                "Created by FLOWNoise (written by Eduardo Alvarez)\nUnits: SI\nFormat: Structured grid, node-centered")
LOAD_COMMENT = ("Compact patch loading data file for PSU-WOPWOP (Format v1.0)\n"
                "------------------------------------------------\nUnits: SI\nFormat: Global coordinate system, "
                "unstructured")
MICROPHONE = np.array([2.5, 1.0, -1.2])


def flownoise_geometry(keys: np.ndarray, lines: np.ndarray, period: float | None) -> bytes:
    """vtk2wopwop(compact=true): lines (n_steps, n, 3) in the ground frame; periodic (period) or aperiodic."""
    kind = 2 if period is not None else 3
    n = lines.shape[1]
    out = (ints(42, 1, 0) + text("N/m^2", 32, b" ") + text(FLOW_COMMENT, 1024, b" ") + ints(1, 1, 1, kind, 1, 1, 0, 0)
           + text("vtkcompactpatch", 32, b" ") + (reals(period) if period is not None else b"") + ints(keys.size, 1, n))
    for key, line in zip(keys, lines):
        half = 0.5 * np.diff(line, axis=0)
        normals = np.zeros_like(line)
        normals[:-1] += half
        normals[1:] += half
        out += reals(key) + blocks(line) + blocks(normals)
    return out


def flowunsteady_loading(keys: np.ndarray, values: np.ndarray, period: float | None) -> bytes:
    """generate_wopwoploading(structured=false): values (n_steps, n − 1, 3) per unit length, ground frame."""
    kind = 2 if period is not None else 3
    out = (ints(42, 1, 0) + text(LOAD_COMMENT, 1024, b" ") + ints(2, 1, 2, kind, 2, 2, 1, 1, 0, 0) + ints(1, -1)
           + text("liftinglineloading", 32, b" ") + (reals(period) if period is not None else b"")
           + ints(keys.size, values.shape[1]))
    for key, value in zip(keys, values):
        out += reals(key) + blocks(value)
    return out


def flowunsteady_files(revolutions: int, periodic: bool) -> dict:
    """One compact geometry file and one loading file per blade over ``revolutions`` (keys = times 0 … tMax)."""
    woptype = "periodic" if periodic else "aperiodic"
    t_max = revolutions * PERIOD
    keys = t_max * np.arange(revolutions * STEPS + 1) / (revolutions * STEPS)
    period = t_max if periodic else None
    files = {}
    for blade in range(BLADES):
        phase = np.pi * blade
        lines = spin(np.stack([NODES_R, 0.0 * NODES_R, 0.0 * NODES_R], axis=-1), OMEGA, keys, phase)[0]
        loads = ground_loads(OMEGA * keys + phase, MID_R)[0]
        stem = f"rc_Sys1_Rotor1_Blade{blade + 1}"
        files[f"{stem}_compact.wop"] = flownoise_geometry(keys, lines.transpose(1, 0, 2), period)
        files[f"{stem}_loading_{woptype}.wop"] = flowunsteady_loading(keys, loads.transpose(1, 0, 2), period)
    return files


def plot3d_observers(points: np.ndarray, ni: int, nj: int) -> str:
    """GeometricTools generatePLOT3D(trickwopwop=true): "ni nj 1", then the x, y and z values ("%8.6f", a line
    break before every 10th value)."""
    rows = [f"{ni} {nj} 1"]
    for column in points.T:
        rows.append("".join(("" if n == 1 else "\n" if n % 10 == 0 else " ") + f"{v:8.6f}"
                            for n, v in enumerate(column, start=1)))
    return "\n".join(rows)


def sphere_points() -> np.ndarray:
    """Observers on a 3.2 m sphere (elevations 5°, 90°, 175° from +z, four azimuths), rounded as the file is."""
    elevation, azimuth = np.meshgrid(np.radians([5.0, 90.0, 175.0]), np.radians([0.0, 90.0, 180.0, 270.0]))
    points = 3.2 * np.stack([np.sin(elevation) * np.cos(azimuth), np.sin(elevation) * np.sin(azimuth),
                             np.cos(elevation)], axis=-1).reshape(-1, 3)
    return np.round(points, 6)


def flowunsteady_case(observer: str, revolutions: int, periodic: bool, observer_cb: str = "") -> str:
    """run_noise_wopwop's case file for one rotor of BLADES blades: ``observer`` the &ObserverIn lines (tMin, tMax,
    nt included), ``observer_cb`` its CB block."""
    woptype = "periodic" if periodic else "aperiodic"
    blades = "".join(f"""&ContainerIn
  patchGeometryFile="rc_Sys1_Rotor1_Blade{b}_compact.wop"
  patchLoadingFile="rc_Sys1_Rotor1_Blade{b}_loading_{woptype}.wop"
  nbBase=0
/
""" for b in range(1, BLADES + 1))
    return f"""&EnvironmentIn

  nbContainer=1
  ASCIIOutputFlag=.true.
  audioFlag=.false.

  OASPLdBFlag = .true.
  OASPLdBAFlag = .true.
  spectrumFlag = .true.
  SPLdBFlag = .true.
  SPLdBAFlag = .true.
  acousticPressureFlag=.true.
  pressureGradient1AFlag = .false.

  debugLevel = 1

  thicknessNoiseFlag=.true.
  loadingNoiseFlag=.true.
  totalNoiseFlag=.true.

/
&EnvironmentConstants
  rho   = {RHO0_KG_M3}
  c     = {C0_M_S}
/
 &ObserverIn
{observer}
 /
{observer_cb}&ContainerIn
  dTau        = {revolutions * PERIOD / (revolutions * STEPS)!r}
  nbBase      = 0
  nbContainer = {BLADES}
/
""" + blades


def observer_lines(n_base: int, window: tuple, position: str) -> str:
    """The &ObserverIn body as FLOWUnsteady indents it."""
    t_min, t_max, nt = window
    return f"   nbBase = {n_base}\n   nt   = {nt}\n{position}\n   tMin = {t_min!r}\n   tMax = {t_max!r}\n"


def microphone(position=MICROPHONE) -> str:
    return "\n".join(f"   {axis}Loc = {float(value)!r}" for axis, value in zip("xyz", position))


def observer_translation(velocity) -> str:
    return ("&CB\n  Title='ObserverTranslation'\n  iB=1\n  TranslationType='KnownFunction'\n  Y0=0,0,0\n"
            "  VH={!r},{!r},{!r}\n/\n".format(*map(float, velocity)))


def flowunsteady_reference(tau: np.ndarray, grid, observers, period=None, observer_velocity=None) -> np.ndarray:
    """Both blades' face-centred sources in numpy: segment midpoints turning with the blade, force on the fluid
    −L ℓ (L per unit length, ℓ the segment length) and its rate."""
    kinematics, force, rate = [], [], []
    for blade in range(BLADES):
        phase = np.pi * blade
        kinematics.append(spin(np.stack([MID_R, 0.0 * MID_R, 0.0 * MID_R], axis=-1), OMEGA, tau, phase))
        value, d_psi = ground_loads(OMEGA * tau + phase, MID_R)
        force.append(-value * SEGMENT[:, None, None])
        rate.append(-OMEGA * d_psi * SEGMENT[:, None, None])
    return reference_pressure(np.concatenate(kinematics, axis=1), tau, grid, observers, force=np.concatenate(force),
                              force_rate=np.concatenate(rate), period_s=period, observer_velocity=observer_velocity)


def direct_tau(grid, reach_s: float, revolutions: float | None = None) -> np.ndarray:
    """Source times k T/STEPS from ``reach_s`` before the window to its end (within the data when
    ``revolutions`` is given)."""
    first = int(np.floor((grid.t_start_s - reach_s) / PERIOD * STEPS))
    last = int(np.ceil((grid.t_start_s + grid.duration_s) / PERIOD * STEPS)) + 4
    if revolutions is not None:
        first, last = max(first, 0), min(last, revolutions * STEPS)
    return PERIOD / STEPS * np.arange(first, last + 1)


def run_flowunsteady(tmp_path, case: str, files: dict, observer_file: str | None = None):
    """Write cases.nam, runcase/runcase.nam (the case) and the files; run: the one observer result."""
    path = write_case_dir(tmp_path, case, "runcase", files)
    (tmp_path / "runcase" / "case.nam").rename(tmp_path / "runcase" / "runcase.nam")
    path.write_text("&casename\nglobalFolderName='./runcase/'\ncaseNameFile='runcase.nam'\n/\n")
    if observer_file is not None:
        (tmp_path / "runcase" / "observergrid.xyz").write_text(observer_file)
    (result,) = run_case(read_case(path))
    return result


def loading_check(result, reference: np.ndarray, mode: str, tolerance: float, label: str) -> None:
    """The run's total loading against the reference, no thickness (compact zones), every container on ``mode``."""
    total = result.total_pa
    error = relative_error(total[:, LOADING], reference[:, LOADING])
    print(f"{label}: peak {np.abs(reference[:, LOADING]).max():.4g} Pa, loading error {error:.2e} of the peak")
    assert len(result.modes) == BLADES and all(m.startswith(mode) for m in result.modes.values())
    assert not np.any(total[:, THICKNESS])
    assert error < tolerance


def test_flowunsteady_periodic_case_with_observer_grid_file(tmp_path):
    """Periodic FLOWUnsteady case (2 revolutions read, T = tMax, 72 steps per revolution) heard on a 3 x 4 observer
    grid file; observer window tMin = 0, tMax = 2T, nt = 144. Periodic path.

    Reference: the same face-centred sources in numpy, radiated periodic with radiate_arrays on the same grid (the
    grid t_i = tMin + i (tMax − tMin)/(nt − 1), built here). Catches: the 1 x n geometry or face-centred data read
    wrong, the per-unit-length loads not times the segment lengths, the observer file misread, keys in seconds
    mapped wrong. Tolerance 2e-5 of the peak (float32 files, 6th-order key differences for the rates); measured
    1.8e-6."""
    points = sphere_points()
    grid = observer_grid(0.0, 2 * PERIOD, 2 * STEPS)
    case = flowunsteady_case(observer_lines(0, (0.0, 2 * PERIOD, 2 * STEPS), '   fileName = "observergrid.xyz"'),
                             2, periodic=True)
    result = run_flowunsteady(tmp_path, case, flowunsteady_files(2, periodic=True), plot3d_observers(points, 3, 4))
    assert np.array_equal(result.observers.grid.times_s, grid.times_s) and result.observers.shape == (3, 4)
    assert np.array_equal(result.observers.position_m, points)
    tau = 2 * PERIOD * np.arange(2 * STEPS) / (2 * STEPS)
    reference = flowunsteady_reference(tau, grid, points, period=2 * PERIOD)
    loading_check(result, reference, "periodic", 2e-5, "FLOWUnsteady periodic, observer file")


def test_flowunsteady_moving_observers_take_the_direct_path(tmp_path):
    """The same periodic files heard by the observer grid translating at 12 m/s (FLOWUnsteady's Vobserver: one
    observer CB, nbBase = 1): the observers do not move with the rotor, so the direct path, with the periodic rows
    wrapping over 2 revolutions of observer time.

    Reference: the sources in numpy over the source times the window needs (non-periodic radiate_arrays, moving
    observers). Catches: periodic rows not wrapping on the direct path, the observer translation lost. Tolerance
    2e-5 of the peak; measured 1.8e-6."""
    points, velocity = sphere_points(), np.array([12.0, -5.0, 0.0])
    window = (0.0, 2 * PERIOD, 2 * STEPS)
    case = flowunsteady_case(observer_lines(1, window, '   fileName = "observergrid.xyz"'), 2, periodic=True,
                             observer_cb=observer_translation(velocity))
    result = run_flowunsteady(tmp_path, case, flowunsteady_files(2, periodic=True), plot3d_observers(points, 3, 4))
    assert np.allclose(result.observers.velocity_mps, velocity)
    grid = observer_grid(*window)
    reference = flowunsteady_reference(direct_tau(grid, 5.0 / C0_M_S), grid, points, observer_velocity=velocity)
    loading_check(result, reference, "direct", 2e-5, "FLOWUnsteady periodic, moving observers")


def test_flowunsteady_aperiodic_case(tmp_path):
    """Aperiodic FLOWUnsteady case (period = nothing: keys = times 0 … 3T, 217 steps), one microphone (xLoc).

    With FLOWUnsteady's own window (tMin = 0, tMax = 2T) the first r/c seconds have no source data: NPS refuses in
    one line naming the geometry file and the window. On a window inside the data (T … 2T) the direct path is
    checked against the numpy sources over the data's source times. Catches: aperiodic keys taken as key indices
    or wrapped, data rows misaligned with the source steps. Tolerance 2e-5 of the peak; measured 2.0e-6."""
    files = flowunsteady_files(3, periodic=False)
    refused = flowunsteady_case(observer_lines(0, (0.0, 2 * PERIOD, 2 * STEPS), microphone()), 3, periodic=False)
    with pytest.raises(WopwopError) as caught:
        run_flowunsteady(tmp_path / "refused", refused, files)
    message = str(caught.value)
    assert "\n" not in message and "rc_Sys1_Rotor1_Blade1_compact.wop" in message, message
    assert f"window needs [0, {2 * PERIOD:.6g}] s" in message, message
    window = (PERIOD, 2 * PERIOD, STEPS + 1)
    case = flowunsteady_case(observer_lines(0, window, microphone()), 3, periodic=False)
    result = run_flowunsteady(tmp_path / "inside", case, files)
    grid = observer_grid(*window)
    reference = flowunsteady_reference(direct_tau(grid, 5.0 / C0_M_S, revolutions=3), grid, MICROPHONE[None, :])
    loading_check(result, reference, "direct", 2e-5, "FLOWUnsteady aperiodic, window inside the data")


def test_flowunsteady_microphone_with_observer_velocity_is_refused(tmp_path):
    """FLOWUnsteady writes ``nbBase = 2`` for a microphone (xLoc) with an observer velocity but only one &CB block
    (run_noise_wopwop: ``nbBase = $(Vobserver!=nothing ? 2 : 0)``): the second CB the count asks for is a
    &ContainerIn. Refused in one line naming the case file and the nbBase field."""
    case = flowunsteady_case(observer_lines(2, (0.0, 2 * PERIOD, 2 * STEPS), microphone()), 2, periodic=True,
                             observer_cb=observer_translation([12.0, 0.0, 0.0]))
    with pytest.raises(WopwopError) as caught:
        run_flowunsteady(tmp_path, case, flowunsteady_files(2, periodic=True))
    message = str(caught.value)
    print(message)
    assert "\n" not in message and "runcase.nam" in message and "nbBase" in message, message


# -------------------------------------------------------------------------------------------- (b) VSP2WOPWOP
MACH_TIP = 0.88                                          # the issue-5 case of test_acoustics_thickness_surface
VSP_OMEGA = MACH_TIP * C0_M_S / RADIUS
VSP_PERIOD = 2.0 * np.pi / VSP_OMEGA
VSP_BLADES, VSP_KEYS = 4, 361                            # loadingFF: phi = linspace(0, 2π, 361)
N_CHORD, N_SPAN = 12, 30                                 # panels per side chordwise, spanwise
OBSERVER_RADIUS = 3.09 * RADIUS


def vsp_surface() -> tuple[np.ndarray, int, np.ndarray]:
    """DegenGeom SURFACE_NODE order: per section (along +y), TE → lower surface → LE → upper surface → TE, chord
    along x with the leading edge at −x (the blade moves toward −x before the −π/2 alignment), pitch axis at the
    quarter chord; (nodes (i fastest), iMax, section radii). The UH-1H model blade: NACA 0012, closed TE, c, R and
    root of test_acoustics_thickness_surface, cosine chordwise spacing as its panels."""
    x = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, N_CHORD + 1)))
    around = np.concatenate([x[::-1], x[1:]])
    z = np.concatenate([-_half_thickness(x[::-1]), _half_thickness(x[1:])]) * CHORD
    radii = np.linspace(ROOT, RADIUS, N_SPAN + 1)
    nodes = np.stack([np.tile((around - 0.25) * CHORD, radii.size), np.repeat(radii, around.size),
                      np.tile(z, radii.size)], axis=-1)
    return nodes, around.size, radii


def vsp_node_normals(nodes: np.ndarray, i_max: int, j_max: int) -> np.ndarray:
    """NodeCenteredNorms' rule, in short: at each node the mean of the adjacent faces' cross products over the mean
    of their magnitudes (a corner node has one face: a unit normal). Face vector ½ d1 × d2 with d1 from node (i, j)
    to (i+1, j+1), d2 from (i+1, j) to (i, j+1): outward for this node order."""
    grid = nodes.reshape(j_max, i_max, 3)
    face = 0.5 * np.cross(grid[1:, 1:] - grid[:-1, :-1], grid[1:, :-1] - grid[:-1, 1:])
    total, size = np.zeros((j_max, i_max, 3)), np.zeros((j_max, i_max))
    for dj in (0, 1):
        for di in (0, 1):
            total[dj:j_max - 1 + dj, di:i_max - 1 + di] += face
            size[dj:j_max - 1 + dj, di:i_max - 1 + di] += np.linalg.norm(face, axis=-1)
    return (total / size[..., None]).reshape(-1, 3)


def vsp_geometry(nodes, normals, i_max: int, line, line_normals) -> bytes:
    """GeomPatchFileWrite: constant, structured, node-centred, two zones, NUL-padded strings."""
    j_max = line.shape[0]
    return (ints(42, 1, 0) + text("Pa", 32) + text("Blade and lifting line geometry patch file", 1024)
            + ints(1, 2, 1, 1, 1, 1, 0, 0) + text("Blade", 32) + ints(i_max, j_max) + text("Lifting Line", 32)
            + ints(1, j_max) + blocks(nodes) + blocks(normals) + blocks(line) + blocks(line_normals))


def vsp_loading(phi: np.ndarray, loads: np.ndarray, rpm: float) -> bytes:
    """PeriodicLoadingPatchFileWrite: zone −2 only, patch frame, keys φ (rad), period (rpm/60)^-1 s; loads
    (n_keys, n, 3): per key the dFx, dFy and dFz blocks."""
    out = (ints(42, 1, 0) + text("Constant loading patch file", 1024) + ints(2, 2, 1, 2, 1, 2, 3, 1, 0, 0)
           + ints(1, -2) + text("LiftingLine", 32) + reals((rpm / 60.0) ** -1) + ints(phi.size, 1, loads.shape[1]))
    for key, value in zip(phi, loads):
        out += reals(key) + blocks(value)
    return out


def vsp_blade_frame_loads(phi: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """The builders' loads in VSP's blade frame (x = −tangential, y = radial, z = axial): (n_keys, n_r, 3)."""
    rotor_frame = blade_loads(phi, radii)[0]
    return np.stack([-rotor_frame[..., 1], rotor_frame[..., 0], rotor_frame[..., 2]], axis=-1).transpose(1, 0, 2)


def vsp_namelist(groups: list[tuple[str, dict]]) -> str:
    """nmlWrite's text: '&name', one 'key = value' a line (lists as '0, 0, 1'), '/', a blank line."""
    out = ""
    for name, fields in groups:
        lines = [f"{key} = {', '.join(map(str, value)) if isinstance(value, list) else value}"
                 for key, value in fields.items()]
        out += "&" + name + "\n" + "".join(line + "\n" for line in lines) + "/\n\n"
    return out


def vsp_cb(title: str, axis: list, angle: float) -> tuple[str, dict]:
    return ("cb", {"Title": f"'{title}'", "AngleType": "'Timeindependent'", "AxisType": "'Timeindependent'",
                   "AxisValue": axis, "angleValue": angle})


def vsp_pitch(periodic: bool) -> tuple[str, dict]:
    """The blade's pitch CB: TimeIndependent (collective 0), or with trim == 3 the Periodic series VSP2WOPWOP
    writes (A0, A1, B1 and no Omega)."""
    if not periodic:
        return vsp_cb("Pitch", [0, 1, 0], 0.0)
    return ("cb", {"Title": "'Pitch'", "AngleType": "'Periodic'", "A0": 0.05, "A1": -0.01, "B1": 0.02,
                   "AxisValue": [0, 1, 0]})


def vsp_case(periodic_pitch: bool = False) -> str:
    """nmlWrite's case: hover (VH = 0), sphere observers at 3.09 R (ψ = −30° and 0, θ = 0), one revolution."""
    groups = [
        ("environmentin", {"nbSourceContainers": 1, "nbObserverContainers": 1, "spectrumFlag": ".false.",
                           "SPLdBFLAG": ".false.", "broadbandFlag": ".false.", "thicknessNoiseFlag": ".true.",
                           "loadingNoiseFlag": ".true.", "acousticPressureFlag": ".true.", "totalNoiseFlag": ".true.",
                           "debugLevel": 1, "ASCIIOutputFlag": ".true.", "sigmaflag": ".false.",
                           "loadingSigmaFlag": ".true.", "MdotrSigmaFlag": ".true.", "velocitySigmaFlag": ".true."}),
        ("environmentconstants", {"rho": RHO0_KG_M3, "c": C0_M_S}),
        ("observerin", {"title": "'Observers'", "!attachedto": "'Aircraft'", "nt": 1024, "tmin": 0.0,
                        "tmax": VSP_PERIOD, "highpassfrequency": 10, "lowpassfrequency": 20000,
                        "radius": OBSERVER_RADIUS, "nbtheta": 1, "nbpsi": 2, "thetamin": 0.0, "thetamax": 0.0,
                        "psimin": -np.pi / 6, "psimax": 0.0, "octaveFlag": ".false.", "octaveNumber": 3,
                        "octaveApproxFlag": ".false.", "nbBase": 1}),
        ("cb", {"Title": "'Observer motion'", "TranslationType": "'KnownFunction'", "VH": [0.0, 0, 0]}),
        ("containerin", {"Title": "'Aircraft'", "nbContainer": 1, "nbBase": 2, "dTau": VSP_PERIOD / 120}),
        ("cb", {"Title": "'Aircraft motion'", "TranslationType": "'KnownFunction'", "VH": [0.0, 0, 0.0]}),
        vsp_cb("Rotor disk AoA tilt", [0, 1, 0], -0.0),
        ("containerin", {"Title": "'Rotor'", "nbContainer": VSP_BLADES, "nbBase": 2}),
        ("cb", {"Title": "'Rotation'", "rotation": ".true.", "AngleType": "'KnownFunction'", "Omega": VSP_OMEGA,
                "Psi0": 0, "AxisValue": [0, 0, 1]}),
        vsp_cb("Rotate to align blades with zero azimuth", [0, 0, 1], -np.pi / 2),
    ]
    for k in range(VSP_BLADES):
        groups += [("containerin", {"Title": f"'Blade {k + 1}'", "patchGeometryFile": "'Geom.dat'",
                                    "patchLoadingFile": "'Load.dat'", "periodicKeyOffset": 2 * np.pi / VSP_BLADES * k,
                                    "nbBase": 2}),
                   vsp_cb("Constant Rotation", [0, 0, 1], 2 * np.pi / VSP_BLADES * k), vsp_pitch(periodic_pitch)]
    return vsp_namelist(groups)


def vsp_files() -> dict:
    """Geom.dat (blade surface and lifting line) and Load.dat (the lifting line's loads over 361 keys)."""
    nodes, i_max, radii = vsp_surface()
    normals = vsp_node_normals(nodes, i_max, radii.size)
    assert abs(np.linalg.norm(normals[0]) - 1.0) < 1e-12  # VSP2WOPWOP's first normal: unit length
    line = np.stack([0.0 * radii, radii, 0.0 * radii], axis=-1)
    line_normals = np.tile([0.0, 0.0, 1.0], (radii.size, 1))  # (sin twist, 0, cos twist), no twist
    phi = np.linspace(0.0, 2.0 * np.pi, VSP_KEYS)
    rpm = VSP_OMEGA * 60.0 / (2.0 * np.pi)
    return {"Geom.dat": vsp_geometry(nodes, normals, i_max, line, line_normals),
            "Load.dat": vsp_loading(phi, vsp_blade_frame_loads(phi, radii), rpm)}


def vsp_observers() -> np.ndarray:
    """The sphere's two observers: elevation −30° and 0 at azimuth 0."""
    elevation = np.array([-np.pi / 6, 0.0])
    return OBSERVER_RADIUS * np.stack([np.cos(elevation), 0.0 * elevation, np.sin(elevation)], axis=-1)


def vsp_loading_reference(grid, observers) -> np.ndarray:
    """The four lifting lines in numpy: nodes at the quarter chord (r_j on the blade's radial axis), span shares
    half the adjacent segments (unit normals: PSU-WOPWOP's rule), blade k at ψ = Ω τ + 2πk/4 carrying the loads of
    its own azimuth (periodicKeyOffset 2πk/4), force on the fluid −L share, one period of 360 steps."""
    _, _, radii = vsp_surface()
    share = np.zeros(radii.size)
    share[:-1] += 0.5 * np.diff(radii)
    share[1:] += 0.5 * np.diff(radii)
    tau = VSP_PERIOD * np.arange(VSP_KEYS - 1) / (VSP_KEYS - 1)
    kinematics, force, rate = [], [], []
    for k in range(VSP_BLADES):
        phase = 2 * np.pi * k / VSP_BLADES
        kinematics.append(spin(np.stack([radii, 0.0 * radii, 0.0 * radii], axis=-1), VSP_OMEGA, tau, phase))
        value, d_psi = ground_loads(VSP_OMEGA * tau + phase, radii)
        force.append(-value * share[:, None, None])
        rate.append(-VSP_OMEGA * d_psi * share[:, None, None])
    return reference_pressure(np.concatenate(kinematics, axis=1), tau, grid, observers,
                              force=np.concatenate(force), force_rate=np.concatenate(rate), period_s=VSP_PERIOD)


def thickness_reference(grid, observers) -> np.ndarray:
    """full_surface_pressure (two blades, N_OUT samples per period from t = 0) at the same panel count, the other
    two blades added by the quarter-period shift, evaluated on ``grid`` through its Fourier series."""
    out = []
    for observer in observers:
        two = full_surface_pressure(MACH_TIP, observer, n_chord=N_CHORD, n_span=N_SPAN)
        four = two + np.roll(two, N_OUT // VSP_BLADES)
        spectrum = np.fft.rfft(four) / N_OUT
        k = np.arange(spectrum.size)
        weight = np.where((k == 0) | (k == N_OUT // 2), 1.0, 2.0) * spectrum
        phase = 2.0 * np.pi * np.outer(k, grid.times_s) / VSP_PERIOD
        out.append(weight.real @ np.cos(phase) - weight.imag @ np.sin(phase))
    return np.array(out)


def test_vsp2wopwop_rotor_thickness_and_loading(tmp_path):
    """VSP2WOPWOP-layout case of a 4-bladed UH-1H model rotor in hover at tip Mach 0.88: blade surface (thickness)
    and lifting line (loading) in one geometry file, loads for zone −2 only, four blade containers with
    periodicKeyOffset 2πk/4. Periodic path; heard at 3.09 R in the rotor plane and 30° below it.

    Thickness against full_surface_pressure (numpy F1A over the same 12 x 30 panels per side, 1024 source steps):
    tolerance 5e-4 of the peak; measured 1.3e-4 in plane, 7.7e-5 at −30° (the runner's panels are the node
    quadrilaterals, the reference's the exact strip fluxes at their centroids; 360 source steps against 1024).
    Loading against the numpy lifting lines: tolerance 2e-5; measured 1.5e-6. The 4 blades: harmonics other than
    multiples of 4 below 1e-12 of the blade-passage ones in both (a blade on the wrong azimuth or a key offset of
    the wrong sign breaks it; the loads vary with azimuth). Catches: the surface's node normals taken as areas,
    panels misoriented, the chain order, the alignment CB, key offsets in radians misread."""
    path = write_case_dir(tmp_path, vsp_case(), "Boeing360_DegenGeom", vsp_files())
    (result,) = run_case(read_case(path))
    observers, grid = vsp_observers(), observer_grid(0.0, VSP_PERIOD, 1024)
    assert np.allclose(result.observers.position_m, observers, rtol=0.0, atol=1e-12)
    assert all(mode.startswith("periodic") for mode in result.modes.values()) and list(result.pressure_pa) == ["Rotor"]
    pressure = result.pressure_pa["Rotor"]
    thickness = thickness_reference(grid, observers)
    loading = vsp_loading_reference(grid, observers)[:, LOADING]
    errors = [relative_error(pressure[o, THICKNESS], thickness[o]) for o in range(2)]
    loading_error = relative_error(pressure[:, LOADING], loading)
    leaks = [harmonic_leak(pressure[:, g, :-1], VSP_BLADES) for g in (THICKNESS, LOADING)]
    print(f"thickness peaks {thickness.min(axis=1)} Pa, errors {errors}; loading peak {np.abs(loading).max():.4g} "
          f"Pa, error {loading_error:.2e}; harmonic leaks {leaks}")
    assert max(errors) < 5e-4 and loading_error < 2e-5 and max(leaks) < 1e-12


def test_vsp2wopwop_periodic_pitch_without_omega_is_refused(tmp_path):
    """With trim = 3 VSP2WOPWOP writes each blade's pitch as AngleType 'Periodic' with A0, A1, B1 and no Omega;
    NPS needs the Omega of a Periodic angle: refused in one line naming the case file, the &CB 'Pitch' block and
    the Omega field."""
    path = write_case_dir(tmp_path, vsp_case(periodic_pitch=True), "Boeing360_DegenGeom", vsp_files())
    with pytest.raises(WopwopError) as caught:
        run_case(read_case(path))
    message = str(caught.value)
    print(message)
    assert "\n" not in message and "case.nam" in message and "'Pitch'" in message and "Omega" in message, message
