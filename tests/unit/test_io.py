"""Artifacts: explicit schema, provenance, determinism, atomicity, refusal of non-finite data."""

import hashlib

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

from nps.app.io import ArtifactError, read_metadata, read_table, write_table


def test_bit_identical_rewrites(tmp_path):
    df = pd.DataFrame({"x_m": np.linspace(0, 1, 11), "name": list("abcdefghijk")})
    digests = []
    for _ in range(2):
        write_table(df, tmp_path / "a.parquet", stage="test", metadata={"case": {"b": 2, "a": 1}})
        digests.append(hashlib.sha256((tmp_path / "a.parquet").read_bytes()).hexdigest())
    assert digests[0] == digests[1]
    assert read_metadata(tmp_path / "a.parquet")["case"] == {"a": 1, "b": 2}


def test_all_null_column_keeps_declared_type(tmp_path):
    df = pd.DataFrame({"label": [None, None]}, dtype=object)
    write_table(df, tmp_path / "n.parquet", stage="test")
    assert str(pq.read_schema(tmp_path / "n.parquet").field("label").type) == "string"


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_is_refused_and_nothing_is_written(tmp_path, bad):
    df = pd.DataFrame({"p_Pa": [1.0, bad]})
    with pytest.raises(ArtifactError, match="column 'p_Pa' has 1 non-finite"):
        write_table(df, tmp_path / "bad.parquet", stage="test")
    assert list(tmp_path.iterdir()) == []


def test_failed_write_leaves_no_partial_file(tmp_path, monkeypatch):
    import nps.app.io

    def explode(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(nps.app.io.pq, "write_table", explode)
    with pytest.raises(OSError):
        write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "x.parquet", stage="test")
    assert list(tmp_path.iterdir()) == []


def test_read_names_missing_columns(tmp_path):
    write_table(pd.DataFrame({"a": [1.0]}), tmp_path / "x.parquet", stage="test")
    with pytest.raises(ArtifactError, match=r"missing column\(s\) \['b'\]"):
        read_table(tmp_path / "x.parquet", required=("a", "b"))


def test_signal_arrays_inverts_signals_table_in_any_row_order():
    """signal_arrays(signals_table(p)) == p, also after shuffling rows (the non-canonical path)."""
    from nps.noise.acoustics import TimeGrid
    from nps.noise.signals import signal_arrays, signals_table

    rng = np.random.default_rng(3)
    ids = np.array([7, 2, 5])
    pressure = rng.normal(size=(3, 2, 16))
    table = signals_table(ids, ("thickness", "loading"), pressure, TimeGrid(0.0, 0.1, 16), total=False)
    order = np.argsort(ids)
    for t in (table, table.sample(frac=1.0, random_state=1)):
        got_ids, time_s, groups = signal_arrays(t)
        np.testing.assert_array_equal(got_ids, ids[order])
        np.testing.assert_allclose(time_s, np.arange(16) * 0.1 / 16)
        np.testing.assert_array_equal(groups["thickness"], pressure[order, 0])
        np.testing.assert_array_equal(groups["loading"], pressure[order, 1])
    with pytest.raises(ValueError, match="same number of samples"):
        signal_arrays(table.iloc[1:])
    with pytest.raises(ValueError, match="expected"):
        signal_arrays(table, groups=("thickness",))
