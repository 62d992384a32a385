"""Tone tables and narrowband spectra (nps.noise.tones, stage nps.stages.tones, ``python -m nps tones``).

Synthetic signals with known amplitudes and phases on the aircraft's common grid (one revolution of the
reference rotor): the reference rotor (exact DFT lines), a rotor turning exactly 3× faster (lines), and a
tail rotor turning 116/28 times faster (its harmonics between the lines: least-squares Fourier fit).
"""

import numpy as np
import pandas as pd
import pytest

from nps.__main__ import main as nps_main
from nps.app.io import read_metadata, read_table, write_table
from nps.noise.signals import signals_table
from nps.noise.acoustics import TimeGrid
from nps.stages.tones import run
from nps.noise.tones import harmonic_amplitudes, loudest_observers, narrowband_table, tone_table
from tests.trim_tables import complete_trim

OMEGA = {"main": 28.0, "aux": 84.0, "tail": 116.0}
BLADES = {"main": 4, "aux": 3, "tail": 4}
N = 512
GRID = TimeGrid(0.0, 2 * np.pi / OMEGA["main"], N)
IDS = np.array([3, 7, 11], dtype=np.int32)
# (rotor, harmonic) -> amplitude (Pa, peak) and phase (rad) per observer
TONES = {
    ("main", 1): ([2.0, 1.0, 0.5], [0.3, -2.9, 1.2]), ("main", 2): ([0.4, 0.2, 0.1], [-1.0, 2.0, 3.1]),
    ("main", 3): ([0.25, 0.3, 0.05], [0.7, 0.1, -0.4]),
    ("aux", 1): ([0.8, 0.1, 0.3], [1.5, -0.5, 2.5]), ("aux", 2): ([0.05, 0.02, 0.01], [0.0, 1.0, -3.0]),
    ("tail", 1): ([0.6, 0.9, 0.2], [-0.2, 2.2, 1.0]), ("tail", 2): ([0.1, 0.3, 0.02], [2.8, -1.7, 0.4]),
}


def bpf(rotor):
    return BLADES[rotor] * OMEGA[rotor] / (2 * np.pi)


def rotor_pressure(rotor, t):
    """(n_obs, n_t): the rotor's tones plus a constant (not sound); thickness part = 40 % of it."""
    p = np.full((IDS.size, t.size), 0.3)
    for (name, m), (amp, phase) in TONES.items():
        if name == rotor:
            p += np.array(amp)[:, None] * np.cos(2 * np.pi * m * bpf(rotor) * t[None, :] + np.array(phase)[:, None])
    return p


def signals(grid=GRID):
    out = {}
    for rotor in OMEGA:
        p = rotor_pressure(rotor, grid.times_s)
        out[rotor] = signals_table(IDS, ("loading", "thickness"), np.stack([0.6 * p, 0.4 * p], axis=1), grid, total=True)
    return out


def trim():
    return complete_trim(pd.DataFrame({"rotor": list(OMEGA), "omega_rad_s": list(OMEGA.values()),
                                       "n_blades": np.int32(list(BLADES.values()))}))


def test_tones_of_each_rotor_recover_amplitude_and_phase():
    """Every rotor's harmonics 1-2 (3 for main): SPL within 1e-9 dB, phase within 1e-9 rad of the synthetic
    tones; a harmonic without a tone is at the level floor; the total's main-BPF harmonics hold main's tones
    only (aux's BPF is 9/4 of main's, tail's 16.57 times: neither lands on them, and the tail's tones, between
    the DFT lines, do not leak into them)."""
    table = tone_table(signals(), trim(), 4)
    assert list(table.columns) == ["observer", "source", "harmonic", "frequency_hz", "spl_db", "phase_rad"]
    for (rotor, m), (amp, phase) in TONES.items():
        rows = table[(table.source == rotor) & (table.harmonic == m)].sort_values("observer")
        assert list(rows.observer) == list(IDS)
        np.testing.assert_allclose(rows.frequency_hz, m * bpf(rotor), rtol=1e-14)
        np.testing.assert_allclose(rows.spl_db, 20 * np.log10(np.array(amp) / np.sqrt(2) / 20e-6), atol=1e-9)
        np.testing.assert_allclose(np.angle(np.exp(1j * (rows.phase_rad - np.array(phase)))), 0.0, atol=1e-9)
    assert table[(table.source.isin(["main", "tail"])) & (table.harmonic == 4)].spl_db.max() < -50.0  # no tone there
    total = table[table.source == "total"].set_index(["observer", "harmonic"])
    np.testing.assert_allclose(total.frequency_hz.unique(), bpf("main") * np.arange(1, 5), rtol=1e-14)
    main = table[table.source == "main"].set_index(["observer", "harmonic"])
    np.testing.assert_allclose(total.spl_db, main.spl_db, atol=1e-9)  # aux (9/4, 18/4) and tail (16.57) land elsewhere
    np.testing.assert_allclose(total.phase_rad, main.phase_rad, atol=1e-9)


def test_commensurate_harmonic_adds_in_the_total():
    """A rotor at 2× the main rotor's speed with the same blade count: its BPF 1 is main BPF 2; the total's
    complex amplitude there is the sum of the two rotors' (phase and level)."""
    grid = TimeGrid(0.0, 2 * np.pi / 28.0, 256)
    t = grid.times_s
    p_main = np.cos(2 * np.pi * 2 * bpf("main") * t + 0.4)[None, :]
    p_fast = 0.5 * np.cos(2 * np.pi * 2 * bpf("main") * t - 1.1)[None, :]
    sig = {name: signals_table(np.int32([0]), ("loading",), p[:, None, :], grid, total=False)
           for name, p in (("main", p_main), ("fast", p_fast))}
    trim2 = complete_trim(pd.DataFrame({"rotor": ["main", "fast"], "omega_rad_s": [28.0, 56.0], "n_blades": np.int32([4, 4])}))
    table = tone_table(sig, trim2, 2)
    fast = table[(table.source == "fast") & (table.harmonic == 1)].iloc[0]
    assert fast.frequency_hz == pytest.approx(2 * bpf("main")) and fast.phase_rad == pytest.approx(-1.1, abs=1e-12)
    total = table[(table.source == "total") & (table.harmonic == 2)].iloc[0]
    expected = np.exp(0.4j) + 0.5 * np.exp(-1.1j)
    assert total.spl_db == pytest.approx(20 * np.log10(abs(expected) / np.sqrt(2) / 20e-6), abs=1e-10)
    assert total.phase_rad == pytest.approx(np.angle(expected), abs=1e-12)


def test_phase_is_relative_to_t0_whatever_the_first_sample():
    """A tone sampled from t0 = 0.37/f1 over 4 periods of f1, at f1 (DFT lines) and at 4.143 f1 (between the
    lines: least squares): the same complex amplitude C_2 = 1.3 e^{-2.5i}, the mean not in C_1."""
    f1 = bpf("main")
    t0, dt = 0.37 / f1, 1 / (64 * f1)
    t = t0 + dt * np.arange(256)
    for f in (f1, 116 / 28 * f1):
        c = harmonic_amplitudes(1.3 * np.cos(2 * np.pi * 2 * f * t - 2.5) + 0.1, t0, dt, f, 2)
        assert abs(c[1] - 1.3 * np.exp(-2.5j)) < 1e-10 and abs(c[0]) < 1e-10


def test_harmonic_amplitudes_refuses_bad_records():
    t = np.arange(64) / 64.0
    with pytest.raises(ValueError, match="periods"):
        harmonic_amplitudes(np.cos(t), 0.0, 1 / 64.0, 0.5, 1)
    with pytest.raises(ValueError, match="Nyquist"):
        harmonic_amplitudes(np.cos(t), 0.0, 1 / 64.0, 4.0, 8)
    with pytest.raises(ValueError, match="finite"):
        harmonic_amplitudes(np.full(64, np.nan), 0.0, 1 / 64.0, 1.0, 1)


def test_tone_table_cuts_harmonics_at_the_nyquist_frequency():
    """N = 512 over one main revolution: lines up to 255·Ω/2π; aux BPF = 9 lines → 28 harmonics, tail BPF =
    16.57 lines → 15."""
    table = tone_table(signals(), trim(), 40)
    counts = table[table.observer == 3].groupby("source").harmonic.max()
    assert counts.to_dict() == {"main": 40, "aux": 28, "tail": 15, "total": 40}


def test_narrowband_table_and_loudest_observers():
    """Lines k·Ω/2π, k = 1…N/2; per observer and source Σ msp = mean square about the mean (Parseval);
    thickness + loading = total; the loudest observer is the one with the largest mean-square total."""
    sig = signals()
    table = narrowband_table(sig, list(OMEGA), [11, 3])
    assert list(table.columns) == ["observer", "source", "frequency_hz", "msp_Pa2", "spl_db"]
    assert sorted(table.observer.unique()) == [3, 11] and set(table.source) == {"loading", "thickness", "total"}
    total = sum(rotor_pressure(r, GRID.times_s) for r in OMEGA)
    for k, obs in enumerate(IDS):
        if obs not in (3, 11):
            continue
        rows = table[(table.observer == obs) & (table.source == "total")]
        assert len(rows) == N // 2
        np.testing.assert_allclose(rows.frequency_hz.iloc[[0, -1]], [28 / (2 * np.pi), N // 2 * 28 / (2 * np.pi)])
        assert rows.msp_Pa2.sum() == pytest.approx(np.var(total[k]), rel=1e-12)
        parts = table[(table.observer == obs) & (table.source != "total")].groupby("source").msp_Pa2.sum()
        assert parts["thickness"] == pytest.approx(0.16 * rows.msp_Pa2.sum(), rel=1e-12)
    loud = int(IDS[np.argmax(np.var(total, axis=1))])
    assert list(loudest_observers(sig, list(OMEGA), 1)) == [loud]
    assert list(loudest_observers(sig, list(OMEGA), 10)) == list(IDS)
    with pytest.raises(ValueError, match=r"observers \[5\]"):
        narrowband_table(sig, list(OMEGA), [5])


def _write_inputs(tmp_path):
    for rotor, table in signals().items():
        write_table(table, tmp_path / "sig" / f"{rotor}.parquet", stage="test", metadata={"obsset": "mics", "variant": "base"})
    write_table(trim(), tmp_path / "trim.parquet", stage="test", metadata={"segment": "seg1"})


def test_stage_writes_tones_csv_and_spectra(tmp_path):
    """Tone Parquet for every observer; CSV and spectra for the loudest one plus the listed id."""
    _write_inputs(tmp_path)
    outputs = {"tones": tmp_path / "t.parquet", "tones_csv": tmp_path / "t.csv", "spectra": tmp_path / "s.parquet"}
    params = {"rotors": list(OMEGA), "harmonics": 3, "loudest": 1, "observers": [11], "aircraft": "x", "segment": "seg1",
              "obsset": "mics", "variant": "base"}
    report = run({"signals": tmp_path / "sig", "trim": tmp_path / "trim.parquet"}, outputs, params)
    tones = read_table(outputs["tones"])
    assert set(tones.observer) == set(IDS) and len(tones) == IDS.size * 4 * 3
    csv = pd.read_csv(outputs["tones_csv"])
    loud = int(loudest_observers(signals(), list(OMEGA), 1)[0])
    assert set(csv.observer) == {loud, 11} and list(csv.columns) == list(tones.columns)
    assert set(read_table(outputs["spectra"]).observer) == {loud, 11}
    assert read_metadata(outputs["tones"])["selected_observers"] == sorted({loud, 11})
    assert "BPF1" in report


def test_cli_round_trip_and_errors(tmp_path, capsys, repo_root):
    """``python -m nps tones`` with the rotors of a synthetic aircraft; a rotor without signals exits 2."""
    _write_inputs(tmp_path)
    args = ["tones", "--aircraft", str(repo_root / "config/aircraft/helicopter.yaml"), "--trim", str(tmp_path / "trim.parquet"),
            "--signals", str(tmp_path / "sig"), "--out", str(tmp_path / "t.parquet"), "--csv", str(tmp_path / "t.csv"),
            "--spectra-out", str(tmp_path / "s.parquet"), "--harmonics", "2"]
    assert nps_main(args + ["--rotor", "main", "tail"]) == 0
    tones = read_table(tmp_path / "t.parquet")
    assert set(tones.source) == {"main", "tail", "total"} and tones.harmonic.max() == 2
    assert read_metadata(tmp_path / "t.parquet")["obsset"] == "mics"
    assert nps_main(args + ["--rotor", "main", "nose"]) == 2
    assert "nose" in capsys.readouterr().err


def test_campaign_output_options_and_their_errors(repo_root):
    """``outputs`` is optional (schema defaults); tone observer sets must name configured sets."""
    from nps.app.config import ConfigError, load_campaign, read_yaml

    config = read_yaml(repo_root / "config/config.yaml")
    bare = load_campaign({k: v for k, v in config.items() if k != "outputs"}, root=repo_root)
    assert (bare.config["outputs"]["tone_harmonics"], bare.config["outputs"]["spectra_loudest"]) == (10, 3)
    assert bare.tone_observer_sets("seg5") == ["hemisphere", "hsi"]
    only = load_campaign(dict(config, outputs={"tone_observer_sets": ["hsi"]}), root=repo_root)
    assert only.tone_observer_sets("seg5") == ["hsi"] and only.tone_observer_sets("seg1") == []
    with pytest.raises(ConfigError, match=r"outputs.tone_observer_sets\[0\]"):
        load_campaign(dict(config, outputs={"tone_observer_sets": ["mics"]}), root=repo_root)


def test_loudest_observers_rank_levels_within_the_tie_tolerance_as_equal():
    """Mirror observers whose levels differ by rounding only (1e-13 relative in mean square) tie: the lower id
    is taken whichever carries the last bit; a real difference (0.01 dB) still ranks."""
    sig = signals()
    for scale in (1.0 + 1e-13, 1.0 - 1e-13):
        mirrored = {}
        for rotor, table in sig.items():
            twin = table[table.observer == 3].copy()
            twin["observer"] = np.int32(2)
            twin["p_Pa"] = twin["p_Pa"] * np.sqrt(scale)
            mirrored[rotor] = pd.concat([table, twin], ignore_index=True)
        assert list(loudest_observers(mirrored, list(OMEGA), 1)) == [2]
    for rotor, table in mirrored.items():
        table.loc[table.observer == 2, "p_Pa"] *= 10 ** (-0.01 / 20)
    assert list(loudest_observers(mirrored, list(OMEGA), 1)) == [3]
