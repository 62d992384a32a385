"""Quasi-static aircraft trim (nps.rotor.trim with an acceleration): closed forms of the force balance.

Σ T_i R_GB a_i − W ẑ − D V̂ = m a (nps.rotor.trim). Tolerances: the trim converges to residuals below 1e-12 W,
so closed forms hold to ~1e-11 relative; the tests use 1e-9.
"""

import math

import numpy as np
import pytest

from nps.app.config import load_aircraft
from nps.core.atmosphere import isa
from nps.mission.path_states import effective_flight_path, state_flight
from nps.rotor.trim import G0_M_S2, FlightCondition, disk_flow_angle_deg, trim_aircraft

RHO = isa(0.0).density_kg_m3


@pytest.fixture(scope="module")
def helicopter(repo_root):
    return load_aircraft(repo_root / "config/aircraft/helicopter.yaml")


@pytest.fixture(scope="module")
def hexacopter(repo_root):
    return load_aircraft(repo_root / "config/aircraft/hexacopter.yaml")


def _thrust_axis_g(row) -> np.ndarray:
    return np.array([row[f"r_gh_{i}2"] for i in range(3)])


def test_zero_acceleration_is_the_steady_trim_bit_for_bit(helicopter):
    """The default (steady) flight and an explicit zero acceleration give identical tables (x − 0.0 ≡ x)."""
    steady = trim_aircraft(helicopter, FlightCondition(25.7, -2.69, isa(0.0)))
    explicit = trim_aircraft(helicopter, FlightCondition(25.7, -2.69, isa(0.0), (0.0, 0.0, 0.0)))
    assert all(np.array_equal(steady[c].to_numpy(), explicit[c].to_numpy()) for c in steady.columns)


def test_coordinated_turn_is_level_flight_with_the_load_factors_thrust(hexacopter):
    """(a) Hexacopter without drag (rotor axes along z_B), V = 30 m/s on R = 300 m to starboard, a_G = (0, −V²/R, 0):
    total thrust n W with n = sqrt(1 + (V²/(gR))²), roll = bank = atan(V²/(gR)), pitch 0; every rotor's thrust,
    C_T, inflow and power equal the level trim of the same aircraft weighing n m (relative 1e-9)."""
    aircraft = {**hexacopter, "fuselage_drag_area_m2": 0.0}
    speed, radius = 30.0, 300.0
    tan_bank = speed**2 / (G0_M_S2 * radius)
    load = math.hypot(1.0, tan_bank)
    turn = trim_aircraft(aircraft, FlightCondition(speed, 0.0, isa(0.0), (0.0, -speed**2 / radius, 0.0)))
    weight = aircraft["gross_weight_kg"] * G0_M_S2
    assert turn.thrust_N.sum() == pytest.approx(load * weight, rel=1e-9)
    assert turn.roll_rad.iloc[0] == pytest.approx(math.atan(tan_bank), rel=1e-9)
    assert abs(turn.pitch_rad.iloc[0]) < 1e-12
    level = trim_aircraft({**aircraft, "gross_weight_kg": aircraft["gross_weight_kg"] * load}, FlightCondition(speed, 0.0, isa(0.0)))
    for column in ("thrust_N", "ct", "lambda_i", "power_W", "mu_x"):
        np.testing.assert_allclose(turn[column], level[column], rtol=1e-9, err_msg=column)
    for column in ("mu_y", "mu_z"):
        np.testing.assert_allclose(turn[column], level[column], atol=1e-12, err_msg=column)


@pytest.mark.parametrize("accel", [-2.0, -1.0, 0.0, 1.0])
def test_longitudinal_acceleration_tilts_the_disk_by_the_force_balance(helicopter, accel):
    """(b) Single main rotor (the helicopter's, no tail rotor) in level flight at V = 30 m/s with a_x: the rotor
    force balances weight, drag and inertia, T (sin ε, 0, cos ε) = (D + m a_x, 0, W), so the forward tilt of the
    thrust axis (tip-path plane) from the vertical is ε = atan((D + m a_x)/W), D = ½ρV²f. A deceleration
    (a_x < 0) turns it aft (ε < 0 once m|a_x| > D); the free stream then enters the disk from below by −ε."""
    single = {**helicopter, "rotors": [helicopter["rotors"][0]]}
    speed, mass = 30.0, helicopter["gross_weight_kg"]
    trim = trim_aircraft(single, FlightCondition(speed, 0.0, isa(0.0), (accel, 0.0, 0.0)))
    drag = 0.5 * RHO * speed**2 * helicopter["fuselage_drag_area_m2"]
    expected = math.atan((drag + mass * accel) / (mass * G0_M_S2))
    axis = _thrust_axis_g(trim.iloc[0])
    assert math.atan2(axis[0], axis[2]) == pytest.approx(expected, abs=1e-10)
    assert disk_flow_angle_deg(trim.iloc[0]) == pytest.approx(-math.degrees(expected), abs=1e-8)
    assert trim.thrust_N.iloc[0] == pytest.approx(math.hypot(drag + mass * accel, mass * G0_M_S2), rel=1e-9)


# measured differences of the decelerating level flight against the steady descent at γ_e (helicopter, 30 m/s):
# the normal load, 1 against cos γ_e, gives the thrust 1/cos γ_e − 1 more (0.52 % at a_x = −1 m/s²)
@pytest.mark.parametrize("accel, ct_rel, mu_z_rel, angle_deg", [(-0.5, 0.0014, 0.0016, 0.003), (-1.0, 0.0055, 0.006, 0.03),
                                                                (-1.5, 0.0125, 0.013, 0.1)])
def test_deceleration_equals_descent_at_the_effective_flight_path_angle(helicopter, accel, ct_rel, mu_z_rel, angle_deg):
    """(c) Level flight decelerating at a_x and the steady descent at γ_e, sin γ_e = a_x/g (eq. (1) of
    nps.mission.path_states), same speed: equal disk flow angle and μ_z up to the thrust-magnitude effect of the
    normal load (1 against cos γ_e; measured: C_T +0.13/0.52/1.16 %, μ_z 0.13/0.52/1.2 %, disk angle 0.002/0.024/0.088°);
    with the normal load matched (the canonical state's pull-up (1 − cos γ_e) g along n̂) the rotor state is equal to 1e-9."""
    speed = 30.0
    decelerating = trim_aircraft(helicopter, FlightCondition(speed, 0.0, isa(0.0), (accel, 0.0, 0.0))).set_index("rotor")
    gamma_e = float(effective_flight_path(np.array([accel / G0_M_S2]))[0])
    descent = trim_aircraft(helicopter, FlightCondition(speed * math.cos(gamma_e), speed * math.sin(gamma_e), isa(0.0))).set_index("rotor")
    main_d, main_s = decelerating.loc["main"], descent.loc["main"]
    assert main_d.ct / main_s.ct - 1.0 == pytest.approx(1.0 / math.cos(gamma_e) - 1.0, rel=0.05)
    assert abs(main_d.ct / main_s.ct - 1.0) < ct_rel
    assert abs(main_d.mu_z / main_s.mu_z - 1.0) < mu_z_rel
    assert abs(disk_flow_angle_deg(main_d) - disk_flow_angle_deg(main_s)) < angle_deg
    matched = np.array([speed / (helicopter["rotors"][0]["omega_rad_s"] * helicopter["rotors"][0]["radius_m"]),
                        math.degrees(gamma_e), 1.0 - math.cos(gamma_e), 0.0, 1.0])
    flight, _ = state_flight(matched, helicopter["rotors"][0]["omega_rad_s"] * helicopter["rotors"][0]["radius_m"], isa(0.0))
    equivalent = trim_aircraft(helicopter, flight).set_index("rotor")
    for column in ("thrust_N", "ct", "mu_x", "mu_z", "lambda_i", "power_W"):
        np.testing.assert_allclose(equivalent[column], decelerating[column], rtol=1e-9, atol=1e-13, err_msg=column)


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_helicopter_turn_rolls_by_the_bank_about_its_level_roll(helicopter, side):
    """The helicopter (tail rotor, drag) in a level turn at 30 m/s on R = 300 m: the roll is the level trim's
    (−1.94°, the tail rotor's side force) plus the bank atan(V²/(gR)) = 17.01° toward the turn (measured within
    0.02°), and the main-rotor thrust is the level one times n (measured within 3e-5)."""
    speed, radius = 30.0, 300.0
    bank = math.atan(speed**2 / (G0_M_S2 * radius))
    level = trim_aircraft(helicopter, FlightCondition(speed, 0.0, isa(0.0))).set_index("rotor")
    turn = trim_aircraft(helicopter, FlightCondition(speed, 0.0, isa(0.0), (0.0, side * speed**2 / radius, 0.0))).set_index("rotor")
    assert math.degrees(turn.roll_rad["main"] - level.roll_rad["main"] + side * bank) == pytest.approx(0.0, abs=0.05)
    assert turn.thrust_N["main"] / level.thrust_N["main"] == pytest.approx(1.0 / math.cos(bank), rel=1e-4)
