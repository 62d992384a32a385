"""``python -m nps hsi``: HSI processing of every rotor's pressure signals at one observer set (stage nps.stages.hsi).

Reads the acoustics directory (``{rotor}.parquet``), the observer table and the trim artifact; writes
``{rotor}.parquet`` (group ``hsi``) and ``{rotor}_diagnostics.parquet`` (M_r, radiation distance,
amplification, shear angle, shocks) into ``--out-dir``; ``--observer`` adds that observer's
intermediate signals (``{rotor}_observer.parquet``) and ``--figure`` draws them (thesis Fig. 6.3 kind).
"""

from __future__ import annotations

from nps.cli import fail, parser, provenance, run_stage


def main(argv: list[str]) -> int:
    ap = parser("hsi", __doc__)
    ap.add_argument("--signals", required=True, help="acoustics directory (results/.../acoustics/SET_VARIANT)")
    ap.add_argument("--observers", required=True, help="observer table (results/.../observers/SET.parquet)")
    ap.add_argument("--trim", required=True, help="aircraft trim artifact (results/.../trim.parquet)")
    ap.add_argument("--rotor", nargs="+", required=True, help="rotor names (rows of the trim artifact)")
    ap.add_argument("--out-dir", required=True, help="output directory (results/.../hsi/SET_VARIANT)")
    ap.add_argument("--observer", type=int, help="observer whose intermediate signals are kept")
    ap.add_argument("--figure", help="PNG of the observer's HSI steps for the first rotor (needs --observer)")
    args = ap.parse_args(argv)
    if args.figure and args.observer is None:
        return fail("--figure needs --observer")
    params = {"rotors": args.rotor, "obsset": provenance(args.observers, "obsset"),
              "variant": provenance(args.signals + "/" + args.rotor[0] + ".parquet", "variant")}
    if args.observer is not None:
        params["observer"] = args.observer
    outputs = {"hsi": args.out_dir, **({"figure": args.figure} if args.figure else {})}
    return run_stage("hsi", {"signals": args.signals, "observers": args.observers, "trim": args.trim}, outputs, params,
                     args.debug)
