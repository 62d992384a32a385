"""Stage ``wopwop_export`` (``nps wopwop export``): an aircraft's (or a rig's) rotors in a segment as a complete
PSU-WOPWOP case directory (nps.wopwop.export; docs/reference/wopwop.md).

inputs: ``disks`` (directory of ``{rotor}.parquet`` disk tables, the loads stage's for variant ``base``, the wake
stage's ``bvi`` directory for ``bvi``), ``trim``, ``observers``: what the acoustics stage radiates.
outputs: ``case``: the case directory (cases.nam, case.nam, observer files, per rotor a geometry and a functional
data file), written atomically.
params: the acoustics stage's (``nps.app.plan``: ``rotors``, ``hinge_offsets_m``, ``thickness``, ``chord_fractions``,
``samples_per_rev``, optional ``phases_deg``) and ``aircraft``, ``segment``, ``obsset``, ``variant``. The case is
the acoustics stage's computation: the same rotors, loads (over a common period where the wake stage wrote one),
blade phases, observers and observer grid (one revolution of the first rotor, ``samples_per_rev`` samples).

Before writing: provenance of every input, the disk tables against their rotors' trim rows (as the acoustics stage).
"""

from __future__ import annotations

from nps.app.io import check_provenance, read_table, rotor_path
from nps.noise.acoustics import AcousticsError
from nps.noise.observers import OBSERVER_STAGES
from nps.noise.sources import DISK_COLUMNS, ThicknessModel, common_grid
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row
from nps.stages.acoustics import DISK_STAGE, OBSERVER_COLUMNS, check_disk_geometry, grid_revolutions, period_timing
from nps.wopwop.export import RotorCase, export_case


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    same = {"aircraft": params["aircraft"], "segment": params["segment"]}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    check_provenance(inputs["observers"], {"stage": OBSERVER_STAGES, "obsset": params["obsset"], **same})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    observers = read_table(inputs["observers"], required=OBSERVER_COLUMNS, nonempty=True, finite=True, unique="observer")
    phases = params["phases_deg"] if "phases_deg" in params else dict.fromkeys(rotors, 0.0)
    cases, timing = [], {}
    for name in rotors:
        path = rotor_path(inputs["disks"], name)
        check_provenance(path, {"stage": DISK_STAGE.get(params["variant"], tuple(DISK_STAGE.values())), "rotor": name, **same})
        disk = read_table(path, required=DISK_COLUMNS, nonempty=True)
        timing[name] = period_timing(path)
        row = trim_row(trim, name, str(inputs["trim"]))
        check_disk_geometry(disk, row, path, timing[name]["revolutions"])
        shifts = timing[name]["blade_shift_steps"]
        cases.append(RotorCase(name, disk, row, float(params["hinge_offsets_m"][name]), float(phases[name]),
                               None if shifts is None else tuple(int(k) for k in shifts)))
    revolutions = grid_revolutions(trim, rotors, timing, str(inputs["trim"]))
    grid = common_grid(trim_row(trim, rotors[0], str(inputs["trim"])), int(params["samples_per_rev"]), revolutions)
    model = ThicknessModel(params["thickness"], tuple(float(f) for f in params["chord_fractions"]))
    title = f"{params['aircraft']} {params['segment']} {params['variant']}".strip()
    try:
        directory = export_case(cases, observers, grid, model, outputs["case"], title, str(params["obsset"] or "observers"),
                                comment=f"NPS export: {title}, observer set {params['obsset']}")
    except AcousticsError as error:
        raise AcousticsError(f"{inputs['disks']}: {error}") from None
    return f"{len(rotors)} rotor(s), {len(observers)} observers x {grid.n_samples} samples -> {directory}"
