"""Stage ``metrics``: noise metrics and 1/3-octave bands of an aircraft at one observer set.

Sums the rotors' signals (HSI-processed ones where given), adds Pegg broadband and ISO 9613-1 air
absorption when asked (nps.metrics) and writes one row per observer and the band table.

inputs: ``signals`` (acoustics directory), optional ``hsi`` (HSI directory), ``trim``, ``observers``.
outputs: ``metrics`` (observer, elevation_deg, azimuth_deg, oaspl_db, oaspl_dba, bvispl_db, per-source
levels …), ``bands`` (observer × source × band), ``figure`` (spectrum of the loudest observer).
params: ``rotors``, ``solidity`` (rotor → σ), ``atmosphere`` (altitude_m, isa_delta_K,
relative_humidity_pct), ``broadband``, ``absorption`` (booleans), ``harmonics`` (first and last
main-rotor BPF harmonic of BVISPL), ``aircraft``, ``segment``, ``obsset``, ``variant``.
"""

from __future__ import annotations

from nps.atmosphere import isa
from nps.io import read_signals, read_table, write_table
from nps.metrics import metrics_tables


def run(inputs: dict, outputs: dict, params: dict) -> str:
    rotors = list(params["rotors"])
    signals = read_signals(inputs["signals"], rotors)
    hsi = read_signals(inputs["hsi"], rotors) if "hsi" in inputs else None
    trim = read_table(inputs["trim"])
    observers = read_table(inputs["observers"])
    atm = params["atmosphere"]
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"]) if params["absorption"] else None
    harmonics = tuple(int(h) for h in params["harmonics"])
    table, bands, levels = metrics_tables(signals, observers, trim, params["solidity"], atmosphere, hsi,
                                          params["broadband"], harmonics)
    meta = {"aircraft": params["aircraft"], "segment": params["segment"], "obsset": params["obsset"],
            "variant": params["variant"], "bvispl_harmonics": list(harmonics), "absorption": params["absorption"],
            "broadband": params["broadband"], "hsi": hsi is not None}
    write_table(table, outputs["metrics"], stage="metrics", metadata=meta)
    write_table(bands, outputs["bands"], stage="metrics", metadata=meta)
    if "figure" in outputs:
        from nps.plots.spectra import loudest_observer_figure

        loudest_observer_figure(table, bands, levels, trim, harmonics,
                                f"{params['aircraft']} {params['segment']} {params['obsset']} ({params['variant']})",
                                outputs["figure"])
    return table.describe().to_string()
