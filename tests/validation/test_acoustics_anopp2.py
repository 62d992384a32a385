"""Compact F1A against NASA ANOPP2 (code-to-code), all 44 cases.

Reference: tests/data/anopp2_compact_f1a (OpenMDAO/AcousticAnalogies.jl @ 8638416, ANOPP2 output).
Case: B = 2 CROTOR propeller, 200–2200 rpm, hub translating at 5 m/s along the rotation axis,
observer 30.48 m away in the rotor plane or 45° below, stationary or translating with the hub.
Sources go through the public long-table API (``nps.acoustics.radiate``, the CLI's function) with
analytic velocities; accelerations, jerks and force rates come from its 6th-order differences.
Criterion (the source project's): max |error| over the ANOPP2 window (≈ four blade passages) below
1 % of the ANOPP2 peak-to-peak, for the loading (dipole) and the compact-monopole thickness. The
windmilling 200 rpm, −45° cases need 4.5 % for the loading (the source project's own allowance;
an independent re-implementation reaches 3.7 % / 4.4 % there too). The dual-compact thickness
(two lines at 13 %/87 % chord, t = area/(0.685 c)) is compared with the monopole and reported.
"""

import numpy as np
import pandas as pd
import pytest

from nps.acoustics import radiate

STEPS_PER_REV = 256
REVOLUTIONS = 3
B, V_HUB, C0, RHO0, R_OBS = 2, 5.0, 340.0, 1.226, 30.48


def _sources(data_dir, nn, thickness):
    r, dr, chord, _, area, np_, tp = np.loadtxt(data_dir / f"anopp2_compact_f1a/ccblade_loads_omega{nn:02d}.csv", delimiter=",", comments="#").T
    omega = 200 * nn * 2 * np.pi / 60
    # start an eighth of a revolution early so the dual-compact lines ahead of the loading line cover the window
    tau = (np.arange(REVOLUTIONS * STEPS_PER_REV) - STEPS_PER_REV // 8) * 2 * np.pi / omega / STEPS_PER_REV
    frames, node = [], 0
    for k in range(B):
        phi = 2 * np.pi * k / B + omega * tau
        for e in range(r.size):
            # dual compact: lines ahead/behind the element along the motion direction (−cos φ, −sin φ)
            lines = [(0.0, 1.0, "loading")]
            if thickness == "dual":
                t = area[e] / (0.685 * chord[e])
                lines += [((0.25 - 0.13) * chord[e], 1.0, "thickness"), ((0.25 - 0.87) * chord[e], -1.0, "thickness")]
            for offset, sign, group in lines:
                x = -r[e] * np.sin(phi) - offset * np.cos(phi)
                y = r[e] * np.cos(phi) - offset * np.sin(phi)
                frame = {
                    "node": node, "group": group, "time_s": tau, "x_m": x, "y_m": y, "z_m": V_HUB * tau,
                    "vx_mps": -omega * y, "vy_mps": omega * x, "vz_mps": np.full_like(tau, V_HUB),
                }
                if group == "loading":
                    frame.update(fx_N=-tp[e] * np.cos(phi) * dr[e], fy_N=-tp[e] * np.sin(phi) * dr[e], fz_N=np.full_like(tau, -np_[e] * dr[e]))
                    if thickness == "monopole":
                        frame["volume_m3"] = np.full_like(tau, area[e] * dr[e])
                    elif thickness == "dual":
                        frame["volume_m3"] = np.zeros_like(tau)
                else:
                    push = sign * RHO0 * C0**2 * t * dr[e]
                    frame.update(fx_N=-push * np.cos(phi), fy_N=-push * np.sin(phi), fz_N=np.zeros_like(tau), volume_m3=np.zeros_like(tau))
                frames.append(pd.DataFrame(frame))
                node += 1
    return pd.concat(frames, ignore_index=True)


def _run(data_dir, nn, below, moving, thickness):
    name = f"anopp2_{'const_vel_' if moving else ''}omega{nn:02d}{'_theta-45' if below else ''}.csv"
    ref = np.loadtxt(data_dir / "anopp2_compact_f1a" / name, delimiter=",", comments="#")
    theta = np.radians(-45.0 if below else 0.0)
    observers = pd.DataFrame({"observer": [0], "x_m": [R_OBS * np.cos(theta)], "y_m": [0.0], "z_m": [R_OBS * np.sin(theta)],
                              "vx_mps": [0.0], "vy_mps": [0.0], "vz_mps": [V_HUB if moving else 0.0]})
    t = ref[:, 0]
    out = radiate(_sources(data_dir, nn, thickness), observers, t[0], (t[1] - t[0]) * t.size, t.size, c0_mps=C0, rho0_kg_m3=RHO0)
    assert np.allclose(out[out.group == "total"].time_s.to_numpy(), t, rtol=0, atol=1e-12)
    p = {g: out[out.group == g].p_Pa.to_numpy() for g in ("thickness", "loading")}
    err = {g: np.abs(p[g] - ref[:, col]).max() / np.ptp(ref[:, col]) for g, col in (("thickness", 1), ("loading", 2))}
    return err, p, ref


CASES = [(nn, below, moving) for moving in (False, True) for below in (False, True) for nn in range(1, 12)]


@pytest.mark.parametrize("nn,below,moving", CASES)
def test_anopp2_compact_monopole_and_loading(data_dir, nn, below, moving):
    """Thickness (compact monopole) and loading within 1 % of peak-to-peak (4.5 % loading at 200 rpm, −45°)."""
    err, _, _ = _run(data_dir, nn, below, moving, "monopole")
    assert err["thickness"] < 0.01
    assert err["loading"] < (0.045 if (nn == 1 and below) else 0.01)


def test_anopp2_dual_compact_thickness_vs_monopole(data_dir):
    """Dual compact (±ρ0c²·t·dr lines, design-notes) vs ANOPP2's compact monopole: measured and printed.

    For a compact section moving along its chord at speed U the two lines radiate
    ρ0c²·t·D·dr ∂²G/∂y_c² = ρ0 (t·D·dr)(c/U)² ∂²G/∂t², i.e. the monopole times (tD/A)/M² (D = 0.74 c,
    A = 0.685 t c): the same waveform, scaled by 1/M². Checked here: correlation with the ANOPP2
    thickness pulse > 0.99 and ratio·M_tip² constant within 3 % at 200–600 rpm (measured ratios 1168, 292,
    130: the dual-compact model with ρ0c² is not valid at these low tip Mach numbers 0.07–0.22;
    see docs/models/acoustics.md). The loading is unaffected (< 1 %).
    """
    scaled = []
    for nn in (1, 2, 3):
        err, p, ref = _run(data_dir, nn, False, False, "dual")
        ratio = np.ptp(p["thickness"]) / np.ptp(ref[:, 1])
        m_tip = 200 * nn * 2 * np.pi / 60 * 1.1684 / C0
        print(f"dual compact {200 * nn} rpm in plane: p2p ratio to ANOPP2 monopole {ratio:.1f}, ratio*M_tip^2 {ratio * m_tip**2:.4f}")
        assert np.corrcoef(p["thickness"], ref[:, 1])[0, 1] > 0.99
        assert err["loading"] < 0.01
        scaled.append(ratio * m_tip**2)
    assert np.ptp(scaled) / np.mean(scaled) < 0.03
