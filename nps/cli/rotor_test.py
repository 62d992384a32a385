"""``python -m nps rotor_test``: set-up of a rotor test case (stage nps.stages.rotor_test).

Writes ``trim.parquet`` (the rotor solved at the test condition) and ``microphones.parquet`` into
``--out-dir``. ``python -m nps rotor`` runs a whole test (set-up, loads, acoustics, tone levels).
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import parser, run_stage


def main(argv: list[str]) -> int:
    ap = parser("rotor_test", __doc__)
    ap.add_argument("--test", required=True, help="rotor test YAML (config/tests/NAME.yaml)")
    ap.add_argument("--out-dir", required=True, help="output directory")
    args = ap.parse_args(argv)
    out = Path(args.out_dir)
    return run_stage("rotor_test", {"config": args.test},
                     {"trim": str(out / "trim.parquet"), "observers": str(out / "microphones.parquet")}, {}, args.debug)
