"""Trade tables (nps.app.trade): Pareto front and sensitivities against hand computations."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from nps.app.trade import pareto_front, sensitivity, sensitivity_ranking, trade_tables


def test_pareto_front_of_a_known_set():
    power = np.array([1.0, 2.0, 3.0, 2.0, 1.0, 4.0])
    noise = np.array([5.0, 3.0, 1.0, 4.0, 6.0, 1.0])
    # (2, 4) is beaten by (2, 3); (1, 6) by (1, 5); (4, 1) by (3, 1)
    assert pareto_front(power, noise).tolist() == [True, True, True, False, False, False]


def _table(values, levels, power, segment="seg2"):
    return pd.DataFrame({"design": [f"d{i}" for i in range(len(values))], "x": values, "aircraft": "heli",
                         "segment": segment, "segment_name": "level", "max_dba_db": levels, "power_W": power})


def test_sensitivity_of_two_variants_is_the_hand_computation():
    """Two designs differing in one variable: the slope is exact; per +10 %: ΔL ln 1.1 / ln(x2/x1)."""
    table = _table([25.0, 28.0], [87.5, 89.3], [4.17e5, 4.74e5])
    result = sensitivity(table, {"x": 28.0}, ["max_dba_db", "power_W"]).set_index("metric")["change_per_10pct"]
    assert result["max_dba_db"] == pytest.approx((89.3 - 87.5) * math.log(1.1) / math.log(28.0 / 25.0), rel=1e-12)
    power_exponent = math.log(4.74e5 / 4.17e5) / math.log(28.0 / 25.0)
    assert result["power_W"] == pytest.approx(100.0 * (1.1 ** power_exponent - 1.0), rel=1e-12)


def test_sensitivity_recovers_main_effects_of_a_factorial():
    """L = 80 + 30 log10(x) − 5 log10(y) on a 3 × 3 factorial: per +10 %, 30 log10 1.1 and −5 log10 1.1."""
    x, y = np.meshgrid([20.0, 25.0, 30.0], [3.0, 4.0, 5.0])
    table = _table(x.ravel(), 80 + 30 * np.log10(x.ravel()) - 5 * np.log10(y.ravel()), np.full(9, 1e5))
    table["y"] = y.ravel()
    result = sensitivity(table, {"x": 25.0, "y": 4.0}, ["max_dba_db"]).set_index("variable")["change_per_10pct"]
    assert result["x"] == pytest.approx(30 * math.log10(1.1), rel=1e-10)
    assert result["y"] == pytest.approx(-5 * math.log10(1.1), rel=1e-10)
    ranking = sensitivity_ranking(sensitivity(table, {"x": 25.0, "y": 4.0}, ["max_dba_db"]))
    assert ranking["variable"].tolist() == ["x", "y"] and ranking["rank"].tolist() == [1, 2]


def test_trade_tables_order_rows_by_design_and_mark_the_front():
    rows = [_table([v], [l], [p]).assign(design=d) for d, v, l, p in
            (("db", 28.0, 89.0, 4.7e5), ("da", 25.0, 87.0, 4.2e5), ("dc", 30.0, 88.0, 5.0e5))]
    table, _, _ = trade_tables(rows, ["da", "db", "dc"], {"x": 28.0})
    assert table["design"].tolist() == ["da", "db", "dc"]
    assert table["pareto"].tolist() == [True, False, False]


def test_certification_and_footprint_columns_repeat_the_aircraft_values_on_every_row():
    from nps.app.trade import certification_columns, footprint_columns

    rows = _table([25.0, 28.0], [87.0, 89.0], [4e5, 5e5])
    summary = pd.DataFrame({"procedure": ["takeoff", "overflight", "approach"], "epnl_db": [93.4, 91.6, 94.9],
                            "margin_db": [0.7, 0.55, 2.2]})
    areas = pd.DataFrame({"metric": ["sel_db", "sel_db"], "level_db": [60.0, 80.0], "area_km2": [131.5, 9.1],
                          "open": [True, False]})
    table = footprint_columns(certification_columns(rows, summary), areas)
    assert table["min_margin_db"].tolist() == [0.55, 0.55] and table["epnl_approach_db"].tolist() == [94.9, 94.9]
    assert table["sel_db_80db_area_km2"].tolist() == [9.1, 9.1] and table["footprint_open"].iloc[0] == "sel_db 60 dB"


def test_trends_mark_the_designs_whose_broadband_model_differs_and_count_blades_in_whole_numbers(tmp_path):
    """``auto`` picks BPM for the slow designs' main rotor and Pegg for the others: those rows (and the means that
    include them) are the ones marked, a case without a switch has none; a blade count gets whole-number ticks."""
    import matplotlib

    matplotlib.use("Agg")
    from nps.plots import trade as figures

    omega = np.repeat([22.4, 25.0, 28.0], 3)
    table = pd.DataFrame({"main.omega_rad_s": omega, "main.n_blades": np.tile([3, 4, 5], 3), "aircraft": "helicopter",
                          "segment": "seg2", "segment_name": "level", "main_broadband": np.where(omega < 23, "bpm", "pegg"),
                          "tail_broadband": "bpm", "max_broadband_db": 80.0, "max_dba_db": 80.0 + omega})
    switched = figures._broadband_switched(table)
    assert switched.tolist() == (omega < 23).tolist()
    assert not figures._broadband_switched(table.assign(main_broadband="pegg")).any()
    assert figures._integer_valued(table["main.n_blades"]) and not figures._integer_valued(table["main.omega_rad_s"])
    path = tmp_path / "trends.png"
    figures.metrics_against_variables(table, ["main.omega_rad_s", "main.n_blades"], ["max_dba_db"], "t", path)
    assert path.stat().st_size > 0


def test_path_energy_is_the_integral_of_the_blended_power():
    """Power blended between two states as the hemispheres are, P(t) = 100 kW + 20 kW t/s, sampled at 0.5 s
    up to 9.5 s of a 9.8 s path: the trapezoid is exact for a linear power, the last 0.3 s hold P(9.5 s)."""
    from nps.app.trade import path_energy_J, state_power_history_W

    time_s = np.arange(0.0, 9.51, 0.5)
    weight = time_s / 10.0  # from state a (100 kW) toward state b (300 kW)
    history = pd.DataFrame({"time_s": time_s, "state": "a", "neighbour": "b", "neighbour_weight": weight})
    power = state_power_history_W(history, {"a": 1.0e5, "b": 3.0e5})
    np.testing.assert_allclose(power, 1.0e5 + 2.0e4 * time_s, rtol=1e-15)
    energy = path_energy_J(time_s, power, 9.8)
    assert energy == pytest.approx(1.0e5 * 9.5 + 1.0e4 * 9.5**2 + (1.0e5 + 2.0e4 * 9.5) * 0.3, rel=1e-14)


def test_procedure_row_has_each_microphone_and_its_maxima():
    from nps.app.trade import procedure_row

    history = pd.DataFrame({"time_s": [0.0, 1.0], "state": ["s1", "s2"], "neighbour": ["s2", "s2"],
                            "neighbour_weight": [0.0, 0.0]})
    microphones = pd.DataFrame({"microphone": ["village", "final"], "sel_db": [80.0, 84.0], "lamax_db": [70.0, 75.0],
                                "epnl_db": [85.0, 88.0]})
    areas = pd.DataFrame({"metric": ["sel_db"], "level_db": [80.0], "area_km2": [0.5], "open": [False]})
    path = {"name": "p", "aircraft": "heli", "description": "an approach"}
    row = procedure_row(path, {"design": "d1", "x.y": 2.0}, history, {"s1": 2.0e5, "s2": 4.0e5}, 1.0, 30.0,
                        microphones, areas, [])
    assert row.iloc[0].to_dict() == {
        "design": "d1", "x.y": 2.0, "aircraft": "heli", "path": "p", "path_description": "an approach", "duration_s": 1.0,
        "distance_m": 30.0, "energy_J": 3.0e5, "n_states": 2, "sel_village_db": 80.0, "sel_final_db": 84.0,
        "max_sel_db": 84.0, "lamax_village_db": 70.0, "lamax_final_db": 75.0, "max_lamax_db": 75.0,
        "epnl_village_db": 85.0, "epnl_final_db": 88.0, "max_epnl_db": 88.0, "sel_db_80db_area_km2": 0.5,
        "footprint_open": "", "validity_warnings": ""}
    with pytest.raises(ValueError, match="sel_final_db"):
        procedure_row(path, {"design": "d1", "sel_final_db": 1.0}, history, {"s1": 1.0, "s2": 1.0}, 1.0, 30.0,
                      microphones, areas, [])


def test_procedure_trade_table_marks_the_front_of_its_pareto_columns():
    """Rows of a procedure study: grouped per aircraft × path, the front of the given columns, energy and
    duration sensitivities in percent (fitted as logarithms, like power)."""
    rows = [pd.DataFrame({"design": [f"d{i}"], "v": [v], "aircraft": ["heli"], "path": ["p"], "path_description": ["a"],
                          "sel_village_db": [s], "energy_J": [e], "duration_s": [t]})
            for i, (v, s, e, t) in enumerate([(26.0, 80.0, 1.0e8, 120.0), (30.0, 81.0, 0.9e8, 110.0), (34.0, 83.0, 0.95e8, 100.0)])]
    table, per_path, _ = trade_tables(rows, ["d0", "d1", "d2"], {"v": 30.0}, {"noise": "sel_village_db", "cost": "duration_s"})
    assert table["pareto"].tolist() == [True, True, True]
    table, _, _ = trade_tables(rows, ["d0", "d1", "d2"], {"v": 30.0}, {"noise": "sel_village_db", "cost": "energy_J"})
    assert table["pareto"].tolist() == [True, True, False]  # d2 is beaten by d1 in both SEL and energy
    assert list(per_path.columns[:2]) == ["aircraft", "path"]
    units = per_path.set_index("metric")["unit"]
    assert units["energy_J"] == units["duration_s"] == "%" and units["sel_village_db"] == "dB"
    slope = np.polyfit(np.log([26.0, 30.0, 34.0]), np.log([120.0, 110.0, 100.0]), 1)[0]
    assert per_path.set_index("metric").loc["duration_s", "change_per_10pct"] == pytest.approx(100 * (1.1**slope - 1), rel=1e-9)
