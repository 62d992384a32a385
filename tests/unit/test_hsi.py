"""Unit tests of nps.noise.hsi: eq. 6.1/6.4 fits, M_r kinematics, eq. 6.5 shear, shock fit API, process().

Tolerances: kinematics against closed forms to 1e-6 (parabolic refinement of 720 samples per
revolution); eq. 6.5 identities to 1e-12 relative; equal areas to 1e-9 relative.
"""

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import minimize_scalar

from nps.noise import hsi
from nps.core.frames import rot_x, rot_y

C0 = 340.0
RHO = 1.225


def trim_row(radius=1.0, mtip=0.8, velocity=(0.0, 0.0, 0.0), r_gh=np.eye(3), sign=1, n_blades=2, name="main", hub=(0, 0, 0)):
    row = dict(rotor=name, rotation_sign=sign, n_blades=n_blades, radius_m=radius, omega_rad_s=mtip * C0 / radius,
               hub_x_m=hub[0], hub_y_m=hub[1], hub_z_m=hub[2], vel_x_mps=velocity[0], vel_y_mps=velocity[1],
               vel_z_mps=velocity[2], density_kg_m3=RHO, speed_of_sound_mps=C0)
    row.update({f"r_gh_{i}{j}": float(r_gh[i, j]) for i in range(3) for j in range(3)})
    return row


def test_amplification_and_shear_fits_branches():
    """Eq. 6.1 is continuous at 0.687 (1e-3) and starts at 1; eq. 6.4 follows its two printed branches."""
    assert hsi.amplification(0.0) == pytest.approx(1.0)
    assert hsi.amplification(0.687 - 1e-12) == pytest.approx(hsi.amplification(0.687 + 1e-12), abs=1e-3)
    assert hsi.shear_angle_rad(0.5) == pytest.approx(0.0006 * np.exp(8.0675 * 0.5))
    m = 0.93
    assert hsi.shear_angle_rad(m) == pytest.approx(914.12 * m**3 - 2645.3 * m**2 + 2548.9 * m - 816.7)


def test_hover_in_plane_mach_r_equals_tip_mach():
    """Hover, in-plane observer: the tip velocity is along r̂ at the tangent point, max M_r = M_tip; distance = hub distance."""
    rotor = hsi.HsiRotor.from_trim_row(trim_row(mtip=0.9))
    obs = np.array([[3.09, 0.0, 0.0], [0.0, -7.0, 0.0], [-2.0, 2.0, 0.0]])
    mach, dist = hsi.radiation_mach(rotor, obs, np.zeros((3, 3)))
    np.testing.assert_allclose(mach, 0.9, rtol=1e-6)
    np.testing.assert_allclose(dist, np.linalg.norm(obs, axis=1), rtol=1e-12)


@pytest.mark.parametrize("sign", [1, -1])
def test_hover_out_of_plane_against_direct_maximisation(sign):
    """Hover, observer below the plane: max over φ of M_t (r_tip × ... ) computed by scipy on the closed form."""
    rotor = hsi.HsiRotor.from_trim_row(trim_row(mtip=0.85, sign=sign, n_blades=3))
    rng = np.random.default_rng(3)
    obs = rng.normal(size=(6, 3)) * 4.0
    obs[:, 2] = -np.abs(obs[:, 2]) - 0.5
    mach, _ = hsi.radiation_mach(rotor, obs, np.zeros_like(obs))
    for o, m in zip(obs, mach):
        def neg_mr(phi):
            tip = np.array([np.cos(phi), sign * np.sin(phi), 0.0])
            vel = 0.85 * np.array([-np.sin(phi), sign * np.cos(phi), 0.0])
            r = o - tip
            return -vel @ r / np.linalg.norm(r)
        best = min(minimize_scalar(neg_mr, bounds=(a, a + np.pi / 2), method="bounded", options={"xatol": 1e-10}).fun
                   for a in np.arange(4) * np.pi / 2)
        assert m == pytest.approx(-best, rel=1e-6)


def test_forward_flight_far_ahead_observer_sees_advancing_tip_mach():
    """Observer moving with the aircraft far ahead in plane: r̂ is the flight direction, M_r = M_tip + M_flight.

    Pitched shaft check: with the rotor plane tilted by 10° the in-plane-ahead max drops to
    M_tip·cos(10°) + M_flight (far field, 1e-4).
    """
    v = 0.2 * C0
    rotor = hsi.HsiRotor.from_trim_row(trim_row(mtip=0.7, velocity=(v, 0, 0)))
    far = np.array([[1e5, 0.0, 0.0]])
    mach, dist = hsi.radiation_mach(rotor, far, np.array([[v, 0.0, 0.0]]))
    assert mach[0] == pytest.approx(0.9, rel=1e-4)
    assert dist[0] == pytest.approx(1e5 / (1 - 0.2), rel=1e-4)  # path length c Δ with Δ = d / (c − V)
    tilted = hsi.HsiRotor.from_trim_row(trim_row(mtip=0.7, velocity=(v, 0, 0), r_gh=rot_y(np.radians(10.0))))
    mach, _ = hsi.radiation_mach(tilted, far, np.array([[v, 0.0, 0.0]]))
    assert mach[0] == pytest.approx(0.7 * np.cos(np.radians(10.0)) + 0.2, rel=1e-4)


def test_rotation_sign_and_frame_of_a_rolled_rotor():
    """A rotor plane rolled 90° about x (shaft along −y_G) radiates M_tip toward ±z in its own plane only."""
    rotor = hsi.HsiRotor.from_trim_row(trim_row(mtip=0.8, r_gh=rot_x(np.radians(90.0)), sign=-1))
    mach, _ = hsi.radiation_mach(rotor, np.array([[0, 0, 5.0], [0, 5.0, 0]]), np.zeros((2, 3)))
    assert mach[0] == pytest.approx(0.8, rel=1e-6)
    assert mach[1] == pytest.approx(0.0, abs=1e-9)


def test_shear_reproduces_calibrated_shear_at_r0_and_grows_linearly_for_fixed_source():
    """Eq. 6.5 reading: δt̃ = p̃ tan γ at r = r0; for p ∝ 1/r the delay grows ∝ r (1e-12)."""
    rotor = hsi.HsiRotor.from_trim_row(trim_row(radius=1.045, mtip=0.9))
    r0 = 3.09 * 1.045
    p = np.array([-500.0, 200.0])
    delay = hsi.shear_delay_s(p, 0.9, r0, rotor)
    delay_nd = delay * rotor.motion.omega_rad_s / (2 * np.pi)
    np.testing.assert_allclose(delay_nd, p / (RHO * C0**2) * np.tan(hsi.shear_angle_rad(0.9)), rtol=1e-12)
    source = 1000.0  # Pa·m
    d1 = hsi.shear_delay_s(source / r0, 0.9, r0, rotor)
    d5 = hsi.shear_delay_s(source / (5 * r0), 0.9, 5 * r0, rotor)
    assert d5 == pytest.approx(5 * d1, rel=1e-12)
    assert delay[0] < 0 < delay[1]  # positive pressure arrives earlier: t_shear = t − δt


def _loop_areas(t, p, t_s, p_minus, p_plus):
    """Signed ∫p dt of the input polyline between its crossings of t = t_s at p_minus and p_plus, split
    at the vertical line into the part left of it and the part right of it (independent of nps)."""
    pts = []
    for i in range(t.size - 1):
        a, b = t[i] - t_s, t[i + 1] - t_s
        if a == b or a * b > 0:
            continue
        w = a / (a - b)
        pts.append((i + w, p[i] + w * (p[i + 1] - p[i])))
    s_a = min(pts, key=lambda q: abs(q[1] - p_minus))[0]
    s_b = min(pts, key=lambda q: abs(q[1] - p_plus))[0]
    s_lo, s_hi = sorted((s_a, s_b))
    grid = np.concatenate([[s_lo], np.arange(np.ceil(s_lo), np.floor(s_hi) + 1), [s_hi]])
    grid = np.unique(np.concatenate([grid, [q[0] for q in pts if s_lo < q[0] < s_hi]]))
    idx = np.arange(t.size)
    tt, pp = np.interp(grid, idx, t), np.interp(grid, idx, p)
    seg = 0.5 * (pp[1:] + pp[:-1]) * np.diff(tt)
    mid = 0.5 * (tt[1:] + tt[:-1])
    return seg[mid < t_s].sum(), seg[mid > t_s].sum()


def test_single_fold_equal_areas_and_single_valued_output():
    """One fold (aperiodic): areas on both sides of the fitted shock agree to 1e-9; output strictly increasing."""
    t0 = np.linspace(-1.0, 1.0, 401)
    p = -np.tanh(4 * t0) * np.exp(-t0**2)
    t = t0 + 0.6 * p  # negative p is delayed: the pulse front folds
    fit = hsi.fit_shocks(t, p)
    assert fit.shock_time_s.size == 1
    assert np.all(np.diff(fit.time_s) > 0)
    left, right = _loop_areas(t, p, fit.shock_time_s[0], fit.p_before_pa[0], fit.p_after_pa[0])
    assert abs(left + right) <= 1e-9 * max(abs(left), abs(right))
    assert abs(left) > 1e-3


def test_single_valued_input_is_returned_unchanged():
    t = np.linspace(0.0, 1.0, 50, endpoint=False)
    p = np.sin(2 * np.pi * t)
    ft, fp = hsi.equal_area_shock_fit(t, p, period_s=1.0)
    np.testing.assert_array_equal(ft, t)
    np.testing.assert_array_equal(fp, p)


def test_mirror_symmetry_of_fold_orientation():
    """fit(t, −p) = −fit(t, p): folds whose backward steps lower p use the lower envelope (1e-12)."""
    t0 = np.linspace(0.0, 1.0, 256, endpoint=False)
    p = np.sin(2 * np.pi * t0) + 0.4 * np.cos(6 * np.pi * t0)
    t = t0 - 0.3 * p
    a = hsi.fit_shocks(t, p, 1.0)
    b = hsi.fit_shocks(t, -p, 1.0)
    assert a.shock_time_s.size >= 1
    np.testing.assert_array_equal(a.time_s, b.time_s)
    np.testing.assert_allclose(b.p_pa, -a.p_pa, atol=1e-12)


@pytest.mark.parametrize(
    "t, p, kw, match",
    [
        (np.zeros(2), np.zeros(2), {}, "1-D of equal length"),
        (np.array([0.0, 1.0, np.nan]), np.zeros(3), {}, "finite"),
        (np.array([0.0, 2.0, 1.0, 3.0, 2.5, 4.0]), np.array([0.0, -1.0, 1.0, 0.0, -1.0, 0.0]), {}, "both raise and lower"),
        (np.array([0.0, -1.0, 2.0]), np.array([0.0, 1.0, 2.0]), {}, "folds past its first"),
        (np.array([0.0, 0.5, 0.7]), np.zeros(3), {"period_s": -1.0}, "period_s must be > 0"),
    ],
)
def test_bad_input_is_refused(t, p, kw, match):
    with pytest.raises(ValueError, match=match):
        hsi.fit_shocks(t, p, **kw)


def _signals(ids, time_s, groups=("thickness", "loading")):
    rows = []
    for o in ids:
        for g, amp in zip(groups, (-300.0, 40.0)):
            rows.append(pd.DataFrame({"observer": o, "group": g, "time_s": time_s,
                                      "p_Pa": amp * np.exp(-((time_s - time_s.mean()) / 0.002) ** 2) * (1 + 0.1 * o)}))
    return pd.concat(rows, ignore_index=True)


def _observers(ids, positions, velocity):
    pos = np.asarray(positions, dtype=float)
    return pd.DataFrame({"observer": ids, "x_m": pos[:, 0], "y_m": pos[:, 1], "z_m": pos[:, 2],
                         "vx_mps": velocity[0], "vy_mps": velocity[1], "vz_mps": velocity[2],
                         "elevation_deg": 0.0, "azimuth_deg": 0.0})


def test_process_outputs_hsi_group_on_input_grid_and_intermediate():
    """process(): group 'hsi', same grid and observers, finite; in-plane observer shocks, the far-below one does
    not; the intermediate observer's final signal equals its row; amplification applied when nothing folds."""
    row = trim_row(radius=2.0, mtip=0.86, velocity=(30.0, 0.0, 0.0))
    period = 2 * np.pi / row["omega_rad_s"]
    time_s = np.arange(512) * period / 512
    ids = [3, 7]
    signals = _signals(ids, time_s)
    observers = _observers(ids, [[20.0, 0.0, 0.0], [0.0, 0.0, -20.0]], (30.0, 0.0, 0.0))
    res = hsi.process(signals, observers, row, intermediate_observer=3)
    out = res.signals
    assert list(out.columns) == ["observer", "group", "time_s", "p_Pa"]
    assert set(out["group"]) == {"hsi"} and np.isfinite(out["p_Pa"]).all()
    np.testing.assert_allclose(out[out.observer == 7]["time_s"].to_numpy(), time_s)
    diag = res.diagnostics.set_index("observer")
    assert diag.loc[3, "n_shocks"] >= 1 and diag.loc[7, "n_shocks"] == 0
    assert diag.loc[3, "mach_r"] > 0.94 > 0.2 > diag.loc[7, "mach_r"]
    np.testing.assert_allclose(res.intermediate.p_final_pa, out[out.observer == 3]["p_Pa"].to_numpy())
    np.testing.assert_allclose(res.intermediate.p_amplified_pa, res.intermediate.p_original_pa * diag.loc[3, "amplification"])
    total7 = signals[signals.observer == 7].groupby("time_s")["p_Pa"].sum().to_numpy()
    assert out[out.observer == 7]["p_Pa"].min() == pytest.approx(total7.min() * diag.loc[7, "amplification"], rel=2e-2)


def test_process_refuses_observers_not_moving_with_the_aircraft_and_missing_columns():
    row = trim_row(velocity=(30.0, 0.0, 0.0))
    time_s = np.arange(64) * 0.001
    with pytest.raises(ValueError, match="moving with the aircraft"):
        hsi.process(_signals([1], time_s), _observers([1], [[10.0, 0, 0]], (0.0, 0.0, 0.0)), row)
    with pytest.raises(ValueError, match="missing column"):
        hsi.process(_signals([1], time_s).drop(columns="group"), _observers([1], [[10.0, 0, 0]], (30.0, 0, 0)), row)
    with pytest.raises(ValueError, match="no row for observer"):
        hsi.process(_signals([1, 2], time_s), _observers([1], [[10.0, 0, 0]], (30.0, 0, 0)), row)


def test_combine_rotors_sums_per_observer_and_time():
    time_s = np.arange(32) * 0.01
    a = _signals([1, 2], time_s, groups=("thickness",)).assign(group="hsi")
    b = a.assign(p_Pa=2.0 * a["p_Pa"])
    total = hsi.combine_rotors([a, b])
    np.testing.assert_allclose(total["p_Pa"].to_numpy(), 3.0 * a.sort_values(["observer", "time_s"])["p_Pa"].to_numpy())
    with pytest.raises(ValueError, match="time grid"):
        hsi.combine_rotors([a, a.assign(time_s=a["time_s"] + 0.5)])


def test_cli_writes_hsi_table_diagnostics_intermediate_and_figure(tmp_path):
    """python -m nps hsi: artifacts written through nps.app.io with the contract columns; an unknown rotor is one line, exit 2."""
    from nps.cli.hsi import main
    from nps.app.io import read_metadata, read_table, write_table
    from tests.trim_tables import complete_trim

    row = trim_row(radius=2.0, mtip=0.86, velocity=(30.0, 0.0, 0.0))
    period = 2 * np.pi / row["omega_rad_s"]
    time_s = np.arange(256) * period / 256
    write_table(complete_trim(pd.DataFrame([row])), tmp_path / "trim.parquet", stage="trim")
    write_table(_signals([0, 1], time_s), tmp_path / "sig" / "main.parquet", stage="acoustics")
    write_table(_observers([0, 1], [[20.0, 0, 0], [0, 0, -20.0]], (30.0, 0, 0)), tmp_path / "obs.parquet", stage="observers")
    args = ["--signals", str(tmp_path / "sig"), "--observers", str(tmp_path / "obs.parquet"), "--trim", str(tmp_path / "trim.parquet"),
            "--out-dir", str(tmp_path / "hsi"), "--observer", "0", "--figure", str(tmp_path / "fig.png"), "--rotor"]
    assert main(args + ["main"]) == 0
    out = read_table(tmp_path / "hsi/main.parquet", required=("observer", "group", "time_s", "p_Pa"))
    assert len(out) == 2 * 256 and read_metadata(tmp_path / "hsi/main.parquet")["stage"] == "hsi"
    assert set(read_table(tmp_path / "hsi/main_observer.parquet")["step"]) == {"original", "amplified", "sheared", "fitted", "final"}
    assert read_table(tmp_path / "hsi/main_diagnostics.parquet")["n_shocks"].iloc[0] >= 1
    assert (tmp_path / "fig.png").stat().st_size > 0
    assert main(args + ["tail"]) == 2


def test_hsi_and_its_figures_import_without_the_kernels():
    """Summing or plotting HSI signals (hsi_figure job) does not load the compiled HSI kernels:
    nps.noise.hsi imports nps.noise.hsi_kernels only when a kernel runs."""
    import subprocess
    import sys
    from pathlib import Path

    code = "import sys, nps.noise.hsi, nps.plots.hsi; print('nps.noise.hsi_kernels' in sys.modules)"
    repo = Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, "-c", code], cwd=repo, capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
