"""Messages name each rotor once (issue 35): no ``rotor 'main': rotor 'main':``, no doubled quote ``'main''s``.

A rig's rotor file with a hub or blade error, a rig's station outside a rotor's disk (the rig's list and a rotor's
own), and the set-up's validity refusal of a rotors[] entry: each is one ConfigError or ValidityError line naming
the file, the rotor once and the field.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from nps.app.config import ConfigError, load_rig
from nps.app.validity import ValidityError
from nps.stages import rig as rig_stage

REPO = Path(__file__).resolve().parents[2]
RIG = "main_tail_rig"


def _rig(tmp_path: Path, rotor_extra: str = "", rig_edit=lambda text: text) -> Path:
    """A copy of the bundled main + tail rig with ``rotor_extra`` appended to the main rotor's file."""
    shutil.copytree(REPO / "config/rigs/main_tail", tmp_path / "main_tail")
    main = tmp_path / "main_tail/main.yaml"
    main.write_text(main.read_text() + rotor_extra)
    path = tmp_path / f"{RIG}.yaml"
    path.write_text(rig_edit((REPO / f"config/rigs/{RIG}.yaml").read_text()))
    return path


def _named_once(message: str, rotor: str = "main") -> None:
    assert "\n" not in message and "''" not in message, message
    assert message.count(f"'{rotor}'") == 1, message


CONFIG_CASES = [
    ("teetering_four_blades", "hub: teetering\n", "main.yaml: rotor 'main': n_blades: a teetering hub"),
    ("precone_articulated", "precone_deg: 2.5\n", "main.yaml: rotor 'main': precone_deg: applies to a teetering or "
                                                  "hingeless hub only"),
    ("hingeless_precone_without_spring", "hub: hingeless\nprecone_deg: 2.5\n",
     "main.yaml: rotor 'main': precone_deg: the precone of a hingeless hub is the zero of its flap spring"),
    ("flap_frequency_articulated", "flap_frequency_per_rev: 1.1\n",
     "main.yaml: rotor 'main': flap_frequency_per_rev: applies to a hingeless hub only"),
    ("blade_table_without_chord", None, "blade.csv: chord_over_R: expected exactly one of chord_over_R or chord_m"),
]


@pytest.mark.parametrize("case, extra, expected", CONFIG_CASES, ids=[c[0] for c in CONFIG_CASES])
def test_rotor_file_errors_of_a_rig_name_the_rotor_once(tmp_path, case, extra, expected):
    path = _rig(tmp_path, extra or "")
    if extra is None:  # the main rotor's linear blade replaced by a table without its chord column
        (tmp_path / "blade.csv").write_text("r_over_R,twist_deg\n0.2,0\n1.0,-8\n")
        main = tmp_path / "main_tail/main.yaml"
        kept = [ln for ln in main.read_text().splitlines() if not ln.startswith(("chord_m", "twist_deg", "thickness_ratio"))]
        main.write_text("\n".join(kept) + f"\nblade: {{table: {tmp_path / 'blade.csv'}}}\n")
    with pytest.raises(ConfigError) as error:
        load_rig(path)
    message = str(error.value)
    assert expected in message, message
    _named_once(message)


@pytest.mark.parametrize("edit, expected", [
    (lambda t: t.replace("stations_r_over_R: [0.75, 0.87]", "stations_r_over_R: [0.75, 0.99]"),
     "stations_r_over_R[1]: r/R 0.99 outside the disk stations [0.2333, 0.9667] of rotor 'main'"),
    (lambda t: t.replace("    pitch_deg: 6.0\n", "    pitch_deg: 6.0\n    stations_r_over_R: [0.99]\n"),
     "rotors[1] 'tail'.stations_r_over_R[0]: r/R 0.99 outside the disk stations [0.2333, 0.9667] of the rotor "),
], ids=["rig_list", "rotor_list"])
def test_station_messages_name_the_rotor_once_without_doubled_quotes(tmp_path, edit, expected):
    with pytest.raises(ConfigError) as error:
        load_rig(_rig(tmp_path, rig_edit=edit))
    message = str(error.value)
    assert expected in message, message
    _named_once(message, "main" if "'main'" in expected else "tail")


def test_validity_refusal_of_a_rotors_entry_names_the_rotor_once(tmp_path):
    """Tunnel 100 m/s: μ 0.67 for the main rotor, refused before any solve as `rotors[0] 'main': advance ratio …`."""
    path = _rig(tmp_path, rig_edit=lambda t: t.replace("tunnel_speed_mps: 20.0", "tunnel_speed_mps: 100.0"))
    with pytest.raises(ValidityError) as error:
        rig_stage.run({"config": str(path)}, {"trim": str(tmp_path / "trim.parquet"),
                                             "observers": str(tmp_path / "mics.parquet")}, {})
    message = str(error.value)
    assert f"{path}: rig '{RIG}': rotors[0] 'main': advance ratio mu = 0.665" in message, message
    _named_once(message)
    assert not (tmp_path / "trim.parquet").exists()


def test_a_failed_rotor_solution_names_the_rotor_once():
    """A thrust the rotor cannot give (collective_only, 50 kN on a 0.3 m tail rotor): one TrimError naming the rotor
    once, then its likely inputs."""
    from nps.rotor.bet import DiskGrid, TrimError
    from nps.rotor.control import RotorControl, solve_rotor
    from nps.rotor.geometry import OperatingPoint, RotorGeometry

    g = RotorGeometry(name="tail", n_blades=2, radius_m=0.3, chord_m=0.04, root_cutout_m=0.06, twist_rad=0.0,
                      thickness_ratio=0.12, lock_number=3.0, hub="teetering")
    with pytest.raises(TrimError) as error:
        solve_rotor(g, OperatingPoint(500.0, 0.1, 0.0, 0.0, 1.225, 340.0, 5.0e4), DiskGrid(36, 10),
                    RotorControl("collective_only"))
    message = str(error.value)
    assert message.startswith("rotor 'tail': ") and "; its inputs: omega_rad_s 500 rad/s" in message, message
    _named_once(message, "tail")
