"""Stage ``acoustics``: compact-F1A pressure signals of every rotor of an aircraft at one observer set.

inputs: ``disks`` (directory of ``{rotor}.parquet`` disk tables: the loads stage's directory for
variant ``base``, the wake stage's ``bvi`` directory for variant ``bvi``), ``trim``, ``observers``.
outputs: ``signals``, a directory of ``{rotor}.parquet`` signal tables (docs/reference/conventions.md:
``observer``, ``group`` (``loading``, ``thickness``), ``time_s``, ``p_Pa``) on the aircraft's common
grid: one revolution of the reference (first) rotor with ``samples_per_rev`` samples from t = 0; over a common
period (disk tables over several revolutions, their metadata ``revolutions``, ``blade_shift_steps`` and ``period_s``,
docs/reference/wake_bvi.md "Common period") the period's revolutions of the reference rotor, recorded as
``revolutions`` in the signal tables' metadata.
params: ``rotors`` (names, the first is the reference), ``hinge_offsets_m`` (rotor → hinge offset),
``thickness`` (``dual_compact`` or ``compact_monopole``), ``chord_fractions`` (dual-compact line
positions), ``samples_per_rev``, ``aircraft``, ``segment``, ``obsset``, ``variant``; optional ``phases_deg``
(rotor → blade phase, the azimuth of blade 0 at t = 0, the aircraft schema's ``rotors[].phase_deg``; without
it every rotor's blade 0 is at ψ = 0 at t = 0). A signal table of a rotor with a non-zero phase records
``phase_deg`` in its metadata.

Before computing: provenance of every input (aircraft, segment, observer set, rotor; disk tables of
the loads stage for variant ``base``, of the BVI stage for ``bvi``), non-empty tables, unique observer
ids, each disk table's geometry against its rotor's trim row (:func:`check_disk_geometry`), memory.
"""

from __future__ import annotations

import math

import numpy as np

from nps.core import periods
from nps.noise.acoustics import LOADING, THICKNESS, AcousticsError, Observers
from nps.app.io import check_provenance, read_metadata, read_table, rotor_path, write_table
from nps.noise.observers import OBSERVER_STAGES
from nps.app.resources import check_memory, estimate_bytes
from nps.noise.signals import signals_table
from nps.noise.sources import DISK_COLUMNS, ThicknessModel, common_grid, radiate_rotor
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row

OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "vx_mps", "vy_mps", "vz_mps")
DISK_STAGE = {"base": "loads", "bvi": "bvi"}  # variant -> stage that wrote its disk tables
RADIUS_RTOL = 1e-6  # outer element edge max(r_m + dr_m/2) against the trim row's radius_m


def check_disk_geometry(disk, row, path, revolutions: int = 1) -> None:
    """Refuse a disk table that is not of the rotor it is radiated for (a table renamed, or written by another
    tool without metadata): its blades' tip max(r_m + dr_m/2) must be the trim row's ``radius_m``, its
    azimuths the grid ψ_i = 2π i/n_psi (over ``revolutions`` turns of a common period: i < m n_psi), every
    azimuth with the same radii, and the trim row's blade count must divide n_psi (blade b sits at
    ψ + 2π b/N on the same grid)."""
    radius, blades = float(row["radius_m"]), int(row["n_blades"])
    tip = float((disk["r_m"] + disk["dr_m"] / 2.0).max())
    rotor = f"rotor '{row['rotor']}'"
    if not abs(tip - radius) <= RADIUS_RTOL * radius:
        raise ValueError(f"{path}: r_m: blade tip max(r_m + dr_m/2) = {tip:.6g} m, expected the radius {radius:.6g} m of "
                         f"{rotor} in the trim table: the disk table is of another rotor; pass that rotor's loads")
    psi = np.sort(disk["psi_rad"].unique())
    n_rows, n_r = psi.size, disk["r_m"].nunique()
    n_psi = n_rows // revolutions
    spans = "" if revolutions == 1 else f" over the {revolutions} revolutions its metadata records"
    spanned = periods.table_revolutions(psi)
    if revolutions == 1 and spanned > 1:
        raise ValueError(f"{path}: psi_rad spans {spanned} revolutions but the table's metadata "
                         "records none ('revolutions', 'blade_shift_steps', as the wake stage writes them over a "
                         "common period): expected one revolution, or the wake stage's table")
    if (len(disk) != n_rows * n_r or n_psi * revolutions != n_rows
            or not np.allclose(psi, 2.0 * np.pi * np.arange(n_rows) / max(n_psi, 1), rtol=0.0, atol=1e-9)):
        raise ValueError(f"{path}: psi_rad: expected the azimuth grid 2 pi i/n_psi{spans} with every azimuth at the "
                         f"same {n_r} radii, got {n_rows} azimuths from {psi[0]:.4g} rad and {len(disk)} rows")
    if n_psi % blades:
        raise ValueError(f"{path}: psi_rad: {n_psi} azimuths, expected a multiple of the {blades} blades of {rotor} "
                         f"in the trim table: the disk table is of another rotor; pass that rotor's loads")


def period_timing(disk_path) -> dict:
    """A disk table's common-period record (its metadata, :meth:`nps.wake.free.FreeWakeSolution.period_record`):
    ``revolutions`` (1 without one), ``blade_shift_steps`` (None: equal spacing) and ``period_s`` (None)."""
    meta = read_metadata(disk_path)
    revolutions = meta.get("revolutions", 1)
    if not isinstance(revolutions, int) or revolutions < 1:
        raise ValueError(f"{disk_path}: metadata 'revolutions': expected a whole number >= 1, got {revolutions!r}")
    return {"revolutions": revolutions, "blade_shift_steps": meta.get("blade_shift_steps"),
            "period_s": meta.get("period_s")}


def grid_revolutions(trim, rotors, timing, trim_path: str) -> int:
    """Revolutions of the reference rotor (``rotors[0]``) that the signals span: 1, or the longest common period
    of the rotors' tables in its revolutions (ValueError when that period is not a whole number of them)."""
    omega = float(trim_row(trim, rotors[0], trim_path)["omega_rad_s"])
    out = 1
    for name in rotors:
        period = timing[name]["period_s"]
        if period is None:
            continue
        turns = period * omega / (2.0 * math.pi)
        if abs(turns - round(turns)) > 1e-6 * max(turns, 1.0):
            raise ValueError(f"rotor '{name}': its loads repeat over {period:.6g} s, {turns:.6g} revolutions of the "
                             f"reference rotor '{rotors[0]}': the signals need a whole number; put the rotors of "
                             "the common period first or in one coupled group")
        out = max(out, int(round(turns)))
    return out


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    model = ThicknessModel(params["thickness"], tuple(float(f) for f in params["chord_fractions"]))
    samples = int(params["samples_per_rev"])
    same = {"aircraft": params["aircraft"], "segment": params["segment"]}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    check_provenance(inputs["observers"], {"stage": OBSERVER_STAGES, "obsset": params["obsset"], **same})
    for name in rotors:
        check_provenance(rotor_path(inputs["disks"], name),
                         {"stage": DISK_STAGE.get(params["variant"], tuple(DISK_STAGE.values())), "rotor": name, **same})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    observers = read_table(inputs["observers"], required=OBSERVER_COLUMNS, nonempty=True, finite=True, unique="observer")
    obs = Observers(observers[["x_m", "y_m", "z_m"]].to_numpy(float), observers[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float))
    phases_deg = params["phases_deg"] if "phases_deg" in params else dict.fromkeys(rotors, 0.0)
    report = []
    disks, timing = {}, {}
    for name in rotors:  # every rotor's disk checked before the first signal table is written
        disk_path = rotor_path(inputs["disks"], name)
        disks[name] = disk = read_table(disk_path, required=DISK_COLUMNS, nonempty=True)
        timing[name] = period_timing(disk_path)
        check_disk_geometry(disk, trim_row(trim, name, str(inputs["trim"])), disk_path, timing[name]["revolutions"])
    revolutions = grid_revolutions(trim, rotors, timing, str(inputs["trim"]))
    grid = common_grid(trim_row(trim, rotors[0], str(inputs["trim"])), samples, revolutions)
    for name, disk in disks.items():
        check_memory(estimate_bytes("acoustics", {"n_psi": disk["psi_rad"].nunique(), "n_r": disk["r_m"].nunique(),
                                                  "samples_per_rev": samples * revolutions}, len(observers), len(rotors)),
                     f"{outputs['signals']}: {len(observers)} observers x {samples * revolutions} samples")
    for name in rotors:
        disk_path, disk = rotor_path(inputs["disks"], name), disks.pop(name)
        hinge = float(params["hinge_offsets_m"][name])
        phase_deg = float(phases_deg[name])
        try:
            pressure = radiate_rotor(disk, trim_row(trim, name, str(inputs["trim"])), obs, grid, thickness=model, hinge_offset_m=hinge,
                                     phase_rad=math.radians(phase_deg), blade_shift_steps=timing[name]["blade_shift_steps"])
        except AcousticsError as exc:
            raise AcousticsError(f"{disk_path} / {inputs['observers']}: {exc}") from None
        table = signals_table(observers["observer"].to_numpy(), (LOADING, THICKNESS), pressure, grid, total=False)
        meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
                "variant": params["variant"], "rotor": name, "reference_rotor": rotors[0], "samples_per_rev": samples,
                "thickness": model.kind, "chord_fractions": list(model.chord_fractions), "hinge_offset_m": hinge,
                **({"phase_deg": phase_deg} if phase_deg else {}),
                **({"revolutions": revolutions} if revolutions > 1 else {}),
                "inputs": [str(disk_path), str(inputs["trim"]), str(inputs["observers"])]}
        write_table(table, rotor_path(outputs["signals"], name), stage="acoustics", metadata=meta)
        report += [f"rotor {name} {group}: p_Pa min {pressure[:, g].min():.6g}, max {pressure[:, g].max():.6g}, "
                   f"std {pressure[:, g].std():.6g}" for g, group in enumerate((LOADING, THICKNESS))]
    return "\n".join(report)
