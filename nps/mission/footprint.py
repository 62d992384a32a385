"""Mission ground footprints: L_A(t), L_Amax, SEL per segment and mission, contour areas.

The mission's flight profile (nps.mission.trajectory) is flown with each segment's source hemisphere
and propagated (nps.mission.propagation) to a ground grid and named microphones on a reception-time
grid of ``record_s`` = 0.5 s. At every receiver:

* L_A(t_k): A-weighted level of the band levels at t_k (the steady level at the instant);
* L_Amax = max_k L_A(t_k); SEL = 10 log10(Σ_k 10^(L_A,k/10) Δt / 1 s) over the whole record
  (full exposure, as airport noise studies sum it; the certification SEL of nps.mission.certification
  is the 10-dB-down one of 14 CFR 36 Appendix J);
* per segment: the same over the records whose ray left the aircraft during that segment
  (every record has exactly one emitting segment, nps.mission.propagation), so the mission SEL is the
  energy sum of the segment SELs;
* at the named microphones also the band histories, PNLT(t_k) and EPNL
  (nps.mission.certification.microphone_histories), for the mission and per leg (the leg's records
  only, the others at the level floor). The grid gets no EPNL: the A36.4.3 tone correction of
  nps.noise.metrics takes ~0.2 ms per spectrum, minutes for a 15 000-receiver grid.

Contour area of a metric at level L: the number of grid points with metric ≥ L times the grid
cell area Δx Δy (each point stands for its cell; exact in the limit of fine grids, the error
is of the order of the contour length times half a cell).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np
import pandas as pd

from nps.mission.certification import microphone_histories, reception_times
from nps.mission.propagation import Ground, Hemisphere, Trajectory, propagate
from nps.mission.terrain import Terrain
from nps.noise.spectra import LEVEL_FLOOR_DB
from nps.mission.trajectory import FlightPath, atmospheres_along

RECORD_S = 0.5
CONTOUR_LEVELS_DB = (60.0, 65.0, 70.0, 75.0, 80.0)
RECEIVER_CHUNK = 512


class FootprintError(ValueError):
    """Bad footprint input (names the field and what was expected)."""


@dataclass(frozen=True)
class GroundGrid:
    """Receivers on a regular grid at ``height_m`` over the ground (E frame, m)."""

    x_range_m: tuple[float, float]
    y_range_m: tuple[float, float]
    spacing_m: float
    height_m: float = 1.2

    def __post_init__(self):
        for name in ("x_range_m", "y_range_m"):
            lo, hi = getattr(self, name)
            if not (np.isfinite(lo) and np.isfinite(hi) and hi > lo):
                raise FootprintError(f"grid.{name}: expected [low, high] with high > low, got {[lo, hi]}")
        if not (np.isfinite(self.spacing_m) and self.spacing_m > 0):
            raise FootprintError(f"grid.spacing_m: expected a positive spacing, got {self.spacing_m}")
        if not (np.isfinite(self.height_m) and self.height_m >= 0):
            raise FootprintError(f"grid.height_m: expected >= 0, got {self.height_m}")

    @property
    def x_m(self) -> np.ndarray:
        return self.x_range_m[0] + self.spacing_m * np.arange(int(np.floor((self.x_range_m[1] - self.x_range_m[0]) / self.spacing_m + 1e-9)) + 1)

    @property
    def y_m(self) -> np.ndarray:
        return self.y_range_m[0] + self.spacing_m * np.arange(int(np.floor((self.y_range_m[1] - self.y_range_m[0]) / self.spacing_m + 1e-9)) + 1)

    def points(self) -> np.ndarray:
        """(n_x·n_y, 3) receivers, x-major order."""
        xx, yy = np.meshgrid(self.x_m, self.y_m, indexing="ij")
        return np.stack([xx.ravel(), yy.ravel(), np.full(xx.size, self.height_m)], axis=-1)


def exposure_metrics(la_db: np.ndarray, segment: np.ndarray, n_segments: int, record_s: float = RECORD_S) -> dict:
    """L_Amax and SEL (dB) per receiver, for the mission and each segment (arrays (n_r,), (n_r, n_seg))."""
    energy = np.where(la_db > LEVEL_FLOOR_DB, 10.0 ** (la_db / 10.0), 0.0) * record_s
    floor = np.full(la_db.shape[0], LEVEL_FLOOR_DB)
    seg_sel = np.empty((la_db.shape[0], n_segments))
    seg_max = np.empty((la_db.shape[0], n_segments))
    for s in range(n_segments):
        mine = segment == s
        e = np.where(mine, energy, 0.0).sum(axis=1)
        seg_sel[:, s] = np.where(e > 0, 10.0 * np.log10(np.maximum(e, 1e-300)), floor)
        seg_max[:, s] = np.where(mine, la_db, LEVEL_FLOOR_DB).max(axis=1)
    total = energy.sum(axis=1)
    return {"sel_db": np.where(total > 0, 10.0 * np.log10(np.maximum(total, 1e-300)), floor),
            "lamax_db": la_db.max(axis=1), "segment_sel_db": seg_sel, "segment_lamax_db": seg_max}


def contour_areas(values_db: np.ndarray, cell_area_m2: float, levels_db=CONTOUR_LEVELS_DB) -> np.ndarray:
    """Area (m²) of the grid where ``values_db`` ≥ each level (points × cell area)."""
    v = np.asarray(values_db, float).ravel()
    return np.array([np.count_nonzero(v >= level) * cell_area_m2 for level in levels_db])


def touches_edge(values_db: np.ndarray, levels_db=CONTOUR_LEVELS_DB) -> np.ndarray:
    """For a grid (n_x, n_y) of levels: does the region ≥ each level reach the grid's edge (then
    its area is only a lower bound: the contour is not closed inside the grid)?"""
    v = np.asarray(values_db, float)
    edge = np.concatenate([v[0], v[-1], v[:, 0], v[:, -1]])
    return np.array([bool(np.any(edge >= level)) for level in levels_db])


@dataclass(frozen=True)
class Footprint:
    """Footprint of one aircraft's mission: grid metrics, microphone histories and metrics."""

    grid: pd.DataFrame          # one row per grid receiver
    microphones: pd.DataFrame   # one row per microphone
    histories: pd.DataFrame     # microphone × record: time_s, la_db, pnlt_db, leg (emitting leg, −1 none)
    areas: pd.DataFrame         # metric × level: area_km2, open (reaches the grid edge: a lower bound)
    segments: list[str]         # label of each leg: its mission segment id, or a path leg (columns leg{k}_* of ``grid``)


def mission_trajectory(path: FlightPath, hemispheres: Mapping[str, Hemisphere], delta_t_k: float,
                       relative_humidity_pct: float, absorption: bool = True) -> tuple[Trajectory, list]:
    """Trajectory of ``path`` with one hemisphere per distinct segment id (order of first use);
    ``absorption=False`` gives the legs no atmosphere (no air absorption)."""
    order = list(dict.fromkeys(path.segments))
    missing = [s for s in order if s not in hemispheres]
    if missing:
        raise FootprintError(f"hemispheres: no source hemisphere for segment(s) {missing} of the flight profile")
    index = np.array([order.index(s) for s in path.segments], dtype=np.int64)
    atmospheres = atmospheres_along(path, delta_t_k, relative_humidity_pct) if absorption else (None,) * len(path.legs)
    trajectory = Trajectory(path.knot_time_s, path.knot_position_m, index, atmospheres)
    return trajectory, [hemispheres[s] for s in order]


def mission_footprint(path: FlightPath, hemispheres: Mapping[str, Hemisphere], grid: GroundGrid,
                      microphones: Mapping[str, Sequence[float]], speed_of_sound_mps: float, delta_t_k: float = 0.0,
                      relative_humidity_pct: float = 70.0, ground: Ground = Ground(),
                      levels_db=CONTOUR_LEVELS_DB, absorption: bool = True) -> Footprint:
    """Fly ``path`` (legs in order) with the segments' ``hemispheres`` over ``grid`` and the named
    ``microphones`` (name → (x, y, z) in E); see the module doc for the metrics."""
    trajectory, hemis = mission_trajectory(path, hemispheres, delta_t_k, relative_humidity_pct, absorption)
    return trajectory_footprint(trajectory, hemis, np.arange(len(path.legs)), path.segments, grid, microphones,
                                speed_of_sound_mps, ground, levels_db)


def trajectory_footprint(trajectory: Trajectory, hemispheres: Sequence[Hemisphere], leg_of_segment: np.ndarray,
                         leg_labels: Sequence[str], grid: GroundGrid, microphones: Mapping[str, Sequence[float]],
                         speed_of_sound_mps: float, ground: Ground = Ground(),
                         levels_db=CONTOUR_LEVELS_DB, terrain: Terrain | None = None) -> Footprint:
    """Footprint of ``trajectory`` radiating ``hemispheres`` over ``grid`` and the named ``microphones``, the
    per-leg metrics (columns leg{k}_*) over the records emitted while trajectory segment s flew leg
    ``leg_of_segment[s]`` (legs 0 … len(leg_labels) − 1, labelled by ``leg_labels``); module doc. With a
    ``terrain``, the grid's and the microphones' heights are above the local ground (z = elevation + height in
    the tables) and the ground reflects at the elevation under each receiver."""
    leg_of_segment = np.asarray(leg_of_segment, dtype=np.int64)
    n_leg = len(leg_labels)
    if leg_of_segment.shape != np.shape(trajectory.hemisphere_index) or np.any(leg_of_segment < 0) or \
            np.any(leg_of_segment >= n_leg):
        raise FootprintError(f"leg_of_segment: expected one leg in 0..{n_leg - 1} per trajectory segment")
    leg_of = np.append(leg_of_segment, -1)  # index −1 (nothing received) stays −1

    points = grid.points()
    mic_names = list(microphones)
    mics = np.array([microphones[m] for m in mic_names], float).reshape(-1, 3)
    elevation = {"points": None, "mics": None}
    if terrain is not None:
        for name, where in (("points", points), ("mics", mics)):
            elevation[name] = terrain.elevation_m(where[:, 0], where[:, 1])
            where[:, 2] += elevation[name]
    times = reception_times(trajectory, np.vstack([points, mics]), speed_of_sound_mps, RECORD_S)
    parts = []
    for start in range(0, points.shape[0], RECEIVER_CHUNK):
        chunk = slice(start, start + RECEIVER_CHUNK)
        hist = propagate(hemispheres, trajectory, points[chunk], times, speed_of_sound_mps, ground,
                         ground_elevation_m=None if terrain is None else elevation["points"][chunk])
        parts.append(exposure_metrics(hist.la_db, leg_of[hist.segment], n_leg))
    grid_m = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    grid_table = pd.DataFrame({"x_m": points[:, 0], "y_m": points[:, 1], "z_m": points[:, 2],
                               "lamax_db": grid_m["lamax_db"], "sel_db": grid_m["sel_db"]})
    for k in range(n_leg):
        grid_table[f"leg{k}_lamax_db"] = grid_m["segment_lamax_db"][:, k]
        grid_table[f"leg{k}_sel_db"] = grid_m["segment_sel_db"][:, k]
    cell = grid.spacing_m**2
    shape = (grid.x_m.size, grid.y_m.size)
    areas = pd.DataFrame([{"metric": metric, "level_db": level, "area_km2": area / 1e6, "open": bool(is_open)}
                          for metric in ("sel_db", "lamax_db")
                          for level, area, is_open in zip(levels_db, contour_areas(grid_table[metric], cell, levels_db),
                                                          touches_edge(grid_table[metric].to_numpy().reshape(shape), levels_db))])
    mic_table = pd.DataFrame(columns=["microphone"])
    histories = pd.DataFrame(columns=["microphone", "time_s", "la_db", "pnlt_db", "leg"])
    if mics.size:
        hist = propagate(hemispheres, trajectory, mics, times, speed_of_sound_mps, ground, store_bands=True,
                         ground_elevation_m=elevation["mics"])
        leg = leg_of[hist.segment]
        table, pnlt_hist = microphone_histories(hist.bands_db, hist.band_numbers, RECORD_S)
        expo = exposure_metrics(hist.la_db, leg, n_leg)
        table["sel_db"] = expo["sel_db"]
        for k in range(n_leg):
            # the leg's own records (rays emitted during leg k), the others at the level floor
            leg_bands = np.where((leg == k)[..., None], hist.bands_db, LEVEL_FLOOR_DB)
            table[f"leg{k}_epnl_db"] = microphone_histories(leg_bands, hist.band_numbers, RECORD_S)[0]["epnl_db"]
            table[f"leg{k}_lamax_db"] = expo["segment_lamax_db"][:, k]
            table[f"leg{k}_sel_db"] = expo["segment_sel_db"][:, k]
        table.insert(0, "microphone", mic_names)
        for i, axis in enumerate("xyz"):
            table.insert(1 + i, f"{axis}_m", mics[:, i])
        mic_table = table
        histories = pd.DataFrame({
            "microphone": np.repeat(mic_names, times.size),
            "time_s": np.tile(times, len(mic_names)),
            "la_db": hist.la_db.ravel(),
            "pnlt_db": pnlt_hist.ravel(),
            "leg": leg.ravel().astype(np.int32),
        })
    return Footprint(grid_table, mic_table, histories, areas, list(leg_labels))
