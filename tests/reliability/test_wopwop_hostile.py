"""Hostile PSU-WOPWOP cases through the command ``nps wopwop run``: one line on stderr naming the file and the
byte or the namelist field, exit status 2, no traceback, no output written.

A valid case is made once (an NPS rotor exported: compact geometry, periodic loading, an observer file), then each
test corrupts one file of a copy: truncated geometry, a wrong magic number, a zone count that overruns the file, a
negative size, NaN in the loading, float size 2, a loading file whose time keys do not match its geometry, text in
the observer file, an unknown AngleType, an unknown CB field, a CB count overrunning the file.
"""

from __future__ import annotations

import math
import shutil
import struct

import numpy as np
import pandas as pd
import pytest

from nps.__main__ import main
from nps.noise.acoustics import TimeGrid
from nps.noise.observers import points
from nps.noise.sources import ThicknessModel
from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.wopwop import binary
from nps.wopwop.export import RotorCase, export_case
from tests.trim_tables import complete_trim

GEOMETRY, LOADING, OBSERVERS, CASE = "r_geometry.dat", "r_loading.dat", "obs.xyz", "case.nam"


@pytest.fixture(scope="module")
def valid_case(tmp_path_factory):
    geometry = RotorGeometry(name="r", n_blades=2, radius_m=1.0, chord_m=0.1, root_cutout_m=0.2, twist_rad=-0.1,
                             thickness_ratio=0.12, lock_number=5.0)
    op = OperatingPoint(omega_rad_s=60.0, mu_x=0.1, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225, speed_of_sound_mps=340.0,
                        thrust_N=1.0)
    disk = bet.rotor_loads(geometry, op, bet.DiskGrid(12, 5), bet.Controls(math.radians(6.0), 0.0, math.radians(-2.0))).disk
    row = complete_trim(pd.DataFrame([{"rotor": "r", "n_blades": np.int32(2), "omega_rad_s": 60.0, "radius_m": 1.0,
                                       "vel_x_mps": 6.0, "speed_of_sound_mps": 340.0}])).iloc[0].to_dict()
    observers = points([[5.0, 1.0, -2.0], [-4.0, 3.0, -1.0]])
    grid = TimeGrid(0.0, 2.0 * math.pi / 60.0, 32)
    return export_case([RotorCase("r", disk, row)], observers, grid, ThicknessModel(), tmp_path_factory.mktemp("c") / "case",
                       "hostile", "obs")


@pytest.fixture
def case(valid_case, tmp_path):
    copy = tmp_path / "case"
    shutil.copytree(valid_case, copy)
    return copy


def _run(case, tmp_path, capsys) -> str:
    """Run the command; assert the refusal's form; return its line."""
    out = tmp_path / "out"
    status = main(["wopwop", "run", str(case), "--out-dir", str(out)])
    err = capsys.readouterr().err.strip()
    assert status == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert not out.exists() or not any(out.rglob("*")), sorted(out.rglob("*"))
    return err


def _patch_bytes(path, offset: int, data: bytes) -> None:
    raw = bytearray(path.read_bytes())
    raw[offset:offset + len(data)] = data
    path.write_bytes(bytes(raw))


def _edit_text(path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new, 1))


def test_the_valid_case_runs(valid_case, tmp_path, capsys):
    assert main(["wopwop", "run", str(valid_case), "--out-dir", str(tmp_path / "out")]) == 0
    assert (tmp_path / "out" / "pressure.fn").is_file() and (tmp_path / "out" / "nps" / "signals" / "r.parquet").is_file()


def test_truncated_geometry(case, tmp_path, capsys):
    path = case / GEOMETRY
    path.write_bytes(path.read_bytes()[:-10])
    err = _run(case, tmp_path, capsys)
    assert GEOMETRY in err and "byte" in err


def test_wrong_magic_number(case, tmp_path, capsys):
    _patch_bytes(case / LOADING, 0, struct.pack("<i", 43))
    err = _run(case, tmp_path, capsys)
    assert LOADING in err and "byte 0: magic number" in err


def test_zone_count_overrunning_the_file(case, tmp_path, capsys):
    _patch_bytes(case / GEOMETRY, 1072, struct.pack("<i", 100000))
    err = _run(case, tmp_path, capsys)
    assert GEOMETRY in err and "byte 1072" in err and "zones" in err


def test_negative_size(case, tmp_path, capsys):
    _patch_bytes(case / GEOMETRY, 1100 + 32 + 8 + 4, struct.pack("<i", -5))  # first zone's jMax (after period, nKey, iMax)
    err = _run(case, tmp_path, capsys)
    assert GEOMETRY in err and "byte 1144" in err


def test_nan_in_the_loading(case, tmp_path, capsys):
    path = case / LOADING
    loading = binary.read_functional(path)
    values = loading.zones[0].values.copy()
    values[3, 2, 1] = np.nan
    raw = bytearray(path.read_bytes())
    index = raw.rfind(np.float32(loading.zones[0].values[3, 2, 1]).tobytes())
    raw[index:index + 4] = np.float32(np.nan).tobytes()
    path.write_bytes(bytes(raw))
    err = _run(case, tmp_path, capsys)
    assert LOADING in err and ("NaN" in err or "finite" in err)


def test_float_size_two(case, tmp_path, capsys):
    _patch_bytes(case / GEOMETRY, 1068 + 5 * 4, struct.pack("<i", 2))
    err = _run(case, tmp_path, capsys)
    assert GEOMETRY in err and "byte 1088" in err


def test_loading_keys_that_do_not_match_the_geometry(case, tmp_path, capsys):
    path = case / LOADING
    loading = binary.read_functional(path)
    zones = tuple(binary.FunctionalZone(z.zone, z.thickness, z.name, z.structured, z.i_max, z.j_max, z.n_data,
                                        z.period_s * 1.5, z.keys, z.values, z.loading_output) for z in loading.zones)
    binary.write_functional(binary.FunctionalFile(loading.comment, loading.n_zones, loading.structured, loading.time_kind,
                                                  loading.face_centred, loading.data_kind, loading.frame, zones,
                                                  minor_version=loading.minor_version), path)
    err = _run(case, tmp_path, capsys)
    assert LOADING in err and "period" in err


def test_text_in_the_observer_file(case, tmp_path, capsys):
    path = case / OBSERVERS
    lines = path.read_text().splitlines()
    lines[1] = lines[1].replace(lines[1].split()[0], "five", 1)
    path.write_text("\n".join(lines) + "\n")
    err = _run(case, tmp_path, capsys)
    assert OBSERVERS in err and "five" in err


def test_unknown_angle_type(case, tmp_path, capsys):
    _edit_text(case / CASE, "AngleType = 'KnownFunction'", "AngleType = 'Spinning'")
    err = _run(case, tmp_path, capsys)
    assert CASE in err and "AngleType" in err and "Spinning" in err


def test_unknown_cb_field(case, tmp_path, capsys):
    _edit_text(case / CASE, "Title = 'rotation'", "Title = 'rotation'\n  Omegaa = 3.0")
    err = _run(case, tmp_path, capsys)
    assert CASE in err and "omegaa" in err.lower()


def test_cb_count_overrunning_the_file(case, tmp_path, capsys):
    text = (case / CASE).read_text()
    last = text.rstrip().rsplit("nbBase = 1", 1)
    (case / CASE).write_text("nbBase = 3".join(last) + "\n")
    err = _run(case, tmp_path, capsys)
    assert CASE in err and "nbBase" in err
