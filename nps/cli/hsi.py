"""``python -m nps hsi``: HSI processing of one rotor's pressure signals (thesis ch. 6).

Reads the rotor's acoustic signals, the observer set and the aircraft trim; writes the ``hsi``
signal table (docs/conventions.md "HSI signals"), optionally a per-observer diagnostics table
(M_r, radiation distance, amplification, shear angle, shocks), and for a named observer the
intermediate signals (Parquet) and the thesis Fig. 6.3 kind of figure.
"""

from __future__ import annotations

import argparse

import numpy as np
import pandas as pd

from nps.hsi import OBSERVER_COLUMNS, process
from nps.io import SIGNAL_COLUMNS, read_table, write_table


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m nps hsi", description=__doc__.splitlines()[0])
    ap.add_argument("--signals", required=True, help="acoustics/{obsset}/{rotor}_{variant}.parquet")
    ap.add_argument("--observers", required=True, help="observers/{obsset}.parquet")
    ap.add_argument("--trim", required=True, help="trim.parquet of the aircraft and segment")
    ap.add_argument("--rotor", required=True, help="rotor name (row of trim.parquet)")
    ap.add_argument("--output", required=True, help="hsi/{obsset}/{rotor}_{variant}.parquet")
    ap.add_argument("--diagnostics", help="optional per-observer table: M_r, distance, factors, shocks")
    ap.add_argument("--observer", type=int, help="observer whose intermediate signals are kept")
    ap.add_argument("--intermediate", help="Parquet of the observer's steps (needs --observer)")
    ap.add_argument("--figure", help="PNG of the observer's steps, thesis Fig. 6.3 kind (needs --observer)")
    return ap


def intermediate_table(inter) -> pd.DataFrame:
    """Long table (step, time_s, p_Pa) of an :class:`nps.hsi.HsiIntermediate`."""
    parts = [
        ("original", inter.time_s, inter.p_original_pa),
        ("amplified", inter.time_s, inter.p_amplified_pa),
        ("sheared", inter.time_sheared_s, inter.p_amplified_pa),
        ("fitted", inter.fitted.time_s, inter.fitted.p_pa),
        ("final", inter.time_s, inter.p_final_pa),
    ]
    return pd.DataFrame(
        {
            "step": np.concatenate([[name] * len(t) for name, t, _ in parts]),
            "time_s": np.concatenate([t for _, t, _ in parts]),
            "p_Pa": np.concatenate([p for _, _, p in parts]),
        }
    )


def main(argv: list[str]) -> int:
    args = _parser().parse_args(argv)
    if (args.intermediate or args.figure) and args.observer is None:
        raise SystemExit("--intermediate and --figure need --observer")
    trim = read_table(args.trim, required=("rotor",))
    rows = trim[trim["rotor"] == args.rotor]
    if len(rows) != 1:
        raise SystemExit(f"{args.trim}: expected one row for rotor '{args.rotor}', found {len(rows)}; rotors: {list(trim['rotor'])}")
    signals = read_table(args.signals, required=SIGNAL_COLUMNS)
    observers = read_table(args.observers, required=OBSERVER_COLUMNS)
    result = process(signals, observers, rows.iloc[0].to_dict(), intermediate_observer=args.observer)
    meta = {"rotor": args.rotor, "inputs": [args.signals, args.observers, args.trim]}
    write_table(result.signals, args.output, stage="hsi", metadata=meta)
    if args.diagnostics:
        write_table(result.diagnostics, args.diagnostics, stage="hsi", metadata=meta)
    if args.intermediate:
        write_table(intermediate_table(result.intermediate), args.intermediate, stage="hsi",
                    metadata={**meta, "observer": args.observer})
    if args.figure:
        from nps.plots.hsi import plot_intermediate

        plot_intermediate(result.intermediate, args.figure)
    d = result.diagnostics
    print(f"hsi {args.rotor}: {len(d)} observers, max M_r {d['mach_r'].max():.3f}, "
          f"{int((d['n_shocks'] > 0).sum())} with shocks -> {args.output}")
    return 0
