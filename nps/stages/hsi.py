"""Stage ``hsi``: HSI processing of every rotor's pressure signals at one observer set (thesis ch. 6).

Each rotor's signals are amplified, sheared and shock-fitted per observer with the rotor's own
radiation Mach number and distance (nps.noise.hsi); the metrics stage sums the rotors.

inputs: ``signals`` (acoustics directory of ``{rotor}.parquet``), ``observers``, ``trim``.
outputs: ``hsi``, a directory with per rotor ``{rotor}.parquet`` (group ``hsi``, same grid) and
``{rotor}_diagnostics.parquet`` (observer, mach_r, radiation_distance_m, amplification,
shear_angle_rad, n_shocks). params: ``rotors``, ``obsset``, ``variant``; optional ``observer``
(id whose intermediate signals are written as ``{rotor}_observer.parquet``: step, time_s, p_Pa; with
the optional output ``figure``, they are drawn for the first rotor, thesis Fig. 6.3 kind); ``aircraft``
and ``segment`` when known (checked against the inputs' provenance).

Before computing: provenance of every input, unique observer ids, every observer of the observer table in every rotor's
signals (and no other), the ``observer`` in the table, memory.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from nps.noise.hsi import OBSERVER_COLUMNS, HsiIntermediate, process
from nps.app.io import artifact_rows, check_provenance, read_signals, read_table, rotor_path, write_table
from nps.noise.observers import OBSERVER_STAGES
from nps.app.resources import check_memory, estimate_bytes
from nps.noise.signals import SIGNAL_STAGES, check_observers
from nps.rotor.trim import TRIM_COLUMNS, TRIM_STAGES, trim_row


def intermediate_table(inter: HsiIntermediate) -> pd.DataFrame:
    """Long table (step, time_s, p_Pa) of the HSI steps at one observer (original … final)."""
    parts = [
        ("original", inter.time_s, inter.p_original_pa),
        ("amplified", inter.time_s, inter.p_amplified_pa),
        ("sheared", inter.time_sheared_s, inter.p_amplified_pa),
        ("fitted", inter.fitted.time_s, inter.fitted.p_pa),
        ("final", inter.time_s, inter.p_final_pa),
    ]
    return pd.DataFrame({
        "step": np.concatenate([[name] * len(t) for name, t, _ in parts]),
        "time_s": np.concatenate([t for _, t, _ in parts]),
        "p_Pa": np.concatenate([p for _, _, p in parts]),
    })


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    observer = params.get("observer")
    same = {"aircraft": params.get("aircraft"), "segment": params.get("segment")}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    check_provenance(inputs["observers"], {"stage": OBSERVER_STAGES, "obsset": params["obsset"], **same})
    for name in rotors:
        check_provenance(rotor_path(inputs["signals"], name), {"stage": SIGNAL_STAGES, "rotor": name, "obsset": params["obsset"],
                                                               "variant": params["variant"], **same})
    trim = read_table(inputs["trim"], required=TRIM_COLUMNS, nonempty=True)
    observers = read_table(inputs["observers"], required=OBSERVER_COLUMNS, nonempty=True, finite=True, unique="observer")
    if observer is not None and int(observer) not in set(observers["observer"].tolist()):
        raise ValueError(f"observer {observer}: not in {inputs['observers']} (observers "
                         f"{int(observers['observer'].min())} to {int(observers['observer'].max())})")
    n_samples = artifact_rows(rotor_path(inputs["signals"], rotors[0])) // (2 * len(observers))
    check_memory(estimate_bytes("hsi", {"n_psi": 1, "n_r": 1, "samples_per_rev": max(1, n_samples)}, len(observers), len(rotors)),
                 f"{outputs['hsi']}: HSI of {len(rotors)} rotor(s) x {len(observers)} observers x {n_samples} samples")
    signals = read_signals(inputs["signals"], rotors)
    for name in rotors:
        check_observers(signals[name], observers["observer"], str(rotor_path(inputs["signals"], name)), str(inputs["observers"]))
    paths = [str(inputs[key]) for key in ("signals", "observers", "trim")]
    report = []
    for name in rotors:
        result = process(signals[name], observers, trim_row(trim, name, str(inputs["trim"])), intermediate_observer=observer)
        meta = {"rotor": name, "obsset": params["obsset"], "variant": params["variant"], "inputs": paths}
        write_table(result.signals, rotor_path(outputs["hsi"], name), stage="hsi", metadata=meta)
        write_table(result.diagnostics, rotor_path(outputs["hsi"], name, "_diagnostics"), stage="hsi", metadata=meta)
        if observer is not None:
            write_table(intermediate_table(result.intermediate), rotor_path(outputs["hsi"], name, "_observer"), stage="hsi",
                        metadata={**meta, "observer": int(observer)})
            if "figure" in outputs and name == rotors[0]:
                from nps.plots.hsi import plot_intermediate

                plot_intermediate(result.intermediate, outputs["figure"])
        report.append(f"rotor {name}:\n{result.diagnostics.describe().to_string()}")
    return "\n".join(report)
