"""Rotor–rotor interaction: BVI loads of every rotor of an aircraft in all rotors' free wakes.

Inputs are the artifacts the ``wake`` workflow job reads for one aircraft × segment: the
aircraft trim (``trim.parquet``), and per rotor its loads disk table (``loads/{rotor}.parquet``)
and loads summary (``loads/{rotor}_summary.parquet``). The wakes of all rotors are relaxed
together (:func:`nps.wake.free.relax`); each rotor's blade stations then see the velocity of
every rotor's wake, split by source rotor q, resolved into (ΔU_T, ΔU_P) (:mod:`nps.wake.bvi`).

No double counting (docs/reference/wake_bvi.md, "Rotor–rotor interaction"):

- own wake (q = p): the trimmed BET's linear inflow already carries the mean and 1/rev
  effect of the rotor's wake *as if isolated*, so harmonics 0 and 1 of the own wake are
  removed (as for the Beddoes wake) — except for the change the other rotors make to it: the
  0/1-rev part of (own wake in the coupled solution − own wake relaxed alone) is interference
  (e.g. a coaxial's lower wake held back by the upper slipstream induces more on its rotor);
- other rotors' wakes (q ≠ p): nothing in the rotor's trim knows them, so their mean and
  1/rev parts are new inflow. They are added to the section velocities and, when they change
  the rotor's thrust by more than the trim tolerance (0.1 %), the rotor is re-trimmed to its
  thrust and hub-moment targets from the aircraft trim with that inflow
  (:func:`nps.rotor.bet.trim_rotor`, ``interference``) so the aircraft still balances;
- momentum level: a wake of tip vortices alone induces the mean (and 1/rev) of a rotor of
  thrust coefficient C_T,Γ = B Γ̄_v/(2π Ω R²), not the rotor's C_T (the inboard trailed sheet,
  of the opposite sense, is not modelled); so the 0/1-rev interference of wake q is scaled by
  C_T,q/C_T,Γ,q — the same momentum level the trim gives every rotor's own mean inflow
  (:func:`nps.wake.free.circulation_thrust_coefficient`). The ≥ 2/rev part keeps the full
  tip-vortex strength (the local vortex, as for the Beddoes wake);
- the ≥ 2/rev part of all wakes is the BVI increment (gust response as in :mod:`nps.wake.bvi`).

Over a common period (``FreeWakeModel.common_period``, docs "Common period") a rotor's loads table is
repeated over its m turns (:func:`nps.wake.bvi.tile_disk`), the wakes' velocity found at blade 0 over the
period and split by :func:`nps.wake.bvi.split_period_harmonics`: the per-turn mean and 1/rev as above (the
re-trim on one turn), everything else (≥ 2/rev and the rev-to-rev variation) as the BVI increment; the
result holds the m turns.

One coupling pass: the wakes are relaxed with the strengths of the loads tables; the
re-trimmed circulation is not fed back into the wake. A rotor alone in its coupled group
(:func:`nps.wake.free.coupled_groups`: a single-rotor aircraft, or rotors too far apart to
change each other's inflow by the trim tolerance) needs no isolated solution (the coupled one
is it) and is never re-trimmed: it gets exactly its isolated result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np
import pandas as pd

from nps.rotor import bet

from nps.wake import bvi

from nps.wake import free as freewake

from nps.wake import prescribed as wake
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import trim_row

TRIM_TOLERANCE = 1e-3  # relative thrust tolerance of the rotor trim (nps.rotor.bet.trim_rotor default)
SUMMARY_COLUMNS = (
    "rotor", "source_rotor", "mean_dup_mps", "rms_1rev_dup_mps", "rms_bvi_dup_mps", "peak_bvi_dup_mps", "bvi_share",
    "dominant", "retrimmed", "thrust_change_before_retrim",
)


@dataclass(frozen=True)
class AircraftBVI:
    """Result of :func:`aircraft_bvi_loads`: the relaxed wake, each rotor's BVI result (loads
    schema disk table, increments), the re-trim (None when not needed) and the interaction
    summary (``SUMMARY_COLUMNS``, one row per rotor × source rotor)."""

    solution: freewake.FreeWakeSolution
    results: dict[str, bvi.BVIResult]
    retrims: dict[str, bet.RotorTrim | None]
    summary: pd.DataFrame


def placements(trim: pd.DataFrame, disks: Mapping[str, pd.DataFrame], summaries: Mapping[str, pd.DataFrame],
               rotor_configs: Mapping[str, Mapping] | None = None) -> list[freewake.RotorPlacement]:
    """Wake state and placement of every rotor in ``disks`` from the artifacts; blade phases from the
    rotors' ``phase_deg`` in ``rotor_configs`` (absent: 0)."""
    out = []
    for name, disk in disks.items():
        row = trim_row(trim, name)
        state = bvi.wake_state(disk, row, bvi.summary_value(summaries[name], "ct", f"{name} loads summary"))
        hub = np.array([row["hub_x_m"], row["hub_y_m"], row["hub_z_m"]], dtype=float)
        r_gh = np.array([[row[f"r_gh_{i}{j}"] for j in range(3)] for i in range(3)], dtype=float)
        config = (rotor_configs or {}).get(name, {})
        phase = math.radians(float(config["phase_deg"])) if "phase_deg" in config else 0.0
        out.append(freewake.RotorPlacement(name, state, hub, r_gh, phase))
    return out


def _disk_thrust(table: pd.DataFrame, n_blades: int, n_psi: int) -> float:
    """Rotor thrust (N) of a disk table: B/N_ψ Σ F_z dr."""
    return n_blades / n_psi * float(np.sum(table["fz_N_per_m"].to_numpy() * table["dr_m"].to_numpy()))


def aircraft_bvi_loads(
    trim: pd.DataFrame,
    rotor_configs: Mapping[str, Mapping],
    disks: Mapping[str, pd.DataFrame],
    summaries: Mapping[str, pd.DataFrame],
    wake_model: wake.WakeModel,
    free_model: freewake.FreeWakeModel = freewake.FreeWakeModel(),
    bvi_model: bvi.BVIModel = bvi.BVIModel(),
    controls: Mapping[str, str] | None = None,
) -> AircraftBVI:
    """BVI loads of every rotor of one aircraft × segment with all rotors' free wakes (module doc).

    ``trim``: the aircraft trim table; ``rotor_configs``: validated ``rotors[]`` entries by
    name; ``disks``/``summaries``: loads disk tables and summaries by rotor name (same keys).
    ``wake_model``: Beddoes initial guess and the blade-load evaluation (segments, lifting-line
    core); ``free_model``: the relaxation; ``controls``: a rig's control mode by rotor (None: the aircraft's
    re-trim of every rotor): ``fixed`` is not re-trimmed (its thrust is the answer), ``rpm`` refused where it
    would need a re-trim. Raises :class:`nps.wake.free.FreeWakeError` when the
    wake does not converge, ValueError naming the rotor/field for bad inputs.
    """
    if set(rotor_configs) != set(disks) or set(disks) != set(summaries):
        raise ValueError(f"aircraft_bvi_loads: rotor_configs {sorted(rotor_configs)}, disks {sorted(disks)} and "
                         f"summaries {sorted(summaries)} must name the same rotors")
    if bvi_model.removed_harmonics != 1:
        raise ValueError("aircraft_bvi_loads: the interaction rule needs BVIModel.removed_harmonics = 1")
    rotors = placements(trim, disks, summaries, rotor_configs)
    solution = freewake.relax(rotors, wake_model, free_model)
    coupled = {r.name: len(solution.group_of(i)) > 1 for i, r in enumerate(rotors)}
    alone = {r.name: freewake.relax([r], wake_model, free_model) for r in rotors if coupled[r.name]}
    # 0/1-rev of a tip-vortex wake scaled to its rotor's momentum thrust (module doc)
    momentum = [r.state.ct / freewake.circulation_thrust_coefficient(r.state) for r in rotors]
    results, retrims, rows = {}, {}, []
    for p, rotor in enumerate(rotors):
        name = rotor.name
        disk = disks[name]
        geometry = RotorGeometry.from_config(rotor_configs[name])
        row = trim_row(trim, name)
        m = solution.revolutions(p)
        tiled = bvi.tile_disk(disk, m)
        grid = bvi.disk_grid(tiled, f"{name} loads", common_period=True)
        n_psi = grid.shape[0] // m
        beta = tiled["beta_rad"].to_numpy(dtype=float).reshape(grid.shape)
        v = freewake.disk_induced_velocity(solution, name, grid.psi_rad, grid.r_m, beta)
        high_ut, high_up, low_ut, low_up, parts = _split_by_source(v, p, grid.psi_rad, beta, m, momentum)
        if coupled[name]:
            # the isolated wake repeats every turn: one turn evaluated, repeated over the period
            v_alone = np.tile(freewake.disk_induced_velocity(alone[name], name, grid.psi_rad[:n_psi], grid.r_m,
                                                             beta[:n_psi])[0], (m, 1, 1))
            a_ut, a_up = bvi.blade_frame_increments(v[p] - v_alone, grid.psi_rad, beta)
            low_ut += momentum[p] * bvi.split_period_harmonics(a_ut, m)[0]
            low_up += momentum[p] * bvi.split_period_harmonics(a_up, m)[0]
        target = float(row["thrust_N"])
        probe = bvi.loads_with_increments(disk, row, geometry, low_ut, low_up, v.sum(axis=0)[:n_psi],
                                          bvi.BVIModel(unsteady=False))
        change = _disk_thrust(probe.disk, geometry.n_blades, n_psi) / target - 1.0
        retrim = None
        mode = "collective" if controls is None else controls.get(name, "collective")
        if abs(change) > TRIM_TOLERANCE and coupled[name] and mode == "rpm":
            raise ValueError(f"aircraft_bvi_loads: rotor '{name}': control 'rpm': the other rotors' wakes change its "
                             f"thrust by {100.0 * change:.3g} %, and its speed cannot be re-trimmed (the other stages "
                             "read the set-up's speed): use control 'collective' or 'fixed' for a coupled rotor")
        if abs(change) > TRIM_TOLERANCE and coupled[name] and mode != "fixed":
            retrim = bet.trim_rotor(geometry, OperatingPoint.from_trim_row(row), bet.DiskGrid(n_psi, grid.shape[1]),
                                    tol_rel=TRIM_TOLERANCE, interference=(low_ut, low_up))
            result = bvi.loads_with_increments(bvi.tile_disk(retrim.disk, m), row, geometry, high_ut, high_up,
                                               v.sum(axis=0), bvi_model)
        else:
            result = bvi.loads_with_increments(tiled, row, geometry, high_ut + np.tile(low_ut, (m, 1)),
                                               high_up + np.tile(low_up, (m, 1)), v.sum(axis=0), bvi_model)
        results[name], retrims[name] = result, retrim
        rows.extend(_summary_rows(name, [r.name for r in rotors], p, parts, retrim is not None, change))
    return AircraftBVI(solution, results, retrims, pd.DataFrame(rows, columns=list(SUMMARY_COLUMNS)))


def _split_by_source(v, p, psi_rad, beta, m, momentum):
    """Blade-frame increments of every source rotor's wake at rotor ``p`` over its m turns: (ΔU_T, ΔU_P) of
    the BVI part (≥ 2/rev and rev-to-rev, all sources; (mN, n_r)), of the other rotors' per-turn mean and
    1/rev scaled by ``momentum`` ((N, n_r)), and per source (per-turn 0/1-rev ΔU_P, BVI ΔU_P) for the summary."""
    high_ut, high_up = np.zeros(v.shape[1:3]), np.zeros(v.shape[1:3])
    low_ut, low_up = np.zeros((v.shape[1] // m, v.shape[2])), np.zeros((v.shape[1] // m, v.shape[2]))
    parts = []
    for q in range(v.shape[0]):
        d_ut, d_up = bvi.blade_frame_increments(v[q], psi_rad, beta)
        (l_ut, h_ut), (l_up, h_up) = bvi.split_period_harmonics(d_ut, m), bvi.split_period_harmonics(d_up, m)
        high_ut += h_ut
        high_up += h_up
        if q != p:
            low_ut += momentum[q] * l_ut
            low_up += momentum[q] * l_up
        parts.append(((momentum[q] if q != p else 1.0) * l_up, h_up))
    return high_ut, high_up, low_ut, low_up, parts


def _summary_rows(name, sources, p, parts, retrimmed, change) -> list[dict]:
    """Interaction summary of one rotor: per source rotor, the mean and 1/rev ΔU_P it induces
    (the own rotor's as a whole, of which only the change against the isolated wake is
    interference) and its ≥ 2/rev BVI part (RMS and peak over the disk, share of the sum)."""
    rms_bvi = np.array([float(np.sqrt(np.mean(h ** 2))) for _, h in parts])
    total = rms_bvi.sum()
    dominant = int(np.argmax(rms_bvi))
    rows = []
    for q, (low, high) in enumerate(parts):
        mean = float(low.mean())
        rows.append({
            "rotor": name, "source_rotor": sources[q], "mean_dup_mps": mean,
            "rms_1rev_dup_mps": float(np.sqrt(np.mean((low - mean) ** 2))),
            "rms_bvi_dup_mps": rms_bvi[q], "peak_bvi_dup_mps": float(np.abs(high).max()),
            "bvi_share": rms_bvi[q] / total if total > 0.0 else 0.0, "dominant": q == dominant,
            "retrimmed": retrimmed, "thrust_change_before_retrim": float(change),
        })
    return rows
