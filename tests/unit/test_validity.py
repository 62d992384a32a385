"""Validity envelope (nps.app.validity): every check on both sides of its limit, the issue-14 "worst"
inputs caught, the bundled study inside the envelope, and enforce()'s error/warning semantics."""

import copy
import json
import math

import numpy as np
import pandas as pd
import pytest

from nps.app import validity as v
from nps.core.atmosphere import isa
from nps.app.config import load_aircraft
from nps.core.frames import rot_y
from nps.noise.observers import ground_grid, hemisphere, points
from nps.rotor.trim import FlightCondition, trim_aircraft
from nps.wake.prescribed import WakeModel

ATM = isa(0.0, 0.0, 70.0)


@pytest.fixture(scope="module")
def helicopter(repo_root):
    return load_aircraft(repo_root / "config" / "aircraft" / "helicopter.yaml")


def trim(aircraft, forward_mps, climb_mps):
    return trim_aircraft(aircraft, FlightCondition(forward_mps, climb_mps, ATM))


def quantities(findings):
    return [f.quantity for f in findings]


# --- single checks, both sides of each limit -----------------------------------------------

def test_advance_ratio_limit():
    assert v.check_advance_ratio(0.49, "r") is None
    found = v.check_advance_ratio(0.51, "r")
    assert found.value == 0.51 and found.limit == "<= 0.5" and "Johnson" in found.source


def test_tip_mach_hover_and_advancing_limits():
    # omega R / c = 0.94 inside, 0.96 outside the default mach_cap 0.95
    assert v.check_tip_mach_hover(0.94 * 340.0 / 7.0, 7.0, 340.0, "r") is None
    assert v.check_tip_mach_hover(0.96 * 340.0 / 7.0, 7.0, 340.0, "r").value == pytest.approx(0.96)
    assert v.check_tip_mach_advancing(0.7, 0.35, "r") is None  # 0.945
    assert v.check_tip_mach_advancing(0.7, 0.36, "r").value == pytest.approx(0.952)
    # the airfoil's mach_cap is the limit: 0.7 (1 + 0.2) = 0.84
    assert v.check_tip_mach_advancing(0.7, 0.2, "r", mach_cap=0.85) is None
    assert v.check_tip_mach_advancing(0.7, 0.2, "r", mach_cap=0.83).limit == "<= 0.83"


def test_blade_loading_and_mean_lift_limits():
    sigma = 0.1
    assert v.check_blade_loading(0.0139, sigma, "r") is None
    assert v.check_blade_loading(0.0141, sigma, "r").value == pytest.approx(0.141)
    # 6 C_T / sigma against c_l,max
    assert v.check_mean_lift_coefficient(0.01, sigma, 0.61, "r") is None
    found = v.check_mean_lift_coefficient(0.01, sigma, 0.59, "r")
    assert found.value == pytest.approx(0.6) and found.limit == "<= 0.59"


def test_vortex_ring_region():
    ct = 0.005
    v_h = math.sqrt(ct / 2.0)  # hover induced velocity / tip speed
    assert v.check_vortex_ring(0.5 * v_h, -1.0 * v_h, ct, "r").value == pytest.approx(-1.0)
    assert v.check_vortex_ring(0.5 * v_h, -1.99 * v_h, ct, "r") is not None
    assert v.check_vortex_ring(0.5 * v_h, -2.01 * v_h, ct, "r") is None  # windmill-brake side
    assert v.check_vortex_ring(0.5 * v_h, -0.01 * v_h, ct, "r") is not None
    assert v.check_vortex_ring(0.5 * v_h, 0.0, ct, "r") is None  # level / hover
    assert v.check_vortex_ring(0.99 * v_h, -1.0 * v_h, ct, "r") is not None
    assert v.check_vortex_ring(1.01 * v_h, -1.0 * v_h, ct, "r") is None  # edgewise speed clears the wake


def test_lock_number_range():
    assert v.check_lock_number(8.0, "r") is None
    assert v.check_lock_number(1.0, "r") is None and v.check_lock_number(25.0, "r") is None
    assert v.check_lock_number(0.9, "r").limit == "within [1, 25]"
    assert v.check_lock_number(25.1, "r") is not None


def test_flap_angle_and_controls():
    limit = math.radians(15.0)
    assert v.check_flap_angle(limit - 0.05, 0.03, 0.04, "r") is None  # |b0| + |b1| = limit
    assert v.check_flap_angle(limit - 0.05, 0.03, 0.0401, "r") is not None
    assert v.check_flap_angle(-0.1, 0.0, 0.17, "r") is not None  # negative coning counts by magnitude
    assert v.check_controls(0.69, -0.2, 0.1, "r") is None
    found = v.check_controls(0.1, -0.7, 0.1, "r")
    assert "theta1c_rad" in found.quantity and found.value == pytest.approx(0.7)


def test_wake_length_minimum():
    # oldest vortex one diameter downstream: phi R mu = 2 R -> revolutions = 1 / (pi mu)
    assert v.minimum_wake_revolutions(0.2, 0.0) == pytest.approx(1.0 / (math.pi * 0.2))
    assert v.minimum_wake_revolutions(0.6, 0.8) == 1.0  # at least one revolution
    assert v.minimum_wake_revolutions(0.0, 0.0) == math.inf
    need = v.minimum_wake_revolutions(0.12, 0.01)
    assert v.check_wake_length(need * 1.001, 0.12, 0.01, "r") is None
    assert v.check_wake_length(need * 0.999, 0.12, 0.01, "r").value == pytest.approx(need * 0.999)


def _path(r_gh=np.eye(3), velocity=(0.0, 0.0, 0.0)):
    return v.BladePath("r", np.zeros(3), np.asarray(velocity, float), np.asarray(r_gh, float), 5.0, 1.0, 0.4)


def test_blade_path_distances_analytic():
    # shaft tilted 30 deg: an observer along the shaft at 4 m sees the root circle at hypot(1, 4)
    tilt = rot_y(math.radians(30.0))
    axis = tilt[:, 2]
    path = _path(tilt)
    obs = np.array([4.0 * axis, 3.0 * tilt[:, 0] + 2.0 * axis, 8.0 * tilt[:, 1]])
    to_blade, to_hub = path.distances(obs, np.zeros((3, 3)), np.zeros(1))
    np.testing.assert_allclose(to_blade, [math.hypot(1.0, 4.0), 2.0, 3.0], rtol=1e-12)
    np.testing.assert_allclose(to_hub, [4.0, math.hypot(3.0, 2.0), 8.0], rtol=1e-12)


def test_observer_checks_both_sides():
    path = _path()
    ids = [7, 8]
    assert v.check_observer_blade_distance(ids, np.array([2.01, 9.0]), path) is None  # 5.025 chords
    found = v.check_observer_blade_distance(ids, np.array([9.0, 1.99]), path)
    assert found.value == pytest.approx(4.975) and "observer 8" in found.quantity
    assert v.check_observer_hub_distance(ids, np.array([5.01, 9.0]), path) is None
    assert v.check_observer_hub_distance(ids, np.array([4.99, 9.0]), path).value == pytest.approx(0.998)


def test_fixed_observer_passed_by_the_rotor_is_caught():
    # the hub flies through a fixed observer 10 m ahead within the signal window (80 m/s, 0.25 s)
    path = _path(velocity=(80.0, 0.0, 0.0))
    obs = np.array([[10.0, 0.0, 0.0]])
    at_start = path.distances(obs, np.zeros((1, 3)), np.zeros(1))[1]
    over_window = path.distances(obs, np.zeros((1, 3)), np.linspace(0.0, 0.25, 9))[1]
    assert at_start[0] == pytest.approx(10.0) and over_window[0] == pytest.approx(0.0, abs=1e-12)


def test_pegg_peak_frequency_range():
    assert v.check_pegg_peak_frequency(50.41e3, 213.4, "r") is None  # 336 Hz (docs/reference/broadband_metrics.md)
    low = v.check_pegg_peak_frequency(1e9, 100.0, "r")  # eq. 3.1 gives f_p < 0
    assert math.isnan(low.value) and "not positive" in low.limit
    assert v.check_pegg_peak_frequency(1.0, 8000.0, "r") is None  # 20.5 kHz: in the 20 kHz band (edge 22.4 kHz)
    high = v.check_pegg_peak_frequency(1.0, 9000.0, "r")  # 23.0 kHz: above the last analysed band
    assert high.value == pytest.approx(2.448 * 9000.0 + 942.0)


# --- enforce -------------------------------------------------------------------------------

def test_enforce_refuses_with_one_line_and_records_when_allowed():
    findings = [None, v.check_advance_ratio(0.7, "main"), v.check_lock_number(1000.0, "main")]
    with pytest.raises(v.ValidityError) as info:
        v.enforce(findings, False, "results/helicopter/seg1/trim.parquet")
    text = str(info.value)
    assert "\n" not in text
    for part in ("results/helicopter/seg1/trim.parquet", "advance ratio mu", "0.7", "<= 0.5", "source:", "Lock number",
                 "allow_outside_validity"):
        assert part in text
    warnings = v.enforce(findings, True, "x")
    assert [w["quantity"] for w in warnings] == ["rotor 'main': advance ratio mu", "rotor 'main': Lock number"]
    json.dumps(warnings)  # storable in the artifact metadata
    assert v.enforce([None, None], False, "x") == []


def test_warnings_round_trip_through_the_artifact_metadata(tmp_path):
    from nps.app.io import read_metadata, write_table

    warnings = v.enforce([v.check_lock_number(1000.0, "main")], True, "x")
    write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "t.parquet", stage="trim", metadata={"validity_warnings": warnings})
    stored = read_metadata(tmp_path / "t.parquet")["validity_warnings"]
    assert stored == warnings and stored[0]["value"] == 1000.0 and "Lock number = 1000" in stored[0]["message"]


def test_recorded_adds_a_metadata_key_only_for_allowed_findings(tmp_path):
    """A stage inside the envelope gets {} (its artifact unchanged), outside it refuses by default, and
    with the switch gets the warnings; the summary lists each distinct message once."""
    from nps.app.io import write_table
    from nps.stages.summary import validity_warnings

    assert v.recorded([None], {}, "x") == {}
    with pytest.raises(v.ValidityError):
        v.recorded([v.check_lock_number(1000.0, "main")], {}, "x")
    meta = v.recorded([v.check_lock_number(1000.0, "main")], {"allow_outside_validity": True}, "x")
    assert [w["quantity"] for w in meta["validity_warnings"]] == ["rotor 'main': Lock number"]
    assert v.report(meta).startswith("\nwarning: rotor 'main': Lock number = 1000")
    for name in ("a", "b"):
        write_table(pd.DataFrame({"a": [1.0]}), tmp_path / f"{name}.parquet", stage="trim", metadata=meta)
    write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "c.parquet", stage="trim")
    paths = [tmp_path / f"{name}.parquet" for name in "abc"]
    assert validity_warnings(paths) == meta["validity_warnings"][0]["message"]
    assert validity_warnings(paths[2:]) == ""


# --- the issue-14 "worst" inputs ---------------------------------------------------------

def test_worst_200_mps_helicopter(helicopter):
    found = quantities(v.trim_findings(helicopter, trim(helicopter, 200.0, 0.0)))
    assert "rotor 'main': advance ratio mu" in found and "rotor 'tail': blade loading C_T/sigma" in found


def test_worst_climb_50_mps(helicopter):
    found = quantities(v.trim_findings(helicopter, trim(helicopter, 40.0, 50.0)))
    assert "rotor 'tail': blade loading C_T/sigma" in found


def test_worst_vortex_ring_descent(helicopter):
    found = v.trim_findings(helicopter, trim(helicopter, 2.0, -10.0))
    vrs = [f for f in found if "V_z/v_h" in f.quantity and "'main'" in f.quantity]
    assert vrs and -2.0 < vrs[0].value < 0.0


def test_worst_advancing_tip_mach_1_12(helicopter):
    fast = copy.deepcopy(helicopter)
    fast["rotors"][0]["omega_rad_s"] = (1.12 * ATM.speed_of_sound_mps - 82.8) / 7.62
    found = [f for f in v.trim_findings(fast, trim(fast, 82.8, 0.0)) if "advancing tip Mach" in f.quantity]
    assert found and found[0].value == pytest.approx(1.12, abs=0.03)


def test_worst_lock_number_1000(helicopter):
    heavy = copy.deepcopy(helicopter)
    heavy["rotors"][0]["lock_number"] = 1000
    assert quantities(v.aircraft_findings(heavy, ATM.speed_of_sound_mps)) == ["rotor 'main': Lock number"]


def test_worst_unit_mistakes_caught_before_the_trim(helicopter):
    feet = copy.deepcopy(helicopter)
    feet["rotors"][0]["radius_m"] = 25.0  # 25 ft typed as metres
    rpm = copy.deepcopy(helicopter)
    rpm["rotors"][0]["omega_rad_s"] = 267.4  # rpm typed as rad/s
    for aircraft in (feet, rpm):
        assert "rotor 'main': hover tip Mach number" in quantities(v.aircraft_findings(aircraft, ATM.speed_of_sound_mps))


def test_implausible_loading_inputs_are_named(helicopter):
    # issue 14: cl_max 0.05 and gross weight x10 ended in "did not trim"; the envelope names the quantity
    weak = copy.deepcopy(helicopter)
    weak["rotors"][0]["airfoil"]["cl_max"] = 0.05
    assert quantities(v.trim_findings(weak, trim(weak, 40.5, 0.0))) == ["rotor 'main': mean lift coefficient 6 C_T/sigma"]
    heavy = copy.deepcopy(helicopter)
    heavy["gross_weight_kg"] *= 10.0
    found = quantities(v.trim_findings(heavy, trim(heavy, 40.5, 0.0)))
    assert "rotor 'main': blade loading C_T/sigma" in found


def test_worst_wake_revolutions_0_01(helicopter):
    row = trim(helicopter, 25.7, -2.69).iloc[0]
    assert v.wake_findings(WakeModel(revolutions=4.0), row) == []
    assert quantities(v.wake_findings(WakeModel(revolutions=0.01), row)) == ["rotor 'main': wake_revolutions"]


@pytest.fixture(scope="module")
def level_trim(helicopter):
    return trim(helicopter, 40.5, 0.0)


def _hub(level_trim, rotor="main"):
    row = level_trim.set_index("rotor").loc[rotor]
    return np.array([row.hub_x_m, row.hub_y_m, row.hub_z_m]), row


def test_worst_observer_at_the_hub(helicopter, level_trim):
    hub, _ = _hub(level_trim)
    found = quantities(v.observer_findings(points([hub]), helicopter, level_trim))
    assert "observer 0: distance to rotor 'main' hub / radius" in found
    assert "observer 0: distance to rotor 'main' blade path / chord" in found


def test_worst_observer_on_the_tip_path_circle(helicopter, level_trim):
    hub, row = _hub(level_trim)
    r_gh = np.array([[row[f"r_gh_{i}{j}"] for j in range(3)] for i in range(3)])
    tip = hub + 7.62 * r_gh[:, 1]
    found = v.observer_findings(points([tip]), helicopter, level_trim)
    blade = [f for f in found if "'main' blade path" in f.quantity]
    assert blade and blade[0].value == pytest.approx(0.0, abs=1e-9)


def test_worst_hemisphere_inside_the_disk(helicopter, level_trim):
    hub, _ = _hub(level_trim)
    found = v.observer_findings(hemisphere(hub, 0.5 * 7.62, 10, 36), helicopter, level_trim)
    hub_finding = [f for f in found if "'main' hub / radius" in f.quantity]
    assert hub_finding and hub_finding[0].value == pytest.approx(0.5)


def test_worst_ground_grid_just_below_the_cg(helicopter, level_trim):
    grid = ground_grid(np.zeros(3), 1e-4, (-300.0, 300.0), (-300.0, 300.0), 13, 13)
    found = quantities(v.observer_findings(grid, helicopter, level_trim))
    assert any("'main' hub / radius" in q for q in found)


def test_bundled_hemisphere_is_inside(helicopter, level_trim):
    hub, _ = _hub(level_trim)
    table = hemisphere(hub, 10.0 * 7.62, 10, 36, level_trim[["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy()[0])
    assert v.observer_findings(table, helicopter, level_trim, 2.0 * math.pi / 28.0) == []
    assert v.observer_findings(table.iloc[:0], helicopter, level_trim) == []


def test_bundled_helicopter_segments_inside(helicopter):
    # thesis chapter 7 segments 1-6 (config/missions/demo.yaml): nothing is outside the envelope
    for forward, climb in ((48.5, 3.96), (40.5, 0.0), (25.7, -2.69), (25.7, -0.51), (82.8, 0.0), (77.2, -6.6)):
        table = trim(helicopter, forward, climb)
        assert v.aircraft_findings(helicopter, ATM.speed_of_sound_mps) == []
        assert v.trim_findings(helicopter, table) == []
        assert v.broadband_findings(helicopter, table) == []
        assert all(v.wake_findings(WakeModel(revolutions=4.0), row) == [] for _, row in table.iterrows())


def test_loads_findings_from_the_summary_table():
    def summary(**values):
        base = dict(theta0_rad=0.1, theta1c_rad=0.02, theta1s_rad=-0.05, beta0_rad=0.03, beta1c_rad=0.0, beta1s_rad=0.0)
        base.update(values)
        return pd.DataFrame({"quantity": list(base), "value": list(base.values())})

    assert v.loads_findings("main", summary()) == []
    # lock_number 1000 (issue 14): beta0 = 4.45 rad, theta1c stuck at its bound
    found = quantities(v.loads_findings("main", summary(beta0_rad=4.45, theta1c_rad=0.7)))
    assert found == ["rotor 'main': largest flap angle (rad)", "rotor 'main': trimmed control |theta1c_rad|"]
