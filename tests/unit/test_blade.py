"""Blade tables (nps.rotor.blade) in the loads: a table encoding the linear blade reproduces it, a
tapered blade against the closed-form integral of blade element theory, local columns in the
disk table, a stall polar changing only stalled sections, and bad input."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from nps.rotor.airfoils import LinearAirfoil, PolarTable, AirfoilTable
from nps.rotor.bet import Controls, DiskGrid, rotor_loads, section_forces, trim_rotor
from nps.rotor.blade import BladeError, BladeTable, blade_from_config, read_blade_csv
from nps.rotor.geometry import OperatingPoint, RotorGeometry

R = 7.62
GEOM = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.15 * R,
                     twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0, hinge_offset_m=0.381)
WEIGHT_N = 5140.1 * 9.80665


def with_blade(geometry, blade, **kw):
    return RotorGeometry(**{**geometry.__dict__, "blade": blade, **kw})


def test_table_of_the_linear_blade_reproduces_the_shorthand():
    """Forward flight (μ 0.3, reverse flow, stall): every disk column and total within 1e-10."""
    table = BladeTable.linear(R, 0.15 * R, 0.58, math.radians(-16.0), 0.09)
    op = OperatingPoint(28.0, 0.3, 0.0, 0.04, 1.225, 340.3, WEIGHT_N)
    a = trim_rotor(GEOM, op, DiskGrid(72, 20))
    b = trim_rotor(with_blade(GEOM, table), op, DiskGrid(72, 20))
    for column in a.disk.columns:
        x, y = a.disk[column].to_numpy(), b.disk[column].to_numpy()
        assert np.abs(x - y).max() <= 1e-10 * max(np.abs(x).max(), 1e-300), column
    for name, value in a.totals.__dict__.items():
        assert abs(value - getattr(b.totals, name)) <= 1e-10 * max(abs(value), WEIGHT_N * R * 1e-6), name


def test_tapered_blade_thrust_matches_integrated_blade_element_theory():
    """Hover, linear taper c(r) = c0 (1 − 0.6 r/R), linear twist, rigid blade, no drag, tip loss
    or compressibility. With the BET's uniform λ (itself checked against momentum,
    λ = √(C_T/2)), the thrust is T = B ∫ ½ ρ c(r) W a (θ(r) − φ) U_T dr, W² = U_T² + U_P²,
    φ = atan(U_P/U_T), U_T = Ωr, U_P = λΩR, integrated by adaptive quadrature: to 1e-5 (the
    BET's 400-station midpoint rule). The same integral with the mean chord differs by more
    than 4 %: the taper is used."""
    foil = LinearAirfoil(cd0=0.0, cd2=0.0, cl_max=10.0)
    c0, k, r0, tw = 0.8, 0.6, 0.1 * R, math.radians(-8.0)
    r_tab = np.array([r0, R])
    blade = BladeTable(r_tab, c0 * (1 - k * r_tab / R), tw * (r_tab / R - 0.75), np.full(2, 0.1), np.zeros(2), np.zeros(2), (), "taper")
    g = RotorGeometry(name="taper", n_blades=4, radius_m=R, chord_m=blade.equivalent_chord_m(r0, R), root_cutout_m=r0,
                      twist_rad=0.0, thickness_ratio=0.1, lock_number=8.0, airfoil=foil, blade=blade)
    omega, rho, theta0 = 28.0, 1.225, math.radians(3.0)
    op = OperatingPoint(omega, 0.0, 0.0, 0.0, rho, 1e9, 1.0)
    t = rotor_loads(g, op, DiskGrid(8, 400), Controls(theta0), tip_loss=False, flapping=False)
    lam = t.inflow.lambda0
    assert abs(lam / math.sqrt(t.totals.ct / 2.0) - 1.0) < 1e-8

    def thrust(chord):
        def per_span(r):
            ut, up = omega * r, lam * omega * R
            theta = theta0 + tw * (r / R - 0.75)
            return 0.5 * rho * chord(r) * math.hypot(ut, up) * 5.73 * (theta - math.atan2(up, ut)) * ut
        return 4 * quad(per_span, r0, R, epsabs=0.0, epsrel=1e-12)[0]

    expected = thrust(lambda r: c0 * (1 - k * r / R))
    assert abs(t.totals.thrust_N / expected - 1.0) < 1e-5
    assert abs(thrust(lambda r: blade.chord_m.mean()) / expected - 1.0) > 0.04


def test_disk_table_carries_local_chord_thickness_and_twist():
    """Nonlinear twist and taper: θ = θ0 + θ_tw(r) − θ_tw(0.75R), chord and t·c interpolated."""
    r = np.array([0.15, 0.5, 0.8, 1.0]) * R
    blade = BladeTable(r, np.array([0.7, 0.6, 0.5, 0.3]), np.radians([10.0, 2.0, -3.0, -4.0]),
                       np.array([0.2, 0.12, 0.09, 0.07]), np.zeros(4), np.zeros(4), (), "test")
    g = with_blade(GEOM, blade, chord_m=blade.equivalent_chord_m(0.15 * R, R))
    out = rotor_loads(g, OperatingPoint(28.0, 0.0, 0.0, 0.0, 1.225, 340.3, 1.0), DiskGrid(8, 30), Controls(0.1)).disk
    rs = out["r_m"].to_numpy()
    sec = blade.at(rs)
    assert np.allclose(out["chord_m"], sec.chord_m, rtol=1e-15)
    assert np.allclose(out["thickness_m"], sec.chord_m * sec.thickness_ratio, rtol=1e-15)
    expected = 0.1 + sec.twist_rad - np.interp(0.75 * R, r, np.radians([10.0, 2.0, -3.0, -4.0]))
    assert np.allclose(out["theta_rad"], expected, rtol=0, atol=1e-15)


def _stall_table(alpha_s_deg=12.0):
    """c_l = 5.73 α and c_d = 0.01 for |α| ≤ α_s, then a stall drop to 0.6 at 20° (±90° table)."""
    a_deg = np.concatenate([[-90.0, -40.0, -20.0], np.linspace(-alpha_s_deg, alpha_s_deg, 25), [20.0, 40.0, 90.0]])
    a = np.radians(a_deg)
    cl = np.where(np.abs(a_deg) <= alpha_s_deg, 5.73 * a, np.sign(a) * np.interp(np.abs(a_deg), [20, 40, 90], [0.6, 0.8, 0.0]))
    cd = np.where(np.abs(a_deg) <= alpha_s_deg, 0.01, np.interp(np.abs(a_deg), [20, 40, 90], [0.2, 0.6, 1.3]))
    tables = [PolarTable(n, a, np.array([0.0]), v[:, None], "stall") for n, v in (("CL", cl), ("CD", cd), ("CM", 0 * cd))]
    return AirfoilTable("stall", *tables, source="stall")


def test_stall_polar_changes_loads_only_in_the_stalled_region():
    """Same kinematics (a trimmed μ 0.38 disk), linear section vs a table equal to it up to 12°
    and stalled beyond: sectional loads identical (1e-12) where |α| ≤ 12°; beyond 13° the lift
    (circulation) at least 10 % lower."""
    linear = LinearAirfoil(cd0=0.01, cd2=0.0, cl_max=100.0, mach_cap=1e-9)
    g_lin = RotorGeometry(**{**GEOM.__dict__, "airfoil": linear})
    d = trim_rotor(g_lin, OperatingPoint(28.0, 0.38, 0.0, 0.06, 1.225, 1e9, WEIGHT_N), DiskGrid(72, 20)).disk
    g_stall = RotorGeometry(**{**GEOM.__dict__, "airfoil": _stall_table()})
    args = (d["ut_mps"], d["up_mps"], d["theta_rad"], d["r_m"])
    a = section_forces(*args, g_lin, 1.225, 1e9)
    b = section_forces(*args, g_stall, 1.225, 1e9)
    alpha = np.degrees(np.abs(a.alpha_eff_rad))
    attached, stalled = alpha <= 12.0, alpha > 13.0
    assert stalled.sum() > 20 and attached.sum() > 1000
    for x, y in ((a.fz_N_per_m, b.fz_N_per_m), (a.fx_N_per_m, b.fx_N_per_m)):
        assert np.allclose(y[attached], x[attached], rtol=1e-12, atol=1e-9)
    ratio = b.circulation_m2_s[stalled] / a.circulation_m2_s[stalled]  # = c_l ratio, tip loss and W common
    assert np.all(ratio < 0.9)


def test_airfoil_blending_between_stations():
    """Stations naming airfoils 'a', 'a', 'b': weight of b rises linearly from 0 to 1 between the
    last two stations; coefficients blend accordingly."""
    r = np.array([1.0, 4.0, 7.62])
    blade = BladeTable(r, np.full(3, 0.5), np.zeros(3), np.full(3, 0.1), np.zeros(3), np.zeros(3), ("a", "a", "b"), "mix")
    w = blade.airfoil_weights(np.array([2.0, 4.0, 5.81, 7.62]))
    assert np.allclose(w["b"], [0.0, 0.0, 0.5, 1.0]) and np.allclose(w["a"] + w["b"], 1.0)
    foils = {"a": LinearAirfoil(lift_slope_per_rad=5.0), "b": LinearAirfoil(lift_slope_per_rad=6.0)}
    g = RotorGeometry(**{**GEOM.__dict__, "root_cutout_m": 1.0, "blade": blade, "airfoils": foils})
    cl = g.coefficients_at(np.full(3, 0.1), np.zeros(3, bool), np.zeros(3), np.array([3.0, 5.81, 7.62]))[0]
    assert np.allclose(cl, [0.5, 0.55, 0.6], rtol=1e-12)


def test_blade_csv_and_config_errors(tmp_path):
    path = tmp_path / "blade.csv"
    path.write_text("# r/R, c/R, deg\nr_over_R,chord_over_R,twist_deg,thickness_ratio\n0.1,0.2,20,0.2\n1.0,0.1,5,0.08\n")
    table = read_blade_csv(path, 0.12)
    assert np.allclose(table.radius_m, [0.012, 0.12]) and np.allclose(table.chord_m, [0.024, 0.012])
    with pytest.raises(BladeError, match=r"blade\.csv: radius: expected stations from the root cutout"):
        RotorGeometry(name="p", n_blades=2, radius_m=0.12, chord_m=0.02, root_cutout_m=0.005, twist_rad=0.0,
                      thickness_ratio=0.1, lock_number=1.0, blade=table)
    path.write_text("r_over_R,chord_m,thickness_ratio\n0.1,0.02,0.2\n1.0,0.01,0.08\n")
    with pytest.raises(BladeError, match=r"blade\.csv: twist_deg: required column missing"):
        read_blade_csv(path, 0.12)
    with pytest.raises(BladeError, match=r"rotor 'x': blade: chord_m: expected 3 values"):
        blade_from_config({"r_over_R": [0.2, 0.5, 1.0], "chord_m": [0.1, 0.1], "twist_deg": [1, 2, 3],
                           "thickness_ratio": [0.1, 0.1, 0.1]}, 1.0, "rotor 'x': blade")
    named = BladeTable(np.array([0.0, R]), np.full(2, 0.5), np.zeros(2), np.full(2, 0.1), np.zeros(2), np.zeros(2), ("naca", "naca"), "t")
    with pytest.raises(BladeError, match="defines no airfoil named 'naca'"):
        with_blade(GEOM, named)
