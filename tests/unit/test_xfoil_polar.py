"""XFOIL polar files (nps.rotor.airfoils.read_xfoil_polar): a published XFOIL output read back
exactly, a write/read round trip, the Viterna extension and clear refusals."""

import math
import shutil

import numpy as np
import pytest

from nps.rotor.airfoils import AirfoilError, read_airfoil, read_xfoil_polar, write_xfoil_polar

POLAR = "naca0012_re200k.pol"  # XFOIL 6.99, NACA 0012, Re 2e5, M 0, Ncrit 9 (tests/data/xfoil/README.md)


@pytest.fixture
def polar_path(data_dir):
    return data_dir / "xfoil" / POLAR


def test_published_points_and_conditions_are_read_exactly(polar_path):
    polar = read_xfoil_polar(polar_path)
    assert (polar.mach, polar.reynolds, polar.ncrit) == (0.0, 200000.0, 9.0)
    assert polar.table.name == "NACA 0012"
    cl, cd, cm = polar.table.coefficients(math.radians(12.0), 0.3)  # any Mach: one polar
    assert (float(cl), float(cd), float(cm)) == (1.0952, 0.04453, 0.0296)
    assert np.degrees(polar.table.cl.alpha_rad).round(6).tolist() == [*range(-2, 15), 17, 19, 20, 21, 22]


def test_gap_of_unconverged_angles_is_interpolated_linearly(polar_path):
    """15°, 16° are missing from the file (XFOIL did not converge): linear between 14° and 17°."""
    table = read_xfoil_polar(polar_path).table
    expected = 0.9861 + 0.5 * (0.5233 - 0.9861)
    assert float(table.cl(math.radians(15.5), 0.0)) == pytest.approx(expected, abs=1e-12)


def test_symmetric_section_data_is_antisymmetric_in_lift_and_moment(polar_path):
    """NACA 0012 is symmetric: c_l(−α) = −c_l(α), c_m(−α) = −c_m(α), c_d(−α) = c_d(α) (XFOIL to its printed digits)."""
    table = read_xfoil_polar(polar_path).table
    for a in (1.0, 2.0):
        plus, minus = (np.array(table.coefficients(math.radians(s * a), 0.0), dtype=float) for s in (1, -1))
        assert minus[0] == pytest.approx(-plus[0], abs=1e-4)
        assert minus[1] == pytest.approx(plus[1], abs=1e-5)
        assert minus[2] == pytest.approx(-plus[2], abs=1e-4)


def test_write_read_round_trip(polar_path, tmp_path):
    polar = read_xfoil_polar(polar_path)
    out = tmp_path / "copy.pol"
    write_xfoil_polar(out, polar)
    again = read_xfoil_polar(out)
    assert (again.mach, again.reynolds, again.ncrit, again.table.name) == (0.0, 200000.0, 9.0, "NACA 0012")
    for a, b in ((polar.table.cl, again.table.cl), (polar.table.cd, again.table.cd), (polar.table.cm, again.table.cm)):
        np.testing.assert_allclose(b.alpha_rad, a.alpha_rad, rtol=0, atol=1e-12)
        np.testing.assert_array_equal(b.values, a.values)


def test_read_airfoil_takes_xfoil_polars_with_the_same_extrapolation(polar_path):
    table = read_airfoil(polar_path)
    assert not table.full_range
    with pytest.raises(AirfoilError, match=r"naca0012_re200k.pol: CL: angle of attack 30.00 deg outside"):
        table.coefficients(math.radians(30.0), 0.0)
    extended = read_airfoil(polar_path, extrapolation="viterna")
    assert extended.full_range
    assert float(extended.cl(math.radians(12.0), 0.0)) == pytest.approx(1.0952, abs=1e-12)
    with pytest.raises(AirfoilError, match=r"reynolds: the XFOIL polar is at Re = 2e\+05, not 1e\+06"):
        read_airfoil(polar_path, reynolds=1.0e6)


def test_refusals_name_file_line_and_expectation(polar_path, tmp_path):
    text = polar_path.read_text()
    repeated = tmp_path / "repeated.pol"
    repeated.write_text(text + "   4.000   0.5400   0.01176   0.00283  -0.0144   0.4165   1.0000  37.3295 160.0000\n")
    with pytest.raises(AirfoilError, match=r"repeated.pol: line 35: alpha 4 deg computed twice"):
        read_xfoil_polar(repeated)
    no_cm = tmp_path / "no_cm.pol"
    no_cm.write_text(text.replace("  CM  ", "  CX  "))
    with pytest.raises(AirfoilError, match=r"no_cm.pol: line 11: column CM: required column missing"):
        read_xfoil_polar(no_cm)
    bad = tmp_path / "bad.pol"
    bad.write_text(text.replace("0.04453", "0.0445x"))
    with pytest.raises(AirfoilError, match=r"bad.pol: line 27: expected 9 numbers"):
        read_xfoil_polar(bad)
    coordinates = tmp_path / "naca0012.dat"
    coordinates.write_text("NACA 0012\n1.0 0.00126\n0.5 0.05\n")
    with pytest.raises(AirfoilError, match=r"naca0012.dat: table: expected a .c81 deck, a .csv polar or an XFOIL polar"):
        read_airfoil(coordinates)
    shutil.copy(polar_path, tmp_path / "polar.dat")
    assert read_airfoil(tmp_path / "polar.dat").name == "NACA 0012"
