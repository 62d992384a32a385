"""PSU-WOPWOP binary geometry and functional files (nps.wopwop.binary).

Files are built here byte by byte with struct from the documented layout (PSU-WOPWOP container.f90
ReadFileHeaderV1_0 / CreatePatchesFromFile, surface.f90, loadingData.f90; FLOWNoise vtk2wopwop, FLOWUnsteady
generate_wopwoploading and VSP2WOPWOP GeomPatchFileWrite / PeriodicLoadingPatchFileWrite for the tool-style
cases), so the reader is checked against the layout and not only against our writer. Round trips compare
exact bytes and exact float32 values (no tolerance: nothing is converted)."""

from __future__ import annotations

import dataclasses
import math
import os
import re
import struct
import time

import numpy as np
import pytest

from nps.wopwop.binary import (
    APERIODIC, CONSTANT, FLOW, GROUND_FRAME, LOADING_VECTOR, MULTI_TIME_APERIODIC, PATCH_FRAME, PERIODIC, PRESSURE,
    ROTATING_FRAME, FunctionalFile, FunctionalZone, GeometryFile, GeometryZone, TimeFile, check_pair, face_count,
    read_functional, read_geometry, write_functional, write_geometry)
from nps.wopwop.errors import WopwopError

RNG_SEED = 20240607
HEADER_FIELDS = {"structured", "iblank", "n_zones"}  # filled by the reader, None allowed when writing


# ------------------------------------------------------------------------------------- layout packing
def ints(*values, order="<") -> bytes:
    return struct.pack(f"{order}{len(values)}i", *values)


def reals(*values, order="<") -> bytes:
    return struct.pack(f"{order}{len(values)}f", *values)


def text(value: str, size: int, pad: bytes = b"\0") -> bytes:
    return value.encode("ascii").ljust(size, pad)


def geometry_header(n_zones=1, grid=1, time_kind=1, centring=1, precision=1, iblank=0, kind=1, order="<",
                    units="m", comment="test", version=(1, 0), pad=b"\0") -> bytes:
    """Bytes 0-1099 of a geometry file: 42, version, units (32), comment (1024), 8 ints."""
    return (ints(42, *version, order=order) + text(units, 32, pad) + text(comment, 1024, pad)
            + ints(kind, n_zones, grid, time_kind, centring, precision, iblank, 0, order=order))


def functional_header(n_zones=1, grid=1, time_kind=1, centring=1, data_kind=2, frame=1, precision=1, order="<",
                      comment="test", pad=b"\0") -> bytes:
    """Bytes 0-1075 of a functional file: 42, version, comment (1024), 10 ints."""
    return (ints(42, 1, 0, order=order) + text(comment, 1024, pad)
            + ints(2, n_zones, grid, time_kind, centring, data_kind, frame, precision, 0, 0, order=order))


def blocks(array: np.ndarray, order="<") -> bytes:
    """(n, k) values as k blocks: all of column 0, then column 1, ..."""
    return np.asarray(array, dtype=order + "f4").T.tobytes()


def write_bytes(tmp_path, name: str, data: bytes):
    path = tmp_path / name
    path.write_bytes(data)
    return path


def refused(reader, path, *fragments: str) -> str:
    """The one-line message of a refused file, which names the file and contains every fragment."""
    with pytest.raises(WopwopError) as caught:
        reader(path)
    message = str(caught.value)
    assert "\n" not in message and message.startswith(f"{path}: "), message
    for fragment in fragments:
        assert fragment in message, (fragment, message)
    return message


# ---------------------------------------------------------------------------------------- model builders
def structured_geometry_zone(rng, name, i_max, j_max, time_kind, face_centred, iblank, n_steps=4, period=0.25):
    n_nodes = i_max * j_max
    n_normals = (i_max - 1) * (j_max - 1) if face_centred else n_nodes
    return _geometry_zone(rng, name, True, i_max, j_max, (), n_nodes, n_normals, time_kind, iblank, n_steps, period)


def unstructured_geometry_zone(rng, name, time_kind, face_centred, iblank, n_steps=4, period=0.25):
    faces = tuple(np.array(f, dtype=np.int32) for f in ([0, 1, 2], [1, 3, 4, 2], [4, 5, 6], [6, 0]))
    n_normals = len(faces) if face_centred else 7
    return _geometry_zone(rng, name, False, 0, 0, faces, 7, n_normals, time_kind, iblank, n_steps, period)


def _geometry_zone(rng, name, structured, i_max, j_max, faces, n_nodes, n_normals, time_kind, iblank, n_steps,
                   period):
    steps = 1 if time_kind == CONSTANT else n_steps
    keys = np.zeros(0, np.float32) if time_kind == CONSTANT else (0.01 + 0.03 * np.arange(steps)).astype(np.float32)
    return GeometryZone(
        name=name, structured=structured, i_max=i_max, j_max=j_max, faces=faces, n_nodes=n_nodes,
        period_s=period if time_kind == PERIODIC else None, keys=keys,
        xyz=rng.normal(size=(steps, n_nodes, 3)).astype(np.float32),
        normals=rng.normal(size=(steps, n_normals, 3)).astype(np.float32),
        iblank=rng.integers(0, 2, size=(steps, n_normals)).astype(np.int32) if iblank else None)


def functional_zone(rng, zone, thickness, structured, n_data, data_kind, time_kind, n_steps=4, period=0.25,
                    dims=(0, 0)):
    steps = 1 if time_kind == CONSTANT else n_steps
    values = rng.normal(size=(steps, n_data, {PRESSURE: 1, LOADING_VECTOR: 3, FLOW: 5}[data_kind]))
    if data_kind == FLOW:
        values[:, :, 0] = 1.0 + np.abs(values[:, :, 0])
    keys = np.zeros(0, np.float32) if time_kind == CONSTANT else (0.01 + 0.03 * np.arange(steps)).astype(np.float32)
    return FunctionalZone(zone=zone, thickness=thickness, name=f"load{zone}", structured=structured,
                          i_max=dims[0], j_max=dims[1], n_data=n_data,
                          period_s=period if time_kind == PERIODIC else None, keys=keys,
                          values=values.astype(np.float32))


def assert_same(original, read_back) -> None:
    """Field by field: arrays equal with the same dtype (float32 / int32), tuples element by element; the
    reader-filled header fields are compared only where the original gives them."""
    if dataclasses.is_dataclass(original):
        for field in dataclasses.fields(original):
            value = getattr(original, field.name)
            if value is None and field.name in HEADER_FIELDS:
                continue
            assert_same(value, getattr(read_back, field.name))
    elif isinstance(original, tuple):
        assert len(original) == len(read_back)
        for a, b in zip(original, read_back):
            assert_same(a, b)
    elif isinstance(original, np.ndarray):
        assert read_back.dtype == original.dtype and read_back.dtype.isnative, (original.dtype, read_back.dtype)
        assert np.array_equal(original, read_back)
    else:
        assert original == read_back, (original, read_back)


def round_trip(folder, obj, write, read):
    """Write, read back (equal), write the read object again (identical bytes); big-endian reads equal too."""
    folder.mkdir(exist_ok=True)
    first, second, big = folder / "a.bin", folder / "b.bin", folder / "big.bin"
    write(obj, first)
    back = read(first)
    assert_same(obj, back)
    write(back, second)
    assert first.read_bytes() == second.read_bytes()
    write(back, big, ">")
    big_back = read(big)
    assert big_back.byte_order == ">" and big.read_bytes()[:4] == b"\0\0\0\x2a"
    assert_same(dataclasses.replace(back, byte_order=">"), big_back)
    assert sorted(p.name for p in folder.iterdir()) == ["a.bin", "b.bin", "big.bin"]  # no temporary left
    return back


# ------------------------------------------------------------------------------------------ round trips
@pytest.mark.parametrize("structured", [True, False])
@pytest.mark.parametrize("time_kind", [CONSTANT, PERIODIC, APERIODIC])
@pytest.mark.parametrize("face_centred", [False, True])
@pytest.mark.parametrize("iblank", [False, True])
def test_geometry_round_trip(tmp_path, structured, time_kind, face_centred, iblank):
    rng = np.random.default_rng(RNG_SEED)
    if structured:
        zones = (structured_geometry_zone(rng, "blade", 5, 3, time_kind, face_centred, iblank),
                 structured_geometry_zone(rng, "tip", 2, 4, time_kind, face_centred, iblank))
    else:
        zones = (unstructured_geometry_zone(rng, "hub", time_kind, face_centred, iblank),)
    geometry = GeometryFile(units="Pa", comment="round trip\nsecond line", time_kind=time_kind,
                            face_centred=face_centred, zones=zones)
    back = round_trip(tmp_path, geometry, write_geometry, read_geometry)
    assert (back.structured, back.iblank, back.n_zones) == (structured, iblank, len(zones))


@pytest.mark.parametrize("structured", [True, False])
@pytest.mark.parametrize("time_kind", [CONSTANT, PERIODIC, APERIODIC])
@pytest.mark.parametrize("face_centred", [False, True])
@pytest.mark.parametrize("data_kind", [PRESSURE, LOADING_VECTOR, FLOW])
def test_functional_round_trip(tmp_path, structured, time_kind, face_centred, data_kind):
    rng = np.random.default_rng(RNG_SEED)
    if structured:
        zones = (functional_zone(rng, 1, True, True, 6, data_kind, time_kind, dims=(3, 2)),
                 functional_zone(rng, 3, False, True, 4, data_kind, time_kind, dims=(1, 4)))
    else:
        zones = (functional_zone(rng, 2, False, False, 9, data_kind, time_kind),)
    functional = FunctionalFile(comment="loads", n_zones=3, structured=structured, time_kind=time_kind,
                                face_centred=face_centred, data_kind=data_kind,
                                frame=ROTATING_FRAME if data_kind == FLOW else PATCH_FRAME, zones=zones)
    round_trip(tmp_path, functional, write_functional, read_functional)


def test_multi_file_aperiodic_indexes_round_trip(tmp_path):
    """Kind 4: the header, a file count, per file a 4096-byte name and its first/last step, nothing else."""
    files = (TimeFile("part1.dat", 1, 40), TimeFile("/abs/part2.dat", 2, 30))
    geometry = GeometryFile(units="m", comment="index", time_kind=MULTI_TIME_APERIODIC, face_centred=False,
                            zones=(), structured=False, iblank=True, n_zones=3, time_files=files)
    back = round_trip(tmp_path / "geometry", geometry, write_geometry, read_geometry)
    assert back.zones == () and back.time_files == files
    raw = (tmp_path / "geometry" / "a.bin").read_bytes()
    assert len(raw) == 1100 + 4 + 2 * (4096 + 8)
    assert raw[1104:1104 + 4096] == b"part1.dat".ljust(4096, b" ")  # Fortran trim removes blanks, not NULs
    functional = FunctionalFile(comment="index", n_zones=3, structured=True, time_kind=MULTI_TIME_APERIODIC,
                                face_centred=False, data_kind=PRESSURE, frame=GROUND_FRAME, zones=(),
                                time_files=files[:1])
    assert round_trip(tmp_path / "functional", functional, write_functional, read_functional).time_files == files[:1]


def test_hand_built_multi_file_index_and_its_data_file(tmp_path):
    """An index built from the layout, and a listed file read as the ordinary aperiodic file it is."""
    index = (geometry_header(n_zones=1, time_kind=MULTI_TIME_APERIODIC) + ints(1)
             + text("  step_file.dat", 4096, b" ") + ints(1, 2))
    read = read_geometry(write_bytes(tmp_path, "index.dat", index))
    assert read.time_files == (TimeFile("step_file.dat", 1, 2),) and read.n_zones == 1
    xyz = np.arange(6, dtype=np.float32).reshape(2, 3)
    step = lambda key: reals(key) + blocks(xyz + key) + blocks(np.ones((2, 3)))  # noqa: E731
    data = geometry_header(time_kind=APERIODIC) + text("z", 32) + ints(2) + ints(2, 1) + step(0.5) + step(0.75)
    zone = read_geometry(write_bytes(tmp_path, "step_file.dat", data)).zones[0]
    assert np.array_equal(zone.keys, np.float32([0.5, 0.75])) and np.array_equal(zone.xyz[1], xyz + 0.75)


# --------------------------------------------------------------------------------------- layout checks
def test_hand_built_unstructured_periodic_geometry_with_iblank(tmp_path):
    """Zone header name, period, key count, node and face counts, faces (count + 1-based ids); per step the
    zone's key, x/y/z blocks, normal blocks and iblank ints; big-endian bytes read the same."""
    xyz = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
    normals = np.array([[0, 0, 0.5], [0, 0, 0.25]], dtype=np.float32)
    def file(order):
        zone = text("plate", 32) + reals(0.2, order=order) + ints(3, 4, 2, 3, 1, 2, 3, 3, 1, 3, 4, order=order)
        steps = b"".join(reals(key, order=order) + blocks(xyz * (k + 1), order) + blocks(normals, order)
                         + ints(1, k, order=order) for k, key in enumerate((0.0, 1.0, 2.0)))
        return geometry_header(grid=2, time_kind=PERIODIC, centring=2, iblank=1, order=order) + zone + steps
    little = read_geometry(write_bytes(tmp_path, "le.dat", file("<")))
    big = read_geometry(write_bytes(tmp_path, "be.dat", file(">")))
    for geometry in (little, big):
        zone = geometry.zones[0]
        assert (geometry.units, geometry.comment, geometry.time_kind, geometry.face_centred) == ("m", "test", 2, True)
        assert (zone.name, zone.structured, zone.n_nodes, zone.period_s) == ("plate", False, 4, np.float32(0.2))
        assert [f.tolist() for f in zone.faces] == [[0, 1, 2], [0, 2, 3]]
        assert np.array_equal(zone.keys, np.float32([0, 1, 2])) and np.array_equal(zone.xyz[2], 3 * xyz)
        assert np.array_equal(zone.normals[1], normals) and zone.iblank.tolist() == [[1, 0], [1, 1], [1, 2]]
    assert (little.byte_order, big.byte_order) == ("<", ">")


def test_hand_built_structured_geometry_runs_i_fastest_and_counts_faces(tmp_path):
    """A 3 x 2 structured zone: node (i, j) is value i + 10 j at index i + 3 j; face-centred normals count
    (iMax-1)(jMax-1) = 2."""
    i, j = np.meshgrid(np.arange(3), np.arange(2), indexing="xy")
    xyz = np.stack([(i + 10 * j).ravel(), np.zeros(6), np.ones(6)], axis=1)
    data = geometry_header(centring=2) + text("wing", 32) + ints(3, 2) + blocks(xyz) + blocks(np.eye(3)[:2])
    zone = read_geometry(write_bytes(tmp_path, "s.dat", data)).zones[0]
    assert zone.xyz[0, :, 0].tolist() == [0, 1, 2, 10, 11, 12] and zone.normals.shape == (1, 2, 3)
    assert (zone.i_max, zone.j_max, zone.n_nodes, face_count(zone), zone.keys.shape) == (3, 2, 6, 2, (0,))


def test_hand_built_flow_file_reads_rho_momentum_pressure_in_order(tmp_path):
    """Flow data: rho block, rho u / rho v / rho w blocks, p' block (loadingData.f90 ReadConstantLoadingAtTime);
    zones read in ascending id whatever the order of the list, -2 meaning zone 2 without thickness noise."""
    rho, mom, p = np.float32([1.2, 1.3]), np.float32([[1, 2, 3], [4, 5, 6]]), np.float32([-7, 8])
    zone_data = blocks(rho[:, None]) + blocks(mom) + blocks(p[:, None])
    data = (functional_header(n_zones=3, grid=2, data_kind=FLOW, frame=4) + ints(2, -2, 1)
            + text("first", 32) + ints(2) + text("second", 32) + ints(2) + zone_data + blocks(
                np.column_stack([rho + 1, mom + 1, p + 1])))
    functional = read_functional(write_bytes(tmp_path, "flow.dat", data))
    first, second = functional.zones
    assert (first.zone, first.thickness, first.name, second.zone, second.thickness) == (1, True, "first", 2, False)
    assert first.values.shape == (1, 2, 5) and np.array_equal(first.values[0], np.column_stack([rho, mom, p]))
    assert np.array_equal(second.values[0], np.column_stack([rho, mom, p]) + 1) and functional.frame == 4


def test_zone_ids_are_one_based_after_the_absolute_value(tmp_path):
    """-2 is zone 2 (pywopwop subtracts 1 before the absolute value and gets zone 1 wrong)."""
    data = (functional_header(n_zones=2, data_kind=PRESSURE) + ints(1, -2) + text("b", 32) + ints(1, 1)
            + reals(101325.0))
    zone = read_functional(write_bytes(tmp_path, "p.dat", data)).zones[0]
    assert (zone.zone, zone.thickness, zone.values.tolist()) == (2, False, [[[101325.0]]])


def test_face_count():
    rng = np.random.default_rng(RNG_SEED)
    assert face_count(structured_geometry_zone(rng, "s", 4, 5, CONSTANT, False, False)) == 12
    assert face_count(structured_geometry_zone(rng, "line", 1, 7, CONSTANT, False, False)) == 6  # segments
    assert face_count(structured_geometry_zone(rng, "line", 7, 1, CONSTANT, False, False)) == 6
    assert face_count(unstructured_geometry_zone(rng, "u", CONSTANT, True, False)) == 4


# --------------------------------------------------------------------------------- tool-style cases
def test_flowunsteady_style_compact_case(tmp_path):
    """FLOWNoise vtk2wopwop (compact=true): structured 1 x n node-centred periodic geometry, node "normals" the
    half segments, strings space-padded; FLOWUnsteady generate_wopwoploading: unstructured face-centred
    periodic loading vectors, n-1 faces, ground frame, zone id -1. The two pair."""
    n, n_steps, period = 5, 4, 0.05
    span = np.linspace(0.1, 0.5, n)
    keys = [period * k / (n_steps - 1) for k in range(n_steps)]
    geometry = (geometry_header(time_kind=PERIODIC, units="N/m^2", comment="Geometry input file", pad=b" ")
                + text("vtkcompactpatch", 32, b" ") + reals(period) + ints(n_steps) + ints(1, n))
    loading = (functional_header(grid=2, time_kind=PERIODIC, centring=2, data_kind=2, frame=1, pad=b" ",
                                 comment="Compact patch loading data file") + ints(1, -1)
               + text("liftinglineloading", 32, b" ") + reals(period) + ints(n_steps) + ints(n - 1))
    for k, key in enumerate(keys):
        angle = 2 * math.pi * k / (n_steps - 1)
        line = np.column_stack([span * math.cos(angle), span * math.sin(angle), np.zeros(n)])
        half = np.diff(line, axis=0) / 2
        node_normals = np.vstack([half, np.zeros((1, 3))]) + np.vstack([np.zeros((1, 3)), half])
        geometry += reals(key) + blocks(line) + blocks(node_normals)
        loading += reals(key) + blocks(np.column_stack([np.zeros(n - 1), np.zeros(n - 1), 10.0 + k + span[1:]]))
    g_path, f_path = write_bytes(tmp_path, "compact.wop", geometry), write_bytes(tmp_path, "loading.wop", loading)
    g, f = read_geometry(g_path), read_functional(f_path)
    check_pair(g, f, g_path, f_path)
    gzone, fzone = g.zones[0], f.zones[0]
    assert (g.units, gzone.name, fzone.name) == ("N/m^2", "vtkcompactpatch", "liftinglineloading")
    assert (gzone.i_max, gzone.j_max, face_count(gzone), fzone.n_data) == (1, n, n - 1, n - 1)
    assert (fzone.zone, fzone.thickness, f.frame, f.face_centred, f.structured) == (1, False, GROUND_FRAME, True, False)
    assert gzone.period_s == fzone.period_s == np.float32(period)
    assert np.array_equal(fzone.values[2, :, 2], np.float32(12.0 + span[1:]))
    assert np.allclose(np.linalg.norm(gzone.normals[0], axis=1).sum(), 0.4, rtol=1e-6)  # the line's length


def test_vsp2wopwop_style_case(tmp_path):
    """VSP2WOPWOP GeomPatchFileWrite: constant structured geometry of 2 zones, a blade surface and a 1 x n
    lifting line, NUL-padded strings; PeriodicLoadingPatchFileWrite: periodic structured node-centred loading
    for zone -2 only, patch frame, keys in radians (0 to 2 pi), period in seconds (60/RPM)."""
    n_chord, n_span, n_keys, rpm = 4, 3, 5, 1200.0
    rng = np.random.default_rng(RNG_SEED)
    surface, surface_normals = rng.normal(size=(n_chord * n_span, 3)), rng.normal(size=(n_chord * n_span, 3))
    line, line_normals = rng.normal(size=(n_span, 3)), np.tile([0.0, 0.0, 1.0], (n_span, 1))
    geometry = (geometry_header(n_zones=2, units="Pa", comment="Blade and lifting line geometry patch file")
                + text("Blade", 32) + ints(n_chord, n_span) + text("Lifting Line", 32) + ints(1, n_span)
                + blocks(surface) + blocks(surface_normals) + blocks(line) + blocks(line_normals))
    keys = np.linspace(0, 2 * np.pi, n_keys)
    loading = (functional_header(n_zones=2, time_kind=PERIODIC, data_kind=2, frame=3,
                                 comment="Periodic loading patch file") + ints(1, -2)
               + text("LiftingLine", 32) + reals((rpm / 60) ** -1) + ints(n_keys) + ints(1, n_span))
    forces = rng.normal(size=(n_keys, n_span, 3))
    for key, force in zip(keys, forces):
        loading += reals(key) + blocks(force)
    g_path, f_path = write_bytes(tmp_path, "Geom.dat", geometry), write_bytes(tmp_path, "Load.dat", loading)
    g, f = read_geometry(g_path), read_functional(f_path)
    check_pair(g, f, g_path, f_path)
    assert [z.name for z in g.zones] == ["Blade", "Lifting Line"] and g.units == "Pa"
    assert np.array_equal(g.zones[0].xyz[0], surface.astype(np.float32))
    zone = f.zones[0]
    assert (zone.zone, zone.thickness, zone.i_max, zone.j_max, f.frame) == (2, False, 1, n_span, PATCH_FRAME)
    assert zone.period_s == np.float32(0.05) and np.array_equal(zone.keys, keys.astype(np.float32))
    assert np.array_equal(zone.values, forces.astype(np.float32))


# ----------------------------------------------------------------------------------------- hostile files
def valid_structured_geometry(n_zones=1, time_kind=CONSTANT, n_keys=2):
    """Zone k: name "zk", [0.1 s, n_keys] | [n_keys], 2 x 2 nodes; per step key (0, 1, ...) and blocks."""
    timing = {CONSTANT: b"", PERIODIC: reals(0.1) + ints(n_keys), APERIODIC: ints(n_keys)}[time_kind]
    header = geometry_header(n_zones=n_zones, time_kind=time_kind)
    header += b"".join(text(f"z{k}", 32) + timing + ints(2, 2) for k in range(1, n_zones + 1))
    steps = 1 if time_kind == CONSTANT else n_keys
    key = lambda s: b"" if time_kind == CONSTANT else reals(float(s))  # noqa: E731
    body = b"".join(key(s) + blocks(np.ones((4, 3))) + blocks(np.ones((4, 3))) for s in range(steps)
                    for _ in range(n_zones))
    return header, body


def patched(data: bytes, offset: int, value: bytes) -> bytes:
    return data[:offset] + value + data[offset + len(value):]


@pytest.mark.parametrize("cut, fragments", [
    (3, ["byte 0: magic number", "4 bytes needed, 3 left"]),
    (600, ["byte 44: comment", "1024 bytes needed, 556 left"]),
    (1139, ["byte 1072: number of zones: expected a count the file can hold (at most 0 zone headers of 40 bytes "
            "or more in the 39 bytes from byte 1100), got 1"]),
    (1200, ["byte 1140: data of 1 step(s) of 96 bytes", "96 bytes needed, 60 left"]),
])
def test_truncated_geometry_names_the_offset_and_the_bytes_needed(tmp_path, cut, fragments):
    header, body = valid_structured_geometry()
    path = write_bytes(tmp_path, "cut.dat", (header + body)[:cut])
    refused(read_geometry, path, *fragments)


def test_wrong_magic_version_and_kind(tmp_path):
    header, body = valid_structured_geometry()
    path = write_bytes(tmp_path, "bad.dat", patched(header + body, 0, ints(43)))
    refused(read_geometry, path, "byte 0: magic number: expected 42 in either byte order, got 43")
    path = write_bytes(tmp_path, "v11.dat", patched(header + body, 8, ints(1)))
    refused(read_geometry, path, "byte 4: format version: expected 1.0", "got 1.1")
    loading = functional_header(data_kind=PRESSURE) + ints(1, 1) + text("z", 32) + ints(1, 1) + reals(1.0)
    path = write_bytes(tmp_path, "loading_as_geometry.dat", loading)
    refused(read_geometry, path, "byte 1068: file kind: expected a geometry (patch) file, got a functional data "
                                 "(loading) file (2 at byte 1036)")
    path = write_bytes(tmp_path, "geometry_as_loading.dat", header + body)
    refused(read_functional, path, "byte 1036: file kind: expected a functional data (loading) file, got a "
                                   "geometry (patch) file (1 at byte 1068)")


@pytest.mark.parametrize("offset, value, fragments", [
    (1068, -1, ["byte 1068: file kind: node-subset geometry (-1) is not supported"]),
    (1072, 0, ["byte 1072: number of zones: expected a count >= 1, got 0"]),
    (1072, 5, ["byte 1072: number of zones: expected a count the file can hold", "got 5"]),
    (1076, 3, ["byte 1076: grid: expected 1 (structured) or 2 (unstructured), got 3"]),
    (1080, 5, ["byte 1080: time kind: quasi-periodic (5) is not supported"]),
    (1080, 6, ["byte 1080: time kind: multi-file quasi-periodic (6) is not supported"]),
    (1080, 9, ["byte 1080: time kind: expected 1 (constant) or 2 (periodic)", "got 9"]),
    (1084, 0, ["byte 1084: centring: expected 1 (node) or 2 (face), got 0"]),
    (1088, 2, ["byte 1088: float size: double precision (2) is not supported"]),
    (1092, 2, ["byte 1092: iblank flag: expected 0 (none) or 1 (iblank values), got 2"]),
    (1132, -3, ["byte 1132: zone 1 'z1' iMax: expected a count >= 1, got -3"]),
    (1136, 0, ["byte 1136: zone 1 'z1' jMax: expected a count >= 1, got 0"]),
])
def test_bad_geometry_header_fields(tmp_path, offset, value, fragments):
    header, body = valid_structured_geometry()
    path = write_bytes(tmp_path, "g.dat", patched(header + body, offset, ints(value)))
    refused(read_geometry, path, *fragments)


def test_face_centred_compact_structured_geometry_is_refused(tmp_path):
    data = geometry_header(centring=2) + text("line", 32) + ints(1, 4) + blocks(np.ones((4, 3)))
    refused(read_geometry, write_bytes(tmp_path, "c.dat", data), "byte 1100: zone 1 'line' centring",
            "WOPWOP reads (iMax-1)(jMax-1) = 0 faces", "got face-centred 1 x 4")


@pytest.mark.parametrize("faces, fragments", [
    (ints(-2), ["byte 1136: zone 1 'u' number of faces: expected a count from 0 to", "got -2"]),
    (ints(1, 3, 1, 2, 5), ["byte 1152: zone 1 'u' face node id: expected a node id from 1 to 4, got 5"]),
    (ints(2, 3, 1, 2, 4, 2, 0, 1), ["byte 1160: zone 1 'u' face node id", "got 0"]),
    (ints(1, 10) + ints(*range(1, 11)), ["byte 1140: zone 1 'u' face 1 node count: expected a count from 1 to 9",
                                         "got 10"]),
    (ints(2, 3, 1, 2, 3, 0), ["byte 1156: zone 1 'u' face 2 node count", "got 0"]),
])
def test_bad_unstructured_geometry_faces(tmp_path, faces, fragments):
    data = (geometry_header(grid=2) + text("u", 32) + ints(4) + faces + blocks(np.zeros((4, 3)))
            + blocks(np.zeros((4, 3))))
    refused(read_geometry, write_bytes(tmp_path, "u.dat", data), *fragments)


def test_truncated_face_list(tmp_path):
    data = geometry_header(grid=2) + text("u", 32) + ints(4, 3, 3, 1, 2, 3, 2, 1)
    refused(read_geometry, write_bytes(tmp_path, "u.dat", data),
            "byte 1160: zone 1 'u' face 2 node ids: the file ends at byte 1164: 8 bytes needed, 4 left")


def test_bad_key_counts_periods_and_keys(tmp_path):
    header, body = valid_structured_geometry(n_zones=2, time_kind=APERIODIC)
    refused(read_geometry, write_bytes(tmp_path, "neg.dat", patched(header + body, 1132, ints(-1))),
            "byte 1132: zone 1 'z1' number of keys: expected a count >= 1, got -1")
    refused(read_geometry, write_bytes(tmp_path, "differ.dat", patched(header + body, 1176, ints(3))),
            "byte 1176: zone 2 'z2' number of keys: expected 2 as zone 1 'z1' (every step holds every zone), got 3")
    header, body = valid_structured_geometry(time_kind=PERIODIC)
    refused(read_geometry, write_bytes(tmp_path, "period.dat", patched(header + body, 1132, reals(0.0))),
            "byte 1132: zone 1 'z1' period: expected a period > 0 s, got 0.0")
    refused(read_geometry, write_bytes(tmp_path, "one.dat", patched(header + body, 1136, ints(1))),
            "byte 1136: zone 1 'z1' number of keys: expected a count >= 2, got 1")
    second_key = len(header) + 100  # step 1: key + 2 blocks of 4 x 3 reals = 100 bytes
    refused(read_geometry, write_bytes(tmp_path, "keys.dat", patched(header + body, second_key, reals(-1.0))),
            f"byte {second_key}: zone 1 'z1' step 2: key: expected a key above 0.0 (keys strictly increase), got -1.0")


def test_nan_inf_and_trailing_bytes(tmp_path):
    header, body = valid_structured_geometry(n_zones=2, time_kind=APERIODIC)
    at = len(header) + 2 * 100 + 100 + 4 + 4 * 5  # step 2, zone 2, position y of node 2
    refused(read_geometry, write_bytes(tmp_path, "nan.dat", patched(header + body, at, reals(float("nan")))),
            f"byte {len(header) + 300 + 4}: zone 2 'z2' step 2: positions: expected finite values, got nan")
    at = len(header) + 4 + 48 + 8  # step 1, zone 1, normal x of node 3
    refused(read_geometry, write_bytes(tmp_path, "inf.dat", patched(header + body, at, reals(float("inf")))),
            f"byte {len(header) + 4 + 48}: zone 1 'z1' step 1: normals: expected finite values, got inf")
    refused(read_geometry, write_bytes(tmp_path, "tail.dat", header + body + b"\0" * 8),
            f"byte {len(header + body)}: end of the last zone: expected the end of the file, got 8 more bytes")


def valid_loading(n_zones=2, listed=(1, -2), time_kind=CONSTANT, data_kind=LOADING_VECTOR, frame=GROUND_FRAME):
    """Loaded zones 1 x 2 structured; constant values 1.0 (densities too)."""
    comps = {PRESSURE: 1, LOADING_VECTOR: 3, FLOW: 5}[data_kind]
    timing = {CONSTANT: b"", PERIODIC: reals(0.1) + ints(2), APERIODIC: ints(2)}[time_kind]
    steps = 1 if time_kind == CONSTANT else 2
    key = lambda s: b"" if time_kind == CONSTANT else reals(float(s))  # noqa: E731
    ids = sorted(abs(z) for z in listed)
    head = (functional_header(n_zones=n_zones, time_kind=time_kind, data_kind=data_kind, frame=frame)
            + ints(len(listed), *listed) + b"".join(text(f"f{z}", 32) + timing + ints(1, 2) for z in ids))
    return head, b"".join(key(s) + blocks(np.ones((2, comps))) for s in range(steps) for _ in ids)


@pytest.mark.parametrize("offset, value, fragments", [
    (1040, 0, ["byte 1040: number of zones: expected a count >= 1, got 0"]),
    (1056, 4, ["byte 1056: data kind: expected 1 (surface pressure) or 2 (loading vector) or 3 (flow parameters)",
               "got 4"]),
    (1060, 5, ["byte 1060: frame: expected 1 (ground)", "got 5"]),
    (1060, 4, ["byte 1060: frame: expected 1 (ground), 2 (rotating) or 3 (patch): 4 is for flow data, got 4"]),
    (1064, 2, ["byte 1064: float size: double precision (2) is not supported"]),
    (1076, 3, ["byte 1076: number of zones with data: expected a count from 1 to 2, got 3"]),
    (1080, 0, ["byte 1080: zone id 1 of the list: expected a signed zone id with 1 <= |id| <= 2, each zone once, "
               "got 0"]),
    (1084, -3, ["byte 1084: zone id 2 of the list", "got -3"]),
    (1084, -1, ["byte 1084: zone id 2 of the list", "each zone once, got -1"]),
    (1120, -1, ["byte 1120: zone 1 'f1' iMax: expected a count >= 1, got -1"]),
])
def test_bad_functional_header_fields(tmp_path, offset, value, fragments):
    head, body = valid_loading()
    refused(read_functional, write_bytes(tmp_path, "l.dat", patched(head + body, offset, ints(value))), *fragments)


def test_bad_functional_data(tmp_path):
    head, body = valid_loading(listed=(2,), time_kind=PERIODIC, data_kind=FLOW, frame=4)
    at = len(head) + 44 + 4 + 4  # step 2 (key + 2 x 5 values = 44 bytes), after its key, density of point 2
    refused(read_functional, write_bytes(tmp_path, "rho.dat", patched(head + body, at, reals(-1.0))),
            f"byte {len(head) + 48}: zone 2 'f2' step 2: density: expected values > 0, got -1.0")
    refused(read_functional, write_bytes(tmp_path, "nan.dat", patched(head + body, at + 8, reals(float("nan")))),
            f"byte {len(head) + 56}: zone 2 'f2' step 2: momentum: expected finite values, got nan")
    refused(read_functional, write_bytes(tmp_path, "short.dat", head + body[:-4]),
            f"byte {len(head)}: data of 2 step(s) of 44 bytes: the file ends at byte {len(head + body) - 4}: 88 bytes "
            f"needed, 84 left")
    head, body = valid_loading(n_zones=1000, listed=(7, 9), time_kind=APERIODIC)
    refused(read_functional, write_bytes(tmp_path, "keys.dat", patched(head + body, 1164, ints(3))),
            "byte 1164: zone 9 'f9' number of keys: expected 2 as zone 7 'f7' (every step holds every zone), got 3")


def test_non_ascii_text_is_refused(tmp_path):
    header, body = valid_structured_geometry()
    refused(read_geometry, write_bytes(tmp_path, "t.dat", patched(header + body, 1100, "zoné".encode("latin-1"))),
            "byte 1100: zone 1 name: expected ASCII text")


def test_writers_refuse_inconsistent_objects_and_leave_no_file(tmp_path):
    rng = np.random.default_rng(RNG_SEED)
    zone = structured_geometry_zone(rng, "blade", 3, 3, PERIODIC, False, False)
    bad_shape = dataclasses.replace(zone, xyz=zone.xyz[:, :4])
    path = tmp_path / "g.dat"
    for geometry, fragment in [
        (GeometryFile("m", "", PERIODIC, False, (bad_shape,)),
         "zone 1 'blade': xyz: expected shape (4, 9, 3), got (4, 4, 3)"),
        (GeometryFile("m", "", APERIODIC, False, (zone,)),
         "zone 1 'blade': period_s: expected None in aperiodic files"),
        (GeometryFile("m" * 33, "", PERIODIC, False, (zone,)), "units: expected at most 32 ASCII characters"),
        (GeometryFile("m", "", PERIODIC, False, (dataclasses.replace(zone, keys=zone.keys[::-1]),)),
         "zone 1 'blade' step 2: key: expected a key above"),
    ]:
        with pytest.raises(WopwopError, match=re.escape(fragment)):
            write_geometry(geometry, path)
    loads = functional_zone(rng, 2, True, False, 9, PRESSURE, CONSTANT)
    unordered = FunctionalFile("", 3, False, CONSTANT, False, PRESSURE, GROUND_FRAME,
                               (loads, dataclasses.replace(loads, zone=1)))
    with pytest.raises(WopwopError, match=re.escape("zones: expected distinct positive zone ids in ascending order")):
        write_functional(unordered, path)
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------------------------------------ pairing
def pair_files(rng, geometry_kind=PERIODIC, loading_kind=PERIODIC, face_centred=False):
    geometry = GeometryFile("m", "", geometry_kind, False,
                            (structured_geometry_zone(rng, "blade", 3, 4, geometry_kind, False, False),
                             structured_geometry_zone(rng, "line", 1, 6, geometry_kind, False, False)))
    n_data = 5 if face_centred else 6
    functional = FunctionalFile("", 2, True, loading_kind, face_centred, LOADING_VECTOR, GROUND_FRAME,
                                (functional_zone(rng, 2, False, True, n_data, LOADING_VECTOR, loading_kind,
                                                 dims=(1, n_data)),))
    return geometry, functional


def test_check_pair_refusals():
    rng = np.random.default_rng(RNG_SEED)
    geometry, functional = pair_files(rng)
    check_pair(geometry, functional, "g.dat", "f.dat")
    check_pair(*pair_files(rng, face_centred=True), "g.dat", "f.dat")  # 5 segments of the 1 x 6 line
    check_pair(*pair_files(rng, CONSTANT, PERIODIC), "g.dat", "f.dat")
    cases = [
        (dataclasses.replace(functional, n_zones=3), "f.dat: header: number of zones: expected 2 as g.dat, got 3"),
        (dataclasses.replace(functional, zones=(dataclasses.replace(functional.zones[0], zone=1),)),
         "f.dat: zone 1 'load2': dimensions: expected 3 x 4 as zone 1 'blade' of g.dat, got 1 x 6"),
        (dataclasses.replace(functional, face_centred=True),
         "f.dat: zone 2 'load2': data points: expected 5 (the faces of zone 2 'line' of g.dat), got 6"),
        (dataclasses.replace(functional, zones=(dataclasses.replace(functional.zones[0], period_s=0.5),)),
         "f.dat: zone 2 'load2': period: expected 0.25 s as zone 2 'line' of g.dat, got 0.5 s"),
        (dataclasses.replace(functional, zones=(dataclasses.replace(functional.zones[0], zone=3),)),
         "f.dat: zone 3 'load2': zone id: expected 1 to 2 (zones of g.dat), got 3"),
    ]
    for bad, message in cases:
        with pytest.raises(WopwopError, match=re.escape(message)):
            check_pair(geometry, bad, "g.dat", "f.dat")
    geometry, functional = pair_files(rng, APERIODIC, APERIODIC)
    check_pair(geometry, functional, "g.dat", "f.dat")
    shifted = dataclasses.replace(functional.zones[0], keys=functional.zones[0].keys + np.float32(0.001))
    with pytest.raises(WopwopError, match=re.escape("f.dat: zone 2 'load2': time keys: expected the 4 keys of zone 2 "
                                                    "'line' of g.dat (a loading file whose time keys do not match")):
        check_pair(geometry, dataclasses.replace(functional, zones=(shifted,)), "g.dat", "f.dat")


def test_a_large_file_reads_fast(tmp_path):
    """About 48 MB of periodic structured geometry: parsed with frombuffer, not value by value."""
    rng = np.random.default_rng(RNG_SEED)
    zone = structured_geometry_zone(rng, "big", 100, 100, PERIODIC, False, False, n_steps=200)
    path = tmp_path / "big.dat"
    write_geometry(GeometryFile("m", "", PERIODIC, False, (zone,)), path)
    assert os.path.getsize(path) > 45e6
    start = time.perf_counter()
    back = read_geometry(path)
    assert time.perf_counter() - start < 3.0
    assert np.array_equal(back.zones[0].xyz, zone.xyz)
