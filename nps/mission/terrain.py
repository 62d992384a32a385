"""Terrain under the receivers: ground elevation on a rectangular grid, bilinear between its nodes.

Mission frame E (m): x, y horizontal, z up from the datum z = 0 of the flight path's heights (the path file's
heights are above the datum, docs/reference/paths.md "Terrain"). A receiver stands ``height_m`` above the local
ground, at z = elevation(x, y) + height; the ground reflection takes the ground as locally flat and horizontal at
the elevation under the receiver (the image source mirrored in z = elevation: nps.mission.propagation). The
elevation is bilinear in each cell of the grid, exact for a plane.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


class TerrainError(ValueError):
    """A terrain grid that is not a grid of finite elevations ≥ 0, or a point outside it."""


@dataclass(frozen=True)
class Terrain:
    """Ground elevation (m above the datum, ≥ 0) ``height_m`` (n_y, n_x) at the nodes ``x_m`` (n_x,) × ``y_m``
    (n_y,), both strictly increasing (m, E)."""

    x_m: np.ndarray
    y_m: np.ndarray
    height_m: np.ndarray

    def __post_init__(self):
        x, y, h = (np.asarray(v, float) for v in (self.x_m, self.y_m, self.height_m))
        if x.ndim != 1 or y.ndim != 1 or x.size < 2 or y.size < 2 or np.any(np.diff(x) <= 0) or np.any(np.diff(y) <= 0):
            raise TerrainError("x_m and y_m: expected strictly increasing lists of at least two nodes")
        if h.shape != (y.size, x.size):
            raise TerrainError(f"height_m: expected {y.size} rows (one per y_m) of {x.size} elevations (one per x_m), "
                               f"got shape {h.shape}")
        if not np.all(np.isfinite(h)) or np.any(h < 0.0):
            raise TerrainError("height_m: expected finite elevations >= 0 above the datum")
        object.__setattr__(self, "x_m", x)
        object.__setattr__(self, "y_m", y)
        object.__setattr__(self, "height_m", h)

    def covers(self, x_m, y_m) -> np.ndarray:
        """Whether each point (x, y) lies inside the grid (edges included)."""
        x, y = np.asarray(x_m, float), np.asarray(y_m, float)
        return (x >= self.x_m[0]) & (x <= self.x_m[-1]) & (y >= self.y_m[0]) & (y <= self.y_m[-1])

    def elevation_m(self, x_m, y_m) -> np.ndarray:
        """Bilinear ground elevation (m) at the points (x, y) (arrays of one shape), all inside the grid."""
        x, y = np.asarray(x_m, float), np.asarray(y_m, float)
        if not np.all(self.covers(x, y)):
            raise TerrainError(f"points outside the terrain grid x {self.x_m[0]:g}..{self.x_m[-1]:g} m, "
                               f"y {self.y_m[0]:g}..{self.y_m[-1]:g} m")
        i = np.clip(np.searchsorted(self.x_m, x, side="right") - 1, 0, self.x_m.size - 2)
        j = np.clip(np.searchsorted(self.y_m, y, side="right") - 1, 0, self.y_m.size - 2)
        u = (x - self.x_m[i]) / (self.x_m[i + 1] - self.x_m[i])
        v = (y - self.y_m[j]) / (self.y_m[j + 1] - self.y_m[j])
        h = self.height_m
        return ((1 - u) * (1 - v) * h[j, i] + u * (1 - v) * h[j, i + 1] + (1 - u) * v * h[j + 1, i]
                + u * v * h[j + 1, i + 1])

    @classmethod
    def from_config(cls, terrain: dict) -> "Terrain":
        """From a path file's validated ``receivers.terrain`` block (``x_m``, ``y_m``, ``height_m``)."""
        return cls(np.asarray(terrain["x_m"], float), np.asarray(terrain["y_m"], float),
                   np.asarray(terrain["height_m"], float))
