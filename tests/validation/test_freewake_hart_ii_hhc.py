"""HART-II with higher-harmonic control: BL → MN (θ3 = 0.8° at ψ3 = 300°) and MV (ψ3 = 180°),
each with its measured elastic-twist harmonics and trim targets (hart_ii_case.CASES), free wake
and Beddoes wake, against the measured M²C_n at r/R = 0.87 (tests/data/hart_ii).

Advancing-side (30°–80°) high-passed peak-to-peak, measured at the time of writing:

| case | measured | free wake | Beddoes |
| BL   | 0.0217   | 0.0426    | 0.0456  |
| MN   | 0.0599 (×2.76 of BL) | 0.0491 (×1.15) | 0.0489 (×1.07) |
| MV   | 0.0308 (×1.42)       | 0.0378 (×0.89) | 0.0365 (×0.80) |

Both wakes predict the measured increase from BL to MN (far too weakly) and a decrease from BL
to MV where the measurement increases (issue target not met for MV). The test asserts the MN
direction and writes the figure of all three against measurement.
"""

import os
from pathlib import Path

import pytest

import hart_ii_case as h

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def cases():
    return {name: h.run_free(case=h.CASES[name]) for name in ("BL", "MN", "MV")}


def _advancing_p2p(psi_deg, cn):
    return h.window_metrics(psi_deg, cn, *h.WINDOWS_DEG[0])[1]


def test_mn_raises_the_advancing_side_bvi_as_measured(cases):
    """Measured: the advancing-side peak-to-peak rises from BL to MN; the free wake too."""
    measured = {name: _advancing_p2p(*h.measured_cn(name)) for name in ("BL", "MN")}
    model = {name: _advancing_p2p(cases[name].psi_deg, cases[name].cn_bvi) for name in ("BL", "MN")}
    assert measured["MN"] > measured["BL"]
    assert model["MN"] > model["BL"]


def test_write_figure(cases, tmp_path):
    """BL, MN, MV: measured and free-wake M²C_n at r/R = 0.87, full and ≥ 10/rev
    (written to $NPS_FIGURES_DIR when set)."""
    import matplotlib.pyplot as plt

    out = Path(os.environ.get("NPS_FIGURES_DIR", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(3, 2, figsize=(11, 8), sharex=True)
    for row, name in enumerate(("BL", "MN", "MV")):
        pm, cm = h.measured_cn(name)
        for col, filt in enumerate((lambda v: v, h.high_pass)):
            ax = axes[row, col]
            ax.plot(pm, filt(cm), "k", lw=1.1, label="measured")
            ax.plot(cases[name].psi_deg, filt(cases[name].cn_bvi), lw=0.9, label="NPS, free wake")
            ax.set_ylabel(f"{name}: M²C_n" + (", ≥ 10/rev" if col else ""))
    axes[0, 0].legend(fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("ψ (deg)")
    fig.suptitle("HART-II r/R = 0.87: baseline, minimum-noise and minimum-vibration HHC")
    fig.tight_layout()
    fig.savefig(out / "hart_ii_hhc_free_wake.png", dpi=100)
    plt.close(fig)
    assert (out / "hart_ii_hhc_free_wake.png").stat().st_size > 10_000
