"""Stage ``station_loads``: C_n and M²c_n against azimuth at radial stations r/R of every rotor's disk table
(nps.rotor.station_loads; the HART-II convention M²c_n = F_n / (½ ρ a² c)).

inputs: ``disks`` (directory of ``{rotor}.parquet`` disk tables: the loads stage's, or the wake stage's BVI
loads), ``trim`` (trim artifact: each rotor's radius, density and speed of sound). outputs: ``table`` (one
table, :data:`nps.rotor.station_loads.STATION_COLUMNS`: rotor, r_over_R, psi_rad, cn, m2cn). params:
``stations`` (r/R list of every rotor, or ``{rotor: r/R list}`` per rotor, e.g. a rig's rotors[].stations_r_over_R,
:func:`nps.rig.case.station_params`), optional ``rotors`` (default: every rotor of the trim, or of the mapping),
``aircraft``, ``segment``, ``variant`` (metadata and provenance). Every rotor is computed before the table is
written.
"""

from __future__ import annotations

from typing import Mapping

import pandas as pd

from nps.app.io import check_provenance, read_table, rotor_path, write_table
from nps.rotor.station_loads import DISK_COLUMNS, station_loads
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row


def run(inputs: dict, outputs: dict, params: dict) -> str:
    same = {key: params.get(key) for key in ("aircraft", "segment")}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    spec = params["stations"]
    per_rotor = isinstance(spec, Mapping)
    rotors = list(params.get("rotors") or (spec if per_rotor else trim["rotor"]))
    if per_rotor and set(rotors) - set(spec):
        raise ValueError(f"station_loads: params stations: expected the stations of every rotor {rotors}, got none for "
                         f"{sorted(set(rotors) - set(spec))}")
    wanted = {name: [float(s) for s in (spec[name] if per_rotor else spec)] for name in rotors}
    if not all(wanted.values()):
        raise ValueError("station_loads: params stations: expected at least one station r/R")
    stations = wanted if per_rotor else wanted[rotors[0]]
    parts = []
    for name in rotors:
        path = rotor_path(inputs["disks"], name)
        check_provenance(path, {"stage": ("loads", "bvi"), "rotor": name, **same})
        row = trim_row(trim, name, str(inputs["trim"]))
        disk = read_table(path, required=DISK_COLUMNS, nonempty=True)
        parts.append(station_loads(disk, name, float(row["radius_m"]), float(row["density_kg_m3"]),
                                   float(row["speed_of_sound_mps"]), wanted[name], what=str(path)))
    table = pd.concat(parts, ignore_index=True)
    meta = {**{k: v for k, v in same.items() if v}, "variant": params.get("variant", ""), "stations_r_over_R": stations,
            "inputs": [str(rotor_path(inputs["disks"], n)) for n in rotors] + [str(inputs["trim"])]}
    write_table(table, outputs["table"], stage="station_loads", metadata=meta)
    peaks = table.groupby(["rotor", "r_over_R"])["m2cn"].agg(["min", "max"]).reset_index()
    return "\n".join(f"rotor {p.rotor}, r/R {p.r_over_R:g}: M2cn {p.min:.4g} ... {p.max:.4g}" for p in peaks.itertuples())
