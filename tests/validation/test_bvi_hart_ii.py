"""HART-II baseline: BVI loading at r/R = 0.87 and tip-vortex positions vs measurement.

Data: tests/data/hart_ii (HART-II via OpenCOPTER, see README there). Case set-up:
tests/validation/hart_ii_case.py. Model defaults (A, B, C, D = 0.5, 1, 1.1, 0.85; r_c = c/2;
Sears response; 0/1-rev harmonics removed). Figures are written to $NPS_FIGURES_DIR when set
(the copies in docs/figures/ were made that way).

Measured at the time of writing (docs/validation/hart_ii_airloads.md), Betz vortex structure (the default)
and Sears response with the local in-plane speed and compressible magnitude; the thesis' point
vortex in brackets:
- advancing window 30°–80°: high-passed (≥ 10/rev) peak-to-peak 0.0222 vs measured 0.0217
  (×1.02 [×2.09]; quasi-steady lifting line ×3.6 [×7.4]); cross-correlation 0.85 at a lag of
  −9°, while each measured event has its model event within 2.2° (median +0.7°): the lag is the
  wider model train shifted by one event spacing.
- retreating window 280°–330°: 0.0362 vs 0.0354 (×1.02 [×1.09]; quasi-steady ×3.1 [×3.3]);
  correlation 0.79 at +7°.
- PIV: mean miss distance 0.148 m (1.2 c), predicted vortices 0.094 m too low on average (the
  vortex structure does not move the wake).
"""

import os
from pathlib import Path

import numpy as np
import pytest

import hart_ii_case as h
from nps.wake import bvi
from nps.wake import prescribed as wake
from nps.wake.vortex import VortexModel


@pytest.fixture(scope="module")
def hart():
    return h.run()


@pytest.fixture(scope="module")
def hart_quasi_steady():
    return h.run(bvi_model=bvi.BVIModel(unsteady=False))


def test_bvi_events_in_measured_windows(hart):
    """BVI content (≥ 10/rev) is concentrated in the measured windows: the peak-to-peak of the
    high-passed M²C_n in 30°–80° and 280°–330° is ≥ 2× that in the quiet 120°–240° sector, as
    measured (a wake on the wrong side of the disk or a sign error moves the events)."""
    hp = h.high_pass(hart.cn_bvi)
    psi = hart.psi_deg

    def p2p(lo, hi):
        return np.ptp(hp[(psi >= lo) & (psi <= hi)])

    quiet = p2p(120, 240)
    assert p2p(30, 80) > 2 * quiet
    assert p2p(280, 330) > 2 * quiet
    pm, cm = h.measured_cn()
    hm = h.high_pass(cm)
    assert np.ptp(hm[(pm >= 30) & (pm <= 80)]) > 2 * np.ptp(hm[(pm >= 120) & (pm <= 240)])


def test_bvi_phase_and_amplitude(hart, hart_quasi_steady):
    """Phase: the high-passed model and measurement correlate with ρ ≥ 0.7 at a lag within
    ±10° in both windows. Amplitude: peak-to-peak within 30 % of the measured one in both
    windows (measured ×1.02 and ×1.02), and closer to it than the quasi-steady lifting line."""
    quasi_steady = h.window_comparison(hart_quasi_steady.psi_deg, hart_quasi_steady.cn_bvi)
    for (lo, hi, lag, rho, p2p_model, p2p_meas), qs in zip(h.window_comparison(hart.psi_deg, hart.cn_bvi), quasi_steady):
        assert abs(lag) <= 10.0 and rho >= 0.7, (lo, hi, lag, rho)
        assert abs(p2p_model / p2p_meas - 1.0) < 0.30, (lo, hi, p2p_model, p2p_meas)
        assert abs(np.log(p2p_model / p2p_meas)) < abs(np.log(qs[4] / p2p_meas))


def test_point_vortex_doubles_the_advancing_bvi():
    """The Betz structure is what brings the advancing amplitude down: with the thesis' point
    vortex (same wake, same response) it is ×2.09 the measured one, the retreating ×1.09 — the
    advancing-side vortices roll up from a sheet half a radius wide (diffuse), the retreating
    ones from a tip-loaded sheet (concentrated)."""
    point = h.run(model=wake.WakeModel(steps_per_rev=360, vortex=VortexModel(vortex_structure="point")))
    (_, _, _, _, adv, adv_meas), (_, _, _, _, ret, ret_meas) = h.window_comparison(point.psi_deg, point.cn_bvi)
    assert adv > 1.8 * adv_meas and abs(ret / ret_meas - 1.0) < 0.15, (adv / adv_meas, ret / ret_meas)


def test_advancing_bvi_event_timing(hart):
    """Each measured advancing-side event (30°–80°, peaks and troughs) has a model event of the
    same kind within 2.5° (measured −2.2° … +1.6°, median +0.7°): the best-correlation lag of
    −9° is the model's wider event train shifted by one event spacing (docs). On the retreating
    side the Beddoes events fall half a spacing (≈ ±6°) from the measured ones: no test."""
    pm, cm = h.measured_cn()
    lo, hi = h.WINDOWS_DEG[0]
    offsets = [e[3] for e in h.event_offsets(hart.psi_deg, hart.cn_bvi, pm, cm, lo, hi)]
    assert len(offsets) >= 6 and max(abs(d) for d in offsets) <= 2.5, offsets


def test_mean_loading_matches_measured_level(hart):
    """Trimmed to the test thrust, the mean M²C_n at r/R = 0.87 is within 10 % of measured."""
    _, cm = h.measured_cn()
    assert hart.cn_bvi.mean() == pytest.approx(cm.mean(), rel=0.10)


def test_tip_vortex_positions_against_piv(hart):
    """Every PIV vortex has a predicted vortex within 0.3 m (2.5 c) in its cut plane; the mean
    miss distance is below 0.2 m (1.65 c). (Beddoes' prescribed wake places the vortices
    ≈ 0.1 m too close to the disk here; see docs/validation/hart_ii_piv.md.)"""
    records = h.piv_miss_distances(hart.state, wake.WakeModel())
    miss = np.array([r[-1] for r in records])
    assert len(records) == 46
    assert miss.max() < 0.3
    assert miss.mean() < 0.2


def test_write_figures(hart, tmp_path):
    """The comparison figures render (written to $NPS_FIGURES_DIR when set)."""
    from nps.plots import wake as plots

    out = Path(os.environ.get("NPS_FIGURES_DIR", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    pm, cm = h.measured_cn()
    fig = plots.hart_ii_loading(pm, cm, hart.psi_deg, hart.cn_base, hart.cn_bvi,
                                (h.high_pass(cm), h.high_pass(hart.cn_bvi)), title="HART-II BL, r/R = 0.87")
    fig.savefig(out / "hart_ii_cnm2.png", dpi=110)
    records = h.piv_miss_distances(hart.state, wake.WakeModel())
    fig2 = plots.hart_ii_vortices(records, title="HART-II BL tip-vortex positions")
    fig2.savefig(out / "hart_ii_piv.png", dpi=90)
    assert (out / "hart_ii_cnm2.png").stat().st_size > 10_000
