"""Code digests of the stages: what makes a workflow job rerun when the code it runs changes.

A stage's digest is the SHA-256 of the sources of every ``nps`` module the stage can execute: its
own module, the job adapter, and everything they import from ``nps``, transitively — module-level
and function-level imports alike, found by parsing the sources (nothing is imported). The workflow
gives each rule its stage's digest as a ``code`` param, so editing any module a rule runs reruns
that rule's jobs, and editing any other module does not. The list cannot go stale: it is derived
from the code itself on every Snakemake start.
"""

from __future__ import annotations

import ast
import hashlib
from functools import lru_cache
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parents[1]  # the nps package
ALWAYS = ("nps", "nps.stages", "nps.stages.job")  # run by every job


def module_path(module: str) -> Path | None:
    """Source file of an ``nps`` module (``nps.plots`` → nps/plots/__init__.py); None if not one."""
    parts = module.split(".")
    if parts[0] != "nps":
        return None
    base = PACKAGE_DIR.joinpath(*parts[1:])
    for candidate in (base.with_suffix(".py"), base / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


@lru_cache(maxsize=None)
def direct_imports(module: str) -> frozenset[str]:
    """``nps`` modules imported anywhere in ``module``'s source, with their parent packages."""
    path = module_path(module)
    if path is None:
        return frozenset()
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            names = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package.split(".")[: len(package.split(".")) - node.level + 1] + ([base] if base else []))
            # ``from nps import wake`` imports the module nps.wake.prescribed; ``from nps.app.io import read_table`` the module nps.app.io
            names = [base] + [f"{base}.{alias.name}" for alias in node.names]
        else:
            continue
        for name in names:
            parts = name.split(".")
            for k in range(1, len(parts) + 1):
                prefix = ".".join(parts[:k])
                if module_path(prefix) is not None:
                    found.add(prefix)
    found.discard(module)
    return frozenset(found)


def closure(modules) -> list[str]:
    """Every ``nps`` module reachable from ``modules`` through imports, sorted."""
    seen: set[str] = set()
    todo = [m for m in modules if module_path(m) is not None]
    while todo:
        module = todo.pop()
        if module not in seen:
            seen.add(module)
            todo.extend(direct_imports(module) - seen)
    return sorted(seen)


def stage_modules(stage: str) -> list[str]:
    """The ``nps`` modules a job of ``stage`` can run."""
    from nps.stages import stage_module

    return closure([stage_module(stage), *ALWAYS])


def stage_digest(stage: str) -> str:
    """SHA-256 (16 hex digits) of the sources of :func:`stage_modules`."""
    digest = hashlib.sha256()
    for module in stage_modules(stage):
        path = module_path(module)
        digest.update(module.encode() + b"\0" + path.read_bytes())
    return digest.hexdigest()[:16]
