"""Stage ``wopwop_read`` (``nps wopwop read``): PSU-WOPWOP's own outputs of a case as NPS artifacts, so that NPS's
HSI, metrics, tones and certification run on pressures PSU-WOPWOP computed (docs/reference/wopwop.md, "Reading").

inputs: ``case`` (the case the outputs belong to: its observers give positions and velocities, its rotors the trim
rows, nps.wopwop.rotors), ``outputs``: the folder holding PSU-WOPWOP's output files of one observer container
(``pressure.tec`` or ``pressure.fn/.nam/.x``; optional ``OASPLdB``, ``OASPLdBA``, ``spl_spectrum``).
outputs: ``out_dir``: ``observers.parquet``, ``trim.parquet`` (the case's rotors), ``signals/{rotor}.parquet``
(groups loading and thickness of the file's pressure), and, when the files are there, ``wopwop_levels.parquet``
(observer, source, weighting dB or dBA, level_db: PSU-WOPWOP's OASPL) and ``wopwop_spectrum.parquet`` (observer,
source, weighting, frequency_hz, spl_db: its narrowband spectrum).
params: optional ``case_index``, ``observer_container`` (the title of the case's observer container the files are
of; default: the case's only one).

PSU-WOPWOP's pressure is the sum of every source container: the signal table is the case's rotor when it has one;
a case with several rotors is refused (NPS's HSI and metrics need each rotor's signal: run the case with
``nps wopwop run``, which keeps the rotors apart). Observer positions of the ``.x`` grid file must be those of the
case's observer container (1e-4 relative): a file from another case is refused.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from nps.app.io import rotor_path, write_table
from nps.noise.acoustics import LOADING, THICKNESS
from nps.noise.signals import signals_table
from nps.stages.wopwop_run import case_file, observer_table
from nps.wopwop.case import read_case
from nps.wopwop.errors import WopwopError
from nps.wopwop.observers import observer_grid
from nps.wopwop.output import SOURCES, pressure_groups, read_output
from nps.wopwop.rotors import rotor_rows
from nps.wopwop.run import ObserverResult, source_containers

STAGE = "wopwop_read"


def _output_file(folder: Path, name: str) -> Path | None:
    """``name.tec`` or ``name.fn`` in ``folder``, or None."""
    for suffix in (".tec", ".fn"):
        if (folder / f"{name}{suffix}").is_file():
            return folder / f"{name}{suffix}"
    return None


def _spec(case, title: str | None):
    specs = [s for s in case.observers if title is None or s.title == title]
    if len(specs) != 1:
        raise WopwopError(f"{case.path}: &ObserverIn: expected {'one titled ' + repr(title) if title else 'exactly one'}, "
                          f"found {len(specs)}; pass observer_container")
    return specs[0]


def _check_positions(table, grid, path) -> None:
    """The grid file's positions against the case's observers (first sample, 1e-4 relative)."""
    if table.positions_m is None:
        return
    expected = grid.position_m + grid.grid.t_start_s * grid.velocity_mps
    scale = max(1.0, float(np.abs(expected).max()))
    if table.positions_m.shape[0] != len(expected) or not np.allclose(table.positions_m[:, 0], expected, rtol=0, atol=1e-4 * scale):
        raise WopwopError(f"{path}: observer positions of its grid file differ from the observers of the case's "
                          f"&ObserverIn '{grid.title}' ({table.positions_m.shape[0]} vs {len(expected)} observers): "
                          "outputs of another case?")


def _source_of(title: str) -> str:
    """The source (thickness, loading, total) a PSU-WOPWOP column title names."""
    return next(source.lower() for source in SOURCES if title.strip().startswith(source))


def _level_tables(folder: Path) -> dict[str, pd.DataFrame]:
    """PSU-WOPWOP's OASPL files as ``wopwop_levels`` (observer, source, weighting "dB" or "dBA", level_db) and its
    narrowband spectrum as ``wopwop_spectrum`` (observer, source, weighting, frequency_hz, spl_db), when present."""
    out, frames = {}, []
    for name, weighting in (("OASPLdB", "dB"), ("OASPLdBA", "dBA")):
        path = _output_file(folder, name)
        if path is not None:
            table = read_output(path)
            frames += [pd.DataFrame({"observer": np.arange(table.values.shape[0], dtype=np.int32),
                                     "source": _source_of(title), "weighting": weighting, "level_db": table.values[:, 0, k]})
                       for k, title in enumerate(table.variables[1:], start=1)]
    if frames:
        out["wopwop_levels"] = pd.concat(frames, ignore_index=True)
    path = _output_file(folder, "spl_spectrum")
    if path is not None:
        table = read_output(path)
        n_obs, n_f, _ = table.values.shape
        out["wopwop_spectrum"] = pd.concat([pd.DataFrame({
            "observer": np.repeat(np.arange(n_obs, dtype=np.int32), n_f), "source": _source_of(title),
            "weighting": "dBA" if "dBA" in title else "dB", "frequency_hz": table.values[:, :, 0].ravel(),
            "spl_db": table.values[:, :, k].ravel()}) for k, title in enumerate(table.variables[1:], start=1)],
            ignore_index=True)
    return out


def run(inputs: dict, outputs: dict, params: dict) -> str:
    path = case_file(inputs["case"])
    case = read_case(path, params.get("case_index"))
    folder = Path(inputs["outputs"])
    pressure_path = _output_file(folder, "pressure")
    if pressure_path is None:
        raise WopwopError(f"{folder}: no pressure.tec or pressure.fn: expected PSU-WOPWOP's pressure output of the case")
    sources = source_containers(case)
    trim = rotor_rows(sources, case.environment.rho_kg_m3, case.environment.c_m_s)
    if len(trim) != 1:
        raise WopwopError(f"{path}: {len(trim)} rotors ({', '.join(trim['rotor'])}): PSU-WOPWOP's pressure is their sum, "
                          "NPS's HSI and metrics need each rotor's signal: run the case with 'nps wopwop run'")
    grid = observer_grid(case, _spec(case, params.get("observer_container")))
    table = read_output(pressure_path)
    _check_positions(table, grid, pressure_path)
    groups = pressure_groups(table)
    if not {"thickness", "loading"} <= set(groups):
        raise WopwopError(f"{pressure_path}: expected thickness and loading pressures (thicknessNoiseFlag and "
                          f"loadingNoiseFlag), found {sorted(groups)}")
    times = table.values[0, :, 0]
    if table.values.shape[0] != len(grid.position_m) or times.size != grid.grid.n_samples:
        raise WopwopError(f"{pressure_path}: {table.values.shape[0]} observers x {times.size} times, expected the case's "
                          f"{len(grid.position_m)} x {grid.grid.n_samples}")
    pressure = np.stack([groups["thickness"], groups["loading"]], axis=1)
    result = ObserverResult(grid, {trim["rotor"].iloc[0]: pressure})
    observers = observer_table(result, trim)
    out_dir = Path(outputs["out_dir"])
    meta = {"case": str(path), "obsset": grid.title, "variant": "wopwop", "inputs": [str(path), str(pressure_path)]}
    write_table(observers, out_dir / "observers.parquet", stage=STAGE, metadata=meta)
    write_table(trim, out_dir / "trim.parquet", stage=STAGE, metadata=meta)
    signals = signals_table(observers["observer"].to_numpy(), (LOADING, THICKNESS), pressure[:, ::-1], grid.grid, total=False)
    signals["time_s"] = np.tile(times, 2 * len(observers))
    write_table(signals, rotor_path(out_dir / "signals", trim["rotor"].iloc[0]), stage=STAGE,
                metadata={**meta, "rotor": trim["rotor"].iloc[0]})
    levels = _level_tables(folder)
    for name, frame in levels.items():
        write_table(frame, out_dir / f"{name}.parquet", stage=STAGE, metadata=meta)
    return (f"{pressure_path}: {len(observers)} observers x {times.size} samples -> {out_dir} "
            f"(rotor {trim['rotor'].iloc[0]}; {', '.join(levels) or 'no level files'})")
