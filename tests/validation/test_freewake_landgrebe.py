"""Free-wake hover geometry against Landgrebe's generalised wake (Landgrebe 1972, J. AHS 17(4);
equations as given by Leishman, Principles of Helicopter Aerodynamics, ch. 10):

    r_v/R = A + (1 − A) e^{−Λ φ},  A = 0.78,  Λ = 0.145 + 27 C_T
    z_v/R = k1 φ (φ ≤ 2π/B),  k1 2π/B + k2 (φ − 2π/B) (φ > 2π/B)
    k1 = −0.25 (C_T/σ + 0.001 θ_tw),  k2 = −(1 + 0.01 θ_tw) √C_T   (θ_tw in degrees)

These are fits to smoke-flow measurements, so the free wake (which knows none of them) is an
independent check. Rotor inside Landgrebe's test range: B = 4, blade aspect ratio 13.9
(c = R/13.9, σ = 0.092), θ_tw = −8°, C_T = 0.005 (k1 = −0.0117, k2 = −0.0650 per rad),
trimmed by nps.rotor.bet; z measured from the release point (tip-path plane). Wake: 3 free + 1 far
revolutions and the semi-infinite continuation (continuation_radii = 50, off by default),
relaxed to a node change < 0.1 % R (the default 1 % stops at 5 iterations, with the
pre-passage rise 0.005 R short of its converged value).

Measured (docs/validation/landgrebe_hover.md, "Landgrebe hover"), before → after the far-wake continuation:
- contraction at ages 2–3 revolutions: 0.726–0.735 R → 0.722–0.737 R against 0.781–0.787
  (−7.2 … −6.5 % → −7.6 … −6.2 %): within the issue's 10 %;
- far descent rate (ages 1–2 revolutions): k2 = −0.0487 → −0.0511 per rad (−25 % → −21 %);
- before the first blade passage the vortex rises 0.035 R → 0.025 R instead of descending
  0.018 R (k1 = +0.022 → +0.016 per rad against −0.0117).
k1 and k2 within 10 % are not met: the 10 % tests are strict expected failures (they fail the
suite once the physics meets them, so that they are turned into plain tests). Why (docs): a
steady helix of tip vortices of strength Γ_v = max_r Γ cannot descend faster than the
self-induced velocity of the infinite vortex cylinder, √(C_T,Γ/2) = 0.058 per rad with
C_T,Γ = B Γ̄/(2π Ω R²) = 0.0068 (11 % below Landgrebe's k2 even infinitely far below the disk);
the model's far descent approaches that bound (test_far_descent_approaches_the_vortex_cylinder).
A wake-coupled lifting line on Landgrebe's own tip-vortex geometry raises Γ̄ by 10 % (the hover
tip peak), the bound only to 0.061; the pre-passage rise does not change when all strengths are
scaled; free inboard trailers reduce it to +0.011, and coupled to a lifting line to +0.004: the
downwash that holds the young vortex down comes from the narrow sheet trailed beside it, which
needs cores thinner than the relaxation converges with (docs, "Landgrebe hover").
"""

import numpy as np
import pytest

from nps.rotor import bet

from nps.wake import bvi

from nps.wake import free as freewake

from nps.wake import prescribed as wake
from nps.rotor.geometry import OperatingPoint, RotorGeometry

B, CT, TWIST_DEG = 4, 0.005, -8.0
R, OMEGA = 1.0, 100.0
CHORD = R / 13.9
SIGMA = B * CHORD / (np.pi * R)
K1 = -0.25 * (CT / SIGMA + 0.001 * TWIST_DEG)
K2 = -(1.0 + 0.01 * TWIST_DEG) * np.sqrt(CT)
PASSAGE = 2.0 * np.pi / B
CONTINUATION_R = 50.0  # semi-infinite far wake, 50 R long (FreeWakeModel.continuation_radii)


def _relaxed(placement, **model):
    model = freewake.FreeWakeModel(**{**dict(revolutions=3.0, far_revolutions=1.0, continuation_radii=CONTINUATION_R,
                                             tolerance_radius_fraction=0.001), **model})
    solution = freewake.relax([placement], wake.WakeModel(), model)
    nodes = freewake.snapshot_nodes(solution, "landgrebe", 0.0)[0] / R
    phi = np.arange(nodes.shape[0]) * model.step_rad
    return phi, np.hypot(nodes[:, 0], nodes[:, 1]), nodes[:, 2] - nodes[0, 2], solution


def _slope(phi, z, lo, hi):
    """Least-squares descent rate dz/dφ (R per rad) over ages lo…hi (rad)."""
    sel = (phi >= lo - 1e-9) & (phi <= hi + 1e-9)
    return np.polyfit(phi[sel], z[sel], 1)[0]


@pytest.fixture(scope="module")
def placement():
    g = RotorGeometry(name="landgrebe", n_blades=B, radius_m=R, chord_m=CHORD, root_cutout_m=0.2 * R,
                      twist_rad=np.radians(TWIST_DEG), thickness_ratio=0.12, lock_number=8.0)
    thrust = CT * 1.225 * np.pi * R**2 * (OMEGA * R) ** 2
    trim = bet.trim_rotor(g, OperatingPoint(OMEGA, 0.0, 0.0, 0.0, 1.225, 340.0, thrust), bet.DiskGrid(72, 30))
    row = dict(n_blades=B, radius_m=R, omega_rad_s=OMEGA, rotation_sign=1, mu_x=0.0, mu_y=0.0, mu_z=0.0)
    return freewake.RotorPlacement("landgrebe", bvi.wake_state(trim.disk, row, trim.totals.ct), np.zeros(3), np.eye(3))


@pytest.fixture(scope="module")
def hover(placement):
    return _relaxed(placement)


def test_converged(hover):
    assert hover[3].residual_history[-1] < 0.001


def test_radial_contraction(hover):
    """Issue target: tip-vortex radius over ages 2–3 revolutions within 10 % of Landgrebe's."""
    phi, r, _, _ = hover
    landgrebe = 0.78 + 0.22 * np.exp(-(0.145 + 27.0 * CT) * phi)
    sel = (phi >= 4 * np.pi) & (phi <= 6 * np.pi)
    assert np.all(np.abs(r[sel] / landgrebe[sel] - 1.0) < 0.10)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="k1 not reproduced: the vortex rises 0.025 R before the first blade passage "
                          "(docs/validation/landgrebe_hover.md, Landgrebe hover)")
def test_descent_before_the_first_blade_passage(hover):
    """Issue target: k1 = z(2π/B)/(2π/B) within 10 % of Landgrebe's."""
    phi, _, z, _ = hover
    k1 = np.interp(PASSAGE, phi, z) / PASSAGE
    assert abs(k1 / K1 - 1.0) < 0.10, (k1, K1)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="k2 21 % slow: above the tip-vortex cylinder's self-induced descent "
                          "(docs/validation/landgrebe_hover.md, Landgrebe hover)")
def test_far_descent_rate(hover):
    """Issue target: k2 (least squares over ages 1–2 revolutions) within 10 % of Landgrebe's."""
    phi, _, z, _ = hover
    k2 = _slope(phi, z, 2 * np.pi, 4 * np.pi)
    assert abs(k2 / K2 - 1.0) < 0.10, (k2, K2)


def test_descent_measured_state(hover):
    """What the model meets (margins on the measured −21 % and +0.025 R): k2 within 25 % of
    Landgrebe's; the vortex passes the next blade within 0.03 R of the tip-path plane."""
    phi, _, z, _ = hover
    k2 = _slope(phi, z, 2 * np.pi, 4 * np.pi)
    assert k2 < 0.0 and abs(k2 / K2 - 1.0) < 0.25, (k2, K2)
    assert abs(np.interp(PASSAGE, phi, z)) < 0.03


def test_far_descent_approaches_the_vortex_cylinder(hover, placement):
    """At ages 2–3 revolutions the descent rate is 85–100 % of the self-induced velocity of an
    infinite helix of the same tip vortices, √(C_T,Γ/2), C_T,Γ = B Γ̄/(2π Ω R²) (vortex
    cylinder γ = B Γ̄/L, edge velocity γ/2, L = 2π R |k|): it tends to the far value from below
    (measured 0.91)."""
    phi, _, z, _ = hover
    ct_gamma = B * np.mean(placement.state.gamma_table_m2_s) / (2 * np.pi * OMEGA * R**2)
    ratio = -_slope(phi, z, 4 * np.pi, 6 * np.pi) / np.sqrt(ct_gamma / 2.0)
    assert 0.85 < ratio <= 1.0, ratio


def test_continuation_adds_the_far_wake_downwash(hover, placement):
    """Without the semi-infinite continuation (truncated helix, 1 far revolution) the far
    descent is slower (measured −0.0477 against −0.0511 per rad, 7 %)."""
    phi, _, z, _ = hover
    t_phi, _, t_z, _ = _relaxed(placement, continuation_radii=0.0)
    assert _slope(phi, z, 2 * np.pi, 4 * np.pi) < 1.05 * _slope(t_phi, t_z, 2 * np.pi, 4 * np.pi)
