"""Bad inputs of a rig with several rotors (``rotors:``): each stops before any computation with one line that
names the file, the rotor and the field — through nps.app.config.load_rig and through ``python -m nps rig``
(exit status 2, one line on stderr)."""

import copy
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from nps.app.config import ConfigError, load_rig

REPO = Path(__file__).resolve().parents[2]
BUNDLED = yaml.safe_load((REPO / "config" / "rigs" / "main_tail_rig.yaml").read_text())


def _both(rig):
    rig["rotor"] = {"file": "main_tail/main.yaml"}


def _duplicate(rig):
    rig["rotors"][1]["rotor"] = {"file": "main_tail/main.yaml"}
    rig["rotors"][1]["hub_position_m"] = [10.0, 0.0, 0.0]


def _overlap(rig):
    rig["rotors"][1]["hub_position_m"] = [1.0, 0.0, 0.0]  # the tail disk through the main rotor's


def _coaxial_coincident(rig):
    rig["rotors"][1].update(rotor={"file": "main_tail/main.yaml"}, name="lower", hub_position_m=[0.0, 0.0, 0.05],
                            lateral_angle_deg=0.0, shaft_angle_deg=4.0)


def _no_thrust(rig):
    del rig["rotors"][0]["thrust_N"]


def _thrust_with_fixed(rig):
    rig["rotors"][1]["thrust_N"] = 50.0


def _rotor_field_in_condition(rig):
    rig["condition"]["rpm"] = 1000.0


def _rpm_coupled(rig):
    rig["rotors"][1].update(control="rpm", thrust_N=50.0)


def _station_outside(rig):
    rig["stations_r_over_R"] = [0.99]


def _own_station_outside(rig):
    rig["rotors"][1]["stations_r_over_R"] = [0.5, 0.99]


def _carpet_loads_only(rig):
    rig["carpet"], rig["loads_only"] = True, True


def _collective_only_coupled(rig):
    rig["rotors"][1].update(control="collective_only", thrust_N=60.0)
    del rig["rotors"][1]["pitch_deg"]


CASES = [
    ("both_forms", _both, "rotor, rotors: expected exactly one of rotor (one rotor) and rotors (several), got both"),
    ("duplicate_names", _duplicate, "rotors[1].name: rotor name 'main' is also rotors[0]'s"),
    ("overlapping_disks", _overlap, "rotors[1] 'tail'.hub_position_m: the disk of rotor 'tail'"),
    ("coincident_coaxial", _coaxial_coincident, "rotors[1] 'lower'.hub_position_m: the disk of rotor 'lower'"),
    ("missing_thrust_target", _no_thrust, "rotors[0] 'main'.thrust_N: required with control 'collective'"),
    ("thrust_with_fixed", _thrust_with_fixed, "rotors[1] 'tail'.thrust_N: got 50.0, but control 'fixed'"),
    ("rotor_field_in_condition", _rotor_field_in_condition, "condition.rpm: with rotors, each rotor gives its own rpm"),
    ("rpm_coupled", _rpm_coupled, "rotors[1] 'tail'.control: 'rpm' is not available for a rotor coupled"),
    ("station_outside", _station_outside, "stations_r_over_R[0]: r/R 0.99 outside the disk stations [0.2333, 0.9667] "
                                          "of rotor 'main' (resolution.n_r 12)"),
    ("own_station_outside", _own_station_outside, "rotors[1] 'tail'.stations_r_over_R[1]: r/R 0.99 outside the disk "
                                                  "stations [0.2333, 0.9667] of the rotor "),
    ("carpet_loads_only", _carpet_loads_only, "carpet: true with loads_only: the carpet is drawn from the acoustics"),
    ("collective_only_coupled", _collective_only_coupled, "rotors[1] 'tail'.control: 'collective_only' is not "
                                                          "available for a rotor coupled"),
]


def _write(tmp_path: Path, edit) -> Path:
    shutil.copytree(REPO / "config" / "rigs" / "main_tail", tmp_path / "main_tail")
    rig = copy.deepcopy(BUNDLED)
    rig["name"] = "bad_rig"
    edit(rig)
    path = tmp_path / "bad_rig.yaml"
    path.write_text(yaml.safe_dump(rig, sort_keys=False))
    return path


@pytest.mark.parametrize("case, edit, expected", CASES, ids=[c[0] for c in CASES])
def test_bad_multirotor_rig_gives_one_clear_message(tmp_path, case, edit, expected):
    path = _write(tmp_path, edit)
    with pytest.raises(ConfigError) as error:
        load_rig(path)
    message = str(error.value)
    assert message.startswith(f"{path}: ") and "\n" not in message, message
    assert expected in message, message


@pytest.mark.parametrize("case, edit, expected", CASES[:3], ids=[c[0] for c in CASES[:3]])
def test_bad_multirotor_rig_through_the_command(tmp_path, case, edit, expected):
    path = _write(tmp_path, edit)
    result = subprocess.run([sys.executable, "-m", "nps", "rig", "--rig", str(path), "--out-dir", str(tmp_path / "out")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2 and expected in result.stderr, result.stderr
    assert len(result.stderr.strip().splitlines()) == 1 and not (tmp_path / "out" / "trim.parquet").exists()


def test_the_bundled_rig_is_valid():
    rig = load_rig(REPO / "config" / "rigs" / "main_tail_rig.yaml")
    assert [r["control"] for r in rig["rotor_configs"]] == ["collective", "fixed"]


def test_speeds_without_a_common_period_are_refused(tmp_path):
    """wake.free.common_period with a tail rotor at 5.02x and a 0.1 % tolerance: no fraction within 16 turns of
    the main rotor; refused at load (before any computation) naming the file, the field and the best fraction."""
    def tail_at(tolerance):
        def edit(rig):
            rig["rotors"][1]["omega_rad_s"] = 502.0
            rig["wake"]["free"]["period_tolerance"] = tolerance
        return edit

    with pytest.raises(ConfigError, match=r"bad_rig.yaml: wake.free.common_period: no common period of the "
                                          r"rotors \('main' 100 rad/s, 'tail' 502 rad/s\) within 16 revolutions"):
        load_rig(_write(tmp_path / "strict", tail_at(0.001)))
    # 5:1 within 0.4 %: accepted (an approximated period)
    assert load_rig(_write(tmp_path / "loose", tail_at(0.005)))["name"] == "bad_rig"
