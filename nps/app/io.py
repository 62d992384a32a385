"""Parquet artifacts: explicit schemas, provenance metadata, atomic and deterministic writes.

Every artifact is written through :func:`write_table`: columns are cast to an explicit
pyarrow schema (so an all-null column never gets a ``null`` type), the file is written to a
temporary name in the target directory and renamed into place (an interrupted run leaves no
half-written artifact), and no wall-clock data enters the file (same inputs, same bytes).

Files: an artifact gets the permissions of the process umask (0666 & ~umask, as ``open`` gives);
its temporary file ``.{name}.{8 random characters}.tmp`` is removed when the write fails, and
temporaries of the same output left by a killed run (SIGKILL cannot be caught) are removed the
next time that output is written. One writer per output path at a time (the workflow's rule).
"""

from __future__ import annotations

import json
import os
import re
import secrets
from pathlib import Path
from typing import Mapping

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

import nps
from nps.core.jit import source_hash
from nps.noise.signals import SIGNAL_COLUMNS


class ArtifactError(ValueError):
    """An artifact is missing, malformed or contains non-finite numbers."""


def _arrow_type(series: pd.Series) -> pa.DataType:
    if pd.api.types.is_bool_dtype(series):
        return pa.bool_()
    if pd.api.types.is_integer_dtype(series):
        return pa.from_numpy_dtype(series.dtype)
    if pd.api.types.is_float_dtype(series):
        return pa.from_numpy_dtype(series.dtype)
    return pa.string()


def check_finite(df: pd.DataFrame, what: str) -> None:
    """Raise :class:`ArtifactError` naming the first column with NaN or inf."""
    for name in df.columns:
        column = df[name]
        if pd.api.types.is_float_dtype(column) and not np.isfinite(column.to_numpy()).all():
            bad = int((~np.isfinite(column.to_numpy())).sum())
            raise ArtifactError(f"{what}: column '{name}' has {bad} non-finite value(s)")


def _arrow_table(df: pd.DataFrame, schema: pa.Schema) -> pa.Table:
    """``df`` as an Arrow table with ``schema``, identical to ``pa.Table.from_pandas(df, schema=schema)``.

    That direct call converts categorical columns to strings element by element (≈0.3 s for a
    rotor's signal table); converting natively (dictionary arrays) and casting is ~20× faster. The
    pandas metadata pyarrow attaches depends on the dtypes only, so it is taken from the first row.
    """
    head = pa.Table.from_pandas(df.iloc[:1], schema=schema, preserve_index=False)
    try:
        table = pa.Table.from_pandas(df, preserve_index=False).cast(schema)
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError, pa.ArrowTypeError):  # types the cast cannot map
        return pa.Table.from_pandas(df, schema=schema, preserve_index=False)
    return table.replace_schema_metadata(head.schema.metadata)


def write_table(
    df: pd.DataFrame,
    path: str | os.PathLike,
    *,
    stage: str,
    metadata: Mapping[str, object] | None = None,
    schema: pa.Schema | None = None,
) -> Path:
    """Write ``df`` to ``path`` atomically with provenance metadata.

    ``metadata`` values are JSON-encoded under ``nps.<key>``. Non-finite floats are refused.
    Returns the path written.
    """
    path = Path(path)
    if path.is_dir():
        raise ArtifactError(f"{path}: is a directory; expected the path of the {stage} Parquet file")
    check_finite(df, f"{path} ({stage})")
    if schema is None:
        schema = pa.schema([pa.field(str(c), _arrow_type(df[c])) for c in df.columns])
    table = _arrow_table(df, schema)
    meta = {
        b"nps.version": nps.__version__.encode(),
        b"nps.source_hash": source_hash().encode(),
        b"nps.stage": stage.encode(),
    }
    for key, value in (metadata or {}).items():
        meta[f"nps.{key}".encode()] = json.dumps(value, sort_keys=True, default=_json_default).encode()
    table = table.replace_schema_metadata({**(table.schema.metadata or {}), **meta})
    path.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_temporaries(path)
    tmp = _create_temporary(path)
    try:
        pq.write_table(table, tmp, compression="zstd", write_statistics=True)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
    return path


_TEMPORARY_TOKEN = re.compile(r"[a-z0-9_]{8}")  # also the names tempfile.mkstemp made before


def _create_temporary(path: Path) -> Path:
    """Create ``.{name}.{token}.tmp`` next to ``path`` with mode 0666 & ~umask (O_EXCL, new token on collision)."""
    while True:
        tmp = path.with_name(f".{path.name}.{secrets.token_hex(4)}.tmp")
        try:
            os.close(os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666))
            return tmp
        except FileExistsError:
            continue


def remove_stale_temporaries(path: str | os.PathLike) -> list[Path]:
    """Remove the temporary files ``.{name}.{token}.tmp`` a killed write of ``path`` left behind; returns them."""
    path = Path(path)
    prefix, removed = f".{path.name}.", []
    if not path.parent.is_dir():
        return removed
    for entry in sorted(os.scandir(path.parent), key=lambda e: e.name):
        name = entry.name
        if name.startswith(prefix) and name.endswith(".tmp") and _TEMPORARY_TOKEN.fullmatch(name[len(prefix):-4]):
            try:
                os.unlink(entry.path)
            except FileNotFoundError:
                continue
            removed.append(Path(entry.path))
    return removed


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot store {type(value).__name__} in artifact metadata")


def read_table(path: str | os.PathLike, required: tuple[str, ...] = (), nonempty: bool = False,
               finite: bool = False, unique: str | None = None) -> pd.DataFrame:
    """Read an artifact; raise :class:`ArtifactError` naming missing ``required`` columns, a table
    without rows (``nonempty``), NaN/inf in a float column (``finite``: inputs from other tools) or a
    value repeated in the column ``unique`` (e.g. the observer ids)."""
    path = Path(path)
    if not path.is_file():
        raise ArtifactError(f"{path}: artifact not found" if not path.exists() else f"{path}: expected a Parquet file")
    try:
        df = pq.read_table(path).to_pandas()
    except (pa.ArrowException, OSError) as exc:
        raise ArtifactError(f"{path}: not a readable Parquet file ({str(exc).splitlines()[0]})") from None
    missing = [c for c in required if c not in df.columns]
    if missing:
        raise ArtifactError(f"{path}: missing column(s) {missing}; has {list(df.columns)}")
    if nonempty and len(df) == 0:
        raise ArtifactError(f"{path}: the table has no rows")
    if finite:
        check_finite(df, str(path))
    if unique is not None and unique in df.columns and df[unique].duplicated().any():
        repeated = df[unique][df[unique].duplicated()].unique()[:5].tolist()
        raise ArtifactError(f"{path}: {unique}: expected unique ids, {repeated} repeat "
                            f"({df[unique].nunique()} distinct in {len(df)} rows)")
    return df


def artifact_rows(path: str | os.PathLike) -> int:
    """Row count of an artifact from its Parquet footer (nothing else is read), for memory estimates."""
    read_metadata(path)  # names a missing or unreadable file
    return int(pq.read_metadata(path).num_rows)


def check_provenance(path: str | os.PathLike, expected: Mapping[str, object]) -> dict[str, object]:
    """Refuse an input artifact made for something else; returns its ``nps.*`` metadata.

    ``expected``: metadata key → the value the reading stage works on (``aircraft``, ``segment``,
    ``rotor``, ``obsset``, ``variant``; ``stage``: a name or a tuple of accepted names). Keys whose
    expected value is ``None`` or ``""``, and keys the artifact does not record (tables from other
    tools), are not checked. One :class:`ArtifactError` lists every mismatch.
    """
    meta = read_metadata(path)
    problems = []
    for key, want in expected.items():
        if want is None or want == "" or key not in meta:
            continue
        accepted = tuple(str(w) for w in want) if isinstance(want, (tuple, list)) else (str(want),)
        if str(meta[key]) not in accepted:
            problems.append(f"{key} '{meta[key]}' (expected {' or '.join(repr(a) for a in accepted)})")
    if problems:
        raise ArtifactError(f"{path}: input made for {', '.join(problems)} according to its provenance metadata; "
                            f"pass the artifact of the same {', '.join(p.split(' ', 1)[0] for p in problems)}")
    return meta


def read_metadata(path: str | os.PathLike) -> dict[str, object]:
    """The ``nps.*`` metadata of an artifact, JSON-decoded where possible."""
    if not Path(path).is_file():
        raise ArtifactError(f"{path}: artifact not found")
    try:
        raw = pq.read_schema(path).metadata or {}
    except (pa.ArrowException, OSError) as exc:
        raise ArtifactError(f"{path}: not a readable Parquet file ({str(exc).splitlines()[0]})") from None
    out: dict[str, object] = {}
    for key, value in raw.items():
        name = key.decode()
        if not name.startswith("nps."):
            continue
        try:
            out[name[4:]] = json.loads(value)
        except json.JSONDecodeError:
            out[name[4:]] = value.decode()
    return out


def rotor_path(directory: str | os.PathLike, rotor: str, suffix: str = "") -> Path:
    """Artifact ``{rotor}{suffix}.parquet`` in a per-aircraft directory holding one file per rotor
    (``bvi/``, ``wake/``, ``acoustics/{obsset}_{variant}/``, ``hsi/{obsset}_{variant}/``)."""
    return Path(directory) / f"{rotor}{suffix}.parquet"


def read_signals(directory: str | os.PathLike, rotors) -> dict[str, pd.DataFrame]:
    """Rotor name → signal table (columns :data:`SIGNAL_COLUMNS`) of every rotor in a signals directory."""
    return {r: read_table(rotor_path(directory, r), required=SIGNAL_COLUMNS, nonempty=True, finite=True) for r in rotors}
