"""End-to-end: the bundled rigs (config/rigs/) through the command and the Snakefile, and a small rig whose
jobs read its own settings only (config/config.yaml does not reach a rig)."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from nps.cli.rotor import main as rotor_command
from nps.app.io import read_table

REPO = Path(__file__).resolve().parents[2]


def _snakemake(workdir: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "snakemake", "-s", str(REPO / "Snakefile"), "-d", str(workdir), *args],
                          capture_output=True, text=True, timeout=1800)


def test_itr_hover_through_the_rotor_command(tmp_path):
    """The ideally twisted rotor in hover (fixed pitch and speed) through set-up, loads and acoustics: the
    BPF tone falls monotonically from the rotor plane to the axis, where the steady axisymmetric loads
    radiate no tone at all."""
    assert rotor_command(["--rig", str(REPO / "config/rigs/itr_hover.yaml"), "--out-dir", str(tmp_path)]) == 0
    levels = pd.read_csv(tmp_path / "levels.csv")
    bpf1 = levels["bpf1_db"].to_numpy()
    assert np.all(np.diff(bpf1) < 0.0) and bpf1[-1] < 0.0 < bpf1[0]
    row = read_table(tmp_path / "trim.parquet").iloc[0]
    assert row["omega_rad_s"] == pytest.approx(5465.0 * np.pi / 30.0, rel=1e-12) and row["thrust_N"] > 0.0


def _jobs(dry_run_output: str) -> list[str]:
    """Rules of the jobs a dry run lists."""
    return re.findall(r"^(?:localrule|rule) (\w+):", dry_run_output, flags=re.M)


def test_a_rig_runs_the_study_rules_with_its_own_settings(tmp_path):
    """A small HART-II BL rig (coarse disk, 2.5 wake revolutions, 2 x 2 microphones) through `snakemake rigs`:
    set-up, the study's loads, wake, acoustics and metrics rules, and the carpet, into results/rigs/NAME/.
    Then config/config.yaml's resolution, models, wake, acoustics, atmosphere and validity switch change:
    a dry run with params as rerun trigger schedules no rig job; a change of the rig's own wake does."""
    root = tmp_path / "work"
    shutil.copytree(REPO / "config", root / "config")
    rigs = root / "config" / "rigs"
    for path in rigs.glob("*.yaml"):
        path.unlink()
    rig = yaml.safe_load((REPO / "config/rigs/hart_ii_bl.yaml").read_text())
    rig.update(name="small", resolution={"n_psi": 36, "n_r": 10, "samples_per_rev": 64, "wake_revolutions": 2.5},
               microphones=[{"kind": "plane", "x_m": [-1.0, 1.0], "y_m": [-1.0, 1.0], "z_m": -2.215}])
    (rigs / "small.yaml").write_text(yaml.safe_dump(rig, sort_keys=False))
    result = _snakemake(root, "-j2", "rigs")
    assert result.returncode == 0, result.stderr[-4000:]
    base = root / "results" / "rigs" / "small"
    assert (base / "carpet.png").stat().st_size > 10_000
    metrics = read_table(base / "metrics" / "microphones_bvi.parquet")
    assert len(metrics) == 4 and np.isfinite(metrics["bvispl_db"]).all()
    assert [p.name for p in (base / "bvi").glob("*.parquet")] == ["hart_ii.parquet"]

    campaign = root / "config" / "config.yaml"
    config = yaml.safe_load(campaign.read_text())
    config["resolution"].update(n_psi=72, n_r=20, samples_per_rev=128, wake_revolutions=2)
    config["models"].update(thickness="compact_monopole", broadband="bpm", absorption=False)
    config["wake"].update(A=0.7, core_radius_chords=0.3, vortex_structure="point", step_deg=10.0, unsteady=False)
    config["acoustics"].update(dual_compact_chord_fractions=[0.2, 0.8], bvispl_harmonics=[8, 30])
    config["atmosphere"].update(altitude_m=500.0, relative_humidity_pct=40.0)
    config["campaign"]["allow_outside_validity"] = True
    campaign.write_text(yaml.safe_dump(config, sort_keys=False))
    dry = _snakemake(root, "-n", "rigs", "--rerun-triggers", "params")
    assert dry.returncode == 0, dry.stderr[-4000:]
    assert "Nothing to be done" in dry.stdout + dry.stderr, _jobs(dry.stdout + dry.stderr)

    # the rig's own wake: its file keeps its time (a newer set-up input reruns every job of the rig), so the
    # jobs listed are the wake, whose params changed, and what reads it
    rig["wake"]["A"] = 0.6
    written = (rigs / "small.yaml").stat()
    (rigs / "small.yaml").write_text(yaml.safe_dump(rig, sort_keys=False))
    os.utime(rigs / "small.yaml", ns=(written.st_atime_ns, written.st_mtime_ns))
    dry = _snakemake(root, "-n", "rigs", "--rerun-triggers", "params")
    assert dry.returncode == 0, dry.stderr[-4000:]
    assert set(_jobs(dry.stdout + dry.stderr)) == {"wake", "acoustics", "metrics", "carpet", "rigs"}


# measured BVISPL carpets (DNW, via PsuAeroacoustics/OpenCOPTER; tests/data/hart_ii/README.md) of the bundled rigs
MEASURED_CARPET = {"hart_ii_bl": "bl", "hart_ii_bl_measured": "bl", "hart_ii_mn_measured": "mn", "hart_ii_mv_measured": "mv"}


@pytest.fixture(scope="module")
def rig_results(tmp_path_factory) -> Path:
    """`snakemake rigs` in a copy of config/: every bundled rig; its results directory (results/rigs)."""
    root = tmp_path_factory.mktemp("rigs")
    shutil.copytree(REPO / "config", root / "config")
    result = _snakemake(root, "-j2", "rigs")
    assert result.returncode == 0, result.stderr[-4000:]
    return root / "results" / "rigs"


def _metrics(base: Path, rig: str) -> pd.DataFrame:
    """Metrics of the rig's microphones (variant bvi for HART-II, base for the ITR hover)."""
    return read_table(base / rig / "metrics" / f"microphones_{'base' if rig == 'itr_hover' else 'bvi'}.parquet")


def _carpet(base: Path, rig: str) -> pd.DataFrame:
    """NPS BVISPL of the rig's microphones with the measured level ``measured_db`` where the measured carpet has
    the microphone (the MV carpet lacks the x_T = 2 m station)."""
    carpet = read_table(base / rig / "observers" / "microphones.parquet").merge(_metrics(base, rig), on="observer")
    measured = np.loadtxt(REPO / f"tests/data/hart_ii/{MEASURED_CARPET[rig]}-contour-meas.tec", skiprows=3)
    level = {(round(y, 2), round(x, 2)): bvispl for y, x, _, bvispl, *_ in measured}
    carpet["measured_db"] = [level.get((round(y, 2), round(x, 2)), np.nan) for y, x in zip(carpet["y_T_m"], carpet["x_T_m"])]
    return carpet.dropna(subset=["measured_db"]).reset_index(drop=True)


def _figure(carpet: pd.DataFrame, rig: str) -> None:
    if os.environ.get("NPS_FIGURES_DIR"):
        _write_carpet_comparison(carpet, Path(os.environ["NPS_FIGURES_DIR"]) / f"{rig}_bvispl_vs_measured.png", rig)


@pytest.mark.slow
def test_bundled_rigs_run_from_the_snakefile(rig_results):
    """Every bundled rig through the Snakefile: metrics finite, the HART-II carpets drawn; the rigid-blade
    HART-II BL BVISPL against the measured BL carpet (tests/data/hart_ii/bl-contour-meas.tec, 221 microphones;
    nothing in NPS is set from it): maximum at the measured maximum's microphone (x_T 0.5 m, y_T 1.81 m,
    under the advancing side) within 2 dB of the measured 113.5 dB, mean difference within ±2 dB, RMS
    difference < 4.5 dB, correlation over the carpet > 0.8. Measured at the time of writing with the Betz
    vortex structure: 113.0 dB, mean +0.3 dB, RMS 3.4 dB, correlation 0.88 (point vortex: 119.3 dB,
    +5.6 dB, 7.2 dB, 0.76; docs/validation/hart_ii_carpets.md)."""
    base = rig_results
    for rig in MEASURED_CARPET:
        assert (base / rig / "carpet.png").stat().st_size > 20_000
    for rig in (*MEASURED_CARPET, "itr_hover"):
        assert np.isfinite(_metrics(base, rig).select_dtypes("number").to_numpy()).all()
    carpet = _carpet(base, "hart_ii_bl")
    loudest = carpet.loc[carpet["bvispl_db"].idxmax()]
    assert (round(loudest["x_T_m"], 2), round(loudest["y_T_m"], 2)) == (0.5, 1.81)
    assert abs(loudest["bvispl_db"] - carpet["measured_db"].max()) < 2.0
    difference = carpet["bvispl_db"] - carpet["measured_db"]
    assert abs(difference.mean()) < 2.0 and np.sqrt(np.mean(difference**2)) < 4.5, difference.describe()
    assert np.corrcoef(carpet["bvispl_db"], carpet["measured_db"])[0, 1] > 0.8
    _figure(carpet, "hart_ii_bl")


@pytest.mark.slow
@pytest.mark.parametrize("rig, correlation", [("hart_ii_bl_measured", 0.85), ("hart_ii_mn_measured", 0.7),
                                              ("hart_ii_mv_measured", 0.85)])
def test_hart_ii_carpets_with_the_measured_blade_motion(rig_results, rig, correlation):
    """BL, MN and MV with the measured blade motion (HHC input, elastic torsion and flap of each condition;
    config/rigs/hart_ii_*_measured.yaml) against their measured carpets (221 / 221 / 208 microphones):
    mean difference within ±2 dB, RMS difference < 4.5 dB, correlation above ``correlation``. Measured at
    the time of writing (docs/validation/hart_ii_carpets.md): BL −0.7 / 3.3 dB / 0.89, MN +1.2 / 3.1 dB / 0.77,
    MV −0.1 / 3.0 dB / 0.91."""
    carpet = _carpet(rig_results, rig)
    difference = carpet["bvispl_db"] - carpet["measured_db"]
    assert abs(difference.mean()) < 2.0 and np.sqrt(np.mean(difference**2)) < 4.5, difference.describe()
    assert np.corrcoef(carpet["bvispl_db"], carpet["measured_db"])[0, 1] > correlation
    _figure(carpet, rig)


def _change_from_bl(base: Path, rig: str) -> pd.DataFrame:
    """(NPS, measured) change of the carpet maximum and mean from BL (measured blade motion) to ``rig``,
    on the microphones both measured carpets have (dB)."""
    bl, other = _carpet(base, "hart_ii_bl_measured"), _carpet(base, rig)
    common = bl.merge(other, on=["x_T_m", "y_T_m"], suffixes=("_bl", ""))
    change = (common[["bvispl_db", "measured_db"]].agg(["max", "mean"]).to_numpy()
              - common[["bvispl_db_bl", "measured_db_bl"]].agg(["max", "mean"]).to_numpy())
    return pd.DataFrame(change.T, index=["nps", "measured"], columns=["max", "mean"])


@pytest.mark.slow
def test_hhc_noise_changes_have_the_measured_direction(rig_results):
    """From BL to MV the carpet maximum rises (measured +3.5 dB) and from BL to MN and MV the carpet mean
    rises (measured +1.8 / +1.5 dB): NPS must give each change with the measured sign and at least half its
    size. Measured at the time of writing: MV maximum +3.4 dB, means MN +3.6 / MV +2.0 dB. With rigid blades
    (HHC pitch input only) NPS gets all three signs wrong (−1.3, −0.2, −1.1 dB): the elastic torsion the HHC
    excites (MV 3/rev 1.5° against the 0.8° input) decides (docs/validation/hart_ii_carpets.md)."""
    mn, mv = (_change_from_bl(rig_results, f"hart_ii_{c}_measured") for c in ("mn", "mv"))
    for change in (mv["max"], mn["mean"], mv["mean"]):
        assert change["measured"] > 0.0 and change["nps"] > 0.5 * change["measured"], (mn, mv)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="MN's quieter maximum is not predicted: NPS +1.8 dB against the measured -1.1 dB "
                          "(docs/validation/hart_ii_carpets.md)")
def test_mn_maximum_is_quieter_than_bl(rig_results):
    """The measured MN maximum is 1.1 dB below BL's (and moves upstream, x_T −1.5 m, y_T 0.46 m)."""
    mn = _change_from_bl(rig_results, "hart_ii_mn_measured")
    assert mn.loc["measured", "max"] < 0.0 and mn.loc["nps", "max"] < 0.0, mn


def _write_carpet_comparison(carpet: pd.DataFrame, path: Path, rig: str) -> None:
    """Measured and NPS BVISPL carpets on one colour scale, and their difference (docs/validation/hart_ii_carpets.md)."""
    import matplotlib.pyplot as plt

    x = np.sort(carpet["x_T_m"].unique())
    y = np.sort(carpet["y_T_m"].unique())
    grid = carpet.set_index(["x_T_m", "y_T_m"])
    fields = {name: grid[column].unstack().reindex(index=x, columns=y).to_numpy()
              for name, column in (("measured", "measured_db"), ("NPS", "bvispl_db"))}
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.8), constrained_layout=True)
    levels = np.arange(86.0, 120.5, 1.5)
    for ax, (name, field) in zip(axes, fields.items()):
        c = ax.contourf(y, x, field, levels=levels, extend="both")
        ax.set_title(f"{name}: max {np.nanmax(field):.1f} dB")
    fig.colorbar(c, ax=axes[:2], label="BVISPL, BPF harmonics 6–40 (dB)")
    d = axes[2].contourf(y, x, fields["NPS"] - fields["measured"], levels=np.arange(-9.0, 9.5, 1.5), cmap="RdBu_r",
                         extend="both")
    fig.colorbar(d, ax=axes[2], label="NPS − measured (dB)")
    axes[2].set_title("difference")
    for ax in axes:
        ax.set_xlabel("y_T (m), advancing side →")
        ax.set_aspect("equal")
    axes[0].set_ylabel("x_T (m), downstream ↑")
    fig.suptitle(f"{rig}, microphone plane 2.215 m below the hub (measured: DNW via OpenCOPTER)")
    fig.savefig(path, dpi=90)
    plt.close(fig)
