"""Rotor broadband self-noise: BPM blade elements as compact rotating sources, averaged over a revolution.

Every blade element of the loads disk table (docs/reference/conventions.md: ψ-major rows, hub frame H) is a
compact broadband source with the element's own chord, flow speed W = √(U_T² + U_P²) and angle of
attack ``alpha_eff_rad``; its 1/3-octave spectrum is RP-1218's (:mod:`nps.noise.broadband.bpm`). At each sampled
azimuth ψ the source sits at r·e_r (e_r = (cos β cos ψ, s cos β sin ψ, sin β), s the rotation
sign), its chordwise axis x_e is the direction of the air relative to the section
(−U_T e_t − U_P e_n)/W (leading to trailing edge; e_t the direction of motion, e_n the blade
normal), its spanwise axis y_e = e_r. The tip-vortex source sits at r = R on the outermost element
with W_tip = √((U_T,N + Ω(R − r_N))² + U_P,N²) and α'_TIP = (lift-slope ratio) · α_N (eq. 67).

Observers are fixed in the hub frame (they move with the hub, like wind-tunnel microphones or an
observer at a given position relative to a flying aircraft). Per observer, element and azimuth:

- geometry at the same instant (no retarded-time solve): r_e, Θ_e, Φ_e from the element to the
  observer; for the rotation average this is exact in hover and neglects the hub's displacement
  during propagation (order M_hub) in forward flight. The directivity factors D̄_h, D̄_l are
  averaged over each azimuth cell (``n_sub`` sub-azimuths): eq. (B1) jumps where x_e points at
  the observer, which near the rotor plane is a few degrees of azimuth wide;
- Doppler factor D = (1 − M_o·r̂)/(1 − M_s·r̂), M_s the element's and M_o the observer's velocity
  relative to the still air over c0: a 1/3-octave band received at f_c came from the source band at
  f_c/D (bands are proportional, so the BPM band level is evaluated at f_c/D); the convective
  amplification is in RP-1218's directivity functions (App. B, with the section Mach number U/c0);
- received mean-square pressure averaged over a revolution in reception time: weights
  dt_obs/dτ = 1/D over the azimuth samples of each element (Σ normalised), then summed over the
  elements and multiplied by the number of blades B (all blades see the same periodic disk table,
  so the time average of Σ_k over blades is B times the azimuth average of one blade).

With ``doppler=False``, D = 1 (no frequency shift, uniform weights): the convention of BPM.jl
and of the ITR comparison in AcousticAnalogies.jl. This is the approach of AcousticAnalogies.jl
(OpenMDAO, ``src/ccblade_helpers.jl`` and the broadband source elements: compact elements,
Doppler-shifted 1/3-octave bands, time-combined at the observer) and of ANOPP's BPM module
(blade segments, rotor-averaged spectra). Sections in reverse flow (U_T ≤ 0) radiate nothing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from nps.noise.broadband import bpm
from nps.core.atmosphere import AtmosphereState
from nps.core.jit import kernel, kernel_array, prange
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.noise.spectra import third_octave_bands

DISK_INPUT_COLUMNS = ("psi_rad", "r_m", "dr_m", "chord_m", "beta_rad", "ut_mps", "up_mps", "alpha_eff_rad")

SUTHERLAND_MU0_PA_S = 1.716e-5  # air viscosity at T0 = 273.15 K (White, Viscous Fluid Flow)
SUTHERLAND_T0_K = 273.15
SUTHERLAND_S_K = 110.4


def medium_from_atmosphere(state: AtmosphereState) -> bpm.Medium:
    """Speed of sound and kinematic viscosity ν = μ/ρ, μ from Sutherland's law (μ0, T0, S above)."""
    t = state.temperature_k
    mu = SUTHERLAND_MU0_PA_S * (t / SUTHERLAND_T0_K) ** 1.5 * (SUTHERLAND_T0_K + SUTHERLAND_S_K) / (t + SUTHERLAND_S_K)
    return bpm.Medium(state.speed_of_sound_mps, mu / state.density_kg_m3)


@dataclass(frozen=True)
class BladeEdge:
    """Blade properties BPM needs beyond the loads.

    ``te_thickness_m`` h and ``te_angle_rad`` Ψ of the trailing edge (h = 0: no bluntness noise),
    ``tripped`` boundary layer, one flag for the blade or a tuple with one flag per radial
    station of the disk table (True: TBL-TE with the tripped thicknesses and no LBL-VS; False:
    natural transition, LBL-VS included), ``tip_shape`` "flat" or "round", and
    ``tip_lift_slope_ratio`` of eq. (67) (None: from the blade aspect ratio R / mean chord,
    :func:`nps.noise.broadband.bpm.tip_lift_slope_ratio`).
    """

    te_thickness_m: float = 0.0
    te_angle_rad: float = float(np.radians(14.0))
    tripped: bool | tuple = True
    tip_shape: str = "flat"
    tip_lift_slope_ratio: float | None = None

    def __post_init__(self):
        if not (np.isfinite(self.te_thickness_m) and self.te_thickness_m >= 0.0):
            raise ValueError(f"BladeEdge.te_thickness_m must be finite and >= 0, got {self.te_thickness_m}")
        if not (np.isfinite(self.te_angle_rad) and self.te_angle_rad >= 0.0):
            raise ValueError(f"BladeEdge.te_angle_rad must be finite and >= 0, got {self.te_angle_rad}")
        if self.tip_shape not in bpm.TIP_SHAPES:
            raise ValueError(f"BladeEdge.tip_shape must be one of {bpm.TIP_SHAPES}, got {self.tip_shape!r}")
        if np.ndim(self.tripped) > 1:
            raise ValueError("BladeEdge.tripped must be one flag or one flag per radial station")
        ratio = self.tip_lift_slope_ratio
        if ratio is not None and not (np.isfinite(ratio) and ratio > 0.0):
            raise ValueError(f"BladeEdge.tip_lift_slope_ratio must be positive or None, got {ratio}")


@dataclass(frozen=True)
class SourceKinematics:
    """Compact sources in the hub frame H, arrays (n_az, n_src, 3).

    ``position_m`` source position, ``span_unit`` y_e, ``flow_unit`` x_e (direction of the air
    relative to the section, leading → trailing edge, normal to the span), ``velocity_mps``
    the source velocity relative to the still air.
    """

    position_m: np.ndarray
    span_unit: np.ndarray
    flow_unit: np.ndarray
    velocity_mps: np.ndarray


# eq. (B1), (B2) compiled: the one formula of nps.noise.broadband.bpm, inlined into the rotation average
_directivity_factors = kernel(inline=True)(bpm.directivity_factors)


@kernel(parallel=True)
def _radiation_kernel(position, span, flow, normal, velocity, mach, observers, observer_velocity, speed_of_sound,
                      sub_cos, sub_sin, doppler, high, low, distance, doppler_factor):
    """For every observer i (rows of ``observers``, H) and source (a, e) of the (n_az, n_src, 3) kinematics: D̄_h
    and D̄_l averaged over the sub-azimuths (the observer turned about z_H by the angles of cosine ``sub_cos`` and
    sine ``sub_sin``), the cell centre's distance r_e and Doppler factor D (1 without ``doppler``), written into
    the (n_obs, n_az, n_src) outputs. With r the source→observer vector and (x_e, y_e, z_e) the ``flow``,
    ``span`` and ``normal`` axes: cos Θ_e = r·x_e / |r| (clipped to [−1, 1]) and
    sin²Φ_e = (r·z_e)² / ((r·z_e)² + (r·y_e)²) (0 on the x_e axis, where Φ_e = atan2(0, 0) = 0)."""
    n_sub = sub_cos.size
    for i in prange(observers.shape[0]):
        ox, oy, oz = observers[i, 0], observers[i, 1], observers[i, 2]
        turned_x, turned_y = sub_cos * ox - sub_sin * oy, sub_sin * ox + sub_cos * oy
        sub_high, sub_low = np.empty(n_sub), np.empty(n_sub)
        for a in range(position.shape[0]):
            for e in range(position.shape[1]):
                px, py, pz = position[a, e, 0], position[a, e, 1], position[a, e, 2]
                fx, fy, fz = flow[a, e, 0], flow[a, e, 1], flow[a, e, 2]
                sx, sy, sz = span[a, e, 0], span[a, e, 1], span[a, e, 2]
                nx, ny, nz = normal[a, e, 0], normal[a, e, 1], normal[a, e, 2]
                m = mach[a, e]
                for j in range(n_sub):  # no dependence between sub-azimuths: vectorised
                    rx, ry, rz = turned_x[j] - px, turned_y[j] - py, oz - pz
                    n = rx * nx + ry * ny + rz * nz
                    s = rx * sx + ry * sy + rz * sz
                    across = n * n + s * s
                    cos_t = min(max((rx * fx + ry * fy + rz * fz) / np.sqrt(rx * rx + ry * ry + rz * rz), -1.0), 1.0)
                    sub_high[j], sub_low[j] = _directivity_factors(cos_t, n * n / across if across > 0.0 else 0.0, m)
                h = 0.0
                lo = 0.0
                for j in range(n_sub):  # the cell means, summed in order
                    h += sub_high[j]
                    lo += sub_low[j]
                rx, ry, rz = ox - px, oy - py, oz - pz
                r = np.sqrt(rx * rx + ry * ry + rz * rz)
                high[i, a, e], low[i, a, e], distance[i, a, e] = h / n_sub, lo / n_sub, r
                doppler_factor[i, a, e] = 1.0
                if doppler:  # Mach numbers of source and observer towards the observer
                    scale = r * speed_of_sound
                    m_src = (velocity[a, e, 0] * rx + velocity[a, e, 1] * ry + velocity[a, e, 2] * rz) / scale
                    m_obs = (observer_velocity[0] * rx + observer_velocity[1] * ry + observer_velocity[2] * rz) / scale
                    doppler_factor[i, a, e] = (1.0 - m_obs) / (1.0 - m_src)


def _radiation(kin: SourceKinematics, mach, observers_m: np.ndarray, observer_velocity_mps: np.ndarray,
               speed_of_sound_mps: float, doppler: bool, cell_rad: float,
               n_sub: int) -> tuple[bpm.Directivity, np.ndarray]:
    """Directivity and Doppler factor D of the (n_az, n_src) sources at observers ``observers_m`` (shape
    (..., 3), H): arrays of shape (...) + (n_az, n_src).

    D̄_h and D̄_l are averaged over ``n_sub`` sub-azimuths spread evenly over the azimuth cell
    (width ``cell_rad``, the source turned about z_H): near the rotor plane D̄_h of eq. (B1) jumps
    where the chordwise axis points at the observer (Θ_e → 180°, sin²Φ_e undefined), a feature a
    few degrees wide that point samples would catch or miss at random. Distance and D are the
    cell centre's (they vary smoothly). Compiled (:func:`_radiation_kernel`), parallel over observers.
    """
    obs = np.asarray(observers_m, dtype=float)
    n_az, n_src = np.shape(kin.position_m)[:2]
    shape = obs.shape[:-1] + (n_az, n_src)
    flat = np.ascontiguousarray(obs.reshape(-1, 3))
    # turning the source by +δ about z_H is turning the observer by −δ in the source's frame
    turn = -((np.arange(n_sub) + 0.5) / n_sub - 0.5) * cell_rad
    sources = [np.ascontiguousarray(v, dtype=float) for v in (
        kin.position_m, kin.span_unit, kin.flow_unit, np.cross(kin.flow_unit, kin.span_unit), kin.velocity_mps,
        np.broadcast_to(np.asarray(mach, dtype=float), (n_az, n_src)))]
    high, low, dist, d = (np.empty((flat.shape[0], n_az, n_src)) for _ in range(4))
    _radiation_kernel(*sources, flat, np.asarray(observer_velocity_mps, dtype=float), float(speed_of_sound_mps),
                      np.cos(turn), np.sin(turn), bool(doppler), high, low, dist, d)
    if np.any(dist <= 0.0):
        raise ValueError("an observer coincides with a blade element")
    return bpm.Directivity(dist.reshape(shape), high.reshape(shape), low.reshape(shape)), d.reshape(shape)


SPECTRUM_STEP_DECADES = 1.0 / 80.0
"""Log-frequency step of the source spectra that Doppler-shifted bands are interpolated from."""

OBSERVER_CHUNK = 128
"""Observers whose geometry (n_az × n_src arrays each) is held at once."""

OBSERVER_BLOCK = 16
"""Observers that :func:`_average_kernel` sums source by source (each source's spectra read once per block)."""


@kernel(parallel=True)
def _average_kernel(spectra, energy, use_low, high, low, weight, log_shift, active, log_bands, log_f0, doppler,
                    out):
    """Adds to out[g, i, q] the sum over the active sources (a, e), a major, of (S_g · F) · w: the reception-time
    average of band q of mechanism g at observer i.

    ``spectra`` (n_g, n_az, n_src, n): with ``doppler`` ln MSP on the grid log10 f = log_f0 +
    k·SPECTRUM_STEP_DECADES, S_g the exponential of its linear interpolation at log10 f = ``log_bands[q]`` −
    ``log_shift[i, a, e]`` (log10 D); without, S_g = ``spectra[g, a, e, q]`` (the band centres). F =
    ``low[i, a, e]`` where ``use_low[g, a, e]``, else ``high[i, a, e]`` (D̄/r_e²); w = ``weight[i, a, e]``.
    Sources (rows) without ``energy[g, a, e]`` add nothing. Parallel over blocks of OBSERVER_BLOCK observers.
    """
    n_obs, n_grid, n_q = high.shape[0], spectra.shape[3], log_bands.size
    for b in prange((n_obs + OBSERVER_BLOCK - 1) // OBSERVER_BLOCK):
        k = np.zeros(n_q, dtype=np.int64)
        w = np.zeros(n_q)
        value = np.zeros(n_q)
        for a in range(spectra.shape[1]):
            for e in range(spectra.shape[2]):
                if not active[a, e]:
                    continue
                for i in range(b * OBSERVER_BLOCK, min(n_obs, (b + 1) * OBSERVER_BLOCK)):
                    if doppler:
                        shift = log_shift[i, a, e]
                        for q in range(n_q):
                            x = ((log_bands[q] - shift) - log_f0) / SPECTRUM_STEP_DECADES
                            k[q] = min(max(int(np.floor(x)), 0), n_grid - 2)
                            w[q] = x - k[q]
                    for g in range(spectra.shape[0]):
                        if not energy[g, a, e]:
                            continue
                        row = spectra[g, a, e]
                        if doppler:
                            for q in range(n_q):
                                lo = row[k[q]]
                                value[q] = np.exp(lo + w[q] * (row[k[q] + 1] - lo))
                        else:
                            value[:] = row
                        factor = low[i, a, e] if use_low[g, a, e] else high[i, a, e]
                        weight_i, total = weight[i, a, e], out[g, i]
                        for q in range(n_q):
                            total[q] += value[q] * factor * weight_i


def _rotation_average(msp, use_low, kin: SourceKinematics, mach, active, observers, observer_velocity_mps,
                      band_center_hz, speed_of_sound_mps: float, doppler: bool, log_f0: float,
                      n_sub: int) -> np.ndarray:
    """Band MSP (Pa², (n_g, n_obs, n_band)) of one blade's sources at the observers, averaged over a revolution in
    reception time and summed over the sources (one blade: no factor B).

    ``msp`` (n_g, n_az, n_src, n): the sources' spectra at unit directivity and distance, with ``doppler`` on the
    grid log10 f = ``log_f0`` + k·SPECTRUM_STEP_DECADES, else at the band centres; ``use_low`` (n_g, n_az, n_src):
    where D̄_l applies instead of D̄_h; ``kin``, ``mach`` (n_az, n_src) and the radiating mask ``active`` of the
    sources; observers (n_obs, 3) in H moving at ``observer_velocity_mps``. OBSERVER_CHUNK observers at a time:
    :func:`_radiation`, then :func:`_average_kernel` with the weights 1/D normalised over each source's azimuths.
    """
    msp = np.broadcast_to(msp, np.shape(use_low) + np.shape(msp)[-1:])
    energy = np.any(msp > 0.0, axis=-1)
    spectra = (np.log(np.maximum(msp, 1e-300), out=np.zeros(msp.shape), where=energy[..., None]) if doppler
               else kernel_array(msp))
    log_bands = np.log10(band_center_hz)
    out = np.empty((msp.shape[0], len(observers), log_bands.size))
    for start in range(0, len(observers), OBSERVER_CHUNK):
        chunk = slice(start, start + OBSERVER_CHUNK)
        radiation, d = _radiation(kin, mach, observers[chunk], observer_velocity_mps, speed_of_sound_mps, doppler,
                                  2.0 * np.pi / msp.shape[1], n_sub)
        r2 = radiation.distance_m**2
        weight = 1.0 / d
        total = np.zeros((msp.shape[0], d.shape[0], log_bands.size))
        _average_kernel(spectra, energy, kernel_array(use_low, dtype=bool), radiation.high / r2, radiation.low / r2,
                        weight / np.sum(weight, axis=1, keepdims=True), np.log10(d),
                        kernel_array(active, dtype=bool), kernel_array(log_bands), log_f0, doppler, total)
        out[:, chunk] = total
    return out


def rotating_sources_msp(
    sections: bpm.Sections,
    kinematics: SourceKinematics,
    tip_kinematics: SourceKinematics,
    tip_chord_m: float,
    tip_speed_mps: np.ndarray,
    tip_alpha_rad: np.ndarray,
    tip_shape: str,
    observers_m,
    observer_velocity_mps,
    band_center_hz,
    n_blades: int,
    medium: bpm.Medium,
    *,
    active=None,
    doppler: bool = True,
    n_sub: int = 16,
) -> dict[str, np.ndarray]:
    """Rotation-averaged band MSP (Pa²) per observer, dict over bpm.COMPONENTS, each (n_obs, n_band).

    ``sections`` and ``kinematics`` hold one blade's elements at n_az azimuths (shape (n_az, n_el));
    ``tip_*`` the tip-vortex source (n_az, 1) with α'_TIP already including the lift-slope ratio;
    ``active`` (n_az, n_el) masks sources that radiate (default all); observers (n_obs, 3) in H
    with common velocity ``observer_velocity_mps`` (3,) relative to the still air. The n_az
    azimuths are equally spaced over a revolution; ``n_sub`` directivity sub-samples per azimuth
    cell (see :func:`_radiation`).

    Each source's band spectrum is computed once at unit directivity and distance (the level is
    proportional to D̄/r_e²: D̄_l for stalled separation, D̄_h otherwise). Without Doppler it is
    taken at the band centres; with Doppler on a log-frequency grid of SPECTRUM_STEP_DECADES
    covering every possible f_c/D and interpolated linearly in dB (≤ 0.02 dB from direct
    evaluation, tests/unit/test_bpm.py). Geometry and the weighted sum over azimuths and sources are
    compiled kernels, parallel over observers (:func:`_rotation_average`).
    """
    obs = np.atleast_2d(np.asarray(observers_m, dtype=float))
    if obs.ndim != 2 or obs.shape[1] != 3 or not np.all(np.isfinite(obs)):
        raise ValueError(f"observers_m must be finite with shape (n, 3), got {obs.shape}")
    f_c = np.asarray(band_center_hz, dtype=float)
    v_obs = np.asarray(observer_velocity_mps, dtype=float)
    active = np.ones(np.shape(kinematics.position_m)[:2], dtype=bool) if active is None else np.asarray(active)
    c0 = medium.speed_of_sound_mps
    mach = np.asarray(sections.speed_mps, dtype=float) / c0
    tip_mach = np.asarray(tip_speed_mps, dtype=float) / c0
    unit = bpm.Directivity(1.0, 1.0, 1.0)
    if doppler:
        m_src = max(np.max(np.linalg.norm(k.velocity_mps, axis=-1)) for k in (kinematics, tip_kinematics)) / c0
        m_obs = np.linalg.norm(v_obs) / c0
        if m_src >= 1.0:
            raise ValueError("a blade element moves supersonically: BPM does not apply")
        log_f0 = np.log10(np.min(f_c) * (1.0 - m_src) / (1.0 + m_obs)) - SPECTRUM_STEP_DECADES
        log_f1 = np.log10(np.max(f_c) * (1.0 + m_src) / (1.0 - m_obs)) + SPECTRUM_STEP_DECADES
        n_grid = int(np.ceil((log_f1 - log_f0) / SPECTRUM_STEP_DECADES)) + 1
        f_source = 10.0 ** (log_f0 + SPECTRUM_STEP_DECADES * np.arange(n_grid))
    else:
        f_source, log_f0 = f_c, 0.0
    section = bpm.section_msp(f_source, sections, unit, medium)
    stalled = bpm.is_stalled(sections, medium)
    use_low = np.zeros((len(bpm.COMPONENTS) - 1,) + np.shape(kinematics.position_m)[:2], dtype=bool)
    use_low[bpm.COMPONENTS.index("separation")] = stalled  # stalled separation radiates with D̄_l (eq. 28)
    groups = (  # (mechanisms, their source spectra stacked on axis 0, D̄_l rows, kinematics, Mach, radiating mask)
        (bpm.COMPONENTS[:-1], np.stack([section[name] for name in bpm.COMPONENTS[:-1]]), use_low, kinematics, mach,
         active),
        (bpm.COMPONENTS[-1:],
         bpm.tip_vortex_msp(f_source, tip_chord_m, tip_speed_mps, tip_alpha_rad, unit, medium, tip_shape)[None],
         np.zeros((1,) + tip_mach.shape, dtype=bool), tip_kinematics, tip_mach, np.ones(tip_mach.shape, dtype=bool)),
    )
    out = {}
    for names, msp, low_rows, kin, m, on in groups:
        total = _rotation_average(msp, low_rows, kin, m, on, obs, v_obs, f_c, c0, doppler, log_f0, n_sub)
        out.update((name, n_blades * total[j]) for j, name in enumerate(names))
    return out


DEFAULT_MAX_AZIMUTHS = 36


def _disk_arrays(disk: pd.DataFrame, n_azimuth: int | None) -> dict[str, np.ndarray]:
    missing = [c for c in DISK_INPUT_COLUMNS if c not in disk.columns]
    if missing:
        raise ValueError(f"disk table lacks column(s) {missing} (expected the loads disk table, docs/reference/conventions.md)")
    psi = disk["psi_rad"].to_numpy(dtype=float)
    n_psi = int(np.unique(psi).size)
    if n_psi < 1 or len(disk) % n_psi:
        raise ValueError("disk table is not a full ψ × r grid")
    n_r = len(disk) // n_psi
    if n_azimuth is None:
        n_azimuth = max(d for d in range(1, DEFAULT_MAX_AZIMUTHS + 1) if n_psi % d == 0)
    if n_azimuth < 1 or n_psi % n_azimuth:
        raise ValueError(f"n_azimuth={n_azimuth} must divide the disk table's {n_psi} azimuths")
    if not np.all(psi.reshape(n_psi, n_r) == psi.reshape(n_psi, n_r)[:, :1]):
        raise ValueError("disk table rows must be ψ-major (all radial stations of one azimuth together)")
    step = n_psi // n_azimuth
    arrays = {c: disk[c].to_numpy(dtype=float).reshape(n_psi, n_r)[::step] for c in DISK_INPUT_COLUMNS}
    for c, values in arrays.items():
        if not np.all(np.isfinite(values)):
            raise ValueError(f"disk table column {c} has non-finite values")
    if not (np.all(arrays["chord_m"] > 0.0) and np.all(arrays["dr_m"] > 0.0) and np.all(arrays["r_m"] > 0.0)):
        raise ValueError("disk table columns chord_m, dr_m and r_m must be positive")
    return arrays


def rotor_broadband_msp(
    disk: pd.DataFrame,
    geometry: RotorGeometry,
    operating: OperatingPoint,
    observers_h_m,
    medium: bpm.Medium,
    band_numbers,
    edge: BladeEdge = BladeEdge(),
    *,
    n_azimuth: int | None = None,
    doppler: bool = True,
) -> dict[str, np.ndarray]:
    """BPM broadband of one rotor: 1/3-octave band MSP (Pa²) per observer, (n_obs, n_band) arrays.

    ``disk``: loads disk table (``loads/{rotor}.parquet`` or ``bvi/{rotor}.parquet``, columns of
    docs/reference/conventions.md); ``geometry``: B, R, rotation sign; ``operating``: Ω and the advance ratios
    (the hub's velocity relative to the air is −(μ_x, μ_y, −μ_z)·ΩR in H); ``observers_h_m``
    (n_obs, 3) observer positions in the hub frame H, moving with the hub; ``medium``: c0 and ν
    (:func:`medium_from_atmosphere`); ``band_numbers``: base-10 1/3-octave band numbers of
    :mod:`nps.noise.spectra` (0 = 1 kHz); ``n_azimuth`` azimuth samples per revolution (must divide the
    table's; default the largest divisor ≤ DEFAULT_MAX_AZIMUTHS = 36); returns a dict over :data:`nps.noise.broadband.bpm.COMPONENTS` plus ``total``.
    """
    a = _disk_arrays(disk, n_azimuth)
    s = int(geometry.rotation_sign)
    omega = operating.omega_rad_s
    psi, beta, r = a["psi_rad"], a["beta_rad"], a["r_m"]
    cp, sp, cb, sb = np.cos(psi), np.sin(psi), np.cos(beta), np.sin(beta)
    e_r = np.stack([cb * cp, s * cb * sp, sb], axis=-1)
    e_t = np.stack([-sp, s * cp, np.zeros_like(psi)], axis=-1)
    e_n = np.stack([-sb * cp, -s * sb * sp, cb], axis=-1)
    ut, up = a["ut_mps"], a["up_mps"]
    speed = np.hypot(ut, up)
    tip_radius = geometry.radius_m
    hub_velocity = -np.array([operating.mu_x, operating.mu_y, -operating.mu_z]) * omega * tip_radius

    def kinematics(columns, radius, ut_, up_, w_):
        e_r_, e_t_, e_n_ = e_r[:, columns], e_t[:, columns], e_n[:, columns]
        flow = -(ut_[..., None] * e_t_ + up_[..., None] * e_n_) / w_[..., None]
        return SourceKinematics(radius[..., None] * e_r_, e_r_, flow, omega * radius[..., None] * e_t_ + hub_velocity)

    ratio = edge.tip_lift_slope_ratio
    if ratio is None:
        chord0, dr0 = a["chord_m"][0], a["dr_m"][0]
        ratio = bpm.tip_lift_slope_ratio(tip_radius / float(np.sum(chord0 * dr0) / np.sum(dr0)))
    tip = slice(r.shape[1] - 1, None)
    ut_tip = ut[:, tip] + omega * (tip_radius - r[:, tip])
    speed_tip = np.hypot(ut_tip, up[:, tip])
    tripped = np.asarray(edge.tripped, dtype=bool)
    if tripped.ndim == 1 and tripped.size != r.shape[1]:
        raise ValueError(f"BladeEdge.tripped has {tripped.size} flags for {r.shape[1]} radial stations")
    sections = bpm.Sections(a["chord_m"], a["dr_m"], speed, a["alpha_eff_rad"], edge.te_thickness_m,
                            edge.te_angle_rad, tripped)
    out = rotating_sources_msp(
        sections, kinematics(slice(None), r, ut, up, speed),
        kinematics(tip, np.full(ut_tip.shape, tip_radius), ut_tip, up[:, tip], speed_tip),
        float(a["chord_m"][0, -1]), speed_tip, ratio * a["alpha_eff_rad"][:, tip], edge.tip_shape, observers_h_m, hub_velocity,
        third_octave_bands(band_numbers)["center_hz"], geometry.n_blades, medium,
        active=ut > 0.0, doppler=doppler,
    )
    out["total"] = sum(out[name] for name in bpm.COMPONENTS)
    return out


def disk_outside_bpm_range(disk: pd.DataFrame, medium: bpm.Medium) -> np.ndarray:
    """Boolean per disk-table row: element outside RP-1218's data range (:func:`nps.noise.broadband.bpm.valid_range`)."""
    speed = np.hypot(disk["ut_mps"].to_numpy(dtype=float), disk["up_mps"].to_numpy(dtype=float))
    return bpm.valid_range(speed, disk["chord_m"].to_numpy(dtype=float), disk["alpha_eff_rad"].to_numpy(dtype=float),
                           medium)["any"]


def hub_frame_observers(trim_row, observers_g_m) -> np.ndarray:
    """Observer positions (n, 3) in a rotor's hub frame H from ground-frame positions at t = 0.

    x_H = R_GHᵀ (x_G − hub_G), with the hub position ``hub_*_m`` and the rotation ``r_gh_ij`` of the
    rotor's trim row (docs/reference/conventions.md).
    """
    hub = np.array([float(trim_row[f"hub_{c}_m"]) for c in "xyz"])
    r_gh = np.array([[float(trim_row[f"r_gh_{i}{j}"]) for j in range(3)] for i in range(3)])
    return (np.asarray(observers_g_m, dtype=float) - hub) @ r_gh


def trimmed_rotor_broadband_msp(disk: pd.DataFrame, rotor_config, trim_row, observers_g_m, medium: bpm.Medium,
                                band_numbers, edge: BladeEdge = BladeEdge()) -> np.ndarray:
    """Total BPM band MSP (Pa², (n_obs, n_band)) of one trimmed rotor of an aircraft at observers given in G.

    ``rotor_config``: the rotor's validated aircraft-configuration entry (B, R, rotation sense);
    ``trim_row``: its trim-artifact row (Ω, advance ratios, hub and frame at t = 0); observers at their
    t = 0 positions, taken as moving with the hub (exact for the observer sets that move with the
    aircraft; for observers fixed on the ground the geometry of t = 0 is used, as Pegg's model does).
    :func:`rotor_broadband_msp` with its defaults (Doppler on, ≤ 36 azimuths).
    """
    return rotor_broadband_msp(disk, RotorGeometry.from_config(rotor_config), OperatingPoint.from_trim_row(trim_row),
                               hub_frame_observers(trim_row, observers_g_m), medium, band_numbers, edge)["total"]
