"""nps.wopwop.output: WOPWOP's output files (exact bytes, round trips, hostile files) and its spectral conventions
(closed forms of its normalisation, windows, A-weighting and band filter).

Layouts and formulas: PSU-WOPWOP 3.4 obsUtility.f90 writeOutTecplotData, observerContainer.f90
WriteTimeHistoryFunctionFile / WriteStationaryObsSurface, observer.f90 WriteNameFile / CalcObsComplexPressure /
FilterPPrime, freqAnalysis.f90 Aweight / CreateHanningWindow (module docstring of nps.wopwop.output)."""

import struct

import numpy as np
import pytest

from nps.wopwop.errors import WopwopError
from nps.wopwop.output import (
    OutputTable,
    a_weighting_power,
    band_filter,
    mean_square_spectrum,
    oaspl,
    output_table,
    pressure_groups,
    read_output,
    spl_spectrum,
    variable_titles,
    window_function,
    write_plot3d,
    write_tec,
)

GREEK = "re20<greek>m</greek>Pa"


def _table(n_obs=3, n=4, seed=0, positions=True) -> OutputTable:
    """A several-observer pressure table of float32-representable values (dim1 = n_obs, dim2 = 1)."""
    rng = np.random.default_rng(seed)
    time = (1.0 + 1e-3 * np.arange(n)).astype(np.float32).astype(float)
    columns = {s: rng.normal(scale=10.0 ** rng.uniform(-4, 2), size=(n_obs, n)).astype(np.float32).astype(float)
               for s in ("Thickness", "Loading", "Total")}
    xyz = rng.normal(scale=50.0, size=(n_obs, n, 3)).astype(np.float32).astype(float) if positions else None
    return output_table("pressure", time, columns, shape=(n_obs, 1), positions_m=xyz)


def _quantum(values: np.ndarray, digits: int) -> np.ndarray:
    """Half a unit of the last of ``digits`` significant digits (the rounding of E / G editing)."""
    exponent = np.floor(np.log10(np.maximum(np.abs(values), 1e-300))) + 1
    return 0.5 * 10.0 ** (exponent - digits) * (1 + 1e-9)


# ---------------------------------------------------------------- exact bytes


def test_tec_bytes_are_wopwops(tmp_path):
    """case2's OASPLdB.tec of PSU-WOPWOP, typed from the file: title, variables, TEXT line, blank, E15.8 rows."""
    table = output_table("OASPLdB", [1.025], {"Thickness": [64.912567], "Loading": [54.000301], "Total": [64.741035]})
    expected = (
        ' TITLE="PSU-WOPWOP"\r\n'
        f'VARIABLES= "SPL Time (s)", "ThicknessOASPL (dB, {GREEK}) OASPL (dB)", "LoadingOASPL (dB, {GREEK}) OASPL (dB)",'
        f' "TotalOASPL (dB, {GREEK}) OASPL (dB)"\r\n'
        f'TEXT X=100 Y=95 AN=HEADRIGHT T="SPL Time (s) vs \\\\nThicknessOASPL (dB, {GREEK}) OASPL (dB)\\\\n'
        f'LoadingOASPL (dB, {GREEK}) OASPL (dB)\\\\nTotalOASPL (dB, {GREEK}) OASPL (dB)\\\\n "\r\n'
        "\r\n"
        " 0.10250000E+01  0.64912567E+02  0.54000301E+02  0.64741035E+02  \r\n"
    )
    write_tec(tmp_path / "OASPLdB.tec", table, "e15.8", "\r\n")
    assert (tmp_path / "OASPLdB.tec").read_bytes() == expected.encode("ascii")


def test_tec_fixed_point_rows(tmp_path):
    """The fixed-point rows of case1's OASPLdB.tec: abscissa F15.6, others F12.6, each and a blank, one more blank."""
    table = output_table("OASPLdB", [0.0], {"Thickness": [84.448151], "Loading": [71.676979], "Total": [84.814499]})
    write_tec(tmp_path / "a.tec", table, "f15.6")
    assert (tmp_path / "a.tec").read_text().splitlines()[4] == "       0.000000    84.448151    71.676979    84.814499  "


def test_ascii_function_file_is_4i12_then_g15_6(tmp_path):
    """(4I12) header, the abscissa for every observer at each step, then each function; Fortran G15.6 values
    (F2008 10.7.5.2.3: F11.(6−s) and four blanks for 0.1 ≤ |x| < 1e6, else E15.6; zero as F11.5)."""
    values = [0.0, 1.025, 0.05, 123456.7, 1.0e6, -2.5e-3, 0.5, -42.0]
    table = output_table("pressure", [0.5, 1.025], {"Thickness": [values[:2], values[2:4]],
                                                      "Total": [values[4:6], values[6:]]}, shape=(2, 1))
    write_plot3d(tmp_path / "p", table)
    lines = (tmp_path / "p.fn").read_text().splitlines()
    assert lines[0] == "           2           1           2           3"
    assert lines[1:5] == ["   0.500000    "] * 2 + ["    1.02500    "] * 2
    assert lines[5:] == ["    0.00000    ", "   0.500000E-01", "    1.02500    ", "    123457.    ",
                         "   0.100000E+07", "   0.500000    ", "  -0.250000E-02", "   -42.0000    "]
    assert (tmp_path / "p.nam").read_bytes() == b" Observer Time (s)\n ThicknessAcoustic Pressure\n TotalAcoustic Pressure\n"


def test_titles_follow_the_number_of_observers():
    """One observer: .tec titles; several: .nam titles (observerContainer.f90, observer.f90)."""
    assert variable_titles("pressure", ["Total", "Thickness"], True) == (
        "Observer Time (s)", "Thickness Acoustic Pressure (Pa)", "Total Acoustic Pressure (Pa)")
    assert variable_titles("pressure", ["Loading", "LoadingPGX"], False) == (
        "Observer Time (s)", "LoadingAcoustic Pressure", "LoadingPGXAcoustic Pressure")
    assert variable_titles("OASPLdBA", ["Total"], True) == ("SPL Time (s)", f"TotalOASPL (dBA, {GREEK})OASPL (dBA)")
    assert variable_titles("OASPLdB", ["Total"], False) == ("SPL Time (s)", f"TotalOASPL (dB, {GREEK})")
    assert variable_titles("spl_spectrum", ["Total_dBA", "Loading_dB"], False) == ("Frequency", "Loading_dB", "Total_dBA")
    assert variable_titles("range", ["Total_dBA"], True) == ("SPL Time (s)", f"TotalSPL (dBA, {GREEK})SPL (dB)")
    assert variable_titles("range", ["Total_dBA"], False) == ("SPL Time (s)", f"TotalSPL (dBA, {GREEK})")
    with pytest.raises(WopwopError):
        variable_titles("pressure", ["Broadband"], True)


# ---------------------------------------------------------------- round trips


@pytest.mark.parametrize("number_format, digits", [("e15.8", 8), ("f15.6", None)])
def test_tec_round_trip_within_printed_precision(tmp_path, number_format, digits):
    table = _table(n_obs=1, n=50, positions=False)
    if number_format == "f15.6":
        table = OutputTable(table.variables, np.clip(table.values, -9000.0, 9000.0), (1, 1))
    write_tec(tmp_path / "p.tec", table, number_format)
    back = read_output(tmp_path / "p.tec")
    assert back.variables == table.variables and back.shape == (1, 1) and back.positions_m is None
    tolerance = _quantum(table.values, digits) if digits else 5e-7 * (1 + 1e-9)
    assert np.all(np.abs(back.values - table.values) <= tolerance)
    assert pressure_groups(back)["loading"].shape == (1, 50)


def test_plot3d_ascii_round_trip_within_g15_6(tmp_path):
    table = _table()
    write_plot3d(tmp_path / "pressure", table)
    for name in ("pressure", "pressure.fn", "pressure.x", "pressure.nam"):
        back = read_output(tmp_path / name)
        assert back.variables == table.variables and back.shape == (3, 1)
        assert np.all(np.abs(back.values - table.values) <= _quantum(table.values, 6))
        assert np.all(np.abs(back.positions_m - table.positions_m) <= _quantum(table.positions_m, 6))


@pytest.mark.parametrize("byte_order", ["<", ">"])
def test_plot3d_binary_round_trip_is_exact(tmp_path, byte_order):
    table = _table(n_obs=4, n=5)
    write_plot3d(tmp_path / "OASPLdB", table, ascii=False, byte_order=byte_order, grid_path=tmp_path / "OASPL.x")
    head = (tmp_path / "OASPLdB.fn").read_bytes()[:16]
    assert head == struct.pack(byte_order + "4i", 4, 1, 5, 4)
    back = read_output(tmp_path / "OASPLdB")
    assert np.array_equal(back.values, table.values)
    assert np.array_equal(back.positions_m, table.positions_m)
    assert pressure_groups(back).keys() == {"thickness", "loading", "total"}


def _hand_built(dim1=2, dim2=1, n=3):
    """Values by explicit loops in WOPWOP's order: time[step] per observer, then f_k[obs, step]; grid x, y, z."""
    time = [0.5 + 0.25 * s for s in range(n)]
    f = [[[100 * k + 10 * o + s for s in range(n)] for o in range(dim1 * dim2)] for k in (1, 2)]
    xyz = [[[1000 * c + 10 * o + s for s in range(n)] for o in range(dim1 * dim2)] for c in range(3)]
    fn = [time[s] for s in range(n) for o in range(dim1 * dim2)]
    fn += [f[k][o][s] for k in range(2) for s in range(n) for o in range(dim1 * dim2)]
    grid = [xyz[c][o][s] for c in range(3) for s in range(n) for o in range(dim1 * dim2)]
    return (dim1, dim2, n), time, f, xyz, fn, grid


def _check_hand_built(table, counts, time, f, xyz):
    assert table.variables == ("Observer Time (s)", "ThicknessAcoustic Pressure", "TotalAcoustic Pressure")
    assert table.shape == counts[:2]
    for o in range(counts[0] * counts[1]):
        for s in range(counts[2]):
            assert table.values[o, s, 0] == time[s]
            assert list(table.values[o, s, 1:]) == [f[0][o][s], f[1][o][s]]
            assert list(table.positions_m[o, s]) == [xyz[c][o][s] for c in range(3)]


@pytest.mark.parametrize("dims", [(2, 1, 3), (3, 2, 4)])
def test_hand_built_big_endian_triple(tmp_path, dims):
    """A moving dim1 × dim2 observer grid (positions per step), big-endian, CRLF titles."""
    counts, time, f, xyz, fn, grid = _hand_built(*dims)
    (tmp_path / "pressure.fn").write_bytes(struct.pack(">4i", *counts, 3) + struct.pack(f">{len(fn)}f", *fn))
    (tmp_path / "pressure.x").write_bytes(struct.pack(">3i", *counts) + struct.pack(f">{len(grid)}f", *grid))
    (tmp_path / "pressure.nam").write_bytes(b" Observer Time (s)\r\n ThicknessAcoustic Pressure\r\n TotalAcoustic Pressure\r\n")
    _check_hand_built(read_output(tmp_path / "pressure"), counts, time, f, xyz)


def test_hand_built_ascii_triple(tmp_path):
    counts, time, f, xyz, fn, grid = _hand_built()
    (tmp_path / "pressure.fn").write_text("".join(f"{c:12d}" for c in counts + (3,)) + "\n"
                                          + "".join(f"{v:15.6G}\n" for v in fn))
    (tmp_path / "pressure.x").write_text("".join(f"{c:12d}" for c in counts) + "\n" + "".join(f"{v:15.6E}\n" for v in grid))
    (tmp_path / "pressure.nam").write_text(" Observer Time (s)\n ThicknessAcoustic Pressure\n TotalAcoustic Pressure\n")
    _check_hand_built(read_output(tmp_path / "pressure.x"), counts, time, f, xyz)


# ---------------------------------------------------------------- hostile files

HEAD = ' TITLE="PSU-WOPWOP"\nVARIABLES= "t", "p"\nTEXT X=100 Y=95 AN=HEADRIGHT T="t vs \\\\np\\\\n "\n\n'


@pytest.mark.parametrize("content, message", [
    (b"", "line 1: expected TITLE"),
    (b'VARIABLES= "t", "p"\n\n1 2\n', "line 1: expected TITLE"),
    (b' TITLE="PSU-WOPWOP"\n 1 2\n', "line 2: expected VARIABLES"),
    (b' TITLE="PSU-WOPWOP"\nVARIABLES= "t"\n1\n', "line 2: expected at least two"),
    ((HEAD + " 1 2\n 1 2 3\n").encode(), "line 6: expected 2 values (one per variable), got 3"),
    ((HEAD + " 1 abc\n").encode(), "line 5, column 2: expected a number, got 'abc'"),
    ((HEAD + " 1 ************\n").encode(), "line 5, column 2: expected a number"),
    ((HEAD + " 1 NaN\n").encode(), "line 5, column 2: expected a finite number"),
    (HEAD.encode(), "expected data rows"),
    ((HEAD + " 1 2\xb5\n").encode("latin-1"), "expected ASCII text"),
])
def test_hostile_tec_refused_in_one_line(tmp_path, content, message):
    path = tmp_path / "bad.tec"
    path.write_bytes(content)
    with pytest.raises(WopwopError) as caught:
        read_output(path)
    text = str(caught.value)
    assert "\n" not in text and text.startswith(str(path)) and message in text, text


def _binary_fn(counts=(2, 1, 3, 2), n_values=None, order="<", nan_at=None):
    values = np.arange(n_values if n_values is not None else int(np.prod(counts)), dtype=float)
    if nan_at is not None:
        values[nan_at] = np.nan
    return struct.pack(f"{order}4i", *counts) + values.astype(order + "f4").tobytes()


@pytest.mark.parametrize("files, message", [
    ({"o.fn": b"\x01\x00\x00"}, "o.fn: byte 0: expected a header of 4 4-byte ints"),
    ({"o.fn": _binary_fn(n_values=11)}, "o.fn: byte 0: header: expected 4 counts >= 1 whose data fill"),
    ({"o.fn": _binary_fn(counts=(2, -1, 3, 2), n_values=12)}, "o.fn: byte 0: header"),
    ({"o.fn": _binary_fn(order=">", nan_at=5), "o.nam": b" t\n p\n"}, "o.fn: byte 36: expected a finite real"),
    ({"o.fn": b"           2           1           3\n1\n2\n"}, "o.fn: line 1: header: expected 4 integer counts"),
    ({"o.fn": b"           2           1           3           1\n1\n2\n"}, "o.fn: line 1: header counts (2, 1, 3, 1) need 6"),
    ({"o.fn": b"           1           1           2           1\n1.0\nabc\n", "o.nam": b" t\n"}, "o.fn: line 3: expected a number"),
    ({"o.fn": b"           1           1           1           1\n NaN\n", "o.nam": b" t\n"}, "o.fn: line 2: expected a finite"),
    ({"o.fn": _binary_fn(), "o.nam": b" t\n p\n q\n"}, "o.nam: line count: expected 2 titles"),
    ({"o.fn": _binary_fn()}, "o.nam: cannot be read"),
    ({"o.fn": _binary_fn(), "o.nam": b" t\n p\n", "o.x": struct.pack("<3i", 2, 1, 2) + bytes(48)},
     "o.x: byte 0: header: expected (dim1, dim2, n) = (2, 1, 3)"),
    ({"o.x": struct.pack("<3i", 1, 1, 1) + bytes(12)}, "o.fn: expected the function file beside the grid"),
])
def test_hostile_plot3d_refused_in_one_line(tmp_path, files, message):
    for name, content in files.items():
        (tmp_path / name).write_bytes(content)
    target = tmp_path / ("o.x" if list(files) == ["o.x"] else "o")
    with pytest.raises(WopwopError) as caught:
        read_output(target)
    text = str(caught.value)
    assert "\n" not in text and str(tmp_path) in text and message in text, text


def test_writers_refuse_what_wopwop_could_not_write(tmp_path):
    several = _table()
    with pytest.raises(WopwopError, match="holds one observer"):
        write_tec(tmp_path / "a.tec", several)
    big = output_table("OASPLdB", [0.0], {"Total": [1.0e6]})
    with pytest.raises(WopwopError, match="value 1: expected a finite number"):
        write_tec(tmp_path / "a.tec", big, "f15.6")
    bad = OutputTable(big.variables, np.array([[[0.0, np.nan]]]), (1, 1))
    for write in (lambda: write_tec(tmp_path / "a.tec", bad), lambda: write_plot3d(tmp_path / "b", bad)):
        with pytest.raises(WopwopError) as caught:
            write()
        assert "\n" not in str(caught.value)
    with pytest.raises(WopwopError, match="byte_order"):
        write_plot3d(tmp_path / "b", several, ascii=False, byte_order="=")
    with pytest.raises(WopwopError, match="quote"):
        write_tec(tmp_path / "a.tec", OutputTable(('t "s"', "p"), np.zeros((1, 1, 2)), (1, 1)))
    with pytest.raises(WopwopError, match="shape"):
        OutputTable(("t", "p"), np.zeros((3, 2, 2)), (2, 1))


# ---------------------------------------------------------------- spectral conventions

P_REF = 2e-5


def test_tone_level_with_wopwops_normalisation():
    """A 1 Pa tone completing k cycles in the nt samples lands in bin k, labelled k/(t_end − t0), with
    P = 2X/(nt − 1): SPL = 10 log10(½ (nt/(nt − 1))² / P_ref²) = 90.969 + 20 log10(nt/(nt − 1)) dB exactly;
    OASPL the same (the other bins hold nothing); at 1 kHz dBA = dB."""
    for nt, k in ((64, 5), (4096, 100)):
        dt = k / (1000.0 * (nt - 1)) if nt == 4096 else 1e-3  # the second tone labelled 1 kHz
        t = dt * np.arange(nt)
        p = np.cos(2 * np.pi * k * np.arange(nt) / nt + 0.3)
        frequency, spl_db, spl_dba = spl_spectrum(t, p)
        expected = 10 * np.log10(0.5 * (nt / (nt - 1)) ** 2 / P_REF**2)
        assert frequency[k] == pytest.approx(k / (t[-1] - t[0]), rel=1e-12)
        assert spl_db[k] == pytest.approx(expected, abs=1e-9)
        level_db, level_dba = oaspl(t, p)
        assert level_db == pytest.approx(expected, abs=1e-9)
    assert expected == pytest.approx(90.969 + 0.00212, abs=2e-4)
    assert frequency[k] == pytest.approx(1000.0, rel=1e-12)
    assert level_dba == pytest.approx(level_db, abs=1e-9) and spl_dba[k] == pytest.approx(spl_db[k], abs=1e-9)


def test_zero_hz_bin_is_half_the_square_and_raw_in_the_spectrum():
    """P_0 = X_0/(nt − 1), MSP_0 = ½P_0²; spl_spectrum keeps that MSP (Pa²) at 0 Hz, in dB and dBA; a
    high-pass above 0 drops the bin."""
    nt, c = 33, 2.0
    t = 0.01 * np.arange(nt)
    frequency, spl_db, spl_dba = spl_spectrum(t, np.full(nt, c))
    assert frequency[0] == 0.0
    assert spl_db[0] == pytest.approx(0.5 * (c * nt / (nt - 1)) ** 2, rel=1e-12) and spl_dba[0] == spl_db[0]
    assert spl_db[1] == pytest.approx(10 * np.log10(1e-15 / P_REF**2), abs=1e-6)
    assert oaspl(t, np.full(nt, c))[0] == pytest.approx(10 * np.log10(0.5 * (c * nt / (nt - 1)) ** 2 / P_REF**2), abs=1e-9)
    assert mean_square_spectrum(t, np.full(nt, c), high_pass_hz=1.0)[0][0] == pytest.approx(1 / 0.32)


def test_hanning_window_tone_closed_form():
    """WOPWOP's Hanning window w_i = 0.5 − 0.5 cos(2πi/nt), i = 1…nt, scaled by √(nt/Σw²) = √(8/3): a tone of
    amplitude a periodic in nt samples gives MSP_k = (nt/(nt − 1))² a²/3 and MSP_{k±1} = (nt/(nt − 1))² a²/12."""
    nt, k, a = 128, 9, 0.7
    w = window_function("hanning window", nt)
    assert w[-1] == 0.0 and np.sum(w**2) == pytest.approx(nt, rel=1e-12)
    assert w[0] == pytest.approx(np.sqrt(8 / 3) * (0.5 - 0.5 * np.cos(2 * np.pi / nt)), rel=1e-12)
    t = 1e-4 * np.arange(nt)
    _, msp = mean_square_spectrum(t, a * np.cos(2 * np.pi * k * np.arange(nt) / nt - 1.1), window="Hanning Window")
    scale = (nt / (nt - 1)) ** 2 * a**2
    assert msp[k] == pytest.approx(scale / 3, rel=1e-12)
    assert msp[k - 1] == pytest.approx(scale / 12, rel=1e-12) and msp[k + 1] == pytest.approx(scale / 12, rel=1e-12)
    for name in ("Hamming Window", "BLACKMAN WINDOW", "flat top window"):
        assert np.sum(window_function(name, nt) ** 2) == pytest.approx(nt, rel=1e-12)


def test_a_weighting_is_wopwops_curve():
    """W_A equals WOPWOP's Aweight (its constants, freqAnalysis.f90) within 2e-6 dB over 1 Hz–20 kHz; 0 at 0 Hz."""
    f = np.logspace(0, np.log10(20000), 2001)
    k1, g1, f4, k3, f2, f3 = 2.242881e16, 20.598997, 12194.22, 1.562339, 107.65265, 737.86223
    wopwop = k3 * f**4 / ((f**2 + f2**2) * (f**2 + f3**2)) * k1 * f**4 / ((f**2 + g1**2) ** 2 * (f**2 + f4**2) ** 2)
    assert np.max(np.abs(10 * np.log10(a_weighting_power(f) / wopwop))) < 2e-6
    assert a_weighting_power([0.0])[0] == 0.0
    assert 10 * np.log10(a_weighting_power(1000.0)) == pytest.approx(0.0, abs=1e-9)


def test_band_filter_keeps_the_bins_between_the_filters():
    """WOPWOP's written pressure: unchanged without filters; else the FFT bins outside [hpf, lpf] and the 0 Hz
    bin zeroed (ConvertFrequencyToTime), inverse divided by nt."""
    nt = 100
    t = 1e-3 * np.arange(nt)
    n = np.arange(nt)
    low, high = np.cos(2 * np.pi * 3 * n / nt), np.sin(2 * np.pi * 20 * n / nt)
    p = 1.5 + low + high
    df = 1 / (t[-1] - t[0])
    assert np.array_equal(band_filter(t, p), p)
    assert np.allclose(band_filter(t, p, high_pass_hz=10 * df), high, atol=1e-12)
    assert np.allclose(band_filter(t, p, low_pass_hz=10 * df), low, atol=1e-12)
    assert np.allclose(band_filter(t, p, high_pass_hz=3 * df, low_pass_hz=3 * df), low, atol=1e-12)


def test_bin_selection_tolerance():
    """Bins within 1e-5 Hz of the high-pass are kept (CalcObsContComplexPressure), farther ones dropped."""
    t = 0.01 * np.arange(11)
    assert mean_square_spectrum(t, np.sin(t), high_pass_hz=20 + 0.5e-5)[0][0] == pytest.approx(20.0)
    assert mean_square_spectrum(t, np.sin(t), high_pass_hz=20 + 2e-5)[0][0] == pytest.approx(30.0)
    assert mean_square_spectrum(t, np.sin(t), low_pass_hz=30 - 0.5e-5)[0][-1] == pytest.approx(30.0)


@pytest.mark.parametrize("time, p, kwargs, message", [
    (np.array([0.0, 0.1, 0.3, 0.31]), np.zeros(4), {}, "time_s: expected increasing times"),
    (np.arange(4.0), np.array([0.0, np.nan, 0.0, 0.0]), {}, "expected finite values"),
    (np.arange(1.0), np.zeros(1), {}, "nt >= 2"),
    (np.arange(4.0), np.zeros(5), {}, "(…, nt) pressures"),
    (np.arange(8.0), np.zeros(8), {"window": "Kaiser"}, "windowFunction"),
    (np.arange(8.0), np.zeros(8), {"high_pass_hz": 10.0}, "got none"),
])
def test_bad_records_refused_in_one_line(time, p, kwargs, message):
    with pytest.raises(WopwopError) as caught:
        spl_spectrum(time, p, **kwargs)
    assert "\n" not in str(caught.value) and message in str(caught.value), str(caught.value)
