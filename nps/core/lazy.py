"""Package faces imported on first use: a job imports only the modules its stage runs.

A package ``__init__`` names its public names and the modules holding them (:func:`lazy_face`), so that
``import nps.rotor.trim`` runs ``nps/rotor/__init__.py`` without importing every other module of the package
(and numba, scipy, ... with them); ``nps.rotor.DiskGrid`` still works, importing ``nps.rotor.bet`` when first
read, and so does a submodule read as an attribute (``nps.wake.free``). The ``__init__`` also keeps the same
imports under ``if TYPE_CHECKING:``, which Python never runs: readers, type checkers and the code digests
(nps.stages.code, which parse the imports) see the face as before.
"""

from __future__ import annotations

import importlib
import importlib.util
from typing import Callable


def lazy_face(package: str, exports: dict[str, tuple[str, ...]]) -> tuple[Callable, Callable, list[str]]:
    """``(__getattr__, __dir__, __all__)`` of ``package`` whose names ``exports`` (module → names) are imported
    from their modules on first use (then kept in the package's namespace)."""
    where = {name: module for module, names in exports.items() for name in names}

    def __getattr__(name: str):
        namespace = vars(importlib.import_module(package))
        if name in where:
            value = getattr(importlib.import_module(where[name]), name)
        elif not name.startswith("__") and importlib.util.find_spec(f"{package}.{name}") is not None:
            value = importlib.import_module(f"{package}.{name}")
        else:
            raise AttributeError(f"module '{package}' has no attribute '{name}'")
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted({*vars(importlib.import_module(package)), *where})

    return __getattr__, __dir__, list(where)
