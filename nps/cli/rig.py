"""``python -m nps rig``: set-up of a rig (stage nps.stages.rig).

Writes ``trim.parquet`` (the rotor solved at the rig's condition) and ``microphones.parquet`` into
``--out-dir``. ``python -m nps rotor`` runs a whole rig (set-up, loads, acoustics, tone levels);
``snakemake -j2 NAME`` runs config/rigs/NAME.yaml through the study's stages.
"""

from __future__ import annotations

from pathlib import Path

from nps.cli import parser, run_stage


def main(argv: list[str]) -> int:
    ap = parser("rig", __doc__)
    ap.add_argument("--rig", required=True, help="rig YAML (config/rigs/NAME.yaml)")
    ap.add_argument("--out-dir", required=True, help="output directory")
    args = ap.parse_args(argv)
    out = Path(args.out_dir)
    return run_stage("rig", {"config": args.rig},
                     {"trim": str(out / "trim.parquet"), "observers": str(out / "microphones.parquet")}, {}, args.debug)
