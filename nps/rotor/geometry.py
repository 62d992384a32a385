"""Rotor description shared by the loads, wake, BVI and acoustics stages.

Geometry comes from an aircraft configuration file (``config/aircraft/*.yaml``, validated
by ``nps/app/schemas/aircraft.schema.yaml``); the operating point comes from the aircraft
trim artifact (``trim.parquet``, one row per rotor). Frames and signs: docs/reference/conventions.md.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from nps.rotor.airfoils import Airfoil, LinearAirfoil, read_airfoil, section_coefficients
from nps.rotor.blade import BladeError, BladeTable, blade_from_config

ARTICULATED, TEETERING, HINGELESS = "articulated", "teetering", "hingeless"
HUBS = (ARTICULATED, TEETERING, HINGELESS)
MAX_FLAP_FREQUENCY_PER_REV = 3.0  # ν_β of a rigid flapping blade: hingeless rotors lie near 1.05–1.2/rev


def without_rotor_label(where: str, message: str) -> str:
    """``message`` without its leading ``rotor '<name>': `` when ``where`` (the place a caller puts before it)
    already ends with that rotor's name (``rotor 'main'``, ``rotors[0] 'main'``): each message names a rotor once."""
    label = re.match(r"rotor '([^']*)': ", message)
    named = label and re.search(rf"(rotor|\]) '{re.escape(label.group(1))}'$", where)
    return message[label.end():] if named else message


class HubError(BladeError):
    """The hub fields of a rotor (``hub``, ``precone_deg``, ``delta3_deg``, ``flap_frequency_per_rev``) do not
    describe a hub NPS models
    (a :class:`~nps.rotor.blade.BladeError`, so configuration loading reports it with the file and rotor)."""


@dataclass(frozen=True)
class RotorGeometry:
    """Blade and hub description of one rotor (SI units).

    Pitch θ(ψ, r) = θ0 + θ1c cos ψ + θ1s sin ψ + θtw(r), θ0 the pitch at 75 % radius. Without a
    blade table (``blade`` None) the blade is the linear shorthand: constant ``chord_m`` and
    ``thickness_ratio``, linear twist θtw(r) = twist_rad · (r/R − 0.75), ``airfoil`` at every
    section. With a :class:`~nps.rotor.blade.BladeTable` the sections take the table's local chord,
    twist, t/c and airfoil (names looked up in ``airfoils``; ``airfoil`` where the table names
    none), and ``chord_m``, ``thickness_ratio``, ``airfoil`` are the rotor's reference values
    (thrust-weighted chord for σ and I_β, t/c and airfoil at 75 % radius; ``twist_rad`` unused),
    as :meth:`from_config` sets them. ``hinge_offset_m`` e of the flap hinge; ``lock_number``
    γ = ρ a c R⁴ / I_β (at the reference density of the configuration, a and c the reference
    lift slope and chord).

    Optional prescribed blade motion (e.g. a wind-tunnel test run as measured; empty = none):
    ``higher_harmonic_pitch`` ((n, θ_n rad, ψ_n rad), ...) adds Σ θ_n cos(nψ − ψ_n) to the pitch
    of the whole blade (higher-harmonic control); ``elastic_twist_harmonics`` ((n, c_n rad,
    s_n rad), ...) adds (r/R) Σ (c_n cos nψ + s_n sin nψ), an elastic torsion given at the tip
    and linear along the span (n = 0 is the mean); ``prescribed_flap_harmonics`` ((n, c_n rad,
    s_n rad), ...) replaces the computed rigid flapping by the measured blade motion
    β(ψ) = Σ (c_n cos nψ + s_n sin nψ) (n = 0 the mean, precone included; tip up positive), the
    flap angle whose sine is the tip height over R (the wake's release height, the blade points
    of the BVI loads) and whose rate enters U_P (:mod:`nps.rotor.bet`, the trim then meets the hub
    moments with the aerodynamic first-harmonic flap moment).

    Hub and pitch–flap coupling (docs/reference/loads.md, "Hingeless rotors", "Teetering rotors",
    "Pitch–flap coupling (δ3)"): ``hub`` is ``articulated`` (every blade flaps on its own hinge at
    ``hinge_offset_m``, coning free), ``hingeless`` (every blade an equivalent rigid blade hinged at
    ``hinge_offset_m`` with a flap spring whose zero is the built-in coning ``precone_rad``; the rotating
    flap frequency ``flap_frequency_per_rev`` ν_β (per rev) sets the spring, none: no spring, the offset
    alone) or ``teetering`` (two blades in one piece on a central teeter hinge: n_blades 2, hinge offset 0;
    the blades flap equal and opposite about the fixed coning ``precone_rad``, no hub moment).
    ``delta3_rad`` δ3 adds θ = −tan δ3 · β_h to the pitch, β_h = β − precone the flap angle from the
    blade's unloaded position (β for an articulated blade, the teeter angle for a teetering rotor).
    """

    name: str
    n_blades: int
    radius_m: float
    chord_m: float
    root_cutout_m: float
    twist_rad: float
    thickness_ratio: float
    lock_number: float
    hinge_offset_m: float = 0.0
    rotation_sign: int = 1
    airfoil: Airfoil = field(default_factory=LinearAirfoil)
    blade: BladeTable | None = None
    airfoils: Mapping[str, Airfoil] = field(default_factory=dict)
    higher_harmonic_pitch: tuple[tuple[int, float, float], ...] = ()
    elastic_twist_harmonics: tuple[tuple[int, float, float], ...] = ()
    prescribed_flap_harmonics: tuple[tuple[int, float, float], ...] = ()
    hub: str = ARTICULATED
    delta3_rad: float = 0.0
    precone_rad: float = 0.0
    flap_frequency_per_rev: float | None = None

    def __post_init__(self):
        check_hub(self)
        if self.blade is not None:
            self.blade.check_covers(self.root_cutout_m, self.radius_m)
            missing = sorted(set(self.blade.airfoils) - set(self.airfoils))
            if missing:
                raise BladeError(f"{self.blade.source}: airfoil: rotor '{self.name}' defines no airfoil named "
                                 f"'{missing[0]}'; defined: {sorted(self.airfoils)}")

    @property
    def solidity(self) -> float:
        """σ = B c / (π R) (c the reference chord)."""
        return self.n_blades * self.chord_m / (np.pi * self.radius_m)

    def twist_at(self, r_m) -> np.ndarray:
        """θtw(r) in rad, zero at 75 % radius."""
        if self.blade is None:
            return self.twist_rad * (np.asarray(r_m, dtype=float) / self.radius_m - 0.75)
        return self.blade.at(r_m).twist_rad - self.blade.at(0.75 * self.radius_m).twist_rad

    def chord_at(self, r_m):
        """Local chord (m) at radii ``r_m``; the scalar ``chord_m`` for the linear shorthand."""
        return self.chord_m if self.blade is None else self.blade.at(r_m).chord_m

    def thickness_ratio_at(self, r_m):
        """Local t/c at radii ``r_m``; the scalar ``thickness_ratio`` for the linear shorthand."""
        return self.thickness_ratio if self.blade is None else self.blade.at(r_m).thickness_ratio

    def coefficients_at(self, alpha_mod_rad, reverse_flow, mach, r_m):
        """(c_l, c_d, c_m) of the local sections: the mod-π angle α, the reverse-flow mask
        (U_T < 0) and M at radii ``r_m``, all broadcast; blended between table stations with
        different airfoils (:meth:`nps.rotor.blade.BladeTable.airfoil_weights`)."""
        if self.blade is None or not self.blade.airfoils:
            return section_coefficients(self.airfoil, alpha_mod_rad, reverse_flow, mach)
        weights = {k: w for k, w in self.blade.airfoil_weights(r_m).items() if w.any()}
        if len(weights) == 1:
            return section_coefficients(self.airfoils[next(iter(weights))], alpha_mod_rad, reverse_flow, mach)
        total = None
        for name, w in weights.items():
            part = [w * c for c in section_coefficients(self.airfoils[name], alpha_mod_rad, reverse_flow, mach)]
            total = part if total is None else [t + p for t, p in zip(total, part)]
        return tuple(total)

    def prescribed_pitch(self, psi_rad, r_m) -> np.ndarray | None:
        """Prescribed pitch (rad), (n_psi, n_r), of the higher-harmonic and elastic-twist
        inputs at azimuths ``psi_rad`` (n_psi,) and stations ``r_m`` (n_r,); None without them."""
        if not (self.higher_harmonic_pitch or self.elastic_twist_harmonics):
            return None
        psi = np.asarray(psi_rad, dtype=float)[:, None]
        rbar = np.asarray(r_m, dtype=float)[None, :] / self.radius_m
        hhc = sum((amp * np.cos(n * psi - phase) for n, amp, phase in self.higher_harmonic_pitch), np.zeros_like(psi))
        return hhc + rbar * _fourier_series(self.elastic_twist_harmonics, psi)

    def prescribed_flap(self, psi_rad) -> tuple[np.ndarray, np.ndarray] | None:
        """(β, dβ/dψ) in rad, (n_psi,), of ``prescribed_flap_harmonics`` at ``psi_rad``; None without them."""
        if not self.prescribed_flap_harmonics:
            return None
        psi = np.asarray(psi_rad, dtype=float)
        rate = tuple((n, n * s, -n * c) for n, c, s in self.prescribed_flap_harmonics)
        return _fourier_series(self.prescribed_flap_harmonics, psi), _fourier_series(rate, psi)

    @classmethod
    def from_config(cls, rotor: Mapping) -> "RotorGeometry":
        """Build from one validated ``rotors[]`` entry of an aircraft configuration.

        Table paths (``airfoil.table``, ``airfoils.*.table``, ``blade.table``) are read as given
        (:func:`nps.app.config.load_aircraft` makes them absolute, relative to the aircraft file).
        Optional prescribed motion entries: ``higher_harmonic_pitch: [{n, amplitude_deg,
        phase_deg}, ...]``, ``elastic_twist_harmonics: [{n, cos_deg, sin_deg}, ...]``,
        ``prescribed_flap: [{n, cos_deg, sin_deg}, ...]``.
        """
        name = str(rotor["name"])
        radius = float(rotor["radius_m"])
        root = float(rotor["root_cutout_m"])
        blade = None
        if "blade" in rotor:
            blade = blade_from_config(rotor["blade"], radius, f"rotor '{name}': blade")
            chord = blade.equivalent_chord_m(root, radius)
            twist = 0.0
            thickness = float(blade.at(0.75 * radius).thickness_ratio)
        else:
            chord = float(rotor["chord_m"])
            twist = np.radians(float(rotor["twist_deg"]))
            thickness = float(rotor["thickness_ratio"])
        aspect_ratio = min((radius - root) / chord, 50.0)
        airfoil = airfoil_from_config(rotor.get("airfoil", {}), aspect_ratio)
        airfoils = {key: airfoil_from_config(value, aspect_ratio) for key, value in rotor.get("airfoils", {}).items()}
        if blade is not None and blade.airfoils:
            reference = blade.airfoils[int(np.argmin(np.abs(blade.radius_m - 0.75 * radius)))]
            airfoil = airfoils.get(reference, airfoil)
        return cls(
            name=name,
            n_blades=int(rotor["n_blades"]),
            radius_m=radius,
            chord_m=chord,
            root_cutout_m=root,
            twist_rad=twist,
            thickness_ratio=thickness,
            lock_number=float(rotor["lock_number"]),
            hinge_offset_m=float(rotor.get("hinge_offset_m", 0.0)),
            rotation_sign=1 if rotor["rotation"] == "ccw" else -1,
            airfoil=airfoil,
            blade=blade,
            airfoils=airfoils,
            higher_harmonic_pitch=tuple(
                (int(h["n"]), math.radians(float(h["amplitude_deg"])), math.radians(float(h["phase_deg"])))
                for h in rotor.get("higher_harmonic_pitch", ())),
            elastic_twist_harmonics=_degree_harmonics(rotor.get("elastic_twist_harmonics", ())),
            prescribed_flap_harmonics=_degree_harmonics(rotor.get("prescribed_flap", ())),
            hub=str(rotor.get("hub", ARTICULATED)),
            delta3_rad=math.radians(float(rotor.get("delta3_deg", 0.0))),
            precone_rad=math.radians(float(rotor.get("precone_deg", 0.0))),
            flap_frequency_per_rev=(None if rotor.get("flap_frequency_per_rev") is None
                                    else float(rotor["flap_frequency_per_rev"])),
        )


def hinge_flap_frequency_sq(geometry: RotorGeometry) -> float:
    """ν_0² = 1 + 3e / (2 (R − e)): the rotating flap frequency (per rev, squared) of a uniform rigid blade
    hinged at e with no spring (Johnson, *Helicopter Theory*, 1980, ch. 9, flap motion with hinge offset)."""
    e = geometry.hinge_offset_m
    return 1.0 + 1.5 * e / (geometry.radius_m - e)


def check_hub(geometry: RotorGeometry) -> None:
    """Raise :class:`HubError` naming the field when the hub fields do not describe a hub NPS models."""
    g, where = geometry, f"rotor '{geometry.name}'"
    if g.hub not in HUBS:
        raise HubError(f"{where}: hub: expected one of {list(HUBS)}, got {g.hub!r}")
    if not (math.isfinite(g.delta3_rad) and abs(g.delta3_rad) < math.radians(89.0)):
        raise HubError(f"{where}: delta3_deg: expected a finite angle within ±89°, got {math.degrees(g.delta3_rad)!r}")
    if g.flap_frequency_per_rev is not None and g.hub != HINGELESS:
        raise HubError(f"{where}: flap_frequency_per_rev: applies to a hingeless hub only (hub: hingeless; an "
                       f"articulated blade's follows from hinge_offset_m), got {g.flap_frequency_per_rev!r} with "
                       f"hub: {g.hub}")
    if g.hub == TEETERING:
        if g.n_blades != 2:
            raise HubError(f"{where}: n_blades: a teetering hub (hub: teetering) carries two blades in one piece, "
                           f"expected n_blades 2, got {g.n_blades}")
        if g.hinge_offset_m != 0.0:
            raise HubError(f"{where}: hinge_offset_m: a teetering hub flaps about the rotor axis, expected 0, "
                           f"got {g.hinge_offset_m}")
    elif g.hub == HINGELESS:
        _check_hingeless(g, where)
    elif g.precone_rad != 0.0:
        raise HubError(f"{where}: precone_deg: applies to a teetering or hingeless hub only (an articulated blade "
                       f"cones freely about its hinge), got {math.degrees(g.precone_rad)!r} with hub: {g.hub}")


def _check_hingeless(g: RotorGeometry, where: str) -> None:
    """A hingeless hub's stiffness: ν_β within [ν_0, MAX_FLAP_FREQUENCY_PER_REV] (a spring ≥ 0), or an offset
    e > 0 without ν_β; a precone only with a spring (its zero)."""
    nu = g.flap_frequency_per_rev
    if nu is None:
        if not g.hinge_offset_m > 0.0:
            raise HubError(f"{where}: flap_frequency_per_rev: a hingeless hub (hub: hingeless) needs its flap "
                           f"stiffness: expected flap_frequency_per_rev (ν_β > 1 per rev) or an equivalent "
                           f"hinge_offset_m > 0, got neither")
        if g.precone_rad != 0.0:
            raise HubError(f"{where}: precone_deg: the precone of a hingeless hub is the zero of its flap spring, "
                           f"and without flap_frequency_per_rev the blade has none (the offset alone): give "
                           f"flap_frequency_per_rev, got precone_deg {math.degrees(g.precone_rad)!r}")
        return
    if not (0.0 <= g.hinge_offset_m < g.radius_m):
        return  # check_geometry names hinge_offset_m
    low = math.sqrt(hinge_flap_frequency_sq(g))
    if not (math.isfinite(nu) and low <= nu <= MAX_FLAP_FREQUENCY_PER_REV):
        raise HubError(f"{where}: flap_frequency_per_rev: expected within [{low:.4g}, {MAX_FLAP_FREQUENCY_PER_REV:g}] "
                       f"(at least the frequency of the hinge offset alone, {low:.4g}/rev with hinge_offset_m "
                       f"{g.hinge_offset_m}: a spring of stiffness >= 0), got {nu!r}")


def _fourier_series(harmonics, psi: np.ndarray) -> np.ndarray:
    """Σ (c_n cos nψ + s_n sin nψ) over ``harmonics`` ((n, c_n, s_n), ...) at ``psi``."""
    return sum((c * np.cos(n * psi) + s * np.sin(n * psi) for n, c, s in harmonics), np.zeros_like(psi))


def _degree_harmonics(entries) -> tuple[tuple[int, float, float], ...]:
    """Config harmonics ``[{n, cos_deg, sin_deg}, ...]`` as ((n, cos rad, sin rad), ...)."""
    return tuple((int(h["n"]), math.radians(float(h["cos_deg"])), math.radians(float(h["sin_deg"]))) for h in entries)


def airfoil_from_config(foil: Mapping, aspect_ratio: float) -> Airfoil:
    """An ``airfoil`` entry: ``{table: path, extrapolation, reynolds}`` or the linear model's
    parameters (defaults of :class:`~nps.rotor.airfoils.LinearAirfoil`); ``aspect_ratio`` of the
    blade for the Viterna extension."""
    if "table" in foil:
        return read_airfoil(foil["table"], extrapolation=foil.get("extrapolation", "none"),
                            aspect_ratio=aspect_ratio, reynolds=foil.get("reynolds"))
    return LinearAirfoil(
        lift_slope_per_rad=float(foil.get("lift_slope_per_rad", LinearAirfoil.lift_slope_per_rad)),
        alpha0_rad=np.radians(float(foil.get("alpha0_deg", 0.0))),
        cl_max=float(foil.get("cl_max", LinearAirfoil.cl_max)),
        cd0=float(foil.get("cd0", LinearAirfoil.cd0)),
        cd1=float(foil.get("cd1", LinearAirfoil.cd1)),
        cd2=float(foil.get("cd2", LinearAirfoil.cd2)),
        mach_cap=float(foil.get("mach_cap", LinearAirfoil.mach_cap)),
    )


@dataclass(frozen=True)
class OperatingPoint:
    """Steady operating state of one rotor from the aircraft trim (one ``trim.parquet`` row).

    Advance ratios in the hub frame (docs/reference/conventions.md): μ_x, μ_y in plane, μ_z positive
    when the free stream goes down through the disk. Targets: thrust along +z_H and hub
    moments about x_H (roll) and y_H (pitch).
    """

    omega_rad_s: float
    mu_x: float
    mu_y: float
    mu_z: float
    density_kg_m3: float
    speed_of_sound_mps: float
    thrust_N: float
    roll_moment_Nm: float = 0.0
    pitch_moment_Nm: float = 0.0

    @classmethod
    def from_trim_row(cls, row: Mapping) -> "OperatingPoint":
        return cls(
            omega_rad_s=float(row["omega_rad_s"]),
            mu_x=float(row["mu_x"]),
            mu_y=float(row["mu_y"]),
            mu_z=float(row["mu_z"]),
            density_kg_m3=float(row["density_kg_m3"]),
            speed_of_sound_mps=float(row["speed_of_sound_mps"]),
            thrust_N=float(row["thrust_N"]),
            roll_moment_Nm=float(row["roll_moment_Nm"]),
            pitch_moment_Nm=float(row["pitch_moment_Nm"]),
        )


@dataclass(frozen=True)
class RotorMotion:
    """Rigid motion of a rotor hub in the ground frame G (one ``trim.parquet`` row).

    Hub position at time t: hub_position_m + velocity_mps · t. ``r_gh`` takes H components
    to G components. Blade k azimuth ψ_k(t) = Ω t + φ + 2πk/B, φ the blade phase (``phase_rad`` of
    :func:`nps.noise.sources.rotor_sources`, default 0).
    """

    hub_position_m: np.ndarray
    velocity_mps: np.ndarray
    r_gh: np.ndarray
    omega_rad_s: float
    rotation_sign: int
    n_blades: int

    @classmethod
    def from_trim_row(cls, row: Mapping) -> "RotorMotion":
        return cls(
            hub_position_m=np.array([row["hub_x_m"], row["hub_y_m"], row["hub_z_m"]], dtype=float),
            velocity_mps=np.array([row["vel_x_mps"], row["vel_y_mps"], row["vel_z_mps"]], dtype=float),
            r_gh=np.array([[row[f"r_gh_{i}{j}"] for j in range(3)] for i in range(3)], dtype=float),
            omega_rad_s=float(row["omega_rad_s"]),
            rotation_sign=int(row["rotation_sign"]),
            n_blades=int(row["n_blades"]),
        )
