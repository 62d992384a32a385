"""PSU-WOPWOP's own output files: read, rewritten byte for byte, and their spectra and levels recomputed from
WOPWOP's own pressure.tec with :mod:`nps.wopwop.output`.

Reference: tests/data/wopwop/psu_wopwop_outputs/ (byuflowlab/FLOWNoise test/data/case{1,2,4,5}/, MIT licence,
copyright 2019 BYU FLOW Lab; README there): the outputs PSU-WOPWOP wrote for four of its example cases, one
observer each. Their inputs are not public, so the processing of each case was found on the data:

- case1 (fixed-point rows, 4192 samples, 0–0.418211 s): no window, no high-pass (0 Hz bin present, its raw MSP
  in the spectrum), bins up to nt/2; OASPL includes the 0 Hz bin (loading 71.676979 dB: 1e-5 dB off with it,
  0.0129 dB without). Its build floors dBA at 1e-20 Pa² instead of ε³ = 1e-15 Pa² (visible at 2.4–12 Hz, where
  A-weighting is below −70 dB: with 1e-15 up to 49 dB off). OASPL ≤ 3.3e-5 dB.
- case2 (E15.8 rows, 1024 samples): Hanning window (without it OASPL is 2.7–3.0 dB off), a high-pass between
  0 and df = 17.35 Hz (no 0 Hz bin), bins up to Nyquist. OASPL ≤ 7.5e-6 dB.
- case4 (fixed-point rows, 1024 samples): no window, high-pass between 0 and df = 12.88 Hz. OASPL ≤ 1.1e-5 dB.
- case5 (E15.8 rows, 256 samples): no window, no high-pass (OASPL with the 0 Hz bin, ≤ 1.6e-6 dB), no spectrum
  file; frequency-range files: spl_Low = bins 1–5 (5.71–28.56 Hz), spl_MidToHigh = bins 6–128 (34.27–731.09 Hz,
  the Nyquist bin), ≤ 5e-6 dB. The namelist limits are not in the output: any f_min in (0, 5.71] with f_max in
  [28.56, 34.27), and f_min in (28.56, 34.27] with f_max ≥ 731.09, select these bins.
- No case is segmented (one SPL time = t_min) and no written pressure is band-filtered (their means are not 0,
  though case2 and case4 ran with a high-pass: WOPWOP 3.4 filters then, these builds did not).

Spectra: every bin agrees within 0.01 dB where WOPWOP's input is known well enough, i.e. where the bound of the
rounding noise below is ≤ 0.01 dB (case1 8 % / 1 % / 8 % of the bins of thickness / loading / total, case2
98–99.6 %, case4 97–100 %; measured there ≤ 0.0043 dB). The other bins cannot be reproduced to 0.01 dB because
what WOPWOP transformed is not in the output: pressure.tec keeps 6 decimals (case1, case4: a rounding noise of
MSP 2σ²n/(n − 1)², σ² = (1e-6 Pa)²/12, −70 dB re 20 µPa per bin for case1, while its spectrum falls to −54 dB)
or 8 digits (case2), and WOPWOP applies the window in single precision (case2). There the difference stays
within 4σ of that noise (measured ≤ 3.1σ): case1 up to 0.09 dB (thickness, total) and 1.50 / 3.19 dB (loading
dB / dBA, bins at −44…−54 dB), case2 up to 0.020 dB (a −52 dB bin at 8.76 kHz), case4 up to 0.0095 dB (loading).
"""

from pathlib import Path

import numpy as np
import pytest

from nps.wopwop.output import (
    PRESSURE_COLUMNS,
    SOURCES,
    mean_square_spectrum,
    oaspl,
    pressure_groups,
    read_output,
    spl_spectrum,
    variable_titles,
    window_function,
    write_tec,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "wopwop" / "psu_wopwop_outputs"
FILES = sorted(p.relative_to(DATA).as_posix() for p in DATA.glob("case*/*.tec"))
LEVELS = [f"{s}_{u}" for u in ("dB", "dBA") for s in SOURCES]
# case: (spectral processing, pressure.tec rows in fixed point (6 decimals), dBA floor Pa² of that build)
CASES = {
    "case1": ({}, True, 1e-20),
    "case2": ({"high_pass_hz": 1.0, "window": "Hanning Window"}, False, 1e-15),
    "case4": ({"high_pass_hz": 1.0}, True, 1e-15),
    "case5": ({}, False, 1e-15),
}


def _pressure(case: str):
    """(observer time s, thickness / loading / total pressure Pa (3, nt)) of a case's pressure.tec."""
    table = read_output(DATA / case / "pressure.tec")
    groups = pressure_groups(table)
    return table.values[0, :, 0], np.stack([groups[s.lower()][0] for s in SOURCES])


def _rounding_noise_msp(p: np.ndarray, fixed_point: bool, window: str | None) -> np.ndarray:
    """Per-bin MSP (Pa²) of the noise between WOPWOP's input and ours: the rounding of the printed pressure
    (uniform, one quantum: 1e-6 Pa, or the 8th significant digit) and, with a window, WOPWOP's two
    single-precision roundings of the windowed samples."""
    n = p.shape[-1]
    if fixed_point:
        quantum = np.full(p.shape, 1e-6)
    else:
        quantum = 10.0 ** (np.floor(np.log10(np.maximum(np.abs(p), 1e-30))) + 1 - 8)
    variance = quantum**2 / 12
    if window is not None:
        w = window_function(window, n)
        ulp = np.spacing(np.abs((p * w).astype(np.float32))).astype(float)
        variance = variance * w**2 + 2 * ulp**2 / 12
    return 2 * n * variance.mean(axis=-1) / (n - 1) ** 2


@pytest.mark.parametrize("name", FILES)
def test_every_file_reads_and_is_rewritten_byte_for_byte(name, tmp_path):
    """Each file reads; write_tec with its row format and line end reproduces it exactly."""
    raw = (DATA / name).read_bytes()
    table = read_output(DATA / name)
    assert table.shape == (1, 1) and table.positions_m is None
    assert np.all(np.isfinite(table.values))
    first_row = raw.splitlines()[4]
    number_format = "e15.8" if b"E+" in first_row or b"E-" in first_row else "f15.6"
    write_tec(tmp_path / "out.tec", table, number_format, "\r\n" if b"\r\n" in raw else "\n")
    assert (tmp_path / "out.tec").read_bytes() == raw


@pytest.mark.parametrize("name", FILES)
def test_titles_are_the_ones_variable_titles_gives(name):
    """The column titles of every real file, character for character."""
    kind = {"pressure": "pressure", "OASPLdB": "OASPLdB", "OASPLdBA": "OASPLdBA", "spl_spectrum": "spl_spectrum"}
    stem = Path(name).stem
    columns = {"pressure": PRESSURE_COLUMNS, "OASPLdB": SOURCES, "OASPLdBA": SOURCES}.get(stem, LEVELS)
    expected = variable_titles(kind.get(stem, "range"), list(columns), single_observer=True)
    assert read_output(DATA / name).variables == expected


@pytest.mark.parametrize("case", sorted(CASES))
def test_oaspl_recomputed_from_pressure(case):
    """OASPLdB / OASPLdBA within 1e-4 dB (measured ≤ 3.3e-5) with each case's processing."""
    processing, _, _ = CASES[case]
    t, p = _pressure(case)
    level_db, level_dba = oaspl(t, p, **processing)
    assert np.abs(level_db - read_output(DATA / case / "OASPLdB.tec").values[0, 0, 1:]).max() < 1e-4
    assert np.abs(level_dba - read_output(DATA / case / "OASPLdBA.tec").values[0, 0, 1:]).max() < 1e-4


def test_oaspl_includes_the_0_hz_bin_without_high_pass():
    """case1's loading OASPL: 1e-5 dB off with the 0 Hz bin, 0.0129 dB without (band from df/2)."""
    t, p = _pressure("case1")
    reference = read_output(DATA / "case1" / "OASPLdB.tec").values[0, 0, 2]
    with_dc, _ = oaspl(t, p[1])
    without_dc, _ = oaspl(t, p[1], band_hz=(0.5 / (t[-1] - t[0]), np.inf))
    assert abs(with_dc - reference) < 1e-4
    assert abs(without_dc - reference) == pytest.approx(0.0129, abs=5e-4)


def test_case2_needs_the_hanning_window():
    """Without a window case2's OASPL is 2.7–3.0 dB off, with WOPWOP's Hanning window 1e-5 dB."""
    t, p = _pressure("case2")
    reference = read_output(DATA / "case2" / "OASPLdB.tec").values[0, 0, 1:]
    plain, _ = oaspl(t, p, high_pass_hz=1.0)
    assert np.all((np.abs(plain - reference) > 2.6) & (np.abs(plain - reference) < 3.1))


@pytest.mark.parametrize("case", ["case1", "case2", "case4"])
def test_spectrum_recomputed_from_pressure(case):
    """spl_spectrum.tec: frequencies to 2e-5 (relative: times printed to 6 decimals), the 0 Hz bin's raw MSP
    to its 6 printed decimals, every dB / dBA bin within 2e-4 dB + 4σ of the rounding noise (module
    docstring), hence within 0.01 dB where that bound is ≤ 0.01 dB."""
    processing, fixed_point, dba_floor = CASES[case]
    t, p = _pressure(case)
    reference = read_output(DATA / case / "spl_spectrum.tec").values[0]
    frequency, spl_db, spl_dba = spl_spectrum(t, p, a_weighted_floor_pa2=dba_floor, **processing)
    _, msp = mean_square_spectrum(t, p, **processing)
    assert frequency.size == reference.shape[0]
    assert np.allclose(frequency, reference[:, 0], rtol=2e-5, atol=0.0)
    first = 1 if frequency[0] == 0.0 else 0
    if first:
        assert np.allclose(spl_db[:, 0], reference[0, 1:4], rtol=0, atol=6e-7)
        assert np.allclose(spl_dba[:, 0], reference[0, 4:7], rtol=0, atol=6e-7)
    noise = _rounding_noise_msp(p, fixed_point, processing.get("window"))[:, None]
    bound = 2e-4 + 20 * np.log10(1 + 4 * np.sqrt(noise / msp))[:, first:]
    for calc, ref in ((spl_db, reference[:, 1:4].T), (spl_dba, reference[:, 4:7].T)):
        difference = np.abs(calc - ref)[:, first:]
        assert np.all(difference <= bound), float(np.max(difference - bound))
        assert np.all(difference[bound <= 0.01] <= 0.01)


def test_case1_dba_floor_is_1e_20():
    """With WOPWOP 3.4's ε³ = 1e-15 Pa² case1's dBA bins below 12 Hz are up to 49 dB off; with 1e-20 ≤ 0.003 dB."""
    t, p = _pressure("case1")
    reference = read_output(DATA / "case1" / "spl_spectrum.tec").values[0, 1:6, 4:7].T
    _, _, floor_3_4 = spl_spectrum(t, p)
    _, _, floor_case1 = spl_spectrum(t, p, a_weighted_floor_pa2=1e-20)
    assert np.abs(floor_3_4[:, 1:6] - reference).max() > 45.0
    assert np.abs(floor_case1[:, 1:6] - reference).max() < 0.01


@pytest.mark.parametrize("name, band, wrong", [("Low", (1.0, 30.0), [(0.0, 30.0), (1.0, 34.3)]),
                                               ("MidToHigh", (30.0, 1000.0), [(29.0, 725.5), (34.3, 1000.0)])])
def test_case5_frequency_ranges(name, band, wrong):
    """spl_Low / spl_MidToHigh (dB and dBA) within 1e-5 dB with their bins; one bin more or less is ≥ 0.03 dB off."""
    t, p = _pressure("case5")
    reference = read_output(DATA / "case5" / f"spl_{name}.tec").values[0, 0, 1:]
    assert np.abs(np.concatenate(oaspl(t, p, band_hz=band)) - reference).max() < 1e-5
    for other in wrong:
        assert np.abs(np.concatenate(oaspl(t, p, band_hz=other)) - reference).max() > 0.03


@pytest.mark.parametrize("case", sorted(CASES))
def test_written_pressure_was_not_band_filtered(case):
    """A filtered pressure has a zero mean (WOPWOP zeroes the 0 Hz bin): these are not."""
    _, p = _pressure(case)
    assert np.all(np.abs(p.mean(axis=-1)) > 1e-4 * np.sqrt(np.mean(p**2, axis=-1)))
