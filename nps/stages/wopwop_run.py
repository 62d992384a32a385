"""Stage ``wopwop_run`` (``nps wopwop run CASE``): a PSU-WOPWOP case radiated by NPS's F1A solver
(nps.wopwop.run; docs/reference/wopwop.md).

inputs: ``case``: a case directory holding ``cases.nam``, a ``cases.nam``, or a case file.
outputs: ``out_dir``: per observer container (``out_dir`` itself for one, ``out_dir/<title>`` for several)
PSU-WOPWOP's output files as the case's switches ask (nps.wopwop.output.run_tables: ``pressure``, ``OASPLdB``,
``OASPLdBA``, ``spl_spectrum``, frequency ranges; ``.tec`` for one observer, PLOT3D ``.fn/.nam/.x`` for several,
ASCII or binary by ASCIIOutputFlag), and NPS's artifacts in ``nps/`` beside them: ``observers.parquet`` (observer,
position at t = 0 and velocity in G, elevation and azimuth from the first rotor's hub, docs/reference/conventions.md),
``trim.parquet`` (one row per rotor, nps.wopwop.rotors) and ``signals/{group}.parquet`` (groups loading and
thickness, one table per source group: a rotor, or a top-level container without rotation), so that ``nps hsi``,
``nps metrics`` and ``nps tones`` run on them.
params: optional ``case_index`` (the case of a ``cases.nam`` holding several, 0-based).

Every file of the case is read and checked before anything is computed; the outputs of an observer container are
written once its pressures are complete (each file atomically).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd

from nps.app.io import rotor_path, write_table
from nps.noise.acoustics import LOADING, THICKNESS
from nps.noise.signals import signals_table
from nps.wopwop.case import read_case
from nps.wopwop.output import run_tables, write_run_tables
from nps.wopwop.rotors import has_rotor, rotor_rows
from nps.wopwop.run import GROUPS, ObserverResult, run_case, source_containers

STAGE = "wopwop_run"


def case_file(path) -> Path:
    """The case a path names: a directory's ``cases.nam``, or the file itself."""
    path = Path(path)
    return path / "cases.nam" if path.is_dir() else path


def observer_table(result: ObserverResult, trim: pd.DataFrame | None) -> pd.DataFrame:
    """Observers (ids 0… in PSU-WOPWOP's order) at t = 0 with their velocities; elevation and azimuth (deg) of each
    from the first rotor's hub (the origin without rotors): d = (−cos az cos el, −sin az cos el, sin el)."""
    grid = result.observers
    hub = trim[["hub_x_m", "hub_y_m", "hub_z_m"]].to_numpy(float)[0] if trim is not None else np.zeros(3)
    d = grid.position_m - hub
    distance = np.linalg.norm(d, axis=1)
    return pd.DataFrame({
        "observer": np.arange(len(d), dtype=np.int32),
        "x_m": grid.position_m[:, 0], "y_m": grid.position_m[:, 1], "z_m": grid.position_m[:, 2],
        "vx_mps": grid.velocity_mps[:, 0], "vy_mps": grid.velocity_mps[:, 1], "vz_mps": grid.velocity_mps[:, 2],
        "elevation_deg": np.degrees(np.arcsin(np.clip(d[:, 2] / np.where(distance > 0, distance, 1.0), -1.0, 1.0))),
        "azimuth_deg": np.degrees(np.arctan2(-d[:, 1], -d[:, 0])) % 360.0,
    })


def _folder_name(title: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", title.strip()) or "observers"


def _write_nps(result: ObserverResult, trim: pd.DataFrame | None, folder: Path, meta: dict) -> list[str]:
    """NPS's artifacts of one observer container (module doc); returns report lines."""
    observers = observer_table(result, trim)
    write_table(observers, folder / "observers.parquet", stage=STAGE, metadata=meta)
    if trim is not None:
        write_table(trim, folder / "trim.parquet", stage=STAGE, metadata=meta)
    order = [GROUPS.index(LOADING), GROUPS.index(THICKNESS)]
    lines = []
    for group, pressure in result.pressure_pa.items():
        table = signals_table(observers["observer"].to_numpy(), (LOADING, THICKNESS), pressure[:, order],
                              result.observers.grid, total=False)
        write_table(table, rotor_path(folder / "signals", group), stage=STAGE, metadata={**meta, "rotor": group})
        lines.append(f"  {group}: thickness p2p max {np.ptp(pressure[:, 0], axis=1).max():.6g} Pa, loading p2p max "
                     f"{np.ptp(pressure[:, 1], axis=1).max():.6g} Pa")
    return lines


def run(inputs: dict, outputs: dict, params: dict) -> str:
    path = case_file(inputs["case"])
    case = read_case(path, params.get("case_index"))
    sources = source_containers(case)
    results = run_case(case, sources=sources)
    trim = rotor_rows(sources, case.environment.rho_kg_m3, case.environment.c_m_s) if has_rotor(sources) else None
    out_dir = Path(outputs["out_dir"])  # written once every observer container's pressures are computed
    report = [f"{path}: {len(sources)} source container(s), {len(results)} observer container(s)"]
    for result in results:
        folder = out_dir if len(results) == 1 else out_dir / _folder_name(result.observers.title)
        grid = result.observers
        times = grid.grid.times_s
        positions = grid.position_m[:, None, :] + times[None, :, None] * grid.velocity_mps[:, None, :]
        total = result.total_pa
        tables = run_tables(case.environment, grid.spec, grid.shape, times, positions,
                            {"thickness": total[:, GROUPS.index(THICKNESS)], "loading": total[:, GROUPS.index(LOADING)]})
        written = write_run_tables(tables, folder, case.environment.ascii_output)
        meta = {"case": str(path), "obsset": grid.title, "variant": "wopwop",
                "modes": sorted(set(result.modes.values())), "inputs": [str(path)]}
        report.append(f"observers '{grid.title}': {len(grid.position_m)} x {grid.grid.n_samples} samples, "
                      f"paths {meta['modes']}, {len(written)} WOPWOP file(s) in {folder}")
        report += _write_nps(result, trim, folder / "nps", meta)
    return "\n".join(report)

