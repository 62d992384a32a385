"""PSU-WOPWOP output files (pressure, OASPL, spectra, frequency ranges) and WOPWOP's spectral conventions.

Units: times in s, pressures in Pa, frequencies in Hz, mean-square pressures (MSP) in Pa², levels in dB
re 20 µPa, observer positions in m in the ground frame. Sources below are PSU-WOPWOP 3.4's Fortran:
obsUtility.f90 (writeOutTecplotData), module ObserverContainerObject (WriteTimeHistoryFunctionFile,
WriteSpectralFunctionFile, WriteStationaryObsSurface, WriteMovingObsContSurface, CalcObsContComplexPressure,
FilterObsContPressure), module ObserverObject (WriteNameFile, CalcObsComplexPressure,
CalcFiltComplexDFTFromPPrime, CalcObsMSPFromComplexPressure, CalcObsdB[A]FromMSP, CalcObsOASPLdB[A]Data,
WindowTimeHistory, FilterPPrime, WriteSingleObs*Data), freqAnalysis.f90 (ConvertMSPTodB[A], Aweight,
Create*Window, ConvertFrequencyToTime), module FrequencyDomainObject (FilterFreqDomain,
AweightIntegrateOverFreqDomain), module TimeHistoryObject (GetPeriod, GetDt), constants.f90 (epsilon = 1e-5,
P_ref = 20e-6).

Files. One observer: a Tecplot ``.tec``: `` TITLE="PSU-WOPWOP"``, ``VARIABLES= "x", "y1", …``, a ``TEXT X=100
Y=95 AN=HEADRIGHT T="x vs \\\\ny1\\\\n… "`` line, a blank line, then one row per abscissa value. Several
observers: PLOT3D ``NAME.fn`` (dim1, dim2, n, nVariables; the abscissa for every observer at each step,
observer index fastest, then each function the same way), ``NAME.nam`` (one title a line, list-directed:
a leading blank) and a grid ``.x`` (dim1, dim2, n; all x, all y, all z, i fastest, then j, then step), ASCII
((4I12) or (3I12) header, one G15.6 value a line) or binary (stream, 4-byte ints and reals, the writer's
byte order). Titles differ between the two layouts (``"Thickness Acoustic Pressure (Pa)"`` in a .tec,
``"ThicknessAcoustic Pressure"`` in a .nam): :func:`variable_titles`.

Spectra (:func:`mean_square_spectrum`): FFT of all n samples of the record (both ends: period = t_max −
t_min = (n − 1) dt), df = 1/period, bins k = 0 … n/2 kept when hpf − 1e-5 ≤ k df ≤ lpf + 1e-5;
P_k = 2 X_k dt df = 2 X_k/(n − 1), P_0 = X_0/(n − 1), MSP_k = |P_k|²/2 (the n/2 bin is not halved). So
bin k of the n-sample DFT (frequency k/(n dt)) is labelled k/((n − 1) dt), and a tone of amplitude a that is
periodic in the n samples shows MSP (n/(n − 1))² a²/2; NPS's :func:`nps.noise.spectra.narrowband_msp`
normalises by n (Parseval), WOPWOP's MSP is (n/(n − 1))² larger (the 0 Hz bin (n/(n − 1))²/2 times the
squared mean).
Levels: dB = 10 log10((MSP + ε³)/P_ref²), ε³ = 1e-15 Pa²; the 0 Hz bin of the dB and dBA spectra is left
as its raw MSP (Pa²). OASPL = 10 log10((Σ MSP + ε³)/P_ref²) over the kept bins: the 0 Hz bin is in the sum
when hpf = 0 (the PSU-WOPWOP cases' OASPL files agree to 1e-4 dB only with it, not "k ≥ 1").
A-weighting: WOPWOP's power weight W_A(f) = k3 f⁴/((f²+f2²)(f²+f3²)) · k1 f⁴/((f²+G1²)²(f²+f4²)²)
(k1 = 2.242881e16, G1 = 20.598997, f4 = 12194.22, k3 = 1.562339, f2 = 107.65265, f3 = 737.86223) is the
IEC 61672-1 curve of :func:`nps.noise.metrics.a_weighting_db` (0 dB at 1 kHz) to within 1.6e-6 dB over
1 Hz–20 kHz (rounding of its constants), so that function is used; W_A(0) = 0. WOPWOP works in single
precision; these functions in double.
"""

from __future__ import annotations

import math
import re
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from nps.noise.metrics import a_weighting_db
from nps.noise.spectra import P_REF_PA
from nps.wopwop.errors import WopwopError

MSP_FLOOR_PA2 = 1.0e-15
"""WOPWOP's ε³ added to every MSP before the logarithm (EnvironmentConstants epsilon = 1e-5, constants.f90)."""
BIN_TOLERANCE_HZ = 1.0e-5
"""Tolerance of the high- and low-pass bin selection (CalcObsContComplexPressure)."""
SOURCES = ("Thickness", "Loading", "Total")
"""WOPWOP's noise sources in its output order (PPRIMETITLEARRAY, observer.f90 ResetPPrimeAndIndices)."""
PRESSURE_COLUMNS = SOURCES + tuple(s + axis for s in SOURCES for axis in ("PGX", "PGY", "PGZ"))
"""Columns of a pressure output: acoustic pressures, then pressure gradients (titled "(Pa)" by WOPWOP)."""
WINDOWS = ("Hanning Window", "Hamming Window", "Blackman Window", "Flat Top Window")
"""WOPWOP's windowFunction values (ObserverIn namelist, case-insensitive; WindowTimeHistory)."""
TEC_FORMATS = ("e15.8", "f15.6")
"""Row formats of .tec files: WOPWOP 3.4's ``(e15.8," ")`` per value, and the fixed-point rows of other
builds (abscissa F15.6, other columns F12.6, each followed by a blank; seen in the public example outputs)."""

_GREEK_MU = "re20<greek>m</greek>Pa"
# kind: (abscissa title, single-observer column title, several-observer column title); {s} = source
_KINDS = {
    "pressure": ("Observer Time (s)", "{s} Acoustic Pressure (Pa)", "{s}Acoustic Pressure"),
    "OASPLdB": ("SPL Time (s)", "{s}OASPL (dB, " + _GREEK_MU + ") OASPL (dB)", "{s}OASPL (dB, " + _GREEK_MU + ")"),
    "OASPLdBA": ("SPL Time (s)", "{s}OASPL (dBA, " + _GREEK_MU + ")OASPL (dBA)", "{s}OASPL (dBA, " + _GREEK_MU + ")"),
    "spl_spectrum": ("Frequency", "{s}_{u}", "{s}_{u}"),
    "range": ("SPL Time (s)", "{s}SPL ({u}, " + _GREEK_MU + ")SPL (dB)", "{s}SPL ({u}, " + _GREEK_MU + ")"),
}
_LEVEL_COLUMNS = tuple(f"{s}_{u}" for u in ("dB", "dBA") for s in SOURCES)


@dataclass(frozen=True)
class OutputTable:
    """One WOPWOP output (pressure, OASPL, spectrum …) of one observer container.

    ``variables``: titles, the first the abscissa (observer time s, or frequency Hz); ``values``:
    (n_observers, n_abscissa, n_variables), observers in WOPWOP order (dim1 index fastest); ``shape``:
    (dim1, dim2) of the observer grid ((1, 1) for a .tec); ``positions_m``: (n_observers, n_abscissa, 3)
    ground-frame observer positions from the .x grid file, else None."""

    variables: tuple[str, ...]
    values: np.ndarray
    shape: tuple[int, int]
    positions_m: np.ndarray | None = None

    def __post_init__(self):
        values = np.asarray(self.values, dtype=float)
        if values.ndim != 3 or values.shape[2] != len(self.variables) or min(values.shape) < 1:
            raise WopwopError(f"OutputTable: values: expected (n_observers, n, {len(self.variables)}), got {values.shape}")
        if len(self.shape) != 2 or self.shape[0] * self.shape[1] != values.shape[0]:
            raise WopwopError(f"OutputTable: shape: expected dim1 × dim2 = {values.shape[0]} observers, got {self.shape}")
        if self.positions_m is not None and np.shape(self.positions_m) != values.shape[:2] + (3,):
            raise WopwopError(f"OutputTable: positions_m: expected {values.shape[:2] + (3,)}, "
                              f"got {np.shape(self.positions_m)}")
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "variables", tuple(str(v) for v in self.variables))
        object.__setattr__(self, "shape", (int(self.shape[0]), int(self.shape[1])))
        if self.positions_m is not None:
            object.__setattr__(self, "positions_m", np.asarray(self.positions_m, dtype=float))


# ---------------------------------------------------------------- titles and tables


def variable_titles(kind: str, columns: Sequence[str], single_observer: bool) -> tuple[str, ...]:
    """WOPWOP's titles for an output ``kind`` ("pressure", "OASPLdB", "OASPLdBA", "spl_spectrum", "range").

    ``columns``: WOPWOP's source titles: "Thickness", "Loading", "Total" (pressure also "ThicknessPGX" …);
    for "spl_spectrum" and "range" the level columns "Thickness_dB" … "Total_dBA". Returned in WOPWOP's
    order, the abscissa first. Single observer (.tec) and several (.nam) differ (observerContainer.f90
    WriteMultipleObsPressureData / WriteObsContOASPLData / WriteObsContFreqRangeData; observer.f90
    WriteSingleObsTimeHistoryData, CalcObsOASPLdB[A]Data, CalcObsFreqRangedB[A]Data, CalcObsdB[A]FromMSP)."""
    if kind not in _KINDS:
        raise WopwopError(f"variable_titles: kind: expected one of {sorted(_KINDS)}, got {kind!r}")
    abscissa, single, several = _KINDS[kind]
    template = single if single_observer else several
    titles = []
    for column in _ordered_columns(kind, columns):
        source, _, unit = column.partition("_")
        titles.append(template.format(s=source, u=unit))
    return (abscissa,) + tuple(titles)


def _ordered_columns(kind: str, columns: Sequence[str]) -> list[str]:
    """``columns`` in WOPWOP's order for ``kind``; unknown, repeated or no columns are refused."""
    allowed = PRESSURE_COLUMNS if kind == "pressure" else _LEVEL_COLUMNS if kind in ("spl_spectrum", "range") else SOURCES
    if not columns or len(set(columns)) != len(columns) or any(c not in allowed for c in columns):
        raise WopwopError(f"variable_titles: {kind} columns: expected distinct names among {allowed}, got {list(columns)}")
    return [c for c in allowed if c in columns]


def output_table(kind: str, abscissa, columns: Mapping[str, object], shape: tuple[int, int] = (1, 1),
                 positions_m=None) -> OutputTable:
    """An :class:`OutputTable` with WOPWOP's titles (:func:`variable_titles`) for ``kind``.

    ``abscissa``: (n,) observer or segment times (s) or frequencies (Hz); ``columns``: source title →
    (n_observers, n) or, for one observer, (n,) values; ``shape``: (dim1, dim2) of the observer grid. The
    titles follow the number of observers, as WOPWOP's do (one: .tec titles)."""
    x = np.asarray(abscissa, dtype=float)
    n_obs = int(shape[0]) * int(shape[1])
    if x.ndim != 1 or x.size < 1:
        raise WopwopError(f"output_table: abscissa: expected a 1-D array, got shape {x.shape}")
    titles = variable_titles(kind, list(columns), n_obs == 1)
    order = _ordered_columns(kind, list(columns))
    values = np.empty((n_obs, x.size, len(titles)))
    values[:, :, 0] = x
    for j, name in enumerate(order, start=1):
        column = np.asarray(columns[name], dtype=float)
        if column.shape not in ((n_obs, x.size),) + (((x.size,),) if n_obs == 1 else ()):
            raise WopwopError(f"output_table: {name}: expected ({n_obs}, {x.size}) values, got {column.shape}")
        values[:, :, j] = column.reshape(n_obs, x.size)
    return OutputTable(titles, values, (int(shape[0]), int(shape[1])), positions_m)


def pressure_groups(table: OutputTable) -> dict[str, np.ndarray]:
    """The acoustic pressures (Pa) of a pressure output: "thickness" / "loading" / "total" → (n_obs, nt).

    Recognises both title layouts ("Thickness Acoustic Pressure (Pa)", "ThicknessAcoustic Pressure");
    pressure-gradient columns ("ThicknessPGX …") are left out."""
    groups = {}
    for j, title in enumerate(table.variables[1:], start=1):
        head = title.removesuffix("(Pa)").strip()
        if head.endswith("Acoustic Pressure"):
            source = head.removesuffix("Acoustic Pressure").strip()
            if source in SOURCES:
                groups[source.lower()] = table.values[:, :, j].copy()
    if not groups:
        raise WopwopError(f"pressure_groups: no acoustic pressure column among {list(table.variables)}")
    return groups


# ---------------------------------------------------------------- Fortran edit descriptors


def _e_field(value: float, width: int, digits: int) -> str:
    """Fortran Ew.d (0.ddddE±xx, processor rounding to nearest), right-justified."""
    if not math.isfinite(value):
        raise ValueError(repr(value))
    if value == 0.0:
        mantissa, exponent = "0" * digits, 0
    else:
        text = f"{abs(value):.{digits - 1}e}"
        mantissa, exponent = text[0] + text[2:text.index("e")], int(text[text.index("e") + 1:]) + 1
    if abs(exponent) > 99:
        raise ValueError(f"{value!r} (a 3-digit exponent)")
    sign = "-" if math.copysign(1.0, value) < 0 else ""
    return f"{sign}0.{mantissa}E{exponent:+03d}".rjust(width)


def _f_field(value: float, width: int, digits: int) -> str:
    """Fortran Fw.d; a value too wide for the field (Fortran writes asterisks) is refused."""
    text = f"{value:#{width}.{digits}f}"  # '#': Fortran keeps the decimal point of F w.0
    if not math.isfinite(value) or len(text) > width:
        raise ValueError(f"{value!r} does not fit F{width}.{digits}")
    return text


def _g_field(value: float, width: int = 15, digits: int = 6) -> str:
    """Fortran Gw.d (F2008 10.7.5.2.3, round to nearest): F(w−4).(d−s) and 4 blanks, else Ew.d."""
    if not math.isfinite(value):
        raise ValueError(repr(value))
    if value == 0.0:
        return _f_field(value, width - 4, digits - 1) + "    "
    magnitude = abs(value)
    for s in range(digits + 1):
        if 10.0 ** (s - 1) - 0.5 * 10.0 ** (s - digits - 1) <= magnitude < 10.0 ** s - 0.5 * 10.0 ** (s - digits - 1):
            return _f_field(value, width - 4, digits - s) + "    "
    return _e_field(value, width, digits)


def _formatted(path, values: np.ndarray, field) -> list[str]:
    """Each value of a 1-D array through ``field``; a value WOPWOP could not have written is refused."""
    out = []
    for i, value in enumerate(values.tolist()):
        try:
            out.append(field(value, i))
        except ValueError as err:
            raise WopwopError(f"{path}: value {i}: expected a finite number WOPWOP's format can hold, got {err}") from None
    return out


# ---------------------------------------------------------------- Tecplot .tec


def write_tec(path, table: OutputTable, number_format: str = "e15.8", newline: str = "\n") -> None:
    """Write a one-observer output as WOPWOP's Tecplot file (obsUtility.f90 writeOutTecplotData).

    ``number_format``: "e15.8" (WOPWOP 3.4: each value E15.8 and a blank) or "f15.6" (abscissa F15.6,
    others F12.6, each and a blank: the other builds' rows); every row ends with one more blank (the
    list-directed record end). ``newline``: "\\n" or "\\r\\n" (WOPWOP writes its platform's)."""
    if table.values.shape[0] != 1:
        raise WopwopError(f"{path}: a .tec holds one observer, the table has {table.values.shape[0]}")
    if number_format not in TEC_FORMATS or newline not in ("\n", "\r\n"):
        raise WopwopError(f"{path}: format: expected one of {TEC_FORMATS} and a newline \\n or \\r\\n, "
                          f"got {number_format!r}, {newline!r}")
    _check_titles(path, table.variables)
    x, ys = table.variables[0], table.variables[1:]
    lines = [' TITLE="PSU-WOPWOP"', "VARIABLES= " + ", ".join(f'"{v}"' for v in table.variables),
             'TEXT X=100 Y=95 AN=HEADRIGHT T="' + x + " vs \\\\n" + "".join(v + "\\\\n" for v in ys) + ' "', ""]
    rows = table.values[0]
    n_var = rows.shape[1]
    if number_format == "e15.8":
        field = lambda v, i: _e_field(v, 15, 8) + " "  # noqa: E731
    else:
        field = lambda v, i: _f_field(v, 15 if i % n_var == 0 else 12, 6) + " "  # noqa: E731
    cells = _formatted(path, rows.ravel(), field)
    lines += ["".join(cells[r * n_var:(r + 1) * n_var]) + " " for r in range(rows.shape[0])]
    Path(path).write_bytes((newline.join(lines) + newline).encode("ascii"))


def _text_lines(path, data: bytes | None = None) -> list[str]:
    """The lines of an ASCII output file (either line end)."""
    data = _read_bytes(path) if data is None else data
    try:
        return data.decode("ascii").splitlines()
    except UnicodeDecodeError as err:
        raise WopwopError(f"{path}: byte {err.start}: expected ASCII text, got byte {data[err.start]:#04x}") from None


def _check_titles(path, titles: Sequence[str]) -> None:
    """Titles WOPWOP could write: ASCII, no line break (and no quote in a .tec)."""
    for title in titles:
        if not title.isascii() or any(c in title for c in '\r\n"'):
            raise WopwopError(f"{path}: variable title {title!r}: expected ASCII text without quote or line break")


def _tec_header(path, lines: list[str]) -> tuple[tuple[str, ...], int]:
    """The variable titles and the index of the first data line."""
    if not lines or not lines[0].strip().upper().startswith("TITLE"):
        raise WopwopError(f"{path}: line 1: expected TITLE=\"PSU-WOPWOP\", got {(lines[0] if lines else '')[:40]!r}")
    if len(lines) < 2 or not lines[1].strip().upper().startswith("VARIABLES"):
        found = lines[1] if len(lines) > 1 else ""
        raise WopwopError(f"{path}: line 2: expected VARIABLES= \"…\", …, got {found[:40]!r}")
    variables = tuple(re.findall(r'"([^"]*)"', lines[1]))
    if len(variables) < 2:
        raise WopwopError(f"{path}: line 2: expected at least two quoted variable titles, got {len(variables)}")
    first = 2
    while first < len(lines) and (not lines[first].strip() or lines[first].lstrip().upper().startswith("TEXT")):
        first += 1
    return variables, first


def _number(path, where: str, token: str) -> float:
    try:
        value = float(token)
    except ValueError:
        raise WopwopError(f"{path}: {where}: expected a number, got {token[:30]!r}") from None
    if not math.isfinite(value):
        raise WopwopError(f"{path}: {where}: expected a finite number, got {token!r}")
    return value


def _read_tec(path) -> OutputTable:
    lines = _text_lines(path)
    variables, first = _tec_header(path, lines)
    rows = []
    for number, line in enumerate(lines[first:], start=first + 1):
        tokens = line.split()
        if not tokens:
            continue
        if len(tokens) != len(variables):
            raise WopwopError(f"{path}: line {number}: expected {len(variables)} values (one per variable), "
                              f"got {len(tokens)}")
        try:
            row = [float(t) for t in tokens]
        except ValueError:
            row = [_number(path, f"line {number}, column {j + 1}", t) for j, t in enumerate(tokens)]
        if not all(math.isfinite(v) for v in row):
            bad = next(j for j, v in enumerate(row) if not math.isfinite(v))
            raise WopwopError(f"{path}: line {number}, column {bad + 1}: expected a finite number, got {tokens[bad]!r}")
        rows.append(row)
    if not rows:
        raise WopwopError(f"{path}: line {first + 1}: expected data rows after the header, got none")
    return OutputTable(variables, np.array(rows)[None, :, :], (1, 1), None)


# ---------------------------------------------------------------- PLOT3D .fn / .x / .nam


def write_plot3d(base_path, table: OutputTable, ascii: bool = True, byte_order: str = "<",
                 grid_path=None) -> None:
    """Write a several-observer output as WOPWOP does: ``base.fn``, ``base.nam`` and, when the table has
    positions, the grid ``grid_path`` (default ``base.x``; WOPWOP names the OASPL grid ``OASPL.x`` beside
    ``OASPLdB.fn``). ``ascii``: (4I12)/(3I12) header and one G15.6 value a line; else stream binary, 4-byte
    ints and reals in ``byte_order`` ("<" little-endian, ">" big-endian; WOPWOP writes its platform's)."""
    if byte_order not in ("<", ">"):
        raise WopwopError(f"{base_path}: byte_order: expected '<' or '>', got {byte_order!r}")
    base = str(base_path)
    _check_titles(base + ".nam", table.variables)
    _, n, n_var = table.values.shape
    counts = (table.shape[0], table.shape[1], n)
    _write_p3d(base + ".fn", counts + (n_var,), table.values.transpose(2, 1, 0), ascii, byte_order)
    Path(base + ".nam").write_text("".join(" " + v + "\n" for v in table.variables), encoding="ascii")
    if table.positions_m is not None:
        grid = base + ".x" if grid_path is None else str(grid_path)
        _write_p3d(grid, counts, table.positions_m.transpose(2, 1, 0), ascii, byte_order)


def _write_p3d(path: str, counts: tuple[int, ...], blocks: np.ndarray, ascii: bool, byte_order: str) -> None:
    """Header ints then the values of ``blocks`` in C order (block, step, observer)."""
    flat = blocks.ravel()
    if not np.all(np.isfinite(flat)) or np.any(np.abs(flat) > np.finfo(np.float32).max):
        i = int(np.argmax(~np.isfinite(flat) | (np.abs(flat) > np.finfo(np.float32).max)))
        raise WopwopError(f"{path}: value {i}: expected a finite 4-byte real, got {flat[i]!r}")
    if ascii:
        header = "".join(f"{c:12d}" for c in counts)
        body = _formatted(path, flat, lambda v, i: _g_field(v))
        Path(path).write_text(header + "\n" + "".join(line + "\n" for line in body), encoding="ascii")
    else:
        head = struct.pack(f"{byte_order}{len(counts)}i", *counts)
        Path(path).write_bytes(head + flat.astype(byte_order + "f4").tobytes())


def _read_bytes(path) -> bytes:
    try:
        return Path(path).read_bytes()
    except OSError as err:
        raise WopwopError(f"{path}: cannot be read: {err.strerror or err}") from None


def _is_text(data: bytes) -> bool:
    head = data[:64]
    return bool(head) and all(32 <= b < 127 or b in (9, 10, 13) for b in head)


def _read_p3d(path, n_header: int, per_point: int) -> tuple[tuple[int, ...], np.ndarray]:
    """(counts, values) of a .fn (4 counts, the 4th the number of values per point) or .x (3 counts, 3 values
    per point) file, ASCII or binary of either byte order (the one whose counts fit the file size)."""
    data = _read_bytes(path)
    if _is_text(data):
        return _read_p3d_ascii(path, data, n_header, per_point)
    if len(data) < 4 * n_header:
        raise WopwopError(f"{path}: byte 0: expected a header of {n_header} 4-byte ints, got a {len(data)}-byte file")
    candidates = {}
    for order in ("<", ">"):
        counts = struct.unpack(f"{order}{n_header}i", data[:4 * n_header])
        candidates[order] = counts
        if min(counts) >= 1 and len(data) == 4 * n_header + 4 * math.prod(counts) * per_point:
            values = np.frombuffer(data, dtype=order + "f4", offset=4 * n_header).astype(float)
            bad = np.flatnonzero(~np.isfinite(values))
            if bad.size:
                offset = 4 * n_header + 4 * int(bad[0])
                raise WopwopError(f"{path}: byte {offset}: expected a finite real, got {values[bad[0]]}")
            return counts, values
    raise WopwopError(f"{path}: byte 0: header: expected {n_header} counts >= 1 whose data fill the file's {len(data)} "
                      f"bytes, got {candidates['<']} (little-endian) / {candidates['>']} (big-endian)")


def _read_p3d_ascii(path, data: bytes, n_header: int, per_point: int) -> tuple[tuple[int, ...], np.ndarray]:
    lines = _text_lines(path, data)
    head = lines[0].split()
    if len(head) != n_header or not all(re.fullmatch(r"\+?\d+", t) for t in head) or min(int(t) for t in head) < 1:
        raise WopwopError(f"{path}: line 1: header: expected {n_header} integer counts >= 1, got {lines[0].strip()[:60]!r}")
    counts = tuple(int(t) for t in head)
    tokens, line_of = [], []
    for number, line in enumerate(lines[1:], start=2):
        parts = line.split()
        tokens += parts
        line_of += [number] * len(parts)
    expected = math.prod(counts) * per_point
    if len(tokens) != expected:
        raise WopwopError(f"{path}: line 1: header counts {counts} need {expected} values, the file has {len(tokens)}")
    try:
        values = np.array(tokens, dtype=float)
    except ValueError:
        values = np.array([_number(path, f"line {line_of[i]}", token) for i, token in enumerate(tokens)])
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        first = int(bad[0])
        raise WopwopError(f"{path}: line {line_of[first]}: expected a finite number, got {tokens[first]!r}")
    return counts, values


def _grid_candidates(base: str) -> list[str]:
    """Grid files WOPWOP writes beside ``base.fn``: base.x; OASPL.x for OASPLdB[A]; spl_PNL.x for spl_PNLdB;
    <SPLpath>_freqRanges.x for the range files <SPLpath>_<range>_dB[A]."""
    name = Path(base).name
    found = [base + ".x"]
    for suffix in ("dBA", "dB"):
        if name.endswith(suffix):
            found.append(str(Path(base).with_name(name.removesuffix(suffix) + ".x")))
            break
    found += [str(Path(base).with_name(name[:i] + "_freqRanges.x")) for i in range(1, len(name)) if name[i] == "_"]
    return found


def _read_plot3d(base: str) -> OutputTable:
    function_path, name_path = base + ".fn", base + ".nam"
    counts, values = _read_p3d(function_path, 4, 1)
    dim1, dim2, n, n_var = counts
    titles = [line.strip() for line in _text_lines(name_path)]
    while titles and not titles[-1]:
        titles.pop()
    if len(titles) != n_var:
        raise WopwopError(f"{name_path}: line count: expected {n_var} titles (the .fn holds {n_var} variables), "
                          f"got {len(titles)}")
    table_values = values.reshape(n_var, n, dim1 * dim2).transpose(2, 1, 0)
    positions = None
    grid = next((g for g in _grid_candidates(base) if Path(g).is_file()), None)
    if grid is not None:
        grid_counts, xyz = _read_p3d(grid, 3, 3)
        if grid_counts != (dim1, dim2, n):
            raise WopwopError(f"{grid}: byte 0: header: expected (dim1, dim2, n) = {(dim1, dim2, n)} as in "
                              f"{function_path}, got {grid_counts}")
        positions = xyz.reshape(3, n, dim1 * dim2).transpose(2, 1, 0)
    return OutputTable(tuple(titles), table_values, (dim1, dim2), positions)


def read_output(path) -> OutputTable:
    """Read a WOPWOP output: a ``.tec`` file, or a PLOT3D output by its base name or any of its
    ``.fn`` / ``.x`` / ``.nam`` files (ASCII or binary, either byte order, told from the header; the grid
    is looked for as in :func:`write_plot3d`; positions None without one)."""
    text = str(path)
    suffix = Path(text).suffix.lower()
    if suffix == ".tec":
        return _read_tec(text)
    base = text[: -len(suffix)] if suffix in (".fn", ".x", ".nam") else text
    if suffix not in (".fn", ".x", ".nam") and not Path(base + ".fn").is_file() and Path(base + ".tec").is_file():
        return _read_tec(base + ".tec")
    if suffix == ".x" and not Path(base + ".fn").is_file():
        raise WopwopError(f"{base}.fn: expected the function file beside the grid {text}, found none")
    return _read_plot3d(base)


# ---------------------------------------------------------------- spectral processing


def _record(time_s, p_pa, caller: str) -> tuple[np.ndarray, np.ndarray, float]:
    """(time, pressure (…, nt), period s) of a uniformly sampled record, checked."""
    t = np.asarray(time_s, dtype=float)
    p = np.asarray(p_pa, dtype=float)
    if t.ndim != 1 or t.size < 2 or p.ndim < 1 or p.shape[-1] != t.size:
        raise WopwopError(f"{caller}: time_s / p_pa: expected (nt,) times (nt >= 2) and (…, nt) pressures, "
                          f"got {t.shape} and {p.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(p))):
        raise WopwopError(f"{caller}: time_s / p_pa: expected finite values, got NaN or infinity")
    step = (t[-1] - t[0]) / (t.size - 1)
    offset = np.abs(t - (t[0] + step * np.arange(t.size)))
    if step <= 0.0 or np.any(np.diff(t) <= 0.0) or offset.max() > 0.5 * step:
        raise WopwopError(f"{caller}: time_s: expected increasing times within half a step of WOPWOP's uniform grid "
                          f"t0 + i (t_end − t0)/(nt − 1), got a time {offset.max():.3g} s off it")
    return t, p, float(t[-1] - t[0])


def window_function(name: str, n: int) -> np.ndarray:
    """WOPWOP's window of n samples times its power correction √(n/Σw²) (WindowTimeHistory).

    w_i, i = 1…n, x = 2πi/n (freqAnalysis.f90): Hanning 0.5 − 0.5 cos x; Hamming 0.54 − 0.46 cos x;
    Blackman 0.42 − 0.5 cos x + 0.08 cos 2x; Flat top 1 − 1.93 cos x + 1.29 cos 2x − 0.388 cos 3x
    + 0.0322 cos 4x. ``name``: one of :data:`WINDOWS`, case-insensitive."""
    key = str(name).strip().upper()
    x = 2.0 * np.pi * np.arange(1, n + 1) / n
    shapes = {
        "HANNING WINDOW": lambda: 0.5 - 0.5 * np.cos(x),
        "HAMMING WINDOW": lambda: 0.54 - 0.46 * np.cos(x),
        "BLACKMAN WINDOW": lambda: 0.42 - 0.5 * np.cos(x) + 0.08 * np.cos(2 * x),
        "FLAT TOP WINDOW": lambda: (1.0 - 1.93 * np.cos(x) + 1.29 * np.cos(2 * x) - 0.388 * np.cos(3 * x)
                                    + 0.0322 * np.cos(4 * x)),
    }
    if key not in shapes or n < 2:
        raise WopwopError(f"window_function: windowFunction: expected one of {WINDOWS} and n >= 2, got {name!r}, {n}")
    w = shapes[key]()
    return w * np.sqrt(n / np.sum(w * w))


def mean_square_spectrum(time_s, p_pa, high_pass_hz: float = 0.0, low_pass_hz: float = np.inf,
                         window: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    """WOPWOP's one-sided MSP line spectrum (Pa²) of a record: (frequency_hz (nf,), msp_pa2 (…, nf)).

    All nt samples, both ends (period = t[-1] − t[0], df = 1/period); bins 0…nt/2 with
    hpf − 1e-5 ≤ f ≤ lpf + 1e-5; P_k = 2X_k/(nt − 1), P_0 = X_0/(nt − 1), MSP = |P|²/2
    (CalcObsContComplexPressure, CalcObsComplexPressure, CalcObsMSPFromComplexPressure). ``window``: None or
    "" (WOPWOP's default) or one of :data:`WINDOWS`, applied before the FFT."""
    t, p, period = _record(time_s, p_pa, "mean_square_spectrum")
    n = t.size
    if window:
        p = p * window_function(window, n)
    frequency = np.arange(n // 2 + 1) / period
    keep = (frequency >= high_pass_hz - BIN_TOLERANCE_HZ) & (frequency <= low_pass_hz + BIN_TOLERANCE_HZ)
    if not np.any(keep):
        raise WopwopError(f"mean_square_spectrum: high/low pass: expected bins of df = {1 / period:.6g} Hz "
                          f"between {high_pass_hz} and {low_pass_hz} Hz, got none")
    amplitude = np.fft.rfft(p, axis=-1) * (2.0 / (n - 1))
    amplitude[..., 0] *= 0.5
    return frequency[keep], 0.5 * np.abs(amplitude[..., keep]) ** 2


def a_weighting_power(frequency_hz) -> np.ndarray:
    """A-weighting as a power weight W_A(f) (WOPWOP's Aweight); = 10^(A(f)/10) with NPS's IEC 61672-1
    :func:`nps.noise.metrics.a_weighting_db` (the same curve to 1.6e-6 dB, module docstring), 0 at 0 Hz."""
    f = np.asarray(frequency_hz, dtype=float)
    if np.any(~np.isfinite(f)) or np.any(f < 0.0):
        raise WopwopError("a_weighting_power: frequency_hz: expected finite frequencies >= 0 Hz")
    weight = np.zeros_like(f)
    positive = f > 0.0
    weight[positive] = 10.0 ** (a_weighting_db(f[positive]) / 10.0)
    return weight


def _db(msp_pa2, floor_pa2: float) -> np.ndarray:
    """WOPWOP's ConvertMSPTodB: 10 log10((MSP + floor)/P_ref²)."""
    return 10.0 * np.log10((msp_pa2 + floor_pa2) / P_REF_PA**2)


def spl_spectrum(time_s, p_pa, high_pass_hz: float = 0.0, low_pass_hz: float = np.inf, window: str | None = None,
                 msp_floor_pa2: float = MSP_FLOOR_PA2, a_weighted_floor_pa2: float = MSP_FLOOR_PA2):
    """WOPWOP's narrowband spectrum: (frequency_hz, spl_db, spl_dba) as in spl_spectrum.tec.

    dB = 10 log10((MSP + floor)/P_ref²), dBA = 10 log10((MSP·W_A + floor_A)/P_ref²) per bin; a 0 Hz bin
    (hpf = 0) keeps its raw MSP in Pa² in both (CalcObsdBFromMSP, CalcObsdBAFromMSP). The floors are ε³ =
    1e-15 Pa² in WOPWOP 3.4 (ConvertMSPTodB[A]); the build that wrote the public case1 floors dBA at 1e-20."""
    frequency, msp = mean_square_spectrum(time_s, p_pa, high_pass_hz, low_pass_hz, window)
    spl_db = _db(msp, msp_floor_pa2)
    spl_dba = _db(msp * a_weighting_power(frequency), a_weighted_floor_pa2)
    if frequency[0] == 0.0:
        spl_db[..., 0] = msp[..., 0]
        spl_dba[..., 0] = msp[..., 0]
    return frequency, spl_db, spl_dba


def oaspl(time_s, p_pa, high_pass_hz: float = 0.0, low_pass_hz: float = np.inf, window: str | None = None,
          band_hz: tuple[float, float] | None = None, msp_floor_pa2: float = MSP_FLOOR_PA2):
    """WOPWOP's overall levels (dB, dBA) of a record, shapes (…): OASPLdB / OASPLdBA files.

    10 log10((Σ MSP + ε³)/P_ref²) and 10 log10((Σ MSP·W_A + ε³)/P_ref²) over the kept bins, the 0 Hz bin
    included when hpf = 0 (CalcObsOASPLdB[A]Data). ``band_hz`` (f_min, f_max): the level of the bins with
    f_min ≤ f ≤ f_max only, as the frequency-range files (spl_<range>.tec; FilterFreqDomain,
    CalcObsFreqRangedB[A]Data)."""
    frequency, msp = mean_square_spectrum(time_s, p_pa, high_pass_hz, low_pass_hz, window)
    if band_hz is not None:
        inside = (frequency >= band_hz[0]) & (frequency <= band_hz[1])
        frequency, msp = frequency[inside], msp[..., inside]
    total = np.sum(msp, axis=-1)
    weighted = np.sum(msp * a_weighting_power(frequency), axis=-1)
    return _db(total, msp_floor_pa2), _db(weighted, msp_floor_pa2)


def band_filter(time_s, p_pa, high_pass_hz: float = 0.0, low_pass_hz: float = np.inf) -> np.ndarray:
    """The pressure WOPWOP writes (FilterObsContPressure, FilterPPrime): unchanged unless hpf > 0 or
    (nt/2 + 1)/period > lpf; then FFT, bins with f < hpf − ε or f > lpf + ε (ε = 1e-5 Hz) and the 0 Hz bin
    zeroed, inverse FFT divided by nt. (Older builds filtered only when df < hpf: the public example
    outputs are all unfiltered.)"""
    t, p, period = _record(time_s, p_pa, "band_filter")
    n = t.size
    if not (high_pass_hz > 0.0 or (n // 2 + 1) / period > low_pass_hz):
        return p.copy()
    spectrum = np.fft.rfft(p, axis=-1)
    frequency = np.arange(n // 2 + 1) / period
    outside = (frequency < high_pass_hz - BIN_TOLERANCE_HZ) | (frequency > low_pass_hz + BIN_TOLERANCE_HZ)
    spectrum[..., outside] = 0.0
    spectrum[..., 0] = 0.0
    return np.fft.irfft(spectrum, n=n, axis=-1)


# ---------------------------------------------------------------- the files of a run


def run_tables(environment, spec, shape: tuple[int, int], time_s, positions_m, pressure: Mapping[str, np.ndarray]
               ) -> dict[str, OutputTable]:
    """The output tables a PSU-WOPWOP run writes for one observer container, by the case's switches.

    ``environment``: the case's :class:`nps.wopwop.case.Environment` (acousticPressureFlag, thicknessNoiseFlag,
    loadingNoiseFlag, totalNoiseFlag, OASPLdBFlag, OASPLdBAFlag, spectrumFlag with narrowbandFlag); ``spec``: the
    observer container (high- and low-pass frequencies, window, frequency ranges); ``time_s`` (nt,) its observer
    times; ``positions_m`` (n_obs, nt, 3) the observers' positions (for the grid files); ``pressure``: "thickness" and
    "loading" → (n_obs, nt) Pa. Returns file name → table: ``pressure``, ``OASPLdB``, ``OASPLdBA``, ``spl_spectrum``
    and ``spl_<range title>`` (the range levels, dB and dBA). Sources: the switched-on ones of Thickness, Loading,
    Total (no switch: Total, as WOPWOP's acousticPressureFlag does)."""
    total = pressure["thickness"] + pressure["loading"]
    by_source = {"Thickness": pressure["thickness"], "Loading": pressure["loading"], "Total": total}
    chosen = [s for s, on in zip(SOURCES, (environment.thickness_noise, environment.loading_noise,
                                           environment.total_noise)) if on] or ["Total"]
    hpf, lpf, window = spec.high_pass_hz, spec.low_pass_hz, spec.window or None
    tables: dict[str, OutputTable] = {}
    if environment.acoustic_pressure:
        columns = {s: band_filter(time_s, by_source[s], hpf, lpf) for s in chosen}
        tables["pressure"] = output_table("pressure", time_s, columns, shape, positions_m)
    levels = {s: oaspl(time_s, by_source[s], hpf, lpf, window) for s in chosen}
    start = np.asarray([time_s[0]])
    first = positions_m[:, :1]
    for name, k, on in (("OASPLdB", 0, environment.oaspl_db), ("OASPLdBA", 1, environment.oaspl_dba)):
        if on:
            tables[name] = output_table(name, start, {s: levels[s][k][:, None] for s in chosen}, shape, first)
    if environment.spectrum and environment.narrowband:
        spectra = {s: spl_spectrum(time_s, by_source[s], hpf, lpf, window) for s in chosen}
        frequency = spectra[chosen[0]][0]
        columns = {f"{s}_{u}": spectra[s][1 + k] for s in chosen for k, u in enumerate(("dB", "dBA"))}
        tables["spl_spectrum"] = output_table("spl_spectrum", frequency, columns, shape, None)
    for title, low, high in spec.ranges:
        band = {s: oaspl(time_s, by_source[s], hpf, lpf, window, band_hz=(low, high)) for s in chosen}
        columns = {f"{s}_{u}": band[s][k][:, None] for s in chosen for k, u in enumerate(("dB", "dBA"))}
        tables[f"spl_{title}"] = output_table("range", start, columns, shape, first)
    return tables


def write_run_tables(tables: Mapping[str, OutputTable], folder, ascii: bool) -> list[Path]:
    """Write a run's tables into ``folder``: one observer as Tecplot ``NAME.tec``, several as PLOT3D
    ``NAME.fn/.nam/.x`` (ASCII or binary as the case's ASCIIOutputFlag; the OASPL grid as ``OASPL.x``). The files
    are written into a temporary sibling folder and moved into place once all are complete."""
    import os
    import shutil
    import tempfile

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{folder.name}.", suffix=".tmp", dir=folder.parent))
    try:
        for name, table in tables.items():
            if table.shape == (1, 1):
                write_tec(work / f"{name}.tec", table)
            else:
                grid = work / "OASPL.x" if name.startswith("OASPL") else None
                write_plot3d(work / name, table, ascii=ascii, grid_path=grid)
        written = []
        for path in sorted(work.iterdir()):
            os.replace(path, folder / path.name)
            written.append(folder / path.name)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return written
