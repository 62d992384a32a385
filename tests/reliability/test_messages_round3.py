"""Messages, third round (issue 34): each refusal blames the file and field the user wrote, and a valid set-up runs.

Refusals through the commands (``python -m nps``, in process, :func:`test_bad_inputs.check_refused`: exit status 2,
one stderr line naming the file and field, no traceback, no Parquet file written; here also no RuntimeWarning,
made an error) and through the loaders and the notebook API (one-line ConfigError, nothing written). The classes:
a thrust axis without direction (the rig's ``thrust_axis_T``, a rotor file's or an aircraft's
``thrust_axis_body``), polars whose CL column cannot hold coefficients (percent, or angles in radians), the
notebook API on a copied campaign whose mission lists more aircraft, ``python -m nps rotor --rig`` (every rotor,
the loads' thrust, options the rig file gives, the former ``--test``), and the bundled campaign's broadband
``auto`` with the thesis' Pegg-only configuration beside it. Accept cases check their results.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
import yaml

from nps.__main__ import main as nps_main
from nps.app.config import ConfigError, load_campaign, load_rig, read_yaml
from nps.app.io import read_table, rotor_path
from nps.rotor.airfoils import AirfoilError, read_airfoil
from test_bad_inputs import REPO, Case, aircraft_file, check_refused, trim_cmd
from test_bad_inputs_round2 import edited_rotor, rig_cmd, rotor_cmd
from test_rig_multirotor_inputs import _write as multirotor_rig

XFOIL_POLAR = REPO / "tests/data/xfoil/naca0012_re200k.pol"
CSV_POLAR = REPO / "tests/data/airfoils/naca0012_sand80_2114_re360k.csv"
QUICK = {"n_psi": 36, "n_r": 10, "wake_revolutions": 2, "samples_per_rev": 128}  # examples/notebook_api.py --quick


# --- inputs ---------------------------------------------------------------------------------------------------------

def _axis_T(vector):
    """Edit of the main/tail rig: the tail rotor's axis given as ``thrust_axis_T`` (its lateral angle removed)."""
    def edit(rig):
        rig["rotors"][1].pop("lateral_angle_deg")
        rig["rotors"][1]["thrust_axis_T"] = vector
    return edit


def _rig_argv(path: Path, out: Path, *extra: str) -> list[str]:
    return ["rotor", "--rig", str(path), *extra, "--out-dir", str(out / "rotor")]


def _percent_xfoil(folder: Path) -> str:
    """The bundled XFOIL polar with its CL column x 100 (the other columns as XFOIL wrote them)."""
    lines = XFOIL_POLAR.read_text().splitlines()
    first = next(k for k, line in enumerate(lines) if line.split()[:1] == ["alpha"]) + 2
    for k in range(first, len(lines)):
        words = lines[k].split()
        if words:
            words[1] = f"{100 * float(words[1]):.2f}"
            lines[k] = "  ".join(words)
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "percent.pol").write_text("\n".join(lines) + "\n")
    return "percent.pol"


def _csv_polar(folder: Path, name: str, edit) -> str:
    """The bundled CSV polar's table edited by ``edit(DataFrame) -> DataFrame``, written as ``name``."""
    folder.mkdir(parents=True, exist_ok=True)
    edit(pd.read_csv(CSV_POLAR, comment="#")).to_csv(folder / name, index=False)
    return name


def _radians_csv(table: pd.DataFrame) -> pd.DataFrame:
    """A thin-airfoil polar over ±0.2 rad written in the degree column."""
    alpha_rad = np.linspace(-0.2, 0.2, 9)
    return pd.DataFrame({"alpha_deg": alpha_rad, "cl": 2 * np.pi * alpha_rad, "cd": 0.008})


def _rotor_with_polar(out: Path, write) -> list[str]:
    """``python -m nps rotor`` on the ITR rotor whose airfoil table is the file ``write(folder)`` makes."""
    path = edited_rotor(out)
    table = write(path.parent)
    rotor = {**yaml.safe_load(path.read_text()), "airfoil": {"table": table, "extrapolation": "viterna"}}
    path.write_text(yaml.safe_dump(rotor))
    return rotor_cmd(out, rotor_file=path)


def _aircraft_with_polar(out: Path) -> list[str]:
    """``python -m nps trim`` of the helicopter whose main rotor's airfoil is a CSV polar in percent."""
    path = Path(aircraft_file(out, lambda a: a["rotors"][0].update(airfoil={"table": "percent.csv"})))
    _csv_polar(path.parent, "percent.csv", lambda t: t.assign(cl=100 * t.cl))
    return trim_cmd(out, str(path))


def _lift_axis(vector):
    return lambda b, out: trim_cmd(out, aircraft_file(out, lambda a: a["rotors"][0].update(thrust_axis_body=vector)))


def _rig_file(out: Path) -> Path:
    """The ITR hover rig copied into ``out`` (python -m nps rig's input of test_bad_inputs_round2)."""
    return Path(rig_cmd(out)[2])


CASES = [
    # --- a thrust axis without direction: the file and field written, before any division -------------------------
    Case("rig_thrust_axis_T_zero", lambda b, out: _rig_argv(multirotor_rig(out, _axis_T([0.0, 0.0, 0.0])), out),
         ("bad_rig.yaml: rotors[1].thrust_axis_T", "expected a non-zero vector", "[0.0, 0.0, 0.0]")),
    Case("rig_thrust_axis_T_1e-12", lambda b, out: _rig_argv(multirotor_rig(out, _axis_T([1e-12, 0.0, 0.0])), out),
         ("bad_rig.yaml: rotors[1].thrust_axis_T", "non-zero vector")),
    Case("rig_stage_thrust_axis_T_zero", lambda b, out: ["rig", "--rig", str(multirotor_rig(out, _axis_T([0, 0, 0]))),
                                                        "--out-dir", str(out / "rig")],
         ("bad_rig.yaml: rotors[1].thrust_axis_T", "non-zero vector")),
    Case("rotor_file_thrust_axis_body_zero",
         lambda b, out: rotor_cmd(out, rotor_file=edited_rotor(out, thrust_axis_body=[0, 0, 0])),
         ("itr/rotor.yaml: rotor 'itr'.thrust_axis_body", "expected a non-zero vector")),
    Case("aircraft_thrust_axis_body_zero", _lift_axis([0.0, 0.0, 0.0]),
         ("helicopter.yaml: rotors[0].thrust_axis_body", "expected a non-zero vector")),
    Case("aircraft_lift_axis_down", _lift_axis([0.0, 0.0, -1.0]),
         ("helicopter.yaml: rotors[0].thrust_axis_body", "pointing up")),
    # --- polars whose CL column holds no coefficients -------------------------------------------------------------
    Case("xfoil_cl_in_percent", lambda b, out: _rotor_with_polar(out, _percent_xfoil),
         ("rotor.yaml: rotor 'itr'", "percent.pol: CL:", "looks like percent", "divide it by 100")),
    Case("csv_cl_in_percent", lambda b, out: _rotor_with_polar(
        out, lambda d: _csv_polar(d, "percent.csv", lambda t: t.assign(cl=100 * t.cl))), ("percent.csv: CL:", "looks like percent")),
    Case("csv_alpha_in_radians", lambda b, out: _rotor_with_polar(out, lambda d: _csv_polar(d, "radians.csv", _radians_csv)),
         ("radians.csv: CL:", "angles look like radians", "give alpha in degrees")),
    Case("aircraft_polar_in_percent", lambda b, out: _aircraft_with_polar(out),
         ("helicopter.yaml: rotors[0]", "percent.csv: CL:", "looks like percent")),
    # --- python -m nps rotor --rig: the rig file gives the rest; the former name --test ------------------------------
    Case("rig_with_rpm", lambda b, out: _rig_argv(_rig_file(out), out, "--rpm", "3000"),
         ("--rpm: the rig file --rig", "bad_rig.yaml", "remove --rpm")),
    Case("rig_with_n_psi", lambda b, out: _rig_argv(_rig_file(out), out, "--n-psi", "36"), ("--n-psi: the rig file",)),
    Case("rig_with_a_microphone", lambda b, out: _rig_argv(_rig_file(out), out, "--mic", "1", "0", "0"), ("--mic: the rig file",)),
    Case("rig_with_allow_outside_validity", lambda b, out: _rig_argv(_rig_file(out), out, "--allow-outside-validity"),
         ("--allow-outside-validity: the rig file",)),
    Case("former_option_test", lambda b, out: ["rotor", "--test", str(_rig_file(out)), "--out-dir", str(out / "rotor")],
         ("python -m nps rotor: --test", "did you mean --rig?")),
    Case("former_option_test_equals", lambda b, out: ["rotor", f"--test={_rig_file(out)}", "--out-dir", str(out / "rotor")],
         ("--test", "did you mean --rig?")),
]


def test_corpus_size():
    assert len(CASES) >= 16 and len({c.id for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_refusal_names_the_file_and_field(case, tmp_path, capsys):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        check_refused(case, SimpleNamespace(root=tmp_path), tmp_path, capsys)
    assert not (tmp_path / "rotor").exists() and not (tmp_path / "rig").exists()


def test_zero_thrust_axis_prints_one_line_and_no_warning(tmp_path):
    """The issue's case as a user runs it: stderr holds the one error line, no RuntimeWarning before it."""
    path = multirotor_rig(tmp_path, _axis_T([0, 0, 0]))
    result = subprocess.run([sys.executable, "-m", "nps", *_rig_argv(path, tmp_path)], capture_output=True, text=True,
                            cwd=REPO, timeout=300)
    assert result.returncode == 2 and result.stderr.splitlines() == [
        f"error: {path}: rotors[1].thrust_axis_T: expected a non-zero vector (the thrust direction; NPS normalises it), "
        "got [0, 0, 0]"], result.stderr
    assert not (tmp_path / "rotor").exists()


def test_thrust_axis_T_of_any_length_is_normalised(tmp_path):
    """An axis written with length 2 along +y_T is the tail rotor's axis along −y_G (the 180° turn about z)."""
    rig = load_rig(multirotor_rig(tmp_path, _axis_T([0.0, 2.0, 0.0])))
    assert rig["rotor_configs"][1]["thrust_axis_body"] == [0.0, -1.0, 0.0]


@pytest.mark.parametrize("path, slope", [(XFOIL_POLAR, 8.86), (REPO / "config/airfoils/naca0012.c81", 6.30), (CSV_POLAR, 6.30)],
                         ids=["xfoil", "c81", "csv"])
def test_bundled_polars_pass_the_lift_check(path, slope):
    assert read_airfoil(path).lift_slope_per_rad == pytest.approx(slope, abs=0.01)


def test_a_high_lift_polar_is_accepted(tmp_path):
    """c_l up to 2.8 (a flapped section) at a lift slope of 2 pi is a coefficient, not percent."""
    alpha_deg = np.arange(-10.0, 26.0, 2.0)
    cl = np.minimum(2 * np.pi * np.radians(alpha_deg) + 0.6, 2.8)
    pd.DataFrame({"alpha_deg": alpha_deg, "cl": cl, "cd": 0.01}).to_csv(tmp_path / "flapped.csv", index=False)
    table = read_airfoil(tmp_path / "flapped.csv")
    assert table.lift_slope_per_rad == pytest.approx(2 * np.pi, rel=1e-9) and table.cl.values.max() == 2.8


def test_a_polar_in_percent_is_refused_when_read(tmp_path):
    with pytest.raises(AirfoilError, match=r"percent.pol: CL: \|c_l\| up to 109.5 .* looks like percent") as error:
        read_airfoil(tmp_path / _percent_xfoil(tmp_path))
    assert "viterna" not in str(error.value)


# --- the notebook API on a campaign copied elsewhere -------------------------------------------------------------

def _copied_campaign(tmp_path: Path, edit=None) -> tuple[Path, Path]:
    """config/config.yaml copied into a folder of another name, and the bundled mission copied (edited by
    ``edit(mission)``): the mission lists all four aircraft, the case runs one."""
    folder = tmp_path / "my_study"
    folder.mkdir()
    config = Path(shutil.copy(REPO / "config/config.yaml", folder / "config.yaml"))
    mission = read_yaml(REPO / "config/missions/demo.yaml")
    if edit:
        edit(mission)
    (folder / "demo.yaml").write_text(yaml.safe_dump(mission, sort_keys=False))
    return config, folder / "demo.yaml"


def test_notebook_runs_a_copied_campaign_whose_mission_lists_more_aircraft(tmp_path, monkeypatch):
    """Case.from_files on a copied config.yaml, run from another folder: accepted (the mission's other three aircraft
    are not run); segment 2 runs with the bundled broadband ``auto``: BPM on the tail rotor, no Pegg warning."""
    import nps

    config, mission = _copied_campaign(tmp_path)
    monkeypatch.chdir(tmp_path)
    case = nps.Case.from_files(REPO / "config/aircraft/helicopter.yaml", mission, config, cache_dir="cache", resolution=QUICK)
    assert list(case.campaign.aircraft) == ["helicopter"] and case.segments == [f"seg{i}" for i in range(1, 7)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)  # the BPM note on the tail rotor, recorded in the row
        row = case.run("seg2").row.iloc[0]
    assert row["aircraft"] == "helicopter" and row["power_W"] > 0.0 and np.isfinite(row["max_broadband_db"])
    assert "Pegg:" not in row["validity_warnings"] and "BPM: rotor 'tail'" in row["validity_warnings"]


@pytest.mark.parametrize("edit, expect", [
    (lambda m: m["segments"][1]["aircraft"].pop("helicopter"),
     "demo.yaml: segments[1].aircraft: expected speeds for aircraft 'helicopter' of the campaign"),
    (lambda m: m["segments"][1]["aircraft"].__setitem__("helicoptr", m["segments"][1]["aircraft"].pop("helicopter")),
     "(did you mean 'helicoptr'?)"),
], ids=["campaign_aircraft_missing", "campaign_aircraft_misspelt"])
def test_notebook_refuses_a_mission_without_the_case_aircraft(tmp_path, monkeypatch, edit, expect):
    import nps

    config, mission = _copied_campaign(tmp_path, edit)
    monkeypatch.chdir(tmp_path)
    with pytest.raises(ConfigError) as error:
        nps.Case.from_files(REPO / "config/aircraft/helicopter.yaml", mission, config, cache_dir="cache")
    assert "\n" not in str(error.value) and expect in str(error.value), str(error.value)
    assert not (tmp_path / "cache").exists()


# --- python -m nps rotor --rig: every rotor, the loads' thrust ----------------------------------------------------

def test_rotor_command_runs_every_rotor_of_a_rig(tmp_path, capsys):
    """The main/tail rig: both rotors' loads and signals, each rotor's line with the thrust of its loads (the main
    rotor's trimmed to 1100 N, the tail's the answer of its pitch), each rotor's harmonics at its own BPF, and the
    note that the trimmed loads are radiated where the rig computes BVI loads."""
    path = multirotor_rig(tmp_path, lambda rig: None)
    assert nps_main(_rig_argv(path, tmp_path)) == 0
    out, printed = tmp_path / "rotor", capsys.readouterr().out
    for name in ("main", "tail"):
        thrust = read_table(rotor_path(out / "loads", name, "_summary")).set_index("quantity").loc["thrust_N", "value"]
        assert f"rotor {name}: " in printed and f"thrust {thrust:.6g} N" in printed
        assert (out / "acoustics" / f"{name}.parquet").exists()
    assert "note: the trimmed loads are radiated (variant base)" in printed and "snakemake -j2 bad_rig" in printed
    levels = pd.read_csv(out / "levels.csv")
    assert levels["main_bpf1_hz"].iloc[0] == pytest.approx(4 * 100.0 / (2 * np.pi), rel=1e-5)
    assert levels["tail_bpf1_hz"].iloc[0] == pytest.approx(3 * 500.0 / (2 * np.pi), rel=1e-5)
    total = 10 ** (levels["oaspl_db"] / 10)
    assert np.all(total >= 10 ** (levels[["main_oaspl_db", "tail_oaspl_db"]].max(axis=1) / 10) * (1 - 1e-9))


def test_rotor_command_on_one_rotor_keeps_its_columns(tmp_path, capsys):
    """The ITR rig (36 x 10 disk): levels.csv's columns as before, no note (no BVI loads), the loads' thrust printed."""
    assert nps_main(_rig_argv(_rig_file(tmp_path), tmp_path)) == 0
    out, printed = tmp_path / "rotor", capsys.readouterr().out
    assert list(pd.read_csv(out / "levels.csv").columns[:7]) == ["observer", "x_T_m", "y_T_m", "z_T_m", "oaspl_db", "bpf1_hz", "bpf1_db"]
    thrust = read_table(rotor_path(out / "loads", "itr", "_summary")).set_index("quantity").loc["thrust_N", "value"]
    assert f"thrust {thrust:.6g} N" in printed and "note:" not in printed


def test_rotor_help_describes_the_resolution_options():
    result = subprocess.run([sys.executable, "-m", "nps", "rotor", "--help"], capture_output=True, text=True, cwd=REPO,
                            timeout=120)
    text = " ".join(result.stdout.split())
    assert result.returncode == 0
    for expected in ("--n-psi N_PSI azimuth steps per revolution", "--n-r N_R radial stations",
                     "--samples-per-rev SAMPLES_PER_REV pressure samples per revolution", "--arc-plane {xz,yz,xy} plane of the arc"):
        assert expected in text, expected


# --- the bundled campaign: broadband auto; the thesis' Pegg-only configuration ----------------------------------

@pytest.mark.parametrize("config, bpm_inputs", [("config/config.yaml", True), ("config/thesis_pegg.yaml", False)],
                         ids=["bundled_auto", "thesis_pegg"])
def test_source_hemispheres_follow_the_campaign_broadband(config, bpm_inputs):
    """With ``auto`` the source hemispheres (footprints, certification) get what BPM needs, as the metrics do; the
    Pegg-only configuration plans them as before."""
    from nps.app.plan import CaseConfig, metrics_reads_disks, stage_params

    campaign = load_campaign(read_yaml(REPO / config), config, root=REPO)
    params = stage_params("source_hemisphere", CaseConfig.from_campaign(campaign, "helicopter", "seg2"))
    assert metrics_reads_disks(campaign.config) is bpm_inputs
    assert ("rotor_configs" in params and "atmosphere" in params) is bpm_inputs
