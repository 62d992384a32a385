"""Bad-input corpus of issue 14 through the commands (``python -m nps <stage>``, in process).

Every case must end with exit status 2 and exactly one line on stderr, ``error: ...``, that names
the file or option and the field or quantity at fault; no Parquet file may be written and no
traceback printed. The inputs are a small helicopter chain (segment 2, 36 × 10 disk, 64 samples
per revolution, three observers ahead) built once; each case edits a copy of one input.
Configuration errors of the workflow (dry runs) are in test_bad_config.py.
"""

from __future__ import annotations

import copy
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace
from typing import Callable

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest
import yaml

from nps.__main__ import main as nps_main
from nps.app.io import read_metadata, read_table

REPO = Path(__file__).resolve().parents[2]
AIRCRAFT = REPO / "config/aircraft/helicopter.yaml"
MISSION = REPO / "config/missions/demo.yaml"
AHEAD = {"kind": "points_ahead", "radius_R": 10.0, "elevations_deg": [0.0, -20.0, -40.0], "moving": True}


def _ok(argv: list[str]) -> None:
    assert nps_main(argv) == 0, argv


def _rewrite(src: Path, dst: Path, edit: Callable) -> Path:
    """Copy of the artifact ``src`` with its table edited by ``edit(DataFrame) -> DataFrame``, written
    as another tool would (pyarrow directly: NaN allowed), with the original metadata."""
    dst.parent.mkdir(parents=True, exist_ok=True)
    table = pq.read_table(src)
    df = edit(table.to_pandas())
    pq.write_table(pa.Table.from_pandas(df, preserve_index=False).replace_schema_metadata(table.schema.metadata), dst)
    return dst


@pytest.fixture(scope="module")
def chain(tmp_path_factory) -> SimpleNamespace:
    d = tmp_path_factory.mktemp("chain")
    b = SimpleNamespace(root=d, trim=d / "trim.parquet", trim3=d / "trim3.parquet", loads=d / "loads",
                        config=d / "sets.yaml", observers=d / "ahead.parquet", signals=d / "acoustics")
    b.config.write_text(yaml.safe_dump({"observer_sets": {"ahead": AHEAD}}))
    for out, segment in ((b.trim, "seg2"), (b.trim3, "seg3")):
        _ok(["trim", "--aircraft", str(AIRCRAFT), "--mission", str(MISSION), "--segment", segment, "--out", str(out)])
    _ok(["loads", "--aircraft", str(AIRCRAFT), "--trim", str(b.trim), "--n-psi", "36", "--n-r", "10", "--out-dir", str(b.loads)])
    _ok(["observers", "--config", str(b.config), "--set", "ahead", "--aircraft", str(AIRCRAFT), "--trim", str(b.trim),
         "--out", str(b.observers)])
    _ok(["acoustics", "--aircraft", str(AIRCRAFT), "--disks", str(b.loads), "--trim", str(b.trim), "--observers",
         str(b.observers), "--samples-per-rev", "64", "--out-dir", str(b.signals)])
    # inputs that do not belong together, or are incomplete
    b.swapped = d / "swapped"  # the tail's loads under the main rotor's name
    b.swapped.mkdir()
    shutil.copy(b.loads / "tail.parquet", b.swapped / "main.parquet")
    shutil.copy(b.loads / "tail.parquet", b.swapped / "tail.parquet")
    b.empty_disks = d / "empty_disks"
    for rotor in ("main", "tail"):
        _rewrite(b.loads / f"{rotor}.parquet", b.empty_disks / f"{rotor}.parquet", lambda df: df.iloc[:0])
    b.empty_observers = _rewrite(b.observers, d / "empty_observers.parquet", lambda df: df.iloc[:0])
    b.nan_observers = _rewrite(b.observers, d / "nan_observers.parquet", lambda df: df.assign(x_m=np.nan))
    b.more_observers = _rewrite(b.observers, d / "more_observers.parquet",
                                lambda df: pd.concat([df, df.iloc[[-1]].assign(observer=df["observer"].max() + 1)]))
    b.bad_columns = d / "bad_columns"
    b.nan_signals = d / "nan_signals"
    b.missing_observer = d / "missing_observer"
    for rotor in ("main", "tail"):
        src = b.signals / f"{rotor}.parquet"
        _rewrite(src, b.bad_columns / f"{rotor}.parquet", lambda df: df.rename(columns={"p_Pa": "p"}))
        _rewrite(src, b.nan_signals / f"{rotor}.parquet", lambda df: df.assign(p_Pa=np.where(df.index == 5, np.nan, df.p_Pa)))
        _rewrite(src, b.missing_observer / f"{rotor}.parquet", lambda df: df[df.observer != df.observer.max()])
    b.text = d / "notes.parquet"
    b.text.write_text("not a table\n")
    b.a_file = d / "a_file"
    b.a_file.write_text("x\n")
    return b


def aircraft_file(out: Path, edit: Callable[[dict], None], name: str = "helicopter") -> str:
    """Edited copy of the bundled helicopter (file stem = name)."""
    data = yaml.safe_load(AIRCRAFT.read_text())
    edit(data)
    path = out / "aircraft" / f"{name}.yaml"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(yaml.safe_dump(data, sort_keys=False))
    return str(path)


def mission_file(out: Path, forward_mps: float, climb_mps: float, **extra) -> str:
    """A one-segment mission ``seg9`` with the helicopter's speeds."""
    speeds = {"forward_speed_mps": forward_mps, "climb_speed_mps": climb_mps, **extra}
    path = out / "mission.yaml"
    path.write_text(yaml.safe_dump({"name": "bad", "segments": [{"id": "seg9", "name": "bad", "aircraft": {"helicopter": speeds}}]}))
    return str(path)


def trim_cmd(out: Path, aircraft: str = str(AIRCRAFT), mission: str = str(MISSION), segment: str = "seg2", *extra) -> list[str]:
    return ["trim", "--aircraft", aircraft, "--mission", mission, "--segment", segment, "--out", str(out / "t.parquet"), *extra]


def flight(forward_mps: float, climb_mps: float, edit=lambda a: None, **extra):
    return lambda b, out: trim_cmd(out, aircraft_file(out, edit), mission_file(out, forward_mps, climb_mps, **extra), "seg9")


def rotor0(key: str, value):
    def edit(a):
        a["rotors"][0][key] = value
    return edit


def loads_cmd(b, out, *extra, trim=None, aircraft=str(AIRCRAFT)) -> list[str]:
    return ["loads", "--aircraft", aircraft, "--trim", str(trim or b.trim), "--n-psi", "36", "--n-r", "10",
            "--out-dir", str(out / "loads"), *extra]


def observers_cmd(b, out, spec: dict | None, name: str = "s", config: str | None = None) -> list[str]:
    if config is None:
        path = out / "config.yaml"
        path.write_text(yaml.safe_dump({"observer_sets": {name: spec}}))
        config = str(path)
    return ["observers", "--config", config, "--set", name, "--aircraft", str(AIRCRAFT), "--trim", str(b.trim),
            "--out", str(out / "o.parquet")]


def acoustics_cmd(b, out, *extra, disks=None, trim=None, observers=None) -> list[str]:
    return ["acoustics", "--aircraft", str(AIRCRAFT), "--disks", str(disks or b.loads), "--trim", str(trim or b.trim),
            "--observers", str(observers or b.observers), "--samples-per-rev", "64", "--out-dir", str(out / "sig"), *extra]


def hsi_cmd(b, out, *extra, signals=None, observers=None, trim=None) -> list[str]:
    return ["hsi", "--signals", str(signals or b.signals), "--observers", str(observers or b.observers), "--trim",
            str(trim or b.trim), "--rotor", "main", "tail", "--out-dir", str(out / "hsi"), *extra]


def metrics_cmd(b, out, *extra, signals=None, observers=None, trim=None) -> list[str]:
    return ["metrics", "--aircraft", str(AIRCRAFT), "--trim", str(trim or b.trim), "--observers", str(observers or b.observers),
            "--signals", str(signals or b.signals), "--out", str(out / "m.parquet"), "--bands-out", str(out / "b.parquet"),
            *extra]


def wake_cmd(b, out, *extra) -> list[str]:
    return ["wake", "--aircraft", str(AIRCRAFT), "--trim", str(b.trim), "--loads-dir", str(b.loads), "--steps-per-rev", "36",
            "--wake-dir", str(out / "wake"), "--bvi-dir", str(out / "bvi"), *extra]


@dataclass(frozen=True)
class Case:
    id: str
    argv: Callable[[SimpleNamespace, Path], list[str]]
    expect: tuple[str, ...]  # texts the one error line must contain


CASES = [
    # --- issue 14 "worst": flight states outside the models' validity -----------------------------------
    Case("speed_200_mps", flight(200.0, 0.0), ("advance ratio mu", "<= 0.5", "source:")),
    Case("climb_50_mps", flight(40.0, 50.0), ("blade loading C_T/sigma", "source:")),
    Case("vortex_ring_descent", flight(2.0, -10.0), ("descent rate V_z/v_h", "vortex-ring")),
    Case("advancing_tip_mach_1_12", flight(82.8, 0.0, rotor0("omega_rad_s", (1.12 * 340.3 - 82.8) / 7.62)),
         ("advancing tip Mach number", "source:")),
    Case("lock_number_1000", flight(30.0, 0.0, rotor0("lock_number", 1000.0)), ("Lock number = 1000", "within [1, 25]")),
    Case("wake_revolutions_0_01", lambda b, out: wake_cmd(b, out, "--revolutions", "0.01"), ("wake_revolutions = 0.01",)),
    Case("observer_at_the_hub", lambda b, out: observers_cmd(b, out, {**AHEAD, "radius_R": 0.001}), ("distance to rotor", "hub")),
    Case("observer_on_the_tip_path", lambda b, out: observers_cmd(b, out, {**AHEAD, "radius_R": 1.0, "elevations_deg": [0.0]}),
         ("blade path / chord",)),
    Case("hemisphere_inside_the_disk", lambda b, out: observers_cmd(
        b, out, {"kind": "hemisphere", "radius_R": 0.5, "n_elevation": 3, "n_azimuth": 4}), ("distance to rotor 'main'",)),
    Case("ground_grid_below_the_cg", lambda b, out: observers_cmd(
        b, out, {"kind": "ground_grid", "height_below_m": 1e-4, "x_range_m": [-10.0, 10.0], "y_range_m": [-10.0, 10.0],
                 "n_x": 3, "n_y": 3}), ("distance to rotor",)),
    Case("acoustics_tail_loads_as_main", lambda b, out: acoustics_cmd(b, out, disks=b.swapped),
         ("swapped/main.parquet", "rotor 'tail'", "expected 'main'")),
    Case("loads_trim_of_another_aircraft", lambda b, out: loads_cmd(b, out, aircraft=str(REPO / "config/aircraft/tandem.yaml")),
         ("trim.parquet", "aircraft 'helicopter'", "expected 'tandem'")),
    Case("hsi_observer_missing_from_signals", lambda b, out: hsi_cmd(b, out, signals=b.missing_observer),
         ("missing_observer/main.parquet", "missing")),
    Case("hsi_more_observers_than_signals", lambda b, out: hsi_cmd(b, out, observers=b.more_observers), ("observer(s) [3]",)),
    Case("acoustics_zero_row_observers", lambda b, out: acoustics_cmd(b, out, observers=b.empty_observers),
         ("empty_observers.parquet", "no rows")),
    Case("metrics_zero_row_observers", lambda b, out: metrics_cmd(b, out, observers=b.empty_observers), ("no rows",)),
    # --- implausible inputs: the message says which input to look at ------------------------------------
    Case("main_radius_in_feet", flight(30.0, 0.0, rotor0("radius_m", 25.0)), ("rotors[1].hub_position_m", "radius 25.0 m")),
    Case("tail_radius_in_feet", flight(30.0, 0.0, lambda a: a["rotors"][1].update(radius_m=5.09)),
         ("rotors[1]", "rotor 'tail'", "crosses the blade path of rotor 'main'", "radius_m")),
    Case("omega_in_rpm", flight(30.0, 0.0, rotor0("omega_rad_s", 258.0)), ("hover tip Mach number",)),
    Case("rotor_omega_scale_in_rpm", flight(30.0, 0.0, rotor_omega_scale={"main": 60.0}), ("rotor_omega_scale.main", "<= 1.5")),
    Case("gross_weight_x10", flight(30.0, 0.0, lambda a: a.update(gross_weight_kg=a["gross_weight_kg"] * 10)),
         ("rotor 'main'",)),
    Case("cl_max_0_05", flight(30.0, 0.0, lambda a: a["rotors"][0]["airfoil"].update(cl_max=0.05)),
         ("mean lift coefficient 6 C_T/sigma",)),
    Case("tail_hub_on_main_hub", flight(30.0, 0.0, lambda a: a["rotors"][1].update(hub_position_m=[0.0, 0.0, 1.8])),
         ("rotors[1].hub_position_m", "inside the disk swept by rotor 'main'")),
    Case("thrust_axis_down", flight(30.0, 0.0, rotor0("thrust_axis_body", [0.0, 0.0, -1.0])),
         ("rotors[0].thrust_axis_body", "pointing up")),
    Case("tail_thrust_axis_to_port", flight(30.0, 0.0, lambda a: a["rotors"][1].update(thrust_axis_body=[0.0, 0.94, 0.34])),
         ("rotor 'tail' (antitorque)", "check its thrust_axis_body")),
    Case("fuselage_drag_1000_m2", flight(30.0, 0.0, lambda a: a.update(fuselage_drag_area_m2=1000.0)),
         ("rotor 'main' (lift)", "fuselage_drag_area_m2")),
    Case("isa_delta_minus_300", lambda b, out: trim_cmd(out, str(AIRCRAFT), str(MISSION), "seg2", "--isa-delta-k", "-300"),
         ("--isa-delta-k", ">= -60")),
    Case("altitude_20_km", lambda b, out: trim_cmd(out, str(AIRCRAFT), str(MISSION), "seg2", "--altitude-m", "20000"),
         ("--altitude-m", "<= 11000")),
    Case("humidity_150", lambda b, out: metrics_cmd(b, out, "--relative-humidity-pct", "150"), ("--relative-humidity-pct",)),
    Case("zero_radius", flight(30.0, 0.0, rotor0("radius_m", 0.0)), ("rotors[0].radius_m", "> 0")),
    Case("cutout_beyond_tip", flight(30.0, 0.0, rotor0("root_cutout_m", 8.0)), ("rotors[0].root_cutout_m",)),
    Case("flight_path_inconsistent", flight(30.0, 3.0, flight_path_deg=20.0), ("flight_path_deg",)),
    Case("negative_blades", flight(30.0, 0.0, rotor0("n_blades", -4)), ("rotors[0].n_blades",)),
    Case("unknown_rotor_key", flight(30.0, 0.0, rotor0("radius_ft", 25.0)), ("rotors[0].radius_ft", "unknown key")),
    # --- files and options ------------------------------------------------------------------------------
    Case("trim_missing_segment", lambda b, out: trim_cmd(out, str(AIRCRAFT), str(MISSION), "seg99"), ("seg99",)),
    Case("trim_missing_aircraft_file", lambda b, out: trim_cmd(out, str(out / "none.yaml")), ("none.yaml", "file not found")),
    Case("aircraft_yaml_syntax", lambda b, out: trim_cmd(out, _text(out / "aircraft/helicopter.yaml", "name: [x\nrotors: 1\n")),
         ("helicopter.yaml", "line 2", "not valid YAML")),
    Case("out_is_a_directory", lambda b, out: ((out / "t.parquet").mkdir(), trim_cmd(out))[1],  # named as a Parquet file
         ("is a directory", "trim Parquet file")),
    Case("out_under_a_file", lambda b, out: loads_cmd(b, out)[:-1] + [str(b.a_file / "loads")],
         ("a_file/loads", "output directory")),
    Case("out_dir_is_a_file", lambda b, out: acoustics_cmd(b, out)[:-1] + [str(b.a_file)], ("a_file", "output directory")),
    Case("trim_not_found", lambda b, out: loads_cmd(b, out, trim=out / "none.parquet"), ("none.parquet", "not found")),
    Case("trim_not_parquet", lambda b, out: loads_cmd(b, out, trim=b.text), ("notes.parquet", "not a readable Parquet file")),
    Case("trim_is_observers", lambda b, out: loads_cmd(b, out, trim=b.observers), ("ahead.parquet", "stage 'observers'")),
    Case("loads_unknown_rotor", lambda b, out: loads_cmd(b, out, "--rotor", "rear"), ("no rotor named 'rear'",)),
    Case("loads_n_psi_5", lambda b, out: loads_cmd(b, out, "--n-psi", "5"), ("--n-psi", ">= 36")),
    Case("loads_n_r_3", lambda b, out: loads_cmd(b, out, "--n-r", "3"), ("--n-r", ">= 10")),
    Case("loads_n_psi_not_a_number", lambda b, out: loads_cmd(b, out, "--n-psi", "many"), ("--n-psi", "invalid int value")),
    Case("loads_too_big_for_memory", lambda b, out: loads_cmd(b, out, "--n-psi", "36000", "--n-r", "5000"),
         ("36000 x 5000", "needs an estimated", "MB available")),
    Case("observers_empty_config", lambda b, out: observers_cmd(b, out, None, config=_text(out / "empty.yaml", "")),
         ("empty.yaml", "observer_sets")),
    Case("observers_unknown_set", lambda b, out: observers_cmd(b, out, None, name="carpet", config=str(b.config)),
         ("no set named 'carpet'",)),
    Case("observers_typo_n_azimut", lambda b, out: observers_cmd(
        b, out, {"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 3, "n_azimut": 72}), ("observer_sets.s.n_azimut", "did you mean 'n_azimuth'")),
    Case("observers_missing_radius", lambda b, out: observers_cmd(b, out, {"kind": "points_ahead", "elevations_deg": [0.0]}),
         ("observer_sets.s.radius_R", "required")),
    Case("observers_n_elevation_1", lambda b, out: observers_cmd(
        b, out, {"kind": "hemisphere", "radius_R": 10.0, "n_elevation": 1, "n_azimuth": 4}), ("n_elevation", ">= 2")),
    Case("observers_upper_case_name", lambda b, out: observers_cmd(b, out, AHEAD, name="Ahead"),
         ("observer_sets.Ahead", "lower-case letter")),
    Case("observers_reversed_range", lambda b, out: observers_cmd(
        b, out, {"kind": "ground_grid", "height_below_m": 150.0, "x_range_m": [300.0, -300.0], "y_range_m": [-300.0, 300.0],
                 "n_x": 3, "n_y": 3}), ("x_range_m", "low < high")),
    Case("observers_unknown_kind", lambda b, out: observers_cmd(b, out, {"kind": "sphere2", "radius_R": 10.0}),
         ("observer_sets.s.kind",)),
    Case("acoustics_bvi_variant_with_trimmed_loads", lambda b, out: acoustics_cmd(b, out, "--variant", "bvi"),
         ("stage 'loads'", "expected 'bvi'")),
    Case("acoustics_zero_row_disk", lambda b, out: acoustics_cmd(b, out, disks=b.empty_disks), ("empty_disks/main.parquet", "no rows")),
    Case("acoustics_trim_of_another_segment", lambda b, out: acoustics_cmd(b, out, trim=b.trim3), ("segment 'seg2'", "'seg3'")),
    Case("acoustics_nan_observers", lambda b, out: acoustics_cmd(b, out, observers=b.nan_observers), ("x_m", "non-finite")),
    Case("acoustics_chord_fractions_equal", lambda b, out: acoustics_cmd(b, out, "--chord-fractions", "0.5", "0.5"),
         ("--chord-fractions", "front < rear")),
    Case("acoustics_samples_0", lambda b, out: acoustics_cmd(b, out, "--samples-per-rev", "0"), ("--samples-per-rev",)),
    Case("acoustics_thickness_unknown", lambda b, out: acoustics_cmd(b, out, "--thickness", "panel"), ("--thickness",)),
    Case("acoustics_samples_5e7", lambda b, out: acoustics_cmd(b, out, "--samples-per-rev", "50000000"),
         ("needs an estimated", "lower the resolution")),
    Case("acoustics_observers_are_trim", lambda b, out: acoustics_cmd(b, out, observers=b.trim), ("stage 'trim'",)),
    Case("hsi_wrong_columns", lambda b, out: hsi_cmd(b, out, signals=b.bad_columns), ("bad_columns/main.parquet", "p_Pa")),
    Case("hsi_nan_signals", lambda b, out: hsi_cmd(b, out, signals=b.nan_signals), ("nan_signals/main.parquet", "p_Pa", "non-finite")),
    Case("hsi_observer_999", lambda b, out: hsi_cmd(b, out, "--observer", "999"), ("observer 999", "ahead.parquet")),
    Case("hsi_observer_not_a_number", lambda b, out: hsi_cmd(b, out, "--observer", "first"), ("--observer",)),
    Case("hsi_figure_without_observer", lambda b, out: hsi_cmd(b, out, "--figure", str(out / "f.png")), ("--figure needs --observer",)),
    Case("hsi_signals_are_loads", lambda b, out: hsi_cmd(b, out, signals=b.loads), ("stage 'loads'", "expected 'acoustics'")),
    Case("hsi_missing_rotor_signals", lambda b, out: hsi_cmd(b, out, signals=b.empty_disks.parent / "nowhere"), ("not found",)),
    Case("metrics_harmonics_reversed", lambda b, out: metrics_cmd(b, out, "--bvispl-harmonics", "40", "7"),
         ("--bvispl-harmonics", "first < last")),
    Case("metrics_hsi_dir_is_acoustics", lambda b, out: metrics_cmd(b, out, "--hsi", str(b.signals)),
         ("stage 'acoustics'", "expected 'hsi'")),
    Case("metrics_observer_missing", lambda b, out: metrics_cmd(b, out, signals=b.missing_observer), ("missing",)),
    Case("metrics_isa_delta_minus_300", lambda b, out: metrics_cmd(b, out, "--isa-delta-k", "-300"), ("--isa-delta-k",)),
    Case("wake_d_above_1", lambda b, out: wake_cmd(b, out, "--D", "1.5"), ("--D", "<= 1")),
    Case("wake_a_nan", lambda b, out: wake_cmd(b, out, "--A", "nan"), ("--A", "finite")),
    Case("wake_step_0", lambda b, out: wake_cmd(b, out, "--step-deg", "0"), ("--step-deg",)),
    Case("wake_loads_of_another_aircraft", lambda b, out: wake_cmd(b, out)[:2] + [str(REPO / "config/aircraft/coaxial.yaml")]
         + wake_cmd(b, out)[3:], ("aircraft 'helicopter'", "expected 'coaxial'")),
    Case("unknown_stage", lambda b, out: ["loudness"], ("unknown stage 'loudness'", "stages: ")),
]


def _text(path: Path, text: str) -> str:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return str(path)


def _parquet_files(root: Path) -> set[Path]:
    return set(root.rglob("*.parquet"))


def test_corpus_size():
    assert len(CASES) >= 60 and len({c.id for c in CASES}) == len(CASES)


def check_refused(case, chain, tmp_path: Path, capsys) -> None:
    """Run ``case``: exit status 2, one stderr line ``error: ...`` holding every ``case.expect`` text, no
    traceback, and no Parquet file written (the chain's and ``tmp_path``'s the same as before)."""
    argv = case.argv(chain, tmp_path)
    before, here = _parquet_files(chain.root), _parquet_files(tmp_path)
    status = nps_main(argv)
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line.strip()]
    assert status == 2, captured.err + captured.out[-2000:]
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    for text in case.expect:
        assert text in lines[0], (text, lines[0])
    assert "Traceback" not in captured.err + captured.out
    assert _parquet_files(tmp_path) == here and _parquet_files(chain.root) == before


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input_is_one_clear_line(case, chain, tmp_path, capsys):
    check_refused(case, chain, tmp_path, capsys)


def test_debug_shows_the_traceback(chain, tmp_path):
    """--debug: the same error with its traceback (real module paths), in a separate process."""
    result = subprocess.run([sys.executable, "-m", "nps", *loads_cmd(chain, tmp_path, trim=chain.observers), "--debug"],
                            capture_output=True, text=True, cwd=REPO, timeout=300)
    assert result.returncode != 0
    assert "Traceback" in result.stderr and "nps/app/io.py" in result.stderr and "stage 'observers'" in result.stderr


def test_the_switch_turns_the_refusal_into_a_recorded_warning(chain, tmp_path, capsys):
    """--allow-outside-validity: the 200 m/s trim is written, its findings in the metadata and the report."""
    argv = flight(200.0, 0.0)(chain, tmp_path) + ["--allow-outside-validity"]
    assert nps_main(argv) == 0
    assert "warning: rotor 'main': advance ratio mu" in capsys.readouterr().out
    warnings = read_metadata(tmp_path / "t.parquet")["validity_warnings"]
    assert any(w["quantity"] == "rotor 'main': advance ratio mu" and w["limit"] == "<= 0.5" for w in warnings)
    assert len(read_table(tmp_path / "t.parquet")) == 2


def test_artifacts_inside_the_envelope_carry_no_warning_key(chain):
    for path in (chain.trim, chain.loads / "main.parquet", chain.observers):
        assert "validity_warnings" not in read_metadata(path)


def test_out_into_a_missing_directory_is_created(chain, tmp_path):
    out = tmp_path / "new" / "deeper" / "loads"
    assert nps_main(loads_cmd(chain, tmp_path)[:-1] + [str(out)]) == 0
    assert (out / "main.parquet").is_file()
