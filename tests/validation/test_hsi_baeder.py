"""Baeder-style hover case: 1/7-scale UH-1H (thesis Table 6.1), in-plane observer at 3.09 R.

Rotor: B = 2, R = 1.045 m, c = 0.0762 m, untwisted rectangular NACA 0012, hover, non-lifting
(Baeder et al. 1993 computed the zero-thrust case, so the signal is thickness noise only).
Signal: linear thickness noise computed here, independently of nps, as a set of compact
monopole lines (source-time dominant): each blade element of volume V radiates
p = ∂²/∂t² [ρ0 V / (4π r (1 − M_r))]_ret, with the observer-time derivative
∂/∂t = (1 − M_r)⁻¹ ∂/∂τ. One compact line per span is not enough at these Mach numbers (the
chord is not compact in observer time: at M = 0.95 it overpredicts the negative peak 4×), so
the NACA 0012 volume is spread over 12 chordwise lines (cosine spacing): 30 × 12 lines per
blade, 8192 source times and 1024 observer samples per revolution (peak and maximum shear slope
converged to 1 % and 3 % against 60 × 24 lines, 32768 / 4096 samples). To be replaced by
``nps.noise.acoustics`` once that module exists.

Acceptance (issue 7): M_r = M_tip and r = r0 for this observer (1e-6); after amplification
and shear the signal is single-valued at M_tip 0.88 and 0.90 and multivalued, hence
shock-fitted, from 0.925 (thesis ch. 6: "for cases Mach 0.925 and 0.95, the shock-fitting
algorithm kicks in"). Measured maximum shear slope max dδt/dt (folds when > 1): 0.26, 0.84,
2.55, 5.9 at 0.88, 0.90, 0.925, 0.95. The figure is written to the pytest temporary directory
and, when NPS_KEEP_FIGURES names a directory, kept there.
"""

import os
from pathlib import Path

import numpy as np
import pytest

from nps.noise import hsi
from nps.plots.hsi import plot_intermediate_grid

R, CHORD, B = 1.045, 0.0762, 2
RHO, C0 = 1.225, 340.29
N_OBS = 1024


def naca0012_half_thickness(x):
    """Half thickness over chord of NACA 0012 at chord fraction x."""
    return 0.6 * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1015 * x**4)


def thickness_signal(mtip, n_tau=8192, n_span=30, n_chord=12, root=0.2):
    """(Ω, observer grid over one revolution, p) of the hover thickness noise at (3.09 R, 0, 0)."""
    omega = mtip * C0 / R
    period = 2 * np.pi / omega
    edges = np.linspace(root * R, R, n_span + 1)
    r_el, dr = 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)
    e = 0.5 * (1 - np.cos(np.linspace(0, np.pi, n_chord + 1)))
    xc = 0.5 * (e[1:] + e[:-1])
    area = 2 * naca0012_half_thickness(xc) * np.diff(e) * CHORD**2
    offset = (xc - 0.25) * CHORD  # behind the quarter chord (pitch axis)
    x_obs = np.array([3.09 * R, 0.0, 0.0])
    tau = np.arange(n_tau) * period / n_tau
    dtau = period / n_tau
    grid = np.arange(N_OBS) * period / N_OBS
    p = np.zeros(N_OBS)
    for k in range(B):
        psi = omega * tau + 2 * np.pi * k / B
        e_r = np.stack([np.cos(psi), np.sin(psi), 0 * psi], -1)
        e_t = np.stack([-np.sin(psi), np.cos(psi), 0 * psi], -1)  # direction of motion (counterclockwise)
        for r_e, d_r in zip(r_el, dr):
            for off, a in zip(offset, area):
                y = r_e * e_r - off * e_t
                v = omega * (r_e * e_t + off * e_r)
                rv = x_obs - y
                r = np.linalg.norm(rv, axis=1)
                doppler = 1 - np.einsum("ij,ij->i", v, rv) / (r * C0)
                q = RHO * a * d_r / (4 * np.pi * r * doppler)
                d1 = (np.roll(q, -1) - np.roll(q, 1)) / (2 * dtau) / doppler
                d2 = (np.roll(d1, -1) - np.roll(d1, 1)) / (2 * dtau) / doppler
                p += np.interp(grid, tau + r / C0, d2, period=period)
    return omega, grid, p


def trim_row(omega):
    row = dict(rotor="uh1h", rotation_sign=1, n_blades=B, radius_m=R, omega_rad_s=omega, hub_x_m=0.0, hub_y_m=0.0,
               hub_z_m=0.0, vel_x_mps=0.0, vel_y_mps=0.0, vel_z_mps=0.0, density_kg_m3=RHO, speed_of_sound_mps=C0)
    row.update({f"r_gh_{i}{j}": float(i == j) for i in range(3) for j in range(3)})
    return row


@pytest.fixture(scope="module")
def cases():
    out = {}
    for mtip in (0.88, 0.90, 0.925, 0.95):
        omega, grid, p = thickness_signal(mtip)
        rotor = hsi.HsiRotor.from_trim_row(trim_row(omega))
        mach, dist = hsi.radiation_mach(rotor, np.array([[3.09 * R, 0.0, 0.0]]), np.zeros((1, 3)))
        p_amp = p * hsi.amplification(mach[0])
        sheared = grid - hsi.shear_delay_s(p_amp, mach[0], dist[0], rotor)
        final, n_shocks = hsi.process_signals(grid, p[None, :], mach, dist, rotor)
        out[mtip] = dict(rotor=rotor, grid=grid, p=p, p_amp=p_amp, mach=mach[0], dist=dist[0], sheared=sheared,
                         fit=hsi.fit_shocks(sheared, p_amp, rotor.period_s), final=final[0], n_shocks=int(n_shocks[0]))
    return out


def test_geometry_is_the_calibration_point(cases):
    for mtip, c in cases.items():
        assert c["mach"] == pytest.approx(mtip, rel=1e-6)
        assert c["dist"] == pytest.approx(3.09 * R, rel=1e-9)


def test_shock_appears_from_tip_mach_0925(cases, tmp_path):
    """Single-valued sheared signal at 0.88/0.90; multivalued and shock-fitted at 0.925/0.95, with one
    recompression shock per blade behind the negative peak (at 0.95 the positive spike ahead of the pulse
    also steepens into a front shock)."""
    for mtip, c in cases.items():
        folded = bool(np.any(np.diff(c["sheared"]) <= 0))
        assert folded == (mtip >= 0.925), mtip
        assert (c["n_shocks"] > 0) == (mtip >= 0.925)
        if mtip >= 0.925:
            fit = c["fit"]
            assert c["n_shocks"] == fit.shock_time_s.size and fit.shock_time_s.size % B == 0
            # every shock is compressive; each blade has one recompression shock out of its negative peak
            assert np.all(fit.p_after_pa > fit.p_before_pa)
            assert np.sum(fit.p_before_pa < 0.3 * c["p_amp"].min()) == B
        else:
            np.testing.assert_allclose(c["final"].min(), c["p_amp"].min(), rtol=0.02)
        assert np.isfinite(c["final"]).all()
    path = plot_intermediate_grid(
        {f"M_tip = {m}": (c["grid"], c["p"], c["p_amp"], c["sheared"], c["fit"]) for m, c in cases.items()},
        tmp_path / "hsi_baeder.png",
    )
    assert path.exists()
    keep = os.environ.get("NPS_KEEP_FIGURES")
    if keep:
        Path(keep).mkdir(parents=True, exist_ok=True)
        (Path(keep) / "hsi_baeder.png").write_bytes(path.read_bytes())
