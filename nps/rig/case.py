"""Rigs: an isolated rotor on a test stand or in a wind tunnel, microphones fixed to the hub.

A rig (``config/rigs/*.yaml``, schema ``nps/app/schemas/rig.schema.yaml``) names one rotor (a rotor
YAML, i.e. one ``rotors[]`` entry of an aircraft file, or a rotor of an aircraft file), its operating
condition with the atmosphere given directly, microphones, and the settings its jobs run with. No
aircraft, mission or aircraft trim is involved: the set-up writes the trim artifact (one row) and the
observer table, and the study stages (loads, wake, acoustics, metrics) run on them unchanged.

Frames (docs/reference/rigs.md has the picture):

- **Test frame T** (microphones): origin at the hub, x_T downstream along the tunnel axis, z_T up
  (vertical, not along the shaft), y_T = z_T × x_T, which is the advancing side of a rotor turning
  counterclockwise seen from above. Fixed to the hub (the microphones do not move relative to it).
- **Flight frame G** (the study's ground frame, docs/reference/conventions.md): the rotor flies at
  V = tunnel speed along +x_G through still air. x_G is *upstream*, so G is T turned by 180°
  about z: (x_G, y_G, z_G) = (−x_T, −y_T, z_T). Microphones move with the hub at V.
- **Shaft angle** α_s, positive with the shaft tilted toward downstream (aft, the usual
  "nose-up" tunnel angle): thrust axis in G = (−sin α_s, 0, cos α_s); the free stream then
  enters the disk from below (μ_z = −V sin α_s / ΩR < 0).

Several rotors (``rotors:`` instead of ``rotor:``): each entry places its rotor in T (``hub_position_m``, from
the origin of T, which the microphones share; the bundled rigs put the first rotor's hub there) with its own
axis — ``shaft_angle_deg`` α, then ``lateral_angle_deg`` l toward +y_T: axis_T = (cos l sin α, sin l, cos l cos α),
or ``thrust_axis_T`` — rotation sense, speed, control and targets. Each rotor is solved under its own control at
its own operating point (the tunnel speed through its own axis); the trim artifact has one row per rotor, hub
and hub frame in G (:func:`rotor_condition`, :func:`rig_rotor`).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Mapping

import numpy as np
import pandas as pd

from nps.core import frames
from nps.rotor.bet import DiskGrid
from nps.rotor.control import TRIMMED_PITCH, RotorControl, RotorSolution, default_mode, solve_rotor
from nps.noise.observers import ObserverError, points, with_directions
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.noise.signals import signal_arrays
from nps.noise.spectra import harmonic_band_msp, level_db, narrowband_msp
from nps.rotor.trim import TRIM_COLUMNS, glauert_inflow

# the aircraft name of every rig in the workflow: a rig's jobs are those of aircraft "rigs", segment NAME
# (results/rigs/NAME/, like results/<aircraft>/<segment>/)
RIG_AIRCRAFT = "rigs"
# a rotor YAML may omit the fields that place a rotor on an aircraft
_ROTOR_DEFAULTS = {"role": "lift", "hub_position_m": [0.0, 0.0, 0.0], "thrust_axis_body": [0.0, 0.0, 1.0]}
MICROPHONE_COLUMNS = ("x_T_m", "y_T_m", "z_T_m", "group")
# rotor fields a rig's condition may set (they replace the rotor file's)
CONDITION_ROTOR_FIELDS = ("control", "pitch_deg", "flapping", "higher_harmonic_pitch", "elastic_twist_harmonics",
                          "prescribed_flap")


# fields of a rotors[] entry that make the rotor's own condition, with the common ones of the rig's condition
ENTRY_CONDITION_FIELDS = ("rpm", "omega_rad_s", "control", "pitch_deg", "flapping", "thrust_N", "roll_moment_Nm",
                          "pitch_moment_Nm", "shaft_angle_deg", "lateral_angle_deg", "thrust_axis_T", "hub_position_m",
                          "higher_harmonic_pitch", "elastic_twist_harmonics", "prescribed_flap")
COMMON_CONDITION_FIELDS = ("tunnel_speed_mps", "atmosphere")


def t_to_g(p_t_m) -> np.ndarray:
    """Test-frame components (..., 3) to flight-frame components: the 180° turn about z."""
    p = np.asarray(p_t_m, dtype=float)
    return p * np.array([-1.0, -1.0, 1.0])


def shaft_axis_flight(shaft_angle_rad: float) -> np.ndarray:
    """Thrust axis in G for a shaft tilted ``shaft_angle_rad`` toward downstream (aft)."""
    return np.array([-math.sin(shaft_angle_rad), 0.0, math.cos(shaft_angle_rad)])


def rotor_axis_test(condition: Mapping) -> np.ndarray:
    """Unit thrust axis in T of a rotor condition: ``thrust_axis_T`` normalised, else the shaft angle α (toward
    +x_T) and lateral angle l (then toward +y_T): (cos l sin α, sin l, cos l cos α)."""
    if "thrust_axis_T" in condition:
        axis = np.asarray(condition["thrust_axis_T"], dtype=float)
        return axis / np.linalg.norm(axis)
    a, lat = math.radians(condition.get("shaft_angle_deg", 0.0)), math.radians(condition.get("lateral_angle_deg", 0.0))
    return np.array([math.cos(lat) * math.sin(a), math.sin(lat), math.cos(lat) * math.cos(a)])


def rotor_axis_flight(condition: Mapping) -> np.ndarray:
    """Thrust axis in G of a rotor condition: :func:`shaft_axis_flight` of the shaft angle alone (the one-rotor
    form, bit for bit), else :func:`t_to_g` of :func:`rotor_axis_test`."""
    if "thrust_axis_T" not in condition and float(condition.get("lateral_angle_deg", 0.0)) == 0.0:
        return shaft_axis_flight(math.radians(condition.get("shaft_angle_deg", 0.0)))
    return t_to_g(rotor_axis_test(condition)) + 0.0  # + 0.0: no negative zeros


def hub_flight(condition: Mapping) -> np.ndarray:
    """Hub position in G (m) of a rotor condition: ``hub_position_m`` (in T) turned, the origin without one."""
    return t_to_g(condition["hub_position_m"]) + 0.0 if "hub_position_m" in condition else np.zeros(3)


def rotor_condition(condition: Mapping, entry: Mapping) -> dict:
    """The condition of one ``rotors[]`` entry: the rig condition's common fields (tunnel speed, atmosphere) with
    the entry's own (speed, control, pitch, targets, shaft and lateral angles or axis, hub position, blade motion)."""
    return {**{k: condition[k] for k in COMMON_CONDITION_FIELDS if k in condition},
            **{k: entry[k] for k in ENTRY_CONDITION_FIELDS if k in entry}}


def rig_rotor(rotor: Mapping, condition: Mapping, entry: Mapping) -> dict:
    """The stages' configuration of one ``rotors[]`` entry (:func:`rotor_for_rig` of its :func:`rotor_condition`
    ``condition``) with the entry's name and rotation sense where given, and its hub and thrust axis in G as
    ``hub_position_m`` / ``thrust_axis_body`` (a rig's body frame is G)."""
    out = rotor_for_rig(rotor, condition)
    out.update({key: entry[key] for key in ("name", "rotation") if key in entry})
    out["hub_position_m"] = [float(v) for v in hub_flight(condition)]
    out["thrust_axis_body"] = [float(v) for v in rotor_axis_flight(condition)]
    return out


def omega_of(condition: Mapping) -> float:
    """Rotor speed (rad/s) of a validated condition: ``omega_rad_s`` or ``rpm``."""
    return float(condition["omega_rad_s"]) if "omega_rad_s" in condition else float(condition["rpm"]) * math.pi / 30.0


def rotor_for_rig(rotor: Mapping, condition: Mapping) -> dict:
    """The rotor configuration the stages use: ``rotor`` with the condition's speed and, where the
    condition gives them, its control, pitch, flapping and prescribed blade motion (higher-harmonic
    pitch, elastic twist and flap harmonics of that condition, e.g. HART-II's MN and MV)."""
    out = {**_ROTOR_DEFAULTS, **rotor, "omega_rad_s": omega_of(condition)}
    for key in CONDITION_ROTOR_FIELDS:
        if key in condition:
            out[key] = condition[key]
    if out.get("control", default_mode(out)) in TRIMMED_PITCH:
        out.pop("pitch_deg", None)
    return out


def control_conflicts(mode: str, condition: Mapping, where: str = "condition") -> list[tuple[str, str]]:
    """(field, problem) of every condition value the control ``mode`` cannot use: a thrust target with
    ``fixed`` (the thrust is the answer), a pitch with ``collective`` or ``collective_only`` (the trim sets it),
    hub-moment targets without the cyclic of ``collective`` with flapping. A value that would be ignored is refused, not dropped.
    ``where``: the fields' prefix (``rotors[1] 'tail'`` for a ``rotors[]`` entry)."""
    problems = []
    if mode == "fixed" and "thrust_N" in condition:
        problems.append((f"{where}.thrust_N", f"got {condition['thrust_N']!r}, but control 'fixed' uses no thrust "
                         "target (the thrust is the answer of the given pitch and speed): remove it, or trim to it "
                         "with control 'collective' or 'rpm'"))
    if mode in TRIMMED_PITCH and "pitch_deg" in condition:
        problems.append((f"{where}.pitch_deg", f"got {condition['pitch_deg']!r}, but control '{mode}' trims the "
                         "pitch to the thrust target: remove it, or hold it with control 'fixed' or 'rpm'"))
    cyclic = mode == "collective" and bool(condition.get("flapping", True))
    for key in ("roll_moment_Nm", "pitch_moment_Nm"):
        if not cyclic and float(condition.get(key, 0.0)) != 0.0:
            problems.append((f"{where}.{key}", f"got {condition[key]!r}, but only control 'collective' with flapping "
                             f"trims the hub moments (control '{mode}'): remove it"))
    return problems


def station_params(rig: Mapping) -> dict:
    """``stations`` and ``rotors`` params of a loaded rig's station_loads jobs (:mod:`nps.stages.station_loads`):
    the rig's ``stations_r_over_R`` list and every rotor when all rotors use it, else ``{rotor: stations}`` of the
    rotors that have stations (``rotor_stations``, :func:`nps.app.config.rotor_stations`), in rig order."""
    stations, names = rig["rotor_stations"], [r["name"] for r in rig["rotor_configs"]]
    common = rig.get("stations_r_over_R")
    if common is not None and list(stations) == names and all(v == [float(x) for x in common] for v in stations.values()):
        return {"stations": common, "rotors": names}
    return {"stations": stations, "rotors": list(stations)}


def read_microphone_file(path: str | Path) -> np.ndarray:
    """Microphone positions (n, 3) in T from a CSV (header x_m, y_m, z_m) or YAML (list of
    mappings with x_m, y_m, z_m). Raises ObserverError naming the file, row and field."""
    path = Path(path)
    if not path.is_file():
        raise ObserverError(f"{path}: microphone file not found")
    if path.suffix.lower() in (".yaml", ".yml"):
        import yaml  # here: a YAML microphone file needs it, not the wake jobs that import this module

        with open(path) as handle:
            try:
                rows = yaml.safe_load(handle)
            except yaml.YAMLError as exc:
                raise ObserverError(f"{path}: not valid YAML: {exc}") from None
        if not isinstance(rows, list) or not rows:
            raise ObserverError(f"{path}: expected a non-empty list of {{x_m, y_m, z_m}} mappings")
    else:
        with open(path, newline="") as handle:
            rows = list(csv.DictReader(line for line in handle if not line.lstrip().startswith("#")))
        if not rows:
            raise ObserverError(f"{path}: expected a header x_m,y_m,z_m and at least one row")
    out = np.empty((len(rows), 3))
    for i, row in enumerate(rows):
        for j, key in enumerate(("x_m", "y_m", "z_m")):
            value = row.get(key) if isinstance(row, Mapping) else None
            try:
                out[i, j] = float(value)
            except (TypeError, ValueError):
                raise ObserverError(f"{path}: row {i + 1}: {key}: expected a number (m), got {value!r}") from None
            if not math.isfinite(out[i, j]):
                raise ObserverError(f"{path}: row {i + 1}: {key}: expected a finite number (m), got {value!r}")
    return out


def microphone_positions(specs, base: str | Path = ".") -> tuple[np.ndarray, np.ndarray]:
    """Positions (n, 3) in T and group index (n,) of validated ``microphones`` entries; file paths
    relative to ``base``. Arc angle a: xz → (r cos a, 0, r sin a), yz → (0, r cos a, r sin a),
    xy → (r cos a, r sin a, 0). A plane is the grid x_m × y_m (x-major) at height z_m."""
    parts = []
    for spec in specs:
        kind = spec["kind"]
        if kind == "point":
            part = np.asarray(spec["positions_m"], dtype=float).reshape(-1, 3)
        elif kind == "file":
            part = read_microphone_file(Path(base) / spec["path"])
        elif kind == "arc":
            a = np.radians(np.asarray(spec["angles_deg"], dtype=float))
            c, s, z = spec["radius_m"] * np.cos(a), spec["radius_m"] * np.sin(a), np.zeros(a.size)
            part = np.stack({"xz": (c, z, s), "yz": (z, c, s), "xy": (c, s, z)}[spec["plane"]], axis=-1)
        else:
            xx, yy = np.meshgrid(np.asarray(spec["x_m"], float), np.asarray(spec["y_m"], float), indexing="ij")
            part = np.stack([xx.ravel(), yy.ravel(), np.full(xx.size, float(spec["z_m"]))], axis=-1)
        parts.append(part)
    groups = np.concatenate([np.full(len(p), g) for g, p in enumerate(parts)])
    return np.concatenate(parts), groups


def rig_operating_point(rotor: Mapping, condition: Mapping) -> OperatingPoint:
    """The rotor's operating point at a validated rig condition: the condition's speed, atmosphere, thrust and
    moment targets, the advance ratios of the tunnel speed through the shaft tilted by the shaft angle."""
    atm = condition["atmosphere"]
    omega, speed = omega_of(condition), float(condition.get("tunnel_speed_mps", 0.0))
    r_gh = frames.hub_to_body(rotor_axis_flight(condition))
    v_h = -(r_gh.T @ np.array([speed, 0.0, 0.0])) / (omega * RotorGeometry.from_config(rotor).radius_m)
    return OperatingPoint(omega, float(v_h[0]), float(v_h[1]), float(-v_h[2]), float(atm["density_kg_m3"]),
                          float(atm["speed_of_sound_mps"]), float(condition.get("thrust_N", 0.0)),
                          float(condition.get("roll_moment_Nm", 0.0)), float(condition.get("pitch_moment_Nm", 0.0)))


def rig_solution(rotor: Mapping, condition: Mapping, grid: DiskGrid) -> RotorSolution:
    """The rig's rotor solved under its control mode (:func:`nps.rotor.control.solve_rotor`) at
    :func:`rig_operating_point`."""
    geometry, control = RotorGeometry.from_config(rotor), RotorControl.from_config(rotor)
    return solve_rotor(geometry, rig_operating_point(rotor, condition), grid, control,
                       tip_loss=bool(rotor.get("tip_loss", True)))


def rig_trim(rotor: Mapping, condition: Mapping, grid: DiskGrid, solution: RotorSolution | None = None) -> pd.DataFrame:
    """The trim row (:data:`nps.rotor.trim.TRIM_COLUMNS`) of a rig's rotor: hub at the origin of G (a ``rotors[]``
    entry's condition: at its ``hub_position_m``, with the rotor's role), moving at the tunnel speed along +x_G,
    axis of :func:`rotor_axis_flight`.

    The rotor is solved under its control mode here (:func:`rig_solution`, or ``solution`` when already
    solved), so the row holds the rotor speed every later stage uses (solved for ``rpm``) and the
    blade-element thrust, torque and power (for ``fixed`` the thrust is the answer, not a target).
    """
    speed = float(condition.get("tunnel_speed_mps", 0.0))
    r_gh = frames.hub_to_body(rotor_axis_flight(condition))
    hub = hub_flight(condition)
    geometry, control = RotorGeometry.from_config(rotor), RotorControl.from_config(rotor)
    solution = rig_solution(rotor, condition, grid) if solution is None else solution
    op, totals = solution.operating_point, solution.result.totals
    mu = math.hypot(op.mu_x, op.mu_y)
    row = {
        "rotor": str(rotor["name"]), "role": str(rotor.get("role", "lift")) if "hub_position_m" in condition else "lift", "rotation_sign": np.int8(geometry.rotation_sign),
        "n_blades": np.int32(geometry.n_blades), "radius_m": geometry.radius_m, "omega_rad_s": op.omega_rad_s,
        "thrust_N": totals.thrust_N if control.mode == "fixed" else op.thrust_N,
        "roll_moment_Nm": op.roll_moment_Nm, "pitch_moment_Nm": op.pitch_moment_Nm,
        "torque_Nm": totals.torque_Nm, "power_W": totals.power_W, "mu_x": op.mu_x, "mu_y": op.mu_y, "mu_z": op.mu_z,
        "lambda_i": glauert_inflow(totals.ct, mu, op.mu_z), "ct": totals.ct,
        "tip_mach": op.omega_rad_s * geometry.radius_m / op.speed_of_sound_mps,
        "hub_x_m": float(hub[0]), "hub_y_m": float(hub[1]), "hub_z_m": float(hub[2]),
        "vel_x_mps": speed, "vel_y_mps": 0.0, "vel_z_mps": 0.0,
        **{f"r_gh_{i}{j}": float(r_gh[i, j]) for i in range(3) for j in range(3)},
        "density_kg_m3": op.density_kg_m3, "speed_of_sound_mps": op.speed_of_sound_mps,
        "pitch_rad": 0.0, "roll_rad": 0.0, "flight_path_rad": 0.0, "trim_iterations": np.int32(solution.result.iterations),
    }
    return pd.DataFrame([row], columns=list(TRIM_COLUMNS))


def microphone_table(positions_t_m: np.ndarray, groups: np.ndarray, speed_mps: float) -> pd.DataFrame:
    """Observer artifact of the microphones: G positions at t = 0 (hub at the origin), all moving
    with the hub at ``speed_mps`` along +x_G, with their T positions and group index and the map
    directions seen from the hub."""
    table = points(t_to_g(positions_t_m), (float(speed_mps), 0.0, 0.0))
    for i, key in enumerate(MICROPHONE_COLUMNS[:3]):
        table[key] = positions_t_m[:, i]
    table["group"] = groups.astype(np.int32)
    return with_directions(table, np.zeros(3))


def tone_levels(signals: Mapping[str, pd.DataFrame], blade_passing_hz: float, n_harmonics: int) -> pd.DataFrame:
    """OASPL and the levels of BPF harmonics 1…``n_harmonics`` (dB re 20 µPa) per observer of the
    summed signals (every group of every rotor; one revolution, so harmonic m of the BPF is one
    spectral line): columns ``observer``, ``oaspl_db``, ``bpf{m}_hz``, ``bpf{m}_db``."""
    total, ids, dt = None, None, None
    for name, table in signals.items():
        ids, time, groups = signal_arrays(table, what=f"pressure signals of rotor '{name}'")
        part = sum(groups.values())
        total, dt = (part if total is None else total + part), time[1] - time[0]
    frequency, msp = narrowband_msp(total, dt)
    out = {"observer": ids, "oaspl_db": level_db(np.mean((total - total.mean(axis=-1, keepdims=True)) ** 2, axis=-1))}
    for m in range(1, n_harmonics + 1):
        out[f"bpf{m}_hz"] = np.full(ids.size, m * blade_passing_hz)
        out[f"bpf{m}_db"] = level_db(harmonic_band_msp(frequency, msp, blade_passing_hz, m, m))
    return pd.DataFrame(out)
