"""Structure of the package: no import circles, physics below the application layer, one code path
per stage (workflow, command and tests call the same function), code digests that cannot go stale."""

from __future__ import annotations

import ast
import pytest

from nps.stages import STAGES
from nps.stages.code import PACKAGE_DIR, closure, direct_imports, module_path, stage_digest, stage_modules

MODULES = sorted(
    ".".join(("nps",) + p.relative_to(PACKAGE_DIR).with_suffix("").parts).removesuffix(".__init__")
    for p in PACKAGE_DIR.rglob("*.py")
)
# The layer of each top-level package (docs/reference/architecture.md): a module imports only from its own
# package and from packages of a lower layer; packages of one layer know nothing of each other.
LAYERS = {"core": 0, "rotor": 1, "wake": 2, "noise": 2, "mission": 3, "rig": 3, "app": 4, "wopwop": 4, "plots": 5,
          "stages": 6, "api": 7, "cli": 7, "__main__": 8}
PHYSICS_PACKAGES = ("core", "rotor", "wake", "noise", "mission", "rig")
MAX_FUNCTION_LINES = 80


def _package(module: str) -> str | None:
    """Top-level package of an nps module (``nps.rotor.bet`` → ``rotor``); None for ``nps`` itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else None


def _imports(module: str) -> set[str]:
    """nps modules a module imports, without the parent packages that Python runs on the way."""
    found = {m for m in direct_imports(module) if not module.startswith(m + ".") and m != "nps"}
    return {m for m in found if not any(other.startswith(m + ".") for other in found)}


def _module_level_imports(module: str) -> set[str]:
    """Every top-level name imported anywhere in a module (``import a.b`` → ``a``, ``from a.b import c`` → ``a``)."""
    tree = ast.parse(module_path(module).read_text())
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
    return names


def test_every_package_has_a_layer():
    """A new folder under nps/ must be placed in the layer table before it can hold code."""
    packages = {_package(m) for m in MODULES} - {None}
    assert packages <= set(LAYERS), sorted(packages - set(LAYERS))


@pytest.mark.parametrize("module", [m for m in MODULES if _package(m)])
def test_imports_follow_the_layers(module):
    """Imports go to the module's own package or to a lower layer, never sideways or up."""
    package = _package(module)
    for imported in _imports(module):
        other = _package(imported)
        if other is None or other == package:
            continue
        assert LAYERS[other] < LAYERS[package], f"{module} (layer {LAYERS[package]}) imports {imported} (layer {LAYERS[other]})"


def test_no_import_circles():
    """No nps module reaches itself through the imports (function-level ones included)."""
    graph = {m: _imports(m) for m in MODULES}
    for start in MODULES:
        seen, todo = set(), list(graph[start])
        while todo:
            module = todo.pop()
            assert module != start, f"{start} reaches itself through its imports"
            if module not in seen:
                seen.add(module)
                todo.extend(graph.get(module, ()))


def _private_uses(module: str) -> list[str]:
    """Private names (``_x``) of another nps module that ``module`` imports or reads as an attribute."""
    tree = ast.parse(module_path(module).read_text())
    aliases, found = {}, []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("nps"):
            for alias in node.names:
                target = f"{node.module}.{alias.name}"
                if module_path(target) is not None:
                    aliases[alias.asname or alias.name] = target
                elif alias.name.startswith("_") and not alias.name.startswith("__") and node.module != module:
                    found.append(f"{node.module}.{alias.name}")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.asname and alias.name.startswith("nps"):
                    aliases[alias.asname] = alias.name
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
                and node.attr.startswith("_") and not node.attr.startswith("__")):
            found.append(f"{aliases[node.value.id]}.{node.attr}")
    return found


@pytest.mark.parametrize("module", MODULES)
def test_no_module_uses_another_modules_private_names(module):
    """A module calls only the public names of the others (a shared helper is public where it lives)."""
    assert not _private_uses(module), _private_uses(module)


@pytest.mark.parametrize("package", PHYSICS_PACKAGES)
def test_physics_packages_know_no_application_layer_or_file_io(package):
    """Physics modules reach no stage, command, workflow, plot or Parquet I/O, through any import."""
    for module in (m for m in MODULES if _package(m) == package):
        reached = closure([module])
        forbidden = [m for m in reached if _package(m) in ("app", "api", "stages", "cli", "plots")]
        assert not forbidden, (module, forbidden)
        assert not any(n.startswith("pyarrow") for n in _module_level_imports(module)), module


def test_solver_knows_no_rotor():
    """The compact-F1A solver imports nothing of NPS but the jit helper: rotor → sources adapters sit above it."""
    assert _imports("nps.noise.acoustics") <= {"nps.core.jit"}


def test_every_kernel_goes_through_the_jit_helper():
    """numba is imported only by nps.core.jit: every compiled kernel gets the project's options from ``kernel()``."""
    for module in MODULES:
        if module != "nps.core.jit":
            assert not any(n == "numba" or n.startswith("numba.") for n in _module_level_imports(module)), module


def test_no_function_is_longer_than_the_limit():
    """Functions (methods and nested functions included) stay readable: at most MAX_FUNCTION_LINES lines each."""
    long = []
    for module in MODULES:
        for node in ast.walk(ast.parse(module_path(module).read_text())):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                length = node.end_lineno - node.lineno + 1
                if length > MAX_FUNCTION_LINES:
                    long.append(f"{module}.{node.name}: {length}")
    assert not long, long


@pytest.fixture
def package_copy(tmp_path, monkeypatch):
    """A copy of the nps sources that the digests read instead of the real package."""
    import shutil

    import nps.stages.code as code

    copy = tmp_path / "nps"
    shutil.copytree(PACKAGE_DIR, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(code, "PACKAGE_DIR", copy)
    code.direct_imports.cache_clear()
    yield copy
    code.direct_imports.cache_clear()


@pytest.mark.parametrize("stage", ["trim", "metrics", "rotor_figures", "wake"])
def test_code_digest_follows_every_module_a_stage_runs(package_copy, stage):
    """Touching any module of a stage's closure changes its digest; touching a module outside it does not."""
    import nps.stages.code as code

    before = stage_digest(stage)
    modules = stage_modules(stage)
    for module in modules:
        path = code.module_path(module)
        original = path.read_bytes()
        path.write_bytes(original + b"\n# touched\n")
        assert stage_digest(stage) != before, (stage, module)
        path.write_bytes(original)
    for module in [m for m in MODULES if m not in modules]:
        path = code.module_path(module)
        path.write_bytes(path.read_bytes() + b"\n# touched\n")
    assert stage_digest(stage) == before, stage


def test_figure_stages_depend_on_the_plots_package():
    """Editing nps/plots/__init__.py (save_figure, dpi) reruns every figure job; trim does not depend on it."""
    for stage in ("rotor_figures", "hsi_figure", "study_maps", "rotor_maps", "bvi_hotspot", "metrics"):
        assert "nps.plots" in stage_modules(stage), stage
    assert "nps.plots" not in stage_modules("trim")


@pytest.mark.parametrize("stage", STAGES)
def test_every_stage_has_a_command_and_a_run_function(stage):
    """Rule name = stage name = command name (``radiate`` is a command without a rule)."""
    from nps.__main__ import stages as commands
    from nps.stages import stage_function

    assert callable(stage_function(stage))
    command = "wopwop" if stage.startswith("wopwop_") else stage  # nps wopwop run | export
    figure_or_study = {"rotor_figures", "hsi_figure", "study_maps", "rotor_maps", "bvi_hotspot", "summary", "results_summary", "carpet",
                       "trade"}
    assert command in commands() or stage in figure_or_study
