"""Rigs with several rotors (``rotors:``, nps.rig.case, nps.app.config.load_rig, nps.stages.rig) and the loads at
radial stations (nps.rotor.station_loads, nps.stages.station_loads, ``python -m nps station-loads``)."""

import math
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from nps.app.config import load_rig
from nps.app.io import read_table
from nps.rig.case import rotor_axis_flight, rotor_axis_test, shaft_axis_flight, t_to_g
from nps.rotor.station_loads import STATION_COLUMNS, m2cn, station_loads
from nps.stages import loads as loads_stage
from nps.stages import rig as rig_stage
from nps.stages import station_loads as station_stage
from nps.stages import wake as wake_stage

REPO = Path(__file__).resolve().parents[2]
BUNDLED = REPO / "config" / "rigs" / "main_tail_rig.yaml"


def _rig_dir(tmp_path: Path) -> Path:
    """A rig directory with the bundled main and tail rotor files."""
    shutil.copytree(REPO / "config" / "rigs" / "main_tail", tmp_path / "main_tail")
    return tmp_path


def _write(directory: Path, name: str, **fields) -> Path:
    rig = yaml.safe_load(BUNDLED.read_text())
    rig.update(name=name, **fields)
    for key in [k for k, v in fields.items() if v is None]:
        rig.pop(key)
    path = directory / f"{name}.yaml"
    path.write_text(yaml.safe_dump(rig, sort_keys=False))
    return path


def _single(directory: Path, name: str, entry: dict, **fields) -> Path:
    """The one-rotor form of one ``rotors[]`` entry (its speed, control and targets in the condition)."""
    rig = yaml.safe_load(BUNDLED.read_text())
    condition = {k: v for k, v in entry.items() if k not in ("rotor", "hub_position_m", "rotation", "lateral_angle_deg")}
    rig.pop("rotors")
    rig.update(name=name, rotor=entry["rotor"], condition={**rig["condition"], **condition}, **fields)
    path = directory / f"{name}.yaml"
    path.write_text(yaml.safe_dump(rig, sort_keys=False))
    return path


def _setup(path: Path, out: Path) -> pd.DataFrame:
    rig_stage.run({"config": str(path)}, {"trim": str(out / "trim.parquet"), "observers": str(out / "mics.parquet")}, {})
    return read_table(out / "trim.parquet")


def test_axes_and_hubs_in_the_flight_frame():
    """T → G is the 180° turn about z; the shaft angle alone keeps the one-rotor axis bit for bit; the lateral
    angle turns the axis toward +y_T (90°: along +y_T, i.e. −y_G); thrust_axis_T is normalised."""
    assert np.array_equal(rotor_axis_flight({"shaft_angle_deg": 4.3}), shaft_axis_flight(math.radians(4.3)))
    assert np.allclose(rotor_axis_test({"shaft_angle_deg": 0.0, "lateral_angle_deg": 90.0}), [0.0, 1.0, 0.0], atol=1e-15)
    assert np.allclose(rotor_axis_flight({"lateral_angle_deg": 90.0}), [0.0, -1.0, 0.0], atol=1e-15)
    a, lat = math.radians(10.0), math.radians(30.0)
    assert np.allclose(rotor_axis_test({"shaft_angle_deg": 10.0, "lateral_angle_deg": 30.0}),
                       [math.cos(lat) * math.sin(a), math.sin(lat), math.cos(lat) * math.cos(a)], rtol=0, atol=1e-15)
    assert np.allclose(rotor_axis_flight({"thrust_axis_T": [0.0, -2.0, 0.0]}), [0.0, 1.0, 0.0])
    assert np.array_equal(t_to_g([1.95, 0.5, 0.3]), [-1.95, -0.5, 0.3])


def test_set_up_rows_of_the_bundled_rig(tmp_path):
    """One row per rotor: hubs and axes in G from T, the rotor's own speed; the main rotor trimmed to its thrust,
    the fixed-pitch tail rotor's thrust the answer — each equal (bit for bit) to its one-rotor rig."""
    rig = load_rig(BUNDLED)
    assert [r["name"] for r in rig["rotor_configs"]] == ["main", "tail"]
    trim = _setup(BUNDLED, tmp_path / "both")
    assert list(trim["rotor"]) == ["main", "tail"]
    main, tail = trim.iloc[0], trim.iloc[1]
    assert [tail["hub_x_m"], tail["hub_y_m"], tail["hub_z_m"]] == [-1.95, 0.0, 0.3]
    assert [main["hub_x_m"], main["hub_y_m"], main["hub_z_m"]] == [0.0, 0.0, 0.0]
    z_tail = [tail[f"r_gh_{i}2"] for i in range(3)]
    assert np.allclose(z_tail, [0.0, -1.0, 0.0], atol=1e-15)  # axis +y_T = -y_G: horizontal
    assert np.allclose([main[f"r_gh_{i}2"] for i in range(3)], shaft_axis_flight(math.radians(4.0)), rtol=0, atol=1e-15)
    assert tail["omega_rad_s"] == 5.0 * main["omega_rad_s"] and main["thrust_N"] == 1100.0
    assert tail["tip_mach"] == pytest.approx(main["tip_mach"], rel=1e-12)
    directory = _rig_dir(tmp_path)
    entries = yaml.safe_load(BUNDLED.read_text())["rotors"]
    for k, entry in enumerate(entries):
        alone = _setup(_single(directory, f"alone{k}", entry), tmp_path / f"alone{k}").iloc[0]
        row = trim.iloc[k]
        for column in ("thrust_N", "torque_Nm", "power_W", "mu_x", "mu_y", "mu_z", "ct", "omega_rad_s"):
            assert row[column] == alone[column], (entry["rotor"], column)


def _chain(path: Path, out: Path) -> dict:
    """Set-up, loads and free wake + BVI loads of a rig (the workflow's stages, the rig's settings)."""
    rig = load_rig(path)
    settings, rotors = rig["settings"], {r["name"]: r for r in rig["rotor_configs"]}
    where = {"aircraft": "rigs", "segment": rig["name"]}
    trim = _setup(path, out)
    resolution = settings["resolution"]
    loads_stage.run({"trim": str(out / "trim.parquet")}, {"loads": str(out / "loads")},
                    {"rotors": rotors, "n_psi": resolution["n_psi"], "n_r": resolution["n_r"], **where})
    wake_stage.run({"trim": str(out / "trim.parquet"), "loads": str(out / "loads")},
                   {"wake": str(out / "wake"), "bvi": str(out / "bvi")},
                   {"rotors": rotors, "wake": settings["wake"], "revolutions": resolution["wake_revolutions"],
                    "steps_per_rev": resolution["n_psi"], **where})
    return {"trim": trim, **{f"{kind}/{n}": read_table(out / kind / f"{n}.parquet") for n in rotors for kind in ("loads", "bvi")}}


def test_rotors_far_apart_give_each_isolated_result(tmp_path):
    """The two rotors 40 main-rotor radii apart: each rotor's set-up row, trimmed loads and free-wake BVI loads
    are its one-rotor rig's (to 1e-6 relative), with the bundled rig's common period on (the rotors are not
    coupled, so each keeps one turn)."""
    directory = _rig_dir(tmp_path)
    entries = yaml.safe_load(BUNDLED.read_text())["rotors"]
    entries[1] = {k: v for k, v in entries[1].items() if k != "lateral_angle_deg"}  # upright: the one-rotor form's axis
    entries[1]["hub_position_m"] = [0.0, 60.0, 0.0]
    both = _chain(_write(directory, "far", rotors=entries), tmp_path / "far")
    for k, entry in enumerate(entries):
        name = ("main", "tail")[k]
        alone = _chain(_single(directory, f"iso{k}", entry), tmp_path / f"iso{k}")
        for kind in ("loads", "bvi"):
            a, b = alone[f"{kind}/{name}"], both[f"{kind}/{name}"]
            for column in ("fz_N_per_m", "fx_N_per_m", "up_mps", "ut_mps"):
                x, y = a[column].to_numpy(), b[column].to_numpy()
                assert np.allclose(y, x, rtol=1e-6, atol=1e-6 * np.abs(x).max()), (name, kind, column)
        assert both["trim"].iloc[k]["thrust_N"] == pytest.approx(alone["trim"].iloc[0]["thrust_N"], rel=1e-12)


def _disk(n_psi=4, radii=(0.5, 0.7, 0.9)):
    rows = []
    for i in range(n_psi):
        for j, r in enumerate(radii):
            rows.append({"psi_rad": 2 * np.pi * i / n_psi, "r_m": r, "chord_m": 0.1 + 0.01 * j,
                         "mach": 0.2 + 0.1 * j + 0.01 * i, "fz_N_per_m": 100.0 * (i + 1) + 10.0 * j})
    return pd.DataFrame(rows)


def test_station_loads_by_hand():
    """M²c_n = F_n/(½ ρ a² c) of a disk row, c_n = M²c_n/M², linear in r between stations; rows in any order."""
    disk = _disk().sample(frac=1.0, random_state=1)  # shuffled rows
    rho, a, radius = 1.2, 340.0, 1.0
    out = station_loads(disk, "r", radius, rho, a, [0.7, 0.8])
    assert list(out.columns) == list(STATION_COLUMNS) and len(out) == 8
    at = out[(out["r_over_R"] == 0.7)].sort_values("psi_rad")
    # psi index 2, radius index 1: F = 310 N/m, c = 0.11 m, M = 0.32
    expected = 310.0 / (0.5 * 1.2 * 340.0**2 * 0.11)
    assert at["m2cn"].iloc[2] == pytest.approx(expected, rel=1e-14)
    assert at["cn"].iloc[2] == pytest.approx(expected / 0.32**2, rel=1e-14)
    mid = out[(out["r_over_R"] == 0.8)].sort_values("psi_rad")
    m_07 = (100.0 * 3 + 10.0) / (0.5 * rho * a**2 * 0.11)
    m_09 = (100.0 * 3 + 20.0) / (0.5 * rho * a**2 * 0.12)
    assert mid["m2cn"].iloc[2] == pytest.approx(0.5 * (m_07 + m_09), rel=1e-13)
    assert mid["cn"].iloc[2] == pytest.approx(0.5 * (m_07 / 0.32**2 + m_09 / 0.42**2), rel=1e-13)
    assert m2cn(310.0, rho, a, 0.11) == pytest.approx(expected, rel=1e-15)
    ends = station_loads(disk, "r", radius, rho, a, [0.5, 0.9])  # the first and last stations exactly
    assert ends["m2cn"].min() == pytest.approx(100.0 / (0.5 * rho * a**2 * 0.1), rel=1e-14)
    with pytest.raises(ValueError, match=r"station r/R 0.95: outside the table's radial stations"):
        station_loads(disk, "r", radius, rho, a, [0.95])


def test_station_loads_stage_and_command(tmp_path):
    """The stage and ``python -m nps station-loads`` on the bundled rig's set-up and loads: one table, every
    rotor at every station, a table row by hand."""
    from nps.__main__ import main as nps_main

    rig = load_rig(BUNDLED)
    rotors = {r["name"]: r for r in rig["rotor_configs"]}
    trim = _setup(BUNDLED, tmp_path)
    where = {"aircraft": "rigs", "segment": rig["name"]}
    loads_stage.run({"trim": str(tmp_path / "trim.parquet")}, {"loads": str(tmp_path / "loads")},
                    {"rotors": rotors, "n_psi": 36, "n_r": 12, **where})
    station_stage.run({"disks": str(tmp_path / "loads"), "trim": str(tmp_path / "trim.parquet")},
                      {"table": str(tmp_path / "st.parquet")}, {"stations": [0.75, 0.87], **where, "variant": "base"})
    table = read_table(tmp_path / "st.parquet")
    assert len(table) == 2 * 2 * 36 and set(table["rotor"]) == {"main", "tail"}
    disk = read_table(tmp_path / "loads" / "tail.parquet")
    r = np.unique(disk["r_m"])
    j = int(np.searchsorted(r, 0.75 * 0.3)) - 1
    w = (0.75 * 0.3 - r[j]) / (r[j + 1] - r[j])
    row0 = disk[disk["psi_rad"] == 0.0].sort_values("r_m")
    row = trim.iloc[1]
    m = [f / (0.5 * row["density_kg_m3"] * row["speed_of_sound_mps"] ** 2 * c)
         for f, c in zip(row0["fz_N_per_m"].iloc[[j, j + 1]], row0["chord_m"].iloc[[j, j + 1]])]
    got = table[(table["rotor"] == "tail") & (table["r_over_R"] == 0.75) & (table["psi_rad"] == 0.0)]["m2cn"].iloc[0]
    assert got == pytest.approx((1 - w) * m[0] + w * m[1], rel=1e-12)
    assert nps_main(["station-loads", "--disks", str(tmp_path / "loads"), "--trim", str(tmp_path / "trim.parquet"),
                     "--stations", "0.75", "0.87", "--out", str(tmp_path / "cmd.parquet")]) == 0
    assert read_table(tmp_path / "cmd.parquet").equals(table)
    # per-rotor stations (a rig's rotors[].stations_r_over_R): each rotor at its own, the same rows as the list form
    station_stage.run({"disks": str(tmp_path / "loads"), "trim": str(tmp_path / "trim.parquet")},
                      {"table": str(tmp_path / "own.parquet")},
                      {"stations": {"main": [0.87], "tail": [0.75, 0.87]}, **where, "variant": "base"})
    own = read_table(tmp_path / "own.parquet")
    assert sorted(set(zip(own["rotor"], own["r_over_R"]))) == [("main", 0.87), ("tail", 0.75), ("tail", 0.87)]
    same = table[~((table["rotor"] == "main") & (table["r_over_R"] == 0.75))].reset_index(drop=True)
    assert own.equals(same)
    with pytest.raises(ValueError, match=r"params stations: expected the stations of every rotor \['main', 'tail'\], "
                                         r"got none for \['tail'\]"):
        station_stage.run({"disks": str(tmp_path / "loads"), "trim": str(tmp_path / "trim.parquet")},
                          {"table": str(tmp_path / "bad.parquet")},
                          {"stations": {"main": [0.87]}, "rotors": ["main", "tail"], **where, "variant": "base"})
