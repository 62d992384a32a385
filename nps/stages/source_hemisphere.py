"""Stage ``source_hemisphere``: the source-hemisphere product of an aircraft in one segment.

Per-observer 1/3-octave band levels (10 Hz–10 kHz) per source on a far-field hemisphere moving
with the aircraft, without air absorption, referred to the reference radius by spherical spreading
(nps.mission.source_hemisphere: schema and why far field).

inputs: ``signals`` (acoustics directory of the far-field hemisphere set), optional ``hsi`` (its HSI
directory: the HSI-processed tonal total replaces thickness + loading), ``trim``, ``observers``.
outputs: ``hemisphere`` (Parquet, one row per observer × source × band).
params: ``rotors``, ``solidity`` (rotor → σ), optional ``tone_sum`` (the aircraft's: ``coherent`` or
``incoherent``; without it ``coherent``), ``broadband`` (``pegg`` or ``none``, true/false; ``bpm`` and
``auto`` are not available here yet: an error before any input is read), ``reference_radius_m``,
``aircraft``, ``segment``, ``obsset``, ``variant``.
"""

from __future__ import annotations

from nps.app.config import broadband_model
from nps.app.io import read_signals, read_table, write_table
from nps.mission.source_hemisphere import source_hemisphere_table
from nps.noise.signals import TONE_SUMS


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    model = broadband_model(params["broadband"])
    if model in ("bpm", "auto"):
        raise ValueError(f"source_hemisphere: models.broadband '{model}' is not available for source hemispheres yet "
                         "(they hold Pegg's broadband or none; 'auto' would give some rotors BPM); use pegg or none")
    signals = read_signals(inputs["signals"], rotors)
    hsi = read_signals(inputs["hsi"], rotors) if "hsi" in inputs else None
    tone_sum = params["tone_sum"] if "tone_sum" in params else TONE_SUMS[0]
    table = source_hemisphere_table(signals, read_table(inputs["observers"]), read_table(inputs["trim"]),
                                    params["solidity"], hsi, model == "pegg",
                                    float(params["reference_radius_m"]), tone_sum)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "broadband": model == "pegg", "hsi": hsi is not None,
            "reference_radius_m": float(params["reference_radius_m"]), "absorption": False,
            "inputs": [str(inputs["signals"]), str(inputs["trim"]), str(inputs["observers"])],
            **({"tone_sum": tone_sum} if tone_sum != TONE_SUMS[0] else {})}
    write_table(table, outputs["hemisphere"], stage="source_hemisphere", metadata=meta)
    total = table[table["source"] == "total"]
    return (f"{total['observer'].nunique()} observers x {total['band'].nunique()} bands, sources "
            f"{sorted(table['source'].unique())}; total band levels {total['level_db'].min():.1f}..{total['level_db'].max():.1f} dB "
            f"at {table['radius_m'].iloc[0]:.2f} m")
