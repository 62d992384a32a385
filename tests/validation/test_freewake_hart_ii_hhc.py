"""HART-II with higher-harmonic control: BL → MN (θ3 = 0.8° at ψ3 = 300°) and MV (ψ3 = 180°),
each with its measured elastic twist, measured flap (2.5° precone) and trim targets
(hart_ii_case.CASES), free wake with the Betz vortex structure (defaults), against the measured
M²C_n at r/R = 0.87 (tests/data/hart_ii).

High-passed peak-to-peak, measured at the time of writing (docs/validation/hart_ii_airloads.md,
"Validation"; advancing ratio to BL in brackets):

| case | window | measured | measured flap | rigid flap | point vortex, measured flap |
| BL | 30°–80° | 0.0217 | 0.0201 | 0.0186 | 0.0439 |
| MN | 30°–80° | 0.0599 (×2.76) | 0.0283 (×1.41) | 0.0359 (×1.93) | 0.0448 (×1.02) |
| MV | 30°–80° | 0.0308 (×1.42) | 0.0386 (×1.92) | 0.0326 (×1.76) | 0.0476 (×1.08) |
| BL | 280°–330° | 0.0354 | 0.0327 | 0.0332 | 0.0393 |
| MN | 280°–330° | 0.0429 | 0.0415 | 0.0393 | 0.0434 |
| MV | 280°–330° | 0.0400 | 0.0468 | 0.0505 | 0.0510 |

NPS predicts the measured direction of change from BL to MN and to MV (issue target) with either
blade motion, by 40–90 % (the point vortex: 2–8 %, within the grid sensitivity). Within 30 % of
the measurement: BL and MV on the advancing side, all three on the retreating side; MN's
advancing amplitude is half the measured one.

PIV tip-vortex positions of all three conditions (tests/data/hart_ii/dnw_*_{bl,mn,mv}53.tec; MV's
opposite-sign inboard vortices left out), free wake as above, at the time of writing:

| case | vortices | mean miss | vertical error: mean, inner planes |y| < 1.2 m, outer |
| BL | 46 | 0.142 m | −0.066, −0.097, −0.042 m |
| MN | 43 | 0.134 m | −0.047, −0.087, −0.016 m |
| MV | 39 | 0.135 m | −0.069, −0.084, −0.057 m |

The HHC moves the vortices (same cut, nearest in x): MN lower, measured −0.031 m (advancing
−0.043 m), NPS −0.014 m (−0.020 m); MV higher, measured +0.016 m (+0.025 m), NPS +0.018 m
(+0.020 m).
"""

import os
from pathlib import Path

import numpy as np
import pytest

import hart_ii_case as h

pytestmark = pytest.mark.slow
NAMES = ("BL", "MN", "MV")


@pytest.fixture(scope="module")
def cases():
    return {name: h.run_free(case=h.CASES[name]) for name in NAMES}


@pytest.fixture(scope="module")
def rigid_flap():
    return {name: h.run_free(case=h.CASES[name], measured_flap=False) for name in NAMES}


@pytest.fixture(scope="module")
def piv_records(cases):
    return {name: h.piv_miss_distances_free(cases[name].result.solution, name) for name in NAMES}


def _p2p(psi_deg, cn, window=0):
    return h.window_metrics(psi_deg, cn, *h.WINDOWS_DEG[window])[1]


def test_direction_of_change_bl_to_mn_and_mv(cases):
    """Measured: the advancing-side peak-to-peak rises from BL to MN and from BL to MV; NPS too."""
    measured = {name: _p2p(*h.measured_cn(name)) for name in NAMES}
    model = {name: _p2p(cases[name].psi_deg, cases[name].cn_bvi) for name in NAMES}
    assert measured["MN"] > measured["BL"] and measured["MV"] > measured["BL"]
    assert model["MN"] > model["BL"] and model["MV"] > model["BL"], model


def test_changes_are_resolved_and_levels_measured(cases, rigid_flap):
    """BL → MN and BL → MV rise by more than 25 % with the measured and with the rigid flap (the
    grid sensitivity is < 5 %); BL and MV advancing and all retreating peak-to-peaks within 30 %
    of the measured ones (MN advancing: ×0.47, not asserted)."""
    for runs in (cases, rigid_flap):
        model = {name: _p2p(r.psi_deg, r.cn_bvi) for name, r in runs.items()}
        assert model["MN"] > 1.25 * model["BL"] and model["MV"] > 1.25 * model["BL"], model
    for name in NAMES:
        measured, predicted = _p2p(*h.measured_cn(name), 1), _p2p(cases[name].psi_deg, cases[name].cn_bvi, 1)
        assert abs(predicted / measured - 1.0) < 0.30, (name, predicted, measured)
    for name in ("BL", "MV"):
        measured, predicted = _p2p(*h.measured_cn(name)), _p2p(cases[name].psi_deg, cases[name].cn_bvi)
        assert abs(predicted / measured - 1.0) < 0.30, (name, predicted, measured)


def test_piv_vortex_positions_of_the_hhc_conditions(piv_records):
    """MN and MV PIV tip vortices are placed as well as BL's (mean miss < 0.15 m, vortices too low
    on the inner planes in all three: the same front-of-disk height error, docs "Where the height
    error is"), and the HHC moves the advancing-side vortices the measured way: MN down, MV up,
    each predicted shift between a third and twice the measured one."""
    records = piv_records
    assert {name: len(r) for name, r in records.items()} == {"BL": 46, "MN": 43, "MV": 39}
    for name, rec in records.items():
        assert np.mean([r[-1] for r in rec]) < 0.15, name
        assert np.mean([r[6] - r[4] for r in rec if abs(r[2]) < 1.2]) < -0.05, name
    for name, sign in (("MN", -1.0), ("MV", 1.0)):
        advancing = [(dm, dp) for side, dm, dp in h.paired_height_changes(records["BL"], records[name])
                     if side == "advancing"]
        measured, predicted = np.mean(advancing, axis=0)
        assert len(advancing) >= 20 and sign * measured > 0.01, (name, measured)
        assert 1.0 / 3.0 < predicted / measured < 2.0, (name, measured, predicted)


def test_write_figure(cases, rigid_flap, tmp_path):
    """BL, MN, MV: measured and free-wake M²C_n at r/R = 0.87, full and ≥ 10/rev, and the window
    peak-to-peaks (written to $NPS_FIGURES_DIR when set)."""
    import matplotlib.pyplot as plt
    import numpy as np

    out = Path(os.environ.get("NPS_FIGURES_DIR", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    fig = plt.figure(figsize=(11, 10.5))
    grid = fig.add_gridspec(4, 2)
    for row, name in enumerate(NAMES):
        pm, cm = h.measured_cn(name)
        for col, filt in enumerate((lambda v: v, h.high_pass)):
            ax = fig.add_subplot(grid[row, col])
            ax.plot(pm, filt(cm), "k", lw=1.1, label="measured")
            ax.plot(cases[name].psi_deg, filt(cases[name].cn_bvi), lw=0.9, label="NPS, free wake")
            ax.set_ylabel(f"{name}: M²C_n" + (", ≥ 10/rev" if col else ""))
            ax.set_xlim(0, 360)
            if row == 0 and col == 0:
                ax.legend(fontsize=8)
    for col, (window, label) in enumerate(((0, "advancing 30°–80°"), (1, "retreating 280°–330°"))):
        ax = fig.add_subplot(grid[3, col])
        x = np.arange(len(NAMES))
        bars = {"measured": [_p2p(*h.measured_cn(n), window) for n in NAMES],
                "NPS, measured flap": [_p2p(cases[n].psi_deg, cases[n].cn_bvi, window) for n in NAMES],
                "NPS, rigid flap": [_p2p(rigid_flap[n].psi_deg, rigid_flap[n].cn_bvi, window)
                                    if n in rigid_flap else np.nan for n in NAMES]}
        for k, (key, values) in enumerate(bars.items()):
            ax.bar(x + (k - 1) * 0.27, values, 0.27, label=key, color=("k", "C1", "C0")[k])
        ax.set_xticks(x, NAMES)
        ax.set_ylabel("peak-to-peak, ≥ 10/rev")
        ax.set_title(label, fontsize=10)
        if col == 0:
            ax.legend(fontsize=8)
    fig.suptitle("HART-II r/R = 0.87: baseline, minimum-noise and minimum-vibration HHC (free wake)")
    fig.tight_layout()
    fig.savefig(out / "hart_ii_hhc_free_wake.png", dpi=100)
    plt.close(fig)
    assert (out / "hart_ii_hhc_free_wake.png").stat().st_size > 10_000


def test_write_piv_figure(piv_records, tmp_path):
    """Height error of every PIV tip vortex (predicted − measured z) against x, per condition,
    coloured by the cut's |y| (written to $NPS_FIGURES_DIR when set)."""
    import matplotlib.pyplot as plt

    out = Path(os.environ.get("NPS_FIGURES_DIR", tmp_path))
    out.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, len(NAMES), figsize=(13, 4), sharey=True)
    for ax, name in zip(axes, NAMES):
        rec = piv_records[name]
        for side, marker in (("advancing", "o"), ("retreating", "x")):
            rows = np.array([r[2:7] for r in rec if r[0] == side])
            dots = ax.scatter(rows[:, 1], rows[:, 4] - rows[:, 2], c=np.abs(rows[:, 0]), marker=marker,
                              cmap="viridis", vmin=0.7, vmax=2.0, label=f"{side} side")
        miss = np.mean([r[-1] for r in rec])
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_title(f"{name}: {len(rec)} vortices, mean miss {miss:.3f} m", fontsize=10)
        ax.set_xlabel("x_H of the measured vortex (m, aft)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("z predicted − z measured (m)")
    axes[0].legend(fontsize=8)
    fig.colorbar(dots, ax=axes, label="|y| of the PIV cut (m)")
    fig.suptitle("HART-II PIV tip vortices against the free wake (measured blade motion)")
    fig.savefig(out / "hart_ii_piv_free_wake.png", dpi=100)
    plt.close(fig)
    assert (out / "hart_ii_piv_free_wake.png").stat().st_size > 10_000
