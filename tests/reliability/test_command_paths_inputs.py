"""The per-stage commands on the workflow's plan (issue 34): an output named for another format, an option outside its
configuration field, a rotor the aircraft file lacks are refused in one line naming the option (or file) and what was
expected, exit status 2, nothing written; what an aircraft file says (blade phases, an incoherent tone sum) reaches
the artifacts.

Command cases run in process on the helicopter chain of test_bad_inputs.py (segment 2, 36 × 10 disk, 64 samples,
three observers ahead), like its corpus.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from nps.__main__ import main as nps_main
from nps.app.io import read_metadata
from test_bad_inputs import AIRCRAFT, Case, acoustics_cmd, aircraft_file, chain, check_refused, loads_cmd, metrics_cmd, \
    observers_cmd, trim_cmd  # noqa: F401 (chain: the shared fixture)
from test_bad_inputs_round2 import AHEAD_ONE, _replace


def tones_cmd(b, out, *extra, aircraft=str(AIRCRAFT)) -> list[str]:
    return ["tones", "--aircraft", aircraft, "--trim", str(b.trim), "--signals", str(b.signals), "--out", str(out / "t.parquet"),
            "--csv", str(out / "t.csv"), "--spectra-out", str(out / "s.parquet"), *extra]


def _paths(*options: str) -> list[str]:
    """Required options of a command with placeholder values (the suffix check comes before any is read)."""
    return [text for option in options for text in (option, "x")]


SUFFIX = "expected a path ending in"
CASES = [
    # --- an output file named for another format than the one written there ----------------------------------
    Case("tones_out_named_csv", lambda b, out: _replace(tones_cmd(b, out), "--out", str(out / "x.csv")),
         ("--out", f"{SUFFIX} .parquet", "x.csv")),
    Case("tones_csv_named_parquet", lambda b, out: _replace(tones_cmd(b, out), "--csv", str(out / "y.parquet")),
         ("--csv", f"{SUFFIX} .csv", "y.parquet")),
    Case("tones_spectra_named_csv", lambda b, out: _replace(tones_cmd(b, out), "--spectra-out", str(out / "s.csv")),
         ("--spectra-out", f"{SUFFIX} .parquet")),
    Case("metrics_out_named_csv", lambda b, out: _replace(metrics_cmd(b, out), "--out", str(out / "m.csv")),
         ("--out", f"{SUFFIX} .parquet", "m.csv")),
    Case("metrics_bands_named_csv", lambda b, out: _replace(metrics_cmd(b, out), "--bands-out", str(out / "b.csv")),
         ("--bands-out", f"{SUFFIX} .parquet")),
    Case("trim_out_named_csv", lambda b, out: _replace(trim_cmd(out), "--out", str(out / "t.csv")),
         ("--out", f"{SUFFIX} .parquet", "t.csv")),
    Case("trim_out_without_a_suffix", lambda b, out: _replace(trim_cmd(out), "--out", str(out / "trim")),
         ("--out", f"{SUFFIX} .parquet")),
    Case("observers_out_named_csv", lambda b, out: _replace(observers_cmd(b, out, AHEAD_ONE), "--out", str(out / "o.csv")),
         ("--out", f"{SUFFIX} .parquet")),
    Case("source_hemisphere_out_named_csv", lambda b, out: ["source_hemisphere", *_paths("--aircraft", "--trim", "--observers",
                                                                                         "--signals"), "--out", str(out / "h.csv")],
         ("source_hemisphere", "--out", f"{SUFFIX} .parquet")),
    Case("station_loads_out_named_csv", lambda b, out: ["station-loads", *_paths("--disks", "--trim"), "--stations", "0.75",
                                                        "--out", str(out / "s.csv")], ("--out", f"{SUFFIX} .parquet")),
    Case("radiate_out_named_csv", lambda b, out: ["radiate", *_paths("--sources", "--observers"), "--t-start", "0",
                                                  "--duration", "1", "--samples", "8", "--out", str(out / "p.csv")],
         ("--out", f"{SUFFIX} .parquet")),
    Case("case_out_named_csv", lambda b, out: ["case", *_paths("--aircraft", "--mission", "--config", "--segment", "--cache"),
                                               "--out", str(out / "rows.csv")], ("--out", f"{SUFFIX} .parquet")),
    # --- an option outside its configuration field, a rotor the aircraft file lacks -------------------------
    Case("acoustics_chord_fractions_reversed", lambda b, out: acoustics_cmd(b, out, "--chord-fractions", "0.87", "0.13"),
         ("--chord-fractions", "front < rear")),
    Case("loads_n_r_below_the_schema", lambda b, out: _replace(loads_cmd(b, out), "--n-r", "4"), ("--n-r", ">= 10", "got 4")),
    Case("metrics_humidity_in_percent_over_100", lambda b, out: metrics_cmd(b, out, "--relative-humidity-pct", "170"),
         ("--relative-humidity-pct", "100")),
    Case("tones_rotor_the_aircraft_lacks", lambda b, out: tones_cmd(b, out, "--rotor", "nose"),
         ("helicopter.yaml", "no rotor named 'nose'")),
]


def _files(root: Path) -> set[Path]:
    return {path for path in root.rglob("*") if path.is_file()}


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_command_input_is_one_clear_line(case, chain, tmp_path, capsys):
    """One stderr line naming the option and what was expected, exit status 2, no traceback, no file written (of any
    format: the CSV outputs too)."""
    before = _files(tmp_path)
    check_refused(case, chain, tmp_path, capsys)
    assert {path for path in _files(tmp_path) - before if path.suffix != ".yaml"} == set()  # YAML: inputs the case wrote


def _incoherent(aircraft: dict) -> None:
    aircraft["tone_sum"] = "incoherent"


def test_the_aircraft_files_tone_sum_reaches_the_tones_and_metrics(chain, tmp_path):
    """The commands sum the rotors as the aircraft file says (the workflow's plan): incoherent in both tables."""
    aircraft = aircraft_file(tmp_path, _incoherent)
    assert nps_main(tones_cmd(chain, tmp_path, aircraft=aircraft)) == 0
    assert nps_main(_replace(metrics_cmd(chain, tmp_path), "--aircraft", aircraft)) == 0
    for table in ("t.parquet", "s.parquet", "m.parquet", "b.parquet"):
        assert read_metadata(tmp_path / table)["tone_sum"] == "incoherent", table
    assert (tmp_path / "t.csv").read_text().startswith("observer")


def test_the_aircraft_files_blade_phase_reaches_the_signals(chain, tmp_path):
    """The command radiates the main rotor at the blade phase of the aircraft file (recorded in its signals)."""
    def phased(aircraft: dict) -> None:
        aircraft["rotors"][0]["phase_deg"] = 30.0

    assert nps_main(_replace(acoustics_cmd(chain, tmp_path), "--aircraft", aircraft_file(tmp_path, phased))) == 0
    assert read_metadata(tmp_path / "sig" / "main.parquet")["phase_deg"] == 30.0
    assert "phase_deg" not in read_metadata(tmp_path / "sig" / "tail.parquet")


def test_an_output_suffix_in_capitals_is_the_formats(chain, tmp_path):
    """``T.PARQUET`` names a Parquet file: accepted, and written."""
    assert nps_main(_replace(trim_cmd(tmp_path), "--out", str(tmp_path / "T.PARQUET"))) == 0
    assert read_metadata(tmp_path / "T.PARQUET")["segment"] == "seg2"
