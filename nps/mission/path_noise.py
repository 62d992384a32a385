"""Noise along a flight path: the time history flown as short chords, each radiating the blend of the
quasi-static states that bracket it (docs/reference/paths.md "Noise along the path", footprint.md §2).

Path samples (nps.mission.paths, the ``path`` stage's history): times t_i, positions X_i (mission frame E: x, y
horizontal, z height above flat ground), heading χ_i (from +x toward +y), flight-path angle γ_i, leg, and the
states that bracket the sample with the neighbour's weight w_i (nps.mission.path_states). Chord k flies from
sample k to sample k + 1 with constant velocity (nps.mission.propagation.Trajectory) and radiates the states of
sample k: (1 − w_k) L[state_k] + w_k L[neighbour_k] in dB.

Frames. A state's hemisphere is computed for its canonical flight (the speed along the effective flight-path
angle γ_e, with the normal and lateral load: nps.mission.path_states), in that flight's level heading frame G.
The rotors' state depends only on the speed and the specific force f in the path axes (quasi-static
equivalence), so the aircraft and its sound field sit in the sample's path axes as in the canonical flight's.
The canonical path axes at the sample's own γ_e are V̂_c = (cos γ_e, 0, sin γ_e), the upward normal
n̂_c = (−sin γ_e, 0, cos γ_e) and the starboard ŝ_c = (0, −1, 0) (the columns of C); the sample's in E are
V̂ = (cos γ cos χ, cos γ sin χ, sin γ), n̂ = (−sin γ cos χ, −sin γ sin χ, cos γ), ŝ = V̂ × n̂ (the columns of A).
A ray leaving in direction n (E) leaves the hemisphere in direction C Aᵀ n (``hemisphere_frames`` of the
trajectory): f has the same components in both. The sample's γ_e (not its lattice state's) keeps that exact
where the speed vanishes (every γ_e at hover is one state, a level hover whose thrust points along f); a state
differs from its samples by at most half a lattice spacing in γ_e. A steady leg (γ_e = γ, χ = 0) gives the identity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from nps.core.atmosphere import isa
from nps.mission.footprint import CONTOUR_LEVELS_DB, Footprint, FootprintError, GroundGrid, trajectory_footprint
from nps.mission.propagation import Ground, Hemisphere, Trajectory
from nps.mission.terrain import Terrain
from nps.noise.metrics import a_weighting_db
from nps.noise.spectra import third_octave_bands


@dataclass(frozen=True)
class PathSamples:
    """A sampled flight path (module doc): ``time_s`` (n,) strictly increasing; ``position_m`` (n, 3) in E;
    ``heading_rad`` χ, ``flight_path_rad`` γ and ``effective_flight_path_rad`` γ_e (n,); ``leg`` (n,) leg index;
    ``state`` and ``neighbour`` (n,) indices of the bracketing states; ``weight`` (n,) the neighbour's weight in
    [0, 1]."""

    time_s: np.ndarray
    position_m: np.ndarray
    heading_rad: np.ndarray
    flight_path_rad: np.ndarray
    effective_flight_path_rad: np.ndarray
    leg: np.ndarray
    state: np.ndarray
    neighbour: np.ndarray
    weight: np.ndarray

    def __post_init__(self):
        n = np.size(self.time_s)
        shapes = {"position_m": (n, 3), **{name: (n,) for name in ("heading_rad", "flight_path_rad", "effective_flight_path_rad",
                                                                     "leg", "state", "neighbour", "weight")}}
        for name, shape in shapes.items():
            value = np.asarray(getattr(self, name))
            if value.shape != shape or not np.all(np.isfinite(value)):
                raise FootprintError(f"path samples: {name} must be finite with shape {shape}, got {value.shape}")
        if n < 2:
            raise FootprintError("path samples: need at least two samples")


def path_axes(heading_rad, flight_path_rad) -> np.ndarray:
    """(..., 3, 3) path axes in E as columns (V̂, n̂, ŝ) for headings χ and flight-path angles γ (rad)."""
    ch, sh = np.cos(heading_rad), np.sin(heading_rad)
    cg, sg = np.cos(flight_path_rad), np.sin(flight_path_rad)
    along = np.stack([cg * ch, cg * sh, sg], axis=-1)
    normal = np.stack([-sg * ch, -sg * sh, cg], axis=-1)
    return np.stack([along, normal, np.cross(along, normal)], axis=-1)


def hemisphere_frames(samples: PathSamples) -> np.ndarray:
    """(n − 1, 3, 3) rotations E → the hemisphere frame of each chord (its state's and neighbour's): C Aᵀ with A
    the path axes of the chord's first sample and C the canonical ones at its γ_e (module doc)."""
    actual = path_axes(samples.heading_rad[:-1], samples.flight_path_rad[:-1])
    canonical = path_axes(np.zeros(actual.shape[0]), samples.effective_flight_path_rad[:-1])
    return np.einsum("kij,klj->kil", canonical, actual)


def path_trajectory(samples: PathSamples, n_states: int, delta_t_k: float, relative_humidity_pct: float,
                    absorption: bool = True) -> Trajectory:
    """The chords of ``samples`` as a :class:`~nps.mission.propagation.Trajectory` with the states' blend and
    frames (module doc); each chord absorbs with ISA + ΔT at its mean height (``absorption``)."""
    for name in ("state", "neighbour"):
        index = np.asarray(getattr(samples, name))
        if np.any(index < 0) or np.any(index >= n_states):
            raise FootprintError(f"path samples: {name} must index the {n_states} states")
    z = np.asarray(samples.position_m, float)[:, 2]
    atmospheres = tuple(isa(float(0.5 * (z[k] + z[k + 1])), delta_t_k, relative_humidity_pct) if absorption else None
                        for k in range(z.size - 1))
    return Trajectory(np.asarray(samples.time_s, float), np.asarray(samples.position_m, float),
                      np.asarray(samples.state[:-1], dtype=np.int64), atmospheres,
                      hemisphere_frames=hemisphere_frames(samples),
                      next_hemisphere_index=np.asarray(samples.neighbour[:-1], dtype=np.int64),
                      hemisphere_weight=np.asarray(samples.weight[:-1], float))


def path_footprint(samples: PathSamples, leg_labels: Sequence[str], hemispheres: Sequence[Hemisphere], grid: GroundGrid,
                   microphones: Mapping[str, Sequence[float]], speed_of_sound_mps: float, delta_t_k: float = 0.0,
                   relative_humidity_pct: float = 70.0, ground: Ground = Ground(), levels_db=CONTOUR_LEVELS_DB,
                   absorption: bool = True, terrain: Terrain | None = None) -> Footprint:
    """Footprint (grid L_Amax and SEL, microphone L_A(t), PNLT(t), EPNL, per-leg metrics, contour areas) of the
    aircraft flying ``samples`` with ``hemispheres[i]`` the source hemisphere of state i, receivers over an
    optional ``terrain`` (nps.mission.footprint.trajectory_footprint)."""
    trajectory = path_trajectory(samples, len(hemispheres), delta_t_k, relative_humidity_pct, absorption)
    return trajectory_footprint(trajectory, list(hemispheres), np.asarray(samples.leg[:-1], dtype=np.int64),
                                leg_labels, grid, microphones, speed_of_sound_mps, ground, levels_db, terrain)


def track_grid(position_m: np.ndarray, margin_m: float, spacing_m: float, height_m: float = 1.2) -> GroundGrid:
    """Receiver grid over the ground track's bounding box widened by ``margin_m``, corners on multiples of
    ``spacing_m`` (m, E)."""
    low = np.floor((np.min(position_m[:, :2], axis=0) - margin_m) / spacing_m) * spacing_m
    high = np.ceil((np.max(position_m[:, :2], axis=0) + margin_m) / spacing_m) * spacing_m
    return GroundGrid((float(low[0]), float(high[0])), (float(low[1]), float(high[1])), spacing_m, height_m)


def source_level_db(samples: PathSamples, hemispheres: Sequence[Hemisphere]) -> np.ndarray:
    """(n,) the loudest A-weighted level (dB(A)) of each sample's blended states over the hemisphere directions
    below the horizon, at the hemisphere radius: how loud the aircraft is toward the ground (BVI's forward-down
    lobe included)."""
    bands = third_octave_bands(hemispheres[0].band_numbers)
    weight = 10.0 ** (a_weighting_db(bands["center_hz"]) / 10.0)
    below = hemispheres[0].elevation_deg < 0.0
    level = np.array([10.0 * np.log10((10.0 ** (h.levels_db[below] / 10.0) @ weight).max()) for h in hemispheres])
    return (1.0 - samples.weight) * level[samples.state] + samples.weight * level[samples.neighbour]
