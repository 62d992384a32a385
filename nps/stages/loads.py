"""Stage ``loads``: trimmed blade loads of every rotor of one aircraft in one segment (nps.rotor.bet).

inputs: ``trim`` (trim.parquet). outputs: ``loads``, a directory with, per rotor,
``{rotor}.parquet`` (disk table), ``{rotor}_summary.parquet`` (quantity, value, unit) and
``{rotor}_history.parquet`` (trim iterations). params: ``rotors`` (rotor name → validated rotor
configuration, in aircraft order), ``n_psi``, ``n_r`` (disk resolution), ``aircraft``, ``segment``;
optional ``allow_outside_validity`` (campaign switch, default false).

Each rotor is solved under its control mode (``control``, ``pitch_deg``, ``flapping``;
:func:`nps.rotor.control.loads_at_trim`): ``collective`` trims the pitch to the trim table's targets,
``rpm`` takes the loads at the table's rotor speed (solved by the trim stage), ``fixed`` at the
given pitch and speed. The summary of an ``rpm`` or ``fixed`` rotor adds its ``omega_rad_s``.

Before computing: the trim artifact must be the aircraft's and segment's (provenance), the disk
must fit in memory (nps.app.resources); after each rotor's loads: flap angle and controls (nps.app.validity).
Every rotor is solved and checked before the first rotor's tables are written, so a refusal (or a trim that
does not converge) on any rotor leaves no table of another behind; the job holds every rotor's tables until then.
"""

from __future__ import annotations

from nps.app import validity
from nps.rotor.bet import DiskGrid
from nps.rotor.control import RotorControl, loads_at_trim
from nps.app.io import check_provenance, read_table, rotor_path, write_table
from nps.app.resources import check_memory, estimate_bytes
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row


def run(inputs: dict, outputs: dict, params: dict) -> str:
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, "aircraft": params["aircraft"], "segment": params["segment"]})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    grid = DiskGrid(int(params["n_psi"]), int(params["n_r"]))
    check_memory(estimate_bytes("loads", {"n_psi": grid.n_psi, "n_r": grid.n_r}, n_rotors=len(params["rotors"])),
                 f"{outputs['loads']}: loads on a {grid.n_psi} x {grid.n_r} disk (n_psi x n_r)")
    report, solved = [], {}
    for name, rotor in params["rotors"].items():  # every rotor solved and checked before the first table is written
        geometry, control = RotorGeometry.from_config(rotor), RotorControl.from_config(rotor)
        solution = loads_at_trim(geometry, OperatingPoint.from_trim_row(trim_row(trim, name, inputs["trim"])), grid, control,
                                 tip_loss=bool(rotor["tip_loss"]))
        result = solution.result
        summary = result.summary() if control.mode == "collective" else solution.summary()
        warnings = validity.recorded(validity.loads_findings(name, result.summary()), params,
                                     str(rotor_path(outputs["loads"], name)))
        solved[name] = (control.mode, result.disk, summary, result.history, warnings)  # the tables only
    for name, (mode, disk, summary, history, warnings) in solved.items():
        meta = {"aircraft": params["aircraft"], "segment": params["segment"], "rotor": name, "n_psi": grid.n_psi,
                "n_r": grid.n_r, "inputs": [str(inputs["trim"])], **warnings}
        write_table(disk, rotor_path(outputs["loads"], name), stage="loads", metadata=meta)
        write_table(summary, rotor_path(outputs["loads"], name, "_summary"), stage="loads", metadata=meta)
        write_table(history, rotor_path(outputs["loads"], name, "_history"), stage="loads", metadata=meta)
        report += [f"rotor {name} (control {mode}):", summary.to_string(index=False),
                   history.to_string(index=False) + validity.report(warnings)]
    return "\n".join(report)
