"""Aircraft trim: force/moment balance of every bundled aircraft in every segment.

The checks recompute the balance from the artifact columns (thrust along z_H = third column of
r_gh, weight, fuselage drag), independently of the solver's own residual.
"""

import numpy as np
import pytest

from nps.core.atmosphere import isa
from nps.app.config import load_campaign, read_yaml
from nps.rotor.trim import G0_M_S2, FlightCondition, glauert_inflow, trim_aircraft, disk_flow_angle_deg


@pytest.fixture(scope="module")
def campaign(repo_root):
    return load_campaign(read_yaml(repo_root / "config/config.yaml"), root=repo_root)


def _trim(campaign, aircraft, forward, climb):
    return trim_aircraft(campaign.aircraft[aircraft], FlightCondition(forward, climb, isa(0.0)))


def _forces(campaign, aircraft, table, forward, climb):
    config = campaign.aircraft[aircraft]
    rho = isa(0.0).density_kg_m3
    velocity = np.array([forward, 0.0, climb])
    speed = np.linalg.norm(velocity)
    drag = 0.5 * rho * speed**2 * config["fuselage_drag_area_m2"] * (velocity / speed if speed else 0.0)
    thrust = sum(row.thrust_N * np.array([getattr(row, f"r_gh_{i}2") for i in range(3)]) for row in table.itertuples())
    return thrust - drag - np.array([0.0, 0.0, config["gross_weight_kg"] * G0_M_S2])


@pytest.mark.parametrize("aircraft", ["helicopter", "tandem", "coaxial", "hexacopter"])
def test_force_balance_every_segment(campaign, aircraft):
    """|Σ F| < 1e-8 W in all six segments."""
    weight = campaign.aircraft[aircraft]["gross_weight_kg"] * G0_M_S2
    for segment in campaign.segments:
        speeds = campaign.segment(segment)["aircraft"][aircraft]
        table = _trim(campaign, aircraft, speeds["forward_speed_mps"], speeds["climb_speed_mps"])
        residual = _forces(campaign, aircraft, table, speeds["forward_speed_mps"], speeds["climb_speed_mps"])
        assert np.max(np.abs(residual)) < 1e-8 * weight, (segment, residual)


@pytest.mark.parametrize("aircraft", ["helicopter", "tandem", "coaxial", "hexacopter"])
def test_hover_has_no_edgewise_flow(campaign, aircraft):
    table = _trim(campaign, aircraft, 0.0, 0.0)
    assert np.allclose(table.mu_x, 0.0, atol=1e-15) and np.allclose(table.mu_y, 0.0, atol=1e-15)
    assert np.allclose(table.mu_z, 0.0, atol=1e-15)


@pytest.mark.parametrize("aircraft, n", [("hexacopter", 6), ("coaxial", 2)])
def test_hover_symmetric_layout_shares_equally(campaign, aircraft, n):
    table = _trim(campaign, aircraft, 0.0, 0.0)
    weight = campaign.aircraft[aircraft]["gross_weight_kg"] * G0_M_S2
    assert np.allclose(table.thrust_N, weight / n, rtol=1e-9)


def test_six_degree_descent_flow_enters_main_rotor_from_below(campaign):
    speeds = campaign.segment("seg3")["aircraft"]["helicopter"]
    table = _trim(campaign, "helicopter", speeds["forward_speed_mps"], speeds["climb_speed_mps"])
    main = table.set_index("rotor").loc["main"]
    assert main.mu_z < 0.0
    assert 3.0 < disk_flow_angle_deg(main) < 7.0


def test_tail_rotor_thrust_times_arm_equals_main_rotor_torque(campaign):
    """Yaw balance about the CG: T_tail (p × a)_z = s_main Q_main a_z,main + s_tail Q_tail a_z,tail."""
    config = campaign.aircraft["helicopter"]
    for segment in campaign.segments:
        speeds = campaign.segment(segment)["aircraft"]["helicopter"]
        table = _trim(campaign, "helicopter", speeds["forward_speed_mps"], speeds["climb_speed_mps"]).set_index("rotor")
        yaw = 0.0
        for rotor in config["rotors"]:
            row = table.loc[rotor["name"]]
            axis = np.asarray(rotor["thrust_axis_body"]) / np.linalg.norm(rotor["thrust_axis_body"])
            arm = np.cross(rotor["hub_position_m"], axis)[2]
            yaw += row.thrust_N * arm - row.rotation_sign * row.torque_Nm * axis[2]
        assert abs(yaw) < 1e-8 * table.loc["main", "torque_Nm"], segment
        assert table.loc["tail", "thrust_N"] * 9.93 == pytest.approx(table.loc["main", "torque_Nm"], rel=0.1)


def test_tandem_split_follows_cg(campaign):
    """The CG lies ahead of the hub mid-point, so the front rotor carries more, with zero pitch moment."""
    table = _trim(campaign, "tandem", 40.0, 0.0).set_index("rotor")
    assert table.loc["front", "thrust_N"] > table.loc["rear", "thrust_N"]
    pitch = 0.0
    for rotor in campaign.aircraft["tandem"]["rotors"]:
        axis = np.asarray(rotor["thrust_axis_body"]) / np.linalg.norm(rotor["thrust_axis_body"])
        pitch += table.loc[rotor["name"], "thrust_N"] * np.cross(rotor["hub_position_m"], axis)[1]
    assert abs(pitch) < 1e-8 * table.thrust_N.sum()


def test_glauert_inflow_limits():
    """Hover: λ_i = sqrt(C_T/2); high speed: λ_i → C_T/(2μ)."""
    assert glauert_inflow(0.008, 0.0, 0.0) == pytest.approx(np.sqrt(0.004), rel=1e-12)
    assert glauert_inflow(0.008, 0.5, 0.0) == pytest.approx(0.008 / (2 * 0.5), rel=1e-3)
    ct, mu, mu_z = 0.007, 0.2, -0.01
    lam_i = glauert_inflow(ct, mu, mu_z)
    assert lam_i == pytest.approx(ct / (2 * np.hypot(mu, mu_z + lam_i)), rel=1e-12)
