"""Legacy-VTK export of the tip-vortex wake and the blade lines (ParaView-readable).

One binary legacy ``POLYDATA`` file per time step (big-endian float32 points, int32 line
connectivity) plus a ``<stem>.vtk.series`` JSON index (ParaView's file-series format) with the
time of each step, so ParaView animates the wake over blade azimuth. Each file holds, in the
ground frame G (m): every blade's tip-vortex polyline and every blade's lifting line (root to
tip); point data ``age_rad`` (0 on the blades) and ``circulation_m2_s``; cell data ``kind``
(0 vortex, 1 blade) and ``blade``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pandas as pd


def polydata_bytes(points: np.ndarray, lines: list[np.ndarray], point_data: dict, cell_data: dict, title: str) -> bytes:
    """A binary legacy-VTK POLYDATA file as bytes.

    ``points`` (N, 3); ``lines``: index arrays into ``points`` (one polyline each);
    ``point_data``/``cell_data``: name → (N,) floats / (len(lines),) ints.
    """
    points = np.asarray(points, dtype=">f4")
    if points.ndim != 2 or points.shape[1] != 3 or not np.isfinite(points).all():
        raise ValueError(f"polydata_bytes: points must be finite (N, 3), got {points.shape}")
    n = points.shape[0]
    conn = np.concatenate([np.concatenate([[len(line)], line]) for line in lines]).astype(">i4")
    if len(lines) and (conn.min() < 0 or max(int(line.max()) for line in lines) >= n):
        raise ValueError("polydata_bytes: line index out of range")
    out = [
        b"# vtk DataFile Version 3.0\n",
        title.encode("ascii", "replace")[:255] + b"\n",
        b"BINARY\nDATASET POLYDATA\n",
        f"POINTS {n} float\n".encode(), points.tobytes(), b"\n",
        f"LINES {len(lines)} {conn.size}\n".encode(), conn.tobytes(), b"\n",
    ]
    if point_data:
        out.append(f"POINT_DATA {n}\n".encode())
        for name, values in point_data.items():
            values = np.asarray(values, dtype=">f4")
            if values.shape != (n,):
                raise ValueError(f"polydata_bytes: point data '{name}' must have shape ({n},)")
            out += [f"SCALARS {name} float 1\nLOOKUP_TABLE default\n".encode(), values.tobytes(), b"\n"]
    if cell_data:
        out.append(f"CELL_DATA {len(lines)}\n".encode())
        for name, values in cell_data.items():
            values = np.asarray(values, dtype=">i4")
            if values.shape != (len(lines),):
                raise ValueError(f"polydata_bytes: cell data '{name}' must have shape ({len(lines)},)")
            out += [f"SCALARS {name} int 1\nLOOKUP_TABLE default\n".encode(), values.tobytes(), b"\n"]
    return b"".join(out)


def wake_step_polydata(step: pd.DataFrame, blades_g_m: np.ndarray, title: str) -> bytes:
    """Polydata of one time step: rows of the wake artifact for that step (any order) and the
    blade lines ``blades_g_m`` (B, M, 3) in G."""
    step = step.sort_values(["blade", "node"])
    vortex_pts = step[["x_m", "y_m", "z_m"]].to_numpy(dtype=float)
    blades_g_m = np.asarray(blades_g_m, dtype=float)
    n_b, m = blades_g_m.shape[:2]
    points = np.vstack([vortex_pts, blades_g_m.reshape(-1, 3)])
    lines, kind, blade_id = [], [], []
    start = 0
    for k, count in step.groupby("blade", sort=True).size().items():
        lines.append(np.arange(start, start + count))
        kind.append(0)
        blade_id.append(int(k))
        start += count
    for k in range(n_b):
        lines.append(len(vortex_pts) + k * m + np.arange(m))
        kind.append(1)
        blade_id.append(k)
    age = np.concatenate([step["age_rad"].to_numpy(dtype=float), np.zeros(n_b * m)])
    gamma = np.concatenate([step["circulation_m2_s"].to_numpy(dtype=float), np.zeros(n_b * m)])
    return polydata_bytes(points, lines, {"age_rad": age, "circulation_m2_s": gamma},
                          {"kind": np.array(kind), "blade": np.array(blade_id)}, title)


def write_series(out_dir: str | os.PathLike, stem: str, frames: list[tuple[float, bytes]]) -> Path:
    """Write ``<stem>_NNNN.vtk`` files and ``<stem>.vtk.series``; returns the series path.

    Files are written to temporary names and renamed (no half-written step is left behind).
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    entries = []
    for i, (time_s, data) in enumerate(frames):
        name = f"{stem}_{i:04d}.vtk"
        tmp = out / f".{name}.tmp"
        tmp.write_bytes(data)
        os.replace(tmp, out / name)
        entries.append({"name": name, "time": float(time_s)})
    series = out / f"{stem}.vtk.series"
    tmp = out / f".{series.name}.tmp"
    tmp.write_text(json.dumps({"file-series-version": "1.0", "files": entries}, indent=1))
    os.replace(tmp, series)
    return series
