"""Prouty helicopter BET case (thesis Table 4.1 / Fig. 4.5, after Yaakub et al.): controls
imposed, no trim. Data: tests/data/prouty/case.csv.

Reading of the table (docs/reference/loads.md): Prouty's cyclic convention θ = θ0 − A1 cos ψ
− B1 sin ψ, so θ1c = −A1 = +2.3°, θ1s = −B1 = −4.9°; no twist (none listed); the controls
are taken relative to the tip-path plane (β ≡ 0; the table gives no flap data); shaft normal
to the flight path (μ_z = 0); linear inflow from the BET's own C_T.
"""

import math

import numpy as np
import pandas as pd
import pytest

from nps.rotor.bet import Controls, DiskGrid, rotor_loads
from nps.plots.disk import disk_grid, disk_plot
from nps.rotor.geometry import OperatingPoint, RotorGeometry


@pytest.fixture(scope="module")
def prouty(data_dir):
    case = pd.read_csv(data_dir / "prouty" / "case.csv").set_index("quantity")["value"]
    radius = case["radius_m"]
    g = RotorGeometry(name="prouty", n_blades=int(case["n_blades"]), radius_m=radius, chord_m=case["chord_m"],
                      root_cutout_m=case["root_cutout_fraction"] * radius, twist_rad=0.0, thickness_ratio=0.12,
                      lock_number=8.0)
    mu = case["flight_speed_mps"] / case["tip_speed_mps"]
    op = OperatingPoint(case["tip_speed_mps"] / radius, mu, 0.0, 0.0, 1.225, 340.3, 1.0)
    controls = Controls(math.radians(case["collective_deg"]), -math.radians(case["lateral_cyclic_A1_deg"]),
                        -math.radians(case["longitudinal_cyclic_B1_deg"]))
    t = rotor_loads(g, op, DiskGrid(int(case["n_psi"]), int(case["n_r"])), controls, flapping=False)
    return t, mu, radius


def test_reverse_flow_circle_is_where_r_below_mu_sin_psi(prouty):
    """U_T < 0 exactly at the stations with r/R < −μ sin ψ (the circle of diameter μR centred
    at ψ = 270°, r = μR/2), only on the retreating side, and the section angle there is the
    reverse-flow one (wind from the trailing edge: |α| measured from the trailing edge)."""
    t, mu, radius = prouty
    d = t.disk
    inside = d["r_m"] / radius < -mu * np.sin(d["psi_rad"])
    reverse = d["ut_mps"] < 0.0
    assert inside.sum() > 0 and (inside == reverse).all()
    assert (np.sin(d.loc[reverse, "psi_rad"]) < 0).all()
    assert d.loc[reverse, "r_m"].max() < mu * radius


def test_advancing_retreating_asymmetry(prouty, tmp_path, repo_root):
    """Fig. 4.5's pattern: outboard (r > 0.6 R, out of the reverse-flow circle) the retreating
    blade (240°–300°) runs at a higher angle of attack than the advancing blade (60°–120°):
    by more than 5° but less than the 2 × 4.9° of cyclic alone, because the inflow angle
    U_P/U_T is larger where U_T is lower; the
    figure is written to tmp_path (kept for the docs as docs/figures/prouty_aoa.png)."""
    t, mu, radius = prouty
    d = t.disk
    psi_deg = np.degrees(d["psi_rad"])
    outer = d["r_m"] > 0.6 * radius
    adv = d.loc[outer & psi_deg.between(60, 120), "alpha_eff_rad"].mean()
    ret = d.loc[outer & psi_deg.between(240, 300), "alpha_eff_rad"].mean()
    assert 5.0 < math.degrees(ret - adv) < 2 * 4.9
    psi, r, alpha = disk_grid(d, "alpha_eff_rad")
    _, _, ut = disk_grid(d, "ut_mps")
    fig, _, _ = disk_plot(psi, r, np.degrees(alpha), label="angle of attack α (deg)", vmin=-5.0, vmax=30.0,
                          title="Prouty case (Table 4.1): α; dashed: U_T = 0", reverse_flow_ut=ut)
    path = tmp_path / "prouty_aoa.png"
    fig.savefig(path, dpi=100)
    assert path.stat().st_size > 10_000
