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
PHYSICS = ("acoustics", "atmosphere", "bet", "broadband", "bvi", "frames", "hsi", "hsi_kernels", "metrics", "observers",
           "rotor", "sources", "signals", "spectra", "tones", "trim", "wake", "jit", "airfoils", "blade", "control",
           "propagation", "trajectory", "certification", "footprint", "source_hemisphere", "rotor_test")


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


def test_no_import_circles():
    """No nps module reaches itself through the imports (function-level ones included)."""
    for module in MODULES:
        assert module not in closure(direct_imports(module) - {m for m in ("nps",)}) or module == "nps", module


def test_physics_modules_do_not_import_the_application_layer_or_file_io():
    """Physics modules know no stage, command, workflow, plot or Parquet I/O."""
    for name in PHYSICS:
        module = f"nps.{name}"
        reached = closure([module])
        forbidden = [m for m in reached if m.startswith(("nps.stages", "nps.cli", "nps.plots")) or m == "nps.io"]
        assert not forbidden, (module, forbidden)
        assert not any(n.startswith("pyarrow") for n in _module_level_imports(module)), module


def test_solver_knows_no_rotor():
    """The compact-F1A solver imports nothing of NPS: rotor → sources adapters sit above it."""
    assert direct_imports("nps.acoustics") <= {"nps", "nps.jit"}


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
    figure_or_study = {"rotor_figures", "hsi_figure", "study_maps", "rotor_maps", "bvi_hotspot", "summary", "carpet"}
    assert stage in commands() or stage in figure_or_study
