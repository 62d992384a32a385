"""Stage ``tones``: tone table (level and phase of each BPF harmonic) and narrowband spectra of an aircraft
at one observer set (nps.noise.tones).

inputs: ``signals`` (acoustics directory of ``{rotor}.parquet``), ``trim``.
outputs: ``tones`` (Parquet, every observer: observer, source, harmonic, frequency_hz, spl_db, phase_rad),
``tones_csv`` (the same rows for the selected observers), ``spectra`` (Parquet, narrowband line spectra of the
selected observers: observer, source, frequency_hz, msp_Pa2, spl_db).
params: ``rotors`` (names, the first is the reference), ``harmonics`` (BPF harmonics per source),
``loudest`` (the selected observers are the ``loudest`` ones by mean-square total pressure …) and
``observers`` (… plus these ids), ``aircraft``, ``segment``, ``obsset``, ``variant``; optional ``tone_sum``
(the aircraft schema's ``tone_sum``: ``coherent`` or ``incoherent``; without it ``coherent``), recorded in the
metadata when ``incoherent``.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from nps.app.io import read_signals, read_table, write_table
from nps.noise.signals import TONE_SUMS
from nps.noise.tones import loudest_observers, narrowband_table, tone_table
from nps.rotor.trim import TRIM_COLUMNS, trim_row


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    signals = read_signals(inputs["signals"], rotors)
    table = read_table(inputs["trim"], required=TRIM_COLUMNS)
    trim = pd.DataFrame([trim_row(table, r, str(inputs["trim"])) for r in rotors])  # the first rotor is the reference
    harmonics = int(params["harmonics"])
    tone_sum = params["tone_sum"] if "tone_sum" in params else TONE_SUMS[0]
    tones = tone_table(signals, trim, harmonics, tone_sum)
    selected = np.union1d(loudest_observers(signals, rotors, int(params["loudest"]), tone_sum),
                          np.asarray(params["observers"], dtype=np.int64)).astype(np.int64)
    spectra = narrowband_table(signals, rotors, selected, tone_sum)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "reference_rotor": rotors[0], "tone_harmonics": harmonics,
            **({"tone_sum": tone_sum} if tone_sum != TONE_SUMS[0] else {}),
            "selected_observers": selected.tolist(), "inputs": [str(inputs["signals"]), str(inputs["trim"])]}
    write_table(tones, outputs["tones"], stage="tones", metadata=meta)
    write_table(spectra, outputs["spectra"], stage="tones", metadata=meta)
    chosen = tones[tones["observer"].isin(selected)]
    chosen.to_csv(outputs["tones_csv"], index=False, float_format="%.6g")
    bpf1 = chosen[chosen["harmonic"] == 1].pivot(index="observer", columns="source", values="spl_db")
    return f"BPF1 SPL (dB) at the selected observers {selected.tolist()}:\n{bpf1.to_string()}"
