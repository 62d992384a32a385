"""Airfoil tables (nps.rotor.airfoils): the shipped NACA 0012 deck against its published source
(Sheldahl & Klimas 1981, SAND80-2114), C81 parser round trip, interpolation against hand values,
CSV polars, the Viterna–Corrigan extension and bad input."""

import math

import numpy as np
import pytest

from nps.rotor.airfoils import (
    AirfoilError,
    LinearAirfoil,
    PolarTable,
    AirfoilTable,
    read_airfoil,
    read_c81,
    read_polar_csv,
    reverse_flow_angle,
    viterna_extension,
    write_c81,
)

NACA0012 = "config/airfoils/naca0012.c81"
SAND80_2114 = "tests/data/airfoils/naca0012_sand80_2114_re360k.csv"
# drag rows of the source left out of the deck (a C81 table holds at most 99 angles), config/airfoils/README.md
OMITTED_CD_DEG = (55.0, 95.0, 115.0)


@pytest.fixture(scope="module")
def naca(repo_root):
    return read_c81(repo_root / NACA0012)


def test_c81_deck_shape_and_reference_values(naca):
    """The shipped deck: one Mach column, 97 c_l and 99 c_d angles over ±180°, c_m two zeros; the lift
    slope from ±2° is the source's 0.11 per degree, c_d0 its 0.0079."""
    assert naca.cl.values.shape == (97, 1) and naca.cd.values.shape == (99, 1) and naca.cm.values.shape == (2, 1)
    assert naca.full_range and naca.name == "NACA 0012 SAND80-2114 Re 3.6e5"
    assert math.isclose(naca.lift_slope_per_rad, 0.22 / math.radians(2.0), rel_tol=1e-12)
    assert naca.cd0 == 0.0079


def test_deck_reproduces_the_published_sand80_2114_points(naca, repo_root):
    """Every point of the source table (SAND80-2114, NACA 0012, Re 3.6e5, 0…180°) at +α and, mirrored for
    the symmetric section (c_l odd, c_d even), at −α: exact, except c_d at the three omitted angles, where
    the interpolation between the neighbours is within 0.005 (0.4 %) of the published value. Spot values
    of the source: c_l,max 0.9811 at 10°, the stall drop to 0.4832 at 12°, c_d 1.80 at 90°; c_m is zero."""
    source = read_polar_csv(repo_root / SAND80_2114)
    alpha, cl, cd = source.cl.alpha_rad, source.cl.values[:, 0], source.cd.values[:, 0]
    assert np.degrees(alpha[-1]) == 180.0 and alpha.size == 59
    for sign in (1.0, -1.0):
        got_cl, got_cd, got_cm = naca.coefficients(sign * alpha, 0.3)
        assert np.allclose(got_cl, sign * cl, rtol=0, atol=1e-12) and np.all(got_cm == 0.0)
        omitted = np.isin(np.round(np.degrees(alpha), 9), OMITTED_CD_DEG)
        assert np.allclose(got_cd[~omitted], cd[~omitted], rtol=0, atol=1e-12)
        assert np.all(np.abs(got_cd[omitted] - cd[omitted]) <= 0.005 + 1e-12)
    spot = naca.coefficients(np.radians([10.0, 12.0, 90.0]), 0.0)
    assert np.allclose(spot[0][:2], [0.9811, 0.4832], atol=1e-12) and math.isclose(spot[1][2], 1.8, abs_tol=1e-12)


def test_interpolation_against_hand_values(naca):
    """Linear in α, the same table at every Mach number (clamped to the single column): c_l(5°) = 5/7 ×
    0.77 (the source is linear up to 7°), c_l(10.5°) = (0.9811 + 0.9132)/2, c_l(−2°, M 1.3) = −0.22,
    c_d(−170°) = 0.14, c_d(55°) = (1.215 + 1.47)/2 between the kept neighbours, c_m(12°) = 0."""
    alpha = np.radians([5.0, 10.5, -2.0, -170.0, 55.0])
    cl, cd, cm = naca.coefficients(alpha, np.array([0.0, 0.5, 1.3, 0.37, 0.8]))
    assert np.allclose(cl[:3], [0.55, 0.5 * (0.9811 + 0.9132), -0.22], rtol=0, atol=1e-12)
    assert np.allclose(cd[3:], [0.14, 0.5 * (1.215 + 1.47)], rtol=0, atol=1e-12)
    assert np.array_equal(naca.cl(alpha, 0.0), naca.cl(alpha, 0.9)) and naca.cm(math.radians(12.0), 0.65) == 0.0


def test_c81_round_trip_is_exact(naca, tmp_path):
    """write_c81 → read_c81 gives the same numbers; the shipped deck and a synthetic deck with
    more than nine Mach numbers (continuation lines) and a one-Mach table."""
    write_c81(tmp_path / "a.c81", naca)
    again = read_c81(tmp_path / "a.c81")
    for p, q in zip((naca.cl, naca.cd, naca.cm), (again.cl, again.cd, again.cm)):
        assert np.array_equal(p.mach, q.mach) and np.array_equal(p.values, q.values)
        assert np.allclose(p.alpha_rad, q.alpha_rad, rtol=0, atol=1e-15)
    rng = np.random.default_rng(1)
    mach = np.round(np.linspace(0.0, 0.95, 12), 3)
    alpha = np.radians(np.arange(-180.0, 181.0, 22.5))
    tables = [PolarTable(n, alpha, mach if n != "CM" else mach[:1], np.round(rng.normal(size=(alpha.size, mach.size if n != "CM" else 1)), 4), "s")
              for n in ("CL", "CD", "CM")]
    synthetic = AirfoilTable("synthetic", *tables, source="s")
    write_c81(tmp_path / "b.c81", synthetic)
    lines = (tmp_path / "b.c81").read_text().splitlines()
    assert lines[0][30:] == f"{12:2d}{17:2d}{12:2d}{17:2d}{1:2d}{17:2d}" and lines[2].startswith(" " * 7)
    back = read_c81(tmp_path / "b.c81")
    for p, q in zip(tables, (back.cl, back.cd, back.cm)):
        assert np.array_equal(p.values, q.values) and np.array_equal(p.mach, q.mach)


def test_c81_errors_name_file_line_and_field(naca, tmp_path):
    path = tmp_path / "bad.c81"
    write_c81(path, naca)
    good = path.read_text().splitlines()
    lines = list(good)
    lines[5] = lines[5][:7] + " x.5   " + lines[5][14:]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(AirfoilError, match=r"bad\.c81: line 6: CL row 4: columns 8-14: expected a number, got ' x\.5   '"):
        read_c81(path)
    path.write_text("NACA 0012                     11xx1165 947\n")
    with pytest.raises(AirfoilError, match=r"bad\.c81: line 1: NAL \(columns 33-34\): expected an integer"):
        read_c81(path)
    path.write_text("\n".join(good[:30]) + "\n")
    with pytest.raises(AirfoilError, match="bad.c81: .*file ends"):
        read_c81(path)
    with pytest.raises(AirfoilError, match=r"nope\.c81: airfoil table not found"):
        read_airfoil(tmp_path / "nope.c81")


def _polar_csv(path, rows, header="alpha_deg,cl,cd,cm"):
    path.write_text("# test polar\n" + header + "\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n")
    return path


def test_csv_polar_range_is_enforced_with_file_and_field(tmp_path):
    """An angle outside a polar without extension stops with the file, coefficient and range."""
    alpha = np.arange(-10.0, 16.0, 1.0)
    path = _polar_csv(tmp_path / "p.csv", [(a, 0.1 * a, 0.01, 0.0) for a in alpha])
    table = read_airfoil(path)
    assert not table.full_range
    cl, _, _ = table.coefficients(np.radians([3.5, -10.0, 15.0]), 0.3)
    assert np.allclose(cl, [0.35, -1.0, 1.5], atol=1e-12)
    with pytest.raises(AirfoilError, match=r"p\.csv: CL: angle of attack 20\.00 deg outside the table's range \[-10\.00, 15\.00\] deg"):
        table.coefficients(np.radians([5.0, 20.0]), 0.3)


def test_csv_polar_with_mach_and_reynolds_columns(tmp_path):
    rows = [(a, m, re, 0.1 * a * (1 + m), 0.01 + m) for re in (1e5, 2e5) for m in (0.0, 0.4) for a in (-5.0, 0.0, 5.0, 10.0)]
    path = _polar_csv(tmp_path / "m.csv", rows, "alpha_deg,mach,reynolds,cl,cd")
    with pytest.raises(AirfoilError, match=r"m\.csv: column reynolds: several Reynolds numbers"):
        read_polar_csv(path)
    with pytest.raises(AirfoilError, match="no polar at Reynolds number 300000"):
        read_polar_csv(path, reynolds=3e5)
    table = read_polar_csv(path, reynolds=2e5)
    assert np.array_equal(table.cl.mach, [0.0, 0.4])
    cl, cd, cm = table.coefficients(math.radians(5.0), 0.2)
    assert math.isclose(cl, 0.5 * 1.2, rel_tol=1e-12) and math.isclose(cd, 0.21, rel_tol=1e-12) and cm == 0.0
    _polar_csv(tmp_path / "x.csv", [(0.0, 0.0, "abc")], "alpha_deg,cl,cd")
    with pytest.raises(AirfoilError, match=r"x\.csv: data row 1: column cd: expected a number, got 'abc'"):
        read_polar_csv(tmp_path / "x.csv")


def test_viterna_extension(tmp_path):
    """±180° extension: unchanged inside the table, continuous at its ends, c_d = c_d,max =
    1.11 + 0.018 AR at 90°, c_l = 0 at 90° and ±180°, reversed-section lift −0.7 c_l(180° − α)."""
    alpha = np.arange(-12.0, 15.0, 1.0)
    table = read_polar_csv(_polar_csv(tmp_path / "v.csv", [(a, 0.1 * a, 0.008 + 1e-4 * a * a, -0.01) for a in alpha]))
    ext = viterna_extension(table, aspect_ratio=10.0)
    assert ext.full_range
    inside = np.radians(alpha)
    assert np.array_equal(ext.cl(inside, 0.0), table.cl(inside, 0.0))
    cl, cd, cm = ext.coefficients(np.radians([90.0, -90.0, 180.0, -180.0]), 0.0)
    assert np.allclose(cd[:2], 1.11 + 0.18, rtol=1e-12) and np.allclose(cl, 0.0, atol=1e-12)
    eps = math.radians(1e-6)
    for end in (math.radians(14.0), math.radians(-12.0)):
        a, b = ext.coefficients(np.array([end - eps, end + eps]), 0.0)[:2]
        assert abs(a[1] - a[0]) < 1e-6 and abs(b[1] - b[0]) < 1e-6
    deep = math.radians(120.0)
    forward = ext.cl(math.pi - deep, 0.0)
    assert math.isclose(ext.cl(deep, 0.0), -0.7 * forward, rel_tol=1e-12)
    with pytest.raises(AirfoilError, match="aspect_ratio"):
        viterna_extension(table, aspect_ratio=80.0)


def test_reverse_flow_angle_and_linear_airfoil_checks():
    """Wind from the trailing edge: full angle = mod-π angle ∓ π; linear-model fields checked."""
    full = reverse_flow_angle(np.array([0.1, -0.1, 0.1]), np.array([True, True, False]))
    assert np.allclose(full, [0.1 - math.pi, math.pi - 0.1, 0.1])
    with pytest.raises(ValueError, match="airfoil.mach_cap"):
        LinearAirfoil(mach_cap=1.2)
    with pytest.raises(ValueError, match="airfoil.lift_slope_per_rad"):
        LinearAirfoil(lift_slope_per_rad=0.0)
