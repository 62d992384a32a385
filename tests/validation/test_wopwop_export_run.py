"""Export → run closes the loop: an NPS case written as a PSU-WOPWOP case (``nps wopwop export``) and run by
``nps wopwop run`` reproduces the acoustics stage's own signals.

Case: two two-bladed rotors in forward flight (μ 0.15, cyclic pitch, flapping: a periodic blade geometry), loads
from the blade-element solver, the second rotor turned 20° in blade phase (two azimuth steps of the 36-step
table) and turning the other way; observers moving with the aircraft (the periodic path) and at rest (the direct
path). Reference: the acoustics stage (nps.stages.acoustics), the same code path as the workflow.

The run is algorithmically the acoustics stage's computation (the same source times, rates, paths and blade
copies): with the files' values kept in double precision it agrees to 1e-12 of peak-to-peak (measured 4e-15).
Through the files, PSU-WOPWOP's single-precision reals set the floor: the rounding of the periodic blade
geometry, differentiated over the keys, gives velocity errors of ~6e-7 relative. Measured here: loading
≤ 1.4e-7, thickness ≤ 9.9e-7 (the two dual-compact lines' contributions nearly cancel, so their rounding errors
weigh ~50x more against the thickness signal), total ≤ 1.6e-7 of peak-to-peak; bounds 1e-6 (loading, total)
and 5e-6 (thickness).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

import nps.wopwop.export as export
import nps.wopwop.run as runner
from nps.app.io import read_table, rotor_path, write_table
from nps.noise.observers import points
from nps.noise.signals import signal_arrays
from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.stages import acoustics, wopwop_export, wopwop_run
from tests.trim_tables import complete_trim

OMEGA, RADIUS, SAMPLES, MU = 40.0, 2.0, 128, 0.15
SPEED = MU * OMEGA * RADIUS
PHASES = {"a": 0.0, "b": 20.0}


@pytest.fixture(scope="module")
def disk() -> pd.DataFrame:
    geometry = RotorGeometry(name="a", n_blades=2, radius_m=RADIUS, chord_m=0.15, root_cutout_m=0.3, twist_rad=-0.15,
                             thickness_ratio=0.12, lock_number=6.0)
    op = OperatingPoint(omega_rad_s=OMEGA, mu_x=MU, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225, speed_of_sound_mps=340.294,
                        thrust_N=1.0)
    controls = bet.Controls(math.radians(8.0), math.radians(2.0), math.radians(-3.0))
    return bet.rotor_loads(geometry, op, bet.DiskGrid(36, 8), controls).disk


def _case(tmp_path, disk, moving: bool):
    """Disk tables, trim and observers of the two rotors written as artifacts; the stage params."""
    same = {"aircraft": "x", "segment": "s"}
    for rotor in PHASES:
        write_table(disk, rotor_path(tmp_path / "disks", rotor), stage="loads", metadata={**same, "rotor": rotor})
    rows = [{"rotor": name, "n_blades": np.int32(2), "omega_rad_s": OMEGA, "radius_m": RADIUS, "hub_x_m": 3.0 * k,
             "hub_z_m": 1.0, "vel_x_mps": SPEED, "rotation_sign": np.int8(1 - 2 * k), "thrust_N": 800.0, "ct": 0.005}
            for k, name in enumerate(PHASES)]
    write_table(complete_trim(pd.DataFrame(rows)), tmp_path / "trim.parquet", stage="trim", metadata=same)
    observers = points([[20.0, 5.0, -3.0], [-6.0, -15.0, -8.0], [8.0, 3.0, -12.0], [0.0, 25.0, 1.0]])
    if moving:
        observers["vx_mps"] = SPEED
    write_table(observers, tmp_path / "obs.parquet", stage="observers", metadata={**same, "obsset": "o"})
    params = {"rotors": list(PHASES), "hinge_offsets_m": dict.fromkeys(PHASES, 0.1), "thickness": "dual_compact",
              "chord_fractions": [0.13, 0.87], "samples_per_rev": SAMPLES, "phases_deg": PHASES, **same, "obsset": "o",
              "variant": "base"}
    return {"disks": tmp_path / "disks", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"}, params


def _errors(tmp_path, disk, moving: bool) -> dict[str, dict[str, float]]:
    """Max |run − acoustics| / peak-to-peak per rotor and group (loading, thickness, total)."""
    inputs, params = _case(tmp_path, disk, moving)
    acoustics.run(inputs, {"signals": tmp_path / "signals"}, params)
    wopwop_export.run(inputs, {"case": tmp_path / "case"}, params)
    wopwop_run.run({"case": tmp_path / "case"}, {"out_dir": tmp_path / "out"}, {})
    out = {}
    for rotor in PHASES:
        _, t_ref, ref = signal_arrays(read_table(rotor_path(tmp_path / "signals", rotor)))
        _, t_got, got = signal_arrays(read_table(rotor_path(tmp_path / "out" / "nps" / "signals", rotor)))
        assert np.array_equal(t_ref, t_got)
        ref["total"], got["total"] = ref["loading"] + ref["thickness"], got["loading"] + got["thickness"]
        out[rotor] = {g: float(np.abs(ref[g] - got[g]).max() / np.ptp(ref[g])) for g in ref}
    return out


@pytest.mark.parametrize("moving", [True, False], ids=["moving-periodic", "stationary-direct"])
def test_export_then_run_reproduces_the_acoustics_stage_through_the_files(tmp_path, disk, moving):
    """Single-precision files: loading and total within 1e-6, thickness within 5e-6 of peak-to-peak (module doc)."""
    errors = _errors(tmp_path, disk, moving)
    print(moving, errors)
    for rotor in PHASES:
        assert errors[rotor]["loading"] < 1e-6 and errors[rotor]["total"] < 1e-6, errors
        assert errors[rotor]["thickness"] < 5e-6, errors


@pytest.mark.parametrize("moving", [True, False], ids=["moving-periodic", "stationary-direct"])
def test_export_then_run_is_the_same_computation_in_double_precision(tmp_path, disk, moving, monkeypatch):
    """The files' values kept in double precision (in memory; the written files are still single): 1e-12."""
    written = {}
    monkeypatch.setattr(export, "FILE_FLOAT", np.float64)
    write_geometry, write_functional = export.binary.write_geometry, export.binary.write_functional

    def keep(writer):
        def write(obj, path, byte_order=None):
            written[str(path).rsplit("/", 1)[-1]] = obj
            single = {"geometry": write_geometry, "functional": write_functional}[writer]
            single(_single(obj), path)
        return write

    monkeypatch.setattr(export.binary, "write_geometry", keep("geometry"))
    monkeypatch.setattr(export.binary, "write_functional", keep("functional"))
    read = runner.read_patch_pair
    monkeypatch.setattr(runner, "read_patch_pair", lambda case, g, l: runner.PatchFiles(
        written[g], written[l] if l else None, read(case, g, l).geometry_path, read(case, g, l).functional_path))
    errors = _errors(tmp_path, disk, moving)
    assert max(e for rotor in errors.values() for e in rotor.values()) < 1e-12, errors


def _single(obj):
    """A geometry or functional file object with its float arrays cast to single precision (what is written)."""
    from dataclasses import fields, replace

    def cast(value):
        return value.astype(np.float32) if isinstance(value, np.ndarray) and value.dtype.kind == "f" else value

    zones = tuple(replace(z, **{f.name: cast(getattr(z, f.name)) for f in fields(z)}) for z in obj.zones)
    return replace(obj, zones=zones)
