"""Blade phasing and the tone sum of several rotors (rotors[].phase_deg, tone_sum; docs/reference/acoustics.md
"Blade phasing", docs/reference/tones.md "Several rotors").

Two identical two-bladed rotors at one hub in hover, loads from the blade-element solver, radiated by the
acoustics stage, tones from the tones stage, levels from the metrics kernel. Analytic results: in phase the
total is twice the pressure (+20 log10 2 = +6.02 dB), an incoherent sum twice the mean-square pressure
(+10 log10 2 = +3.01 dB); a blade phase of half a blade passage (90° for B = 2) shifts harmonic m by
m·B·φ = m·π, so the odd harmonics cancel and the even ones add in phase.
"""

import math

import numpy as np
import pandas as pd
import pytest

from nps.app.config import ConfigError, load_aircraft
from nps.app.io import read_metadata, read_table, rotor_path, write_table
from nps.noise.acoustics import Observers, radiate_arrays
from nps.noise.metrics import metrics_tables
from nps.noise.observers import points
from nps.noise.signals import signal_arrays
from nps.noise.spectra import LEVEL_FLOOR_DB, P_REF_PA
from nps.noise.sources import ThicknessModel, common_grid, rotor_sources
from nps.rotor import bet
from nps.rotor.geometry import OperatingPoint, RotorGeometry, RotorMotion
from nps.rotor.trim import trim_row
from nps.stages import acoustics, tones
from tests.trim_tables import complete_trim

OMEGA, RADIUS, SAMPLES = 40.0, 2.0, 128
SIX_DB, THREE_DB = 20.0 * math.log10(2.0), 10.0 * math.log10(2.0)


@pytest.fixture(scope="module")
def disk() -> pd.DataFrame:
    """Hover loads of a two-bladed rotor (blade-element solver, 36 × 8, θ0 8°)."""
    geometry = RotorGeometry(name="a", n_blades=2, radius_m=RADIUS, chord_m=0.15, root_cutout_m=0.3, twist_rad=-0.15,
                             thickness_ratio=0.12, lock_number=6.0)
    op = OperatingPoint(omega_rad_s=OMEGA, mu_x=0.0, mu_y=0.0, mu_z=0.0, density_kg_m3=1.225, speed_of_sound_mps=340.294,
                        thrust_N=1.0)
    return bet.rotor_loads(geometry, op, bet.DiskGrid(36, 8), bet.Controls(math.radians(8.0))).disk


def _trim() -> pd.DataFrame:
    rows = [{"rotor": name, "n_blades": np.int32(2), "omega_rad_s": OMEGA, "radius_m": RADIUS, "hub_z_m": 1.0,
             "thrust_N": 800.0, "ct": 0.005} for name in ("a", "b")]
    return complete_trim(pd.DataFrame(rows))


def _observers() -> pd.DataFrame:
    return points([[20.0, 5.0, -3.0], [-6.0, -15.0, -8.0], [8.0, 3.0, -12.0], [0.0, 25.0, 1.0]])


def _signals(tmp_path, disk, phases_deg=None, name="out", trim=None):
    """Run the acoustics stage for rotors a, b (same disk, same hub; trim rows ``trim``, default :func:`_trim`);
    return the signals directory."""
    for rotor in ("a", "b"):
        write_table(disk, rotor_path(tmp_path / "disks", rotor), stage="loads", metadata={"aircraft": "x", "segment": "s", "rotor": rotor})
    write_table(_trim() if trim is None else trim, tmp_path / "trim.parquet", stage="trim", metadata={"aircraft": "x", "segment": "s"})
    write_table(_observers(), tmp_path / "obs.parquet", stage="observers", metadata={"aircraft": "x", "segment": "s", "obsset": "o"})
    params = {"rotors": ["a", "b"], "hinge_offsets_m": {"a": 0.0, "b": 0.0}, "thickness": "dual_compact",
              "chord_fractions": [0.13, 0.87], "samples_per_rev": SAMPLES, "aircraft": "x", "segment": "s", "obsset": "o",
              "variant": "base"}
    if phases_deg is not None:
        params["phases_deg"] = phases_deg
    acoustics.run({"disks": tmp_path / "disks", "trim": tmp_path / "trim.parquet", "observers": tmp_path / "obs.parquet"},
                  {"signals": tmp_path / name}, params)
    return tmp_path / name


def _tones(tmp_path, signals_dir, tone_sum=None) -> pd.DataFrame:
    params = {"rotors": ["a", "b"], "harmonics": 6, "loudest": 2, "observers": [], "aircraft": "x", "segment": "s",
              "obsset": "o", "variant": "base"}
    if tone_sum is not None:
        params["tone_sum"] = tone_sum
    out = {"tones": tmp_path / f"tones_{tone_sum}.parquet", "tones_csv": tmp_path / f"tones_{tone_sum}.csv",
           "spectra": tmp_path / f"spectra_{tone_sum}.parquet"}
    tones.run({"signals": signals_dir, "trim": tmp_path / "trim.parquet"}, out, params)
    return read_table(out["tones"])


def _levels(table: pd.DataFrame, source: str) -> np.ndarray:
    """SPL (dB) per observer (rows) × harmonic (columns) of one source of a tone table."""
    return table[table["source"] == source].pivot(index="observer", columns="harmonic", values="spl_db").to_numpy()


def test_identical_rotors_in_phase_add_6_02_db_coherently_and_3_01_db_incoherently(tmp_path, disk):
    signals_dir = _signals(tmp_path, disk)
    coherent, incoherent = _tones(tmp_path, signals_dir), _tones(tmp_path, signals_dir, "incoherent")
    single = _levels(coherent, "a")
    assert single[:, 0].min() > 40.0  # a real tone at every observer
    np.testing.assert_allclose(_levels(coherent, "total")[:, :3] - single[:, :3], SIX_DB, atol=0.01)
    np.testing.assert_allclose(_levels(incoherent, "total")[:, :3] - single[:, :3], THREE_DB, atol=0.01)
    np.testing.assert_array_equal(_levels(incoherent, "a"), single)  # the rotors' own rows do not depend on the sum
    assert (incoherent[incoherent["source"] == "total"]["phase_rad"] == 0.0).all()
    spectra = read_table(tmp_path / "spectra_incoherent.parquet")
    assert read_metadata(tmp_path / "spectra_incoherent.parquet")["tone_sum"] == "incoherent"
    assert "tone_sum" not in read_metadata(tmp_path / "spectra_None.parquet")
    ratio = spectra["msp_Pa2"].to_numpy() / read_table(tmp_path / "spectra_None.parquet")["msp_Pa2"].to_numpy()
    np.testing.assert_allclose(ratio[np.isfinite(ratio) & (spectra["msp_Pa2"].to_numpy() > 1e-12)], 0.5, rtol=1e-9)


def test_half_a_blade_passage_cancels_the_odd_harmonics_of_two_coincident_two_bladed_rotors(tmp_path, disk):
    """Rotor b's blade 0 at 90° at t = 0: odd BPF harmonics of the total > 60 dB below one rotor's, even +6.02 dB."""
    signals_dir = _signals(tmp_path, disk, {"a": 0.0, "b": 90.0})
    table = _tones(tmp_path, signals_dir)
    single, total = _levels(table, "a"), _levels(table, "total")
    odd, even = np.arange(0, 6, 2), np.arange(1, 6, 2)  # columns of harmonics 1, 3, 5 and 2, 4, 6
    assert ((single[:, odd] - total[:, odd] > 60.0) | (total[:, odd] <= LEVEL_FLOOR_DB)).all()
    assert (single[:, 0] - total[:, 0]).min() > 140.0  # BPF1: from 45-49 dB to the -100 dB floor
    np.testing.assert_allclose(total[:, even[:2]] - single[:, even[:2]], SIX_DB, atol=0.01)
    assert read_metadata(rotor_path(signals_dir, "b"))["phase_deg"] == 90.0
    assert "phase_deg" not in read_metadata(rotor_path(signals_dir, "a"))


def test_a_blade_phase_shifts_the_tone_phases_by_m_b_phi(tmp_path, disk):
    """ψ_0(t) = Ω t + φ: rotor b leads rotor a by φ/Ω, so C_m(b) = C_m(a) e^{i m B φ}; within 1e-3 of the
    observer's BPF1 amplitude (the source times no longer fall on the reception grid's: interpolation)."""
    phase = 25.0
    table = _tones(tmp_path, _signals(tmp_path, disk, {"a": 0.0, "b": phase}))

    def amplitudes(source):
        rows = table[table["source"] == source]
        c = np.sqrt(2.0) * P_REF_PA * 10.0 ** (rows["spl_db"] / 20.0) * np.exp(1j * rows["phase_rad"])
        return c.to_numpy().reshape(-1, 6)

    a, b = amplitudes("a"), amplitudes("b")
    expected = a * np.exp(1j * np.arange(1, 7) * 2 * math.radians(phase))
    assert (np.abs(b - expected) <= 1e-3 * np.abs(a[:, :1])).all()
    assert np.abs(b[:, 0] - expected[:, 0]).max() < 2e-5 * np.abs(a[:, 0]).min()  # BPF1: 1.5e-5


def test_phase_zero_is_bit_identical_to_no_phase(tmp_path, disk):
    zero = _signals(tmp_path, disk, {"a": 0.0, "b": 0.0}, "zero")
    none = _signals(tmp_path, disk, None, "none")
    for rotor in ("a", "b"):
        assert read_table(rotor_path(zero, rotor)).equals(read_table(rotor_path(none, rotor)))


def test_phase_in_the_all_blade_path_matches_the_periodic_path(disk):
    """Sources over a source-time span (every blade, the stationary-observer path) with a blade phase agree with
    the periodic one-blade path at the same phase (1e-3 of peak-to-peak)."""
    trim = _trim()
    motion = RotorMotion.from_trim_row(trim_row(trim, "b"))
    obs_table = _observers()
    obs = Observers(obs_table[["x_m", "y_m", "z_m"]].to_numpy(float), np.zeros((len(obs_table), 3)))
    grid = common_grid(trim_row(trim, "a"), SAMPLES)
    kwargs = dict(thickness=ThicknessModel(), rho0_kg_m3=1.225, c0_mps=340.294, phase_rad=math.radians(70.0))
    periodic = radiate_arrays(rotor_sources(disk, motion, **kwargs), obs, grid, c0_mps=340.294, rho0_kg_m3=1.225)
    span = rotor_sources(disk, motion, tau_range_s=(-0.3, grid.n_samples * grid.dt_s + 0.1), **kwargs)
    direct = radiate_arrays(span, obs, grid, c0_mps=340.294, rho0_kg_m3=1.225)
    scale = np.ptp(periodic, axis=-1, keepdims=True)
    assert np.abs(direct - periodic).max() < 1e-3 * scale.max()
    assert np.abs(direct - periodic).max() < 1e-3 * scale.min() * 10


def test_incoherent_metrics_add_mean_square_pressures(tmp_path, disk):
    """OASPL of two identical coincident rotors: +6.02 dB coherent, +3.01 dB incoherent (tonal only)."""
    signals_dir = _signals(tmp_path, disk)
    signals = {rotor: read_table(rotor_path(signals_dir, rotor)) for rotor in ("a", "b")}
    observers = _observers().assign(elevation_deg=0.0, azimuth_deg=0.0)
    trim = _trim()
    solidity = {"a": 0.05, "b": 0.05}
    coherent, _, _ = metrics_tables(signals, observers, trim, solidity, None, broadband_on=False)
    incoherent, _, _ = metrics_tables(signals, observers, trim, solidity, None, broadband_on=False, tone_sum="incoherent")
    one, _, _ = metrics_tables({"a": signals["a"]}, observers, trim.iloc[:1], solidity, None, broadband_on=False)
    np.testing.assert_allclose(coherent["oaspl_db"] - one["oaspl_db"], SIX_DB, atol=1e-9)
    np.testing.assert_allclose(incoherent["oaspl_db"] - one["oaspl_db"], THREE_DB, atol=1e-9)
    np.testing.assert_allclose(incoherent["oaspl_loading_db"] - one["oaspl_loading_db"], THREE_DB, atol=1e-9)
    with pytest.raises(ValueError, match="tone_sum"):
        metrics_tables(signals, observers, trim, solidity, None, broadband_on=False, tone_sum="random")
    ids, _, groups = signal_arrays(signals["a"])
    assert ids.size == len(observers) and set(groups) == {"loading", "thickness"}


def test_schema_defaults_and_a_bad_tone_sum(tmp_path, repo_root):
    aircraft = load_aircraft(repo_root / "config/aircraft/helicopter.yaml")
    assert aircraft["tone_sum"] == "coherent" and {r["phase_deg"] for r in aircraft["rotors"]} == {0.0}
    text = (repo_root / "config/aircraft/helicopter.yaml").read_text().replace("name: helicopter", "name: bad\ntone_sum: random")
    (tmp_path / "bad.yaml").write_text(text)
    with pytest.raises(ConfigError, match=r"bad.yaml: tone_sum: expected one of \['coherent', 'incoherent'\]"):
        load_aircraft(tmp_path / "bad.yaml")


def test_a_rotor_turning_half_a_percent_faster_adds_3_01_db_incoherently(tmp_path, disk):
    """A speed offset (rotor b at 1.005 Ω: its own omega_rad_s, or the segment's rotor_omega_scale) on the reference
    rotor's one-revolution grid: the incoherent OASPL is the energy sum of the two rotors' OASPL (exact: Parseval
    per rotor record), +3.01 dB over rotor a within 0.1 dB (b is 0.05-0.06 dB louder at its higher speed); b's own
    BPF1 level (least-squares tones) is above a's by less than the Ω³ scaling."""
    trim = _trim()
    trim.loc[trim["rotor"] == "b", "omega_rad_s"] = 1.005 * OMEGA
    offset = _signals(tmp_path, disk, name="offset", trim=trim)
    signals = {rotor: read_table(rotor_path(offset, rotor)) for rotor in ("a", "b")}
    observers = _observers().assign(elevation_deg=0.0, azimuth_deg=0.0)
    both, _, _ = metrics_tables(signals, observers, trim, {"a": 0.05, "b": 0.05}, None, broadband_on=False,
                                tone_sum="incoherent")
    one, _, _ = metrics_tables({"a": signals["a"]}, observers, trim.iloc[:1], {"a": 0.05}, None, broadband_on=False)
    alone, _, _ = metrics_tables({"b": signals["b"]}, observers, trim.iloc[1:], {"b": 0.05}, None, broadband_on=False)
    energy = 10.0 * np.log10(10.0 ** (one["oaspl_db"] / 10.0) + 10.0 ** (alone["oaspl_db"] / 10.0))
    np.testing.assert_allclose(both["oaspl_db"], energy, atol=1e-9)
    np.testing.assert_allclose(both["oaspl_db"] - one["oaspl_db"], THREE_DB, atol=0.1)  # b is louder by its speed
    table = _tones(tmp_path, offset, "incoherent")
    louder = _levels(table, "b")[:, 0] - _levels(table, "a")[:, 0]  # 0.10-0.12 dB: ≈ Ω^2.5 at the same loads
    assert (louder > 0.0).all() and (louder < 20.0 * np.log10(1.005**3)).all()
