"""PSU-WOPWOP v3 binary input files, format 1.0: geometry ("patch") files and functional data ("loading") files.

Layout, as PSU-WOPWOP itself reads it (container.f90 DeterminePatchFileFormat, ReadFileHeaderV1_0 and
CreatePatchesFromFile; patch.f90 CreatePatch; surface.f90 ReadSurfaceDimensions, ReadDimensions,
ReadConnectivity, ReadSurfaceData; loadingData.f90 ReadLoadingDimensions, ReadDimensions and
Read{Constant,Periodic,Aperiodic}LoadingAtTime; the IO module's ReadBinaryString reads as many bytes as the
Fortran variable holds):

- An unformatted stream of 4-byte ints and 4-byte reals in the writer's byte order: the int 42 at byte 0 tells
  it (read as 704643072 it is byte-swapped: the file is big-endian).
- Geometry: 42, 1, 0 (format version), units (32 bytes), comment (1024), then 8 ints from byte 1068: file kind
  1, zone count, grid (1 structured, 2 unstructured), time kind, centring of the normals (1 node, 2 face),
  float size (1 single), iblank flag (0/1), reserved.
- Functional: 42, 1, 0, comment (1024; no units), then 10 ints from byte 1036: file kind 2, zone count (of the
  geometry file), grid, time kind, centring, data kind, frame, float size, reserved, reserved; then the number
  of zones carrying data and their signed 1-based ids (a negative id: no thickness noise for that zone).
- All zone headers come before any data, in ascending zone order: CreatePatchesFromFile calls CreatePatch for
  zone 1, 2, ... and reads a functional zone header only for a zone the list names, whatever the order of the
  list. Header: name (32), then [period real, key count] (periodic) or [key count] (aperiodic) or nothing
  (constant), then iMax, jMax (structured) or, geometry, the node count, the face count and per face its node
  count and 1-based node ids; a functional unstructured header gives only its data-point count.
- Data: for each step, for each zone, the zone's own key (a real; none in constant files), then its blocks,
  each an x block then a y block then a z block over the data points (Fortran (n, 3) arrays). Geometry: node
  positions, normals at the data points, iblank ints at the data points when flagged. Functional: pressure p;
  loading vector f; flow rho, (rho u, rho v, rho w), p'. Structured nodes run i fastest.
- Data points: geometry nodes iMax jMax (or the node count); geometry faces (iMax-1)(jMax-1) (structured) or
  the face count; functional: iMax jMax or the count given (surface.f90 and loadingData.f90 ReadDimensions).
- Multi-file aperiodic (time kind 4) files are indexes: after the header (and nothing else) come a file count
  and, per file, its name (4096 bytes), first and last step (1-based); each listed file is an ordinary
  aperiodic file that WOPWOP reads from its first zone header on with the index's header flags
  (ReadFileHeaderV1_0, case GEO_TIMETYPE_MTFAPERIODIC / LOAD_TIMETYPE_MTFAPERIODIC). :func:`read_geometry` and
  :func:`read_functional` read an index into ``time_files`` (no zones) and the listed files as aperiodic
  files; joining their steps is left to the caller.

Refused, each in one line naming the file and the byte offset (:class:`~nps.wopwop.errors.WopwopError`): a
wrong magic number, a format version other than 1.0 (functional files: 1.0 or 1.1, whose zone headers carry
``loadingOutput`` after the name: 1 adds the zone's loading noise to the thickness output, patch.f90 CreatePatch),
a file of the other kind, node-subset geometry (kind -1), quasi-periodic time
kinds (5, 6), double precision (WOPWOP reads 4-byte reals only), unknown flags, counts below their minimum or
beyond what the file holds, face node ids out of range, more than 9 nodes on a face (ReadConnectivity), a
face-centred compact structured geometry zone (no faces), key counts that differ between zones (the steps
interleave the zones), periods <= 0, keys not strictly increasing (WOPWOP refuses them in loading files and
aperiodic geometry; in periodic geometry they would make its key-to-time map fold), NaN or inf anywhere,
flow densities <= 0 (Read*LoadingAtTime stops on them) and bytes after the last zone.

Strings are ASCII: read up to the first NUL, trailing spaces stripped; written NUL-padded (file names in
indexes space-padded: Fortran's trim removes blanks, not NULs). Values stay float32 / int32 as in the file.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from nps.wopwop.errors import WopwopError

CONSTANT, PERIODIC, APERIODIC, MULTI_TIME_APERIODIC = 1, 2, 3, 4  # time kinds
PRESSURE, LOADING_VECTOR, FLOW = 1, 2, 3  # functional data kinds
GROUND_FRAME, ROTATING_FRAME, PATCH_FRAME = 1, 2, 3  # loading-vector frames
BLADE_SCALED_V_FRAME = 4  # flow data only: momentum scaled by the local speed (patch.f90 LOAD_REFFRAME_BLADE_SCALEV)

GEOMETRY_FILE, FUNCTIONAL_FILE = 1, 2  # file kinds (header int "check")
MAGIC = 42
UNITS_BYTES, COMMENT_BYTES, NAME_BYTES, FILE_NAME_BYTES = 32, 1024, 32, 4096
GEOMETRY_FLAGS_AT, FUNCTIONAL_FLAGS_AT = 1068, 1036  # byte offsets of the header ints
MAX_NODES_PER_FACE = 9  # surface.f90 ReadConnectivity refuses 10 or more
COMPONENTS = {PRESSURE: 1, LOADING_VECTOR: 3, FLOW: 5}  # values per data point: p | f | rho, rho u, rho v, rho w, p'
PAIR_RTOL = 1e-6  # relative tolerance of check_pair on periods and aperiodic keys (float32 has 6e-8)

_TIME_KINDS = {CONSTANT: "constant", PERIODIC: "periodic", APERIODIC: "aperiodic",
               MULTI_TIME_APERIODIC: "multi-file aperiodic"}
_UNSUPPORTED_TIME = {5: "quasi-periodic (5) is not supported", 6: "multi-file quasi-periodic (6) is not supported"}


@dataclass(frozen=True)
class TimeFile:
    """One file listed by a multi-file aperiodic index: its name as written (WOPWOP opens it as
    globalFolderName // name unless it starts with '/' or '~/') and the steps used, 1-based, both included."""

    name: str
    first_step: int
    last_step: int


@dataclass(frozen=True)
class GeometryZone:
    """One zone (patch) of a geometry file. Positions and normals in the file's units and frame; ``normals`` at
    the nodes (node-centred) or the faces; their length is an area (or, compact, a length) or they are unit
    vectors (surface.f90 CalculateSurfaceAreas decides). ``iblank`` has one int per normal (ReadSurfaceData
    reads nbData of them), None when the file has no iblank."""

    name: str
    structured: bool
    i_max: int  # structured dims (0 for unstructured)
    j_max: int
    faces: tuple[np.ndarray, ...]  # unstructured: 0-based node ids (int32) of each face; () for structured
    n_nodes: int  # i_max*j_max, or the unstructured node count
    period_s: float | None  # periodic zones: the period from the header (float32 value, as float)
    keys: np.ndarray  # (n_steps,) float32: keys/times of the steps; constant zones: shape (0,)
    xyz: np.ndarray  # (n_steps, n_nodes, 3) float32, n_steps = 1 for constant; structured: i fastest
    normals: np.ndarray  # (n_steps, n_normals, 3) float32: n_normals = n_nodes (node-centred) or faces
    iblank: np.ndarray | None  # (n_steps, n_normals) int32 or None


@dataclass(frozen=True)
class GeometryFile:
    """A geometry file. ``structured``, ``iblank`` and ``n_zones`` are header fields: the reader sets them; a
    writer takes them from the zones when None (an index, which has no zones, needs them). ``time_files``: the
    files a multi-file aperiodic index lists (``zones`` is then empty)."""

    units: str
    comment: str
    time_kind: int
    face_centred: bool
    zones: tuple[GeometryZone, ...]
    byte_order: str = "<"  # "<" little-endian, ">" big-endian: as read, or as to be written
    structured: bool | None = None
    iblank: bool | None = None
    n_zones: int | None = None
    time_files: tuple[TimeFile, ...] = ()


@dataclass(frozen=True)
class FunctionalZone:
    """The data of one zone: ``values`` per data point, in the order p | fx, fy, fz | rho, rho u, rho v, rho w,
    p'. Loading vectors are the force on the surface per unit area (per unit span on a compact zone), in the
    file's frame; pressure is gauge pressure (loadingData.f90; WOPWOP negates f to get the force on the
    fluid)."""

    zone: int  # 1-based id of the geometry zone it belongs to (always positive here)
    thickness: bool  # False when the file lists -zone (no thickness noise for that zone)
    name: str
    structured: bool
    i_max: int
    j_max: int
    n_data: int  # data points per step
    period_s: float | None
    keys: np.ndarray  # (n_steps,) float32; constant: shape (0,)
    values: np.ndarray  # (n_steps, n_data, n_comp) float32; n_comp 1, 3 or 5 by data kind
    loading_output: int = 2  # format 1.1: 1 adds the zone's loading noise to the thickness output, 2 normal


@dataclass(frozen=True)
class FunctionalFile:
    """A functional data file; ``zones`` in ascending zone id (the order WOPWOP reads them in), ``time_files``
    for a multi-file aperiodic index (no zones: the zone list is in the listed files)."""

    comment: str
    n_zones: int  # zone count of the geometry file it goes with (header field)
    structured: bool
    time_kind: int
    face_centred: bool
    data_kind: int
    frame: int
    zones: tuple[FunctionalZone, ...]  # the zones carrying data, in file order
    byte_order: str = "<"
    time_files: tuple[TimeFile, ...] = ()
    minor_version: int = 0  # format 1.0, or 1.1 (each zone header carries loadingOutput after its name)


@dataclass(frozen=True)
class _ZoneHeader:
    """A zone header as read: ``label`` names it in messages; ``n_data`` data points per step."""

    label: str
    name: str
    structured: bool
    i_max: int
    j_max: int
    n_nodes: int
    faces: tuple[np.ndarray, ...]
    n_data: int
    period_s: float | None
    n_keys: int
    keys_at: int  # byte offset of the key count (for messages)
    loading_output: int = 2  # format 1.1 functional zones


class _Cursor:
    """Reads one file's bytes in order; every read checks that the bytes are there and names its offset."""

    def __init__(self, data: bytes, path, order: str):
        self.data, self.path, self.order, self.pos, self.minor = data, path, order, 0, 0

    def error(self, offset: int, what: str, expected: str, got) -> WopwopError:
        return WopwopError(f"{self.path}: byte {offset}: {what}: expected {expected}, got {got}")

    def take(self, n_bytes: int, what: str) -> int:
        """Offset of the next ``n_bytes`` bytes, which are skipped over."""
        start, size = self.pos, len(self.data)
        if start + n_bytes > size:
            raise WopwopError(f"{self.path}: byte {start}: {what}: the file ends at byte {size}: {n_bytes} bytes "
                              f"needed, {size - start} left")
        self.pos += n_bytes
        return start

    def array(self, count: int, kind: str, what: str) -> np.ndarray:
        at = self.take(4 * count, what)
        return np.frombuffer(self.data, dtype=self.order + kind, count=count, offset=at)

    def int(self, what: str) -> int:
        return int(self.array(1, "i4", what)[0])

    def real(self, what: str) -> np.float32:
        return np.float32(self.array(1, "f4", what)[0])

    def count(self, what: str, minimum: int, maximum: int | None = None) -> int:
        value = self.int(what)
        if value < minimum or (maximum is not None and value > maximum):
            expected = f"a count >= {minimum}" if maximum is None else f"a count from {minimum} to {maximum}"
            raise self.error(self.pos - 4, what, expected, value)
        return value

    def choice(self, what: str, allowed: dict[int, str], refusals: dict[int, str] | None = None) -> int:
        value = self.int(what)
        if refusals and value in refusals:
            raise WopwopError(f"{self.path}: byte {self.pos - 4}: {what}: {refusals[value]}")
        if value not in allowed:
            raise self.error(self.pos - 4, what, " or ".join(f"{k} ({v})" for k, v in allowed.items()), value)
        return value

    def text(self, n_bytes: int, what: str) -> str:
        at = self.take(n_bytes, what)
        raw = self.data[at:at + n_bytes].split(b"\0", 1)[0]
        try:
            return raw.decode("ascii").rstrip(" ")
        except UnicodeDecodeError:
            raise self.error(at, what, "ASCII text", repr(raw[:40])) from None

    def end(self) -> None:
        if self.pos != len(self.data):
            raise WopwopError(f"{self.path}: byte {self.pos}: end of the last zone: expected the end of the file, got "
                              f"{len(self.data) - self.pos} more bytes (a count in the file is wrong)")


# ---------------------------------------------------------------------------------------------- headers
def _open(data: bytes, path, minors: tuple[int, ...] = (0,)) -> _Cursor:
    """Cursor past the magic number (which sets the byte order) and the format version, which must be 1.0 (or 1.1
    where ``minors`` allows it: functional files); the minor version is kept as ``cur.minor``."""
    if len(data) < 4:
        _Cursor(data, path, "<").take(4, "magic number")
    little = int(np.frombuffer(data, dtype="<i4", count=1)[0])
    if little == MAGIC:
        order = "<"
    elif int(np.frombuffer(data, dtype=">i4", count=1)[0]) == MAGIC:
        order = ">"
    else:
        raise WopwopError(f"{path}: byte 0: magic number: expected 42 in either byte order, got {little} "
                          f"(little-endian reading)")
    cur = _Cursor(data, path, order)
    cur.pos = 4
    major, minor = cur.int("format version"), cur.int("format version")
    if major != 1 or minor not in minors:
        expected = " or ".join(f"1.{m}" for m in minors)
        raise cur.error(4, "format version", f"{expected} (PSU-WOPWOP v3 format {expected})", f"{major}.{minor}")
    cur.minor = minor
    return cur


def _kind_at(data: bytes, order: str, offset: int) -> int | None:
    """The file-kind int at ``offset`` (1068 in geometry files, 1036 in functional files), None if cut short."""
    if len(data) < offset + 4:
        return None
    return int(np.frombuffer(data, dtype=order + "i4", count=1, offset=offset)[0])


def _check_kind(cur: _Cursor, expected: int) -> None:
    """The file kind: a functional file given as geometry (or the other way round) is named as such."""
    at = cur.pos
    kind = cur.int("file kind")
    if kind == expected:
        return
    if expected == GEOMETRY_FILE and kind == -1:
        raise WopwopError(f"{cur.path}: byte {at}: file kind: node-subset geometry (-1) is not supported")
    other_at = FUNCTIONAL_FLAGS_AT if expected == GEOMETRY_FILE else GEOMETRY_FLAGS_AT
    other = FUNCTIONAL_FILE if expected == GEOMETRY_FILE else GEOMETRY_FILE
    names = {GEOMETRY_FILE: "a geometry (patch) file", FUNCTIONAL_FILE: "a functional data (loading) file"}
    found = _kind_at(cur.data, cur.order, other_at)
    if found in (other, -other):
        raise WopwopError(f"{cur.path}: byte {at}: file kind: expected {names[expected]}, got {names[other]} "
                          f"({found} at byte {other_at})")
    raise cur.error(at, "file kind", f"{expected} ({names[expected]})", kind)


def _common_flags(cur: _Cursor) -> tuple[int, bool, int, bool]:
    """Zone count, structured, time kind, face-centred: the four header ints after the file kind."""
    n_zones = cur.count("number of zones", 1)
    structured = cur.choice("grid", {1: "structured", 2: "unstructured"}) == 1
    time_kind = cur.choice("time kind", _TIME_KINDS, _UNSUPPORTED_TIME)
    face_centred = cur.choice("centring", {1: "node", 2: "face"}) == 2
    return n_zones, structured, time_kind, face_centred


def _precision(cur: _Cursor) -> None:
    cur.choice("float size", {1: "single precision"},
               {2: "double precision (2) is not supported: PSU-WOPWOP reads 4-byte reals only"})


def _read_time_files(cur: _Cursor) -> tuple[TimeFile, ...]:
    """The list of a multi-file aperiodic index (container.f90 ReadFileHeaderV1_0), which ends the file."""
    entry_bytes = FILE_NAME_BYTES + 8
    n_files = cur.count("number of time files", 1, max(1, (len(cur.data) - cur.pos - 4) // entry_bytes))
    files = []
    for index in range(1, n_files + 1):
        name = cur.text(FILE_NAME_BYTES, f"time file {index} name").strip(" ")
        if not name:
            raise cur.error(cur.pos - FILE_NAME_BYTES, f"time file {index} name", "a file name", "blanks")
        first = cur.count(f"time file {index} first step", 1)
        last = cur.count(f"time file {index} last step", first)
        files.append(TimeFile(name, first, last))
    cur.end()
    return tuple(files)


# ----------------------------------------------------------------------------------------- zone headers
def _zone_timing(cur: _Cursor, time_kind: int, label: str) -> tuple[float | None, int, int]:
    """Period (s, periodic only), key count and the offset of the key count (ReadSurfaceDimensions,
    ReadLoadingDimensions). Periodic: the period > 0 and at least 2 keys (dt = period/(nKey-1))."""
    if time_kind == CONSTANT:
        return None, 1, cur.pos
    period = None
    if time_kind == PERIODIC:
        at = cur.pos
        period = cur.real(f"{label} period")
        if not (np.isfinite(period) and period > 0):
            raise cur.error(at, f"{label} period", "a period > 0 s", float(period))
        period = float(period)
    keys_at = cur.pos
    n_keys = cur.count(f"{label} number of keys", 2 if time_kind == PERIODIC else 1)
    return period, n_keys, keys_at


def _structured_dims(cur: _Cursor, label: str) -> tuple[int, int]:
    return cur.count(f"{label} iMax", 1), cur.count(f"{label} jMax", 1)


def _face_starts(cur: _Cursor, ints: np.ndarray, n_faces: int, label: str) -> np.ndarray:
    """Index in ``ints`` (the file from the first face on) of each face's node count, 1 to 9 (ReadConnectivity).
    Faces all with the node count of the first are found at once; mixed faces by one scan."""
    start, first = cur.pos, int(ints[0]) if len(ints) else 0
    if 1 <= first <= MAX_NODES_PER_FACE and (first + 1) * n_faces <= len(ints):
        starts = np.arange(n_faces) * (first + 1)
        if np.all(ints[starts] == first):
            return starts
    window = ints[:n_faces * (MAX_NODES_PER_FACE + 1)].tolist()
    starts, at = np.empty(n_faces, dtype=np.int64), 0
    for face in range(n_faces):
        what = f"{label} face {face + 1} node count"
        if at >= len(window):
            cur.pos = start + 4 * at
            cur.take(4, what)
        count = window[at]
        if not 1 <= count <= MAX_NODES_PER_FACE:
            raise cur.error(start + 4 * at, what, f"a count from 1 to {MAX_NODES_PER_FACE}", count)
        if at + 1 + count > len(window):  # the window holds 10 ints a face: only the file's end stops it short
            cur.pos = start + 4 * (at + 1)
            cur.take(4 * count, f"{label} face {face + 1} node ids")
        starts[face] = at
        at += count + 1
    return starts


def _read_faces(cur: _Cursor, n_faces: int, n_nodes: int, label: str) -> tuple[np.ndarray, ...]:
    """Faces of an unstructured zone: per face its node count and 1-based node ids (1 to n_nodes), returned as
    0-based int32 arrays."""
    if n_faces == 0:
        return ()
    start = cur.pos
    ints = np.frombuffer(cur.data, dtype=cur.order + "i4", count=(len(cur.data) - start) // 4, offset=start)
    starts = _face_starts(cur, ints, n_faces, label)
    counts = ints[starts]
    end = int(starts[-1] + counts[-1] + 1)
    cur.pos = start
    cur.take(4 * end, f"{label} faces")
    is_id = np.ones(end, dtype=bool)
    is_id[starts] = False
    ids = ints[:end][is_id]
    bad = (ids < 1) | (ids > n_nodes)
    if bad.any():
        first_bad = int(np.argmax(bad))
        raise cur.error(start + 4 * int(np.flatnonzero(is_id)[first_bad]), f"{label} face node id",
                        f"a node id from 1 to {n_nodes}", int(ids[first_bad]))
    zero_based = (ids - 1).astype(np.int32)
    if np.all(counts == counts[0]):
        return tuple(zero_based.reshape(n_faces, int(counts[0])))
    return tuple(np.split(zero_based, np.cumsum(counts)[:-1]))


def _geometry_zone(cur: _Cursor, zone: int, time_kind: int, structured: bool, face_centred: bool) -> _ZoneHeader:
    """One geometry zone header (surface.f90 ReadSurfaceDimensions, ReadDimensions, ReadConnectivity)."""
    at = cur.pos
    name = cur.text(NAME_BYTES, f"zone {zone} name")
    label = f"zone {zone} '{name}'"
    period, n_keys, keys_at = _zone_timing(cur, time_kind, label)
    if structured:
        i_max, j_max = _structured_dims(cur, label)
        n_nodes, faces = i_max * j_max, ()
        if face_centred and min(i_max, j_max) == 1:
            raise cur.error(at, f"{label} centring", "node-centred data on a compact (iMax or jMax = 1) zone: "
                            "WOPWOP reads (iMax-1)(jMax-1) = 0 faces", f"face-centred {i_max} x {j_max}")
        n_faces = (i_max - 1) * (j_max - 1)
    else:
        i_max = j_max = 0
        n_nodes = cur.count(f"{label} number of nodes", 1)
        n_faces = cur.count(f"{label} number of faces", 1 if face_centred else 0, (len(cur.data) - cur.pos) // 8)
        faces = _read_faces(cur, n_faces, n_nodes, label)
    n_data = n_faces if face_centred else n_nodes
    return _ZoneHeader(label, name, structured, i_max, j_max, n_nodes, faces, n_data, period, n_keys, keys_at)


def _functional_zone(cur: _Cursor, zone: int, time_kind: int, structured: bool) -> _ZoneHeader:
    """One functional zone header (loadingData.f90 ReadLoadingDimensions, ReadDimensions)."""
    name = cur.text(NAME_BYTES, f"zone {zone} name")
    label = f"zone {zone} '{name}'"
    output = cur.choice(f"{label} loadingOutput", {1: "added to thickness", 2: "loading"}) if cur.minor == 1 else 2
    period, n_keys, keys_at = _zone_timing(cur, time_kind, label)
    if structured:
        i_max, j_max = _structured_dims(cur, label)
        n_data = i_max * j_max
    else:
        i_max = j_max = 0
        n_data = cur.count(f"{label} number of data points", 1)
    return _ZoneHeader(label, name, structured, i_max, j_max, n_data, (), n_data, period, n_keys, keys_at, output)


def _zone_headers(cur: _Cursor, zones: list[int], read_one, count_at: int, count_what: str) -> list[_ZoneHeader]:
    """Headers of the zones (ids in file order), after checking that the file can hold that many (a header
    takes at least 40 bytes) against the count read at ``count_at``. Key counts must agree: each step holds
    every zone (the step loop of CreatePatchesFromFile stops at the last zone's count)."""
    left = len(cur.data) - cur.pos
    if len(zones) > left // (NAME_BYTES + 8):
        raise cur.error(count_at, count_what, f"a count the file can hold (at most {left // (NAME_BYTES + 8)} zone "
                        f"headers of 40 bytes or more in the {left} bytes from byte {cur.pos})", len(zones))
    headers = [read_one(zone) for zone in zones]
    for header in headers[1:]:
        if header.n_keys != headers[0].n_keys:
            raise cur.error(header.keys_at, f"{header.label} number of keys",
                            f"{headers[0].n_keys} as {headers[0].label} (every step holds every zone)",
                            header.n_keys)
    return headers


def _zone_list(cur: _Cursor, n_zones: int) -> dict[int, bool]:
    """The zones carrying data: zone id -> thickness noise wanted (a negative id: not; container.f90
    ReadFileHeaderV1_0 takes abs(id) as the 1-based zone, nothing subtracted)."""
    count = cur.count("number of zones with data", 1, n_zones)
    listed: dict[int, bool] = {}
    for index in range(1, count + 1):
        at = cur.pos
        zone = cur.int(f"zone id {index} of the list")
        if zone == 0 or abs(zone) > n_zones or abs(zone) in listed:
            raise cur.error(at, f"zone id {index} of the list",
                            f"a signed zone id with 1 <= |id| <= {n_zones}, each zone once", zone)
        listed[abs(zone)] = zone > 0
    return listed


# ------------------------------------------------------------------------------------------------- data
_GEOMETRY_BLOCKS = [("positions", "f4", 3, "n_nodes"), ("normals", "f4", 3, "n_data")]
_IBLANK_BLOCK = ("iblank", "i4", 1, "n_data")
_FUNCTIONAL_BLOCKS = {PRESSURE: [("pressure", "f4", 1, "n_data")],
                      LOADING_VECTOR: [("loading vectors", "f4", 3, "n_data")],
                      FLOW: [("density", "f4", 1, "n_data"), ("momentum", "f4", 3, "n_data"),
                             ("pressure", "f4", 1, "n_data")]}


def _step_dtype(order: str, headers: list[_ZoneHeader], blocks: list[tuple[str, str, int, str]], keyed: bool):
    """One step as a record: for each zone its key (``keyed``) then its blocks, each given as (name, "f4" | "i4",
    rows, "n_nodes" | "n_data"): rows x count values, the x row first (Fortran (count, rows) arrays)."""
    fields = []
    for z, header in enumerate(headers):
        if keyed:
            fields.append((f"key{z}", order + "f4"))
        fields += [(f"{name}{z}", order + kind, (rows, getattr(header, count))) for name, kind, rows, count in blocks]
    return np.dtype(fields)


def _read_steps(cur: _Cursor, step: np.dtype, n_steps: int) -> tuple[np.ndarray, int]:
    """The records of all steps, which must end the file, and the offset of the first."""
    at = cur.take(step.itemsize * n_steps, f"data of {n_steps} step(s) of {step.itemsize} bytes")
    cur.end()
    return np.frombuffer(cur.data, dtype=step, count=n_steps, offset=at), at


def _step_error(path, records: np.ndarray, at: int, field: str, step: int, label: str, what: str) -> str:
    """Start of a message on one step of one zone: file, byte offset of the field in that step, zone, step."""
    offset = at + step * records.dtype.itemsize + records.dtype.fields[field][1]
    return f"{path}: byte {offset}: {label} step {step + 1}: {what}"


def _block(records: np.ndarray, at: int, name: str, z: int, label: str, path) -> np.ndarray:
    """One block of one zone over all steps, (n_steps, count, rows) in native byte order; NaN or inf refused."""
    raw = records[f"{name}{z}"]
    if raw.dtype.kind == "f":
        finite = np.isfinite(raw.reshape(len(raw), -1)).all(axis=1)
        if not finite.all():
            step = int(np.argmin(finite))
            got = "nan" if np.isnan(raw[step]).any() else "inf"
            raise WopwopError(_step_error(path, records, at, f"{name}{z}", step, label, name)
                              + f": expected finite values, got {got}")
    native = raw.astype(raw.dtype.newbyteorder("="))
    return np.ascontiguousarray(np.swapaxes(native, 1, 2))


def _keys(records: np.ndarray, at: int, z: int, label: str, path, keyed: bool) -> np.ndarray:
    """The zone's keys, finite and strictly increasing (WOPWOP refuses others in loading files and aperiodic
    geometry: loadingData.f90 ReadPeriodicLoadingAtTime, surface.f90 ReadAperiodicSurfaceAtTime)."""
    if not keyed:
        return np.zeros(0, dtype=np.float32)
    keys = records[f"key{z}"].astype(np.float32)
    bad = ~np.isfinite(keys)
    bad[1:] |= ~(keys[1:] > keys[:-1])
    if bad.any():
        step = int(np.argmax(bad))
        expected = "a finite key" if step == 0 or not np.isfinite(keys[step - 1]) else \
            f"a key above {float(keys[step - 1])!r} (keys strictly increase)"
        raise WopwopError(_step_error(path, records, at, f"key{z}", step, label, "key")
                          + f": expected {expected}, got {float(keys[step])!r}")
    return keys


def _blocks(records: np.ndarray, at: int, blocks, z: int, label: str, path) -> np.ndarray:
    """The blocks of one zone side by side: (n_steps, count, total rows)."""
    return np.concatenate([_block(records, at, name, z, label, path) for name, *_ in blocks], axis=2)


# --------------------------------------------------------------------------------------------- geometry
def _decode_geometry(data: bytes, path) -> GeometryFile:
    cur = _open(data, path)
    units = cur.text(UNITS_BYTES, "units")
    comment = cur.text(COMMENT_BYTES, "comment")
    _check_kind(cur, GEOMETRY_FILE)
    n_zones, structured, time_kind, face_centred = _common_flags(cur)
    _precision(cur)
    iblank = cur.choice("iblank flag", {0: "none", 1: "iblank values"}) == 1
    cur.int("reserved")
    base = dict(units=units, comment=comment, time_kind=time_kind, face_centred=face_centred, byte_order=cur.order,
                structured=structured, iblank=iblank, n_zones=n_zones)
    if time_kind == MULTI_TIME_APERIODIC:
        return GeometryFile(zones=(), time_files=_read_time_files(cur), **base)
    headers = _zone_headers(cur, list(range(1, n_zones + 1)),
                            lambda z: _geometry_zone(cur, z, time_kind, structured, face_centred),
                            GEOMETRY_FLAGS_AT + 4, "number of zones")
    keyed = time_kind != CONSTANT
    blocks = _GEOMETRY_BLOCKS + ([_IBLANK_BLOCK] if iblank else [])
    records, at = _read_steps(cur, _step_dtype(cur.order, headers, blocks, keyed), headers[0].n_keys)
    zones = []
    for z, h in enumerate(headers):
        xyz = _block(records, at, "positions", z, h.label, path)
        normals = _block(records, at, "normals", z, h.label, path)
        flags = _block(records, at, "iblank", z, h.label, path)[:, :, 0] if iblank else None
        zones.append(GeometryZone(h.name, h.structured, h.i_max, h.j_max, h.faces, h.n_nodes, h.period_s,
                                  _keys(records, at, z, h.label, path, keyed), xyz, normals, flags))
    return GeometryFile(zones=tuple(zones), **base)


def _read_bytes(path) -> bytes:
    try:
        with open(path, "rb") as file:
            return file.read()
    except OSError as error:
        raise WopwopError(f"{path}: cannot be read: {error.strerror}") from None


def read_geometry(path) -> GeometryFile:
    """Read a geometry (patch) file, either byte order; ``byte_order`` records the one found."""
    return _decode_geometry(_read_bytes(path), path)


# ------------------------------------------------------------------------------------------- functional
def _decode_functional(data: bytes, path) -> FunctionalFile:
    cur = _open(data, path, minors=(0, 1))
    comment = cur.text(COMMENT_BYTES, "comment")
    _check_kind(cur, FUNCTIONAL_FILE)
    n_zones, structured, time_kind, face_centred = _common_flags(cur)
    data_kind = cur.choice("data kind", {PRESSURE: "surface pressure", LOADING_VECTOR: "loading vector",
                                         FLOW: "flow parameters"})
    frame = cur.choice("frame", {GROUND_FRAME: "ground", ROTATING_FRAME: "rotating", PATCH_FRAME: "patch",
                                 BLADE_SCALED_V_FRAME: "blade, scaled velocity; flow data"})
    if frame == BLADE_SCALED_V_FRAME and data_kind != FLOW:
        raise cur.error(cur.pos - 4, "frame", "1 (ground), 2 (rotating) or 3 (patch): 4 is for flow data", frame)
    _precision(cur)
    cur.int("reserved")
    cur.int("reserved")
    base = dict(comment=comment, n_zones=n_zones, structured=structured, time_kind=time_kind,
                face_centred=face_centred, data_kind=data_kind, frame=frame, byte_order=cur.order,
                minor_version=cur.minor)
    if time_kind == MULTI_TIME_APERIODIC:
        return FunctionalFile(zones=(), time_files=_read_time_files(cur), **base)
    list_at = cur.pos
    listed = _zone_list(cur, n_zones)
    ids = sorted(listed)
    headers = _zone_headers(cur, ids, lambda z: _functional_zone(cur, z, time_kind, structured), list_at,
                            "number of zones with data")
    keyed = time_kind != CONSTANT
    blocks = _FUNCTIONAL_BLOCKS[data_kind]
    records, at = _read_steps(cur, _step_dtype(cur.order, headers, blocks, keyed), headers[0].n_keys)
    zones = []
    for z, (zone, h) in enumerate(zip(ids, headers)):
        values = _blocks(records, at, blocks, z, h.label, path)
        if data_kind == FLOW:
            _check_density(records, at, z, h.label, path, values[:, :, 0])
        zones.append(FunctionalZone(zone, listed[zone], h.name, h.structured, h.i_max, h.j_max, h.n_data,
                                    h.period_s, _keys(records, at, z, h.label, path, keyed), values, h.loading_output))
    return FunctionalFile(zones=tuple(zones), **base)


def _check_density(records: np.ndarray, at: int, z: int, label: str, path, density: np.ndarray) -> None:
    """Flow densities > 0 (loadingData.f90 Read*LoadingAtTime: "densVals must be greater than zero")."""
    positive = (density > 0).all(axis=1)
    if not positive.all():
        step = int(np.argmin(positive))
        raise WopwopError(_step_error(path, records, at, f"density{z}", step, label, "density")
                          + f": expected values > 0, got {float(density[step].min())!r}")


def read_functional(path) -> FunctionalFile:
    """Read a functional data (loading) file, either byte order; ``byte_order`` records the one found."""
    return _decode_functional(_read_bytes(path), path)


# ---------------------------------------------------------------------------------------------- writers
def _ints(order: str, *values: int) -> bytes:
    return np.array(values, dtype=order + "i4").tobytes()


def _text(value: str, n_bytes: int, path, what: str, pad: bytes = b"\0") -> bytes:
    """A fixed-length ASCII field, padded with ``pad``; too long, non-ASCII or NUL-bearing text refused."""
    raw = value.encode("ascii", errors="replace")
    if raw.decode("ascii") != value or b"\0" in raw or len(raw) > n_bytes:
        raise WopwopError(f"{path}: {what}: expected at most {n_bytes} ASCII characters and no NUL, got "
                          f"{value[:40]!r} ({len(value)} characters)")
    return raw.ljust(n_bytes, pad)


def _check_header(path, time_kind: int, zones: tuple, time_files: tuple, data_kind: int | None = None) -> None:
    """Header values a writer can check before encoding: known kinds, and zones xor an index's file list."""
    if time_kind not in _TIME_KINDS:
        raise WopwopError(f"{path}: time_kind: expected one of {sorted(_TIME_KINDS)}, got {time_kind!r}")
    if data_kind is not None and data_kind not in COMPONENTS:
        raise WopwopError(f"{path}: data_kind: expected one of {sorted(COMPONENTS)}, got {data_kind!r}")
    index = time_kind == MULTI_TIME_APERIODIC
    if index and (zones or not time_files) or not index and time_files:
        raise WopwopError(f"{path}: time_files: expected a file list and no zones for a multi-file aperiodic index, "
                          f"zones and no file list otherwise; got {len(zones)} zone(s), {len(time_files)} file(s)")


def _byte_order(order: str, path) -> str:
    if order not in ("<", ">"):
        raise WopwopError(f"{path}: byte order: expected '<' (little-endian) or '>' (big-endian), got {order!r}")
    return order


def _check_shape(array, shape: tuple[int, ...], path, label: str, what: str) -> None:
    """A one-line refusal naming the field unless ``array`` has exactly ``shape`` (values are cast to float32 /
    int32 as they are written)."""
    if np.shape(array) != shape:
        raise WopwopError(f"{path}: {label}: {what}: expected shape {shape}, got {np.shape(array)}")


def _timing_bytes(order: str, time_kind: int, period_s: float | None, keys: np.ndarray, path, label: str) -> bytes:
    """[period, key count] | [key count] | nothing; the period given exactly for periodic zones only."""
    if (period_s is None) != (time_kind != PERIODIC):
        raise WopwopError(f"{path}: {label}: period_s: expected {'a period' if time_kind == PERIODIC else 'None'} "
                          f"in {_TIME_KINDS.get(time_kind, time_kind)} files, got {period_s!r}")
    if time_kind == CONSTANT:
        return b""
    n_keys = _ints(order, len(keys))
    return (np.array([period_s], dtype=order + "f4").tobytes() + n_keys) if time_kind == PERIODIC else n_keys


def _n_steps(time_kind: int, keys, path, label: str) -> int:
    keys = np.asarray(keys)
    if keys.ndim != 1 or (time_kind == CONSTANT and len(keys)):
        raise WopwopError(f"{path}: {label}: keys: expected shape {'(0,)' if time_kind == CONSTANT else '(n_steps,)'}, "
                          f"got {keys.shape}")
    return 1 if time_kind == CONSTANT else len(keys)


def _records(order: str, headers: list[_ZoneHeader], blocks, keyed: bool, path) -> np.ndarray:
    """Zeroed step records for the zones; every zone must have the same number of steps."""
    for header in headers[1:]:
        if header.n_keys != headers[0].n_keys:
            raise WopwopError(f"{path}: {header.label}: keys: expected {headers[0].n_keys} steps as "
                              f"{headers[0].label} (every step holds every zone), got {header.n_keys}")
    return np.zeros(headers[0].n_keys if headers else 0, dtype=_step_dtype(order, headers, blocks, keyed))


def _fill(records: np.ndarray, z: int, keys, arrays: list[np.ndarray], blocks, keyed: bool) -> None:
    """Put one zone's keys and blocks (one (n_steps, count, rows) array per block) into the step records."""
    if keyed:
        records[f"key{z}"] = keys
    for (name, *_), array in zip(blocks, arrays):
        records[f"{name}{z}"] = np.swapaxes(array, 1, 2)


def _geometry_zone_header(zone: GeometryZone, z: int, geometry: GeometryFile, order: str, path):
    """The header of a zone to write (its arrays' shapes checked) and its header bytes."""
    label = f"zone {z} '{zone.name}'"
    n_steps = _n_steps(geometry.time_kind, zone.keys, path, label)
    if zone.structured:
        n_nodes, n_faces = zone.i_max * zone.j_max, (zone.i_max - 1) * (zone.j_max - 1)
        dims = _ints(order, zone.i_max, zone.j_max)
    else:
        n_nodes, n_faces = zone.n_nodes, len(zone.faces)
        dims = _ints(order, n_nodes, n_faces) + _face_bytes(order, zone.faces)
    if zone.n_nodes != n_nodes:
        raise WopwopError(f"{path}: {label}: n_nodes: expected {n_nodes} (iMax jMax), got {zone.n_nodes}")
    n_data = n_faces if geometry.face_centred else n_nodes
    _check_shape(zone.xyz, (n_steps, n_nodes, 3), path, label, "xyz")
    _check_shape(zone.normals, (n_steps, n_data, 3), path, label, "normals")
    if zone.iblank is not None:
        _check_shape(zone.iblank, (n_steps, n_data), path, label, "iblank")
    header = _ZoneHeader(label, zone.name, zone.structured, zone.i_max, zone.j_max, n_nodes, zone.faces, n_data,
                         zone.period_s, n_steps, 0)
    timing = _timing_bytes(order, geometry.time_kind, zone.period_s, zone.keys, path, label)
    return header, _text(zone.name, NAME_BYTES, path, f"zone {z} name") + timing + dims


def _face_bytes(order: str, faces: tuple[np.ndarray, ...]) -> bytes:
    """Per face its node count and 1-based node ids, as one int array."""
    if not faces:
        return b""
    counts = np.array([len(face) for face in faces], dtype=np.int64)
    starts = np.concatenate(([0], np.cumsum(counts + 1)[:-1]))
    out = np.empty(int(counts.sum()) + len(faces), dtype=order + "i4")
    is_id = np.ones(len(out), dtype=bool)
    is_id[starts] = False
    out[starts] = counts
    out[is_id] = np.concatenate([np.asarray(face, dtype=np.int64) for face in faces]) + 1
    return out.tobytes()


def _geometry_flags(geometry: GeometryFile, path) -> tuple[bool, bool, int]:
    """Structured, iblank and zone count of the header: from the zones, or as given for an index."""
    zones = geometry.zones
    if any(z.structured != zones[0].structured or (z.iblank is None) != (zones[0].iblank is None) for z in zones):
        raise WopwopError(f"{path}: zones: expected one grid kind and iblank in every zone or in none")
    derived = (zones[0].structured, zones[0].iblank is not None, len(zones)) if zones else (True, False, None)
    given = (geometry.structured, geometry.iblank, geometry.n_zones)
    for name, value, other in zip(("structured", "iblank", "n_zones"), given, derived):
        if zones and value is not None and value != other:
            raise WopwopError(f"{path}: {name}: expected {other} (as the zones), got {value}")
    flags = tuple(other if value is None else value for value, other in zip(given, derived))
    if flags[2] is None:
        raise WopwopError(f"{path}: n_zones: expected the zone count of the geometry for an index, got None")
    return flags


def _time_files_bytes(order: str, files: tuple[TimeFile, ...], path) -> bytes:
    """The list of a multi-file index; names space-padded (Fortran's trim removes blanks, not NULs)."""
    return _ints(order, len(files)) + b"".join(
        _text(f.name, FILE_NAME_BYTES, path, f"time file {i} name", b" ") + _ints(order, f.first_step, f.last_step)
        for i, f in enumerate(files, 1))


def _encode_geometry(geometry: GeometryFile, path, order: str) -> bytes:
    _check_header(path, geometry.time_kind, geometry.zones, geometry.time_files)
    structured, iblank, n_zones = _geometry_flags(geometry, path)
    kind = geometry.time_kind
    head = [_ints(order, MAGIC, 1, 0), _text(geometry.units, UNITS_BYTES, path, "units"),
            _text(geometry.comment, COMMENT_BYTES, path, "comment"),
            _ints(order, GEOMETRY_FILE, n_zones, 1 if structured else 2, kind, 2 if geometry.face_centred else 1,
                  1, int(iblank), 0)]
    if kind == MULTI_TIME_APERIODIC:
        return b"".join(head) + _time_files_bytes(order, geometry.time_files, path)
    headers = []
    for z, zone in enumerate(geometry.zones, 1):
        header, header_bytes = _geometry_zone_header(zone, z, geometry, order, path)
        headers.append(header)
        head.append(header_bytes)
    blocks = _GEOMETRY_BLOCKS + ([_IBLANK_BLOCK] if iblank else [])
    keyed = kind != CONSTANT
    records = _records(order, headers, blocks, keyed, path)
    for z, zone in enumerate(geometry.zones):
        arrays = [np.asarray(zone.xyz), np.asarray(zone.normals)]
        _fill(records, z, zone.keys, arrays + ([np.asarray(zone.iblank)[:, :, None]] if iblank else []), blocks, keyed)
    return b"".join(head) + records.tobytes()


def _functional_zone_header(zone: FunctionalZone, functional: FunctionalFile, order: str, path):
    """The header of a zone to write (its values' shape checked) and its header bytes."""
    label = f"zone {zone.zone} '{zone.name}'"
    n_steps = _n_steps(functional.time_kind, zone.keys, path, label)
    if zone.structured != functional.structured:
        raise WopwopError(f"{path}: {label}: structured: expected {functional.structured} (as the file), got "
                          f"{zone.structured}")
    n_data = zone.i_max * zone.j_max if zone.structured else zone.n_data
    if zone.n_data != n_data:
        raise WopwopError(f"{path}: {label}: n_data: expected {n_data} (iMax jMax), got {zone.n_data}")
    n_comp = COMPONENTS[functional.data_kind]
    _check_shape(zone.values, (n_steps, n_data, n_comp), path, label, "values")
    dims = _ints(order, zone.i_max, zone.j_max) if zone.structured else _ints(order, n_data)
    header = _ZoneHeader(label, zone.name, zone.structured, zone.i_max, zone.j_max, n_data, (), n_data,
                         zone.period_s, n_steps, 0)
    timing = _timing_bytes(order, functional.time_kind, zone.period_s, zone.keys, path, label)
    allowed = (1, 2) if functional.minor_version == 1 else (2,)
    if zone.loading_output not in allowed:
        raise WopwopError(f"{path}: {label}: loading_output: expected one of {list(allowed)} in format "
                          f"1.{functional.minor_version} (1: thickness output, format 1.1 only), got {zone.loading_output!r}")
    output = _ints(order, zone.loading_output) if functional.minor_version == 1 else b""
    return header, _text(zone.name, NAME_BYTES, path, f"zone {zone.zone} name") + output + timing + dims


def _encode_functional(functional: FunctionalFile, path, order: str) -> bytes:
    _check_header(path, functional.time_kind, functional.zones, functional.time_files, functional.data_kind)
    kind, zones = functional.time_kind, functional.zones
    if functional.minor_version not in (0, 1):
        raise WopwopError(f"{path}: minor_version: expected 0 or 1 (format 1.0 or 1.1), got {functional.minor_version!r}")
    head = [_ints(order, MAGIC, 1, functional.minor_version), _text(functional.comment, COMMENT_BYTES, path, "comment"),
            _ints(order, FUNCTIONAL_FILE, functional.n_zones, 1 if functional.structured else 2, kind,
                  2 if functional.face_centred else 1, functional.data_kind, functional.frame, 1, 0, 0)]
    if kind == MULTI_TIME_APERIODIC:
        return b"".join(head) + _time_files_bytes(order, functional.time_files, path)
    ids = [zone.zone for zone in zones]
    if ids != sorted(set(ids)) or (ids and ids[0] < 1):
        raise WopwopError(f"{path}: zones: expected distinct positive zone ids in ascending order (the order "
                          f"WOPWOP reads the zones in), got {ids}")
    head.append(_ints(order, len(zones), *(z.zone if z.thickness else -z.zone for z in zones)))
    headers = []
    for zone in zones:
        header, header_bytes = _functional_zone_header(zone, functional, order, path)
        headers.append(header)
        head.append(header_bytes)
    blocks = _FUNCTIONAL_BLOCKS[functional.data_kind]
    keyed = kind != CONSTANT
    records = _records(order, headers, blocks, keyed, path)
    for z, zone in enumerate(zones):
        values, arrays, first = np.asarray(zone.values), [], 0
        for _name, _kind, rows, _count in blocks:
            arrays.append(values[:, :, first:first + rows])
            first += rows
        _fill(records, z, zone.keys, arrays, blocks, keyed)
    return b"".join(head) + records.tobytes()


def _write_atomic(path, data: bytes) -> None:
    """Write through a temporary file in the same folder, renamed over ``path`` once complete."""
    target = Path(path)
    handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=target.parent)
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
        os.chmod(temporary, 0o644)
        os.replace(temporary, target)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


def write_geometry(geometry: GeometryFile, path, byte_order: str | None = None) -> None:
    """Write a geometry file in ``byte_order`` ("<" or ">"; default: ``geometry.byte_order``), atomically. The
    bytes are read back with :func:`read_geometry`'s rules before the file is written: what we write, we read."""
    order = _byte_order(byte_order or geometry.byte_order, path)
    data = _encode_geometry(geometry, path, order)
    _decode_geometry(data, path)
    _write_atomic(path, data)


def write_functional(functional: FunctionalFile, path, byte_order: str | None = None) -> None:
    """Write a functional data file in ``byte_order`` (default: ``functional.byte_order``), atomically, after
    checking its bytes with :func:`read_functional`'s rules. Zones must come in ascending zone id."""
    order = _byte_order(byte_order or functional.byte_order, path)
    data = _encode_functional(functional, path, order)
    _decode_functional(data, path)
    _write_atomic(path, data)


# ----------------------------------------------------------------------------------------------- pairing
def face_count(zone: GeometryZone) -> int:
    """Faces of a zone: unstructured, its face count; structured, (iMax-1)(jMax-1) quadrilaterals, except a
    compact line (iMax or jMax = 1), which counts its max(iMax, jMax) - 1 segments (the face-centred loading of
    a 1 x n lifting line as FLOWUnsteady writes it; WOPWOP's own structured count would be 0)."""
    if not zone.structured:
        return len(zone.faces)
    if min(zone.i_max, zone.j_max) == 1:
        return max(zone.i_max, zone.j_max) - 1
    return (zone.i_max - 1) * (zone.j_max - 1)


def _close(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal within PAIR_RTOL of the largest magnitude (float32 values written by two tools)."""
    scale = max(float(np.max(np.abs(a), initial=0.0)), float(np.max(np.abs(b), initial=0.0)))
    return a.shape == b.shape and bool(np.all(np.abs(a.astype(np.float64) - b) <= PAIR_RTOL * scale))


def _pair_zone(gzone: GeometryZone, fzone: FunctionalZone, geometry: GeometryFile, functional: FunctionalFile,
               geometry_path) -> str | None:
    """What does not match between a functional zone and its geometry zone, or None."""
    where = f"zone {fzone.zone} '{gzone.name}' of {geometry_path}"
    if functional.face_centred:
        expected, what = face_count(gzone), "faces"
    else:
        expected, what = gzone.n_nodes, "nodes"
    if fzone.structured and gzone.structured and not functional.face_centred and \
            (fzone.i_max, fzone.j_max) != (gzone.i_max, gzone.j_max):
        return f"dimensions: expected {gzone.i_max} x {gzone.j_max} as {where}, got {fzone.i_max} x {fzone.j_max}"
    if fzone.n_data != expected:
        return f"data points: expected {expected} (the {what} of {where}), got {fzone.n_data}"
    both = (geometry.time_kind, functional.time_kind)
    if both == (PERIODIC, PERIODIC) and not _close(np.array([gzone.period_s]), np.array([fzone.period_s])):
        return f"period: expected {gzone.period_s!r} s as {where}, got {fzone.period_s!r} s"
    if both == (APERIODIC, APERIODIC) and not _close(np.asarray(gzone.keys), np.asarray(fzone.keys)):
        return (f"time keys: expected the {len(gzone.keys)} keys of {where} (a loading file whose time keys do not "
                f"match its geometry), got {len(fzone.keys)} keys from {float(fzone.keys[0])!r} s")
    return None


def check_pair(geometry: GeometryFile, functional: FunctionalFile, geometry_path, functional_path) -> None:
    """The functional file belongs to the geometry file: the same zone count (container.f90 ReadFileHeaderV1_0
    refuses others); every data zone exists; its data count matches the geometry zone's nodes (node-centred)
    or :func:`face_count` (face-centred), and structured node-centred dims match; when both are periodic, equal
    periods; when both are aperiodic, equal keys (both within PAIR_RTOL). An index (multi-file aperiodic) is
    checked for its zone count only. One line naming the functional file and the zone."""
    n_geometry = geometry.n_zones if geometry.n_zones is not None else len(geometry.zones)
    if functional.n_zones != n_geometry:
        raise WopwopError(f"{functional_path}: header: number of zones: expected {n_geometry} as {geometry_path}, "
                          f"got {functional.n_zones}")
    if not geometry.zones:
        return
    for fzone in functional.zones:
        label = f"{functional_path}: zone {fzone.zone} '{fzone.name}'"
        if not 1 <= fzone.zone <= len(geometry.zones):
            raise WopwopError(f"{label}: zone id: expected 1 to {len(geometry.zones)} (zones of {geometry_path}), "
                              f"got {fzone.zone}")
        problem = _pair_zone(geometry.zones[fzone.zone - 1], fzone, geometry, functional, geometry_path)
        if problem:
            raise WopwopError(f"{label}: {problem}")
