"""Unit tests of nps.noise.metrics: levels of synthetic signals, PNL/PNLT properties, artifact tables."""

import numpy as np
import pandas as pd
import pytest

from nps.noise import metrics

from nps.noise import spectra
from nps.core.atmosphere import isa

P_REF2 = 4e-10


def _level(msp):
    return 10 * np.log10(msp / P_REF2)


def test_a_weighting_shape_and_errors():
    """A-weighting peaks near 2.5 kHz at +1.27 dB and is −19.1 dB at 100 Hz (IEC table, 0.1 dB)."""
    f = np.linspace(1000, 5000, 4001)
    a = metrics.a_weighting_db(f)
    assert 2300 < f[np.argmax(a)] < 2700 and a.max() == pytest.approx(1.27, abs=0.01)
    assert metrics.a_weighting_db(100.0) == pytest.approx(-19.1, abs=0.1)
    with pytest.raises(ValueError, match="positive"):
        metrics.a_weighting_db([0.0, 10.0])


def test_pnl_flat_spectrum_has_no_tone_correction():
    """A smooth spectrum gets C_max = 0 and PNLT = PNL; PNL rises with level."""
    flat = np.full(24, 70.0)
    assert metrics.tone_correction(flat).c_max_db == 0.0
    assert metrics.pnlt(flat) == pytest.approx(metrics.pnl(flat))
    assert metrics.pnl(flat + 10) > metrics.pnl(flat) + 9
    with pytest.raises(ValueError, match="24"):
        metrics.pnl(np.zeros(23))


def test_time_history_truncation_and_band_check():
    """A record sequence whose maximum is the last record is flagged truncated; missing PNL bands
    are named."""
    lv = np.full((3, 24), 30.0)
    lv[:, 13] = [50.0, 65.0, 80.0]
    out = metrics.time_history_metrics(lv, np.arange(-13, 11))
    assert out.truncated and out.epnl_duration_s == 0.5
    with pytest.raises(ValueError, match="missing"):
        metrics.time_history_metrics(lv[:, :20], np.arange(-13, 7))


def _signals(n_obs=2, n=512, bpf=20.0):
    """Thickness: 2 Pa tone at BPF harmonic 10 (200 Hz, inside BVISPL 7..40); loading: 5 Pa at
    harmonic 2 (40 Hz, outside). One period of the BPF/… fundamental: 1 revolution = 1/5 s
    (4 blades), dt = 0.2/n."""
    period = 4 / bpf
    dt = period / n
    t = np.arange(n) * dt
    thick = np.tile(2.0 * np.cos(2 * np.pi * 10 * bpf * t), (n_obs, 1))
    load = np.tile(5.0 * np.sin(2 * np.pi * 2 * bpf * t), (n_obs, 1))
    return {"thickness": thick, "loading": load}, dt


def test_observer_set_levels_synthetic():
    """Tones of MSP 2 and 12.5 Pa² at 200 and 40 Hz: OASPL per source 97.0/114.95 dB, total =
    energy sum (the tones are at different frequencies), BVISPL = the 200 Hz tone only,
    OASPL_A = Σ MSP·10^(A/10); broadband bands add by energy to bands and OASPL."""
    sig, dt = _signals()
    out = metrics.observer_set_metrics(sig, dt, bpf_hz=20.0)
    assert out.oaspl_db["thickness"] == pytest.approx(_level(2.0))
    assert out.oaspl_db["loading"] == pytest.approx(_level(12.5))
    assert out.oaspl_db["total"] == pytest.approx(_level(14.5))
    assert out.bvispl_db == pytest.approx(_level(2.0))
    a = 2.0 * 10 ** (metrics.a_weighting_db(200.0) / 10) + 12.5 * 10 ** (metrics.a_weighting_db(40.0) / 10)
    assert out.oaspl_dba == pytest.approx(_level(a))
    j200 = np.flatnonzero(out.band_numbers == -7)[0]  # 200 Hz band
    assert out.bands_db["total"][0, j200] == pytest.approx(_level(2.0))
    bb = np.full((2, out.band_numbers.size), spectra.LEVEL_FLOOR_DB)
    bb[:, j200] = _level(2.0)
    out2 = metrics.observer_set_metrics(sig, dt, bpf_hz=20.0, broadband_db=bb)
    assert out2.bands_db["total"][0, j200] == pytest.approx(_level(4.0))
    assert out2.oaspl_db["broadband"] == pytest.approx(_level(2.0))
    assert out2.oaspl_db["total"] == pytest.approx(_level(16.5))
    assert out2.bvispl_db == pytest.approx(out.bvispl_db)  # BVISPL is tonal only


def test_hsi_replaces_tonal_total():
    """With an 'hsi' signal the tonal total is that signal (here: thickness+loading doubled → +6.02 dB)."""
    sig, dt = _signals()
    sig["hsi"] = 2.0 * (sig["thickness"] + sig["loading"])
    out = metrics.observer_set_metrics(sig, dt, bpf_hz=20.0)
    assert out.oaspl_db["total"] == pytest.approx(_level(14.5) + 20 * np.log10(2))
    assert out.oaspl_db["hsi"] == pytest.approx(out.oaspl_db["total"])


def _trim_row(name, hub_x, n_blades, omega):
    eye = np.eye(3)
    row = {"rotor": name, "n_blades": n_blades, "radius_m": 7.62 if name == "main" else 1.7,
           "omega_rad_s": omega, "thrust_N": 5.0e4 if name == "main" else 3.0e3, "ct": 0.005,
           "hub_x_m": hub_x, "hub_y_m": 0.0, "hub_z_m": 0.0, "speed_of_sound_mps": 340.29,
           "density_kg_m3": 1.225}
    row.update({f"r_gh_{i}{j}": eye[i, j] for i in range(3) for j in range(3)})
    return row


def _signal_table(p_by_group, time):
    rows = []
    for group, p in p_by_group.items():
        for obs in range(p.shape[0]):
            rows.append(pd.DataFrame({"observer": np.int32(obs), "group": group, "time_s": time, "p_Pa": p[obs]}))
    return pd.concat(rows, ignore_index=True)


def test_metrics_tables_from_artifacts():
    """Two rotors on one grid, two observers (76.2 m below, 76.2 m ahead in plane): one row per
    observer, no NaN; BVISPL from the first (main) rotor's BPF = 4·28/2π Hz; absorption lowers
    every level; broadband raises the total more below the rotor than in plane; bands table has
    observer × source × 34 bands."""
    n = 1024  # 512 rotor harmonics = 128 main BPF harmonics: no aliasing of harmonic 45
    period = 2 * np.pi / 28.0
    time = np.arange(n) * period / n
    bpf = 4 * 28.0 / (2 * np.pi)
    def tone(harmonic_of_main_bpf, amplitude):
        return np.tile(amplitude * np.cos(2 * np.pi * harmonic_of_main_bpf * bpf * time), (2, 1))

    # tail: 5x the main rotor speed, same blade count -> tail BPF = 5 main BPF; its harmonics 2
    # (10 main BPF, inside 7..40) and 9 (45 main BPF, outside)
    signals = {
        "main": _signal_table({"thickness": tone(10, 1.0), "loading": tone(1, 3.0)}, time),
        "tail": _signal_table({"thickness": tone(45, 0.2), "loading": tone(10, 0.5)}, time),
    }
    trim = pd.DataFrame([_trim_row("main", 0.0, 4, 28.0), _trim_row("tail", -9.9, 4, 28.0 * 5)])
    observers = pd.DataFrame({"observer": np.int32([1, 0]), "x_m": [76.2, 0.0], "y_m": [0.0, 0.0],
                              "z_m": [0.0, -76.2], "elevation_deg": [0.0, -90.0], "azimuth_deg": [180.0, 0.0]})
    solidity = {"main": 0.097, "tail": 0.1}
    m0, b0, _ = metrics.metrics_tables(signals, observers, trim, solidity, None, broadband_on=False)
    m1, _, _ = metrics.metrics_tables(signals, observers, trim, solidity, isa(0.0), broadband_on=False)
    m2, _, _ = metrics.metrics_tables(signals, observers, trim, solidity, None, broadband_on=True)
    assert list(m0["observer"]) == [0, 1]
    assert not m2.isna().any().any()
    # the two 10th-harmonic tones are in phase: amplitudes add (1.5 Pa)
    assert m0["bvispl_db"].to_numpy() == pytest.approx(_level(1.5**2 / 2))
    assert np.all(m1["oaspl_db"] < m0["oaspl_db"]) and np.all(m1["bvispl_db"] < m0["bvispl_db"])
    gain = m2["oaspl_db"] - m0["oaspl_db"]
    assert gain[0] > gain[1] > 0  # observer 0 is below the rotor
    assert set(b0["source"]) == {"thickness", "loading", "total"}
    assert len(b0) == 2 * 3 * 34
    with pytest.raises(ValueError, match="rotors"):
        metrics.metrics_tables({"main": signals["main"]}, observers, trim, solidity, None)


def test_cli_end_to_end(tmp_path, repo_root):
    """`python -m nps metrics` on synthetic artifacts writes both tables (and a figure) with the
    contract columns, and a missing rotor signal is a clear error (exit 2), not a traceback."""
    from nps.cli.metrics import main
    from nps.app.io import read_table, write_table

    n = 256
    period = 2 * np.pi / 28.0
    time = np.arange(n) * period / n
    p = np.tile(np.cos(2 * np.pi * 4 * time / period), (2, 1))
    from tests.trim_tables import complete_trim

    trim = complete_trim(pd.DataFrame([_trim_row("main", 0.0, 4, 28.0), _trim_row("tail", -9.9, 4, 28.0)]))
    write_table(trim, tmp_path / "trim.parquet", stage="trim")
    observers = pd.DataFrame({"observer": np.int32([0, 1]), "x_m": [0.0, 76.2], "y_m": 0.0, "z_m": [-76.2, 0.0],
                              "vx_mps": 0.0, "vy_mps": 0.0, "vz_mps": 0.0,
                              "elevation_deg": [-90.0, 0.0], "azimuth_deg": [0.0, 180.0]})
    write_table(observers, tmp_path / "obs.parquet", stage="observers")
    for rotor in ("main", "tail"):
        write_table(_signal_table({"thickness": p, "loading": 0.5 * p}, time), tmp_path / "sig" / f"{rotor}.parquet", stage="acoustics")
    args = ["--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"), "--trim", str(tmp_path / "trim.parquet"),
            "--observers", str(tmp_path / "obs.parquet"), "--out", str(tmp_path / "m.parquet"),
            "--bands-out", str(tmp_path / "b.parquet"), "--signals", str(tmp_path / "sig")]
    assert main(args + ["--figure", str(tmp_path / "s.png")]) == 0
    table = read_table(tmp_path / "m.parquet")
    for column in ("observer", "elevation_deg", "azimuth_deg", "oaspl_db", "oaspl_dba", "bvispl_db",
                   "oaspl_thickness_db", "oaspl_loading_db", "oaspl_broadband_db"):
        assert column in table.columns
    assert set(read_table(tmp_path / "b.parquet")["source"]) == {"thickness", "loading", "broadband", "total"}
    assert (tmp_path / "s.png").stat().st_size > 10_000
    assert main(args + ["--rotor", "main", "aux"]) == 2


def test_pnlt_of_many_spectra_equals_one_at_a_time():
    """PNLT over a (n, 24) array (vectorised tone correction) is bit-identical to spectrum by spectrum."""
    rng = np.random.default_rng(7)
    spl = np.cumsum(rng.normal(0.0, 4.0, size=(40, 24)), axis=1) + 60.0
    spl[::3, 12] += 15.0  # tones: circled bands and non-zero corrections
    rows = np.array([metrics.pnl(s) + metrics.tone_correction(s).c_max_db for s in spl])
    assert np.array_equal(metrics.pnlt(spl), rows)
    assert (rows > metrics.pnl(spl)).any()
