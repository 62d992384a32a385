"""``python -m nps metrics``: noise metrics and 1/3-octave bands of one observer set.

Reads the pressure signals of every rotor (and optionally the HSI-processed signals), the
observers and trim artifacts and the aircraft configuration; writes the metrics table (one row
per observer) and the band table (observer × source × band), and optionally a spectrum figure
of the loudest observer.
"""

from __future__ import annotations

import argparse
import sys

from nps.atmosphere import isa
from nps.config import ConfigError, load_aircraft
from nps.io import SIGNAL_COLUMNS, ArtifactError, read_table, write_table
from nps.metrics import metrics_tables, rotor_solidities

OBSERVER_COLUMNS = ("observer", "x_m", "y_m", "z_m", "elevation_deg", "azimuth_deg")
TRIM_COLUMNS = ("rotor", "n_blades", "radius_m", "omega_rad_s", "thrust_N", "ct", "hub_x_m", "hub_y_m", "hub_z_m",
                "r_gh_02", "r_gh_12", "r_gh_22", "speed_of_sound_mps")


def _rotor_paths(items: list[str], option: str) -> dict[str, str]:
    out = {}
    for item in items:
        name, sep, path = item.partition("=")
        if not sep or not name or not path:
            raise ValueError(f"{option} expects ROTOR=PATH, got {item!r}")
        out[name] = path
    return out


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="python -m nps metrics", description=__doc__)
    parser.add_argument("--aircraft", required=True, help="aircraft YAML (rotor solidities)")
    parser.add_argument("--trim", required=True, help="trim.parquet")
    parser.add_argument("--observers", required=True, help="observers/{obsset}.parquet")
    parser.add_argument("--signals", nargs="+", required=True, metavar="ROTOR=PATH", help="pressure signals per rotor")
    parser.add_argument("--hsi", nargs="+", default=None, metavar="ROTOR=PATH", help="HSI-processed signals per rotor")
    parser.add_argument("--altitude-m", type=float, default=0.0)
    parser.add_argument("--isa-delta-k", type=float, default=0.0)
    parser.add_argument("--relative-humidity-pct", type=float, default=70.0)
    parser.add_argument("--no-absorption", action="store_true", help="skip ISO 9613-1 air absorption")
    parser.add_argument("--no-broadband", action="store_true", help="skip the Pegg broadband source")
    parser.add_argument("--bvispl-harmonics", type=int, nargs=2, default=(7, 40), metavar=("FIRST", "LAST"))
    parser.add_argument("--out", required=True, help="metrics Parquet (one row per observer)")
    parser.add_argument("--bands-out", required=True, help="1/3-octave band Parquet")
    parser.add_argument("--figure", default=None, help="optional spectrum figure (PNG) of the loudest observer")
    args = parser.parse_args(argv)
    try:
        aircraft = load_aircraft(args.aircraft)
        signals = {r: read_table(p, SIGNAL_COLUMNS) for r, p in _rotor_paths(args.signals, "--signals").items()}
        hsi = None
        if args.hsi:
            hsi = {r: read_table(p, SIGNAL_COLUMNS) for r, p in _rotor_paths(args.hsi, "--hsi").items()}
        observers = read_table(args.observers, OBSERVER_COLUMNS)
        trim = read_table(args.trim, TRIM_COLUMNS)
        atmosphere = None if args.no_absorption else isa(args.altitude_m, args.isa_delta_k, args.relative_humidity_pct)
        harmonics = tuple(args.bvispl_harmonics)
        table, bands, levels = metrics_tables(
            signals, observers, trim, rotor_solidities(aircraft), atmosphere, hsi, not args.no_broadband, harmonics
        )
    except (ConfigError, ArtifactError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    meta = {"aircraft": aircraft["name"], "bvispl_harmonics": list(harmonics), "absorption": atmosphere is not None,
            "broadband": not args.no_broadband, "hsi": hsi is not None}
    write_table(table, args.out, stage="metrics", metadata=meta)
    write_table(bands, args.bands_out, stage="metrics", metadata=meta)
    if args.figure:
        from nps.plots.spectra import loudest_observer_figure

        loudest_observer_figure(table, bands, levels, trim, harmonics, aircraft["name"], args.figure)
    print(table.describe().loc[["min", "max"]].to_string())
    return 0
