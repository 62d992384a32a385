"""HART-II baseline (BL) with the free wake (issue 12), against the measured M²C_n at r/R = 0.87
and the PIV tip-vortex positions (tests/data/hart_ii). Case: tests/validation/hart_ii_case.py,
360 × 50 disk, 1° load segments, 10° relaxation grid (``FreeWakeModel`` defaults).

Measured at the time of writing (Beddoes wake in brackets, docs/models/wake_bvi.md):
- advancing window 30°–80°: high-passed peak-to-peak 0.0503 vs measured 0.0217 (×2.31 [×2.1]),
  best-correlation lag −0.8° (ρ = 0.87) [−9.0°];
- retreating window 280°–330°: 0.0416 vs 0.0354 (×1.17 [×1.09]), lag −3.9° (ρ = 0.76) [+7.1°];
- PIV miss distance mean 0.155 m [0.148 m], vortices 0.063 m too low on average [0.094 m];
- halving the relaxation step (10° → 5°): peak |ΔU_P| 5.118 → 5.143 m/s (0.5 %).
Issue targets: phase within 5° met in both windows, retreating amplitude within 30 % met;
advancing amplitude (×2.31) and PIV miss < 0.05 m not met. The tests assert the measured state
with margins and that the free wake lifts the vortices toward the measured positions.
"""

import os
from pathlib import Path

import numpy as np
import pytest

import hart_ii_case as h
from nps import freewake, wake

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def free():
    return h.run_free()


def test_converged(free):
    solution = free.result.solution
    assert solution.residual_history[-1] < 0.01
    assert free.result.retrims["hart_ii"] is None  # one rotor: no interference, no re-trim


def test_bvi_amplitude_and_phase(free):
    """Both windows: correlation ρ ≥ 0.7 at a lag within ±10°, peak-to-peak within a factor 2.5."""
    for lo, hi, lag, rho, p2p_model, p2p_meas in h.window_comparison(free.psi_deg, free.cn_bvi):
        assert abs(lag) <= 10.0 and rho >= 0.7, (lo, hi, lag, rho)
        assert p2p_meas / 2.5 <= p2p_model <= 2.5 * p2p_meas, (lo, hi, p2p_model, p2p_meas)


def test_piv_vortex_positions(free):
    """Mean miss distance below 0.2 m and the vortices higher (closer to the measured ones) than
    the Beddoes wake puts them."""
    records = h.piv_miss_distances_free(free.result.solution)
    miss = np.array([r[-1] for r in records])
    dz_free = np.mean([r[6] - r[4] for r in records])
    beddoes = h.piv_miss_distances(h.run(n_psi=72, n_r=20).state, wake.WakeModel())
    dz_beddoes = np.mean([r[6] - r[4] for r in beddoes])
    assert len(records) == 46 and miss.mean() < 0.2
    assert dz_beddoes < dz_free < 0.0


def test_halving_the_relaxation_step(free):
    """10° → 5° relaxation grid changes the peak BVI |ΔU_P| on the disk by < 5 %."""
    fine = h.run_free(free_model=freewake.FreeWakeModel(steps_per_rev=72))
    coarse_peak = np.abs(free.result.results["hart_ii"].d_up_mps).max()
    fine_peak = np.abs(fine.result.results["hart_ii"].d_up_mps).max()
    assert abs(coarse_peak / fine_peak - 1.0) < 0.05


def test_write_figure(free, tmp_path):
    """BL loading, measured vs Beddoes vs free wake (written to $NPS_FIGURES_DIR when set)."""
    import matplotlib.pyplot as plt

    out = Path(os.environ.get("NPS_FIGURES_DIR", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    pm, cm = h.measured_cn()
    beddoes = h.run()
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for ax, filt in zip(axes, (lambda v: v, h.high_pass)):
        ax.plot(pm, filt(cm), "k", lw=1.2, label="measured (HART-II BL)")
        ax.plot(beddoes.psi_deg, filt(beddoes.cn_bvi), lw=0.9, label="NPS, Beddoes wake")
        ax.plot(free.psi_deg, filt(free.cn_bvi), lw=0.9, label="NPS, free wake")
    axes[0].set_ylabel("M²C_n")
    axes[1].set_ylabel("M²C_n, ≥ 10/rev")
    axes[1].set_xlabel("ψ (deg)")
    axes[0].legend(fontsize=8)
    axes[0].set_title("HART-II BL, r/R = 0.87")
    fig.tight_layout()
    fig.savefig(out / "hart_ii_free_wake.png", dpi=110)
    plt.close(fig)
    assert (out / "hart_ii_free_wake.png").stat().st_size > 10_000
