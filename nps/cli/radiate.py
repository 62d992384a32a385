"""``python -m nps radiate``: compact F1A pressure signals of tabulated sources at observers (stage nps.stages.radiate).

Sources (Parquet or CSV, long format, one row per node × source time): node, [group], time_s
(uniform, the same for all nodes), x_m, y_m, z_m (ground frame), fx_N, fy_N, fz_N (force on the
fluid), optional volume_m3 (compact thickness monopole), optional vx_mps, vy_mps, vz_mps.
Observers: observer, x_m, y_m, z_m (position at t = 0), vx_mps, vy_mps, vz_mps.
Output: observer, group (each group and "total"), time_s (t_k = T0 + k·D/N), p_Pa.
"""

from __future__ import annotations

from nps.noise.acoustics import C0_MPS, RHO0_KG_M3
from nps.cli import output_file, parser, run_stage


def main(argv: list[str]) -> int:
    ap = parser("radiate", __doc__)
    ap.add_argument("--sources", required=True, help="source table (.parquet or .csv)")
    ap.add_argument("--observers", required=True, help="observer table (.parquet or .csv)")
    ap.add_argument("--t-start", type=float, required=True, help="first observer time T0 (s)")
    ap.add_argument("--duration", type=float, required=True, help="window length D (s)")
    ap.add_argument("--samples", type=int, required=True, help="number of observer samples N")
    ap.add_argument("--c0", type=float, default=C0_MPS, help="speed of sound (m/s), default %(default)s")
    ap.add_argument("--rho0", type=float, default=RHO0_KG_M3, help="density (kg/m^3), default %(default)s")
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="output Parquet")
    args = ap.parse_args(argv)
    params = {"t_start_s": args.t_start, "duration_s": args.duration, "n_samples": args.samples, "c0_mps": args.c0,
              "rho0_kg_m3": args.rho0}
    return run_stage("radiate", {"sources": args.sources, "observers": args.observers}, {"signals": args.out}, params,
                     args.debug)
