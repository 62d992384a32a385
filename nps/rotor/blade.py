"""Blade geometry tables: chord, twist, thickness, quarter-chord offsets and airfoil per station.

A :class:`BladeTable` lists stations r_k (m, strictly increasing, covering the blade from the
root cutout to the tip) with, at each, the chord c (m), the geometric twist θ_tw (rad), the
thickness ratio t/c, the quarter-chord line's in-plane offset from the pitch axis ``sweep_m``
(m, positive toward the leading edge) and out-of-plane offset ``droop_m`` (m, positive along
+z_H), and the name of the section's airfoil. Between stations every quantity is linear in r;
airfoil coefficients are blended linearly in r between two stations with different airfoils
(weights :meth:`BladeTable.airfoil_weights`). Pitch: θ(r) = θ0 + θ_tw(r) − θ_tw(0.75 R), so
θ0 stays the pitch at 75 % radius as for the linear twist.

Sources: inline in the aircraft file (``rotors[].blade``, lists of equal length) or a CSV
file (``rotors[].blade.table``) with one row per station. Columns/keys: ``r_over_R`` or
``radius_m``; ``chord_over_R`` or ``chord_m``; ``twist_deg``; ``thickness_ratio``; optional
``sweep_m``, ``droop_m`` (default 0) and ``airfoil`` (names of ``rotors[].airfoils``; default:
the rotor's ``airfoil`` everywhere).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping

import numpy as np

_NUMERIC = ("r_over_R", "radius_m", "chord_over_R", "chord_m", "twist_deg", "thickness_ratio", "sweep_m", "droop_m")
_ALTERNATIVES = (("r_over_R", "radius_m"), ("chord_over_R", "chord_m"))


class BladeError(ValueError):
    """A blade table is missing, malformed or does not describe the blade."""


@dataclass(frozen=True, eq=False)
class BladeSections:
    """Blade properties at given radii (arrays broadcast like the radii; SI, rad)."""

    chord_m: np.ndarray
    twist_rad: np.ndarray
    thickness_ratio: np.ndarray
    sweep_m: np.ndarray
    droop_m: np.ndarray


@dataclass(frozen=True, eq=False)
class BladeTable:
    """Stations of one blade (module docstring); ``source`` names the file or config field."""

    radius_m: np.ndarray
    chord_m: np.ndarray
    twist_rad: np.ndarray
    thickness_ratio: np.ndarray
    sweep_m: np.ndarray
    droop_m: np.ndarray
    airfoils: tuple[str, ...]
    source: str

    def __post_init__(self):
        r = np.asarray(self.radius_m, dtype=float)
        n = r.size
        where = self.source
        if r.ndim != 1 or n < 2 or not np.all(np.diff(r) > 0.0) or r[0] < 0.0:
            raise BladeError(f"{where}: radius: expected at least two stations, r >= 0 strictly increasing, got {r.tolist()}")
        for name, low, high in (("chord_m", 0.0, np.inf), ("thickness_ratio", 0.0, 1.0)):
            v = np.asarray(getattr(self, name), dtype=float)
            if v.shape != (n,) or not np.all((v > low) & (v < high)):
                raise BladeError(f"{where}: {name}: expected {n} values in ({low}, {high}), got {v.tolist()}")
            object.__setattr__(self, name, v)
        for name in ("twist_rad", "sweep_m", "droop_m"):
            v = np.asarray(getattr(self, name), dtype=float)
            if v.shape != (n,) or not np.isfinite(v).all():
                raise BladeError(f"{where}: {name}: expected {n} finite values, got {v.tolist()}")
            object.__setattr__(self, name, v)
        if self.airfoils and len(self.airfoils) != n:
            raise BladeError(f"{where}: airfoil: expected {n} names (one per station), got {len(self.airfoils)}")
        object.__setattr__(self, "radius_m", r)
        object.__setattr__(self, "airfoils", tuple(str(a) for a in self.airfoils))

    @classmethod
    def linear(cls, radius_m: float, root_cutout_m: float, chord_m: float, twist_rad: float,
               thickness_ratio: float, airfoil: str | None = None) -> "BladeTable":
        """The table of the linear shorthand: constant chord and t/c, θ_tw = twist (r/R − 0.75)."""
        r = np.array([root_cutout_m, radius_m])
        return cls(r, np.full(2, chord_m), twist_rad * (r / radius_m - 0.75), np.full(2, thickness_ratio),
                   np.zeros(2), np.zeros(2), (airfoil,) * 2 if airfoil else (), "linear blade")

    def check_covers(self, root_cutout_m: float, radius_m: float) -> None:
        """Raise :class:`BladeError` unless the stations span [root_cutout_m, radius_m]."""
        r = self.radius_m
        tol = 1e-9 * radius_m
        if r[0] > root_cutout_m + tol or abs(r[-1] - radius_m) > tol:
            raise BladeError(f"{self.source}: radius: expected stations from the root cutout {root_cutout_m:.6g} m "
                             f"(or inboard) to the tip {radius_m:.6g} m, got {r[0]:.6g} to {r[-1]:.6g} m")

    def at(self, r_m) -> BladeSections:
        """Linear interpolation of every numeric column at radii ``r_m`` (any shape)."""
        r = np.asarray(r_m, dtype=float)
        return BladeSections(*(np.interp(r, self.radius_m, getattr(self, name))
                               for name in ("chord_m", "twist_rad", "thickness_ratio", "sweep_m", "droop_m")))

    def airfoil_weights(self, r_m) -> dict[str, np.ndarray]:
        """Airfoil name → blending weight at ``r_m`` (linear in r between stations; weights sum to 1)."""
        r = np.asarray(r_m, dtype=float)
        return {name: np.interp(r, self.radius_m, [1.0 if a == name else 0.0 for a in self.airfoils])
                for name in dict.fromkeys(self.airfoils)}

    def equivalent_chord_m(self, root_cutout_m: float, radius_m: float, n: int = 2001) -> float:
        """Thrust-weighted chord c_e = ∫ c r² dr / ∫ r² dr over [root cutout, R] (σ_e = B c_e/(πR))."""
        r = np.linspace(root_cutout_m, radius_m, n)
        w = r * r
        return float(np.trapezoid(self.at(r).chord_m * w, r) / np.trapezoid(w, r))


def _columns_to_table(columns: Mapping[str, list], radius_m: float, source: str) -> BladeTable:
    """BladeTable from column lists (keys as in the module docstring)."""
    unknown = set(columns) - set(_NUMERIC) - {"airfoil", "table"}
    if unknown:
        raise BladeError(f"{source}: {sorted(unknown)[0]}: unknown column; allowed {', '.join(_NUMERIC)}, airfoil")
    for pair in _ALTERNATIVES:
        given = [name for name in pair if name in columns]
        if len(given) != 1:
            raise BladeError(f"{source}: {pair[0]}: expected exactly one of {pair[0]} or {pair[1]}, got {given or 'neither'}")
    for name in ("twist_deg", "thickness_ratio"):
        if name not in columns:
            raise BladeError(f"{source}: {name}: required column missing")
    n = len(columns.get("r_over_R", columns.get("radius_m")))
    arrays = {}
    for name in _NUMERIC:
        if name in columns:
            values = list(columns[name])
            if len(values) != n:
                raise BladeError(f"{source}: {name}: expected {n} values (one per station), got {len(values)}")
            try:
                arrays[name] = np.array([float(v) for v in values])
            except (TypeError, ValueError):
                raise BladeError(f"{source}: {name}: expected numbers, got {values}") from None
            if not np.isfinite(arrays[name]).all():
                raise BladeError(f"{source}: {name}: expected finite numbers, got {values}")
    def metres(over_r: str, absolute: str) -> np.ndarray:
        return arrays[over_r] * radius_m if over_r in arrays else arrays[absolute]

    return BladeTable(
        radius_m=metres("r_over_R", "radius_m"),
        chord_m=metres("chord_over_R", "chord_m"),
        twist_rad=np.radians(arrays["twist_deg"]),
        thickness_ratio=arrays["thickness_ratio"],
        sweep_m=arrays.get("sweep_m", np.zeros(n)),
        droop_m=arrays.get("droop_m", np.zeros(n)),
        airfoils=tuple(columns.get("airfoil", ())),
        source=source,
    )


def read_commented_csv(path: Path, what: str, error: type[Exception]) -> tuple[csv.DictReader, list[str]]:
    """A CSV table whose blank lines and ``#`` comment lines are skipped: (row reader, stripped column names).
    A missing file raises ``error`` naming the file and ``what`` it should hold."""
    if not path.is_file():
        raise error(f"{path}: {what} not found")
    with open(path, newline="") as handle:
        rows = [line for line in handle if line.strip() and not line.lstrip().startswith("#")]
    reader = csv.DictReader(rows)
    return reader, [f.strip() for f in reader.fieldnames or []]


def read_blade_csv(path: str | Path, radius_m: float) -> BladeTable:
    """A blade table from a CSV file (one row per station; ``#`` starts a comment line)."""
    path = Path(path)
    reader, fields = read_commented_csv(path, "blade table", BladeError)
    columns: dict[str, list] = {f: [] for f in fields}
    for row in reader:
        for f in fields:
            columns[f].append((row.get(f) or "").strip())
    if not columns or not any(columns.values()):
        raise BladeError(f"{path}: expected a header and at least two station rows")
    return _columns_to_table(columns, radius_m, str(path))


def blade_from_config(blade: Mapping, radius_m: float, where: str) -> BladeTable:
    """The ``rotors[].blade`` entry: ``{table: path}`` or inline columns; ``where`` names it in errors."""
    if "table" in blade:
        if len(blade) != 1:
            raise BladeError(f"{where}: table: expected either a table file or inline columns, not both")
        return read_blade_csv(blade["table"], radius_m)
    return _columns_to_table(blade, radius_m, where)
