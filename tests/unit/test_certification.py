"""Flight profiles and certification procedures (nps.mission.trajectory), EPNL and limits (nps.mission.certification)."""

import math

import numpy as np
import pytest

from nps.mission.certification import certify, microphone_histories, noise_limit_epndb
from nps.mission.propagation import Ground
from nps.mission.trajectory import (
    FlightPathError,
    certification_procedure,
    mission_path,
    overflight_speed_mps,
    reference_parameters,
)
from tests.unit.test_footprint import omnidirectional

BANDS = np.arange(-20, 11)
MISSION = {
    "name": "m",
    "segments": [
        {"id": "seg1", "aircraft": {"heli": {"forward_speed_mps": 40.0, "climb_speed_mps": 4.0}}},
        {"id": "seg2", "aircraft": {"heli": {"forward_speed_mps": 50.0, "climb_speed_mps": 0.0}}},
        {"id": "seg5", "aircraft": {"heli": {"forward_speed_mps": 80.0, "climb_speed_mps": 0.0}}},
    ],
    "profile": [
        {"segment": "seg1", "distance_m": 1000.0, "start_altitude_m": 20.0},
        {"segment": "seg2", "duration_s": 30.0, "start_altitude_m": 120.0},
    ],
}


def test_mission_profile_path_and_errors():
    path = mission_path(MISSION, "heli")
    assert path.knot_time_s.tolist() == [0.0, 25.0, 55.0]
    assert path.knot_position_m[:, 2].tolist() == [20.0, 120.0, 120.0]
    assert path.knot_position_m[-1, 0] == 1000.0 + 1500.0
    bad = dict(MISSION, profile=[dict(MISSION["profile"][0]), {"segment": "seg2", "duration_s": 30.0, "start_altitude_m": 150.0}])
    with pytest.raises(FlightPathError, match=r"profile\[1\].start_altitude_m.*120.00"):
        mission_path(bad, "heli")
    with pytest.raises(FlightPathError, match=r"profile\[0\]: give exactly one"):
        mission_path(dict(MISSION, profile=[{"segment": "seg1", "start_altitude_m": 20.0}]), "heli")
    with pytest.raises(FlightPathError, match=r"profile\[0\].segment"):
        mission_path(dict(MISSION, profile=[{"segment": "seg9", "duration_s": 1.0, "start_altitude_m": 0.0}]), "heli")
    with pytest.raises(FlightPathError, match="below the ground"):
        mission_path({"name": "d", "segments": [{"id": "seg3", "aircraft": {"heli": {"forward_speed_mps": 25.0, "climb_speed_mps": -3.0}}}],
                     "profile": [{"segment": "seg3", "duration_s": 60.0, "start_altitude_m": 100.0}]}, "heli")


def test_reference_procedures_geometry():
    """Take-off: 20 m level flight until 500 m before the reference point, then the V_y climb
    (height over the point 20 + 500 tan γ); overflight at 150 m at min(0.9 V_H, 0.45 V_H + 65 km/h);
    approach on 6° through 120 m over the point; microphones on the track and ±150 m at 1.2 m."""
    params = reference_parameters(MISSION, "heli", {"takeoff": "seg1"})
    assert params["vh_mps"] == 80.0 and params["vy_mps"] == pytest.approx(math.hypot(40.0, 4.0))
    to = certification_procedure("takeoff", "seg1", params)
    z_at_0 = np.interp(0.0, to.path.knot_position_m[:, 0], to.path.knot_position_m[:, 2])
    assert z_at_0 == pytest.approx(20.0 + 500.0 * 0.1) == to.height_over_reference_m
    assert to.path.knot_position_m[1].tolist() == pytest.approx([-500.0, 0.0, 20.0])
    fo = certification_procedure("overflight", "seg2", params)
    assert fo.speed_mps == pytest.approx(min(72.0, 36.0 + 65.0 / 3.6)) == overflight_speed_mps(80.0)
    assert overflight_speed_mps(80.0, vne_mps=50.0) == 45.0
    ap = certification_procedure("approach", "seg3", params)
    p = ap.path.knot_position_m
    assert np.interp(0.0, p[:, 0], p[:, 2]) == pytest.approx(120.0)
    assert math.degrees(math.atan2(p[0, 2] - p[-1, 2], p[-1, 0] - p[0, 0])) == pytest.approx(6.0)
    assert ap.speed_mps == params["vy_mps"]
    assert to.microphones_m.tolist() == [[0.0, 0.0, 1.2], [0.0, 150.0, 1.2], [0.0, -150.0, 1.2]]
    assert to.atmosphere.temperature_k == pytest.approx(298.15)
    with pytest.raises(FlightPathError, match="segments.takeoff: expected the best-rate-of-climb"):
        reference_parameters(MISSION, "heli", {"takeoff": "seg2"})
    with pytest.raises(FlightPathError, match="vy_mps"):
        certification_procedure("approach", "seg3", {"vh_mps": 80.0})


def test_limits():
    """Chapter 8 (8.4.2) limits: 106/104/109 EPNdB at 80 t, −3 EPNdB per halving, floors
    86/84/89 EPNdB reached at 788 kg."""
    assert noise_limit_epndb("takeoff", 100_000.0) == 106.0
    assert noise_limit_epndb("overflight", 40_000.0) == pytest.approx(101.0)
    assert noise_limit_epndb("approach", 788.0) == pytest.approx(89.0, abs=0.01)
    assert noise_limit_epndb("takeoff", 500.0) == 86.0
    assert noise_limit_epndb("takeoff", 5140.1) == pytest.approx(106.0 + 3.0 * math.log2(5140.1 / 80000.0))
    with pytest.raises(ValueError, match="max_mass_kg"):
        noise_limit_epndb("takeoff", -1.0)


def test_epnl_hand_made_tonal_history():
    """A36.4 by hand: a 1 kHz band at L over bands at 0 dB (no noy) has PNL = L exactly (the
    1 kHz noy slope M(b)·(10/log10 2) = 1) and, as a tone with F = L ≥ 20 dB in 500-5000 Hz,
    C = 20/3 dB: PNLT = L + 6.67. History L_k = 90 − 2.2|k| (k = −10…10): PNLTM = 96.67, the
    10-dB-down window holds |k| ≤ 4 (9 records, 4.5 s), EPNL = 10 log10(0.05 Σ 10^(PNLT_k/10)),
    i.e. the duration correction D = EPNL − PNLTM, to 0.1 EPNdB."""
    k = np.arange(-10, 11)
    levels = np.zeros((k.size, BANDS.size))
    levels[:, BANDS == 0] = (90.0 - 2.2 * np.abs(k))[:, None]
    table, hist = microphone_histories(levels[None], BANDS)
    pnlt_hand = 90.0 - 2.2 * np.abs(k) + 20.0 / 3.0
    assert hist[0] == pytest.approx(pnlt_hand, abs=1e-3)
    window = np.abs(k) <= 4
    epnl_hand = 10 * np.log10(0.5 / 10.0 * np.sum(10 ** (pnlt_hand[window] / 10)))
    row = table.iloc[0]
    assert row["pnltm_db"] == pytest.approx(96.667, abs=0.01)
    assert row["epnl_db"] == pytest.approx(epnl_hand, abs=0.1)
    assert row["epnl_duration_s"] == 4.5 and not row["truncated"]
    # a flat broadband spectrum has no tone correction: PNLT = PNL
    flat = np.full((k.size, BANDS.size), 0.0) + (80.0 - 2.0 * np.abs(k))[:, None]
    _, hist_flat = microphone_histories(flat[None], BANDS)
    from nps.noise.metrics import pnl
    assert hist_flat[0] == pytest.approx(pnl(flat[:, 7:]), abs=1e-9)


def test_certify_overflight_symmetry_and_margin():
    """An omnidirectional source in the overflight: both sidelines score the same EPNL, lower than
    the centre; the procedure EPNL is their mean; margin = limit − EPNL."""
    params = reference_parameters(MISSION, "heli", {"takeoff": "seg1"})
    proc = certification_procedure("overflight", "seg2", params)
    hemi = omnidirectional(100.0, (50.0, 0.0, 0.0))
    res = certify(proc, hemi, 5000.0, Ground("hard"))
    e = res.microphones["epnl_db"].to_numpy()
    assert e[1] == pytest.approx(e[2], abs=1e-9) and e[0] > e[1]
    assert res.epnl_db == pytest.approx(e.mean())
    assert res.margin_db == pytest.approx(noise_limit_epndb("overflight", 5000.0) - res.epnl_db)
    assert not res.microphones["truncated"].any()
