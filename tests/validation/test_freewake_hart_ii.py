"""HART-II baseline (BL) with the free wake (issue 12), against the measured M²C_n at r/R = 0.87
and the PIV tip-vortex positions (tests/data/hart_ii). Case: tests/validation/hart_ii_case.py
with the measured blade motion (elastic twist and flap with the 2.5° precone, ``CASES["BL"]``),
360 × 50 disk, 1° load segments, 10° relaxation grid (``FreeWakeModel`` defaults).

Measured at the time of writing (docs/validation/hart_ii_airloads.md, "Validation"), Betz vortex structure
(the default; point vortex in brackets):
- advancing window 30°–80°: high-passed peak-to-peak 0.0201 vs measured 0.0217 (×0.92 [×2.02]),
  best-correlation lag +9.1° (ρ = 0.83) [+8.9°];
- retreating window 280°–330°: 0.0327 vs 0.0354 (×0.92 [×1.11]), lag −3.9° (ρ = 0.79) [−4.1°];
- event timing (each measured peak/trough against the nearest model one of the same kind):
  advancing −2.2° … −0.4° (median −0.7°), retreating median −4.2°; the advancing lag above is
  the model's wider event train, shifted by one event spacing (docs);
- PIV miss distance mean 0.142 m (wake as the loads see it, 4 revolutions; the vortex structure
  does not move the wake); vortices 0.066 m too low on average, retreating side 0.035 m,
  advancing side 0.082 m.
Issue targets met: both amplitudes within 30 %, phase within 5° on both sides by event timing
(the advancing best-correlation lag, +9.1°, is not). Not met: PIV miss < 0.05 m (0.142 m;
causes in the docs).
"""

import os
from pathlib import Path

import numpy as np
import pytest

import hart_ii_case as h
from nps.wake import free as freewake
from nps.wake import prescribed as wake

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def free():
    return h.run_free(case=h.CASES["BL"])


@pytest.fixture(scope="module")
def piv(free):
    """PIV comparison records of the relaxed wake (``h.piv_miss_distances_free``)."""
    return h.piv_miss_distances_free(free.result.solution)


def _mean_dz(records, side):
    return np.mean([r[6] - r[4] for r in records if r[0] == side])


def test_converged(free):
    solution = free.result.solution
    assert solution.residual_history[-1] < 0.01
    assert free.result.retrims["hart_ii"] is None  # one rotor: no interference, no re-trim


def test_bvi_amplitude_and_phase(free):
    """Both windows: peak-to-peak within 30 % of the measured one (issue target; measured ×0.92
    and ×0.92); correlation ρ ≥ 0.7 at a lag within 10° (the phase target is checked event by
    event below)."""
    for lo, hi, lag, rho, p2p, meas in h.window_comparison(free.psi_deg, free.cn_bvi):
        assert abs(p2p / meas - 1.0) < 0.30, (lo, hi, p2p, meas)
        assert abs(lag) <= 10.0 and rho >= 0.7, (lo, hi, lag, rho)


def test_bvi_event_timing(free):
    """Each BVI event against the measured one (``h.event_offsets``): in the advancing window all
    (≥ 6) measured peaks and troughs have a model event of the same kind within 2.5° (measured
    −2.2° … −0.4°, median −0.7°); in the retreating window the median offset is within 5°
    (measured −4.2°). The best-correlation lag of the advancing train (+8.9°) is a hop by one
    event spacing: the model's train is wider (strong events at 15°–25° and 60°–75°, where the
    measured ones are weak), and the correlation at −1° is 0.78 against 0.86 at +9°."""
    pm, cm = h.measured_cn()
    (lo_a, hi_a), (lo_r, hi_r) = h.WINDOWS_DEG
    advancing = [e[3] for e in h.event_offsets(free.psi_deg, free.cn_bvi, pm, cm, lo_a, hi_a)]
    retreating = [e[3] for e in h.event_offsets(free.psi_deg, free.cn_bvi, pm, cm, lo_r, hi_r)]
    assert len(advancing) >= 6 and max(abs(d) for d in advancing) <= 2.5, advancing
    assert abs(np.median(retreating)) <= 5.0, retreating


def test_piv_vortex_positions(piv):
    """Mean miss distance below 0.15 m; the vortices higher (closer to the measured ones) than the
    Beddoes wake puts them; the measured flap (precone, tip down on the advancing side, up on the
    retreating side) lifts the retreating-side vortices by > 1 cm against the rigid-flap model."""
    miss = np.array([r[-1] for r in piv])
    dz_free = np.mean([r[6] - r[4] for r in piv])
    beddoes = h.piv_miss_distances(h.run(n_psi=72, n_r=20).state, wake.WakeModel())
    dz_beddoes = np.mean([r[6] - r[4] for r in beddoes])
    assert len(piv) == 46 and miss.mean() < 0.15
    assert dz_beddoes < dz_free < 0.0
    rigid = h.piv_miss_distances_free(h.run_free(case=h.CASES["BL"], measured_flap=False).result.solution)
    assert _mean_dz(piv, "retreating") > _mean_dz(rigid, "retreating") + 0.01


@pytest.mark.xfail(strict=True, reason="issue 12 target not met: mean miss 0.142 m (docs/validation/hart_ii_piv.md, "
                   "HART-II: front-half upwash and faster convection that no rotor-wake element gives)")
def test_piv_mean_miss_within_the_issue_target(piv):
    """Issue 12: PIV tip-vortex mean miss distance < 0.05 m (measured 0.142 m)."""
    assert np.mean([r[-1] for r in piv]) < 0.05


def test_front_half_convection_speed(piv):
    """Spacing of consecutive vortices in the front half of the PIV cuts, in blade-passage advances
    of the free stream (``h.convection_spacings``, 13 pairs): measured 1.04–1.21 (mean 1.12), the wake
    speeding up over the front half; NPS's free wake convects at the free-stream speed (mean
    within 5 % of 1; measured 0.96–1.07). The gap is the streamwise half of the PIV miss
    (docs/validation/hart_ii_piv.md, "Streamwise convection")."""
    measured, predicted = h.convection_spacings(piv)
    assert measured.size >= 12
    assert measured.mean() >= 1.08
    assert abs(predicted.mean() - 1.0) < 0.05


def test_halving_the_relaxation_step(free):
    """10° → 5° relaxation grid changes the peak BVI |ΔU_P| on the disk by < 5 %."""
    fine = h.run_free(case=h.CASES["BL"], free_model=freewake.FreeWakeModel(steps_per_rev=72))
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
        ax.plot(beddoes.psi_deg, filt(beddoes.cn_bvi), lw=0.9, label="NPS, Beddoes wake (rigid blade)")
        ax.plot(free.psi_deg, filt(free.cn_bvi), lw=0.9, label="NPS, free wake (measured blade motion)")
    axes[0].set_ylabel("M²C_n")
    axes[1].set_ylabel("M²C_n, ≥ 10/rev")
    axes[1].set_xlabel("ψ (deg)")
    axes[0].legend(fontsize=8)
    axes[0].set_title("HART-II BL, r/R = 0.87")
    fig.tight_layout()
    fig.savefig(out / "hart_ii_free_wake.png", dpi=110)
    plt.close(fig)
    assert (out / "hart_ii_free_wake.png").stat().st_size > 10_000
