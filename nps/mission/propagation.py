"""Propagation of source hemispheres along a flight trajectory to fixed receivers (RNM method).

Frames and units. Mission frame E (m): x along the ground track's first heading from the trajectory's
first point, y to port, z height above flat ground (z = 0 is the ground). The aircraft's level
heading frame is E translated and turned by the heading χ about +z (χ = 0 on a straight track along +x), so a
hemisphere direction (map azimuth az, elevation el, docs/reference/conventions.md "Observer azimuth") is the unit
vector d = R_z(χ) (−cos az cos el, −sin az cos el, sin el) in E. Times in s, levels dB re 20 µPa, bands are the
1/3-octave band numbers n of nps.noise.spectra (f_m = 1000·10^(n/10) Hz).

Source. A :class:`Hemisphere` holds the band levels L_h(d, n) that observers moving with the
aircraft (velocity V_h, Mach vector M_h = V_h/c) hear at radius r_h from the source centre in
direction d, without absorption (docs/reference/footprint.md). For a compact source in uniform motion
the retarded solution at a point depends on the emission direction n (unit vector from the
source's emission position to the point) and on the emission distance r_e = c (t − τ) only
through p ∝ D(n)/r_e. A co-moving observer at r_h d heard a ray emitted at r_e,h = r_h/|n − M_h|
in direction n with d = (n − M_h)/|n − M_h| (from r_h d = r_e,h (n − M_h)). A fixed receiver whose
ray leaves the source in direction n at emission distance r_e therefore hears, per band,

    L(n_b') = L_h(d, n_b) − 20 log10(r_e |n − M_h| / r_h) − α(f_b') r_e + G_b'    (1)

(n_b a source band, n_b' = n_b + δ its received position):

* spherical spreading from the co-moving reference distance to r_e (the mean square over a
  received period is the co-moving one times (r_e,h / r_e)²: the Doppler compression of the
  waveform does not change its mean square);
* Doppler: the received frequency is f' = f/(1 − M·n) with the trajectory's Mach vector M at
  emission, a shift of δ = −10 log10(1 − M·n) band numbers; each band's energy, taken as
  uniform in log-frequency over the band, is split between the two receiver bands it overlaps
  (weights 1 − frac(δ), frac(δ)); energy shifted outside the band range is dropped;
* ISO 9613-1 absorption α (dB/m) with the atmosphere of the emitting segment over the straight
  ray r_e, at each source band's received frequency (the frequency in the air at rest, band
  number n + δ; α is taken at the mid-band frequencies and interpolated linearly in band
  number, exact when δ = 0);
* ground reflection G (dB) from an image source mirrored in z = 0, or over terrain in the horizontal plane
  at the ground's elevation under the receiver (locally flat ground, nps.mission.terrain) (same emission point and
  level for the reflected ray; ratio of path lengths a = r_1/r_2, path difference Δr = r_2 − r_1):
  band-averaged coherent sum G = 10 log10(1 + a²|Q|² + 2a|Q| ⟨cos(kΔr + φ_Q)⟩), the average of
  the cosine taken over the band's wavenumbers k ∈ [2πf_l/c, 2πf_u/c] in closed form. For a
  hard ground (Q = 1) a receiver on the ground (Δr = 0) gets +6.02 dB in every band and a raised
  receiver +6 dB at low frequency tending to +3 dB (1 + a²) in bands where kΔr ≫ 1 (incoherent
  limit). ``coherent=False`` takes the incoherent sum 1 + a²|Q|² in every band.
  Finite-impedance ground: normalised impedance Z of Delany & Bazley (1970) or Miki (1990) with
  flow resistivity σ, the spherical-wave reflection coefficient Q = R_p + (1 − R_p) F(w) with
  R_p = (sin ψ − 1/Z)/(sin ψ + 1/Z) (ψ the grazing angle), w = sqrt(i k r_2/2)(sin ψ + 1/Z) and
  F(w) = 1 + i sqrt(π) w exp(−w²) erfc(−i w) (e^{−iωt}; Attenborough, Li & Horoshenkov,
  Predicting Outdoor Sound, 2007, eqs. 2.39-2.42), evaluated at the band's mid frequency.

Emission time. The trajectory is a continuous piecewise-linear path X(τ) with constant velocity
per segment; for a receiver x and reception time t the emission time τ solves
|x − X(τ)| = c (t − τ). For subsonic flight g(τ) = t − τ − |x − X(τ)|/c decreases strictly, so
exactly one segment holds the root; each segment's root is the closed-form solution of the
quadratic for uniform motion, accepted when it lies inside that segment's time span. Segment
joins are thus continuous: every reception time maps to one emission time on the whole path,
with no gap or double count. Reception times whose emission lies before the first or after
the last trajectory point receive nothing (level floor).

Sphere interpolation: bilinear in (elevation, azimuth) of the levels in dB on the hemisphere's
regular grid, periodic in azimuth; a direction above the highest elevation (possible only for
near-horizontal rays in descent) takes the highest elevation's value.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nps.core.atmosphere import AtmosphereState, absorption_db_per_m
from nps.core.jit import kernel, kernel_array, prange
from nps.noise.metrics import a_weighting_db
from nps.noise.spectra import LEVEL_FLOOR_DB, third_octave_bands

GROUND_MODELS = ("hard", "delany_bazley", "miki", "none")
_DB_TO_NEPER = np.log(10.0) / 10.0  # 10^(L/10) = exp(_DB_TO_NEPER·L)
_INCOHERENT_SPAN = 400.0
"""Bands with (k_u − k_l)Δr above this take ⟨cos⟩ = 0 (|⟨cos⟩| ≤ 2/400: < 0.022 dB on a hard ground)."""


class PropagationError(ValueError):
    """Bad propagation input (names the field and what was expected)."""


@dataclass(frozen=True)
class Hemisphere:
    """Source band levels on a regular (elevation, azimuth) grid about the source centre.

    ``levels_db`` (n_el, n_az, n_bands): dB re 20 µPa at ``radius_m`` (m) heard by observers
    moving with the aircraft, without absorption; ``elevation_deg`` (n_el,) strictly ascending
    within [−90, 90]; ``azimuth_deg`` (n_az,) = j·360/n_az (map convention); ``band_numbers``
    (n_bands,) consecutive; ``velocity_mps`` (3,) the aircraft velocity (E frame: horizontal
    speed along +x, climb speed along +z) when the hemisphere was computed and
    ``speed_of_sound_mps`` the sound speed it was computed with.
    """

    elevation_deg: np.ndarray
    azimuth_deg: np.ndarray
    band_numbers: np.ndarray
    levels_db: np.ndarray
    radius_m: float
    velocity_mps: np.ndarray
    speed_of_sound_mps: float

    def __post_init__(self):
        el = np.asarray(self.elevation_deg, float)
        az = np.asarray(self.azimuth_deg, float)
        bands = np.asarray(self.band_numbers)
        lv = np.asarray(self.levels_db, float)
        if el.ndim != 1 or el.size < 2 or np.any(np.diff(el) <= 0) or el[0] < -90.0 or el[-1] > 90.0:
            raise PropagationError("hemisphere: elevation_deg must ascend strictly within [-90, 90] with >= 2 values")
        if az.ndim != 1 or az.size < 1 or not np.allclose(az, np.arange(az.size) * 360.0 / az.size, atol=1e-6):
            raise PropagationError("hemisphere: azimuth_deg must be j*360/n_az, j = 0..n_az-1")
        if bands.ndim != 1 or bands.size < 1 or np.any(np.diff(bands) != 1):
            raise PropagationError("hemisphere: band_numbers must be consecutive integers")
        if lv.shape != (el.size, az.size, bands.size) or not np.all(np.isfinite(lv)):
            raise PropagationError(f"hemisphere: levels_db must be finite with shape {(el.size, az.size, bands.size)}, got {lv.shape}")
        if not (np.isfinite(self.radius_m) and self.radius_m > 0):
            raise PropagationError(f"hemisphere: radius_m must be positive, got {self.radius_m}")
        v = np.asarray(self.velocity_mps, float)
        if v.shape != (3,) or not np.all(np.isfinite(v)) or abs(v[1]) > 0.0:
            raise PropagationError("hemisphere: velocity_mps must be (V_h, 0, V_c) in the heading frame")
        if not (np.isfinite(self.speed_of_sound_mps) and np.linalg.norm(v) < self.speed_of_sound_mps):
            raise PropagationError("hemisphere: speed_of_sound_mps must exceed the flight speed")


@dataclass(frozen=True)
class Ground:
    """Ground model: ``model`` in GROUND_MODELS; ``flow_resistivity_kPa_s_m2`` σ for the
    impedance models (grass ≈ 200, Attenborough et al. 2007 Table 5.1); ``coherent``: band-
    averaged coherent sum (True) or incoherent energy sum of direct and reflected rays."""

    model: str = "hard"
    flow_resistivity_kPa_s_m2: float = 200.0
    coherent: bool = True

    def __post_init__(self):
        if self.model not in GROUND_MODELS:
            raise PropagationError(f"ground.model must be one of {GROUND_MODELS}, got {self.model!r}")
        if not (np.isfinite(self.flow_resistivity_kPa_s_m2) and self.flow_resistivity_kPa_s_m2 > 0):
            raise PropagationError(f"ground.flow_resistivity_kPa_s_m2 must be positive, got {self.flow_resistivity_kPa_s_m2}")


@dataclass(frozen=True)
class Trajectory:
    """Continuous piecewise-linear flight path in the mission frame E.

    ``time_s`` (n_seg + 1,) strictly increasing knot times; ``position_m`` (n_seg + 1, 3) knot
    positions (z ≥ 0 height); segment k flies from knot k to knot k + 1 with constant velocity,
    radiates hemisphere ``hemisphere_index[k]`` and absorbs with ``atmospheres[k]``.

    Optional, for paths that turn and change state (nps.mission.path_noise): ``hemisphere_frames``
    (n_seg, 3, 3), for segment k the rotation F from E to the frame of its hemispheres (a ray leaving in
    direction n, E, leaves in direction F n of the hemisphere;
    None: the identity, the straight track along +x of a hemisphere computed for this very flight;
    :func:`turn_about_z` for a heading); ``next_hemisphere_index`` and ``hemisphere_weight`` (n_seg,)
    make segment k radiate the levels (1 − w_k) L[h_k] + w_k L[h'_k] (dB, each hemisphere read at its
    own co-moving direction and spread from its own radius; None: w = 0).
    """

    time_s: np.ndarray
    position_m: np.ndarray
    hemisphere_index: np.ndarray
    atmospheres: tuple[AtmosphereState | None, ...]
    hemisphere_frames: np.ndarray | None = None
    next_hemisphere_index: np.ndarray | None = None
    hemisphere_weight: np.ndarray | None = None

    def __post_init__(self):
        t = np.asarray(self.time_s, float)
        p = np.asarray(self.position_m, float)
        n = t.size - 1
        if t.ndim != 1 or n < 1 or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(t)):
            raise PropagationError("trajectory: time_s must have >= 2 strictly increasing finite knots")
        if p.shape != (n + 1, 3) or not np.all(np.isfinite(p)):
            raise PropagationError(f"trajectory: position_m must be finite with shape {(n + 1, 3)}, got {p.shape}")
        if np.any(p[:, 2] < 0.0):
            raise PropagationError("trajectory: the flight path goes below the ground (z < 0)")
        if np.asarray(self.hemisphere_index).shape != (n,) or len(self.atmospheres) != n:
            raise PropagationError(f"trajectory: need one hemisphere index and one atmosphere per segment ({n})")
        if self.hemisphere_frames is not None:
            f = np.asarray(self.hemisphere_frames, float)
            gram = np.einsum("...ji,...jk->...ik", f, f) if f.shape == (n, 3, 3) else None
            if gram is None or not np.all(np.isfinite(f)) or np.abs(gram - np.eye(3)).max() > 1e-9:
                raise PropagationError(f"trajectory: hemisphere_frames must hold one rotation matrix (3 x 3, "
                                       f"orthonormal) per segment, shape ({n}, 3, 3)")
        if (self.next_hemisphere_index is None) != (self.hemisphere_weight is None):
            raise PropagationError("trajectory: next_hemisphere_index and hemisphere_weight go together")
        if self.hemisphere_weight is not None:
            w = np.asarray(self.hemisphere_weight, float)
            if np.shape(self.next_hemisphere_index) != (n,) or w.shape != (n,) or not np.all((w >= 0.0) & (w <= 1.0)):
                raise PropagationError(f"trajectory: next_hemisphere_index and hemisphere_weight (within [0, 1]) "
                                       f"need one value per segment ({n})")

    @property
    def velocity_mps(self) -> np.ndarray:
        """(n_seg, 3) constant velocity of each segment (m/s, E)."""
        return np.diff(np.asarray(self.position_m, float), axis=0) / np.diff(np.asarray(self.time_s, float))[:, None]

    def position_at(self, time_s) -> np.ndarray:
        """Positions (..., 3) at times inside the knot span (linear between knots)."""
        t = np.asarray(time_s, float)
        return np.stack([np.interp(t, self.time_s, self.position_m[:, i]) for i in range(3)], axis=-1)


# ------------------------------------------------------------------------- ground impedance
def normalised_impedance(model: str, frequency_hz, flow_resistivity_kPa_s_m2: float) -> np.ndarray:
    """Normalised surface impedance Z/(ρc) of a locally reacting porous ground (e^{−iωt}).

    Delany & Bazley (1970): Z = 1 + 9.08 X^−0.75 + 11.9i X^−0.73; Miki (1990):
    Z = 1 + 5.50 X^−0.632 + 8.43i X^−0.632, with X = f/σ (f in Hz, σ in kPa·s/m²).
    """
    x = np.asarray(frequency_hz, float) / flow_resistivity_kPa_s_m2
    if model == "delany_bazley":
        return 1.0 + 9.08 * x**-0.75 + 11.9j * x**-0.73
    if model == "miki":
        return 1.0 + 5.50 * x**-0.632 + 8.43j * x**-0.632
    raise PropagationError(f"impedance model must be 'delany_bazley' or 'miki', got {model!r}")


@kernel(inline=True)
def _faddeeva_upper(z):
    """w(z) = exp(−z²) erfc(−iz) for Im z ≥ 0, Humlicek (1982) W4 (relative error < 1e-4)."""
    x = z.real
    y = z.imag
    t = complex(y, -x)
    s = abs(x) + y
    if s >= 15.0:
        return t * 0.5641896 / (0.5 + t * t)
    if s >= 5.5:
        u = t * t
        return t * (1.410474 + u * 0.5641896) / (0.75 + u * (3.0 + u))
    if y >= 0.195 * abs(x) - 0.176:
        return (16.4955 + t * (20.20933 + t * (11.96482 + t * (3.778987 + t * 0.5642236)))) / (
            16.4955 + t * (38.82363 + t * (39.27121 + t * (21.69274 + t * (6.699398 + t)))))
    u = t * t
    return np.exp(u) - t * (36183.31 - u * (3321.9905 - u * (1540.787 - u * (219.0313 - u * (35.76683 - u * (
        1.320522 - u * 0.56419)))))) / (32066.6 - u * (24322.84 - u * (9022.228 - u * (2186.181 - u * (364.2191 - u * (
            61.57037 - u * (1.841439 - u)))))))


@kernel(inline=True)
def _faddeeva(z):
    """w(z) for any z (w(z) = 2 exp(−z²) − w(−z) in the lower half plane)."""
    if z.imag >= 0.0:
        return _faddeeva_upper(z)
    return 2.0 * np.exp(-z * z) - _faddeeva_upper(-z)


@kernel(inline=True)
def _spherical_q(sin_psi, k_r2, beta):
    """Spherical-wave reflection coefficient Q for grazing sin ψ, k·r_2, admittance β = 1/Z."""
    rp = (sin_psi - beta) / (sin_psi + beta)
    w = np.sqrt(0.5j * k_r2) * (sin_psi + beta)
    f = 1.0 + 1j * np.sqrt(np.pi) * w * _faddeeva(w)
    return rp + (1.0 - rp) * f


@kernel
def _spherical_q_array(sin_psi, k_r2, beta):
    out = np.empty(sin_psi.size, dtype=np.complex128)
    for i in range(sin_psi.size):
        out[i] = _spherical_q(sin_psi[i], k_r2[i], beta[i])
    return out


def spherical_reflection_coefficient(sin_psi, k_r2, impedance) -> np.ndarray:
    """Q (complex) for grazing angles sin ψ, k r_2 (rad) and normalised impedances Z (broadcast)."""
    s, kr, z = np.broadcast_arrays(np.asarray(sin_psi, float), np.asarray(k_r2, float), np.asarray(impedance, complex))
    beta = (1.0 / z).astype(np.complex128)
    return _spherical_q_array(s.ravel().copy(), kr.ravel().copy(), beta.ravel().copy()).reshape(s.shape)


# --------------------------------------------------------------------------------- kernel
@kernel(inline=True)
def _emission(knot_t, knot_p, vel, x0, x1, x2, t, c):
    """(segment, τ) of the ray heard at (x, t); segment −1 when τ is outside the path."""
    n_seg = vel.shape[0]
    c2 = c * c
    for k in range(n_seg):
        v0 = vel[k, 0]
        v1 = vel[k, 1]
        v2 = vel[k, 2]
        # D = x − P_k + V t_k: x − X(τ) = D − V τ
        d0 = x0 - knot_p[k, 0] + v0 * knot_t[k]
        d1 = x1 - knot_p[k, 1] + v1 * knot_t[k]
        d2 = x2 - knot_p[k, 2] + v2 * knot_t[k]
        a = c2 - (v0 * v0 + v1 * v1 + v2 * v2)
        b = c2 * t - (d0 * v0 + d1 * v1 + d2 * v2)
        disc = b * b + a * (d0 * d0 + d1 * d1 + d2 * d2 - c2 * t * t)
        tau = (b - np.sqrt(max(disc, 0.0))) / a
        if (tau >= knot_t[k] or k == 0) and (tau <= knot_t[k + 1] or k == n_seg - 1):
            if tau < knot_t[0] or tau > knot_t[n_seg]:
                return -1, tau
            return k, tau
    return -1, t


@kernel(inline=True)
def _map_weights(h_el, n_az, h_daz, m0, m1, m2, mlen):
    """Bilinear weights (e0, we, a0, a1, wa) of the hemisphere direction d = m/|m| on the map grid."""
    n_el = h_el.size
    el = np.degrees(np.arcsin(min(1.0, max(-1.0, m2 / mlen))))
    az = np.degrees(np.arctan2(-m1, -m0))
    if az < 0.0:
        az += 360.0
    if el <= h_el[0]:
        e0 = 0
        we = 0.0
    elif el >= h_el[n_el - 1]:
        e0 = n_el - 2
        we = 1.0
    else:
        e0 = np.searchsorted(h_el, el) - 1
        we = (el - h_el[e0]) / (h_el[e0 + 1] - h_el[e0])
    fa = az / h_daz
    a0 = int(np.floor(fa))
    wa = fa - a0
    a0 = a0 % n_az
    a1 = (a0 + 1) % n_az
    return e0, we, a0, a1, wa


@kernel(inline=True)
def _hemisphere_reading(h_el, n_az, h_daz, h_radius, h_mach, h, n0, n1, n2, re):
    """Where hemisphere h hears the ray leaving in direction n (its frame) at emission distance r_e: the map
    weights of d = (n − M_h)/|n − M_h| (:func:`_map_weights`) and the spreading 20 log10(r_e |n − M_h| / r_h)."""
    m0 = n0 - h_mach[h, 0]
    m1 = n1 - h_mach[h, 1]
    m2 = n2 - h_mach[h, 2]
    mlen = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
    e0, we, a0, a1, wa = _map_weights(h_el, n_az, h_daz, m0, m1, m2, mlen)
    return e0, we, a0, a1, wa, 20.0 * np.log10(re * mlen / h_radius[h])


@kernel(inline=True)
def _map_level(h_levels, h, e0, we, a0, a1, wa, b):
    """Level (dB) of band b of hemisphere h at the bilinear weights of :func:`_map_weights`."""
    lo = (1.0 - wa) * h_levels[h, e0, a0, b] + wa * h_levels[h, e0, a1, b]
    hi = (1.0 - wa) * h_levels[h, e0 + 1, a0, b] + wa * h_levels[h, e0 + 1, a1, b]
    return (1.0 - we) * lo + we * hi


@kernel(inline=True)
def _received_bands(h_levels, h, e0, we, a0, a1, wa, spread, w2, h2, e0b, web, a0b, a1b, wab, spread2,
                    alpha, k, re, delta, src, out):
    """Mean-square band pressures ``out`` at the receiver before the ground: the map level less spreading and
    absorption (``src``, per source band), shifted by δ bands (Doppler) into the receiver bands. With ``w2`` > 0
    the level is (1 − w2)(map level of h − spread) + w2 (map level of h2 − spread2) (dB)."""
    n_b = src.size
    shift = int(np.floor(delta))
    frac = delta - shift
    for b in range(n_b):
        lev = _map_level(h_levels, h, e0, we, a0, a1, wa, b)
        heard = lev - spread
        if w2 > 0.0:
            lev2 = _map_level(h_levels, h2, e0b, web, a0b, a1b, wab, b)
            lev = (1.0 - w2) * lev + w2 * lev2
            heard = (1.0 - w2) * heard + w2 * (lev2 - spread2)
        # absorption at the band's received frequency (band number b + δ, α linear between bands)
        q = min(max(b + shift, 0), n_b - 2)
        wq = min(max(b + delta - q, 0.0), 1.0)
        att = (1.0 - wq) * alpha[k, q] + wq * alpha[k, q + 1]
        src[b] = np.exp(_DB_TO_NEPER * (heard - att * re)) if lev > LEVEL_FLOOR_DB else 0.0
        out[b] = 0.0
    for b in range(n_b):
        t0 = b + shift
        if 0 <= t0 < n_b:
            out[t0] += (1.0 - frac) * src[b]
        if 0 <= t0 + 1 < n_b:
            out[t0 + 1] += frac * src[b]


@kernel(inline=True)
def _ground_band_gain(b, ratio, dr, sin_psi, rr, sin_lo, k_edge, ground_kind, coherent, beta):
    """Ground gain 1 + a²|Q|² + 2a|Q|⟨cos(kΔr + φ_Q)⟩ of band b (module doc) and the updated sin(k_lo Δr) of the
    next band (the hard ground's band average reuses it)."""
    qa = 1.0
    qp = 0.0
    if ground_kind == 2:
        q = _spherical_q(sin_psi, 0.5 * (k_edge[b] + k_edge[b + 1]) * rr, beta[b])
        qa = abs(q)
        qp = np.arctan2(q.imag, q.real)
    mean_cos = 0.0
    span = (k_edge[b + 1] - k_edge[b]) * dr
    if not coherent:
        mean_cos = 0.0
    elif span <= 1e-9:
        mean_cos = np.cos(k_edge[b] * dr + qp)
    elif ground_kind == 2:
        mean_cos = (np.sin(k_edge[b + 1] * dr + qp) - np.sin(k_edge[b] * dr + qp)) / span
    elif span <= _INCOHERENT_SPAN:
        sin_hi = np.sin(k_edge[b + 1] * dr)
        mean_cos = (sin_hi - sin_lo) / span
        sin_lo = sin_hi
    return 1.0 + ratio * ratio * qa * qa + 2.0 * ratio * qa * mean_cos, sin_lo


@kernel(inline=True)
def _ground_and_weighting(out, x0, x1, x2, s0, s1, s2, re, k_edge, ground_kind, coherent, beta, a_weight,
                          store_bands, bands_out, i, j):
    """A-weighted mean square of the receiver bands ``out`` after the ground reflection (image source mirrored
    in z = 0: ``x2``, ``s2`` are the receiver's and the source's heights above the receiver's ground); the band
    levels (dB) into ``bands_out[i, j]`` when ``store_bands``."""
    floor_msp = 10.0 ** (LEVEL_FLOOR_DB / 10.0)
    ratio = 0.0
    dr = 0.0
    sin_psi = 1.0
    rr = re
    if ground_kind > 0:
        i0 = x0 - s0
        i1 = x1 - s1
        i2 = x2 + s2  # receiver to image source (source mirrored in z = 0)
        rr = np.sqrt(i0 * i0 + i1 * i1 + i2 * i2)
        ratio = re / rr
        dr = rr - re
        sin_psi = (x2 + s2) / rr
    sin_lo = np.sin(k_edge[0] * dr)
    la_ms = 0.0
    for b in range(out.size):
        ms = out[b]
        if ground_kind > 0:
            gain, sin_lo = _ground_band_gain(b, ratio, dr, sin_psi, rr, sin_lo, k_edge, ground_kind, coherent, beta)
            ms *= max(gain, 0.0)
        la_ms += ms * a_weight[b]
        if store_bands:
            bands_out[i, j, b] = 10.0 * np.log10(ms) if ms > floor_msp else LEVEL_FLOOR_DB
    return la_ms


@kernel(parallel=True)
def _propagate_kernel(rec, ground_z, times, c, knot_t, knot_p, vel, hemi_of_seg, hemi_next, hemi_weight, frames, turned, h_levels, h_el, h_daz, h_radius, h_mach,
                      alpha, a_weight, k_edge, ground_kind, coherent, beta, store_bands,
                      la_out, seg_out, bands_out):
    """Per receiver (parallel) and reception time: band levels (1), A-weighted level, segment.

    ``ground_z`` (n_r,) the ground's elevation under each receiver (m; the reflecting plane, 0 on flat ground).

    ``hemi_of_seg``, ``hemi_next``, ``hemi_weight`` (n_seg,) the segments' hemispheres and blend weights,
    ``frames`` (n_seg, 3, 3) the rotations E → hemisphere frame, applied where ``turned`` (n_seg,) (:class:`Trajectory`);
    ``h_levels`` (n_hemi, n_el, n_az, n_b) dB; ``alpha`` (n_seg, n_b) dB/m; ``beta`` (n_b,)
    normalised admittance for the impedance ground (ground_kind 2), ground_kind 1 = hard,
    0 = none. Outputs: ``la_out`` (n_r, n_t) dB(A), ``seg_out`` (n_r, n_t) emitting segment or
    −1, ``bands_out`` (n_r, n_t, n_b) dB when ``store_bands``.
    """
    n_r = rec.shape[0]
    n_t = times.size
    n_b = a_weight.size
    n_az = h_levels.shape[2]
    floor_msp = 10.0 ** (LEVEL_FLOOR_DB / 10.0)
    for i in prange(n_r):
        src = np.empty(n_b)
        out = np.empty(n_b)
        x0 = rec[i, 0]
        x1 = rec[i, 1]
        x2 = rec[i, 2]
        for j in range(n_t):
            k, tau = _emission(knot_t, knot_p, vel, x0, x1, x2, times[j], c)
            seg_out[i, j] = k
            if k < 0:
                la_out[i, j] = LEVEL_FLOOR_DB
                if store_bands:
                    for b in range(n_b):
                        bands_out[i, j, b] = LEVEL_FLOOR_DB
                continue
            dt_k = tau - knot_t[k]
            s0 = knot_p[k, 0] + vel[k, 0] * dt_k
            s1 = knot_p[k, 1] + vel[k, 1] * dt_k
            s2 = knot_p[k, 2] + vel[k, 2] * dt_k
            r0 = x0 - s0
            r1 = x1 - s1
            r2 = x2 - s2
            re = np.sqrt(r0 * r0 + r1 * r1 + r2 * r2)
            n0 = r0 / re
            n1 = r1 / re
            n2 = r2 / re
            # the ray's direction in the hemispheres' frame (F n where the segment's frame turns)
            hn0, hn1, hn2 = n0, n1, n2
            if turned[k]:
                hn0 = frames[k, 0, 0] * n0 + frames[k, 0, 1] * n1 + frames[k, 0, 2] * n2
                hn1 = frames[k, 1, 0] * n0 + frames[k, 1, 1] * n1 + frames[k, 1, 2] * n2
                hn2 = frames[k, 2, 0] * n0 + frames[k, 2, 1] * n1 + frames[k, 2, 2] * n2
            h = hemi_of_seg[k]
            e0, we, a0, a1, wa, spread = _hemisphere_reading(h_el, n_az, h_daz, h_radius, h_mach, h, hn0, hn1, hn2, re)
            w2 = hemi_weight[k]
            h2 = hemi_next[k]
            e0b, web, a0b, a1b, wab, spread2 = e0, we, a0, a1, wa, spread
            if w2 > 0.0:
                e0b, web, a0b, a1b, wab, spread2 = _hemisphere_reading(h_el, n_az, h_daz, h_radius, h_mach, h2, hn0,
                                                                        hn1, hn2, re)
            # Doppler: shift by δ bands with the trajectory's Mach number toward the receiver
            mr = (vel[k, 0] * n0 + vel[k, 1] * n1 + vel[k, 2] * n2) / c
            delta = -10.0 * np.log10(1.0 - mr)
            _received_bands(h_levels, h, e0, we, a0, a1, wa, spread, w2, h2, e0b, web, a0b, a1b, wab, spread2,
                            alpha, k, re, delta, src, out)
            la_ms = _ground_and_weighting(out, x0, x1, x2 - ground_z[i], s0, s1, s2 - ground_z[i], re, k_edge, ground_kind,
                                          coherent, beta, a_weight, store_bands, bands_out, i, j)
            la_out[i, j] = 10.0 * np.log10(la_ms) if la_ms > floor_msp else LEVEL_FLOOR_DB


@dataclass(frozen=True)
class ReceiverHistories:
    """Levels at the receivers on the reception-time grid ``time_s`` (n_t,).

    ``la_db`` (n_r, n_t) A-weighted level dB(A); ``segment`` (n_r, n_t) index of the emitting
    trajectory segment (−1: nothing received); ``bands_db`` (n_r, n_t, n_b) band levels for
    ``band_numbers`` or None.
    """

    time_s: np.ndarray
    la_db: np.ndarray
    segment: np.ndarray
    band_numbers: np.ndarray
    bands_db: np.ndarray | None


def _check_inputs(hemispheres, trajectory, receivers, speed_of_sound_mps):
    if not hemispheres:
        raise PropagationError("propagate: need at least one hemisphere")
    bands = np.asarray(hemispheres[0].band_numbers)
    shape = hemispheres[0].levels_db.shape
    for i, h in enumerate(hemispheres):
        if h.levels_db.shape != shape or np.any(np.asarray(h.band_numbers) != bands) or \
                np.any(h.elevation_deg != hemispheres[0].elevation_deg):
            raise PropagationError(f"hemispheres[{i}]: grid and bands must match hemispheres[0]")
    for field in ("hemisphere_index", "next_hemisphere_index"):
        idx = getattr(trajectory, field)
        if idx is not None and (np.any(np.asarray(idx) < 0) or np.any(np.asarray(idx) >= len(hemispheres))):
            raise PropagationError(f"trajectory.{field} must lie in 0..{len(hemispheres) - 1}")
    rec = np.asarray(receivers, float)
    if rec.ndim != 2 or rec.shape[1] != 3 or not np.all(np.isfinite(rec)) or np.any(rec[:, 2] < 0):
        raise PropagationError("receivers must be finite (n, 3) positions in E with z >= 0")
    if not (np.isfinite(speed_of_sound_mps) and speed_of_sound_mps > 0):
        raise PropagationError(f"speed_of_sound_mps must be positive, got {speed_of_sound_mps}")
    if np.any(np.linalg.norm(trajectory.velocity_mps, axis=1) >= 0.95 * speed_of_sound_mps):
        raise PropagationError("trajectory: flight speeds must stay below 0.95 of the sound speed")
    return bands, rec


def turn_about_z(heading_rad) -> np.ndarray:
    """(..., 3, 3) rotations E → the level heading frame of headings χ (rad, from +x toward +y): R_z(−χ)."""
    c, s = np.cos(heading_rad), np.sin(heading_rad)
    zero, one = np.zeros_like(c), np.ones_like(c)
    return np.stack([np.stack([c, s, zero], -1), np.stack([-s, c, zero], -1), np.stack([zero, zero, one], -1)], -2)


def _segment_states(trajectory: Trajectory) -> tuple[np.ndarray, ...]:
    """Per segment: the blended hemisphere's index and weight, the frames and whether they turn (kernel layout)."""
    n = np.asarray(trajectory.hemisphere_index).size
    if trajectory.hemisphere_weight is None:
        nxt, weight = np.zeros(n, dtype=np.int64), np.zeros(n)
    else:
        nxt = kernel_array(trajectory.next_hemisphere_index, dtype=np.int64)
        weight = kernel_array(trajectory.hemisphere_weight)
    if trajectory.hemisphere_frames is None:
        return nxt, weight, np.zeros((n, 3, 3)), np.zeros(n, dtype=np.bool_)
    frames = kernel_array(trajectory.hemisphere_frames)
    return nxt, weight, frames, np.any(frames != np.eye(3), axis=(1, 2))


def propagate(hemispheres, trajectory: Trajectory, receivers, time_s, speed_of_sound_mps: float,
              ground: Ground = Ground(), store_bands: bool = False, ground_elevation_m=None) -> ReceiverHistories:
    """Levels (eq. 1 of the module doc) at ``receivers`` (n_r, 3; E, m) at reception ``time_s``.

    ``hemispheres``: sequence of :class:`Hemisphere` on the same grid and bands, indexed by
    ``trajectory.hemisphere_index``; ``speed_of_sound_mps``: uniform sound speed for the ray
    times (straight rays, no refraction); ``ground_elevation_m`` (n_r,), optional: the elevation of the
    ground under each receiver (terrain, nps.mission.terrain; m, at most the receiver's z), where the ground
    reflects as a horizontal plane (default 0: flat ground z = 0).
    """
    bands, rec = _check_inputs(hemispheres, trajectory, receivers, speed_of_sound_mps)
    ground_z = np.zeros(rec.shape[0]) if ground_elevation_m is None else kernel_array(ground_elevation_m)
    if ground_z.shape != (rec.shape[0],) or not np.all(np.isfinite(ground_z)) or np.any(ground_z < 0.0) \
            or np.any(ground_z > rec[:, 2]):
        raise PropagationError("ground_elevation_m: expected one finite elevation >= 0 per receiver, at most its z")
    times = kernel_array(time_s)
    if times.ndim != 1 or times.size < 1 or not np.all(np.isfinite(times)):
        raise PropagationError("time_s must be a finite 1-D array")
    c = float(speed_of_sound_mps)
    info = third_octave_bands(bands)
    centres = info["center_hz"]
    alpha = np.array([np.zeros(bands.size) if a is None else
                      absorption_db_per_m(centres, a.temperature_k, a.relative_humidity_pct, a.pressure_pa)
                      for a in trajectory.atmospheres])
    a_weight = 10.0 ** (a_weighting_db(centres) / 10.0)
    k_edge = 2.0 * np.pi * np.append(info["lower_hz"], info["upper_hz"][-1]) / c
    ground_kind = {"none": 0, "hard": 1}.get(ground.model, 2)
    if ground_kind == 2:
        beta = 1.0 / normalised_impedance(ground.model, centres, ground.flow_resistivity_kPa_s_m2)
    else:
        beta = np.ones(bands.size, dtype=np.complex128)
    h_levels = kernel_array(np.stack([h.levels_db for h in hemispheres]))
    h_mach = np.array([np.asarray(h.velocity_mps, float) / h.speed_of_sound_mps for h in hemispheres])
    n_r, n_t = rec.shape[0], times.size
    la = np.empty((n_r, n_t))
    seg = np.empty((n_r, n_t), dtype=np.int64)
    out = np.empty((n_r, n_t, bands.size) if store_bands else (1, 1, 1))
    _propagate_kernel(kernel_array(rec), ground_z, times, c, kernel_array(trajectory.time_s),
                      kernel_array(trajectory.position_m), kernel_array(trajectory.velocity_mps),
                      kernel_array(trajectory.hemisphere_index, dtype=np.int64), *_segment_states(trajectory), h_levels,
                      kernel_array(hemispheres[0].elevation_deg),
                      360.0 / hemispheres[0].azimuth_deg.size, np.array([h.radius_m for h in hemispheres], float),
                      h_mach, alpha, a_weight, k_edge, ground_kind, bool(ground.coherent),
                      kernel_array(beta, dtype=np.complex128), bool(store_bands), la, seg, out)
    return ReceiverHistories(times, la, seg, bands.astype(np.int64), out if store_bands else None)
