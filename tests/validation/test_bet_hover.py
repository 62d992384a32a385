"""Hover checks of the blade element model against closed forms (thesis ch. 4, issue 3)."""

import math

import numpy as np
import pytest

from nps.rotor.bet import Controls, DiskGrid, rotor_loads, trim_rotor
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.geometry import OperatingPoint, RotorGeometry

R, OMEGA, RHO = 7.62, 28.0, 1.225


def test_hover_thrust_matches_closed_form_and_momentum_inflow():
    """Hover, no twist, no root cutout, no drag, no tip loss, incompressible: the trimmed rotor
    gives C_T = (σa/2)(θ0/3 − λ/2) to 1e-3 relative and λ = √(C_T/2) to 1e-8.

    The closed form is the small-angle limit of the exact-angle section model (differences
    O(θφ²/(θ − φ)), ~5e-4 here), so the case uses θ0 ≈ 2°; 200 radial stations keep the
    midpoint-rule error (≈ h²/4 = 2e-5) below it. In hover the linear inflow is uniform
    (χ = 0) and flapping has no effect (β̇ = U_R = 0)."""
    foil = LinearAirfoil(cd0=0.0, cd2=0.0, cl_max=10.0)
    g = RotorGeometry(name="ideal", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.0, twist_rad=0.0,
                      thickness_ratio=0.09, lock_number=8.0, airfoil=foil)
    k = g.solidity * foil.lift_slope_per_rad / 2.0
    theta = math.radians(2.0)
    lam = (-k / 2.0 + math.sqrt(k * k / 4.0 + 8.0 * k * theta / 3.0)) / 4.0  # closed form + momentum
    thrust = 2.0 * lam**2 * RHO * math.pi * R**2 * (OMEGA * R) ** 2
    op = OperatingPoint(OMEGA, 0.0, 0.0, 0.0, RHO, 1e9, thrust)
    t = trim_rotor(g, op, DiskGrid(8, 200), tip_loss=False, tol_rel=1e-7)
    ct, lambda0, theta0 = t.totals.ct, t.inflow.lambda0, t.controls.theta0_rad
    assert abs(ct / (k * (theta0 / 3.0 - lambda0 / 2.0)) - 1.0) < 1e-3
    assert abs(lambda0 / math.sqrt(ct / 2.0) - 1.0) < 1e-8
    assert t.inflow.kx == 0.0 and t.inflow.ky == 0.0


@pytest.mark.parametrize("hinge_offset_m", [0.0, 0.381])
def test_hover_loads_independent_of_azimuth(hinge_offset_m):
    """Hover with the full model (twist, tip loss, drag, compressibility, flapping): every
    disk-table column except ψ is the same at all azimuths to 1e-10 relative (β̇, zero, to
    1e-10 of Ω β0)."""
    g = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=0.15 * R,
                      twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0,
                      hinge_offset_m=hinge_offset_m)
    op = OperatingPoint(OMEGA, 0.0, 0.0, 0.0, RHO, 340.3, 5140.1 * 9.80665)
    t = trim_rotor(g, op, DiskGrid(90, 30))
    beta_dot_ref = OMEGA * abs(t.flapping.beta0_rad)  # β̇ is physically zero: compare with Ω β0
    for column in t.disk.columns.drop("psi_rad"):
        v = t.disk[column].to_numpy().reshape(90, 30)
        scale = beta_dot_ref if column == "beta_dot_rad_s" else np.abs(v).max()
        assert np.abs(v - v[0]).max() <= 1e-10 * scale, column
    assert t.iterations == 1


def test_hover_feathering_equals_flapping():
    """Hover, e = 0: the periodic flap response to cyclic pitch is β1s = θ1c, β1c = −θ1s
    (rotor-disk tilt follows the swashplate, 90° phase lag), exact in linear theory whatever
    the radial loading; within 2 % with exact angles, twist, tip loss and drag."""
    g = RotorGeometry(name="main", n_blades=4, radius_m=R, chord_m=0.58, root_cutout_m=1.1,
                      twist_rad=math.radians(-16.0), thickness_ratio=0.09, lock_number=8.0)
    op = OperatingPoint(OMEGA, 0.0, 0.0, 0.0, RHO, 340.3, 5e4)
    t = rotor_loads(g, op, DiskGrid(72, 40), Controls(0.12, math.radians(1.0), math.radians(0.5)))
    assert math.isclose(t.flapping.beta1s_rad, math.radians(1.0), rel_tol=0.02)
    assert math.isclose(t.flapping.beta1c_rad, -math.radians(0.5), rel_tol=0.02)
