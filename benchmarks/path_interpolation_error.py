"""Interpolation error of the path states: the blend of a sample's bracketing states' source hemispheres against
the hemisphere computed directly at the sample's own (unrounded) state, for the samples of a path whose neighbour
weight is nearest 0.5 (the largest interpolation), in the campaign's configuration.

    python benchmarks/path_interpolation_error.py [PATH] [N_SAMPLES]

Prints per sample the state coordinates, the weight and the A-weighted level difference (blend − direct) over the
hemisphere directions below the horizon: mean, RMS and largest |difference| (dB), and the difference of the
loudest level. The bracketing states' hemispheres are the workflow's (results/<aircraft>/<key>/, run
`snakemake -j2 path_NAME` first); the direct ones run in-process through the stage cache results/studies/cache with
the same stage params (nps.app.plan), so the two differ by the state only."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

from nps.app.config import load_campaign, load_path, read_yaml
from nps.app.io import read_table
from nps.core.atmosphere import isa
from nps.mission.path_states import plan_path, state_flight, state_speeds
from nps.mission.source_hemisphere import hemisphere_from_table
from nps.noise.metrics import a_weighting_db
from nps.noise.spectra import third_octave_bands
from nps.stages.case import StageCache, run_chain


def a_levels(hemisphere) -> np.ndarray:
    """A-weighted level (dB(A)) of every direction below the horizon."""
    bands = third_octave_bands(hemisphere.band_numbers)
    weight = 10.0 ** (a_weighting_db(bands["center_hz"]) / 10.0)
    below = hemisphere.elevation_deg < 0.0
    return 10.0 * np.log10(10.0 ** (hemisphere.levels_db[below] / 10.0) @ weight)


def main(path_name: str = "helicopter_decelerating_approach", n_samples: int = 3) -> None:
    config = read_yaml("config/config.yaml")
    campaign = load_campaign(config, "config/config.yaml", root=".")
    path = load_path(f"config/paths/{path_name}.yaml", campaign.config["paths"]["dt_s"])
    campaign = campaign.with_paths({path_name: path})
    aircraft = campaign.aircraft[path["aircraft"]]
    atm = campaign.config["atmosphere"]
    atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
    plan = plan_path(aircraft, path, campaign.config["paths"], atmosphere)
    reference = aircraft["rotors"][0]
    tip_speed = reference["omega_rad_s"] * reference["radius_m"]
    rotors = [r["name"] for r in aircraft["rotors"]]
    weight = plan.states.weight
    picks = np.argsort(np.abs(weight - 0.5))[:n_samples]
    direct_states = {}
    for i in picks:
        flight, fraction = state_flight(plan.coordinates[i], tip_speed, atmosphere)
        direct_states[f"direct{i}"] = {"aircraft": {path["aircraft"]: state_speeds(flight, fraction, rotors)}}
    campaign = dataclasses.replace(campaign, path_states={**campaign.path_states, **direct_states})
    cache = StageCache(Path("results/studies/cache"))

    def hemisphere(segment):
        product = Path(f"results/{path['aircraft']}/{segment}/source_hemisphere.parquet")
        if not product.is_file():
            chain = run_chain(campaign, path["aircraft"], segment, cache, [], source_set=True)
            product = chain["source_hemisphere"].paths["hemisphere"]
        return hemisphere_from_table(read_table(product))

    print(f"{path_name}: {plan.history.time_s.size} samples, {len(plan.keys)} lattice states, {len(set(plan.keys))} distinct trims")
    for i in picks:
        key_a, key_b = plan.keys[plan.states.state[i]], plan.keys[plan.states.neighbour[i]]
        w = weight[i]
        blend = (1.0 - w) * a_levels(hemisphere(key_a)) + w * a_levels(hemisphere(key_b))
        direct = a_levels(hemisphere(f"direct{i}"))
        diff = blend - direct
        coords = ", ".join(f"{v:.4g}" for v in plan.coordinates[i])
        print(f"t = {plan.history.time_s[i]:6.1f} s  ({coords})  w = {w:.2f}: blend − direct mean {diff.mean():+.2f}, "
              f"RMS {np.sqrt(np.mean(diff**2)):.2f}, max |.| {np.abs(diff).max():.2f} dB; loudest "
              f"{blend.max():.2f} vs {direct.max():.2f} dB(A)")


if __name__ == "__main__":
    main(*(sys.argv[1:2] or []), *(int(a) for a in sys.argv[2:3]))
