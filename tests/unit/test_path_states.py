"""Trim states covering a path (nps.mission.path_states) and the ``path`` command's artifacts."""

import math

import numpy as np
import pandas as pd
import pytest

from nps.__main__ import main as nps_main
from nps.core.atmosphere import isa
from nps.mission.path_states import StateTolerances, choose_states, state_flight, state_key
from nps.rotor.trim import TRIM_COLUMNS, FlightCondition

TOL = StateTolerances(0.01, 1.0, 0.05, 0.02)


def _coords(mu, gamma_deg=0.0, dn=0.0, ns=0.0, fraction=1.0):
    mu = np.atleast_1d(np.asarray(mu, float))
    return np.column_stack([mu, *(np.broadcast_to(v, mu.shape) for v in (gamma_deg, dn, ns, fraction))])


def test_a_steady_path_is_one_state_with_weight_zero():
    states = choose_states(_coords(np.full(50, 0.1212)), TOL)
    assert len(states.lattice) == 1 and not states.weight.any() and not states.state.any()
    np.testing.assert_allclose(states.values[0], [0.12, 0.0, 0.0, 0.0, 1.0], atol=1e-15)


def test_a_linear_deceleration_is_interpolated_between_neighbouring_states():
    """μ from 0.20 to 0.10: eleven states 0.20 … 0.10, and (1 − w) A + w B reproduces μ to 1e-12 everywhere."""
    mu = np.linspace(0.20, 0.10, 401)
    states = choose_states(_coords(mu), TOL)
    np.testing.assert_allclose(states.values[:, 0], np.linspace(0.20, 0.10, 11), atol=1e-12)
    interpolated = (1 - states.weight) * states.values[states.state, 0] + states.weight * states.values[states.neighbour, 0]
    np.testing.assert_allclose(interpolated, mu, atol=1e-12)


def test_a_jump_between_states_is_not_blended():
    """Entering a turn (lateral load 0 → 0.3) at one sample: every sample sits on its own state, weight 0."""
    ns = np.where(np.arange(40) < 20, 0.0, 0.3)
    states = choose_states(_coords(np.full(40, 0.12), ns=ns), TOL)
    assert len(states.lattice) == 2 and not states.weight.any()


def test_keys_are_deterministic_and_shared_by_equal_states():
    """Two different paths through the same lattice point give the same key; a steady state's canonical flight is
    the plain FlightCondition (zero acceleration, no negative zeros): the mission segment's trim input."""
    a = choose_states(_coords(np.linspace(0.118, 0.122, 9), gamma_deg=-6.1), TOL)
    b = choose_states(_coords(np.full(3, 0.1204), gamma_deg=-5.9), TOL)
    tip = 28.0 * 7.62
    keys = [state_key(*state_flight(s.values[0], tip, isa(0.0))) for s in (a, b)]
    assert keys[0] == keys[1] and keys[0].startswith("s") and len(keys[0]) == 13
    flight, fraction = state_flight(a.values[0], tip, isa(0.0))
    assert flight.acceleration_mps2 == (0.0, 0.0, 0.0) and all(math.copysign(1.0, c) > 0 for c in flight.acceleration_mps2)
    assert flight.forward_speed_mps == 0.12 * tip * math.cos(math.radians(-6.0)) and fraction == 1.0
    other = state_key(*state_flight(np.array([0.12, -6.0, 0.0, 0.05, 1.0]), tip, isa(0.0)))
    assert other != keys[0]


def test_path_command_writes_the_history_and_the_trimmed_states(tmp_path, repo_root):
    """The stabilised 6° approach: the history's times and bracketing keys; the steady −6° state is a mission
    segment's flight (zero acceleration); the trim stage given a state's speeds entry (state_speeds: here a
    push-over state, with its acceleration) writes that state's trim rows bit for bit."""
    from nps.app.config import load_aircraft
    from nps.mission.path_states import state_speeds
    from nps.stages import trim as trim_stage

    out = tmp_path / "approach"
    status = nps_main(["path", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"),
                       "--path", str(repo_root / "config/paths/helicopter_approach_6deg.yaml"), "--out", str(out)])
    assert status == 0
    history = pd.read_parquet(out / "path_history.parquet")
    states = pd.read_parquet(out / "path_states.parquet")
    assert np.allclose(np.diff(history.time_s), 0.5) and set(history.state) <= set(states.state)
    assert set(TRIM_COLUMNS) <= set(states.columns) and (states.groupby("state").size() == 2).all()
    final = states[states.state == history.state.iloc[-1]].reset_index(drop=True)
    assert final.effective_flight_path_deg.iloc[0] == -6.0 and final.normal_load_increment.iloc[0] == 0.0
    assert (final[["state_acc_x_mps2", "state_acc_y_mps2", "state_acc_z_mps2"]].to_numpy() == 0.0).all()
    push_over = states[states.normal_load_increment < 0].reset_index(drop=True)
    chosen = push_over[push_over.state == push_over.state.iloc[0]].reset_index(drop=True)
    flight = FlightCondition(chosen.forward_speed_mps.iloc[0], chosen.climb_speed_mps.iloc[0], isa(0.0),
                             tuple(chosen[f"state_acc_{c}_mps2"].iloc[0] for c in "xyz"))
    assert flight.acceleration_mps2[2] < 0.0
    speeds = state_speeds(flight, 1.0, ["main", "tail"])
    trim_stage.run({}, {"trim": tmp_path / "trim.parquet"}, {
        "aircraft_config": load_aircraft(repo_root / "config/aircraft/helicopter.yaml"), "speeds": speeds,
        "atmosphere": {"altitude_m": 0.0, "isa_delta_K": 0.0, "relative_humidity_pct": 70.0}, "segment": "seg0",
        "n_psi": 360, "n_r": 50})
    trim = pd.read_parquet(tmp_path / "trim.parquet")
    for column in TRIM_COLUMNS:
        assert np.array_equal(chosen[column].to_numpy(), trim[column].to_numpy()), column
