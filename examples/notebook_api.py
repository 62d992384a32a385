"""The notebook API in a script: one case with ``nps.Case``, then a small design study with ``nps.Study``.

Run from the repository root: ``python examples/notebook_api.py`` (preview fidelity, about a minute), or
``python examples/notebook_api.py --quick`` (a coarse resolution, seconds: what tests/workflow/test_examples.py
runs). Results are cached in results/studies/cache/ (or ``--cache DIR``), shared with ``snakemake study_NAME``.
"""

from __future__ import annotations

import argparse

import pandas as pd

import nps
from nps.app.designs import PREVIEW_RESOLUTION

QUICK_RESOLUTION = {"n_psi": 36, "n_r": 10, "wake_revolutions": 2, "samples_per_rev": 128}


def main(argv=None) -> pd.DataFrame:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="coarse resolution (seconds)")
    ap.add_argument("--cache", default="results/studies/cache", help="stage cache directory")
    args = ap.parse_args(argv)
    resolution = QUICK_RESOLUTION if args.quick else PREVIEW_RESOLUTION

    # one aircraft, one mission, one configuration: trim, loads, acoustics and metrics of segment 2
    case = nps.Case.from_files("config/aircraft/helicopter.yaml", "config/missions/demo.yaml", "config/config.yaml",
                               cache_dir=args.cache, resolution=resolution)
    result = case.run("seg2")
    row = result.row.iloc[0]
    print(f"helicopter seg2: main-rotor power {row['main_power_W'] / 1e3:.0f} kW, "
          f"C_T/sigma {row['main_ct_sigma']:.3f}, hemisphere max. {row['max_dba_db']:.1f} dBA")
    print(result.metrics["hemisphere"][["observer", "azimuth_deg", "elevation_deg", "oaspl_db", "oaspl_dba"]].head())

    # a design study: the main-rotor speed at three values (examples/rotor_speed_study.yaml)
    study = nps.Study.from_file("examples/rotor_speed_study.yaml", cache_dir=args.cache, resolution=resolution)
    print(study.designs)
    trade = study.run()
    print(trade.table[["main.omega_rad_s", "segment", "power_W", "max_oaspl_db", "max_dba_db", "pareto"]].to_string(index=False))
    print(trade.ranking.to_string(index=False))
    return trade.table


if __name__ == "__main__":
    main()
