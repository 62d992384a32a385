"""Content digests of a campaign's Parquet artifacts, to prove that a refactor changed no result.

The digest of an artifact is the SHA-256 of its Parquet bytes after the one field that must
change with any code edit, the ``nps.source_hash`` provenance metadata, is blanked: the file is
re-serialised (same writer options as :func:`nps.app.io.write_table`) with that field set to "".
Everything else (columns, values, schema, the other metadata) enters the digest bit for bit.

    python -m nps.app.digests RESULTS_DIR            # prints "<sha256>  <path>" lines
    python -m nps.app.digests RESULTS_DIR --check MANIFEST

Bit-identity holds on one class of CPU, not across classes: NumPy dispatches its float64
transcendental functions (sin, cos, exp, log) to AVX-512 implementations where the CPU has them,
and those round differently in the last bit from the AVX2 ones. A manifest therefore belongs to
the :func:`cpu_class` it was made on (``tiny_campaign.<class>.sha256``).
"""

from __future__ import annotations

import argparse
import hashlib
import io
import platform
import sys
from pathlib import Path

import pyarrow.parquet as pq


def content_digest(path: Path) -> str:
    """SHA-256 of the artifact with ``nps.source_hash`` blanked."""
    table = pq.read_table(path)
    meta = dict(table.schema.metadata or {})
    meta[b"nps.source_hash"] = b""
    buffer = io.BytesIO()
    pq.write_table(table.replace_schema_metadata(meta), buffer, compression="zstd", write_statistics=True)
    return hashlib.sha256(buffer.getvalue()).hexdigest()


def digests(results: Path) -> dict[str, str]:
    """Relative artifact path → content digest, for every Parquet file under ``results``."""
    return {p.relative_to(results).as_posix(): content_digest(p) for p in sorted(results.rglob("*.parquet"))}


def cpu_class() -> str:
    """The CPU class whose results are bit-identical: the machine and the CPU model numba compiles its kernels
    for (``x86_64-znver5``, ``x86_64-skylake-avx512``, ...; :func:`nps.core.jit.host_cpu_name`). NumPy's SIMD
    dispatch follows the same model, so one class reproduces both."""
    from nps.core.jit import host_cpu_name

    return f"{platform.machine()}-{host_cpu_name()}"


def manifest_path(directory: Path, name: str) -> Path:
    """The manifest ``<directory>/<name>.<cpu_class>.sha256`` of this machine's CPU class."""
    return Path(directory) / f"{name}.{cpu_class()}.sha256"


def read_manifest(path: Path) -> dict[str, str]:
    entries = {}
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            digest, name = line.split(maxsplit=1)
            entries[name] = digest
    return entries


def compare(found: dict[str, str], expected: dict[str, str]) -> list[str]:
    """Human-readable differences (missing, extra, changed artifacts); empty when identical."""
    problems = [f"missing: {n}" for n in sorted(set(expected) - set(found))]
    problems += [f"extra: {n}" for n in sorted(set(found) - set(expected))]
    problems += [f"changed: {n}" for n in sorted(set(found) & set(expected)) if found[n] != expected[n]]
    return problems


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", type=Path)
    parser.add_argument("--check", type=Path, help="manifest to compare with")
    args = parser.parse_args(argv)
    found = digests(args.results)
    if args.check is None:
        for name, digest in found.items():
            print(f"{digest}  {name}")
        return 0
    problems = compare(found, read_manifest(args.check))
    for line in problems:
        print(line)
    print(f"{len(found)} artifacts, {len(problems)} difference(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
