"""``python -m nps tones``: tone table (level and phase of each BPF harmonic, per rotor and total) and
narrowband spectra of an aircraft at one observer set (stage nps.stages.tones).

Reads the acoustics directory of every rotor and the trim artifact; writes the tone table of every observer
(Parquet), its rows for the selected observers (CSV) and their narrowband line spectra (Parquet). The selected
observers are the ``--loudest`` ones (mean-square total pressure) and those listed with ``--observer``.
"""

from __future__ import annotations

from nps.cli import default, fail, option, parser, provenance, run_stage, trim_rotors
from nps.app.config import ConfigError, load_aircraft
from nps.app.io import rotor_path


def main(argv: list[str]) -> int:
    ap = parser("tones", __doc__)
    ap.add_argument("--aircraft", help="aircraft YAML (rotor names and order; the first is the reference); default: "
                                       "the rotors of the trim artifact, in its order (a PSU-WOPWOP case's)")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    ap.add_argument("--harmonics", type=int, default=default("outputs.tone_harmonics"),
                    help="BPF harmonics per source (default %(default)s)")
    ap.add_argument("--loudest", type=int, default=default("outputs.spectra_loudest"),
                    help="select the N loudest observers (default %(default)s)")
    option(ap, "--observer", "outputs.spectra_observers", nargs="+", help="also select these observer ids")
    ap.add_argument("--out", required=True, help="tone table Parquet (every observer)")
    ap.add_argument("--csv", required=True, help="tone table CSV (selected observers)")
    ap.add_argument("--spectra-out", required=True, help="narrowband spectra Parquet (selected observers)")
    args = ap.parse_args(argv)
    if args.aircraft:
        try:
            aircraft = load_aircraft(args.aircraft)
        except ConfigError as error:
            return fail(str(error))
        names, name = [r["name"] for r in aircraft["rotors"]], aircraft["name"]
    else:
        names, name = trim_rotors(args.trim), provenance(args.trim, "aircraft")
        if isinstance(names, str):
            return fail(names)
    rotors = args.rotor or names
    first = str(rotor_path(args.signals, rotors[0]))  # its metadata names the observer set and the variant
    params = {"rotors": rotors, "harmonics": args.harmonics, "loudest": args.loudest, "observers": args.observer,
              "aircraft": name, "segment": provenance(args.trim, "segment"),
              "obsset": provenance(first, "obsset"), "variant": provenance(first, "variant") or "base"}
    outputs = {"tones": args.out, "tones_csv": args.csv, "spectra": args.spectra_out}
    return run_stage("tones", {"signals": args.signals, "trim": args.trim}, outputs, params, args.debug,
                     sources={"--aircraft": args.aircraft} if args.aircraft else None)
