"""Common period of rotors at different speeds (nps.core.periods; docs/reference/wake_bvi.md "Common period"):
the rational search and its approximation, the split of a field over m revolutions into its once-per-revolution
and rev-to-rev parts, the gust response over m revolutions, disk tables over several revolutions, and the
acoustic sources of such a table (a one-revolution table repeated m times radiates exactly as itself)."""

import math

import numpy as np
import pandas as pd
import pytest

from nps.core import periods
from nps.noise.acoustics import Observers
from nps.noise.sources import common_grid, radiate_rotor
from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.wake import bvi
from tests.trim_tables import complete_trim


@pytest.mark.parametrize("omega, revolutions", [
    ((100.0, 500.0), (1, 5)),          # main and tail rotor at 5:1
    ((30.0, 20.0), (3, 2)),            # 3:2: the faster first rotor turns 3 times
    ((28.0, 116.0), (7, 29)),          # the bundled helicopter: 116/28 = 29/7
    ((40.0, 40.0, 120.0), (1, 1, 3)),  # equal speeds and 3:1
])
def test_exact_ratios(omega, revolutions):
    period = periods.common_period([f"r{i}" for i in range(len(omega))], omega)
    assert period.revolutions == revolutions and period.exact
    assert period.period_s == pytest.approx(2.0 * math.pi * revolutions[0] / omega[0], rel=1e-15)
    for m, w in zip(revolutions, omega):  # every rotor completes whole turns in the period
        assert w * period.period_s / (2.0 * math.pi) == pytest.approx(m, rel=1e-12)


def test_nearest_rational_within_the_tolerance():
    """5.02:1 is 5:1 within 0.4 %: accepted at 0.5 % with the ratio error recorded, refused at 0.1 % up to 16
    turns of the reference (then 5.02 = 251/50 needs 50)."""
    period = periods.common_period(["main", "tail"], [100.0, 502.0], tolerance=0.005)
    assert period.revolutions == (1, 5) and not period.exact
    assert period.ratio_errors[1] == pytest.approx(5.0 / 5.02 - 1.0, rel=1e-12)
    assert "'tail' 5 rev (speed ratio approximated by -0.398%)" in period.describe()
    with pytest.raises(periods.PeriodError, match=r"no common period of the rotors \('main' 100 rad/s, 'tail' 502 "
                                                  r"rad/s\) within 16 revolutions.*period_tolerance"):
        periods.common_period(["main", "tail"], [100.0, 502.0], tolerance=0.001)


def test_bad_speeds_are_refused():
    with pytest.raises(ValueError, match="speeds must be finite and > 0"):
        periods.common_period(["a", "b"], [100.0, 0.0])
    with pytest.raises(ValueError, match="one speed per rotor"):
        periods.common_period(["a"], [1.0, 2.0])


def test_table_revolutions():
    assert periods.table_revolutions(2.0 * np.pi * np.arange(36) / 36) == 1
    assert periods.table_revolutions(2.0 * np.pi * np.arange(5 * 36) / 36) == 5
    assert periods.table_revolutions([0.0]) == 1


def test_split_period_harmonics():
    """Over m = 5 turns: the mean and 1/rev (period harmonics 0 and 5) are the low part, one turn long; the
    3/rev and a 0.8/rev rev-to-rev variation (period harmonic 4, e.g. a 4-bladed rotor turning 5x slower)
    are the high part."""
    n_rev, m = 24, 5
    psi = 2.0 * np.pi * np.arange(m * n_rev) / n_rev
    low = 1.5 + 0.7 * np.cos(psi - 0.3)
    high = 0.2 * np.sin(3.0 * psi) + 0.4 * np.cos(0.8 * psi + 1.0)
    got_low, got_high = bvi.split_period_harmonics(np.stack([low + high, 2.0 * (low + high)], axis=1), m)
    assert got_low.shape == (n_rev, 2) and got_high.shape == (m * n_rev, 2)
    np.testing.assert_allclose(got_low[:, 0], low[:n_rev], atol=1e-12)
    np.testing.assert_allclose(got_high[:, 1], 2.0 * high, atol=1e-12)
    one_low, one_high = bvi.split_period_harmonics((low + high)[:n_rev, None], 1)  # one turn: harmonics 0, 1
    np.testing.assert_allclose(one_low[:, 0] + one_high[:, 0], (low + high)[:n_rev], atol=1e-12)


def _sections(n_rev, n_r, m, seed=3):
    rng = np.random.default_rng(seed)
    psi = 2.0 * np.pi * np.arange(m * n_rev) / n_rev
    ut = np.tile((60.0 + 140.0 * np.linspace(0.3, 1.0, n_r))[None, :] + 45.0 * np.sin(psi[:n_rev])[:, None], (m, 1))
    return rng.normal(size=(m * n_rev, n_r, 2)), ut


def test_gust_response_over_several_revolutions():
    """The O(N n_h) filter of a series over m turns (coefficients repeating every turn) equals the direct
    frozen-coefficient sum, and a series that repeats every turn is filtered as its one-turn self."""
    n_rev, n_r, m = 24, 3, 3
    values, ut = _sections(n_rev, n_r, m)
    args = dict(omega_rad_s=30.0, radius_m=6.0, chord_m=0.4, speed_of_sound_mps=340.0)
    fast = bvi.unsteady_response(values, ut, revolutions=m, **args)
    direct = bvi.unsteady_response(values, ut + np.arange(m * n_rev)[:, None] * 1e-13, revolutions=m, **args)
    np.testing.assert_allclose(fast, direct, atol=1e-9 * np.abs(direct).max())
    one = bvi.unsteady_response(values[:n_rev], ut[:n_rev], **args)
    np.testing.assert_allclose(bvi.unsteady_response(np.tile(values[:n_rev], (m, 1, 1)), ut, revolutions=m, **args),
                               np.tile(one, (m, 1, 1)), atol=1e-12 * np.abs(one).max())


def _disk() -> pd.DataFrame:
    geometry = RotorGeometry(name="a", n_blades=3, radius_m=2.0, chord_m=0.15, root_cutout_m=0.3, twist_rad=-0.15,
                             thickness_ratio=0.12, lock_number=6.0)
    op = OperatingPoint(omega_rad_s=40.0, mu_x=0.15, mu_y=0.0, mu_z=-0.01, density_kg_m3=1.225,
                        speed_of_sound_mps=340.294, thrust_N=1.0)
    return bet.rotor_loads(geometry, op, bet.DiskGrid(36, 8), bet.Controls(math.radians(8.0), math.radians(1.0),
                                                                              math.radians(-2.0))).disk


def test_disk_tables_over_several_revolutions():
    disk = _disk()
    tiled = bvi.tile_disk(disk, 4)
    grid = bvi.disk_grid(tiled, "tiled", common_period=True)
    assert grid.revolutions == 4 and grid.shape == (4 * 36, 8)
    np.testing.assert_allclose(grid.psi_rad, 2.0 * np.pi * np.arange(144) / 36)
    with pytest.raises(ValueError, match="tiled: psi_rad spans 4 revolutions"):
        bvi.disk_grid(tiled, "tiled")


def _trim_row():
    trim = complete_trim(pd.DataFrame([{"rotor": "a", "n_blades": np.int32(3), "omega_rad_s": 40.0, "radius_m": 2.0,
                                        "hub_z_m": 1.0, "vel_x_mps": 12.0, "thrust_N": 800.0, "ct": 0.005}]))
    return trim.iloc[0].to_dict()


@pytest.mark.parametrize("moving", [True, False])
def test_a_repeated_table_radiates_as_itself(moving):
    """A one-revolution table repeated over 3 turns, every blade's loads those of blade 0 at its azimuth in the
    same turn (blade_shift_steps k N/B), radiates the one-turn signal: observers moving with the rotor (periodic
    sources over the period, every blade) and fixed ones (all blades over the window)."""
    disk, row = _disk(), _trim_row()
    velocity = np.array([row["vel_x_mps"], row["vel_y_mps"], row["vel_z_mps"]]) if moving else np.zeros(3)
    obs = Observers(np.array([[30.0, 10.0, -20.0], [-15.0, -25.0, -5.0]]), np.tile(velocity, (2, 1)))
    grid = common_grid(row, 64, 3)
    one = radiate_rotor(disk, row, obs, grid)
    scale = np.abs(one).max()
    three = radiate_rotor(bvi.tile_disk(disk, 3), row, obs, grid, blade_shift_steps=[0, 12, 24])
    # every blade explicit instead of blade 0 and its symmetry: the retarded-time interpolation differs (< 1e-3)
    np.testing.assert_allclose(three, one, atol=1e-3 * scale)
    later = radiate_rotor(bvi.tile_disk(disk, 3), row, obs, grid, blade_shift_steps=[0, 48, 96])  # next turns
    np.testing.assert_allclose(later, one, atol=1e-3 * scale)
    wrong = radiate_rotor(bvi.tile_disk(disk, 3), row, obs, grid, blade_shift_steps=[0, 0, 0])  # all blades' loads at blade 0's
    assert np.abs(wrong - one).max() > 0.05 * scale


def test_a_table_over_several_turns_needs_its_metadata(tmp_path):
    """The acoustics stage reads how a table spans several turns from its metadata; a bare table over several
    turns (another tool's, or metadata lost) is refused naming the file, before any signal is written."""
    from nps.app.io import rotor_path, write_table
    from nps.stages import acoustics
    from nps.noise.observers import points

    trim = complete_trim(pd.DataFrame([{"rotor": "a", "n_blades": np.int32(3), "omega_rad_s": 40.0, "radius_m": 2.0,
                                        "hub_z_m": 1.0, "thrust_N": 800.0, "ct": 0.005}]))
    where = {"aircraft": "x", "segment": "s"}
    write_table(bvi.tile_disk(_disk(), 3), rotor_path(tmp_path / "disks", "a"), stage="bvi", metadata={**where, "rotor": "a"})
    write_table(trim, tmp_path / "trim.parquet", stage="trim", metadata=where)
    write_table(points([[20.0, 5.0, -3.0]]), tmp_path / "obs.parquet", stage="observers", metadata={**where, "obsset": "o"})
    params = {"rotors": ["a"], "hinge_offsets_m": {"a": 0.0}, "thickness": "dual_compact", "chord_fractions": [0.13, 0.87],
              "samples_per_rev": 64, "obsset": "o", "variant": "bvi", **where}
    with pytest.raises(ValueError, match=r"a.parquet: psi_rad spans 3 revolutions but the table's metadata records none"):
        acoustics.run({"disks": tmp_path / "disks", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"},
                      {"signals": tmp_path / "signals"}, params)
    assert not (tmp_path / "signals").exists()
