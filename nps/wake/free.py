"""Free-vortex tip wake of all rotors of an aircraft, relaxed to the periodic state.

Equations, constants and their sources: ``docs/reference/wake_bvi.md`` ("Free-vortex wake").

Unknowns. For every rotor q, the tip vortex trailed by blade 0 is stored as node positions
X_q[i, j] in the rotor's ccw-equivalent hub frame H'_q (metres, :mod:`nps.wake.prescribed`): blade 0 at
azimuth ψ_i = iΔ, wake age φ_j = jΔ, Δ = 2π/N (``FreeWakeModel.steps_per_rev``), j = 0…J
(J = revolutions · N). Blade k's vortex at time t is blade 0's at ψ + 2πk/B (identical blades,
periodic flight). Node j = 0 is the flapped blade tip (release radius r_r). X_q is written
as the Beddoes geometry plus a distortion, X = X_Beddoes + D; D = 0 is the prescribed wake,
the initial guess, so that the first iterate gives exactly today's Beddoes result.

Kinematics. In the frame moving with the aircraft every node moves with the local flow:

    Ω_q (∂X/∂ψ + ∂X/∂φ) = V_∞,q + Σ_{rotors p} [Σ_{blades} V_BS(X; tip and bound vortex of p)
                                                 + V_rings(X; far-wake continuation of p)]

V_∞,q = Ω_q R_q (μ_x, s μ_y, −μ_z) (NPS signs, H'_q), V_BS the Biot–Savart velocity of
straight segments with a Vatistas core (:func:`nps.wake.vortex.segment_velocity`); a blade's bound vortex
runs from the hub centre to its tip node (horseshoe with the tip vortex). Rotor p's wake enters
rotor q's equations at the same time t = ψ_i/Ω_q, i.e. at p's azimuth Ω_p t (blade 0 of every
rotor is at ψ = 0 at t = 0, as in :class:`nps.rotor.geometry.RotorMotion`); p's distortion is
interpolated linearly (periodic) in ψ and linearly in φ.

Far wake: the free wake is continued by ``far_revolutions`` turns convected rigidly with the
mean velocity of the last free turn, X[i, J+m] = X[i−m, J] + m Δt V̄_J (Δt = Δ/Ω, V̄_J the
mean over ψ of V[·, J]), so that the old, rolled-up wake cannot wander. Beyond it the wake
continues to infinity as a semi-infinite vortex cylinder (:func:`_continuation_rings`,
``continuation_radii``) with the radius and centre of the last turn, convected with the free
stream plus the momentum-theory velocity of its own circulation, integrated with vortex rings
parallel to the disk. It enters the node kinematics only (a truncated helix induces half the
far value at its end; a hover wake needs the downwash of the whole slipstream below). Off by
default: it moves the HART-II results that depend on the wake's truncation (docs).

Discretisation (Bagai & Leishman 1995, five-point central difference about (i−½, j−½), with
Δψ = Δφ the ψ and φ differences combine into a march along the characteristic i − j):

    X[i, j] = X[i−1, j−1] + (Δ/Ω) · ¼ (V[i, j] + V[i−1, j] + V[i, j−1] + V[i−1, j−1])

marched in j (pseudo-implicit: X[i−1, j−1] is already the new value), i periodic.
Predictor–corrector per iteration n (PIPC): the predictor uses velocities V⁽ⁿ⁻¹⁾ of the last
geometry; the corrector marches again with ½(V⁽ⁿ⁻¹⁾ + V(X̃)) of the last and the predicted
geometry. Stabilising scheme: under-relaxation X⁽ⁿ⁾ = X⁽ⁿ⁻¹⁾ + ω (X_c − X⁽ⁿ⁻¹⁾)
(``relaxation`` ω) and a core floor of the node kinematics (the core smooths close
vortex–vortex encounters that the straight segments of the coarse grid cannot resolve). Converged when max |X⁽ⁿ⁾ − X⁽ⁿ⁻¹⁾| < ``tolerance_radius_fraction`` · R for
every rotor; non-finite nodes or no convergence raise :class:`FreeWakeError`.

Vortices (:class:`nps.wake.vortex.VortexModel`). Node kinematics: ``FreeWakeModel.vortex``, point
vortices with r_c² = r_c0² + 4 α δ ν φ/Ω, δ = 1 + a₁ Γ/ν (Squire / Bhagwat–Leishman) and
r_c0 = max(HART-II PIV core, floor) (``FreeWakeModel.kinematics_vortex``); blade loads: the
lifting-line vortex of the Beddoes model, ``WakeModel.vortex`` (c/2, chordwise averaging; docs).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Mapping, Sequence

import numpy as np

from nps.core import periods
from nps.core.jit import kernel, prange
from nps.wake import prescribed as wake
from nps.wake.vortex import (POINT_VORTEX_PROFILE, VortexModel, add_polyline_velocity, core_radius, profile_row,
                              segment_velocity, structure_row)

# r_c0 / c of a young tip vortex: HART-II PIV (van der Wall & Richard 2006; Yu et al. 2002),
# core radii of ≈ 0.14 c for the young advancing- and retreating-side vortices.
HART_II_CORE_RADIUS_CHORDS = 0.14
# The physical tip vortex of the node kinematics: the HART-II core, growing with age (Squire /
# Bhagwat–Leishman), a point vortex.
FREE_WAKE_VORTEX = VortexModel(core_radius_chords=HART_II_CORE_RADIUS_CHORDS, core_growth=True, vortex_structure="point")
# Rotors are coupled when one's far-field velocity estimate at the other reaches this fraction
# of the other's mean induced velocity: the rotor trim's relative thrust tolerance
# (docs/reference/wake_bvi.md, "Far-apart rotors").
COUPLING_THRESHOLD = 1e-3


class FreeWakeError(RuntimeError):
    """The free-wake relaxation diverged, produced non-finite nodes or did not converge."""


@dataclass(frozen=True)
class FreeWakeModel:
    """Parameters of the free-wake relaxation (SI; docs/reference/wake_bvi.md).

    ``steps_per_rev`` N: relaxation grid Δψ = Δφ = 2π/N; ``revolutions``: free (relaxed) wake
    age; ``far_revolutions``: rigid far wake after it; ``continuation_radii``: length (in radii
    R of the source rotor) of the semi-infinite vortex-cylinder continuation beyond the far wake
    in the node kinematics (0, the default: none; docs for why); ``vortex``: the physical tip
    vortex of the node kinematics (:class:`nps.wake.vortex.VortexModel`, a point vortex; its
    ``core_radius_chords`` is the initial physical core r_c0/c); ``core_floor_chords``: lower
    bound (> 0) of r_c0/c in the node kinematics (the resolution of the straight-segment wake on
    the relaxation grid; docs); ``relaxation`` ω in (0, 1]; ``tolerance_radius_fraction``:
    convergence when the largest node change between two iterations is below this × R;
    ``max_iterations``; ``far_group_deg`` and ``far_group_distance``: in the blade-load
    evaluation another rotor's vortex is summed in groups of this many degrees of wake age, a
    group farther than ``far_group_distance`` × its half-extent from the blade station counting
    as its chord segment (0: every segment; docs "Far-field grouping"). ``common_period``: rotors of
    a coupled group turning at different speeds are relaxed over their common period
    (:func:`nps.core.periods.common_period` with ``period_tolerance`` and ``max_period_revolutions``;
    docs "Common period"); off: each rotor's wake is periodic in its own revolution. Bounds as in the
    config schema (``wake.free``).
    """

    steps_per_rev: int = 36
    revolutions: float = 1.5
    far_revolutions: float = 1.0
    continuation_radii: float = 0.0
    vortex: VortexModel = FREE_WAKE_VORTEX
    core_floor_chords: float = 1.0
    relaxation: float = 0.5
    tolerance_radius_fraction: float = 0.01
    max_iterations: int = 60
    far_group_deg: float = 8.0
    far_group_distance: float = 4.0
    common_period: bool = False
    period_tolerance: float = periods.DEFAULT_TOLERANCE
    max_period_revolutions: int = periods.DEFAULT_MAX_REVOLUTIONS

    def __post_init__(self):
        checks = {
            "steps_per_rev": self.steps_per_rev >= 8,
            "revolutions": self.revolutions > 0.0,
            "far_revolutions": self.far_revolutions >= 0.0,
            "continuation_radii": self.continuation_radii >= 0.0,
            "vortex": self.vortex.vortex_structure == "point",
            "core_floor_chords": self.core_floor_chords > 0.0,
            "relaxation": 0.0 < self.relaxation <= 1.0,
            "tolerance_radius_fraction": self.tolerance_radius_fraction > 0.0,
            "max_iterations": self.max_iterations >= 1,
            "far_group_deg": 0.0 <= self.far_group_deg <= 90.0,
            "far_group_distance": self.far_group_distance >= 2.0,
            "period_tolerance": 0.0 <= self.period_tolerance <= 0.05,
            "max_period_revolutions": 1 <= self.max_period_revolutions <= 64,
        }
        bad = [name for name, ok in checks.items() if not ok]
        if bad:
            raise ValueError(f"FreeWakeModel: invalid {bad} in {self}")

    @classmethod
    def from_config(cls, block: Mapping | None) -> "FreeWakeModel":
        """From the optional config ``wake.free`` mapping: the relaxation's field names and the
        vortex's (``core_radius_chords``, ``core_growth``, ``vatistas_n``, …; the schema gives no
        defaults there, absent keys keep this class's and :data:`FREE_WAKE_VORTEX`'s). Unknown
        keys are an error naming them."""
        block = dict(block or {})
        own = set(cls.__dataclass_fields__) - {"vortex"}
        of_vortex = set(VortexModel.__dataclass_fields__) - {"vortex_structure"}
        unknown = sorted(set(block) - own - of_vortex)
        if unknown:
            raise ValueError(f"FreeWakeModel: unknown field(s) {unknown}; expected some of {sorted(own | of_vortex)}")
        vortex = replace(FREE_WAKE_VORTEX, **{key: block.pop(key) for key in sorted(of_vortex & set(block))})
        return cls(vortex=vortex, **block)

    @property
    def kinematics_vortex(self) -> VortexModel:
        """The vortex of the node kinematics: ``vortex`` with r_c0 = max(physical core, floor)."""
        return replace(self.vortex, core_radius_chords=max(self.vortex.core_radius_chords, self.core_floor_chords))

    @property
    def n_age(self) -> int:
        """Free (relaxed) age steps J."""
        return int(round(self.revolutions * self.steps_per_rev))

    @property
    def n_far(self) -> int:
        """Far-wake age steps appended after the free wake."""
        return int(round(self.far_revolutions * self.steps_per_rev))

    @property
    def step_rad(self) -> float:
        return 2.0 * math.pi / self.steps_per_rev


@dataclass(frozen=True)
class RotorPlacement:
    """One rotor of the aircraft: its wake state and where it sits.

    ``hub_position_m`` (3,) in the aircraft-fixed frame with G axes (``trim.parquet`` hub at
    t = 0), ``r_gh`` (3, 3) takes H components to G components; ``phase_rad``: the azimuth of blade 0
    at t = 0 (the rotor's own sense, ``rotors[].phase_deg``), which places the rotors' blades relative to
    one another (blade 0 at ψ = Ω t + phase_rad).
    """

    name: str
    state: wake.WakeState
    hub_position_m: np.ndarray
    r_gh: np.ndarray
    phase_rad: float = 0.0

    def __post_init__(self):
        hub = np.asarray(self.hub_position_m, dtype=float)
        r_gh = np.asarray(self.r_gh, dtype=float)
        if hub.shape != (3,) or not np.isfinite(hub).all():
            raise ValueError(f"rotor '{self.name}': hub_position_m: expected 3 finite numbers, got {self.hub_position_m!r}")
        if r_gh.shape != (3, 3) or not np.allclose(r_gh @ r_gh.T, np.eye(3), atol=1e-6):
            raise ValueError(f"rotor '{self.name}': r_gh: expected a 3 x 3 rotation matrix, got {self.r_gh!r}")
        if not math.isfinite(self.phase_rad):
            raise ValueError(f"rotor '{self.name}': phase_rad: expected a finite azimuth, got {self.phase_rad!r}")

    @property
    def to_common(self) -> np.ndarray:
        """Rotation H' → G: R_GH M_s (M_s = diag(1, s, 1))."""
        return np.asarray(self.r_gh, dtype=float) @ np.diag([1.0, float(self.state.rotation_sign), 1.0])

    @property
    def free_stream_hp_mps(self) -> np.ndarray:
        """Free stream in H' (m/s): Ω R (μ_x, s μ_y, −μ_z)."""
        s = self.state
        return s.omega_rad_s * s.radius_m * np.array([s.mu_x, s.rotation_sign * s.mu_y, -s.mu_z])


@dataclass(frozen=True)
class FreeWakeSolution:
    """Converged free wake: distortion (n_rotors, N, J+1, 3) from the Beddoes geometry (m, each
    rotor's H'), on ψ_i = iΔ, φ_j = jΔ; ``residual_history`` (iterations,) max |ΔX|/R (of the
    coupled group that needed the most iterations); ``groups``: the coupled groups of rotor
    indices (:func:`coupled_groups`), each relaxed on its own (None: all rotors one group);
    ``timing``: the common period of the groups relaxed over one (:class:`WakeTiming`; None: every
    rotor periodic in its own revolution, the distortion (n_rotors, N, J+1, 3)). With a timing rotor q's
    table holds m_q N rows (ψ of blade 0 over its m_q revolutions in the period), the array is padded
    to the longest."""

    rotors: tuple[RotorPlacement, ...]
    beddoes: wake.WakeModel
    model: FreeWakeModel
    distortion_m: np.ndarray
    iterations: int
    residual_history: np.ndarray
    groups: tuple[tuple[int, ...], ...] | None = None
    timing: "WakeTiming | None" = None

    def revolutions(self, index: int) -> int:
        """Own revolutions of rotor ``index`` in its tables (1 unless relaxed over a common period)."""
        return 1 if self.timing is None else int(self.timing.revolutions[index])

    def period_record(self, index: int, n_psi: int) -> dict:
        """Metadata of rotor ``index``'s loads over a common period, for a disk table of ``n_psi`` azimuths per
        revolution: {} when the rotor is periodic in its own revolution; else ``revolutions`` (m),
        ``blade_shift_steps`` (blade k's loads are blade 0's table row i + shift_k at row i), ``period_s`` and
        ``common_period`` (:meth:`nps.core.periods.CommonPeriod.describe`)."""
        if self.revolutions(index) == 1:
            return {}
        rotor = self.rotors[index]
        b = rotor.state.n_blades
        period = next(p for p in self.timing.periods if rotor.name in p.names)
        shifts = self.timing.blade_shift_rad[index, :b] * n_psi / (2.0 * math.pi)
        return {"revolutions": self.revolutions(index), "blade_shift_steps": [int(round(x)) for x in shifts],
                "period_s": period.period_s, "common_period": period.describe(),
                "blade_shift_mismatch_passages": float(self.timing.shift_mismatch[index])}

    def group_of(self, index: int) -> tuple[int, ...]:
        """The coupled group (rotor indices, ascending) that rotor ``index`` belongs to."""
        if self.groups is None:
            return tuple(range(len(self.rotors)))
        return next(g for g in self.groups if index in g)

    def index(self, name: str) -> int:
        names = [r.name for r in self.rotors]
        if name not in names:
            raise ValueError(f"free wake: no rotor '{name}' (rotors {names})")
        return names.index(name)


@dataclass(frozen=True)
class WakeTiming:
    """How the rotors' tables are timed over a common period (docs "Common period").

    ``revolutions`` (n_rot,) m_q: own revolutions of rotor q in its table (N m_q rows);
    ``speed_ratio`` (n_rot, n_rot): Ω_q/Ω_t = m_q/m_t used to place rotor q's blades when rotor t is the
    target (the rational ratio of the period); ``blade_shift_rad`` (n_rot, max B): blade k of rotor q
    at table azimuth ψ uses blade 0's row at ψ + shift (2π(k/B + n_k), n_k the own revolutions after
    which the other rotors' blade passages repeat best); ``shift_mismatch`` (n_rot,): the largest
    residual phase of another rotor's blade passage at those shifts, in passages (0: exact);
    ``periods``: the :class:`nps.core.periods.CommonPeriod` of each group relaxed over one."""

    revolutions: np.ndarray
    speed_ratio: np.ndarray
    blade_shift_rad: np.ndarray
    shift_mismatch: np.ndarray
    periods: tuple[periods.CommonPeriod, ...]


def own_timing(rotors: Sequence[RotorPlacement]) -> WakeTiming:
    """Each rotor periodic in its own revolution: m_q = 1, Ω_q/Ω_t the speed ratio, blade k at 2πk/B."""
    omega = np.array([r.state.omega_rad_s for r in rotors])
    max_b = max(r.state.n_blades for r in rotors)
    shifts = np.zeros((len(rotors), max_b))
    for q, r in enumerate(rotors):
        b = r.state.n_blades
        shifts[q, :b] = 2.0 * np.pi * np.arange(b) / b
    return WakeTiming(np.ones(len(rotors), dtype=np.int64), np.ascontiguousarray([omega / omega[t] for t in range(len(rotors))]),
                      shifts, np.zeros(len(rotors)), ())


def period_timing(rotors: Sequence[RotorPlacement], model: FreeWakeModel) -> WakeTiming:
    """Timing of one coupled group over its common period (:func:`nps.core.periods.common_period`, first
    rotor the reference): m_q revolutions, rational speed ratios m_q/m_t, and for blade k of rotor q the
    shift 2π(k/B_q + n) (n = 0…m_q−1) after which every other rotor p's blades are closest to a whole
    number of its blade passages, (k/B_q + n)(m_p/m_q)B_p (exact for e.g. a 5:1 pair of four and two
    blades; else the closest, recorded in ``shift_mismatch``). Raises :class:`nps.core.periods.PeriodError`."""
    period = periods.common_period([r.name for r in rotors], [r.state.omega_rad_s for r in rotors],
                                   model.period_tolerance, model.max_period_revolutions)
    m = np.array(period.revolutions, dtype=np.int64)
    blades = [r.state.n_blades for r in rotors]
    shifts = np.zeros((len(rotors), max(blades)))
    mismatch = np.zeros(len(rotors))
    for q, b in enumerate(blades):
        for k in range(b):
            best = (math.inf, 0)
            for n in range(int(m[q])):
                own = k / b + n
                miss = max([abs(x - round(x)) for x in (own * m[p] / m[q] * blades[p]
                                                         for p in range(len(rotors)) if p != q)] or [0.0])
                if miss < best[0] - 1e-12:
                    best = (miss, n)
            shifts[q, k] = 2.0 * np.pi * k / b + 2.0 * np.pi * best[1]
            mismatch[q] = max(mismatch[q], best[0])
    ratio = np.ascontiguousarray([m / float(m[t]) for t in range(len(rotors))])
    return WakeTiming(m, ratio, shifts, mismatch, (period,))


def far_field_ratio(source: RotorPlacement, target: RotorPlacement) -> float:
    """Estimate of the velocity the source rotor's wake induces at the target's hub, relative to
    the target's own mean induced velocity (momentum far field of a lifting rotor; docs):

        w / v_i,q = (v_i,p / v_i,q) · R_p² / (2 d²),

    v_i = Ω R λ0 (Glauert, :func:`nps.wake.prescribed.mean_inflow`), d the hub distance (m). For a distant
    rotor in forward flight w = T/(4π ρ V d²) is the upwash beside a semi-infinite trailing
    vortex pair, in hover A v_i/(2π d²) bounds the inflow into the slipstream; both equal
    v_i R²/(2 d²)."""
    d = float(np.linalg.norm(np.asarray(source.hub_position_m, float) - np.asarray(target.hub_position_m, float)))
    if d == 0.0:
        return math.inf

    def v_i(s: wake.WakeState) -> float:
        return s.omega_rad_s * s.radius_m * wake.mean_inflow(s.ct, s.mu_inplane, s.mu_z)

    return v_i(source.state) / v_i(target.state) * source.state.radius_m ** 2 / (2.0 * d * d)


def coupled_groups(rotors: Sequence[RotorPlacement]) -> tuple[tuple[int, ...], ...]:
    """Rotor indices grouped so that two rotors share a group when a chain of rotors connects
    them in which each wake reaches the next rotor with :func:`far_field_ratio` ≥
    ``COUPLING_THRESHOLD`` (either direction). Rotors of different groups are not coupled: the
    other wake's far field would change a rotor's inflow by less than the trim tolerance, and
    a tip-vortex wake's far field is not the physical one there (docs, "Far-apart rotors")."""
    parent = list(range(len(rotors)))

    def root(i):
        while parent[i] != i:
            i = parent[i]
        return i

    for q in range(len(rotors)):
        for p in range(q + 1, len(rotors)):
            if max(far_field_ratio(rotors[p], rotors[q]), far_field_ratio(rotors[q], rotors[p])) >= COUPLING_THRESHOLD:
                parent[root(p)] = root(q)
    groups: dict[int, list[int]] = {}
    for i in range(len(rotors)):
        groups.setdefault(root(i), []).append(i)
    return tuple(tuple(g) for g in sorted(groups.values()))


@dataclass(frozen=True)
class _Sources:
    """Packed per-rotor arrays of the Biot–Savart kernel (see :func:`_sources`)."""

    params: np.ndarray  # (n_rot, n_p) wake.wake_scalars
    gamma: np.ndarray  # (n_rot, n_tab)
    beta: np.ndarray  # (n_rot, n_tab)
    distortion: np.ndarray  # (n_rot, max rows, J+1, 3), rotor q's first table_rows[q] rows
    table_rows: np.ndarray  # (n_rot,) int: rows of each rotor's table (N m_q)
    revolutions: np.ndarray  # (n_rot,) float: m_q, own revolutions the table spans
    blade_shift: np.ndarray  # (n_rot, max B): WakeTiming.blade_shift_rad
    core: np.ndarray  # (n_rot, 3): VortexModel.core_constants (r_c0, growth coefficient, a1/ν)
    profiles: np.ndarray  # (n_rot, n_rows, M) VortexModel.structure_coefficients, zero-padded
    profile_rows: np.ndarray  # (n_rot,) int: each rotor's number of release azimuths in it
    profile_s2: np.ndarray  # (n_rot,) scale s² of the structure factor (m²)
    vatistas_n: float


def _common_tables(rotors: Sequence[RotorPlacement]) -> tuple[np.ndarray, np.ndarray]:
    """Γ and β tables of all rotors on one periodic grid (the longest one), (n_rot, n)."""
    n = max(len(r.state.gamma_table_m2_s) for r in rotors)
    psi = 2.0 * np.pi * np.arange(n) / n
    out = []
    for r in rotors:
        own = r.state.psi_table_rad
        out.append([np.interp(psi, own, np.asarray(t, dtype=float), period=2.0 * np.pi) if len(own) != n
                    else np.asarray(t, dtype=float) for t in (r.state.gamma_table_m2_s, r.state.beta_table_rad)])
    return np.ascontiguousarray([o[0] for o in out]), np.ascontiguousarray([o[1] for o in out])


def _sources(rotors, beddoes: wake.WakeModel, distortion, vortex: VortexModel, timing: WakeTiming) -> _Sources:
    """The rotors' Beddoes geometry (``beddoes``) and ``distortion`` (a list of each rotor's table
    (N m_q, J+1, 3), or an array of equal tables) carrying ``vortex``, timed by ``timing``."""
    gamma, beta = _common_tables(rotors)
    rows = np.array([len(d) for d in distortion], dtype=np.int64)
    packed = np.zeros((len(rotors), int(rows.max())) + tuple(np.shape(distortion[0])[1:]))
    for q, d in enumerate(distortion):
        packed[q, : rows[q]] = d
    params = np.ascontiguousarray([wake.wake_scalars(r.state, beddoes) for r in rotors])
    core = np.array([vortex.core_constants(r.state.chord_m, r.state.omega_rad_s) for r in rotors])
    tables = [vortex.structure_coefficients(r.state.vortex_profile, r.state.radius_m, r.state.chord_m) for r in rotors]
    profiles = np.zeros((len(rotors), max(t[0].shape[0] for t in tables), max(t[0].shape[1] for t in tables)))
    for q, (table, _) in enumerate(tables):
        profiles[q, : table.shape[0], : table.shape[1]] = table
    return _Sources(params, gamma, beta, packed, rows, np.asarray(timing.revolutions, dtype=float),
                    np.ascontiguousarray(timing.blade_shift_rad, dtype=float), core, profiles,
                    np.array([t[0].shape[0] for t in tables], dtype=np.int64), np.array([t[1] for t in tables]),
                    float(vortex.vatistas_n))


def _physical_sources(rotors, beddoes, model: FreeWakeModel, distortion, timing: WakeTiming) -> _Sources:
    """Node kinematics: :attr:`FreeWakeModel.kinematics_vortex` (point vortices, r_c0 = max(physical
    core, floor) · c, growing with age)."""
    return _sources(rotors, beddoes, distortion, model.kinematics_vortex, timing)


def _lifting_line_sources(rotors, beddoes: wake.WakeModel, distortion, timing: WakeTiming) -> _Sources:
    """Blade-load evaluation: the Beddoes model's lifting-line vortex (as the prescribed wake)."""
    return _sources(rotors, beddoes, distortion, beddoes.vortex, timing)


def _transforms(rotors: Sequence[RotorPlacement], target: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maps from each source rotor's H' to the target rotor's H': rotation (n, 3, 3),
    offset (n, 3) and circulation sign s_q s_p (a mirror reverses the sense of rotation).
    The target's own map is the exact identity."""
    t = rotors[target]
    back = t.to_common.T
    rot = np.empty((len(rotors), 3, 3))
    off = np.empty((len(rotors), 3))
    sign = np.empty(len(rotors))
    for q, r in enumerate(rotors):
        if q == target:
            rot[q], off[q] = np.eye(3), 0.0
        else:
            rot[q] = back @ r.to_common
            off[q] = back @ (np.asarray(r.hub_position_m, float) - np.asarray(t.hub_position_m, float))
        sign[q] = r.state.rotation_sign * t.state.rotation_sign
    return rot, off, sign


@kernel(inline=True)
def _distortion_at(table, n, revolutions, psi, phi, step):
    """Bilinear interpolation of one rotor's distortion (first ``n`` rows of ``table``, spanning
    ``revolutions`` turns of ψ, J+1 ages, 3): periodic in ψ over 2π·revolutions, linear in φ (clamped
    to the table's age range)."""
    m = table.shape[1]
    u = (psi / (2.0 * math.pi * revolutions)) % 1.0 * n
    i0 = int(math.floor(u))
    wu = u - i0
    i0 = i0 % n
    i1 = (i0 + 1) % n
    v = min(phi / step, m - 1.0)
    j0 = min(int(math.floor(v)), m - 2)
    wv = v - j0
    a = (1.0 - wu) * (1.0 - wv)
    b = wu * (1.0 - wv)
    c = (1.0 - wu) * wv
    d = wu * wv
    return (
        a * table[i0, j0, 0] + b * table[i1, j0, 0] + c * table[i0, j0 + 1, 0] + d * table[i1, j0 + 1, 0],
        a * table[i0, j0, 1] + b * table[i1, j0, 1] + c * table[i0, j0 + 1, 1] + d * table[i1, j0 + 1, 1],
        a * table[i0, j0, 2] + b * table[i1, j0, 2] + c * table[i0, j0 + 1, 2] + d * table[i1, j0 + 1, 2],
    )


@kernel
def _rotor_nodes(p, gamma_tab, beta_tab, table, table_rows, revolutions, shift, table_step, core, psi0, n_age, dphi,
                 n_rows, nodes, strength, radius, row):
    """Nodes (B, n_age+1, 3) in the rotor's own H' when its blade 0 is at table azimuth ``psi0``:
    Beddoes geometry of blade k at ψ0 + 2πk/B plus the distortion of the table at ψ0 + ``shift[k]``
    (``table_rows`` rows over ``revolutions`` turns, :class:`WakeTiming`); Γ, core radius and
    structure-factor row (of ``n_rows``, :func:`nps.wake.vortex.profile_row`) per node; ``core``:
    :meth:`VortexModel.core_constants`."""
    n_blades = int(p[1])
    cpw, spw = math.cos(p[3]), math.sin(p[3])
    for j in range(n_age + 1):
        phi = j * dphi
        r_v = wake.vortex_radius(p, phi)
        for k in range(n_blades):
            psi_k = psi0 + 2.0 * math.pi * k / n_blades
            psi_table = psi0 + shift[k]
            x, y, z, g = wake.node_position_at(p, gamma_tab, beta_tab, psi_k - phi, phi, r_v, cpw, spw)
            dx, dy, dz = _distortion_at(table, table_rows, revolutions, psi_table, phi, table_step)
            nodes[k, j, 0], nodes[k, j, 1], nodes[k, j, 2] = x + dx, y + dy, z + dz
            strength[k, j] = g
            radius[k, j] = core_radius(core, g, phi)
            row[k, j] = profile_row(psi_k - phi, n_rows)


@kernel(inline=True)
def _add_bound(vx, vy, vz, px, py, pz, hub, nodes, k, gamma, rc, vatistas_n):
    """Add to (vx, vy, vz) (n_pts,) the velocity at the points (px, py, pz) of blade k's bound
    vortex, straight from the hub centre ``hub`` (3,) to its tip node (strength ``gamma``, core
    ``rc``)."""
    for m in range(px.shape[0]):
        h1x, h1y, h1z = px[m] - hub[0], py[m] - hub[1], pz[m] - hub[2]
        t1x, t1y, t1z = px[m] - nodes[k, 0, 0], py[m] - nodes[k, 0, 1], pz[m] - nodes[k, 0, 2]
        dx, dy, dz = segment_velocity(h1x, h1y, h1z, math.sqrt(h1x * h1x + h1y * h1y + h1z * h1z),
                                      t1x, t1y, t1z, math.sqrt(t1x * t1x + t1y * t1y + t1z * t1z), gamma, rc, vatistas_n,
                                      False, POINT_VORTEX_PROFILE[0], 1.0)
        vx[m] += dx
        vy[m] += dy
        vz[m] += dz


@kernel
def _far_groups(nodes, strength, radius, n_blades, n_age, group, ratio, groups):
    """Per blade k and group g of ``group`` consecutive segments (nodes gG … min((g+1)G, n_age)):
    centre (mid-chord), squared far distance (ratio · half the largest node distance from the
    centre, squared), the segment-mean Γ and core of the chord segment; into ``groups``
    (B, n_groups, 6)."""
    n_groups = (n_age + group - 1) // group
    for k in range(n_blades):
        for g in range(n_groups):
            j0 = g * group
            j1 = min(j0 + group, n_age)
            cx = 0.5 * (nodes[k, j0, 0] + nodes[k, j1, 0])
            cy = 0.5 * (nodes[k, j0, 1] + nodes[k, j1, 1])
            cz = 0.5 * (nodes[k, j0, 2] + nodes[k, j1, 2])
            extent = 0.0
            s = 0.0
            rc = 0.0
            for j in range(j0, j1 + 1):
                dx, dy, dz = nodes[k, j, 0] - cx, nodes[k, j, 1] - cy, nodes[k, j, 2] - cz
                extent = max(extent, dx * dx + dy * dy + dz * dz)
            for j in range(j0, j1):
                s += 0.5 * (strength[k, j] + strength[k, j + 1])
                rc += 0.5 * (radius[k, j] + radius[k, j + 1])
            groups[k, g, 0], groups[k, g, 1], groups[k, g, 2] = cx, cy, cz
            groups[k, g, 3] = ratio * ratio * extent
            groups[k, g, 4] = s / (j1 - j0)
            groups[k, g, 5] = rc / (j1 - j0)


@kernel(inline=True)
def _to_target(nodes, n_blades, n_age, rot, off):
    """Map the nodes (B, n_age+1, 3) in place from the source rotor's H' to the target's:
    x ↦ rot x + off (``rot`` (3, 3), ``off`` (3,), :func:`_transforms`)."""
    for k in range(n_blades):
        for j in range(n_age + 1):
            x, y, z = nodes[k, j, 0], nodes[k, j, 1], nodes[k, j, 2]
            nodes[k, j, 0] = rot[0, 0] * x + rot[0, 1] * y + rot[0, 2] * z + off[0]
            nodes[k, j, 1] = rot[1, 0] * x + rot[1, 1] * y + rot[1, 2] * z + off[1]
            nodes[k, j, 2] = rot[2, 0] * x + rot[2, 1] * y + rot[2, 2] * z + off[2]


@kernel(inline=True)
def _add_grouped(px, py, pz, nodes, strength, radius, row, groups, profiles, s2, k, group, n_age, g_sign, vatistas_n,
                 near, scratch, vx, vy, vz):
    """Add to (vx, vy, vz) (n_pts,) the velocity at (px, py, pz) of blade k's tip vortex in groups of
    ``group`` segments (``groups``: :func:`_far_groups`): a group beyond its far distance from a
    point counts as its chord segment (with the structure-factor row of its first node), a near
    one segment by segment (the near points gathered, so that the sweep vectorises, and scattered
    back: each point sums in the same order). ``near`` (n_pts,) int and ``scratch`` (10, n_pts): work
    arrays."""
    n_groups = (n_age + group - 1) // group
    structured = profiles.shape[1] > 1
    for g in range(n_groups):
        j0 = g * group
        j1 = min(j0 + group, n_age)
        profile = structure_row(profiles, row[k, j0], structured)
        n_near = 0
        for m in range(px.shape[0]):  # the chord of every far group, all points at once
            dx, dy, dz = px[m] - groups[k, g, 0], py[m] - groups[k, g, 1], pz[m] - groups[k, g, 2]
            is_far = dx * dx + dy * dy + dz * dz > groups[k, g, 3]
            r1x, r1y, r1z = px[m] - nodes[k, j0, 0], py[m] - nodes[k, j0, 1], pz[m] - nodes[k, j0, 2]
            r2x, r2y, r2z = px[m] - nodes[k, j1, 0], py[m] - nodes[k, j1, 1], pz[m] - nodes[k, j1, 2]
            dx, dy, dz = segment_velocity(
                r1x, r1y, r1z, math.sqrt(r1x * r1x + r1y * r1y + r1z * r1z),
                r2x, r2y, r2z, math.sqrt(r2x * r2x + r2y * r2y + r2z * r2z),
                g_sign * groups[k, g, 4], groups[k, g, 5], vatistas_n, structured, profile, s2,
            )
            vx[m] += dx if is_far else 0.0
            vy[m] += dy if is_far else 0.0
            vz[m] += dz if is_far else 0.0
            near[n_near] = m
            n_near += 0 if is_far else 1
        if n_near == 0:
            continue
        for e in range(n_near):  # segment by segment where the group is near
            m = near[e]
            scratch[4, e], scratch[5, e], scratch[6, e] = px[m], py[m], pz[m]
            scratch[7, e], scratch[8, e], scratch[9, e] = vx[m], vy[m], vz[m]
        add_polyline_velocity(scratch[4, :n_near], scratch[5, :n_near], scratch[6, :n_near], nodes, strength, radius,
                              profiles, row, s2, k, j0, j1, g_sign, vatistas_n, scratch[0, :n_near], scratch[1, :n_near],
                              scratch[2, :n_near], scratch[3, :n_near], scratch[7, :n_near], scratch[8, :n_near],
                              scratch[9, :n_near])
        for e in range(n_near):
            m = near[e]
            vx[m], vy[m], vz[m] = scratch[7, e], scratch[8, e], scratch[9, e]


@kernel(parallel=True)
def _induced_kernel(points, row_psi, omega_ratio, phase_offset, params, gamma, beta, distortion, table_rows, revolutions,
                    shifts, table_step, core, profiles, profile_rows, profile_s2, rot, off, sign, bound, far, group, ratio,
                    n_age, dphi, vatistas_n):
    """Velocity (n_tgt, n_src, n_rows, n_pts, 3) induced at ``points`` (n_tgt, n_rows, n_pts, 3)
    by every source rotor's tip vortices, in each target rotor's H'. Row i of target t is the
    instant when the target's blade 0 is at ``row_psi[i]``; source q's blade 0 is then at
    omega_ratio[t, q]·row_psi[i] + phase_offset[t, q] (φ_q − ratio·φ_t, the blade phases); ``distortion``, ``table_rows``, ``revolutions``, ``shifts``: the
    sources' tables and timing (:class:`_Sources`). rot (n_tgt, n_src, 3, 3), off (n_tgt, n_src, 3), sign
    (n_tgt, n_src) map source H' to target H' (:func:`_transforms`); ``bound[t, q]``: add the
    blades' bound vortices, straight from the hub centre to the tip node (strength Γ_v, core
    r_c0), closing each tip vortex into a horseshoe. ``far[t, q]``: far-field grouping of
    source q's vortices (:func:`_far_groups`): a group of ``group`` segments farther than
    ``ratio`` times its half-extent from the point counts as its chord segment (with the
    structure-factor row of its first node). ``profiles`` (n_src, n_rows, M), ``profile_rows``
    (n_src,), ``profile_s2`` (n_src,): the sources' vortex structure (:class:`_Sources`); bound
    vortices are point vortices."""
    n_src = params.shape[0]
    n_tgt, n_rows, n_pts = points.shape[0], points.shape[1], points.shape[2]
    out = np.zeros((n_tgt, n_src, n_rows, n_pts, 3))
    max_b = 0
    for q in range(n_src):
        max_b = max(max_b, int(params[q, 1]))
    n_groups = (n_age + group - 1) // group
    for ti in prange(n_tgt * n_rows):
        t = ti // n_rows
        i = ti % n_rows
        nodes = np.empty((max_b, n_age + 1, 3))
        strength = np.empty((max_b, n_age + 1))
        radius = np.empty((max_b, n_age + 1))
        row = np.empty((max_b, n_age + 1), dtype=np.int64)
        groups = np.empty((max_b, n_groups, 6))
        px, py, pz = points[t, i, :, 0].copy(), points[t, i, :, 1].copy(), points[t, i, :, 2].copy()
        scratch = np.empty((10, n_pts))
        vx, vy, vz = np.empty(n_pts), np.empty(n_pts), np.empty(n_pts)
        near = np.empty(n_pts, dtype=np.int64)
        for q in range(n_src):
            n_blades = int(params[q, 1])
            _rotor_nodes(params[q], gamma[q], beta[q], distortion[q], table_rows[q], revolutions[q], shifts[q], table_step,
                         core[q], omega_ratio[t, q] * row_psi[i] + phase_offset[t, q], n_age, dphi, profile_rows[q], nodes,
                         strength, radius, row)
            _to_target(nodes, n_blades, n_age, rot[t, q], off[t, q])
            q_profiles, s2 = profiles[q], profile_s2[q]
            g_sign = sign[t, q]
            vx[:] = 0.0
            vy[:] = 0.0
            vz[:] = 0.0
            grouped = far[t, q] and group > 1
            if grouped:
                _far_groups(nodes, strength, radius, n_blades, n_age, group, ratio, groups)
            for k in range(n_blades):
                if grouped:
                    _add_grouped(px, py, pz, nodes, strength, radius, row, groups, q_profiles, s2, k, group, n_age,
                                 g_sign, vatistas_n, near, scratch, vx, vy, vz)
                else:
                    add_polyline_velocity(px, py, pz, nodes, strength, radius, q_profiles, row, s2, k, 0, n_age,
                                          g_sign, vatistas_n, scratch[0], scratch[1], scratch[2], scratch[3], vx, vy,
                                          vz)
                if bound[t, q]:
                    _add_bound(vx, vy, vz, px, py, pz, off[t, q], nodes, k, g_sign * strength[k, 0], core[q, 0],
                               vatistas_n)
            out[t, q, i, :, 0], out[t, q, i, :, 1], out[t, q, i, :, 2] = vx, vy, vz
    return out


def _induced(rotors, sources: _Sources, timing: WakeTiming, targets, points, row_psi, n_age: int, dphi: float,
             table_step: float, own_bound: bool, far_group: int = 1, far_distance: float = 0.0) -> np.ndarray:
    """Per-source induced velocity (n_tgt, n_src, n_rows, n_pts, 3) in each target's H' (m/s)
    at ``points`` (n_tgt, n_rows, n_pts, 3); ``targets``: rotor indices; bound vortices of the
    other rotors always, of the target itself when ``own_bound``; the other rotors' vortices
    with the far-field grouping of ``far_group`` segments beyond ``far_distance`` half-extents (1: none);
    source blades placed by ``timing.speed_ratio`` (rows: targets) and the rotors' ``phase_rad``."""
    maps = [_transforms(rotors, t) for t in targets]
    rot = np.ascontiguousarray([m[0] for m in maps])
    off = np.ascontiguousarray([m[1] for m in maps])
    sign = np.ascontiguousarray([m[2] for m in maps])
    ratio = np.ascontiguousarray(timing.speed_ratio[list(targets)])
    phase = np.array([r.phase_rad for r in rotors])
    phase_offset = np.ascontiguousarray(phase[None, :] - ratio * phase[list(targets)][:, None])
    bound = np.ascontiguousarray([[own_bound or q != t for q in range(len(rotors))] for t in targets], dtype=np.bool_)
    far = np.ascontiguousarray([[q != t for q in range(len(rotors))] for t in targets], dtype=np.bool_)
    return _induced_kernel(np.ascontiguousarray(points, dtype=float), np.ascontiguousarray(row_psi, dtype=float), ratio,
                           phase_offset,
                           sources.params, sources.gamma, sources.beta, sources.distortion, sources.table_rows,
                           sources.revolutions, sources.blade_shift, float(table_step),
                           np.ascontiguousarray(sources.core), sources.profiles, sources.profile_rows,
                           sources.profile_s2, rot, off, sign, bound, far, max(int(far_group), 1),
                           float(far_distance), int(n_age), float(dphi), sources.vatistas_n)


def _node_table(rotor: RotorPlacement, beddoes: wake.WakeModel, model: FreeWakeModel, revolutions: int = 1) -> np.ndarray:
    """Beddoes nodes of blade 0 on the relaxation grid (N·revolutions, J+1, 3), H' (m): the Beddoes
    geometry is periodic in one revolution, so it repeats."""
    p = wake.wake_scalars(rotor.state, beddoes)
    gamma = np.ascontiguousarray(rotor.state.gamma_table_m2_s, dtype=float)
    beta = np.ascontiguousarray(rotor.state.beta_table_rad, dtype=float)
    one = _beddoes_table(p, gamma, beta, model.steps_per_rev, model.n_age + model.n_far, model.step_rad)
    return one if revolutions == 1 else np.tile(one, (int(revolutions), 1, 1))


@kernel
def _beddoes_table(p, gamma, beta, n_psi, n_age, step):
    out = np.empty((n_psi, n_age + 1, 3))
    for i in range(n_psi):
        for j in range(n_age + 1):
            x, y, z, _ = wake.node_position(p, gamma, beta, i * step - j * step, j * step)
            out[i, j, 0], out[i, j, 1], out[i, j, 2] = x, y, z
    return out


def _node_velocities(rotors, beddoes, model, base, distortion, timing: WakeTiming) -> list[np.ndarray]:
    """Velocity (N m_q, J+1, 3) of every rotor's free nodes in its own H' (m/s): free stream +
    all wakes (free and far parts and the semi-infinite continuation). ``base``, ``distortion``: each
    rotor's table (lists); row i of rotor q is the instant its blade 0 is at ψ_i = iΔ."""
    sources = _physical_sources(rotors, beddoes, model, distortion, timing)
    free = model.n_age + 1
    points = [base[q][:, :free] + distortion[q][:, :free] for q in range(len(rotors))]
    out = []
    for t, r in enumerate(rotors):
        psi = np.arange(len(points[t])) * model.step_rad
        v = _induced(rotors, sources, timing, [t], points[t][None], psi, model.n_age + model.n_far, model.step_rad,
                     model.step_rad, True).sum(axis=1)[0]
        out.append(v + r.free_stream_hp_mps)
    rings = [_continuation_rings(r, base[q] + distortion[q], sources.gamma[q], sources.core[q, 0], model)
             for q, r in enumerate(rotors)]
    if any(ring is not None for ring in rings):
        for t in range(len(rotors)):
            rot, off, sign = _transforms(rotors, t)
            flat = points[t].reshape(-1, 3)
            for q, ring in enumerate(rings):
                if ring is not None:
                    far = _ring_velocity(flat, ring[0] @ rot[q].T + off[q], rot[q][:, 2], ring[1], sign[q] * ring[2],
                                         ring[3])
                    out[t] += far.reshape(points[t].shape)
    return out


# Growth ratio of the ring intervals of the far-wake continuation: the first interval is one
# blade passage (L/B), each next one 1.25 times longer (the cylinder's field is smooth there;
# on-axis velocity of the ring sum within 1 % of the exact semi-infinite cylinder; unit test, bound 1.5 %).
CONTINUATION_GROWTH = 1.25


def circulation_thrust_coefficient(state: wake.WakeState, gamma_mean_m2_s: float | None = None) -> float:
    """C_T,Γ = B Γ̄_v/(2π Ω R²), Γ̄_v the ψ-mean tip-vortex strength (default: of the state's
    table): the thrust coefficient of a rotor whose uniform bound circulation is Γ̄_v — what a
    wake of these tip vortices alone induces on average (vortex-cylinder theory; docs, "Mean
    inflow of a tip-vortex wake")."""
    gamma = float(np.mean(state.gamma_table_m2_s)) if gamma_mean_m2_s is None else gamma_mean_m2_s
    return state.n_blades * gamma / (2.0 * np.pi * state.omega_rad_s * state.radius_m ** 2)


def _continuation_rings(rotor: RotorPlacement, x: np.ndarray, gamma_table: np.ndarray, core_m: float,
                        model: FreeWakeModel):
    """Vortex rings (centres (M, 3), radius m, circulations (M,) m²/s, core m) continuing the
    rotor's wake x (N, J+1, 3) (own H') as a semi-infinite vortex cylinder; ``None`` when off
    or when the tip vortices carry no lift (Γ̄ ≤ 0).

    The cylinder convects with V_c = V_∞ − λ_Γ Ω R e_z, λ_Γ from Glauert's momentum relation
    (:func:`nps.wake.prescribed.mean_inflow`) at the circulation's thrust coefficient
    C_T,Γ = B Γ̄/(2π Ω R²) (Γ̄: ψ-mean tip-vortex strength): the self-induced velocity
    w = γ/2 of the tip vortices of an infinite cylinder with γ = B Γ̄/L, L = 2π|V_c|/Ω the
    advance per revolution, satisfies w |V_c| = B Γ̄ Ω/(4π), which is that relation. The
    cylinder starts at the centre c₀ of the wake's last turn with its mean radius a (disk
    plane); its azimuthal vorticity γ (circulation about +z negative: the flow through it goes
    down, as the tip vortices') is lumped into rings at the midpoints of intervals along
    V_c, the first L/B long, each next ``CONTINUATION_GROWTH`` times longer, up to
    ``continuation_radii`` R. The longitudinal (swirl) part of the helix is not continued.
    V_c and γ do not depend on the iterate (no feedback from the wake's end).
    """
    s = rotor.state
    length = model.continuation_radii * s.radius_m
    gamma_mean = float(np.mean(gamma_table))
    if length == 0.0 or not gamma_mean > 0.0:
        return None
    lam = wake.mean_inflow(circulation_thrust_coefficient(s, gamma_mean), s.mu_inplane, s.mu_z)
    velocity = rotor.free_stream_hp_mps - np.array([0.0, 0.0, lam * s.omega_rad_s * s.radius_m])
    speed = float(np.linalg.norm(velocity))
    per_rev = 2.0 * np.pi * speed / s.omega_rad_s
    widths = [per_rev / s.n_blades]
    while sum(widths) < length:
        widths.append(widths[-1] * CONTINUATION_GROWTH)
    widths = np.array(widths)
    mid = np.cumsum(widths) - 0.5 * widths
    centre = x[:, -1].mean(axis=0)
    radius = float(np.hypot(x[:, -1, 0] - centre[0], x[:, -1, 1] - centre[1]).mean())
    centres = centre + mid[:, None] * (velocity / speed)
    gamma = -s.n_blades * gamma_mean / per_rev * widths
    return centres, radius, gamma, float(core_m)


def _ring_velocity(points: np.ndarray, centres: np.ndarray, axis: np.ndarray, radius_m: float, gamma_m2_s: np.ndarray,
                   core_m: float) -> np.ndarray:
    """Velocity (P, 3) (m/s) at ``points`` (P, 3) induced by circular vortex rings of radius
    ``radius_m``, centres (M, 3), common unit ``axis`` (3,), circulations (M,) right-handed about
    the axis (any frame, metres). Exact ring field (Lamb, Hydrodynamics §161; K, E complete
    elliptic integrals of parameter m), with ρ, z the point's radial and axial offsets:

        A = (ρ+a)² + z²,  b² = (ρ−a)² + z²,  m = 4aρ/A,
        u_z = Γ/(2π√A) [K + (a² − ρ² − z²) E/b²],  u_ρ = Γ z/(2πρ√A) [−K + (a² + ρ² + z²) E/b²],

    times b²/(b² + r_c²) (a core: finite on the filament). u_ρ is evaluated as
    Γ z/(2π√A) [(E − K)/ρ + 2aE/b²], with the series (E − K)/ρ = −(πa/A)(1 + 3m/8 + 15m²/64)
    for m < 1e-3 (no cancellation near the axis)."""
    return _rings_kernel(np.ascontiguousarray(points, dtype=float), np.ascontiguousarray(centres, dtype=float),
                         np.ascontiguousarray(axis, dtype=float), float(radius_m),
                         np.ascontiguousarray(gamma_m2_s, dtype=float), float(core_m))


@kernel(inline=True)
def _elliptic_ke(m):
    """Complete elliptic integrals K(m), E(m), 0 ≤ m < 1: Hastings' polynomial approximations,
    Abramowitz & Stegun 17.3.34 and 17.3.36 (|error| ≤ 2e-8), m₁ = 1 − m."""
    m1 = 1.0 - m
    log = -math.log(m1)
    k = (1.38629436112 + m1 * (0.09666344259 + m1 * (0.03590092383 + m1 * (0.03742563713 + m1 * 0.01451196212)))
         + log * (0.5 + m1 * (0.12498593597 + m1 * (0.06880248576 + m1 * (0.03328355346 + m1 * 0.00441787012)))))
    e = (1.0 + m1 * (0.44325141463 + m1 * (0.06260601220 + m1 * (0.04757383546 + m1 * 0.01736506451)))
         + log * m1 * (0.24998368310 + m1 * (0.09200180037 + m1 * (0.04069697526 + m1 * 0.00526449639))))
    return k, e


@kernel
def _rings_kernel(points, centres, axis, a, gamma, core):
    out = np.zeros_like(points)
    for i in range(points.shape[0]):
        vx = vy = vz = 0.0
        for j in range(centres.shape[0]):
            dx, dy, dz = points[i, 0] - centres[j, 0], points[i, 1] - centres[j, 1], points[i, 2] - centres[j, 2]
            z = dx * axis[0] + dy * axis[1] + dz * axis[2]
            rx, ry, rz = dx - z * axis[0], dy - z * axis[1], dz - z * axis[2]
            rho = math.sqrt(rx * rx + ry * ry + rz * rz)
            a_sq = (rho + a) ** 2 + z * z
            b_sq = (rho - a) ** 2 + z * z
            m = min(4.0 * a * rho / a_sq, 1.0 - 1e-12)
            k, e = _elliptic_ke(m)
            scale = gamma[j] / (2.0 * math.pi * math.sqrt(a_sq)) / (b_sq + core * core)
            u_z = scale * (b_sq * k + (a * a - rho * rho - z * z) * e)
            if m < 1e-3:
                e_minus_k_over_rho = -math.pi * a / a_sq * (1.0 + 3.0 * m / 8.0 + 15.0 * m * m / 64.0)
            else:
                e_minus_k_over_rho = (e - k) / rho
            u_r = scale * z * (b_sq * e_minus_k_over_rho + 2.0 * a * e)
            if rho > 0.0:
                u_r /= rho
            vx += u_z * axis[0] + u_r * rx
            vy += u_z * axis[1] + u_r * ry
            vz += u_z * axis[2] + u_r * rz
        out[i, 0], out[i, 1], out[i, 2] = vx, vy, vz
    return out


def _march(x_old: np.ndarray, velocity: np.ndarray, step_time_s: float) -> np.ndarray:
    """Five-point PIPC march X[i, j] = X[i−1, j−1] + Δt ¼ ΣV over the free nodes j ≤ J
    (``velocity`` (N, J+1, 3)), node 0 fixed, then the far wake (module doc)."""
    x = x_old.copy()
    free = velocity.shape[1]
    v_avg = 0.25 * (velocity + np.roll(velocity, 1, axis=0))
    v_avg = v_avg[:, 1:] + v_avg[:, :-1]
    for j in range(1, free):
        x[:, j] = np.roll(x[:, j - 1], 1, axis=0) + step_time_s * v_avg[:, j - 1]
    v_far = velocity[:, free - 1].mean(axis=0)
    for m in range(1, x.shape[1] - free + 1):
        x[:, free - 1 + m] = np.roll(x[:, free - 1], m, axis=0) + m * step_time_s * v_far
    return x


def relax(rotors: Sequence[RotorPlacement], beddoes: wake.WakeModel, model: FreeWakeModel = FreeWakeModel()) -> FreeWakeSolution:
    """Free wake of all ``rotors`` (module doc), from the Beddoes wake as initial guess; each
    group of :func:`coupled_groups` is relaxed together, the groups independently (a rotor alone
    in its group gets exactly its isolated wake).

    Raises :class:`FreeWakeError` naming the rotor, the iteration and the residual when a node
    becomes non-finite, the residual exceeds one radius (divergence) or ``max_iterations`` pass
    without max |ΔX| < ``tolerance_radius_fraction`` · R for every rotor of a group;
    :class:`nps.core.periods.PeriodError` (before any relaxation) when ``model.common_period`` finds no
    common period of a group's speeds.
    """
    rotors = tuple(rotors)
    if not rotors:
        raise ValueError("free wake: expected at least one rotor")
    names = [r.name for r in rotors]
    if len(set(names)) != len(names):
        raise ValueError(f"free wake: rotor names must be unique, got {names}")
    groups = coupled_groups(rotors)
    # every group's common period found (or refused, PeriodError) before the first relaxation
    periodic = {group: period_timing([rotors[i] for i in group], model) for group in groups
                if model.common_period and len({rotors[i].state.omega_rad_s for i in group}) > 1}
    parts: list[np.ndarray | None] = [None] * len(rotors)
    timed = []  # (group, timing) of the groups relaxed over a common period
    slowest = (0, np.zeros(0))
    for group in groups:
        members = [rotors[i] for i in group]
        own = own_timing(members)
        part, iterations, history = _relax_group(members, beddoes, model, own)
        if group in periodic:
            timing = periodic[group]  # from the own-period wake, repeated over the period
            start = [np.tile(d, (int(m), 1, 1)) for d, m in zip(part, timing.revolutions)]
            part, more, history = _relax_group(members, beddoes, model, timing, start)
            iterations += more
            timed.append((group, timing))
        for i, d in zip(group, part):
            parts[i] = d
        if iterations > slowest[0]:
            slowest = (iterations, history)
    timing = _solution_timing(rotors, timed)
    distortion = np.zeros((len(rotors), max(len(d) for d in parts)) + parts[0].shape[1:])
    for q, d in enumerate(parts):
        distortion[q, : len(d)] = d
    return FreeWakeSolution(rotors, beddoes, model, distortion, slowest[0], slowest[1], groups, timing)


def _solution_timing(rotors, timed) -> WakeTiming | None:
    """The timing of all rotors from their own-period timing and the groups relaxed over a common
    period (None when there are none)."""
    if not timed:
        return None
    out = own_timing(rotors)
    shifts = np.zeros((len(rotors), max(out.blade_shift_rad.shape[1], *(t.blade_shift_rad.shape[1] for _, t in timed))))
    shifts[:, : out.blade_shift_rad.shape[1]] = out.blade_shift_rad
    revolutions, ratio, mismatch = out.revolutions.copy(), out.speed_ratio.copy(), out.shift_mismatch.copy()
    for group, timing in timed:
        index = np.array(group)
        revolutions[index] = timing.revolutions
        ratio[np.ix_(index, index)] = timing.speed_ratio
        shifts[index, : timing.blade_shift_rad.shape[1]] = timing.blade_shift_rad
        mismatch[index] = timing.shift_mismatch
    return WakeTiming(revolutions, ratio, shifts, mismatch, tuple(t.periods[0] for _, t in timed))


def _relax_group(rotors, beddoes, model, timing: WakeTiming, start=None) -> tuple[list[np.ndarray], int, np.ndarray]:
    """Relaxation of coupled rotors timed by ``timing``, from the distortion ``start`` (None: zero, the
    Beddoes wake): (distortion of each rotor (N m_q, J+J_far+1, 3), iterations, residual history)."""
    names = [r.name for r in rotors]
    base = [_node_table(r, beddoes, model, int(m)) for r, m in zip(rotors, timing.revolutions)]
    distortion = [np.zeros_like(b) for b in base] if start is None else list(start)
    radius = np.array([r.state.radius_m for r in rotors])
    dt = np.array([model.step_rad / r.state.omega_rad_s for r in rotors])
    history = []
    n = len(rotors)
    for iteration in range(1, model.max_iterations + 1):
        x_old = [base[q] + distortion[q] for q in range(n)]
        v_old = _node_velocities(rotors, beddoes, model, base, distortion, timing)
        predicted = [_march(x_old[q], v_old[q], dt[q]) for q in range(n)]
        _check_finite(rotors, predicted, iteration, "predictor")
        v_pred = _node_velocities(rotors, beddoes, model, base, [predicted[q] - base[q] for q in range(n)], timing)
        corrected = [_march(x_old[q], 0.5 * (v_old[q] + v_pred[q]), dt[q]) for q in range(n)]
        x_new = [x_old[q] + model.relaxation * (corrected[q] - x_old[q]) for q in range(n)]
        _check_finite(rotors, x_new, iteration, "corrector")
        change = np.array([np.abs(x_new[q] - x_old[q]).max() / radius[q] for q in range(n)])
        history.append(float(change.max()))
        distortion = [x_new[q] - base[q] for q in range(n)]
        worst = int(np.argmax(change))
        if change[worst] > 1.0:
            raise FreeWakeError(f"free wake diverged: rotor '{names[worst]}', iteration {iteration}, "
                                f"node change {change[worst]:.3g} R (> 1 R)")
        if change.max() < model.tolerance_radius_fraction:
            return distortion, iteration, np.array(history)
    raise FreeWakeError(
        f"free wake did not converge: rotor '{names[worst]}', {model.max_iterations} iterations, node change "
        f"{change[worst]:.3g} R between the last two (tolerance {model.tolerance_radius_fraction:g} R)")


def _check_finite(rotors, x, iteration, stage):
    for q, r in enumerate(rotors):
        if not np.isfinite(x[q]).all():
            raise FreeWakeError(f"free wake: non-finite node positions of rotor '{r.name}' in the {stage} of "
                                f"iteration {iteration}")


def disk_induced_velocity(solution: FreeWakeSolution, target: str, psi_rad, r_m, beta_rad) -> np.ndarray:
    """Velocity (n_rotors, n_psi, n_r, 3) in the target rotor's H' (m/s) induced at its blade
    stations by each rotor's free wake (index = ``solution.rotors`` order; zero for rotors
    outside the target's coupled group).

    ``psi_rad`` (n_psi,) target blade-0 azimuths (over the target's m revolutions of a common period:
    ψ in [0, 2πm), :meth:`FreeWakeSolution.revolutions`), ``r_m`` (n_r,), ``beta_rad`` broadcastable to
    (n_psi, n_r). Segments 2π/``beddoes.steps_per_rev`` long, lifting-line core of the
    Beddoes model; with a zero distortion the target's own term equals
    :func:`nps.wake.prescribed.disk_induced_velocity`.
    """
    t = solution.index(target)
    group = list(solution.group_of(t))
    psi = np.ascontiguousarray(psi_rad, dtype=float)
    points = wake.blade_points(psi, r_m, beta_rad)
    rotors = [solution.rotors[i] for i in group]
    timing = _group_timing(solution, group)
    sources = _lifting_line_sources(rotors, solution.beddoes, _tables(solution, group), timing)
    model = solution.model
    n_group = int(round(math.radians(model.far_group_deg) / solution.beddoes.dphi_rad))
    out = np.zeros((len(solution.rotors),) + points.shape)
    out[group] = _induced(rotors, sources, timing, [group.index(t)], points[None], psi, solution.beddoes.n_age,
                          solution.beddoes.dphi_rad, model.step_rad, False, n_group, model.far_group_distance)[0]
    return out


def _tables(solution: FreeWakeSolution, indices) -> list[np.ndarray]:
    """The distortion tables of rotors ``indices`` (each its own N m_q rows)."""
    n = solution.model.steps_per_rev
    return [solution.distortion_m[i, : n * solution.revolutions(i)] for i in indices]


def _group_timing(solution: FreeWakeSolution, indices) -> WakeTiming:
    """The timing of the rotors ``indices`` (own periods unless the solution has a common period)."""
    rotors = [solution.rotors[i] for i in indices]
    if solution.timing is None:
        return own_timing(rotors)
    t, index = solution.timing, np.array(indices)
    width = max(r.state.n_blades for r in rotors)
    return WakeTiming(t.revolutions[index], np.ascontiguousarray(t.speed_ratio[np.ix_(index, index)]),
                      np.ascontiguousarray(t.blade_shift_rad[index, :width]), t.shift_mismatch[index], t.periods)


def snapshot_nodes(solution: FreeWakeSolution, rotor: str, psi_blade_rad: float) -> np.ndarray:
    """Nodes (B, J+1, 3) of the rotor's tip vortices in its own H' (m) when its blade 0 is at
    ``psi_blade_rad``, on the relaxation age grid (for plots and PIV comparisons)."""
    return _snapshot(solution, rotor, psi_blade_rad, solution.model.n_age, solution.model.step_rad)[0]


def wake_snapshot(solution: FreeWakeSolution, rotor: str, psi_blade_rad: float) -> wake.WakeSnapshot:
    """The free wake as a :class:`nps.wake.prescribed.WakeSnapshot` on the Beddoes model's age grid (the
    ``wake/{rotor}.parquet`` artifact via ``nps.wake.prescribed.wake_table(..., snapshot=...)``); node
    strength Γ_v and the physical core radius of the node kinematics."""
    n_age, step = solution.beddoes.n_age, solution.beddoes.dphi_rad
    nodes, strength, radius = _snapshot(solution, rotor, psi_blade_rad, n_age, step)
    return wake.WakeSnapshot(float(psi_blade_rad), nodes, np.arange(n_age + 1) * step, strength, radius)


def _snapshot(solution, rotor, psi_blade_rad, n_age, step):
    q = solution.index(rotor)
    indices = list(range(len(solution.rotors)))
    sources = _physical_sources(solution.rotors, solution.beddoes, solution.model, _tables(solution, indices),
                                _group_timing(solution, indices))
    n_b = solution.rotors[q].state.n_blades
    nodes = np.empty((n_b, n_age + 1, 3))
    strength = np.empty((n_b, n_age + 1))
    radius = np.empty((n_b, n_age + 1))
    row = np.empty((n_b, n_age + 1), dtype=np.int64)
    _rotor_nodes(sources.params[q], sources.gamma[q], sources.beta[q], sources.distortion[q], sources.table_rows[q],
                 sources.revolutions[q], sources.blade_shift[q], solution.model.step_rad, sources.core[q],
                 float(psi_blade_rad), n_age, step, 1, nodes, strength, radius, row)
    return nodes, strength, radius
