"""Stage ``metrics``: noise metrics and 1/3-octave bands of an aircraft at one observer set.

Sums the rotors' signals (HSI-processed ones where given), adds broadband (Pegg or BPM) and ISO 9613-1
air absorption when asked (nps.noise.metrics) and writes one row per observer and the band table.

inputs: ``signals`` (acoustics directory), optional ``hsi`` (HSI directory), ``trim``, ``observers``;
``disks`` (directory of the rotors' disk tables, the one the acoustics stage radiated) with BPM broadband (``bpm``, or
``auto`` when a rotor is outside Pegg's data range).
outputs: ``metrics`` (observer, elevation_deg, azimuth_deg, oaspl_db, oaspl_dba, bvispl_db, per-source
levels …), ``bands`` (observer × source × band), ``figure`` (spectrum of the loudest observer).
params: ``rotors``, ``solidity`` (rotor → σ), ``atmosphere`` (altitude_m, isa_delta_K,
relative_humidity_pct), ``broadband`` (``pegg``, ``bpm``, ``none`` or ``auto``; true/false = pegg/none,
:func:`nps.app.broadband.broadband_model`; written to the metadata as given; ``auto``: per rotor from the trim,
:func:`nps.app.broadband.rotor_broadband_models`, BPM for the rotors outside Pegg's data range and Pegg for the
others, recorded as ``broadband_rotors``), ``absorption`` (boolean),
``harmonics`` (first and last main-rotor BPF harmonic of BVISPL), with BPM ``rotor_configs`` (rotor →
validated aircraft-configuration entry), ``aircraft``, ``segment``, ``obsset``, ``variant``.
Pegg outside its helicopter main-rotor data range, and BPM on elements outside RP-1218's, are reported
as warnings (stderr and the report) and, when there are any, recorded in both tables' metadata as
``model_warnings`` (a list of the messages). ``rotor_configs`` (rotor → validated rotor configuration) is also
used for Pegg's validity checks; optional ``allow_outside_validity``; optional ``tone_sum`` (the aircraft
schema's ``tone_sum``: ``coherent`` or ``incoherent``, how the rotors' tones add; without it ``coherent``),
recorded in the metadata when ``incoherent``.

Before computing: provenance of every input, unique observer ids, every observer in every rotor's signals, memory,
and for the rotors with Pegg broadband its peak frequency and mean lift coefficient
(nps.app.validity.broadband_findings).
The metrics carry the observer table's validity warnings with their own: levels at observers
outside the envelope are outside it too.
"""

from __future__ import annotations

import warnings

import numpy as np

from nps.app import validity
from nps.core.atmosphere import isa
from nps.noise.broadband.pegg import pegg_outside_range
from nps.app.broadband import broadband_model, rotor_broadband_models
from nps.app.io import artifact_rows, check_provenance, read_signals, read_table, rotor_path, write_table
from nps.noise.metrics import STUDY_BANDS, metrics_tables
from nps.noise.observers import OBSERVER_STAGES
from nps.app.resources import check_memory, estimate_bytes
from nps.noise.signals import SIGNAL_STAGES, TONE_SUMS, check_observers
from nps.rotor.trim import TRIM_STAGES, trim_row


def _bpm_band_msp(inputs: dict, params: dict, trim, observers, atmosphere, names) -> tuple[dict, list[str]]:
    """Rotor → BPM band MSP at the observers (ascending ids) of the rotors ``names``, and warnings for elements
    outside RP-1218's range."""
    from nps.noise.broadband.rotor import (DISK_INPUT_COLUMNS, disk_outside_bpm_range, medium_from_atmosphere,
                                     trimmed_rotor_broadband_msp)

    medium = medium_from_atmosphere(atmosphere)
    positions = observers.sort_values("observer", kind="mergesort")[["x_m", "y_m", "z_m"]].to_numpy(dtype=float)
    out, notes = {}, []
    for name in names:
        disk = read_table(rotor_path(inputs["disks"], name), required=DISK_INPUT_COLUMNS)
        out[name] = trimmed_rotor_broadband_msp(disk, params["rotor_configs"][name], trim_row(trim, name, str(inputs["trim"])),
                                                positions, medium, STUDY_BANDS)
        outside = float(np.mean(disk_outside_bpm_range(disk, medium)))
        if outside > 0.0:
            notes.append(f"BPM: rotor '{name}': {100 * outside:.0f} % of the blade elements outside RP-1218's data range "
                         "(Re_c, Mach ≤ 0.21, |α| ≤ 25.2°): extrapolated (docs/reference/bpm.md)")
    return out, notes


def broadband_sources(inputs: dict, params: dict, models: dict, trim, observers) -> tuple[dict | None, list[str]]:
    """BPM band MSP of the rotors ``models`` gives BPM (None without any; from the input ``disks`` with the params
    ``rotor_configs`` and ``atmosphere``) and the model-range warnings: Pegg outside his data range for the Pegg
    rotors (suggesting BPM), BPM elements outside RP-1218's range. The metrics and source-hemisphere stages'."""
    notes = []
    for name in [name for name, model in models.items() if model == "pegg"]:
        row = trim_row(trim, name, str(inputs["trim"]))
        outside = pegg_outside_range(float(row["radius_m"]), float(row["omega_rad_s"]) * float(row["radius_m"]),
                                     float(row["thrust_N"]))
        notes += [f"Pegg: rotor '{name}': {m}; consider models.broadband: bpm, or auto (BPM for the rotors outside "
                  "Pegg's range; docs/reference/broadband_metrics.md)" for m in outside]
    bpm_rotors = [name for name, model in models.items() if model == "bpm"]
    if not bpm_rotors:
        return None, notes
    if "disks" not in inputs or "rotor_configs" not in params or "atmosphere" not in params:
        raise ValueError(f"broadband '{params['broadband']}' needs the input 'disks' (the rotors' disk tables) "
                         "and the params 'rotor_configs' and 'atmosphere'")
    atm = params["atmosphere"]
    state = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
    bpm_msp, bpm_notes = _bpm_band_msp(inputs, params, trim, observers, state, bpm_rotors)
    return bpm_msp, notes + bpm_notes


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    model = broadband_model(params["broadband"])
    same = {"aircraft": params["aircraft"], "segment": params["segment"]}
    check_provenance(inputs["trim"], {"stage": TRIM_STAGES, **same})
    observer_meta = check_provenance(inputs["observers"], {"stage": OBSERVER_STAGES, "obsset": params["obsset"], **same})
    signal_dirs = {"signals": SIGNAL_STAGES, **({"hsi": "hsi"} if "hsi" in inputs else {})}
    for key, stage in signal_dirs.items():
        for name in rotors:
            check_provenance(rotor_path(inputs[key], name), {"stage": stage, "rotor": name, "obsset": params["obsset"],
                                                             "variant": params["variant"], **same})
    trim = read_table(inputs["trim"], nonempty=True)
    models = rotor_broadband_models(params["broadband"], trim, rotors)
    observers = read_table(inputs["observers"], nonempty=True, finite=True, unique="observer")
    pegg_configs = [config for name, config in params["rotor_configs"].items() if models.get(name, model) == "pegg"]
    findings = validity.broadband_findings({"rotors": pegg_configs}, trim) if pegg_configs else []
    recorded = validity.recorded(findings, params, str(outputs["metrics"]))
    inherited = observer_meta.get("validity_warnings", [])
    if inherited or recorded:
        recorded = {"validity_warnings": inherited + recorded.get("validity_warnings", [])}
    n_samples = artifact_rows(rotor_path(inputs["signals"], rotors[0])) // (2 * len(observers))
    check_memory(estimate_bytes("metrics", {"n_psi": 1, "n_r": 1, "samples_per_rev": max(1, n_samples)}, len(observers),
                                len(rotors), "hsi" in inputs),
                 f"{outputs['metrics']}: metrics of {len(rotors)} rotor(s) x {len(observers)} observers x {n_samples} samples")
    loaded = {key: read_signals(inputs[key], rotors) for key in signal_dirs}
    for key, tables in loaded.items():
        for name, table in tables.items():
            check_observers(table, observers["observer"], str(rotor_path(inputs[key], name)), str(inputs["observers"]))
    signals, hsi = loaded["signals"], loaded.get("hsi")
    atm = params["atmosphere"]
    state = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
    atmosphere = state if params["absorption"] else None
    harmonics = tuple(int(h) for h in params["harmonics"])
    bpm_msp, notes = broadband_sources(inputs, params, models, trim, observers)
    for note in notes:
        warnings.warn(note)
    tone_sum = params["tone_sum"] if "tone_sum" in params else TONE_SUMS[0]
    table, bands, levels = metrics_tables(signals, observers, trim, params["solidity"], atmosphere, hsi,
                                          model != "none", harmonics, bpm_msp, tone_sum)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "bvispl_harmonics": list(harmonics), "absorption": params["absorption"],
            "broadband": params["broadband"], "hsi": hsi is not None,
            **({"tone_sum": tone_sum} if tone_sum != TONE_SUMS[0] else {}),
            **({"broadband_rotors": models} if model == "auto" else {}), **recorded,
            **({"model_warnings": notes} if notes else {})}
    write_table(table, outputs["metrics"], stage="metrics", metadata=meta)
    write_table(bands, outputs["bands"], stage="metrics", metadata=meta)
    if "figure" in outputs:
        from nps.plots.spectra import loudest_observer_figure

        loudest_observer_figure(table, bands, levels, trim, harmonics,
                                f"{params['aircraft']} {params['segment']} {params['obsset']} ({params['variant']})",
                                outputs["figure"])
    return "\n".join(notes + [table.describe().to_string()]) + validity.report(recorded)
