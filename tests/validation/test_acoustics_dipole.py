"""Point forces against the analytic dipole field, near and far field (relative error 1e-4).

* Stationary force F(t) = F0 sin ωt at the origin: p = x̂·[Ḟ(t−r/c)/(c r) + F(t−r/c)/r²]/(4π) (exact).
* Constant force moving at M = 0.3 (uniform motion): the steady field in the moving frame ξ = x − V t is
  p = −F·∇_ξ (1/√(ξ₁²/β² + ξ₂² + ξ₃²)) / (4π β), β² = 1 − M² (Prandtl–Glauert solution of the convected
  wave equation: independent of the retarded-time formulation being tested).
Both through the long-table API (6th-order derivatives from the positions and forces).
"""

import numpy as np
import pandas as pd

from nps.noise.sources import radiate

C0 = 340.0


def _run(tau, pos, force, observers, t0, duration, n):
    src = pd.DataFrame({"node": 0, "time_s": tau, "x_m": pos[:, 0], "y_m": pos[:, 1], "z_m": pos[:, 2],
                        "fx_N": force[:, 0], "fy_N": force[:, 1], "fz_N": force[:, 2]})
    obs = pd.DataFrame({"observer": np.arange(len(observers)), "x_m": observers[:, 0], "y_m": observers[:, 1],
                        "z_m": observers[:, 2], "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0})
    out = radiate(src, obs, t0, duration, n, c0_mps=C0)
    total = out[out.group == "total"]
    return total.time_s.to_numpy().reshape(len(observers), n)[0], total.p_Pa.to_numpy().reshape(len(observers), n)


def test_stationary_oscillating_dipole():
    """Near (r = 0.39 m, kr ≈ 0.36) and far (r = 374 m) field within 1e-4 of the peak."""
    omega, f0 = 2 * np.pi * 50.0, np.array([3.0, -1.0, 2.0])
    tau = np.arange(-1.2, 0.1, 1e-4)
    force = f0[None, :] * np.sin(omega * tau)[:, None]
    observers = np.array([[0.3, 0.2, -0.15], [300.0, 200.0, -100.0]])
    t, p = _run(tau, np.zeros((tau.size, 3)), force, observers, 0.0, 0.04, 200)
    for o, x in enumerate(observers):
        r = np.linalg.norm(x)
        te = t - r / C0
        exact = (x / r) @ f0 * (omega * np.cos(omega * te) / (C0 * r) + np.sin(omega * te) / r**2) / (4 * np.pi)
        assert np.abs(p[o] - exact).max() < 1e-4 * np.abs(exact).max()


def test_uniformly_moving_force():
    """Constant force at M = 0.3 passing observers 2–50 m away: within 1e-4 of the convected-frame solution."""
    mach, f0 = 0.3, np.array([3.0, -1.0, 2.0])
    v = np.array([mach * C0, 0.0, 0.0])
    tau = np.arange(-0.6, 0.2, 2e-4)
    observers = np.array([[1.0, 2.0, -0.5], [30.0, 20.0, -10.0], [-5.0, 1.0, 3.0]])
    t, p = _run(tau, v[None, :] * tau[:, None], np.broadcast_to(f0, (tau.size, 3)), observers, 0.0, 0.02, 100)
    beta = np.sqrt(1 - mach**2)
    for o, x in enumerate(observers):
        xi = x[None, :] - v[None, :] * t[:, None]
        s = np.sqrt(xi[:, 0] ** 2 / beta**2 + xi[:, 1] ** 2 + xi[:, 2] ** 2)
        grad = -np.stack([xi[:, 0] / beta**2, xi[:, 1], xi[:, 2]], axis=1) / s[:, None] ** 3
        exact = -(grad @ f0) / (4 * np.pi * beta)
        assert np.abs(p[o] - exact).max() < 1e-4 * np.abs(exact).max()
