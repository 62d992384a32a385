"""Validity envelope of the NPS models: every quantity checked against its limit before computing.

Each ``check_*`` function tests one quantity against one limit and returns a :class:`Finding`
when the quantity lies outside (``None`` inside). Each stage has one function that takes the
objects it already holds and returns its findings (``aircraft_findings`` before the trim,
``trim_findings``, ``loads_findings``, ``wake_findings``, ``observer_findings``,
``broadband_findings``); :func:`enforce` turns findings into one :class:`ValidityError` line
(default) or, with the campaign switch ``allow_outside_validity: true``, into warnings for the
artifact metadata (``nps.validity_warnings``). Limits, their sources and the choices made where
the literature gives a range: ``docs/reference/validity.md``.

Units SI, angles in rad, frames and advance-ratio signs of docs/reference/conventions.md (μ_z > 0 when
the free stream goes down through the disk, i.e. in climb).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from typing import TYPE_CHECKING, Iterable, Mapping, Sequence

import numpy as np
import pandas as pd

from nps.rotor.bet import MAX_CONTROL_RAD
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.geometry import RotorGeometry, without_rotor_label

if TYPE_CHECKING:  # an annotation only: the trim, loads and observers jobs need no wake module
    from nps.wake.prescribed import WakeModel

JOHNSON_1980 = "Johnson, Helicopter Theory (1980)"
LEISHMAN_2006 = "Leishman, Principles of Helicopter Aerodynamics, 2nd ed. (2006)"

ADVANCE_RATIO_MAX = 0.5
ADVANCE_RATIO_SOURCE = (f"linear inflow + first-harmonic rigid flapping, applied to conventional rotors up to mu ~ 0.5 "
                        f"({JOHNSON_1980}, ch. 5; {LEISHMAN_2006}, ch. 3-4)")
TIP_MACH_SOURCE = ("subsonic sources of Farassat formulation 1A (Farassat, NASA/TM-2007-214853) and the "
                   "Prandtl-Glauert section lift bounded at the airfoil's mach_cap (nps.rotor.airfoils.LinearAirfoil)")
BLADE_LOADING_MAX = 0.14
BLADE_LOADING_SOURCE = (f"thrust-limit (stall) boundary measured by McHugh (1978, AHS 34th Forum), C_T/sigma ~ 0.12-0.13 "
                        f"at its low-mu peak as reproduced in {LEISHMAN_2006}; NPS uses 0.14 at every mu")
MEAN_LIFT_SOURCE = f"uniform-lift blade element relation C_L = 6 C_T/sigma ({JOHNSON_1980}, ch. 2; {LEISHMAN_2006}, ch. 3)"
VRS_AXIAL_RANGE = (-2.0, 0.0)
VRS_EDGEWISE_MAX = 1.0
VRS_SOURCE = (f"momentum theory (Glauert inflow) has no valid solution for -2 < V_z/v_h < 0 ({LEISHMAN_2006}, ch. 2; "
              f"{JOHNSON_1980}, ch. 2); the vortex-ring region closes near V_x ~ v_h (Wolkovitch, J. AHS 17(3), 1972; "
              f"Johnson, NASA/TP-2005-213477)")
LOCK_NUMBER_RANGE = (1.0, 25.0)
LOCK_NUMBER_SOURCE = (f"Lock numbers of real blades lie between about 3 and 15 ({JOHNSON_1980}, ch. 5; "
                      f"{LEISHMAN_2006}, ch. 4); NPS bounds 1-25")
FLAP_ANGLE_MAX_RAD = math.radians(15.0)
FLAP_ANGLE_SOURCE = (f"linearised flap equation (sin b cos b ~ b, {JOHNSON_1980}, ch. 5): centrifugal moment error "
                     f"<= 4.5 % up to 15 deg")
CONTROL_SOURCE = ("the rotor trim searches |theta0|, |theta1c|, |theta1s| < 0.7 rad (nps.rotor.bet); "
                  "a control at the bound is not a trim")
WAKE_DIAMETERS = 2.0
WAKE_SOURCE = ("oldest tip-vortex node at least one rotor diameter from its release point, travel "
               "phi R sqrt(mu^2 + lambda^2) (Beddoes geometry, thesis eq. 5.4-5.7), and at least one revolution")
OBSERVER_CHORDS_MIN = 5.0
OBSERVER_CHORD_SOURCE = ("compact-chord sources: the distance varies by c/2 across the chord, <= 10 % of the distance "
                         "from 5 chords on (docs/reference/validity.md)")
OBSERVER_RADII_MIN = 1.0
OBSERVER_RADIUS_SOURCE = ("observer outside the sphere holding the blades: the acoustic analogy takes the observer in "
                          "a medium at rest (Farassat, NASA/TM-2007-214853), Pegg's level a far-field 1/r^2 law "
                          "(NASA TM-80200)")
PEGG_SOURCE = "Pegg, NASA TM-80200 (1979), eq. 3.1-3.3 (thesis)"
DENSITY_RANGE_KG_M3 = (0.05, 10.0)
SPEED_OF_SOUND_RANGE_MPS = (100.0, 600.0)
INCOMPRESSIBLE_SPEED_OF_SOUND_MPS = 1.0e6  # and above: a deliberate incompressible limit (closed-form rig checks)
ATMOSPHERE_SOURCE = ("plausible gas: air from the ISA at 11 km (0.36 kg/m^3, 295 m/s) to cold sea level (1.55 kg/m^3), "
                     "heavy-gas wind tunnels (R-134a, about 4 kg/m^3 and 165 m/s) included; outside, a unit error "
                     "(g/m^3, km/s) is likely (NPS choice, docs/reference/validity.md)")


class ValidityError(ValueError):
    """An input lies outside the validity envelope of a model; one line names quantity, value, limit, source."""


@dataclass(frozen=True)
class Finding:
    """One quantity outside its validity limit.

    ``quantity``: what was checked and where (e.g. ``rotor 'main': advance ratio mu``);
    ``value``: its value (units in ``quantity``); ``limit``: the condition it violates, as text;
    ``source``: where the limit comes from; ``stage``: the stage that checked it.
    """

    quantity: str
    value: float
    limit: str
    source: str
    stage: str

    def message(self) -> str:
        return f"{self.quantity} = {self.value:.4g} is outside the validity limit {self.limit} [source: {self.source}]"

    def as_dict(self) -> dict:
        return {**asdict(self), "value": float(self.value), "message": self.message()}


def enforce(findings: Iterable[Finding | None], allow_outside_validity: bool, where: str) -> list[dict]:
    """Refuse (default) or record findings; ``None`` entries (checks passed) are ignored.

    Raises :class:`ValidityError` with one line ``<where>: <first finding>`` (+ the names of the
    others) unless ``allow_outside_validity``; then returns the findings as JSON-ready dicts for
    the artifact metadata key ``validity_warnings`` (empty list when everything is inside).
    """
    found = [f for f in findings if f is not None]
    if found and not allow_outside_validity:
        others = (f"; also outside: {', '.join(without_rotor_label(where, f.quantity) for f in found[1:])}"
                  if len(found) > 1 else "")
        raise ValidityError(f"{where}: {without_rotor_label(where, found[0].message())}{others}; "
                            f"set allow_outside_validity: true in the campaign to run it with a warning")
    return [f.as_dict() for f in found]


def recorded(findings: Iterable[Finding | None], params: Mapping, where: str) -> dict:
    """A stage's validity metadata: :func:`enforce` with the switch ``params["allow_outside_validity"]``
    (default false); ``{"validity_warnings": [...]}`` when findings were allowed, ``{}`` when there are
    none (so an artifact inside the envelope carries no extra key)."""
    warnings = enforce(findings, bool(params.get("allow_outside_validity", False)), where)
    return {"validity_warnings": warnings} if warnings else {}


def report(metadata: Mapping) -> str:
    """Lines ``warning: <finding>`` of the ``validity_warnings`` in a stage's metadata, for its log."""
    return "".join(f"\nwarning: {w['message']}" for w in metadata.get("validity_warnings", []))


def _above(quantity: str, value: float, limit: float, source: str, stage: str) -> Finding | None:
    """Finding when ``value`` > ``limit`` (or is not finite)."""
    if math.isfinite(value) and value <= limit:
        return None
    return Finding(quantity, float(value), f"<= {limit:.4g}", source, stage)


def _below(quantity: str, value: float, limit: float, source: str, stage: str) -> Finding | None:
    """Finding when ``value`` < ``limit`` (or is not finite)."""
    if math.isfinite(value) and value >= limit:
        return None
    return Finding(quantity, float(value), f">= {limit:.4g}", source, stage)


# ---------------------------------------------------------------------------------------------
# single checks
# ---------------------------------------------------------------------------------------------

def check_advance_ratio(mu: float, name: str, stage: str = "trim") -> Finding | None:
    """In-plane advance ratio μ = |(μ_x, μ_y)| ≤ 0.5."""
    return _above(f"rotor '{name}': advance ratio mu", mu, ADVANCE_RATIO_MAX, ADVANCE_RATIO_SOURCE, stage)


def check_tip_mach_hover(omega_rad_s: float, radius_m: float, speed_of_sound_mps: float, name: str,
                         mach_cap: float = LinearAirfoil.mach_cap, stage: str = "config") -> Finding | None:
    """Hover tip Mach number ΩR/c ≤ the airfoil's ``mach_cap`` (checkable before the trim)."""
    return _above(f"rotor '{name}': hover tip Mach number", omega_rad_s * radius_m / speed_of_sound_mps, mach_cap,
                  TIP_MACH_SOURCE, stage)


def check_tip_mach_advancing(tip_mach: float, mu: float, name: str, mach_cap: float = LinearAirfoil.mach_cap,
                             stage: str = "trim") -> Finding | None:
    """Advancing-tip Mach number M_tip (1 + μ) ≤ the airfoil's ``mach_cap``."""
    return _above(f"rotor '{name}': advancing tip Mach number", tip_mach * (1.0 + mu), mach_cap, TIP_MACH_SOURCE, stage)


def check_blade_loading(ct: float, solidity: float, name: str, stage: str = "trim") -> Finding | None:
    """Blade loading C_T/σ ≤ 0.14 (stall boundary)."""
    return _above(f"rotor '{name}': blade loading C_T/sigma", ct / solidity, BLADE_LOADING_MAX, BLADE_LOADING_SOURCE, stage)


def check_mean_lift_coefficient(ct: float, solidity: float, cl_max: float, name: str, stage: str = "trim") -> Finding | None:
    """Mean lift coefficient 6 C_T/σ ≤ the airfoil's c_l,max."""
    return _above(f"rotor '{name}': mean lift coefficient 6 C_T/sigma", 6.0 * ct / solidity, cl_max, MEAN_LIFT_SOURCE, stage)


def check_vortex_ring(mu: float, mu_z: float, ct: float, name: str, stage: str = "trim") -> Finding | None:
    """Vortex-ring / turbulent-wake region: −2 < V_z/v_h < 0 with V_x/v_h < 1.

    V_x = μ ΩR (edgewise), V_z = μ_z ΩR (NPS sign: > 0 in climb), v_h = ΩR √(C_T/2) the hover
    induced velocity at the rotor's thrust. Rotors without positive thrust are not checked here.
    """
    if not ct > 0.0:
        return None
    v_h = math.sqrt(0.5 * ct)
    vx, vz = mu / v_h, mu_z / v_h
    low, high = VRS_AXIAL_RANGE
    if vx < VRS_EDGEWISE_MAX and low < vz < high:
        return Finding(f"rotor '{name}': descent rate V_z/v_h (at V_x/v_h = {vx:.3g})", vz,
                       f"V_z/v_h <= {low:g} or >= {high:g} when V_x/v_h < {VRS_EDGEWISE_MAX:g} (vortex-ring state)",
                       VRS_SOURCE, stage)
    return None


def check_lock_number(lock_number: float, name: str, stage: str = "config") -> Finding | None:
    """Lock number γ within [1, 25]."""
    low, high = LOCK_NUMBER_RANGE
    if math.isfinite(lock_number) and low <= lock_number <= high:
        return None
    return Finding(f"rotor '{name}': Lock number", float(lock_number), f"within [{low:g}, {high:g}]",
                   LOCK_NUMBER_SOURCE, stage)


def check_atmosphere(density_kg_m3: float, speed_of_sound_mps: float, where: str = "atmosphere",
                     stage: str = "config") -> list[Finding]:
    """Density within 0.05-10 kg/m³ and speed of sound within 100-600 m/s (a gas a rotor can run in); a
    speed of sound of at least :data:`INCOMPRESSIBLE_SPEED_OF_SOUND_MPS` is the incompressible limit of
    closed-form checks, not a unit error, and passes."""
    out = []
    for key, value, (low, high) in (("density_kg_m3", density_kg_m3, DENSITY_RANGE_KG_M3),
                                    ("speed_of_sound_mps", speed_of_sound_mps, SPEED_OF_SOUND_RANGE_MPS)):
        if key == "speed_of_sound_mps" and math.isfinite(value) and value >= INCOMPRESSIBLE_SPEED_OF_SOUND_MPS:
            continue
        if not (math.isfinite(value) and low <= value <= high):
            out.append(Finding(f"{where}.{key}", float(value), f"within [{low:g}, {high:g}]", ATMOSPHERE_SOURCE, stage))
    return out


def check_flap_angle(beta0_rad: float, beta1c_rad: float, beta1s_rad: float, name: str,
                     stage: str = "loads") -> Finding | None:
    """Largest flap angle |β0| + √(β1c² + β1s²) ≤ 15°."""
    beta_max = abs(beta0_rad) + math.hypot(beta1c_rad, beta1s_rad)
    return _above(f"rotor '{name}': largest flap angle (rad)", beta_max, FLAP_ANGLE_MAX_RAD, FLAP_ANGLE_SOURCE, stage)


def check_controls(theta0_rad: float, theta1c_rad: float, theta1s_rad: float, name: str,
                   stage: str = "loads") -> Finding | None:
    """Every trimmed control strictly inside the trim's search bound (|θ| < 0.7 rad)."""
    controls = {"theta0_rad": theta0_rad, "theta1c_rad": theta1c_rad, "theta1s_rad": theta1s_rad}
    key = max(controls, key=lambda k: abs(controls[k]))
    value = abs(controls[key])
    if math.isfinite(value) and value < MAX_CONTROL_RAD * (1.0 - 1e-9):
        return None
    return Finding(f"rotor '{name}': trimmed control |{key}|", value, f"< {MAX_CONTROL_RAD:g}", CONTROL_SOURCE, stage)


def minimum_wake_revolutions(mu: float, inflow_ratio: float) -> float:
    """max(1, 2 / (2π √(μ² + λ²))): revolutions for the oldest vortex to travel one diameter."""
    speed = math.hypot(mu, inflow_ratio)
    return max(1.0, WAKE_DIAMETERS / (2.0 * math.pi * speed)) if speed > 0.0 else math.inf


def check_wake_length(revolutions: float, mu: float, inflow_ratio: float, name: str, stage: str = "wake") -> Finding | None:
    """Wake revolutions ≥ :func:`minimum_wake_revolutions` (μ in-plane, λ = μ_z + λ_i)."""
    return _below(f"rotor '{name}': wake_revolutions", revolutions, minimum_wake_revolutions(mu, inflow_ratio),
                  WAKE_SOURCE, stage)


@dataclass(frozen=True)
class BladePath:
    """Where one rotor's blades sweep: the annulus root_cutout_m ≤ r ≤ radius_m in the hub plane.

    ``hub_m``: hub in G at t = 0 (m); ``velocity_mps``: hub velocity in G; ``r_gh``: H → G
    rotation (3 × 3). The coning (β0 R, small for the bundled rotors) is not included.
    """

    name: str
    hub_m: np.ndarray
    velocity_mps: np.ndarray
    r_gh: np.ndarray
    radius_m: float
    root_cutout_m: float
    chord_m: float

    def distances(self, observers_m: np.ndarray, observer_velocity_mps: np.ndarray, times_s: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray]:
        """(distance to the blade annulus, distance to the hub), m, shape (n_obs,), minimum over ``times_s``."""
        to_blade = np.full(len(observers_m), np.inf)
        to_hub = np.full(len(observers_m), np.inf)
        for t in np.atleast_1d(times_s):
            rel = (observers_m + observer_velocity_mps * t) - (self.hub_m + self.velocity_mps * t)
            p = rel @ self.r_gh  # H components: p_H = R_GH^T rel
            rho = np.hypot(p[:, 0], p[:, 1])
            nearest = np.clip(rho, self.root_cutout_m, self.radius_m)
            to_blade = np.minimum(to_blade, np.hypot(rho - nearest, p[:, 2]))
            to_hub = np.minimum(to_hub, np.linalg.norm(p, axis=1))
        return to_blade, to_hub


def check_observer_blade_distance(observer_ids: Sequence[int], to_blade_m: np.ndarray, path: BladePath,
                                  stage: str = "observers") -> Finding | None:
    """Smallest observer distance to the blade path ≥ 5 chords; names the closest observer."""
    i = int(np.argmin(to_blade_m))
    return _below(f"observer {int(observer_ids[i])}: distance to rotor '{path.name}' blade path / chord",
                  float(to_blade_m[i] / path.chord_m), OBSERVER_CHORDS_MIN, OBSERVER_CHORD_SOURCE, stage)


def check_observer_hub_distance(observer_ids: Sequence[int], to_hub_m: np.ndarray, path: BladePath,
                                stage: str = "observers") -> Finding | None:
    """Smallest observer distance to the hub ≥ 1 rotor radius; names the closest observer."""
    i = int(np.argmin(to_hub_m))
    return _below(f"observer {int(observer_ids[i])}: distance to rotor '{path.name}' hub / radius",
                  float(to_hub_m[i] / path.radius_m), OBSERVER_RADII_MIN, OBSERVER_RADIUS_SOURCE, stage)


def check_pegg_peak_frequency(thrust_N: float, tip_speed_mps: float, name: str, stage: str = "metrics") -> Finding | None:
    """Pegg's peak frequency (eq. 3.1) positive and inside the analysed bands (10 Hz – 20 kHz)."""
    from nps.noise.broadband.pegg import peak_frequency_hz  # here: the jobs without broadband need no noise module
    from nps.noise.metrics import STUDY_BANDS
    from nps.noise.spectra import band_number_of

    low, high = int(STUDY_BANDS[0]), int(STUDY_BANDS[-1])
    limit = "inside the analysed 1/3-octave bands 10 Hz - 20 kHz"
    try:
        fp = peak_frequency_hz(thrust_N, tip_speed_mps)
    except ValueError as exc:
        return Finding(f"rotor '{name}': Pegg peak frequency f_p (Hz)", math.nan, f"{limit} ({exc})", PEGG_SOURCE, stage)
    if low <= band_number_of(fp) <= high:
        return None
    return Finding(f"rotor '{name}': Pegg peak frequency f_p (Hz)", fp, limit, PEGG_SOURCE, stage)


# ---------------------------------------------------------------------------------------------
# per-stage call sites: the objects each stage already holds -> findings
# ---------------------------------------------------------------------------------------------

def _solidity(rotor: Mapping) -> float:
    return RotorGeometry.from_config(rotor).solidity


def _foil(rotor: Mapping, key: str) -> float:
    return float(rotor.get("airfoil", {}).get(key, getattr(LinearAirfoil, key)))


def _rotor_rows(aircraft: Mapping, trim: pd.DataFrame):
    rotors = {r["name"]: r for r in aircraft["rotors"]}
    for _, row in trim.iterrows():
        if row["rotor"] in rotors:
            yield rotors[row["rotor"]], row


def aircraft_findings(aircraft: Mapping, speed_of_sound_mps: float,
                      omega_scale: Mapping[str, float] | None = None) -> list[Finding]:
    """Before the trim: hover tip Mach number and Lock number of every rotor (stage ``config``).

    ``omega_scale``: the segment's per-rotor speed factors (``rotor_omega_scale``).
    """
    out = []
    for rotor in aircraft["rotors"]:
        omega = rotor["omega_rad_s"] * (omega_scale or {}).get(rotor["name"], 1.0)
        out.append(check_tip_mach_hover(omega, rotor["radius_m"], speed_of_sound_mps, rotor["name"],
                                        _foil(rotor, "mach_cap")))
        out.append(check_lock_number(rotor["lock_number"], rotor["name"]))
    return [f for f in out if f is not None]


def _rpm_hint(found: Finding | None, rotor: Mapping, row: Mapping) -> Finding | None:
    """A blade-loading finding of an ``rpm``-controlled rotor with the solved speed and the pitch that set it."""
    if found is None or rotor["control"] != "rpm":
        return found
    return replace(found, quantity=f"{found.quantity} (control rpm: solved omega_rad_s {row['omega_rad_s']:.4g} at "
                                   f"pitch_deg {rotor['pitch_deg']:g}; a smaller pitch_deg turns the rotor faster at a "
                                   f"lower C_T/sigma)")


def trim_findings(aircraft: Mapping, trim: pd.DataFrame) -> list[Finding]:
    """After the aircraft trim (table of ``nps.rotor.trim.trim_aircraft``): advance ratio, advancing-tip
    Mach number, blade loading, mean lift coefficient and vortex-ring state of every rotor."""
    out = []
    for rotor, row in _rotor_rows(aircraft, trim):
        name, sigma = rotor["name"], _solidity(rotor)
        mu = math.hypot(row["mu_x"], row["mu_y"])
        out += [
            check_advance_ratio(mu, name),
            check_tip_mach_advancing(row["tip_mach"], mu, name, _foil(rotor, "mach_cap")),
            _rpm_hint(check_blade_loading(row["ct"], sigma, name), rotor, row),
            check_mean_lift_coefficient(row["ct"], sigma, _foil(rotor, "cl_max"), name),
            check_vortex_ring(mu, row["mu_z"], row["ct"], name),
        ]
    return [f for f in out if f is not None]


def loads_findings(rotor_name: str, summary: pd.DataFrame) -> list[Finding]:
    """After the rotor trim: flap angle and controls from the loads summary table
    (``RotorTrim.summary()`` / ``loads/{rotor}_summary.parquet``: columns quantity, value)."""
    v = summary.set_index("quantity")["value"]
    out = [
        check_flap_angle(v["beta0_rad"], v["beta1c_rad"], v["beta1s_rad"], rotor_name),
        check_controls(v["theta0_rad"], v["theta1c_rad"], v["theta1s_rad"], rotor_name),
    ]
    return [f for f in out if f is not None]


def wake_findings(model: WakeModel, trim_row: Mapping) -> list[Finding]:
    """Before the wake of one rotor: ``model.revolutions`` against its trim row (μ_x, μ_y, μ_z, λ_i)."""
    mu = math.hypot(trim_row["mu_x"], trim_row["mu_y"])
    found = check_wake_length(model.revolutions, mu, trim_row["mu_z"] + trim_row["lambda_i"], str(trim_row["rotor"]))
    return [found] if found is not None else []


def blade_paths(aircraft: Mapping, trim: pd.DataFrame) -> list[BladePath]:
    """:class:`BladePath` of every rotor from the aircraft configuration and its trim table."""
    paths = []
    for rotor, row in _rotor_rows(aircraft, trim):
        paths.append(BladePath(
            name=rotor["name"],
            hub_m=np.array([row["hub_x_m"], row["hub_y_m"], row["hub_z_m"]], dtype=float),
            velocity_mps=np.array([row["vel_x_mps"], row["vel_y_mps"], row["vel_z_mps"]], dtype=float),
            r_gh=np.array([[row[f"r_gh_{i}{j}"] for j in range(3)] for i in range(3)], dtype=float),
            radius_m=float(rotor["radius_m"]), root_cutout_m=float(rotor["root_cutout_m"]), chord_m=RotorGeometry.from_config(rotor).chord_m,
        ))
    return paths


def observer_findings(observers: pd.DataFrame, aircraft: Mapping, trim: pd.DataFrame, duration_s: float = 0.0,
                      n_times: int = 9) -> list[Finding]:
    """Observer table (``observer``, ``x_m`` … ``vz_mps``, G at t = 0) against every rotor's blade
    path and hub, at ``n_times`` instants over the signal's ``duration_s`` (one reference-rotor
    revolution, 2π/Ω_ref; 0 for observers moving with the aircraft)."""
    if len(observers) == 0:
        return []
    ids = observers["observer"].to_numpy()
    pos = observers[["x_m", "y_m", "z_m"]].to_numpy(float)
    vel = observers[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float)
    times = np.linspace(0.0, duration_s, n_times) if duration_s > 0.0 else np.zeros(1)
    out = []
    for path in blade_paths(aircraft, trim):
        to_blade, to_hub = path.distances(pos, vel, times)
        out += [check_observer_blade_distance(ids, to_blade, path), check_observer_hub_distance(ids, to_hub, path)]
    return [f for f in out if f is not None]


def broadband_findings(aircraft: Mapping, trim: pd.DataFrame) -> list[Finding]:
    """Before Pegg's broadband model: peak frequency and mean lift coefficient (eq. 3.3's C̄_L up to
    the airfoil's c_l,max) of every rotor."""
    out = []
    for rotor, row in _rotor_rows(aircraft, trim):
        name = rotor["name"]
        out += [
            check_pegg_peak_frequency(row["thrust_N"], row["omega_rad_s"] * row["radius_m"], name),
            check_mean_lift_coefficient(row["ct"], _solidity(rotor), _foil(rotor, "cl_max"), name, stage="metrics"),
        ]
    return [f for f in out if f is not None]


def rig_condition_findings(rotor: Mapping, op, control_mode: str) -> list[Finding]:
    """Before a rig's rotor solve (stage ``rig``): the atmosphere, hover tip Mach and Lock number, and,
    where the rotor speed is not trimmed (``collective``, ``fixed``), the advance ratio and advancing-tip
    Mach number of the tunnel speed. ``op``: the rig's :class:`nps.rotor.geometry.OperatingPoint`."""
    name = rotor["name"]
    out = check_atmosphere(op.density_kg_m3, op.speed_of_sound_mps, "condition.atmosphere", stage="rig")
    if out:  # a speed of sound in km/s makes every Mach number below meaningless
        return out
    out += aircraft_findings({"rotors": [{**rotor, "omega_rad_s": op.omega_rad_s}]}, op.speed_of_sound_mps)
    if control_mode != "rpm":
        mu = math.hypot(op.mu_x, op.mu_y)
        out += [check_advance_ratio(mu, name, stage="rig"),
                check_tip_mach_advancing(op.omega_rad_s * RotorGeometry.from_config(rotor).radius_m / op.speed_of_sound_mps,
                                         mu, name, _foil(rotor, "mach_cap"), stage="rig")]
    return [f for f in out if f is not None]


def rig_findings(rotor: Mapping, trim: pd.DataFrame, summary: pd.DataFrame, microphones: pd.DataFrame) -> list[Finding]:
    """After a rig's rotor solve, before its artifacts: the trim checks (:func:`trim_findings`), flap angle and
    controls of the solved rotor (:func:`loads_findings` of ``summary``, ``RotorTrim.summary()``) and the
    microphones against the blade path and hub (:func:`observer_findings`; they move with the hub)."""
    one = {"rotors": [rotor]}
    return trim_findings(one, trim) + loads_findings(rotor["name"], summary) + observer_findings(microphones, one, trim)


def pegg_range_notes(trim: pd.DataFrame, rotors: Sequence[str]) -> list[str]:
    """Pegg's data-range warnings of the ``rotors`` in a trim table (radius, tip speed, thrust outside his
    helicopter main rotors', :func:`nps.noise.broadband.pegg.pegg_outside_range`), each suggesting BPM."""
    from nps.noise.broadband.pegg import pegg_outside_range

    out = []
    for _, row in trim[trim["rotor"].isin(list(rotors))].iterrows():
        tip_speed = float(row["omega_rad_s"]) * float(row["radius_m"])
        out += [f"Pegg: rotor '{row['rotor']}': {m}; consider models.broadband: bpm (BPM blade self-noise, "
                f"docs/reference/bpm.md), which holds for any rotor"
                for m in pegg_outside_range(float(row["radius_m"]), tip_speed, float(row["thrust_N"]))]
    return out
