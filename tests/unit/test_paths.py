"""Flight paths (nps.mission.paths): kinematics against closed forms and finite differences, continuity at the
joins, coordinated-turn bank and load factor, the limits' messages, and the bundled paths."""

import dataclasses
import math

import numpy as np
import pytest

from nps.app.config import load_path
from nps.mission.paths import (LegSpec, PathError, PathLimits, PathSpec, check_limits, flight_path_history, leg_kinematics,
                               solve_path)
from nps.rotor.trim import G0_M_S2

LIMITS = PathLimits(math.radians(45.0), 0.5, 1.5, 2.0, math.radians(15.0), math.radians(15.0))


def _spec(*legs, speed=30.0, limits=LIMITS, height=300.0):
    return PathSpec("p", "helicopter", (0.0, 0.0, height), 0.0, speed, 0.0, 1.0, 0.1, limits, tuple(legs))


MIXED = _spec(LegSpec("straight", distance_m=400.0),
              LegSpec("straight", distance_m=1500.0, flight_path_rad=math.radians(-6.0), end_speed_mps=24.0),
              LegSpec("turn", heading_change_rad=math.radians(90.0), radius_m=400.0, height_change_m=-40.0),
              LegSpec("straight", duration_s=20.0, acceleration_mps2=-0.5, end_rotor_speed_fraction=0.95, flight_path_rad=0.0),
              LegSpec("turn", heading_change_rad=math.radians(-45.0), bank_rad=math.radians(10.0)))


def test_joins_are_continuous_in_position_velocity_heading_and_rotor_speed():
    legs = solve_path(MIXED)
    for before, after in zip(legs[:-1], legs[1:]):
        end, start = leg_kinematics(before, [before.duration_s]), leg_kinematics(after, [0.0])
        assert after.t0_s == before.t0_s + before.duration_s
        for key, tol in (("position_m", 1e-9), ("velocity_mps", 1e-12), ("heading_rad", 1e-15), ("rotor_speed_fraction", 0.0)):
            assert np.max(np.abs(end[key] - start[key])) <= tol, (after.index, key)


ROLLING = dataclasses.replace(MIXED, roll_rate_rad_s=math.radians(5.0))  # turns rolled in and out at 5°/s


@pytest.mark.parametrize("spec", [MIXED, ROLLING], ids=["instant_roll", "rolling"])
@pytest.mark.parametrize("index", range(5))
def test_velocity_and_acceleration_are_the_derivatives_of_the_position(spec, index):
    """Central differences (h = 1e-4 s) of position and velocity against the closed forms (circle arcs, and the
    Fresnel-integral clothoids of a rolled-in turn), away from the kinks (the end of a flight-path change): 1e-6 m/s
    and 1e-5 m/s²."""
    leg = solve_path(spec)[index]
    tau = np.linspace(0.0, leg.duration_s, 301)[1:-1]
    tau = tau[np.abs(tau - leg.gamma_time_s) > 1e-3]
    h = 1e-4
    plus, minus, mid = leg_kinematics(leg, tau + h), leg_kinematics(leg, tau - h), leg_kinematics(leg, tau)
    np.testing.assert_allclose((plus["position_m"] - minus["position_m"]) / (2 * h), mid["velocity_mps"], atol=1e-6)
    np.testing.assert_allclose((plus["velocity_mps"] - minus["velocity_mps"]) / (2 * h), mid["acceleration_mps2"], atol=1e-5)


def test_turn_ends_on_its_heading_and_circle():
    """A level 90° port turn on R = 400 m from (0, 0) heading +x ends at (R, R) heading +y after π R / (2V)."""
    legs = solve_path(_spec(LegSpec("turn", heading_change_rad=math.pi / 2, radius_m=400.0)))
    end = leg_kinematics(legs[0], [legs[0].duration_s])
    assert legs[0].duration_s == pytest.approx(math.pi * 400.0 / 2 / 30.0, rel=1e-12)
    np.testing.assert_allclose(end["position_m"][0], [400.0, 400.0, 300.0], atol=1e-9)
    assert end["heading_rad"][0] == pytest.approx(math.pi / 2, abs=1e-12)


def test_rolled_in_turn_banks_continuously_and_keeps_its_heading_change():
    """A level 90° port turn on R = 400 m at 30 m/s rolled in and out at p = 5°/s: the curvature ramps over
    L_r = V φ₀ / p at each end (φ₀ = atan(V²/(gR))), so the bank goes from 0 to −φ₀ in φ₀/p seconds (never faster than
    p tan φ₀/φ₀, the slope of atan at 0), holds −φ₀ and returns to 0; the turn ends on heading +y, its end point
    the quadrature of its velocity within 1e-6 m; joins continuous in bank."""
    rate = math.radians(5.0)
    spec = dataclasses.replace(_spec(LegSpec("straight", distance_m=100.0),
                                     LegSpec("turn", heading_change_rad=math.pi / 2, radius_m=400.0),
                                     LegSpec("straight", distance_m=100.0)), roll_rate_rad_s=rate)
    legs, history = flight_path_history(spec, 0.01)
    turn = legs[1]
    phi0 = math.atan(30.0**2 / (G0_M_S2 * 400.0))
    assert turn.roll_length_m == pytest.approx(30.0 * phi0 / rate, rel=1e-14)
    assert turn.duration_s == pytest.approx((400.0 * math.pi / 2 + turn.roll_length_m) / 30.0, rel=1e-12)
    tau = np.linspace(0.0, turn.duration_s, 400001)
    velocity = leg_kinematics(turn, tau)["velocity_mps"]
    quadrature = np.asarray(turn.position0_m) + np.sum(0.5 * (velocity[1:] + velocity[:-1]) * np.diff(tau)[:, None], axis=0)
    end = leg_kinematics(turn, [turn.duration_s])
    np.testing.assert_allclose(end["position_m"][0], quadrature, atol=1e-6)
    assert end["heading_rad"][0] == pytest.approx(math.pi / 2, abs=1e-12)
    bank = history.bank_rad
    assert np.max(np.abs(np.diff(bank))) <= rate * 0.01 * math.tan(phi0) / phi0 * (1 + 1e-9)
    in_turn = (history.time_s > turn.t0_s + phi0 / rate + 0.01) & (history.time_s < turn.t0_s + turn.duration_s - phi0 / rate - 0.01)
    np.testing.assert_allclose(bank[in_turn], -phi0, atol=1e-9)
    assert abs(bank[history.leg == 0]).max() < 1e-12 and abs(bank[history.leg == 2]).max() < 1e-12


def test_turn_too_short_to_roll_in_and_out_is_refused():
    spec = dataclasses.replace(_spec(LegSpec("turn", heading_change_rad=math.radians(5.0), radius_m=400.0)),
                               roll_rate_rad_s=math.radians(5.0))
    with pytest.raises(PathError) as error:
        solve_path(spec)
    assert error.value.field == "legs[0].turn.heading_change_deg" and "expected a larger heading change" in error.value.expected


def test_coordinated_turn_bank_and_load_factor():
    """Level turn at V = 30 m/s on R = 200 m: tan φ = V²/(gR), n = 1/cos φ; a starboard turn banks φ > 0."""
    for sign in (1.0, -1.0):
        legs, history = flight_path_history(_spec(LegSpec("turn", heading_change_rad=sign * math.pi, radius_m=200.0)), 1.0)
        bank = math.atan(30.0**2 / (G0_M_S2 * 200.0))
        np.testing.assert_allclose(history.bank_rad, -sign * bank, rtol=1e-12)
        np.testing.assert_allclose(history.load_factor, 1.0 / math.cos(bank), rtol=1e-12)


def test_constant_angle_descent_and_push_over():
    """Entering level, a −6° leg first pushes over at 0.1 g (γ̇ = −g 0.1/V, n = 1 − 0.1 at the start, over
    6° V/(0.1 g)), then descends at −6° with n = cos 6°; the leg's height change is the closed form of both."""
    legs, history = flight_path_history(_spec(LegSpec("straight", distance_m=1000.0, flight_path_rad=math.radians(-6.0))), 0.05)
    leg = legs[0]
    rate = G0_M_S2 * 0.1 / 30.0
    assert leg.gamma_time_s == pytest.approx(math.radians(6.0) / rate, rel=1e-12)
    ramp = history.time_s < leg.gamma_time_s
    np.testing.assert_allclose(history.load_factor[ramp], np.cos(history.flight_path_rad[ramp]) - 0.1, rtol=1e-12)
    np.testing.assert_allclose(history.load_factor[~ramp], math.cos(math.radians(6.0)), rtol=1e-12)
    ramp_length = 30.0 * leg.gamma_time_s
    drop = (1.0 - math.cos(math.radians(6.0))) / math.radians(6.0) * ramp_length + (1000.0 - ramp_length) * math.sin(math.radians(6.0))
    end = leg_kinematics(leg, [leg.duration_s])
    assert end["position_m"][0, 2] == pytest.approx(300.0 - drop, abs=1e-9)


def test_height_change_solves_the_flight_path_angle():
    legs = solve_path(_spec(LegSpec("straight", distance_m=1200.0, height_change_m=-100.0, end_speed_mps=20.0)))
    end = leg_kinematics(legs[0], [legs[0].duration_s])
    assert end["position_m"][0, 2] == pytest.approx(200.0, abs=1e-9)
    assert end["speed_mps"][0] == pytest.approx(20.0, abs=1e-12)
    assert legs[0].accel_mps2 == pytest.approx((20.0**2 - 30.0**2) / (2 * 1200.0), rel=1e-12)


@pytest.mark.parametrize("leg, field, words", [
    (LegSpec("turn", heading_change_rad=1.0, radius_m=50.0), "legs[0].turn.radius_m", "exceeds limits.max_bank_deg"),
    (LegSpec("turn", heading_change_rad=1.0, bank_rad=math.radians(44.0)), "legs[0].turn.bank_deg", "load factor"),
    (LegSpec("straight", duration_s=5.0, end_speed_mps=10.0), "legs[0].end_speed_mps", "longitudinal acceleration"),
    (LegSpec("straight", distance_m=2000.0, flight_path_rad=math.radians(-20.0)), "legs[0].flight_path_deg", "flight-path angle"),
    (LegSpec("straight", distance_m=5000.0, flight_path_rad=math.radians(-6.0)), "legs[0].flight_path_deg", "below the ground"),
    (LegSpec("straight", distance_m=20.0, flight_path_rad=math.radians(-6.0)), "legs[0]", "flight-path change"),
    (LegSpec("straight", distance_m=1000.0, acceleration_mps2=-1.0), "legs[0].acceleration_mps2", "speed reaches zero"),
])
def test_limits_name_the_leg_field(leg, field, words):
    limits = PathLimits(math.radians(45.0), 0.5, 1.3, 2.0, math.radians(15.0), math.radians(15.0))
    with pytest.raises(PathError) as error:
        check_limits(_spec(leg, limits=limits), solve_path(_spec(leg, limits=limits)))
    assert error.value.field == field and words in error.value.expected and "\n" not in str(error.value)


@pytest.mark.parametrize("name", ["helicopter_approach_6deg", "helicopter_approach_9deg", "helicopter_decelerating_approach",
                                  "helicopter_turning_approach", "hexacopter_transition"])
def test_bundled_paths_load_within_their_limits(repo_root, name):
    path = load_path(repo_root / "config/paths" / f"{name}.yaml", 0.5)
    assert path["name"] == name and path["limits"]["max_bank_deg"] == 45.0
