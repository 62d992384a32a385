"""The PSU-WOPWOP runner (nps.wopwop.run.run_case): its periodic and direct paths, periodicKeyOffset, the frames of
loading vectors, face-centred compact data, surface pressure against loading vectors, and its refusals.

Cases are small files written here (nps.wopwop.binary writers, namelist text) and read back with
nps.wopwop.case.read_case, as a user's case would be. A compact blade line of four nodes at r = 0.25 … 1 m (values
exact in float32) turns about +z at Ω = 64π rad/s (T = 31.25 ms, tip Mach 0.59); its loads vary with azimuth. Most
tests compare the runner with itself along two routes that must agree (the claim under test); the surface-pressure
test also compares with sources built here in numpy and radiated with nps.noise.acoustics.radiate_arrays.
"""

from __future__ import annotations

import numpy as np
import pytest

from nps.wopwop import binary
from nps.wopwop.case import read_case
from nps.wopwop.errors import WopwopError
from nps.wopwop.run import GROUPS, run_case
from tests.wopwop_builders import (C0_M_S, RHO0_KG_M3, blade_loads, ground_loads, reference_pressure, relative_error,
                                   spin, write_case_dir)

PERIOD = 0.03125                   # s, exact in float32 (the files hold the period in single precision)
OMEGA = 2.0 * np.pi / PERIOD       # 64π rad/s
N_KEYS = 128                       # distinct keys per revolution
RADII = np.array([0.25, 0.5, 0.75, 1.0])
OBSERVER_BOX = "nbx=2 xMin=-2.0 xMax=3.0 nby=1 yMin=1.5 yMax=1.5 nbz=1 zMin=-1.0 zMax=-1.0"
LOADING = GROUPS.index("loading")
DTAU = f"dTau={PERIOD / N_KEYS!r}"  # the source-time step of constant data


# ------------------------------------------------------------------------------------------------ builders
def loads_by_key(psi: np.ndarray, radii: np.ndarray = RADII, ground: bool = False) -> np.ndarray:
    """The builders' blade loads (rotor frame, or turned into the ground frame) in file order (n_keys, n_r, 3)."""
    return (ground_loads if ground else blade_loads)(psi, radii)[0].transpose(1, 0, 2)


def line_zone(xyz: np.ndarray, normals: np.ndarray, keys=(), period_s=None, iblank=None) -> binary.GeometryZone:
    """A structured 1 x n zone: node positions and normals (n_steps, n, 3)."""
    n = xyz.shape[1]
    return binary.GeometryZone("line", True, 1, n, (), n, period_s, np.asarray(keys, np.float32),
                               np.asarray(xyz, np.float32), np.asarray(normals, np.float32),
                               None if iblank is None else np.asarray(iblank, np.int32))


def constant_line(radii: np.ndarray = RADII, **kw) -> binary.GeometryFile:
    """The blade line along the local x axis, constant; node normals (0, 0, 0.25): span 0.25 m each (|n|)."""
    xyz = np.stack([radii, 0.0 * radii, 0.0 * radii], axis=-1)[None]
    normals = np.tile([0.0, 0.0, 0.25], (1, radii.size, 1))
    return binary.GeometryFile("m", "blade line", binary.CONSTANT, False, (line_zone(xyz, normals, **kw),))


def data_file(values, time_kind, keys=(), period_s=None, data_kind=binary.LOADING_VECTOR, frame=binary.PATCH_FRAME,
              face_centred=False, structured=True, zone_id=-1, dims=None) -> binary.FunctionalFile:
    """A functional file with one data zone for geometry zone |zone_id| (negative: no thickness noise);
    values (n_steps, n_data, n_components); structured dims (1, n_data) unless given."""
    values = np.asarray(values, np.float32)
    n = values.shape[1]
    i_max, j_max = (dims or (1, n)) if structured else (0, 0)
    zone = binary.FunctionalZone(abs(zone_id), zone_id > 0, "data", structured, i_max, j_max, n, period_s,
                                 np.asarray(keys, np.float32), values)
    return binary.FunctionalFile("data", 1, structured, time_kind, face_centred, data_kind, frame, (zone,))


def periodic_keys() -> np.ndarray:
    """Keys 0 … 2π (N_KEYS + 1, the last repeating the first), as VSP2WOPWOP writes them."""
    return np.linspace(0.0, 2.0 * np.pi, N_KEYS + 1)


def patch_frame_loads() -> binary.FunctionalFile:
    """Periodic loads of the blade line in the patch frame, keys 0 … 2π."""
    return data_file(loads_by_key(periodic_keys()), binary.PERIODIC, periodic_keys(), PERIOD)


def rotor(title: str, files: str, extra: str = "", blade_extra: str = "") -> str:
    """A rotor container (KnownFunction turn about +z) holding one blade container with ``files``."""
    return (f"&ContainerIn Title='{title}' nbContainer=1 nbBase=1 {extra} /\n"
            f"&CB Title='spin' Rotation=.true. AngleType='KnownFunction' Omega={OMEGA!r} AxisValue=0,0,1 /\n"
            f"&ContainerIn Title='{title} blade' nbBase=0 {files} {blade_extra} /\n")


def pair(stem: str) -> str:
    return f"patchGeometryFile='{stem}_g.dat' patchLoadingFile='{stem}_f.dat'"


def case_text(containers: list[str], window=(0.05, 0.05 + 2 * PERIOD, 256), observer: str = OBSERVER_BOX,
              observer_cbs: str = "") -> str:
    """A case: ρ0, c0 of the builders, one observer container (``observer`` fields, its CB blocks), the given
    top-level containers."""
    t_min, t_max, nt = window
    n_base = observer_cbs.count("&CB")
    return (f"&EnvironmentIn nbSourceContainers={len(containers)} nbObserverContainers=1 "
            "acousticPressureFlag=.true. /\n"
            f"&EnvironmentConstants rho={RHO0_KG_M3} c={C0_M_S} /\n"
            f"&ObserverIn Title='mics' nt={nt} tMin={t_min!r} tMax={t_max!r} nbBase={n_base} {observer} /\n"
            + observer_cbs + "".join(containers))


def run(tmp_path, text: str, files: dict):
    """Write the case (files: stem → (geometry, functional)) and run it: its one ObserverResult."""
    case_path = write_case_dir(tmp_path, text)
    for stem, (geometry, functional) in files.items():
        binary.write_geometry(geometry, tmp_path / "case" / f"{stem}_g.dat")
        binary.write_functional(functional, tmp_path / "case" / f"{stem}_f.dat")
    (result,) = run_case(read_case(case_path))
    return result


# ------------------------------------------------------------------------------------------------ the paths
FLIGHT_MPS = 30.0


@pytest.mark.parametrize("flight", [False, True], ids=["hover-observers-at-rest", "flight-observers-moving-along"])
def test_periodic_and_direct_paths_agree(tmp_path, flight):
    """One rotor heard along both paths: periodic loads (keys 0 … 2π) take the periodic path; the same loads written
    as aperiodic keys (times k T/128 over 4.5 revolutions) force the direct path, with nothing else changed. Hover
    with observers at rest, and a 30 m/s flight (aircraft CB) with observers moving along (observer CB).

    Catches: a wrong path choice, a periodic resampling or direct-window error, a frame velocity not applied to one
    path. Tolerance 5e-5 of the peak loading pressure: the two paths interpolate the reception samples differently
    (the periodic one through one period and a Fourier series), an error that falls as ~h^5 with the key spacing:
    measured 6.5e-6 (hover), 1.2e-5 (flight) with 128 keys per revolution, 1.7e-4 and 3.7e-4 with 64."""
    motion = (f"&CB Title='flight' TranslationType='KnownFunction' VH={-FLIGHT_MPS!r},0.0,0.0 /\n" if flight else "")
    aircraft = "&ContainerIn Title='aircraft' nbContainer=1 nbBase={} /\n{}".format(int(flight), motion)
    times = PERIOD / N_KEYS * np.arange(int(4.5 * N_KEYS))
    aperiodic = data_file(loads_by_key(OMEGA * times), binary.APERIODIC, times)
    results = {}
    for stem, loads in (("periodic", patch_frame_loads()), ("direct", aperiodic)):
        text = case_text([aircraft + rotor("rotor", pair(stem))], observer_cbs=motion.replace("'flight'", "'obs'"))
        results[stem] = run(tmp_path / stem, text, {stem: (constant_line(), loads)})
    for stem, result in results.items():
        assert set(result.modes.values()) == {stem}
    periodic, direct = (results[s].pressure_pa["rotor"][:, LOADING] for s in ("periodic", "direct"))
    error = relative_error(direct, periodic)
    print(f"flight={flight}: peak {np.abs(periodic).max():.4g} Pa, direct vs periodic {error:.2e}")
    assert np.abs(periodic).max() > 0.1 and error < 5e-5


# ------------------------------------------------------------------------------------------ periodicKeyOffset
def rotating_line_files(keys_s: np.ndarray) -> tuple[binary.GeometryFile, binary.FunctionalFile]:
    """FLOWUnsteady-style ground-frame files: the line turning (periodic geometry keyed in seconds, 0 … T) and its
    loads turned into the ground frame."""
    psi = OMEGA * keys_s
    xyz = spin(np.stack([RADII, 0.0 * RADII, 0.0 * RADII], axis=-1), OMEGA, keys_s)[0].transpose(1, 0, 2)
    normals = np.tile([0.0, 0.0, 0.25], (keys_s.size, RADII.size, 1))
    loads = loads_by_key(psi, ground=True)
    geometry = binary.GeometryFile("m", "", binary.PERIODIC, False, (line_zone(xyz, normals, keys_s, PERIOD),))
    return geometry, data_file(loads, binary.PERIODIC, keys_s, PERIOD, frame=binary.GROUND_FRAME)


def test_periodic_key_offset_shifts_by_whole_keys(tmp_path):
    """Three top-level containers share ground-frame periodic files (keys in seconds); B has periodicKeyOffset = 3
    keys, C 3.4 keys (PSU-WOPWOP rounds to whole keys). Geometry and loads both shift, so B and C are A heard
    3 T/128 later: on a one-period grid of 256 samples, p_B(t_i) = p_A(t_i + 6 dt) = p_C(t_i).

    Catches: an offset applied in the wrong direction, to the loads only, in the wrong units, or not rounded to a
    whole key. Tolerance 1e-9 of the peak (the same arithmetic shifted); measured ~1e-15."""
    keys = PERIOD * np.arange(N_KEYS + 1) / N_KEYS
    step = PERIOD / N_KEYS
    containers = [f"&ContainerIn Title='{name}' nbBase=0 {pair('line')} periodicKeyOffset={offset * step!r} /\n"
                  for name, offset in (("A", 0.0), ("B", 3.0), ("C", 3.4))]
    nt = 2 * N_KEYS
    result = run(tmp_path, case_text(containers, window=(0.0, PERIOD * (nt - 1) / nt, nt)),
                 {"line": rotating_line_files(keys)})
    assert set(result.modes.values()) == {"periodic"}
    a, b, c = (result.pressure_pa[name][:, LOADING] for name in "ABC")
    shifted = np.roll(a, -6, axis=-1)
    print(f"peak {np.abs(a).max():.4g} Pa; B vs A shifted {relative_error(b, shifted):.1e}; C vs B "
          f"{relative_error(c, b):.1e}; B vs A unshifted {relative_error(b, a):.2f}")
    assert relative_error(b, shifted) < 1e-9 and relative_error(c, b) < 1e-9
    assert relative_error(b, a) > 0.05  # the shift is visible


# -------------------------------------------------------------------------------------------- loading frames
def test_ground_frame_loads_equal_patch_frame_loads(tmp_path):
    """The blade line under a turning CB with the same loads three ways: patch frame (3), rotating frame (2, the
    same for loading vectors) and ground frame (1: each key's vector turned by its azimuth Ω t_k in numpy).

    Catches: a frame flag ignored or mixed up, a rotation applied twice or with the wrong sense. Tolerance 2e-5 of
    the peak (float32 data; the ground-frame force rate comes from 6th-order differences over 128 keys, the others
    from the analytic turn); measured 1.2e-7. Frames 2 and 3: identical (tolerance 1e-12; measured 0)."""
    keys = periodic_keys()
    ground = loads_by_key(keys, ground=True)
    files = {"patch": (constant_line(), patch_frame_loads()),
             "rotating": (constant_line(), data_file(loads_by_key(keys), binary.PERIODIC, keys, PERIOD,
                                                     frame=binary.ROTATING_FRAME)),
             "ground": (constant_line(), data_file(ground, binary.PERIODIC, keys, PERIOD, frame=binary.GROUND_FRAME))}
    result = run(tmp_path, case_text([rotor(stem, pair(stem)) for stem in files]), files)
    patch, rotating, ground_p = (result.pressure_pa[stem][:, LOADING] for stem in files)
    print(f"peak {np.abs(patch).max():.4g} Pa; ground vs patch {relative_error(ground_p, patch):.1e}, rotating vs "
          f"patch {relative_error(rotating, patch):.1e}")
    assert relative_error(ground_p, patch) < 2e-5 and relative_error(rotating, patch) < 1e-12


# ---------------------------------------------------------------------------------- face-centred compact data
def test_face_centred_compact_data_equal_node_centred_equivalent(tmp_path):
    """Face-centred compact loads (FLOWUnsteady: one value per segment, n − 1 values, unstructured data file) on
    the 4-node line equal node-centred loads on a 3-node line at the segment midpoints whose normals (0, 0, ℓ) carry
    the segment lengths ℓ = 0.25 m (PSU-WOPWOP takes |n| as the span of a compact node when the first normal is not
    of unit length). Positions, lengths and loads are exact in float32, so the sources are the same numbers.

    Catches: face values placed at nodes, a wrong span (half segments, or the node shares), an off-by-one in the
    segment order. Tolerance 1e-12 of the peak; measured 0."""
    keys = periodic_keys()
    midpoints = 0.5 * (RADII[1:] + RADII[:-1])
    loads = loads_by_key(keys, midpoints)
    faces = data_file(loads, binary.PERIODIC, keys, PERIOD, face_centred=True, structured=False)
    nodes = data_file(loads, binary.PERIODIC, keys, PERIOD)
    files = {"faces": (constant_line(), faces), "nodes": (constant_line(midpoints), nodes)}
    result = run(tmp_path, case_text([rotor(stem, pair(stem)) for stem in files]), files)
    face_p, node_p = (result.pressure_pa[stem][:, LOADING] for stem in files)
    print(f"peak {np.abs(node_p).max():.4g} Pa; faces vs nodes {relative_error(face_p, node_p):.1e}")
    assert np.abs(node_p).max() > 0.1 and relative_error(face_p, node_p) < 1e-12


# ------------------------------------------------------------------------------ pressure vs loading vectors
PLATE_R = np.array([0.375, 0.625, 0.875])  # span stations (j) of a flat plate in the rotor plane
PLATE_Y = np.array([-0.0625, 0.0, 0.0625])  # chordwise stations (i)


def plate_geometry() -> binary.GeometryFile:
    """A flat 3 x 3-node plate in the rotor plane (z = 0), unit node normals +z: four quadrilateral panels."""
    yy, rr = np.meshgrid(PLATE_Y, PLATE_R)  # j outer, i fastest
    xyz = np.stack([rr.ravel(), yy.ravel(), 0.0 * rr.ravel()], axis=-1)[None]
    normals = np.tile([0.0, 0.0, 1.0], (1, xyz.shape[1], 1))
    zone = binary.GeometryZone("plate", True, 3, 3, (), 9, None, np.zeros(0, np.float32), xyz.astype(np.float32),
                               normals.astype(np.float32), None)
    return binary.GeometryFile("m", "plate", binary.CONSTANT, False, (zone,))


def plate_pressure() -> np.ndarray:
    """Gauge pressure (Pa) at the 9 nodes, i fastest: varies along the chord and the span."""
    yy, rr = np.meshgrid(PLATE_Y, PLATE_R)
    return (800.0 * rr * (1.0 - 4.0 * yy)).ravel()


def plate_reference(grid, observers) -> np.ndarray:
    """Four panels in numpy: centre the mean of the four nodes, area vector (0, 0, 0.25 x 0.0625 m²) (flat
    rectangles), force on the fluid p̄ A (p̄ the mean of the four nodes' pressures), turning with the rotor."""
    p = plate_pressure().reshape(3, 3)
    yy, rr = np.meshgrid(PLATE_Y, PLATE_R)
    mean = lambda a: 0.25 * (a[1:, 1:] + a[:-1, 1:] + a[1:, :-1] + a[:-1, :-1])  # noqa: E731
    centres = np.stack([mean(rr).ravel(), mean(yy).ravel(), np.zeros(4)], axis=-1)
    area = 0.25 * 0.0625  # each panel 0.25 m (span) x 0.0625 m (chord)
    tau = PERIOD * np.arange(N_KEYS) / N_KEYS
    force = np.broadcast_to((mean(p).ravel() * area)[:, None, None] * np.array([0.0, 0.0, 1.0]), (4, tau.size, 3))
    return reference_pressure(spin(centres, OMEGA, tau), tau, grid, observers, force=np.array(force),
                              force_rate=np.zeros((4, tau.size, 3)), period_s=PERIOD)


def test_surface_pressure_equals_loading_vectors(tmp_path):
    """A flat plate (structured 3 x 3 nodes, unit normals) under a turning CB, constant data, dTau = T/128: surface
    pressure p (force on the fluid p A) and loading vectors −p n̂ (the force on the surface, patch frame) give the
    same loading noise, equal to four panels built here with force on the fluid p̄ A (reference_pressure).

    Catches: a sign error in either convention, node data not averaged to the panels, a wrong panel area or
    orientation. Tolerance 1e-6 of the peak (all inputs exact in float32); measured 1e-14. Both zones are listed
    with a negative id: no thickness output."""
    p = plate_pressure()[None, :, None]
    vectors = -p * np.array([0.0, 0.0, 1.0])
    files = {"pressure": (plate_geometry(), data_file(p, binary.CONSTANT, data_kind=binary.PRESSURE, dims=(3, 3))),
             "vectors": (plate_geometry(), data_file(vectors, binary.CONSTANT, dims=(3, 3)))}
    result = run(tmp_path, case_text([rotor(stem, pair(stem), extra=DTAU) for stem in files]), files)
    reference = plate_reference(result.observers.grid, result.observers.position_m)[:, LOADING]
    for stem in files:
        assert not np.any(result.pressure_pa[stem][:, GROUPS.index("thickness")])
    pressure, vectors_p = (result.pressure_pa[stem][:, LOADING] for stem in files)
    print(f"peak {np.abs(reference).max():.4g} Pa; pressure {relative_error(pressure, reference):.1e}, vectors "
          f"{relative_error(vectors_p, reference):.1e}")
    assert relative_error(pressure, reference) < 1e-6 and relative_error(vectors_p, reference) < 1e-6


# -------------------------------------------------------------------------------------------------- refusals
def refusal(tmp_path, text: str, files: dict) -> str:
    """The one-line WopwopError of a refused case."""
    with pytest.raises(WopwopError) as caught:
        run(tmp_path, text, files)
    message = str(caught.value)
    assert "\n" not in message, message
    return message


def _blanked() -> dict:
    return {"b": (constant_line(iblank=[[1, 0, 1, 1]]), patch_frame_loads())}


def _flow() -> dict:
    values = np.ones((1, RADII.size, 5))
    flow = data_file(values, binary.CONSTANT, data_kind=binary.FLOW, frame=binary.GROUND_FRAME)
    return {"b": (constant_line(), flow)}


def _short_aperiodic() -> dict:
    times = PERIOD / N_KEYS * np.arange(3 * N_KEYS)
    return {"b": (constant_line(), data_file(loads_by_key(OMEGA * times), binary.APERIODIC, times))}


def _constant_loads() -> dict:
    return {"b": (constant_line(), data_file(loads_by_key(np.zeros(1)), binary.CONSTANT))}


def _mismatched_keys() -> dict:
    geometry_keys = PERIOD * np.arange(2 * N_KEYS + 1) / (2 * N_KEYS)
    geometry, _ = rotating_line_files(geometry_keys)
    _, loads = rotating_line_files(PERIOD * np.arange(N_KEYS + 1) / N_KEYS)
    return {"b": (geometry, loads)}


BLADE = [rotor("rotor", pair("b"), extra=DTAU)]
ACCELERATING = "&CB Title='obs' TranslationType='KnownFunction' VH=1.0,0.0,0.0 AH=0.5,0.0,0.0 /\n"
TURNING = "&CB Title='obs' AngleType='KnownFunction' Omega=1.0 AxisValue=0,0,1 /\n"
REFUSALS = {
    "iblank": (_blanked, {}, ["b_g.dat: zone 'line': iblank: blanked nodes"]),
    "accelerating observer": (_constant_loads, {"observer_cbs": ACCELERATING},
                              ["case.nam: &ObserverIn 'mics': its change-of-base chain turns or accelerates"]),
    "turning observer": (_constant_loads, {"observer_cbs": TURNING},
                         ["case.nam: &ObserverIn 'mics': its change-of-base chain turns or accelerates"]),
    "aperiodic data short of the window": (_short_aperiodic, {"window": (0.06, 0.15, 64)},
                                           ["b_g.dat (container 'rotor blade')", "window needs [0.06, 0.15] s"]),
    "constant data without dTau": (_constant_loads, {"containers": [rotor("rotor", pair("b"))]},
                                   ["container 'rotor blade'", "set dTau"]),
    "geometry and loading keys differ": (_mismatched_keys, {},
                                         [f"b_f.dat: keys: periodic data with {N_KEYS} keys",
                                          "expected the periodic keys of", f"b_g.dat ({2 * N_KEYS}"]),
}


@pytest.mark.parametrize("name", list(REFUSALS))
def test_refusals_name_the_file_and_field(tmp_path, name):
    """Each refusal is one line naming the file (or case file, or container) and the field: blanked iblank nodes;
    observers whose CB chain accelerates or turns; aperiodic data that end inside the observer window (0.06–0.15 s
    needs sources up to 0.15 s, the data stop at 0.094 s); constant data with no dTau; geometry keyed every T/256
    and loads every T/128."""
    files, options, fragments = REFUSALS[name]
    options = {"containers": BLADE, **options}
    message = refusal(tmp_path, case_text(**options), files())
    for fragment in fragments:
        assert fragment in message, (fragment, message)


def test_flow_data_refused_in_one_line(tmp_path):
    """Flow-parameter data (permeable surfaces) are read but not radiated: refused, one line naming the zone and
    the data kind."""
    message = refusal(tmp_path, case_text(BLADE), _flow())
    assert "zone 'line': flow-parameter data" in message


def test_flow_data_refusal_names_the_file(tmp_path):
    """The flow-data refusal names the data file, as every other refusal of the runner does."""
    message = refusal(tmp_path, case_text(BLADE), _flow())
    assert "b_f.dat" in message or "b_g.dat" in message, message
