"""Stage ``metrics``: noise metrics and 1/3-octave bands of an aircraft at one observer set.

Sums the rotors' signals (HSI-processed ones where given), adds Pegg broadband and ISO 9613-1 air
absorption when asked (nps.metrics) and writes one row per observer and the band table.

inputs: ``signals`` (acoustics directory), optional ``hsi`` (HSI directory), ``trim``, ``observers``.
outputs: ``metrics`` (observer, elevation_deg, azimuth_deg, oaspl_db, oaspl_dba, bvispl_db, per-source
levels …), ``bands`` (observer × source × band), ``figure`` (spectrum of the loudest observer).
params: ``rotors``, ``solidity`` (rotor → σ), ``atmosphere`` (altitude_m, isa_delta_K,
relative_humidity_pct), ``broadband``, ``absorption`` (booleans), ``harmonics`` (first and last
main-rotor BPF harmonic of BVISPL), ``aircraft``, ``segment``, ``obsset``, ``variant``; ``rotor_configs``
(rotor name → validated rotor configuration: Pegg's validity checks when ``broadband``); optional
``allow_outside_validity``.

Before computing: provenance of every input, every observer in every rotor's signals, memory, and
with Pegg broadband its peak frequency and mean lift coefficient (nps.validity.broadband_findings).
The metrics carry the observer table's validity warnings with their own: levels at observers
outside the envelope are outside it too.
"""

from __future__ import annotations

from nps import validity
from nps.atmosphere import isa
from nps.io import artifact_rows, check_provenance, read_signals, read_table, rotor_path, write_table
from nps.metrics import metrics_tables
from nps.resources import check_memory, estimate_bytes
from nps.signals import check_observers


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    same = {"aircraft": params["aircraft"], "segment": params["segment"]}
    check_provenance(inputs["trim"], {"stage": "trim", **same})
    observer_meta = check_provenance(inputs["observers"], {"stage": "observers", "obsset": params["obsset"], **same})
    signal_dirs = {"signals": "acoustics", **({"hsi": "hsi"} if "hsi" in inputs else {})}
    for key, stage in signal_dirs.items():
        for name in rotors:
            check_provenance(rotor_path(inputs[key], name), {"stage": stage, "rotor": name, "obsset": params["obsset"],
                                                             "variant": params["variant"], **same})
    trim = read_table(inputs["trim"], nonempty=True)
    observers = read_table(inputs["observers"], nonempty=True, finite=True)
    findings = validity.broadband_findings({"rotors": list(params["rotor_configs"].values())}, trim) if params["broadband"] else []
    warnings = validity.recorded(findings, params, str(outputs["metrics"]))
    inherited = observer_meta.get("validity_warnings", [])
    if inherited or warnings:
        warnings = {"validity_warnings": inherited + warnings.get("validity_warnings", [])}
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
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"]) if params["absorption"] else None
    harmonics = tuple(int(h) for h in params["harmonics"])
    table, bands, levels = metrics_tables(signals, observers, trim, params["solidity"], atmosphere, hsi,
                                          params["broadband"], harmonics)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "bvispl_harmonics": list(harmonics), "absorption": params["absorption"],
            "broadband": params["broadband"], "hsi": hsi is not None, **warnings}
    write_table(table, outputs["metrics"], stage="metrics", metadata=meta)
    write_table(bands, outputs["bands"], stage="metrics", metadata=meta)
    if "figure" in outputs:
        from nps.plots.spectra import loudest_observer_figure

        loudest_observer_figure(table, bands, levels, trim, harmonics,
                                f"{params['aircraft']} {params['segment']} {params['obsset']} ({params['variant']})",
                                outputs["figure"])
    return table.describe().to_string() + validity.report(warnings)
