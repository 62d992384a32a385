"""Stage ``rotor_figures``: disk plots of the trimmed loads and, where the wake was computed, its top/side views and the BVI

Stage contract: :mod:`nps.stages`.
"""

from __future__ import annotations

from pathlib import Path

from nps.app.io import read_table, rotor_path


def run(inputs: dict, outputs: dict, params: dict) -> str:
    """Disk plots of the trimmed loads and, where the wake was computed, its top/side views and the BVI
    loading maps of the drawn rotors.

    inputs: ``loads`` (directory), optional ``wake`` and ``bvi`` (directories). outputs: ``figures``
    (directory: ``disk_{rotor}.png``, ``wake_{rotor}.png``, ``bvi_{rotor}.png``). params: ``rotors``
    (drawn rotor → {rotation_sign, radius_m}), ``aircraft``, ``segment``; optional ``segment_name`` (the
    mission's name of the segment, in the titles).
    """
    from nps.plots import segment_title
    from nps.plots.disk import loads_figure
    from nps.plots.wake import bvi_figure_from_tables, wake_figure_from_tables

    out = Path(outputs["figures"])
    out.mkdir(parents=True, exist_ok=True)
    report = []
    for rotor, spec in params["rotors"].items():
        name = f"{params['aircraft']} {segment_title(params['segment'], params.get('segment_name'))}, rotor '{rotor}'"
        disk = read_table(rotor_path(inputs["loads"], rotor))
        loads_figure(disk, out / f"disk_{rotor}.png", rotation_sign=int(spec["rotation_sign"]), title=f"{name} (flying toward the top)")
        if "wake" in inputs:
            wake_figure_from_tables(read_table(rotor_path(inputs["wake"], rotor)), disk, out / f"wake_{rotor}.png",
                                    radius_m=float(spec["radius_m"]), title=f"{name}: tip vortices, blade 0 at ψ = 0")
            bvi_figure_from_tables(disk, read_table(rotor_path(inputs["bvi"], rotor)), out / f"bvi_{rotor}.png",
                                   rotation_sign=int(spec["rotation_sign"]), title=f"{name} (flying toward the top)")
        report.append(f"rotor {rotor}: figures written")
    return "\n".join(report)
