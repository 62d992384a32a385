"""Stage ``source_hemisphere``: the source-hemisphere product of an aircraft in one segment.

Per-observer 1/3-octave band levels (10 Hz–10 kHz) per source on a far-field hemisphere moving
with the aircraft, without air absorption, referred to the reference radius by spherical spreading
(nps.mission.source_hemisphere: schema and why far field).

inputs: ``signals`` (acoustics directory of the far-field hemisphere set), optional ``hsi`` (its HSI
directory: the HSI-processed tonal total replaces thickness + loading), ``trim``, ``observers``; ``disks``
(the rotors' disk tables the signals were radiated from) with BPM broadband (``bpm``, or ``auto`` when a rotor
is outside Pegg's data range), as the metrics stage.
outputs: ``hemisphere`` (Parquet, one row per observer × source × band).
params: ``rotors``, ``solidity`` (rotor → σ), optional ``tone_sum`` (the aircraft's: ``coherent`` or
``incoherent``; without it ``coherent``), ``broadband`` (``pegg``, ``bpm``, ``none`` or ``auto``, true/false;
per rotor as in the metrics stage, :func:`nps.app.broadband.rotor_broadband_models`; written to the metadata as
given, with ``broadband_rotors`` for ``auto``), with BPM ``rotor_configs`` (rotor → validated rotor
configuration) and ``atmosphere`` (the medium of BPM; no absorption here), ``reference_radius_m``,
``aircraft``, ``segment``, ``obsset``, ``variant``. The model-range warnings (Pegg outside his data range, BPM
elements outside RP-1218's) are printed and recorded as ``model_warnings``, as in the metrics stage.
"""

from __future__ import annotations

import warnings

from nps.app.broadband import broadband_model, rotor_broadband_models
from nps.app.io import read_signals, read_table, write_table
from nps.mission.source_hemisphere import source_hemisphere_table
from nps.noise.signals import TONE_SUMS
from nps.stages.metrics import broadband_sources


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    model = broadband_model(params["broadband"])
    trim, observers = read_table(inputs["trim"], nonempty=True), read_table(inputs["observers"])
    models = rotor_broadband_models(params["broadband"], trim, rotors)
    bpm_msp, notes = broadband_sources(inputs, params, models, trim, observers)
    for note in notes:
        warnings.warn(note)
    signals = read_signals(inputs["signals"], rotors)
    hsi = read_signals(inputs["hsi"], rotors) if "hsi" in inputs else None
    tone_sum = params["tone_sum"] if "tone_sum" in params else TONE_SUMS[0]
    table = source_hemisphere_table(signals, observers, trim, params["solidity"], hsi, model != "none",
                                    float(params["reference_radius_m"]), tone_sum, bpm_msp)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "broadband": params["broadband"], "hsi": hsi is not None,
            "reference_radius_m": float(params["reference_radius_m"]), "absorption": False,
            "inputs": [str(inputs["signals"]), str(inputs["trim"]), str(inputs["observers"])],
            **({"tone_sum": tone_sum} if tone_sum != TONE_SUMS[0] else {}),
            **({"broadband_rotors": models} if model == "auto" else {}), **({"model_warnings": notes} if notes else {})}
    write_table(table, outputs["hemisphere"], stage="source_hemisphere", metadata=meta)
    total = table[table["source"] == "total"]
    return "\n".join(notes + [
        f"{total['observer'].nunique()} observers x {total['band'].nunique()} bands, sources "
        f"{sorted(table['source'].unique())}; total band levels "
        f"{total['level_db'].min():.1f}..{total['level_db'].max():.1f} dB "
        f"at {table['radius_m'].iloc[0]:.2f} m"])
