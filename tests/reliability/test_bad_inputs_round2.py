"""Bad-input corpus, second round: the same checks on every entry path, checks across fields, refusals
without tracebacks (docs/reference/validity.md).

Command cases run in process (``nps.__main__.main``) like test_bad_inputs.py, whose helicopter chain
(segment 2, 36 × 10 disk, 64 samples, three observers ahead) they reuse: each must end with exit status 2
and exactly one stderr line ``error: ...`` naming the file or option, the field or quantity and what was
expected; no traceback and no Parquet file written. The rotor and rig cases use the ITR rotor
(config/rigs/itr/rotor.yaml) at 5465 rpm on a 36 × 10 disk. Then: configuration cases of the workflow
(``nps.app.config.load_campaign``, one ``snakemake -n``), a workflow job's expected and unexpected
failures (``nps.stages.job.run_job``) and the model-range warnings of summary.csv.
"""

from __future__ import annotations

import copy
import os
import shutil
import subprocess
import sys
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
from nps.app.config import ConfigError, load_campaign
from nps.app.io import write_table
from test_bad_inputs import REPO, Case, _rewrite, acoustics_cmd, aircraft_file, chain, check_refused, flight, hsi_cmd, \
    loads_cmd, metrics_cmd, observers_cmd, trim_cmd, wake_cmd  # noqa: F401 (chain: the shared fixture)

ITR = REPO / "config/rigs/itr/rotor.yaml"
ITR_RIG = yaml.safe_load((REPO / "config/rigs/itr_hover.yaml").read_text())
SMALL = ["--n-psi", "36", "--n-r", "10", "--samples-per-rev", "64"]
FAR_MIC = ["--mic", "2.0", "0.0", "-1.0"]
AHEAD_ONE = {"kind": "points_ahead", "radius_R": 10.0, "elevations_deg": [0.0]}


def rotor_cmd(out: Path, *extra: str, mic=FAR_MIC, rotor_file=ITR, resolution=SMALL) -> list[str]:
    """``python -m nps rotor`` on the ITR rotor, fixed pitch 9.2° at 5465 rpm unless ``extra`` says otherwise."""
    control = [] if "--control" in extra else ["--control", "fixed", "--pitch-deg", "9.2"]
    speed = [] if "--rpm" in extra or "--omega-rad-s" in extra else ["--rpm", "5465"]
    return ["rotor", "--rotor-file", str(rotor_file), *speed, *control, *extra, *mic, *resolution, "--out-dir",
            str(out / "rotor")]


def _replace(argv: list[str], flag: str, value: str) -> list[str]:
    """``argv`` with the value of ``flag`` replaced."""
    argv = list(argv)
    argv[argv.index(flag) + 1] = value
    return argv


def edited_rotor(out: Path, **fields) -> Path:
    """Copy of the ITR rotor YAML with ``fields`` replaced (its blade and airfoil tables copied along)."""
    data = {**yaml.safe_load(ITR.read_text()), **fields}
    folder = out / "rigs" / "itr"
    shutil.copytree(ITR.parent, folder, dirs_exist_ok=True)
    (folder / "rotor.yaml").write_text(yaml.safe_dump(data, sort_keys=False))
    shutil.copytree(REPO / "config/airfoils", out / "airfoils", dirs_exist_ok=True)
    return folder / "rotor.yaml"


def rig_cmd(out: Path, condition: dict | None = None, microphones: list | None = None, **extra) -> list[str]:
    """``python -m nps rig`` on a copy of config/rigs/itr_hover.yaml (36 × 10 disk) with its condition
    updated by ``condition`` (None values delete a key) and, when given, other microphones."""
    rig = copy.deepcopy(ITR_RIG)
    for key, value in (condition or {}).items():
        if value is None:
            rig["condition"].pop(key, None)
        else:
            rig["condition"][key] = value
    rig.update(microphones=microphones or rig["microphones"], resolution={"n_psi": 36, "n_r": 10, "samples_per_rev": 64},
               **extra)
    shutil.copytree(REPO / "config/rigs/itr", out / "rigs/itr", dirs_exist_ok=True)
    shutil.copytree(REPO / "config/airfoils", out / "airfoils", dirs_exist_ok=True)
    path = out / "rigs/bad_rig.yaml"
    path.write_text(yaml.safe_dump({**rig, "name": "bad_rig"}, sort_keys=False))
    return ["rig", "--rig", str(path), "--out-dir", str(out / "rig")]


def without_metadata(src: Path, dst: Path, edit: Callable = lambda df: df) -> Path:
    """``src`` edited and written with no metadata, as another tool would write it."""
    dst.parent.mkdir(parents=True, exist_ok=True)
    pq.write_table(pa.Table.from_pandas(edit(pq.read_table(src).to_pandas()), preserve_index=False), dst)
    return dst


def _copy_of(path: Path, out: Path) -> str:
    out.mkdir(parents=True, exist_ok=True)
    return str(shutil.copy(path, out / path.name))


def _disks(b, out: Path, edit: Callable, rotor: str = "tail") -> Path:
    """A disk directory whose main.parquet is ``edit`` of the ``rotor``'s loads, without metadata."""
    d = out / "disks"
    without_metadata(b.loads / f"{rotor}.parquet", d / "main.parquet", edit)
    shutil.copy(b.loads / "tail.parquet", d / "tail.parquet")
    return d


def _tail_is_main(b, out: Path) -> Path:
    """A disk directory with the main rotor's loads and, as tail.parquet, the main rotor's again without metadata:
    the tail is refused before the main rotor's signals are written."""
    d = out / "disks"
    d.mkdir(parents=True, exist_ok=True)
    shutil.copy(b.loads / "main.parquet", d / "main.parquet")
    without_metadata(b.loads / "main.parquet", d / "tail.parquet")
    return d


def _first_azimuths(df: pd.DataFrame, n: int = 35) -> pd.DataFrame:
    """The disk table's first ``n`` azimuths, relabelled as a grid of ``n`` azimuths over the revolution."""
    psi = np.sort(df["psi_rad"].unique())[:n]
    kept = df[df["psi_rad"].isin(psi)].copy()
    kept["psi_rad"] = kept["psi_rad"].map(dict(zip(psi, 2.0 * np.pi * np.arange(n) / n)))
    return kept


def _observers(b, out: Path, edit: Callable) -> Path:
    return _rewrite(b.observers, out / "obs" / "ahead.parquet", edit)


def _hemisphere(n_elevation: int, n_azimuth: int) -> dict:
    return {"kind": "hemisphere", "radius_R": 10.0, "n_elevation": n_elevation, "n_azimuth": n_azimuth}


def rotor_edit(index: int, **fields):
    def edit(a):
        a["rotors"][index].update(fields)
    return edit


UH60_AIRFRAME = [[0.0, 0.0, 1.0], [-3.0, 0.0, 0.2], [-6.0, 0.0, 0.0], [-8.0, 0.0, 0.3], [-9.93, 0.66, 1.66]]
"""UH-60A-like airframe points of the bundled helicopter (body frame): fuselage top under the hub, tail boom at
3, 6 and 8 m aft, the fin 0.7 m to port of the tail rotor's plane; all clear of the swept volumes."""


def airframe_points(*extra: list):
    def edit(a):
        a["airframe_points_m"] = UH60_AIRFRAME + [list(p) for p in extra]
    return edit


CASES = [
    # --- one validity gate: python -m nps rotor applies the envelope before it writes -----------------------
    Case("rotor_speed_of_sound_in_km_s", lambda b, out: rotor_cmd(out, "--speed-of-sound-mps", "0.34"),
         ("condition.atmosphere.speed_of_sound_mps = 0.34", "within [100, 600]")),
    Case("rotor_speed_of_sound_34000", lambda b, out: rotor_cmd(out, "--speed-of-sound-mps", "34029"),
         ("speed_of_sound_mps", "within [100, 600]")),
    Case("rotor_density_in_g_m3", lambda b, out: rotor_cmd(out, "--density-kg-m3", "1225"),
         ("condition.atmosphere.density_kg_m3 = 1225", "within [0.05, 10]")),
    Case("rotor_density_0_001", lambda b, out: rotor_cmd(out, "--density-kg-m3", "0.001"), ("density_kg_m3",)),
    Case("rotor_tunnel_500_mps", lambda b, out: rotor_cmd(out, "--speed-mps", "500"),
         ("rotor 'itr': advance ratio mu", "<= 0.5", "source:")),
    Case("rotor_rpm_x10", lambda b, out: rotor_cmd(out, "--rpm", "54650"),
         ("rotor 'itr': hover tip Mach number", "<= 0.95")),
    Case("rotor_omega_rad_s_given_rpm", lambda b, out: rotor_cmd(out, "--omega-rad-s", "5465"), ("hover tip Mach number",)),
    Case("rotor_mic_inside_the_disk", lambda b, out: rotor_cmd(out, mic=["--mic", "0.1", "0.0", "0.0"]),
         ("observer 0", "rotor 'itr' blade path / chord", ">= 5")),
    Case("rotor_mic_at_the_hub", lambda b, out: rotor_cmd(out, mic=["--mic", "0.0", "0.0", "0.0"]),
         ("rotor.yaml: microphones", "observer 0")),
    Case("rotor_mic_above_the_hub", lambda b, out: rotor_cmd(out, mic=["--mic", "2.0", "0.0", "0.0", "--mic", "0.0", "0.0", "0.158"]),
         ("observer 1", "hub / radius", ">= 1")),
    Case("rotor_arc_inside_the_disk", lambda b, out: rotor_cmd(out, mic=["--arc-radius-m", "0.05", "--arc-angles-deg", "0", "-45"]),
         ("rotor 'itr'", "validity limit")),
    Case("rotor_mic_file_inside_the_disk", lambda b, out: rotor_cmd(
        out, mic=["--mic-file", _text_file(out / "mics.csv", "x_m,y_m,z_m\n2.0,0.0,-1.0\n0.12,0.0,0.0\n")]),
         ("observer 1", "blade path / chord")),
    Case("rotor_too_big_for_memory", lambda b, out: rotor_cmd(out, resolution=["--n-psi", "36000", "--n-r", "5000"]),
         ("36000 x 5000", "needs an estimated")),
    Case("rotor_lock_number_1000", lambda b, out: rotor_cmd(out, rotor_file=edited_rotor(out, lock_number=1000.0)),
         ("rotor 'itr': Lock number = 1000", "within [1, 25]")),
    Case("rotor_40_blades", lambda b, out: rotor_cmd(out, rotor_file=edited_rotor(out, n_blades=40)),
         ("rotor 'itr'", "solidity", "expected <= 0.5")),
    # --- contradictory or ignored options, bounded controls --------------------------------------------------
    Case("rotor_fixed_with_a_thrust_target", lambda b, out: rotor_cmd(out, "--control", "fixed", "--pitch-deg", "9.2",
                                                                      "--thrust-n", "50"),
         ("condition.thrust_N (--thrust-n)", "control 'fixed' uses no thrust target")),
    Case("rotor_collective_with_a_pitch", lambda b, out: rotor_cmd(out, "--control", "collective", "--pitch-deg", "9.2",
                                                                   "--thrust-n", "10"),
         ("condition.pitch_deg (--pitch-deg)", "control 'collective' trims the pitch")),
    Case("rotor_rpm_without_a_thrust_target", lambda b, out: rotor_cmd(out, "--control", "rpm", "--pitch-deg", "9.2"),
         ("condition.thrust_N (--thrust-n)", "required with control 'rpm'")),
    Case("rotor_collective_beyond_the_bound", lambda b, out: rotor_cmd(out, "--control", "collective", "--thrust-n", "500"),
         ("rotor 'itr'", "|theta0| < 0.7 rad", "thrust target 500 N", "settings to change")),
    Case("rotor_fixed_pitch_44_deg", lambda b, out: rotor_cmd(out, "--control", "fixed", "--pitch-deg", "44"), ("rotor 'itr'",)),
    Case("rig_fixed_with_a_thrust_target", lambda b, out: rig_cmd(out, {"thrust_N": 50.0}),
         ("bad_rig.yaml", "condition.thrust_N", "control 'fixed'")),
    Case("rig_collective_with_a_pitch", lambda b, out: rig_cmd(out, {"control": "collective", "thrust_N": 10.0}),
         ("bad_rig.yaml", "condition.pitch_deg", "control 'collective'")),
    Case("rig_fixed_with_a_moment_target", lambda b, out: rig_cmd(out, {"roll_moment_Nm": 2.0}),
         ("condition.roll_moment_Nm", "only control 'collective' with flapping")),
    # --- the same gate through python -m nps rig (the workflow's rig stage) -----------------------------------
    Case("rig_speed_of_sound_in_km_s", lambda b, out: rig_cmd(
        out, {"atmosphere": {"density_kg_m3": 1.225, "speed_of_sound_mps": 0.34}}), ("bad_rig.yaml", "speed_of_sound_mps = 0.34")),
    Case("rig_density_in_g_m3", lambda b, out: rig_cmd(
        out, {"atmosphere": {"density_kg_m3": 1225.0, "speed_of_sound_mps": 340.0}}), ("bad_rig.yaml", "density_kg_m3 = 1225")),
    Case("rig_tunnel_500_mps", lambda b, out: rig_cmd(out, {"tunnel_speed_mps": 500.0}), ("bad_rig.yaml", "advance ratio mu")),
    Case("rig_microphone_in_the_disk", lambda b, out: rig_cmd(out, microphones=[{"kind": "point", "positions_m": [[0.1, 0.0, 0.0]]}]),
         ("bad_rig.yaml", "blade path / chord")),
    Case("rig_rpm_x10", lambda b, out: rig_cmd(out, {"rpm": 54650.0}), ("bad_rig.yaml", "hover tip Mach number")),
    # --- an output never overwrites an input ------------------------------------------------------------------
    Case("metrics_out_is_the_observers", lambda b, out: _replace(
        metrics_cmd(b, out, observers=_copy_of(b.observers, out / "o")), "--out", str(out / "o" / "ahead.parquet")),
         ("metrics", "ahead.parquet: is the input observers", "expected an output path that is no input")),
    Case("metrics_bands_out_is_the_trim", lambda b, out: _replace(
        metrics_cmd(b, out, trim=_copy_of(b.trim, out / "t")), "--bands-out", str(out / "t" / "trim.parquet")),
         ("bands", "is the input trim")),
    Case("metrics_figure_is_the_observers", lambda b, out: metrics_cmd(b, out, "--figure", _copy_of(b.observers, out / "o"),
                                                                    observers=out / "o" / "ahead.parquet"),
         ("figure", "is the input observers")),
    Case("metrics_out_in_the_signals_directory", lambda b, out: _replace(
        metrics_cmd(b, out, signals=_signals_copy(b, out)), "--out", str(out / "sig" / "main.parquet")),
         ("sig/main.parquet", "lies in the input directory signals")),
    Case("trim_out_is_the_aircraft_file", lambda b, out: _replace(
        trim_cmd(out, aircraft_file(out, lambda a: None)), "--out", str(out / "aircraft" / "helicopter.yaml")),
         ("--out", "expected a path ending in .parquet", "helicopter.yaml")),  # no Parquet name: refused first
    Case("loads_out_dir_is_the_trim", lambda b, out: _replace(
        loads_cmd(b, out, trim=_copy_of(b.trim, out / "t")), "--out-dir", str(out / "t" / "trim.parquet")),
         ("trim.parquet", "is the input trim")),
    Case("acoustics_out_dir_is_the_disks", lambda b, out: _replace(
        acoustics_cmd(b, out, disks=_loads_copy(b, out)), "--out-dir", str(out / "l")), ("is the input disks",)),
    Case("hsi_out_dir_is_the_signals", lambda b, out: _replace(
        hsi_cmd(b, out, signals=_signals_copy(b, out)), "--out-dir", str(out / "sig")), ("is the input signals",)),
    Case("observers_out_is_the_trim", lambda b, out: _replace(_replace(
        observers_cmd(b, out, AHEAD_ONE), "--trim", _copy_of(b.trim, out / "t")), "--out", str(out / "t" / "trim.parquet")),
         ("trim.parquet", "is the input trim")),
    Case("observers_out_is_the_config", lambda b, out: _replace(observers_cmd(b, out, AHEAD_ONE), "--out", str(out / "config.yaml")),
         ("--out", "expected a path ending in .parquet", "config.yaml")),
    Case("tones_csv_is_the_aircraft_file", lambda b, out: ["tones", "--aircraft", aircraft_file(out, lambda a: None), "--trim",
                                                          str(b.trim), "--signals", str(b.signals), "--out", str(out / "t.parquet"),
                                                          "--csv", str(out / "aircraft" / "helicopter.yaml"),
                                                          "--spectra-out", str(out / "s.parquet")],
         ("--csv", "expected a path ending in .csv", "helicopter.yaml")),
    Case("wake_dir_is_the_loads_dir", lambda b, out: _wake_into_loads(b, out), ("is the input loads",)),
    Case("rotor_out_dir_holds_the_rotor_file", lambda b, out: _replace(
        rotor_cmd(out, rotor_file=edited_rotor(out)), "--out-dir", str(out / "rigs" / "itr")),
         ("rotor.yaml", "--rotor-file")),
    # --- a loads table is of the rotor it is radiated for ----------------------------------------------------
    Case("acoustics_tail_loads_renamed_without_metadata", lambda b, out: acoustics_cmd(b, out, disks=_disks(b, out, lambda df: df)),
         ("disks/main.parquet", "r_m", "expected the radius 7.62 m of rotor 'main'")),
    Case("acoustics_main_loads_as_tail_writes_no_main_signals", lambda b, out: acoustics_cmd(b, out, disks=_tail_is_main(b, out)),
         ("disks/tail.parquet", "expected the radius 1.55 m of rotor 'tail'")),
    Case("acoustics_radius_scaled_without_metadata", lambda b, out: acoustics_cmd(b, out, disks=_disks(
        b, out, lambda df: df.assign(r_m=df.r_m * 0.3048, dr_m=df.dr_m * 0.3048), rotor="main")), ("r_m", "radius 7.62 m")),
    Case("acoustics_azimuths_shifted", lambda b, out: acoustics_cmd(b, out, disks=_disks(
        b, out, lambda df: df.assign(psi_rad=df.psi_rad + 0.01), rotor="main")), ("disks/main.parquet", "psi_rad", "2 pi i/n_psi")),
    Case("acoustics_azimuths_not_for_the_blades", lambda b, out: acoustics_cmd(b, out, disks=_disks(b, out, _first_azimuths, "main")),
         ("psi_rad", "35 azimuths", "multiple of the 4 blades")),
    Case("acoustics_radii_missing_at_an_azimuth", lambda b, out: acoustics_cmd(b, out, disks=_disks(b, out, lambda df: df.iloc[1:], "main")),
         ("psi_rad", "same 10 radii")),
    # --- observer ids unique ------------------------------------------------------------------------------------
    Case("acoustics_every_observer_id_0", lambda b, out: acoustics_cmd(b, out, observers=_observers(b, out, lambda df: df.assign(observer=0))),
         ("ahead.parquet", "observer: expected unique ids", "[0] repeat")),
    Case("acoustics_one_observer_id_twice", lambda b, out: acoustics_cmd(b, out, observers=_observers(
        b, out, lambda df: df.assign(observer=[0, 1, 1]))), ("observer: expected unique ids", "[1]")),
    Case("metrics_every_observer_id_0", lambda b, out: metrics_cmd(b, out, observers=_observers(b, out, lambda df: df.assign(observer=0))),
         ("ahead.parquet", "observer: expected unique ids", "[0] repeat")),
    Case("hsi_one_observer_id_twice", lambda b, out: hsi_cmd(b, out, observers=_observers(
        b, out, lambda df: df.assign(observer=[0, 1, 1]))), ("ahead.parquet", "observer: expected unique ids", "[1]")),
    # --- every rotor checked before the first rotor's tables are written ------------------------------------------
    Case("loads_tail_refused_writes_no_main_loads", lambda b, out: loads_cmd(b, out, trim=_rewrite(
        b.trim, out / "t" / "trim.parquet", lambda df: df.assign(thrust_N=np.where(df.rotor == "tail", 30 * df.thrust_N, df.thrust_N)))),
         ("rotor 'tail'",)),
    Case("wake_tail_summary_without_ct_writes_no_main_wake", lambda b, out: _wake_with_loads(b, out, lambda l: _rewrite(
        b.loads / "tail_summary.parquet", l / "tail_summary.parquet", lambda df: df[df.quantity != "ct"])),
         ("tail_summary.parquet", "quantity 'ct'")),
    Case("wake_tail_disk_without_rows_at_an_azimuth_writes_no_main_wake", lambda b, out: _wake_with_loads(b, out, lambda l: _rewrite(
        b.loads / "tail.parquet", l / "tail.parquet", lambda df: df.iloc[1:])),
         ("l/tail.parquet", "psi_rad/r_m do not form a full grid")),
    Case("metrics_auto_without_disks", lambda b, out: metrics_cmd(b, out, "--broadband", "auto"), ("--broadband auto needs --disks",)),
    # --- memory of observer sets before allocation --------------------------------------------------------------
    Case("observers_hemisphere_1e4_x_1e5", lambda b, out: observers_cmd(b, out, _hemisphere(10_000, 100_000)),
         ("config.yaml", "observer_sets.s", "1,000,000,000 observers", "needs an estimated")),
    # --- checks across fields: swept disks, the rotor to blame ----------------------------------------------------
    Case("tail_disk_crosses_the_main_blade_path", flight(30.0, 0.0, rotor_edit(1, hub_position_m=[-8.5, 0.0, 1.9])),
         ("rotors[1]", "rotor 'tail'", "crosses the blade path of rotor 'main'")),
    Case("tail_in_the_main_flapping_margin", flight(30.0, 0.0, rotor_edit(1, hub_position_m=[-7.0, 0.0, 3.4], radius_m=1.0)),
         ("rotors[1]", "crosses the blade path of rotor 'main'", "flapping margin")),
    Case("main_100_blades", flight(30.0, 0.0, rotor_edit(0, n_blades=100)),
         ("rotors[0]", "rotor 'main': 100 blades", "solidity", "expected <= 0.5")),
    Case("tail_40_blades", flight(30.0, 0.0, rotor_edit(1, n_blades=40)), ("rotors[1]", "rotor 'tail': 40 blades")),
    Case("main_chord_in_mm", flight(30.0, 0.0, rotor_edit(0, chord_m=580.0)), ("rotors[0]", "rotor 'main'", "chord_m")),
    # --- rotor-airframe clearance: airframe points outside the swept volumes -------------------------------------
    Case("tail_boom_under_the_flapping_main_blades", flight(30.0, 0.0, airframe_points([-7.0, 0.0, 0.5])),
         ("helicopter.yaml", "airframe_points_m[5]", "rotor 'main'", "6.92 m from its axis", "1.66 m from its plane",
          "expected the airframe clear")),
    Case("fin_in_the_tail_rotor_disk", flight(30.0, 0.0, airframe_points([-9.33, 0.188, 1.832])),
         ("airframe_points_m[5]", "rotor 'tail'", "0.2 m from its plane", "at least one chord 0.23 m")),
    Case("airframe_point_in_the_main_hub_plane", flight(30.0, 0.0, airframe_points([-4.0, 2.0, 1.6])),
         ("airframe_points_m[5]", "rotor 'main'", "0.409 m from its plane")),
    Case("airframe_point_of_two_coordinates", flight(30.0, 0.0, airframe_points([-4.0, 2.0])),
         ("helicopter.yaml", "airframe_points_m")),
    # --- solver failures name the likely inputs --------------------------------------------------------------------
    Case("loads_trim_omega_in_rpm", lambda b, out: loads_cmd(b, out, trim=_rewrite(
        b.trim, out / "t" / "trim.parquet", lambda df: df.assign(omega_rad_s=np.where(df.rotor == "main", df.omega_rad_s * 30 / np.pi,
                                                                                      df.omega_rad_s)))),
         ("rotor 'main'", "omega_rad_s", "omega in rpm?", "settings to change")),
]


def _text_file(path: Path, text: str) -> str:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return str(path)


def _signals_copy(b, out: Path) -> str:
    return str(shutil.copytree(b.signals, out / "sig"))


def _loads_copy(b, out: Path) -> str:
    return str(shutil.copytree(b.loads, out / "l"))


def _wake_with_loads(b, out: Path, edit: Callable[[Path], object]) -> list[str]:
    """``python -m nps wake`` on a copy of the chain's loads directory changed by ``edit(directory)``."""
    argv = wake_cmd(b, out)
    loads = Path(_loads_copy(b, out))
    edit(loads)
    argv[argv.index("--loads-dir") + 1] = str(loads)
    return argv


def _wake_into_loads(b, out: Path) -> list[str]:
    argv = wake_cmd(b, out)
    argv[argv.index("--loads-dir") + 1] = _loads_copy(b, out)
    argv[argv.index("--wake-dir") + 1] = str(out / "l")
    return argv


def test_corpus_size():
    assert len(CASES) >= 40 and len({c.id for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_input_is_one_clear_line(case, chain, tmp_path, capsys):
    check_refused(case, chain, tmp_path, capsys)
    assert not (tmp_path / "rotor").exists() and not (tmp_path / "rig").exists()  # nothing left behind


def test_the_bundled_rig_passes_the_gate(tmp_path, capsys):
    """The ITR hover rig runs through the gate and writes its artifacts without a warning key."""
    assert nps_main(rig_cmd(tmp_path)) == 0
    from nps.app.io import read_metadata

    assert "validity_warnings" not in read_metadata(tmp_path / "rig" / "trim.parquet")


def test_the_rig_switch_records_the_findings(tmp_path, capsys):
    """allow_outside_validity: true in the rig: the microphone in the disk is written with its warning."""
    assert nps_main(rig_cmd(tmp_path, microphones=[{"kind": "point", "positions_m": [[0.1, 0.0, 0.0]]}],
                            allow_outside_validity=True)) == 0
    from nps.app.io import read_metadata

    warnings = read_metadata(tmp_path / "rig" / "microphones.parquet")["validity_warnings"]
    assert any("blade path / chord" in w["quantity"] for w in warnings)
    assert "warning: observer 0" in capsys.readouterr().out


def test_the_rotor_switch_records_the_findings(tmp_path, capsys):
    """python -m nps rotor --allow-outside-validity: the microphone in the disk runs, with its warning recorded."""
    assert nps_main(rotor_cmd(tmp_path, "--allow-outside-validity", mic=["--mic", "0.1", "0.0", "0.0"])) == 0
    from nps.app.io import read_metadata

    warnings = read_metadata(tmp_path / "rotor" / "microphones.parquet")["validity_warnings"]
    assert any("blade path / chord" in w["quantity"] for w in warnings)
    assert "warning: observer 0" in capsys.readouterr().out


# --- the workflow: configuration refused before the first job --------------------------------------------------

BUNDLED = yaml.safe_load((REPO / "config/config.yaml").read_text())


def _campaign_error(edit: Callable[[dict], None]) -> str:
    config = copy.deepcopy(BUNDLED)
    edit(config)
    with pytest.raises(ConfigError) as error:
        load_campaign(config, "config/config.yaml", root=REPO)
    return str(error.value)


@pytest.mark.parametrize("name, edit, expect", [
    ("hemisphere_1e4_x_1e5", lambda c: c["observer_sets"]["hemisphere"].update(n_elevation=10_000, n_azimuth=100_000),
     ("observer_sets.hemisphere", "1,000,000,000 observers", "needs an estimated", "MB available")),
    ("ground_grid_1e5_x_1e5", lambda c: c["observer_sets"]["ground"].update(n_x=100_000, n_y=100_000),
     ("observer_sets.ground", "observers", "needs an estimated")),
    ("resolution_36000_x_5000", lambda c: c["resolution"].update(n_psi=36000, n_r=5000),
     ("resolution", "36000 x 5000", "needs an estimated")),
], ids=["hemisphere_1e4_x_1e5", "ground_grid_1e5_x_1e5", "resolution_36000_x_5000"])
def test_campaign_too_big_for_memory_is_refused_at_validation(name, edit, expect):
    message = _campaign_error(edit)
    assert "\n" not in message and message.startswith("config/config.yaml: "), message
    for text in expect:
        assert text in message, (text, message)


def test_workflow_refuses_the_huge_hemisphere_before_the_first_job(tmp_path):
    config = copy.deepcopy(BUNDLED)
    config["observer_sets"]["hemisphere"].update(n_elevation=10_000, n_azimuth=100_000)
    shutil.copytree(REPO / "config", tmp_path / "config")
    (tmp_path / "config/config.yaml").write_text(yaml.safe_dump(config))
    result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(tmp_path), "-n", "all"],
                            capture_output=True, text=True, timeout=300)
    errors = [line for line in result.stderr.splitlines() if line.startswith("NPS configuration error")]
    assert result.returncode != 0
    assert len(errors) == 1 and "observer_sets.hemisphere" in errors[0] and "needs an estimated" in errors[0], result.stderr[-3000:]
    assert "Traceback" not in result.stderr + result.stdout
    assert not (tmp_path / "results").exists()


def test_workflow_job_refusal_is_one_line_without_traceback(tmp_path):
    """A trim job refused by the validity envelope (200 m/s): one ``error: stage 'trim'`` line in the terminal
    and the job's log, no Python traceback, no trim artifact."""
    shutil.copytree(REPO / "config", tmp_path / "config")
    mission_path = tmp_path / "config/missions/demo.yaml"
    mission = yaml.safe_load(mission_path.read_text())
    next(s for s in mission["segments"] if s["id"] == "seg2")["aircraft"]["helicopter"]["forward_speed_mps"] = 200.0
    mission_path.write_text(yaml.safe_dump(mission, sort_keys=False))
    env = dict(os.environ)
    env.pop("NPS_DEBUG", None)
    result = subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(tmp_path), "-j1",
                             "results/helicopter/seg2/trim.parquet"], capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode != 0
    ours = [line for line in result.stderr.splitlines() if line.startswith("error: stage 'trim': ")]
    assert len(ours) == 1 and "advance ratio mu" in ours[0], result.stderr[-3000:]
    assert "Traceback" not in result.stderr + result.stdout
    log = (tmp_path / "results/logs/trim/helicopter/seg2.log").read_text().splitlines()
    assert log == ours
    assert not (tmp_path / "results/helicopter/seg2/trim.parquet").exists()


# --- a workflow job: expected refusals are one line, unexpected errors keep their traceback ------------------------

class _Named(dict):
    """Snakemake's named lists: a dict with ``items()`` and ``get`` (and attribute access is not needed)."""


def _job(tmp_path: Path, trim: Path) -> SimpleNamespace:
    return SimpleNamespace(threads=1, rule="loads", params=_Named(rotors={}, n_psi=36, n_r=10, code="x"),
                           wildcards=_Named(aircraft="helicopter", segment="seg2"), input=_Named(trim=str(trim)),
                           output=_Named(loads=str(tmp_path / "loads")), log=[str(tmp_path / "job.log")])


def _run_job(job, capsys) -> tuple[str, str]:
    from unittest import mock

    from nps.stages.job import run_job

    # run_job sizes numba's thread pool through the environment (a job is a fresh process); restore it, or
    # numba refuses to change the size of this test process's running pool later
    with mock.patch.dict(os.environ), pytest.raises(SystemExit) as exit_:
        run_job(job, "loads")
    assert exit_.value.code == 1
    return Path(job.log[0]).read_text(), capsys.readouterr().err


def test_job_expected_refusal_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.delenv("NPS_DEBUG", raising=False)
    log, err = _run_job(_job(tmp_path, tmp_path / "none.parquet"), capsys)
    for text in (log, err):
        lines = [line for line in text.splitlines() if line.strip()]
        assert len(lines) == 1 and lines[0].startswith("error: stage 'loads': ") and "none.parquet" in lines[0], text
        assert "Traceback" not in text
    assert not (tmp_path / "loads").exists()


def test_job_expected_refusal_with_nps_debug_keeps_the_traceback(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("NPS_DEBUG", "1")
    log, err = _run_job(_job(tmp_path, tmp_path / "none.parquet"), capsys)
    assert "Traceback" in log and "Traceback" in err and "none.parquet" in log


def test_job_unexpected_error_keeps_the_traceback(tmp_path, capsys, monkeypatch):
    import nps.stages

    def broken(inputs, outputs, params):
        raise ZeroDivisionError("a bug")

    monkeypatch.delenv("NPS_DEBUG", raising=False)
    monkeypatch.setattr(nps.stages, "stage_function", lambda stage: broken)
    log, err = _run_job(_job(tmp_path, tmp_path / "none.parquet"), capsys)
    assert "Traceback" in log and "ZeroDivisionError" in err and "a bug" in log


# --- warnings recorded where the user looks ------------------------------------------------------------------------

def test_pegg_outside_its_range_reaches_summary_csv(chain, tmp_path):
    """Metrics computed with Pegg broadband: every rotor outside Pegg's data range is listed in summary.csv's
    validity_warnings, with BPM suggested; without broadband, nothing."""
    from nps.stages.summary import model_range_notes, validity_warnings

    trim = pd.read_parquet(chain.trim)
    table = pd.DataFrame({"observer": [0]})
    with_pegg, without = tmp_path / "pegg.parquet", tmp_path / "none.parquet"
    write_table(table, with_pegg, stage="metrics", metadata={"broadband": "pegg"})
    write_table(table, without, stage="metrics", metadata={"broadband": "none"})
    notes = model_range_notes([with_pegg], trim, ["main", "tail"])
    assert any("rotor 'tail'" in n and "radius_m=1.55" in n and "models.broadband: bpm" in n for n in notes), notes
    assert model_range_notes([without], trim, ["main", "tail"]) == []
    column = validity_warnings([without], notes)
    assert column == " | ".join(dict.fromkeys(notes)) and "Pegg: rotor 'tail'" in column


def test_broadband_auto_chooses_bpm_where_pegg_is_outside_its_range(chain):
    from nps.app.broadband import rotor_broadband_models

    trim = pd.read_parquet(chain.trim)
    assert rotor_broadband_models("auto", trim, ["main", "tail"]) == {"main": "pegg", "tail": "bpm"}
    assert rotor_broadband_models("pegg", trim, ["main", "tail"]) == {"main": "pegg", "tail": "pegg"}
    assert rotor_broadband_models(False, trim, ["main"]) == {"main": "none"}


def _bands_msp(path: Path) -> np.ndarray:
    bands = pd.read_parquet(path)
    return 10.0 ** (bands[bands.source == "broadband"].sort_values(["observer", "band"]).level_db.to_numpy() / 10.0)


def _one_rotor_metrics(b, out: Path, rotor: str, *extra: str) -> int:
    """``python -m nps metrics`` on the chain's ``rotor`` alone (its trim row and signals)."""
    trim = _rewrite(b.trim, out / "trim.parquet", lambda df: df[df.rotor == rotor].reset_index(drop=True))
    (out / "sig").mkdir(parents=True)
    shutil.copy(b.signals / f"{rotor}.parquet", out / "sig" / f"{rotor}.parquet")
    return nps_main(metrics_cmd(b, out, "--rotor", rotor, *extra, trim=trim, signals=out / "sig"))


def test_broadband_auto_on_the_helicopter_is_pegg_on_main_and_bpm_on_tail(chain, tmp_path):
    """``--broadband auto`` on the bundled helicopter (segment 2): the main rotor gets Pegg, the tail rotor BPM; the
    broadband bands are the energy sum of Pegg on the main rotor alone and BPM on the tail rotor alone (1e-9 dB).
    The metadata keep ``auto`` with the choice per rotor; Pegg on both rotors records the tail's range warnings."""
    from nps.app.io import read_metadata

    assert nps_main(metrics_cmd(chain, tmp_path / "auto", "--broadband", "auto", "--disks", str(chain.loads))) == 0
    meta = read_metadata(tmp_path / "auto" / "m.parquet")
    assert meta["broadband"] == "auto" and meta["broadband_rotors"] == {"main": "pegg", "tail": "bpm"}
    assert not any(w.startswith("Pegg") for w in meta.get("model_warnings", []))
    assert _one_rotor_metrics(chain, tmp_path / "main", "main", "--broadband", "pegg") == 0
    assert _one_rotor_metrics(chain, tmp_path / "tail", "tail", "--broadband", "bpm", "--disks", str(chain.loads)) == 0
    np.testing.assert_allclose(10 * np.log10(_bands_msp(tmp_path / "auto" / "b.parquet")),
                               10 * np.log10(_bands_msp(tmp_path / "main" / "b.parquet") + _bands_msp(tmp_path / "tail" / "b.parquet")),
                               atol=1e-9)
    assert nps_main(metrics_cmd(chain, tmp_path / "pegg", "--broadband", "pegg")) == 0
    warned = read_metadata(tmp_path / "pegg" / "b.parquet")["model_warnings"]
    assert any("Pegg: rotor 'tail'" in w and "radius_m=1.55" in w for w in warned) and not any("'main'" in w for w in warned)
    assert "model_warnings" not in read_metadata(tmp_path / "main" / "m.parquet")


def test_uh60_airframe_points_clear_the_bundled_helicopter(tmp_path):
    from nps.app.config import load_aircraft

    assert load_aircraft(aircraft_file(tmp_path, airframe_points()))["airframe_points_m"] == UH60_AIRFRAME


def test_loads_refusal_of_the_tail_rotor_leaves_no_main_rotor_table(chain, tmp_path, capsys, monkeypatch):
    """A validity finding on the second rotor (the tail's flap angle, made to exceed 15°) refuses the loads job
    before the main rotor's tables are written."""
    from nps.app import validity

    real = validity.loads_findings
    monkeypatch.setattr(validity, "loads_findings", lambda name, summary: real(name, summary) + (
        [validity.check_flap_angle(0.3, 0.0, 0.0, name)] if name == "tail" else []))
    check_refused(Case("loads_tail_flap_angle", lambda b, out: loads_cmd(b, out), ("rotor 'tail': largest flap angle",)),
                  chain, tmp_path, capsys)
    assert not (tmp_path / "loads").exists() or not any((tmp_path / "loads").iterdir())
