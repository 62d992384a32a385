"""Builders shared by the PSU-WOPWOP runner tests (tests/unit/test_wopwop_run.py and
tests/validation/test_wopwop_public_writers.py): binary packing in the file layout, rigid rotor kinematics in
closed form, the independent reference (NPS's compact kernel fed with sources built here in numpy) and case
directories.

Nothing here imports nps.wopwop: the references must not share code with the runner under test. Units SI; the
rotor turns about +z (right-handed), a blade at azimuth ψ = Ω τ + ψ0 points along (cos ψ, sin ψ, 0).
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np

from nps.noise.acoustics import CompactSources, Observers, TimeGrid, radiate_arrays

RHO0_KG_M3, C0_M_S = 1.225, 340.294
GROUPS = ("thickness", "loading")  # the runner's output groups, in its order


# ------------------------------------------------------------------------------------- binary layout packing
def ints(*values: int) -> bytes:
    """Little-endian int32s."""
    return struct.pack(f"<{len(values)}i", *values)


def reals(*values: float) -> bytes:
    """Little-endian float32s."""
    return struct.pack(f"<{len(values)}f", *values)


def text(value: str, size: int, pad: bytes = b"\0") -> bytes:
    """A fixed-length ASCII string, padded with NULs (Python and Fortran writers) or spaces (Julia's ``st``)."""
    return value.encode("ascii").ljust(size, pad)


def blocks(array) -> bytes:
    """(n, k) values as k float32 blocks: all of column 0, then column 1, ... (the x, y, z blocks of a zone)."""
    return np.ascontiguousarray(np.asarray(array, dtype="<f4").T).tobytes()


# --------------------------------------------------------------------------------------------- case files
def write_case_dir(root: Path, case_text: str, folder: str = "case", files: dict | None = None) -> Path:
    """``root/cases.nam`` naming ``folder/case.nam`` (globalFolderName './folder/'), the case text and the
    binary ``files`` (name → bytes) inside ``folder``; returns the cases.nam path."""
    (root / folder).mkdir(parents=True, exist_ok=True)
    (root / "cases.nam").write_text(f"&casename\nglobalFolderName='./{folder}/'\ncaseNameFile='case.nam'\n/\n")
    (root / folder / "case.nam").write_text(case_text)
    for name, data in (files or {}).items():
        (root / folder / name).write_bytes(data)
    return root / "cases.nam"


def observer_grid(t_min_s: float, t_max_s: float, nt: int) -> TimeGrid:
    """PSU-WOPWOP's observer times t_i = tMin + i (tMax − tMin)/(nt − 1) as a TimeGrid."""
    return TimeGrid(t_min_s, (t_max_s - t_min_s) * nt / (nt - 1), nt)


# -------------------------------------------------------------------------------------- rigid rotor motion
def turn_z(vectors: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """(n_point, 3) or (n_point, n_tau, 3) vectors turned by ψ (n_tau,) about +z: (n_point, n_tau, 3)."""
    v = np.broadcast_to(vectors[:, None, :] if vectors.ndim == 2 else vectors, (vectors.shape[0], psi.size, 3))
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1], v[..., 2]], axis=-1)


def spin(points: np.ndarray, omega: float, tau: np.ndarray, phase: float = 0.0) -> np.ndarray:
    """Kinematics (4, n_point, n_tau, 3): position, velocity, acceleration, jerk of rotor-frame ``points``
    (n_point, 3) turning about +z at ``omega`` (rad/s), azimuth ψ = Ω τ + phase (closed form:
    d^k/dτ^k R(ψ) p = Ω^k R(ψ + kπ/2) (p_x, p_y, 0) for k >= 1)."""
    psi = omega * np.asarray(tau, dtype=float) + phase
    flat = points * np.array([1.0, 1.0, 0.0])
    out = [turn_z(points, psi)]
    out += [omega**k * turn_z(flat, psi + 0.5 * np.pi * k) for k in (1, 2, 3)]
    return np.stack(out)


def blade_loads(psi: np.ndarray, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Force on the blade per unit span (N/m) in the rotor frame (radial, tangential, axial) and its ψ-derivative,
    both (n_r, n_psi, 3): a drag (−tangential) and a lift with 1/rev and 2/rev content."""
    r, p = np.asarray(radii, dtype=float)[:, None], np.asarray(psi, dtype=float)[None, :]
    zero = 0.0 * r * p
    value = np.stack([zero, -3.0 * r**2 * (1.0 + 0.3 * np.sin(p)),
                      40.0 * r**2 * (1.0 + 0.2 * np.cos(p) + 0.1 * np.sin(2.0 * p))], axis=-1)
    rate = np.stack([zero, -0.9 * r**2 * np.cos(p), 40.0 * r**2 * (-0.2 * np.sin(p) + 0.2 * np.cos(2.0 * p))], axis=-1)
    return value, rate


def ground_loads(psi: np.ndarray, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`blade_loads` of a blade at azimuth ψ turned into the ground frame, and its ψ-derivative
    (d/dψ R(ψ) L(ψ) = R(ψ) L'(ψ) + R(ψ + π/2) (L_x, L_y, 0)), both (n_r, n_psi, 3)."""
    value, rate = blade_loads(psi, radii)
    psi = np.asarray(psi, dtype=float)
    return turn_z(value, psi), turn_z(rate, psi) + turn_z(value * np.array([1.0, 1.0, 0.0]), psi + 0.5 * np.pi)


# ----------------------------------------------------------------------------------------- the reference
def reference_pressure(kinematics: np.ndarray, tau: np.ndarray, grid: TimeGrid, observers_m: np.ndarray, *,
                       force: np.ndarray, force_rate: np.ndarray, period_s: float | None = None,
                       observer_velocity=None) -> np.ndarray:
    """(n_obs, 2, nt) thickness and loading of point forces built by the caller, radiated with
    :func:`nps.noise.acoustics.radiate_arrays` (periodic when ``period_s`` is set: ``tau`` one period, observers
    at rest or moving with ``observer_velocity``, which is then the frame velocity).

    ``kinematics`` (4, n_point, n_tau, 3) as :func:`spin`; ``force``/``force_rate`` (n_point, n_tau, 3): force on
    the fluid (N) and its rate, in the loading group (the thickness group stays zero)."""
    n_point = kinematics.shape[1]
    observers_m = np.atleast_2d(np.asarray(observers_m, dtype=float))
    velocity = np.zeros_like(observers_m)
    if observer_velocity is not None:
        velocity += np.asarray(observer_velocity, dtype=float)
    sources = CompactSources(
        np.asarray(tau, dtype=float), *(np.ascontiguousarray(k) for k in kinematics), np.ascontiguousarray(force),
        np.ascontiguousarray(force_rate), np.zeros(n_point), GROUPS, np.full(n_point, GROUPS.index("loading")),
        np.full(n_point, -1), period_s=period_s, frame_velocity_mps=None if period_s is None else velocity[0].copy())
    return radiate_arrays(sources, Observers(observers_m, velocity), grid, c0_mps=C0_M_S, rho0_kg_m3=RHO0_KG_M3)


def relative_error(result: np.ndarray, reference: np.ndarray) -> float:
    """Largest difference over the largest magnitude of the reference."""
    return float(np.abs(result - reference).max() / np.abs(reference).max())


def harmonic_leak(signal: np.ndarray, blades: int) -> float:
    """Energy of the harmonics k >= 1 that are not multiples of ``blades``, over the energy of those that are,
    for a signal sampled over whole periods (last axis)."""
    spectrum = np.abs(np.fft.rfft(signal, axis=-1)) ** 2
    k = np.arange(spectrum.shape[-1])
    return float(spectrum[..., (k > 0) & (k % blades != 0)].sum() / spectrum[..., (k > 0) & (k % blades == 0)].sum())
