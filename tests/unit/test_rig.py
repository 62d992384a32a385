"""Rigs (nps.rig.case, stage rig, ``python -m nps rig`` and ``python -m nps rotor``): frames, microphones,
bad input, the rig's own settings, and the command against a closed-form hover case."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from nps.rotor.bet import DiskGrid
from nps.cli.rotor import main as rotor_command
from nps.app.config import ConfigError, load_rig
from nps.app.io import read_table
from nps.rig.case import microphone_positions, microphone_table, rig_trim, rotor_for_rig, shaft_axis_flight, t_to_g

REPO = Path(__file__).resolve().parents[2]
ROTOR = {"name": "prop", "n_blades": 2, "radius_m": 0.5, "chord_m": 0.05, "root_cutout_m": 0.0, "twist_deg": 0.0,
         "thickness_ratio": 0.12, "rotation": "ccw", "lock_number": 5.0, "flapping": False, "tip_loss": False,
         "airfoil": {"lift_slope_per_rad": 5.7, "cd0": 0.0, "cd2": 0.0, "cl_max": 10.0}}
ATMOSPHERE = {"density_kg_m3": 1.225, "speed_of_sound_mps": 1.0e9}


ACOUSTICS = {"dual_compact_chord_fractions": [0.13, 0.87], "bvispl_harmonics": [6, 40]}


def write_rig(tmp_path, rotor=None, condition=None, microphones=None, name="case", **sections):
    (tmp_path / "prop.yaml").write_text(yaml.safe_dump(rotor or ROTOR))
    rig = {"name": name, "description": "unit test", "rotor": {"file": "prop.yaml"},
           "condition": condition or {"rpm": 3000.0, "control": "fixed", "pitch_deg": 8.0, "atmosphere": ATMOSPHERE},
           "microphones": microphones or [{"kind": "point", "positions_m": [[0.0, 0.0, -5.0]]}],
           "resolution": {"n_psi": 36, "n_r": 100, "samples_per_rev": 256}, "acoustics": ACOUSTICS, **sections}
    path = tmp_path / f"{name}.yaml"
    path.write_text(yaml.safe_dump(rig))
    return path


def test_test_frame_is_the_flight_frame_turned_by_180_degrees_about_z():
    """A microphone downstream of the hub (+x_T) is behind the flying rotor (−x_G); the advancing side of a
    counterclockwise rotor (+y_T) is starboard (−y_G); heights are unchanged."""
    assert np.array_equal(t_to_g([[1.0, 2.0, -3.0]]), [[-1.0, -2.0, -3.0]])
    table = microphone_table(np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.array([0, 0]), 30.0)
    assert table["azimuth_deg"].tolist() == pytest.approx([0.0, 90.0])  # behind; advancing side (map convention)
    assert np.all(table["vx_mps"] == 30.0) and table["x_T_m"].tolist() == [1.0, 0.0]


def test_aft_shaft_tilt_takes_the_free_stream_up_through_the_disk():
    """α_s = 4.3° aft at V = 32.9 m/s: μ_x = V cos α_s/ΩR, μ_z = −V sin α_s/ΩR (tests/validation/hart_ii_case.py)."""
    assert shaft_axis_flight(math.radians(10.0))[0] < 0.0
    condition = {"omega_rad_s": 109.12, "control": "fixed", "pitch_deg": 8.0, "shaft_angle_deg": 4.3,
                 "tunnel_speed_mps": 32.9, "atmosphere": {"density_kg_m3": 1.2055, "speed_of_sound_mps": 341.7}}
    rotor = rotor_for_rig({**ROTOR, "radius_m": 2.0, "chord_m": 0.121, "root_cutout_m": 0.44}, condition)
    row = rig_trim(rotor, condition, DiskGrid(36, 10)).iloc[0]
    tip = 109.12 * 2.0
    assert row["mu_x"] == pytest.approx(32.9 * math.cos(math.radians(4.3)) / tip, rel=1e-12)
    assert row["mu_z"] == pytest.approx(-32.9 * math.sin(math.radians(4.3)) / tip, rel=1e-12)
    assert row["vel_x_mps"] == 32.9 and row["r_gh_22"] == pytest.approx(math.cos(math.radians(4.3)), rel=1e-15)


def test_microphone_kinds_with_uneven_spacing(tmp_path):
    (tmp_path / "mics.csv").write_text("# two microphones\nx_m,y_m,z_m\n1,2,3\n4,5,6\n")
    (tmp_path / "mics.yaml").write_text(yaml.safe_dump([{"x_m": 7.0, "y_m": 8.0, "z_m": 9.0}]))
    specs = [{"kind": "point", "positions_m": [[0.0, 0.0, -1.0]]}, {"kind": "file", "path": "mics.csv"},
             {"kind": "file", "path": "mics.yaml"}, {"kind": "arc", "radius_m": 2.0, "angles_deg": [0.0, -30.0, -90.0],
                                                     "plane": "xz"},
             {"kind": "plane", "x_m": [-1.0, 0.5], "y_m": [0.0, 0.1, 1.0], "z_m": -2.0}]
    p, groups = microphone_positions(specs, tmp_path)
    assert groups.tolist() == [0, 1, 1, 2, 3, 3, 3] + [4] * 6
    assert p[1:4].tolist() == [[1, 2, 3], [4, 5, 6], [7, 8, 9]]
    np.testing.assert_allclose(p[5], [2 * math.cos(math.radians(30)), 0.0, -1.0], atol=1e-15)
    np.testing.assert_allclose(p[6], [0.0, 0.0, -2.0], atol=1e-15)
    assert p[7:].tolist() == [[-1, 0, -2], [-1, 0.1, -2], [-1, 1, -2], [0.5, 0, -2], [0.5, 0.1, -2], [0.5, 1, -2]]


@pytest.mark.parametrize("text, expected", [
    ("x_m,y_m\n1,2\n", "row 1: z_m: expected a number (m), got None"),
    ("x_m,y_m,z_m\n1,2,3\n1,a,3\n", "row 2: y_m: expected a number (m), got 'a'"),
    ("x_m,y_m,z_m\n1,2,nan\n", "row 1: z_m: expected a finite number"),
    ("x_m,y_m,z_m\n", "expected a header x_m,y_m,z_m and at least one row"),
])
def test_bad_microphone_file_stops_with_file_row_and_field(tmp_path, text, expected):
    (tmp_path / "mics.csv").write_text(text)
    path = write_rig(tmp_path, microphones=[{"kind": "file", "path": "mics.csv"}])
    with pytest.raises(ConfigError) as error:
        load_rig(path)
    assert str(tmp_path / "mics.csv") in str(error.value) and expected in str(error.value)


def test_missing_microphone_file_and_bad_microphone_entry(tmp_path):
    with pytest.raises(ConfigError, match=r"nowhere\.csv: microphone file not found"):
        load_rig(write_rig(tmp_path, microphones=[{"kind": "file", "path": "nowhere.csv"}]))
    with pytest.raises(ConfigError, match=r"case\.yaml: microphones\[0\]\.radius_m: required field is missing"):
        load_rig(write_rig(tmp_path, microphones=[{"kind": "arc", "angles_deg": [0.0], "plane": "xz"}]))
    with pytest.raises(ConfigError, match=r"case\.yaml: condition\.thrust_N: required with control 'rpm'"):
        load_rig(write_rig(tmp_path, condition={"rpm": 3000.0, "control": "rpm", "pitch_deg": 8.0,
                                                        "atmosphere": ATMOSPHERE}))


def test_condition_blade_motion_replaces_the_rotor_files(tmp_path):
    """A condition's higher-harmonic pitch, elastic twist and flap harmonics (e.g. HART-II MN) replace the
    rotor file's in the rotor the stages use; a bad entry stops naming the rig file and the field."""
    motion = {"higher_harmonic_pitch": [{"n": 3, "amplitude_deg": 0.8, "phase_deg": 300.0}],
              "elastic_twist_harmonics": [{"n": 3, "cos_deg": -0.4, "sin_deg": 0.5}],
              "prescribed_flap": [{"n": 0, "cos_deg": 2.1, "sin_deg": 0.0}]}
    rotor = {**ROTOR, "higher_harmonic_pitch": [{"n": 2, "amplitude_deg": 1.0, "phase_deg": 0.0}]}
    condition = {"rpm": 3000.0, "thrust_N": 100.0, "atmosphere": ATMOSPHERE, **motion}
    assert {k: rotor_for_rig(rotor, condition)[k] for k in motion} == motion
    assert load_rig(write_rig(tmp_path, condition=condition))["rotor_config"]["higher_harmonic_pitch"] == \
        motion["higher_harmonic_pitch"]
    bad = {**condition, "higher_harmonic_pitch": [{"n": 3, "amplitude_deg": "0.8 deg", "phase_deg": 300.0}]}
    with pytest.raises(ConfigError, match=r"case\.yaml: condition\.higher_harmonic_pitch\[0\]\.amplitude_deg: .*number"):
        load_rig(write_rig(tmp_path, condition=bad))


def test_missing_airfoil_table_names_the_rotor_file_and_field(tmp_path):
    rotor = {**{k: v for k, v in ROTOR.items() if k != "airfoil"}, "airfoil": {"table": "missing.c81"}}
    with pytest.raises(ConfigError) as error:
        load_rig(write_rig(tmp_path, rotor=rotor))
    assert f"{tmp_path / 'prop.yaml'}: rotor 'prop'.airfoil.table: file not found" in str(error.value)


def test_operating_point_outside_the_polar_stops_the_command_naming_file_and_field(tmp_path, capsys):
    """A polar from −4° to 4° without extrapolation; 20° pitch puts the sections outside it."""
    (tmp_path / "narrow.csv").write_text("alpha_deg,cl,cd\n-4,-0.4,0.01\n0,0,0.008\n4,0.4,0.01\n")
    rotor = {**{k: v for k, v in ROTOR.items() if k != "airfoil"}, "airfoil": {"table": "narrow.csv"}}
    condition = {"rpm": 3000.0, "control": "fixed", "pitch_deg": 20.0, "atmosphere": ATMOSPHERE}
    assert rotor_command(["--rig", str(write_rig(tmp_path, rotor=rotor, condition=condition)),
                          "--out-dir", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and len(err.splitlines()) == 1
    assert str(tmp_path / "narrow.csv") in err and "CL: angle of attack" in err and "outside the table's range" in err


def test_rotor_command_reproduces_closed_form_hover(tmp_path, capsys):
    """Hover, untwisted blade without root cutout, linear lift, no drag, tip loss or compressibility, rigid:
    C_T = (σa/2)(θ/3 − λ/2) with uniform λ = √(C_T/2) (Johnson, Rotorcraft Aeromechanics §3). θ = 8°:
    thrust within 0.5 %, induced power P = T λ ΩR within 1 %; a microphone on the axis hears no tone
    (steady loads on an axisymmetric disk), one in the plane hears BPF 1 loudest."""
    out = tmp_path / "out"
    status = rotor_command(["--rotor-file", str(write_rig(tmp_path).parent / "prop.yaml"), "--rpm", "3000",
                            "--control", "fixed", "--pitch-deg", "8", "--speed-of-sound-mps", "1e9",
                            "--mic", "0", "0", "-5", "--mic", "5", "0", "0", "--n-psi", "36", "--n-r", "100",
                            "--samples-per-rev", "256", "--out-dir", str(out)])
    assert status == 0
    omega, rho, radius = 3000.0 * math.pi / 30.0, 1.225, 0.5
    k = (2 * 0.05 / (math.pi * radius)) * 5.7 / 2.0
    lam = (-k / 2.0 + math.sqrt(k * k / 4.0 + 8.0 * k * math.radians(8.0) / 3.0)) / 4.0
    thrust = 2.0 * lam**2 * rho * math.pi * radius**2 * (omega * radius) ** 2
    row = read_table(out / "trim.parquet").iloc[0]
    assert abs(row["thrust_N"] / thrust - 1.0) < 5e-3
    assert abs(row["power_W"] / (thrust * lam * omega * radius) - 1.0) < 1e-2
    levels = pd.read_csv(out / "levels.csv")
    assert levels.loc[0, "bpf1_db"] < 0.0 < levels.loc[1, "bpf1_db"]
    assert levels.loc[1, "bpf1_db"] > levels.loc[1, "bpf2_db"]
    assert "thrust" in capsys.readouterr().out


def test_rotor_command_with_loads_only_writes_the_loads_and_no_acoustics(tmp_path, capsys):
    """--loads-only (the rig's loads_only): set-up and loads, the same trim as with the acoustics; no acoustics
    directory, no levels."""
    args = ["--rotor-file", str(write_rig(tmp_path).parent / "prop.yaml"), "--rpm", "3000", "--control", "fixed",
            "--pitch-deg", "8", "--mic", "5", "0", "0", "--n-psi", "36", "--n-r", "20", "--samples-per-rev", "128"]
    assert rotor_command([*args, "--loads-only", "--out-dir", str(tmp_path / "loads_only")]) == 0
    assert "loads only (loads_only): no acoustics" in capsys.readouterr().out
    assert rotor_command([*args, "--out-dir", str(tmp_path / "full")]) == 0
    assert not (tmp_path / "loads_only/acoustics").exists() and not (tmp_path / "loads_only/levels.csv").exists()
    assert (tmp_path / "full/levels.csv").exists()
    assert read_table(tmp_path / "loads_only/trim.parquet").equals(read_table(tmp_path / "full/trim.parquet"))
    assert read_table(tmp_path / "loads_only/loads/prop.parquet").equals(read_table(tmp_path / "full/loads/prop.parquet"))


def test_bundled_rigs_validate():
    rigs = {p.stem: load_rig(p) for p in sorted((REPO / "config/rigs").glob("*.yaml"))}
    hart_ii = {"hart_ii_bl", "hart_ii_bl_measured", "hart_ii_mn_measured", "hart_ii_mv_measured"}
    assert set(rigs) == hart_ii | {"itr_hover", "main_tail_rig", "bo105_main_tail_rig"}
    for name in hart_ii:
        assert rigs[name]["microphones_T"].shape == (221, 3)
        assert np.all(rigs[name]["microphones_T"][:, 2] == -2.215)
    assert rigs["itr_hover"]["rotor_config"]["control"] == "fixed"
    # the Bo105-type pair: HART-II main rotor, a teetering delta3 45 deg tail rotor at exactly 5x (common period 1:5)
    main, tail = rigs["bo105_main_tail_rig"]["rotor_configs"]
    assert main["radius_m"] == 2.0 and (tail["hub"], tail["n_blades"], tail["delta3_deg"]) == ("teetering", 2, 45.0)
    assert tail["omega_rad_s"] == 5.0 * main["omega_rad_s"] and tail["radius_m"] == pytest.approx(0.19 * main["radius_m"])


def test_hart_ii_rigs_carry_their_own_wake_and_acoustics():
    """The HART-II carpets are computed with the settings in their rig files, the Beddoes wake with the Betz
    vortex structure and BVISPL of BPF harmonics 6-40, whatever config/config.yaml says; the defaults come
    from the config schema's wake section (nps.app.config.rig_settings)."""
    for name in ("hart_ii_bl", "hart_ii_bl_measured", "hart_ii_mn_measured", "hart_ii_mv_measured"):
        settings = load_rig(REPO / f"config/rigs/{name}.yaml")["settings"]
        assert settings["wake"] == {"model": "beddoes", "A": 0.5, "B": 1.0, "C": 1.1, "D": 0.85, "core_radius_chords": 0.5,
                                    "core_growth": False, "vortex_structure": "betz", "step_deg": 5.0, "unsteady": True,
                                    "free": {}}
        assert settings["acoustics"] == ACOUSTICS and settings["resolution"]["n_psi"] == 360
        assert settings["models"] == {"bvi": True, "thickness": "dual_compact", "broadband": False, "absorption": False}


def test_rig_with_bvi_needs_its_wake_section(tmp_path):
    with pytest.raises(ConfigError, match=r"case\.yaml: wake: required field is missing"):
        load_rig(write_rig(tmp_path, models={"bvi": True}))
    with pytest.raises(ConfigError, match=r"case\.yaml: acoustics"):
        load_rig(write_rig(tmp_path, acoustics={"dual_compact_chord_fractions": [0.13, 0.87]}))


def test_rpm_test_solves_the_speed_once_for_every_stage(tmp_path):
    """control rpm in a rig: the set-up solves Ω to the thrust target (0.1 %) and writes it; the loads stage
    at that Ω meets the target and reports the same Ω, bit for bit."""
    from nps.stages import loads as loads_stage
    from nps.stages import rig as setup_stage

    condition = {"rpm": 3000.0, "control": "rpm", "pitch_deg": 10.0, "thrust_N": 40.0, "atmosphere": ATMOSPHERE}
    path = write_rig(tmp_path, condition=condition)
    setup_stage.run({"config": path}, {"trim": tmp_path / "trim.parquet", "observers": tmp_path / "mics.parquet"}, {})
    row = read_table(tmp_path / "trim.parquet").iloc[0]
    assert row["thrust_N"] == 40.0 and row["omega_rad_s"] != 3000.0 * math.pi / 30.0
    rig = load_rig(path)
    loads_stage.run({"trim": tmp_path / "trim.parquet"}, {"loads": tmp_path / "loads"},
                    {"rotors": {"prop": rig["rotor_config"]}, "n_psi": 36, "n_r": 100, "aircraft": "rigs", "segment": "case"})
    summary = read_table(tmp_path / "loads" / "prop_summary.parquet").set_index("quantity")["value"]
    assert summary["omega_rad_s"] == row["omega_rad_s"] and abs(summary["thrust_N"] / 40.0 - 1.0) <= 1e-3
