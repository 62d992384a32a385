"""Section aerodynamics: the airfoil interface, the linear model and tabulated polars.

Every airfoil model answers one question, :meth:`Airfoil.coefficients`: the lift, drag and
quarter-chord pitching-moment coefficients (c_l, c_d, c_m) at angles of attack α (rad) and
Mach numbers M, vectorised over broadcast arrays. Sign conventions: α from the chord line
(toward the leading edge) to the relative wind, nose up positive; c_l perpendicular to the
relative wind, c_d along it, c_m nose up positive.

Two implementations (``docs/reference/loads.md``, section "Airfoils"):

- :class:`LinearAirfoil` (the default): c_l = a (α − α0)/√(1 − min(M, M_cap)²) clipped to
  ±c_l,max, c_d = cd0 + cd1 α + cd2 α², c_m = 0. It is defined on α ∈ [−π/2, π/2): a section in
  reverse flow is a symmetric section seen from behind (``full_range = False``).
- :class:`AirfoilTable`: c_l, c_d, c_m tabulated against (α, M), bilinear interpolation, Mach
  clamped to the table's ends; read from a C81 deck (:func:`read_c81`) or a CSV polar
  (:func:`read_polar_csv`), optionally extended to ±180° by Viterna–Corrigan
  (:func:`viterna_extension`). A table covering ±180° is evaluated at the full angle, so
  reverse flow uses the table's own post-stall and reversed-section data (``full_range``).
  An angle outside a table's range is an error naming the file and the coefficient.

C81 format (fixed columns, the rotorcraft airfoil-deck standard; read and written here):

- line 1: airfoil name in columns 1–30 (A30), then six 2-column integers (6I2): NML, NAL, NMD,
  NAD, NMM, NAM, the numbers of Mach numbers and angles of the c_l, c_d and c_m tables;
- each table: a Mach line, columns 1–7 blank then the Mach numbers in 7-column fields, nine to
  a line (7X, 9F7.0; more than nine continue on the next lines, again after 7 blank columns);
  then one row per angle: α in degrees in columns 1–7 and the coefficients at each Mach
  number in 7-column fields, nine to a line, continuation lines as for the Mach line
  (F7.0, 9F7.0 / 7X, 9F7.0). Tables in the order c_l, c_d, c_m; α strictly increasing.

XFOIL polars: the file XFOIL's ``PACC`` command writes (``.pol``, ``.dat`` or ``.txt``; recognised
by its ``XFOIL`` banner): header lines with the airfoil name (``Calculated polar for:``), the
Mach and Reynolds numbers and N_crit, then a column-name line starting with ``alpha``, a line of
dashes, and one row per converged angle (``alpha CL CD CDp CM`` and transition columns, in any
order XFOIL writes them; only ``alpha``, ``CL``, ``CD``, ``CM`` are used). Rows come in the order
XFOIL ran them: they are sorted by α; an angle computed twice must give the same coefficients.
The polar applies at every Mach number (XFOIL already applied its Kármán–Tsien correction at the
header's Mach number); several Mach numbers need a C81 deck or a CSV polar with a ``mach`` column.

CSV polars: columns ``alpha_deg``, ``cl``, ``cd`` and optionally ``cm``, ``mach`` and
``reynolds``; ``#`` starts a comment line. Rows with several ``mach`` values form a table in
Mach (each Mach's polar interpolated onto the union of the angles inside the range common to
all); several ``reynolds`` values require choosing one (``reynolds=``): the blade element
model has no Reynolds-number dependence. Without a ``mach`` column the polar applies at
every Mach number (no compressibility correction).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import ClassVar, Protocol

import numpy as np

from nps.rotor.blade import read_commented_csv
from nps.core.jit import kernel

_FIELD = 7
_PER_LINE = 9
_RANGE_SLACK_RAD = 1e-9
# Viterna–Corrigan: maximum drag of a flat plate of aspect ratio AR, c_d,max = 1.11 + 0.018 AR
# (AR ≤ 50); reversed-section lift factor 0.7 beyond 90° (AirfoilPrep, Hansen 2012)
_VITERNA_CD_MAX_0 = 1.11
_VITERNA_CD_MAX_AR = 0.018
_REVERSED_LIFT_FACTOR = 0.7
_EXTENSION_STEP_DEG = 2.0
# bounds no section's lift coefficients reach (|c_l| stays below about 3 even with high-lift devices, the lift
# slope near alpha = 0 near 2 pi per rad, 2 pi/sqrt(1 - M^2) at M 0.9): beyond them the CL column holds
# something else, c_l in percent or angles in radians where degrees belong
_CL_MAX_PLAUSIBLE = 5.0
_LIFT_SLOPE_MAX_PER_RAD = 30.0


class AirfoilError(ValueError):
    """An airfoil table is missing, malformed, or does not cover the requested angles."""


class Airfoil(Protocol):
    """Section aerodynamic model (see the module docstring for signs).

    ``lift_slope_per_rad`` and ``cd0`` are reference values for linear estimates (flap inertia
    from the Lock number, trim start values, the aircraft trim's profile power).
    ``full_range``: True when :meth:`coefficients` takes α over [−π, π) (reverse flow from the
    model itself), False when it takes the mod-π angle α ∈ [−π/2, π/2).
    """

    lift_slope_per_rad: float
    cd0: float
    full_range: bool

    def coefficients(self, alpha_rad, mach) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(c_l, c_d, c_m) at α (rad) and M, broadcast together."""
        ...


@dataclass(frozen=True)
class LinearAirfoil:
    """Linear lift, quadratic drag (thesis ch. 4).

    c_l = a (α − α0) / √(1 − min(M, mach_cap)²) (Prandtl–Glauert), limited to ±``cl_max``;
    c_d = cd0 + cd1 α + cd2 α²; c_m = 0. α in rad on [−π/2, π/2).
    """

    lift_slope_per_rad: float = 5.73
    alpha0_rad: float = 0.0
    cl_max: float = 1.4
    cd0: float = 0.008
    cd1: float = 0.0
    cd2: float = 0.4
    mach_cap: float = 0.95
    full_range: ClassVar[bool] = False

    def __post_init__(self):
        checks = [
            ("lift_slope_per_rad", self.lift_slope_per_rad > 0.0, "a positive number"),
            ("cl_max", self.cl_max > 0.0, "a positive number"),
            ("mach_cap", 0.0 < self.mach_cap < 1.0, "0 < mach_cap < 1"),
            ("cd0", self.cd0 >= 0.0, "a non-negative number"),
        ]
        for name, ok, expected in checks:
            if not (ok and math.isfinite(getattr(self, name))):
                raise ValueError(f"airfoil.{name}: expected {expected}, got {getattr(self, name)!r}")

    def coefficients(self, alpha_rad, mach):
        pg = np.sqrt(1.0 - np.minimum(mach, self.mach_cap) ** 2)
        cl = np.minimum(np.maximum(self.lift_slope_per_rad * (alpha_rad - self.alpha0_rad) / pg, -self.cl_max), self.cl_max)
        cd = self.cd0 + self.cd1 * alpha_rad + self.cd2 * alpha_rad * alpha_rad
        return cl, cd, np.zeros_like(cl)


def reverse_flow_angle(alpha_mod_rad, reverse_flow) -> np.ndarray:
    """Full angle α ∈ [−π, π] from the mod-π angle where the wind comes from the trailing edge.

    With φ the inflow angle, the mod-π angle is θ − φ reduced to [−π/2, π/2); where U_T < 0
    (``reverse_flow``) the wind comes from behind and the full angle differs from it by π.
    """
    alpha = np.asarray(alpha_mod_rad, dtype=float)
    return np.where(reverse_flow, alpha - np.copysign(np.pi, alpha), alpha)


def section_coefficients(foil: Airfoil, alpha_mod_rad, reverse_flow, mach):
    """(c_l, c_d, c_m) of ``foil`` at the angle its model is defined on (``full_range``)."""
    alpha = reverse_flow_angle(alpha_mod_rad, reverse_flow) if foil.full_range else alpha_mod_rad
    return foil.coefficients(alpha, mach)


@dataclass(frozen=True, eq=False)
class PolarTable:
    """One coefficient tabulated against α (rad, strictly increasing) and M (increasing).

    ``values`` has shape (n_alpha, n_mach). :meth:`__call__` interpolates bilinearly, clamps M
    to [mach[0], mach[-1]] and raises :class:`AirfoilError` naming ``source`` and ``name`` for
    α outside [alpha_rad[0], alpha_rad[-1]].
    """

    name: str
    alpha_rad: np.ndarray
    mach: np.ndarray
    values: np.ndarray
    source: str

    def __post_init__(self):
        a, m, v = (np.ascontiguousarray(x, dtype=float) for x in (self.alpha_rad, self.mach, self.values))
        where = f"{self.source}: {self.name}"
        if a.ndim != 1 or a.size < 2 or not np.all(np.diff(a) > 0.0):
            raise AirfoilError(f"{where}: angles of attack: expected at least two, strictly increasing")
        if m.ndim != 1 or m.size < 1 or not np.all(np.diff(m) > 0.0):
            raise AirfoilError(f"{where}: Mach numbers: expected at least one, strictly increasing")
        if v.shape != (a.size, m.size) or not np.isfinite(v).all():
            raise AirfoilError(f"{where}: values: expected {a.size} x {m.size} finite numbers, got shape {v.shape}")
        for name, value in (("alpha_rad", a), ("mach", m), ("values", v)):
            object.__setattr__(self, name, value)

    @property
    def full_range(self) -> bool:
        """True when the table covers α from −180° to +180°."""
        return bool(self.alpha_rad[0] <= -np.pi + 1e-6 and self.alpha_rad[-1] >= np.pi - 1e-6)

    def __call__(self, alpha_rad, mach) -> np.ndarray:
        alpha, mach = np.broadcast_arrays(np.asarray(alpha_rad, dtype=float), np.asarray(mach, dtype=float))
        a = self.alpha_rad
        low, high = float(alpha.min(initial=a[0])), float(alpha.max(initial=a[-1]))
        if low < a[0] - _RANGE_SLACK_RAD or high > a[-1] + _RANGE_SLACK_RAD:
            raise AirfoilError(
                f"{self.source}: {self.name}: angle of attack {math.degrees(low if low < a[0] else high):.2f} deg "
                f"outside the table's range [{math.degrees(a[0]):.2f}, {math.degrees(a[-1]):.2f}] deg; "
                "extend the polar to +-180 deg (extrapolation: viterna) or give a wider table"
            )
        out = np.empty(alpha.shape)
        _bilinear(a, self.mach, self.values, alpha.ravel(), mach.ravel(), out.reshape(-1))
        return out


@kernel
def _bilinear(alpha_grid, mach_grid, values, alpha, mach, out):
    """out[k] = values bilinearly interpolated at (alpha[k], mach[k]); Mach clamped to the grid.

    α must lie within the grid (checked by the caller); one Mach number: linear in α only.
    """
    na, nm = alpha_grid.size, mach_grid.size
    for k in range(alpha.size):
        x = alpha[k]
        i = min(max(np.searchsorted(alpha_grid, x, side="right") - 1, 0), na - 2)
        ta = min(max((x - alpha_grid[i]) / (alpha_grid[i + 1] - alpha_grid[i]), 0.0), 1.0)
        if nm == 1:
            out[k] = values[i, 0] + ta * (values[i + 1, 0] - values[i, 0])
            continue
        y = min(max(mach[k], mach_grid[0]), mach_grid[nm - 1])
        j = min(max(np.searchsorted(mach_grid, y, side="right") - 1, 0), nm - 2)
        tm = (y - mach_grid[j]) / (mach_grid[j + 1] - mach_grid[j])
        low = values[i, j] + ta * (values[i + 1, j] - values[i, j])
        high = values[i, j + 1] + ta * (values[i + 1, j + 1] - values[i, j + 1])
        out[k] = low + tm * (high - low)


@dataclass(frozen=True, eq=False)
class AirfoilTable:
    """Tabulated section coefficients c_l, c_d, c_m (one :class:`PolarTable` each)."""

    name: str
    cl: PolarTable
    cd: PolarTable
    cm: PolarTable
    source: str
    lift_slope_per_rad: float = field(init=False)
    cd0: float = field(init=False)

    def __post_init__(self):
        # reference values at the lowest tabulated Mach number: central-difference lift slope
        # over ±2° and the drag at α = 0 (clipped to the table)
        m0 = min(self.cl.mach[0], self.cd.mach[0])
        step = math.radians(2.0)
        lo, hi = max(-step, self.cl.alpha_rad[0]), min(step, self.cl.alpha_rad[-1])
        slope = float((self.cl(hi, m0) - self.cl(lo, m0)) / (hi - lo))
        if not slope > 0.0:
            raise AirfoilError(f"{self.source}: CL: expected a positive lift slope near alpha = 0, got {slope:.4g} per rad")
        _check_lift_magnitudes(self.cl, slope, self.source)
        alpha0 = float(np.clip(0.0, self.cd.alpha_rad[0], self.cd.alpha_rad[-1]))
        object.__setattr__(self, "lift_slope_per_rad", slope)
        object.__setattr__(self, "cd0", float(self.cd(alpha0, m0)))

    @property
    def full_range(self) -> bool:
        return self.cl.full_range and self.cd.full_range and self.cm.full_range

    def coefficients(self, alpha_rad, mach):
        return self.cl(alpha_rad, mach), self.cd(alpha_rad, mach), self.cm(alpha_rad, mach)


def _check_lift_magnitudes(cl: PolarTable, slope_per_rad: float, source: str) -> None:
    """Refuse lift coefficients no section has (:data:`_CL_MAX_PLAUSIBLE`, :data:`_LIFT_SLOPE_MAX_PER_RAD`), naming
    the likely cause: c_l in percent, or (plausible c_l, steep slope) angles in radians in a degree column."""
    peak = float(np.abs(cl.values).max())
    found = f"|c_l| up to {peak:.4g} and a lift slope of {slope_per_rad:.4g} per rad near alpha = 0"
    plausible = f"a section's c_l stays within about +-3 and its slope near 2 pi = {2 * math.pi:.3g} per rad"
    if peak > _CL_MAX_PLAUSIBLE:
        raise AirfoilError(f"{source}: CL: {found}, but {plausible}: the CL column looks like percent (c_l x 100); "
                           "divide it by 100")
    if slope_per_rad > _LIFT_SLOPE_MAX_PER_RAD:
        raise AirfoilError(f"{source}: CL: {found}, but {plausible}: the angles look like radians; give alpha in degrees")


# ---------------------------------------------------------------------------------------------
# C81 decks


def _c81_fields(lines: list[str], start: int, count: int, first_field: bool, path, what: str) -> tuple[list[float], int]:
    """Read ``count`` 7-column numbers from line ``start`` on, nine per line after columns 1–7.

    Returns the numbers (preceded by columns 1–7 of the first line if ``first_field``) and the
    index of the next line.
    """
    values: list[float] = []
    index = start
    need = count
    leading = first_field
    while need > 0:
        if index >= len(lines):
            raise AirfoilError(f"{path}: {what}: file ends before its {count} values (line {index + 1})")
        line = lines[index].rstrip("\n")
        columns = []
        if leading:
            columns.append((0, line[:_FIELD]))
        take = min(need, _PER_LINE)
        for k in range(take):
            lo = _FIELD * (k + 1)
            columns.append((lo, line[lo:lo + _FIELD]))
        for lo, text in columns:
            try:
                values.append(float(text.strip().replace("D", "E").replace("d", "e")))
            except ValueError:
                raise AirfoilError(
                    f"{path}: line {index + 1}: {what}: columns {lo + 1}-{lo + _FIELD}: expected a number, got {text!r}"
                ) from None
        need -= take
        leading = False
        index += 1
    return values, index


def read_c81(path: str | Path) -> AirfoilTable:
    """Read a C81 airfoil deck (format in the module docstring); angles in the file in degrees."""
    path = Path(path)
    if not path.is_file():
        raise AirfoilError(f"{path}: airfoil table not found")
    lines = path.read_text().splitlines()
    if not lines:
        raise AirfoilError(f"{path}: line 1: expected the C81 header (name, NML NAL NMD NAD NMM NAM), file is empty")
    header = lines[0]
    name = header[:30].strip()
    counts = []
    for k, label in enumerate(("NML", "NAL", "NMD", "NAD", "NMM", "NAM")):
        text = header[30 + 2 * k:32 + 2 * k]
        try:
            counts.append(int(text))
        except ValueError:
            raise AirfoilError(
                f"{path}: line 1: {label} (columns {31 + 2 * k}-{32 + 2 * k}): expected an integer, got {text!r}"
            ) from None
        if counts[-1] < (1 if label.startswith("NM") else 2):
            raise AirfoilError(f"{path}: line 1: {label}: expected at least {1 if label.startswith('NM') else 2}, got {counts[-1]}")
    tables = []
    index = 1
    for label, (n_mach, n_alpha) in zip(("CL", "CD", "CM"), (counts[0:2], counts[2:4], counts[4:6])):
        mach, index = _c81_fields(lines, index, n_mach, False, path, f"{label} Mach numbers")
        alpha, rows = [], []
        for k in range(n_alpha):
            row, index = _c81_fields(lines, index, n_mach, True, path, f"{label} row {k + 1}")
            alpha.append(row[0])
            rows.append(row[1:])
        if not np.all(np.diff(alpha) > 0.0):
            raise AirfoilError(f"{path}: {label}: angles of attack: expected strictly increasing, got {alpha}")
        tables.append(PolarTable(label, np.radians(alpha), np.array(mach), np.array(rows), str(path)))
    return AirfoilTable(name or path.stem, *tables, source=str(path))


def _c81_number(value: float) -> str:
    """Shortest text of ``value`` that fits a 7-column field (exact when it has ≤ 6 digits)."""
    text = repr(float(value))
    if text.endswith(".0"):
        text = text[:-1]
    if text.startswith(("0.", "-0.")) and not text.endswith("."):
        text = text.replace("0.", ".", 1)
    digits = 6
    while len(text) > _FIELD and digits > 0:
        text = f"{value:.{digits}g}"
        digits -= 1
    if len(text) > _FIELD:
        raise AirfoilError(f"C81: {value!r} does not fit a 7-column field")
    return text.ljust(_FIELD)


def _c81_lines(first: str, values) -> list[str]:
    """``first`` (7 columns) then ``values`` nine per line; continuation lines start with 7 blanks."""
    values = [_c81_number(v) for v in values]
    lines = []
    for k in range(0, max(len(values), 1), _PER_LINE):
        lines.append((first if k == 0 else " " * _FIELD) + "".join(values[k:k + _PER_LINE]))
    return [line.rstrip() for line in lines]


def write_c81(path: str | Path, table: AirfoilTable) -> None:
    """Write ``table`` as a C81 deck (angles in degrees, rounded to the 7-column fields)."""
    polars = (table.cl, table.cd, table.cm)
    if any(p.mach.size > 99 or p.alpha_rad.size > 99 for p in polars):
        raise AirfoilError(f"{path}: C81 holds at most 99 Mach numbers and 99 angles per table")
    counts = "".join(f"{p.mach.size:2d}{p.alpha_rad.size:2d}" for p in polars)
    lines = [f"{table.name[:30]:<30}{counts}"]
    for p in polars:
        lines += _c81_lines(" " * _FIELD, p.mach)
        for alpha, row in zip(np.degrees(p.alpha_rad), p.values):
            lines += _c81_lines(_c81_number(round(float(alpha), 10)), row)
    Path(path).write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# CSV polars


def read_polar_csv(path: str | Path, *, reynolds: float | None = None) -> AirfoilTable:
    """Read a CSV polar (format in the module docstring); ``reynolds`` selects one polar."""
    path = Path(path)
    reader, columns = read_commented_csv(path, "airfoil table", AirfoilError)
    for required in ("alpha_deg", "cl", "cd"):
        if required not in columns:
            raise AirfoilError(f"{path}: column {required}: required column missing; found {columns}")
    unknown = set(columns) - {"alpha_deg", "cl", "cd", "cm", "mach", "reynolds"}
    if unknown:
        raise AirfoilError(f"{path}: column {sorted(unknown)[0]}: unknown column; allowed alpha_deg, cl, cd, cm, mach, reynolds")
    data = {c: [] for c in columns}
    for line_no, row in enumerate(reader, start=2):
        for c in columns:
            text = (row.get(c) or "").strip()
            try:
                data[c].append(float(text))
            except ValueError:
                raise AirfoilError(f"{path}: data row {line_no - 1}: column {c}: expected a number, got {text!r}") from None
    arrays = {c: np.array(v) for c, v in data.items()}
    if not arrays["alpha_deg"].size:
        raise AirfoilError(f"{path}: expected at least two data rows, found none")
    keep = np.ones(arrays["alpha_deg"].size, dtype=bool)
    if "reynolds" in arrays:
        available = sorted(set(arrays["reynolds"].tolist()))
        if reynolds is None and len(available) > 1:
            raise AirfoilError(f"{path}: column reynolds: several Reynolds numbers {available}; choose one (reynolds)")
        chosen = available[0] if reynolds is None else reynolds
        if chosen not in available:
            raise AirfoilError(f"{path}: column reynolds: no polar at Reynolds number {reynolds}; available {available}")
        keep = arrays["reynolds"] == chosen
    elif reynolds is not None:
        raise AirfoilError(f"{path}: column reynolds: reynolds {reynolds} requested but the file has no reynolds column")
    mach_values = arrays["mach"][keep] if "mach" in arrays else np.zeros(int(keep.sum()))
    machs = np.unique(mach_values)
    blocks = []
    for m in machs:
        sel = keep.copy()
        sel[keep] = mach_values == m
        order = np.argsort(arrays["alpha_deg"][sel], kind="stable")
        alpha = arrays["alpha_deg"][sel][order]
        if alpha.size < 2 or not np.all(np.diff(alpha) > 0.0):
            raise AirfoilError(f"{path}: column alpha_deg: expected at least two distinct angles per polar (mach {m}), "
                               f"got {alpha.tolist()}")
        blocks.append((alpha, {c: arrays[c][sel][order] for c in ("cl", "cd", "cm") if c in arrays}))
    low = max(b[0][0] for b in blocks)
    high = min(b[0][-1] for b in blocks)
    grid = np.unique(np.concatenate([b[0] for b in blocks]))
    grid = grid[(grid >= low) & (grid <= high)]
    tables = []
    for label in ("cl", "cd", "cm"):
        values = np.column_stack([
            np.interp(grid, alpha, coeffs[label]) if label in coeffs else np.zeros(grid.size) for alpha, coeffs in blocks
        ])
        tables.append(PolarTable(label.upper(), np.radians(grid), machs, values, str(path)))
    return AirfoilTable(path.stem, *tables, source=str(path))


# ---------------------------------------------------------------------------------------------
# XFOIL polars

_XFOIL_HEADER = re.compile(r"Mach\s*=\s*([-+0-9.eE]+)\s+Re\s*=\s*([-+0-9.]+)\s*e\s*([-+]?\d+)\s+Ncrit\s*=\s*([-+0-9.]+)")
XFOIL_SUFFIXES = (".pol", ".dat", ".txt")


@dataclass(frozen=True)
class XfoilPolar:
    """An XFOIL polar file's contents: the airfoil table and the conditions XFOIL computed it at."""

    table: AirfoilTable
    mach: float
    reynolds: float
    ncrit: float


def is_xfoil_polar(path: str | Path) -> bool:
    """True when the first non-blank line of ``path`` is XFOIL's banner (``XFOIL  Version …``)."""
    with open(path, errors="replace") as handle:
        for line in handle:
            if line.strip():
                return line.split()[0] == "XFOIL"
    return False


def _xfoil_rows(lines: list[str], path: Path) -> tuple[list[str], int]:
    """(column names, index of the first data line) of an XFOIL polar."""
    for k, line in enumerate(lines):
        words = line.split()
        if words and words[0] == "alpha":
            if k + 1 >= len(lines) or not set(lines[k + 1].split()) <= {"-" * len(w) for w in lines[k + 1].split()}:
                raise AirfoilError(f"{path}: line {k + 2}: expected the line of dashes under the column names")
            missing = [c for c in ("CL", "CD", "CM") if c not in words]
            if missing:
                raise AirfoilError(f"{path}: line {k + 1}: column {missing[0]}: required column missing; found {words}")
            return words, k + 2
    raise AirfoilError(f"{path}: expected XFOIL's column-name line starting with 'alpha'; found none")


def read_xfoil_polar(path: str | Path) -> XfoilPolar:
    """Read an XFOIL polar file (format in the module docstring)."""
    path = Path(path)
    lines = path.read_text(errors="replace").splitlines()
    if not is_xfoil_polar(path):
        raise AirfoilError(f"{path}: expected an XFOIL polar (first line 'XFOIL  Version ...')")
    name = next((ln.split(":", 1)[1].strip() for ln in lines if "Calculated polar for:" in ln), "") or path.stem
    header = next((_XFOIL_HEADER.search(ln) for ln in lines if _XFOIL_HEADER.search(ln)), None)
    if header is None:
        raise AirfoilError(f"{path}: expected the line 'Mach = ...  Re = ... e ...  Ncrit = ...'; found none")
    mach, mantissa, exponent, ncrit = (float(g) for g in header.groups())
    columns, first = _xfoil_rows(lines, path)
    rows = {}
    for line_no, line in enumerate(lines[first:], start=first + 1):
        words = line.split()
        if not words:
            continue
        try:
            values = dict(zip(columns, (float(w) for w in words), strict=True))
        except ValueError:
            raise AirfoilError(f"{path}: line {line_no}: expected {len(columns)} numbers ({' '.join(columns)}), "
                               f"got {line.strip()!r}") from None
        coeffs = (values["CL"], values["CD"], values["CM"])
        if rows.setdefault(values["alpha"], coeffs) != coeffs:
            raise AirfoilError(f"{path}: line {line_no}: alpha {values['alpha']:g} deg computed twice with different "
                               "coefficients; keep one")
    if len(rows) < 2:
        raise AirfoilError(f"{path}: expected at least two converged angles, found {len(rows)}")
    alpha_deg = np.array(sorted(rows))
    coeffs = np.array([rows[a] for a in alpha_deg])
    tables = [PolarTable(label, np.radians(alpha_deg), np.array([mach]), coeffs[:, [k]], str(path))
              for k, label in enumerate(("CL", "CD", "CM"))]
    return XfoilPolar(AirfoilTable(name, *tables, source=str(path)), mach, mantissa * 10.0**exponent, ncrit)


def write_xfoil_polar(path: str | Path, polar: XfoilPolar) -> None:
    """Write ``polar`` in XFOIL's polar format (α to 3 decimals, c_l and c_m to 4, c_d to 5, as XFOIL does)."""
    table = polar.table
    if table.cl.mach.size != 1:
        raise AirfoilError(f"{path}: an XFOIL polar holds one Mach number; the table has {table.cl.mach.size}")
    if not (np.array_equal(table.cl.alpha_rad, table.cd.alpha_rad) and np.array_equal(table.cl.alpha_rad, table.cm.alpha_rad)):
        raise AirfoilError(f"{path}: an XFOIL polar needs c_l, c_d and c_m at the same angles")
    exponent = int(math.floor(math.log10(polar.reynolds))) if polar.reynolds > 0 else 0
    lines = ["", "       XFOIL         Version 6.99", "", f" Calculated polar for: {table.name}", "",
             " 1 1 Reynolds number fixed          Mach number fixed", "",
             f" Mach = {polar.mach:7.3f}     Re = {polar.reynolds / 10.0**exponent:9.3f} e {exponent}     "
             f"Ncrit = {polar.ncrit:7.3f}", "",
             "   alpha    CL        CD       CDp       CM",
             "  ------ -------- --------- --------- --------"]
    for alpha, cl, cd, cm in zip(np.degrees(table.cl.alpha_rad), table.cl.values[:, 0], table.cd.values[:, 0],
                                 table.cm.values[:, 0]):
        lines.append(f"  {alpha:6.3f} {cl:8.4f} {cd:9.5f} {0.0:9.5f} {cm:8.4f}")
    Path(path).write_text("\n".join(lines) + "\n")


# ---------------------------------------------------------------------------------------------
# ±180° extension


def _viterna_branch(alpha, alpha_s, cl_s, cd_s, cd_max):
    """Viterna–Corrigan c_l, c_d for α ∈ [α_s, π/2] from the stall point (α_s, c_l,s, c_d,s) > 0."""
    sin_s, cos_s = math.sin(alpha_s), math.cos(alpha_s)
    b2 = (cd_s - cd_max * sin_s**2) / cos_s
    a2 = (cl_s - cd_max * sin_s * cos_s) * sin_s / cos_s**2
    sin_a, cos_a = np.sin(alpha), np.cos(alpha)
    cl = 0.5 * cd_max * np.sin(2.0 * alpha) + a2 * cos_a**2 / sin_a
    cd = cd_max * sin_a**2 + b2 * cos_a
    return cl, cd


def _extend_side(alpha_s, cl_s, cd_s, cm_s, cd_max):
    """Angles α_s < α ≤ π and their (c_l, c_d, c_m) for one side, from the end point at α_s > 0."""
    step = math.radians(_EXTENSION_STEP_DEG)
    n = max(int(math.ceil((np.pi - alpha_s) / step)), 2)
    alpha = alpha_s + (np.pi - alpha_s) * np.arange(1, n + 1) / n
    cl, cd = np.empty_like(alpha), np.empty_like(alpha)
    up = alpha <= 0.5 * np.pi
    cl[up], cd[up] = _viterna_branch(alpha[up], alpha_s, cl_s, cd_s, cd_max)
    mirror = (alpha > 0.5 * np.pi) & (alpha <= np.pi - alpha_s)
    cl_v, cd_v = _viterna_branch(np.pi - alpha[mirror], alpha_s, cl_s, cd_s, cd_max)
    cl[mirror], cd[mirror] = -_REVERSED_LIFT_FACTOR * cl_v, cd_v
    tail = alpha > np.pi - alpha_s
    cl[tail] = -_REVERSED_LIFT_FACTOR * cl_s * (np.pi - alpha[tail]) / alpha_s
    cd[tail] = cd_s
    return alpha, cl, cd, np.full_like(alpha, cm_s)


def viterna_extension(table: AirfoilTable, *, aspect_ratio: float = 10.0) -> AirfoilTable:
    """Extend every Mach column of ``table`` to α = ±180° (Viterna & Corrigan 1982).

    The tabulated range is the one common to c_l, c_d and c_m, [α_lo, α_hi], on the union of
    their angles. From its upper end (α_s, c_l,s, c_d,s), for α_s < α ≤ 90°:
    c_l = (c_d,max/2) sin 2α + A2 cos²α / sin α, c_d = c_d,max sin²α + B2 cos α with
    c_d,max = 1.11 + 0.018 AR, B2 = (c_d,s − c_d,max sin²α_s)/cos α_s,
    A2 = (c_l,s − c_d,max sin α_s cos α_s) sin α_s / cos²α_s; for 90° < α ≤ 180° − α_s the
    reversed section, c_l = −0.7 c_l(180° − α), c_d = c_d(180° − α) (AirfoilPrep); beyond,
    c_l linear to 0 at 180° and c_d = c_d,s. The lower end gives the negative side by the same
    construction mirrored (α → −α, c_l → −c_l, c_m → −c_m). c_m is held at its end values.
    Values inside the tabulated range are unchanged.
    """
    if not 0.0 < aspect_ratio <= 50.0:
        raise AirfoilError(f"{table.source}: aspect_ratio: expected 0 < AR <= 50, got {aspect_ratio!r}")
    if table.full_range:
        return table
    polars = (table.cl, table.cd, table.cm)
    low = max(p.alpha_rad[0] for p in polars)
    high = min(p.alpha_rad[-1] for p in polars)
    if not (-0.5 * np.pi < low < 0.0 < high < 0.5 * np.pi):
        raise AirfoilError(f"{table.source}: angles of attack: the Viterna extension needs tables from below 0 deg to "
                           f"above 0 deg within +-90 deg, common range [{math.degrees(low):.2f}, {math.degrees(high):.2f}] deg")
    inner = np.unique(np.concatenate([p.alpha_rad for p in polars]))
    inner = inner[(inner >= low) & (inner <= high)]
    cd_max = _VITERNA_CD_MAX_0 + _VITERNA_CD_MAX_AR * aspect_ratio
    mach = np.unique(np.concatenate([p.mach for p in polars]))
    columns = []
    for m in mach:
        coeffs = table.coefficients(inner, m)
        sides = []
        for sign, end in ((1.0, -1), (-1.0, 0)):
            a, cl, cd, cm = _extend_side(sign * inner[end], sign * coeffs[0][end], coeffs[1][end], sign * coeffs[2][end], cd_max)
            sides.append((sign * a, sign * cl, cd, sign * cm))
        (a_hi, *c_hi), (a_lo, *c_lo) = sides
        alpha = np.concatenate([a_lo[::-1], inner, a_hi])
        columns.append([np.concatenate([lo[::-1], mid, hi]) for lo, mid, hi in zip(c_lo, coeffs, c_hi)])
    tables = [PolarTable(name, alpha, mach, np.column_stack([c[k] for c in columns]), table.source)
              for k, name in enumerate(("CL", "CD", "CM"))]
    return AirfoilTable(table.name, *tables, source=table.source)


def read_airfoil(path: str | Path, *, extrapolation: str = "none", aspect_ratio: float = 10.0,
                 reynolds: float | None = None) -> AirfoilTable:
    """An airfoil table from a C81 deck (``.c81``), a CSV polar (``.csv``) or an XFOIL polar
    (``.pol``, ``.dat``, ``.txt`` with XFOIL's banner), optionally extended.

    ``extrapolation``: ``none`` (angles outside the table are an error) or ``viterna``
    (:func:`viterna_extension` with the blade ``aspect_ratio``).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".c81":
        if reynolds is not None:
            raise AirfoilError(f"{path}: reynolds: a C81 deck has one Reynolds number; remove reynolds")
        table = read_c81(path)
    elif suffix == ".csv":
        table = read_polar_csv(path, reynolds=reynolds)
    elif suffix in XFOIL_SUFFIXES and path.is_file() and is_xfoil_polar(path):
        polar = read_xfoil_polar(path)
        if reynolds is not None and not math.isclose(reynolds, polar.reynolds, rel_tol=1e-3):
            raise AirfoilError(f"{path}: reynolds: the XFOIL polar is at Re = {polar.reynolds:.4g}, not {reynolds:.4g}")
        table = polar.table
    else:
        raise AirfoilError(f"{path}: table: expected a .c81 deck, a .csv polar or an XFOIL polar "
                           f"({', '.join(XFOIL_SUFFIXES)} starting with XFOIL's banner), got {path.name!r}")
    if extrapolation == "viterna":
        return viterna_extension(table, aspect_ratio=aspect_ratio)
    if extrapolation != "none":
        raise AirfoilError(f"{path}: extrapolation: expected 'none' or 'viterna', got {extrapolation!r}")
    return table
