"""``python -m nps station-loads`` (or ``station_loads``): C_n and M²c_n against azimuth at radial stations
(stage nps.stages.station_loads).

Reads the disk tables ``{rotor}.parquet`` in ``--disks`` (a loads directory, or a wake job's ``bvi/``) and the
trim artifact ``--trim`` (radius, density, speed of sound of each rotor); writes one table to ``--out``
(rotor, r_over_R, psi_rad, cn, m2cn). M²c_n = F_n / (½ ρ a² c), c_n = M²c_n / M² (the section's Mach number),
both interpolated linearly in r between the table's stations. Example:

    python -m nps station-loads --disks results/rigs/main_tail_rig/bvi --trim results/rigs/main_tail_rig/trim.parquet \\
        --stations 0.75 0.87 --out out/station_loads.parquet
"""

from __future__ import annotations

from nps.cli import output_file, parser, run_stage


def main(argv: list[str]) -> int:
    ap = parser("station-loads", __doc__)
    ap.add_argument("--disks", required=True, help="directory of {rotor}.parquet disk tables (loads or bvi)")
    ap.add_argument("--trim", required=True, help="trim artifact (trim.parquet)")
    ap.add_argument("--stations", required=True, type=float, nargs="+", help="radial stations r/R")
    ap.add_argument("--rotors", nargs="+", default=None, help="rotors (default: every rotor of the trim)")
    ap.add_argument("--out", required=True, type=output_file(".parquet"), help="output table (.parquet)")
    args = ap.parse_args(argv)
    params = {"stations": args.stations, **({"rotors": args.rotors} if args.rotors else {})}
    return run_stage("station_loads", {"disks": args.disks, "trim": args.trim}, {"table": args.out}, params, args.debug)
