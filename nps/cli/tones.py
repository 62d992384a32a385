"""``python -m nps tones``: tone table (level and phase of each BPF harmonic, per rotor and total) and
narrowband spectra of an aircraft at one observer set (stage nps.stages.tones), with the params the workflow plans
for it (nps.app.plan: the aircraft file's rotors and tone sum).

Reads the acoustics directory of every rotor and the trim artifact; writes the tone table of every observer
(Parquet), its rows for the selected observers (CSV) and their narrowband line spectra (Parquet). The selected
observers are the ``--loudest`` ones (mean-square total pressure) and those listed with ``--observer``.
"""

from __future__ import annotations

from nps.cli import command_rotors, fail, option, output_file, parser, plan, provenance, run_stage, signals_variant


def main(argv: list[str]) -> int:
    ap = parser("tones", __doc__)
    ap.add_argument("--aircraft", help="aircraft YAML (rotor names and order, the first the reference; tone sum); default: "
                                       "the rotors of the trim artifact, in its order (a PSU-WOPWOP case's), summed coherently")
    ap.add_argument("--trim", required=True, help="trim.parquet")
    ap.add_argument("--signals", required=True, help="acoustics directory of the rotors' signals")
    ap.add_argument("--rotor", nargs="+", help="rotor names (default: every rotor of the aircraft)")
    option(ap, "--harmonics", "outputs.tone_harmonics", help="BPF harmonics per source (default %(default)s)")
    option(ap, "--loudest", "outputs.spectra_loudest", help="select the N loudest observers (default %(default)s)")
    option(ap, "--observer", "outputs.spectra_observers", nargs="+", help="also select these observer ids")
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="tone table Parquet (every observer)")
    ap.add_argument("--csv", required=True, type=output_file(".csv"), help="tone table CSV (selected observers)")
    ap.add_argument("--spectra-out", required=True, type=output_file(".parquet"),
                    help="narrowband spectra Parquet (selected observers)")
    args = ap.parse_args(argv)
    try:
        aircraft, rotors = command_rotors(args.aircraft, args.rotor, args.trim)
        params = plan("tones", ap, args, aircraft)
    except ValueError as error:  # a bad file or field (ConfigError), an unreadable trim artifact
        return fail(str(error))
    params.update(rotors=rotors or params["rotors"], aircraft=aircraft["name"], segment=provenance(args.trim, "segment"))
    first = params["rotors"][0]  # its signals' metadata names the observer set and the variant
    params.update(obsset=provenance(f"{args.signals}/{first}.parquet", "obsset"), variant=signals_variant(args.signals, first))
    outputs = {"tones": args.out, "tones_csv": args.csv, "spectra": args.spectra_out}
    return run_stage("tones", {"signals": args.signals, "trim": args.trim}, outputs, params, args.debug,
                     sources={"--aircraft": args.aircraft} if args.aircraft else None)
