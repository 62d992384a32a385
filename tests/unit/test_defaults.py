"""Defaults live in one place, the configuration schemas (nps/app/schemas/).

The loaders fill every schema default (nps.app.config.fill_defaults), so stages, rules and commands
read ``cfg["key"]``: a ``.get("<schema field>", <literal>)`` in them, an argparse option whose default
is a literal, or an option default that differs from its schema field's is a second source and fails here.
"""

import ast
import importlib
import pkgutil
import re
from pathlib import Path

import pytest

import nps.cli
from nps.app.config import fill_defaults, load_campaign, load_schema, read_yaml, resolve_ref, rig_schema

REPO = Path(__file__).resolve().parents[2]
SCANNED = sorted([*REPO.glob("nps/stages/*.py"), *REPO.glob("nps/cli/*.py"), *REPO.glob("nps/wake/*.py"),
                  *REPO.glob("workflow/rules/*.smk"), REPO / "Snakefile"])
CLI_MODULES = sorted(m.name for m in pkgutil.iter_modules(nps.cli.__path__))
# a command with subcommands (``nps wopwop run | export | read``) is checked per subcommand: "module subcommand"
CLI_COMMANDS = sorted(f"{m} {sub}" if sub else m for m in CLI_MODULES
                      for sub in (getattr(importlib.import_module(f"nps.cli.{m}"), "COMMANDS", None) or [None]))
CLI_FILES = sorted(REPO.glob("nps/cli/*.py"))


def _fields(node: dict, root: dict, prefix: str = "") -> dict[str, dict]:
    """Dotted field → schema node of every named property of a schema (``$ref`` and ``$defs`` followed,
    array items and ``additionalProperties`` values under the parent's name)."""
    node = resolve_ref(node, root)
    out = {}
    for key, sub in node.get("properties", {}).items():
        out[f"{prefix}{key}"] = sub
        out.update(_fields(sub, root, f"{prefix}{key}."))
    for child in (node.get("items"), node.get("additionalProperties")):
        if isinstance(child, dict):
            out.update(_fields(child, root, prefix))
    return out


SCHEMAS = {**{name: load_schema(name) for name in ("config", "aircraft", "mission")}, "rig": rig_schema()}
FIELDS = {name: _fields(schema, schema) for name, schema in SCHEMAS.items()}
for _name, _schema in SCHEMAS.items():
    for _field, _node in list(FIELDS[_name].items()):
        FIELDS[_name][_field] = resolve_ref(_node, _schema)
# leaf name of every field that declares a default (e.g. "tip_loss", "step_deg", "model")
DEFAULTED_NAMES = {field.rsplit(".", 1)[-1] for fields in FIELDS.values() for field, node in fields.items() if "default" in node}


def _get_with_default(text: str) -> list[tuple[int, str]]:
    """(line, field) of every ``.get("<field>", <anything>)``: a lookup with a default of its own."""
    return [(text.count("\n", 0, m.start()) + 1, m.group(1))
            for m in re.finditer(r"\.get\(\s*[\"'](\w+)[\"']\s*,", text)]


@pytest.mark.parametrize("path", SCANNED, ids=lambda p: str(p.relative_to(REPO)))
def test_no_stage_rule_or_command_carries_a_default_of_a_schema_field(path):
    """(a) The configuration arrives filled: ``.get("tip_loss", True)`` on it duplicates the schema."""
    found = [f"{path.relative_to(REPO)}:{line}: .get({field!r}, ...)" for line, field in _get_with_default(path.read_text())
             if field in DEFAULTED_NAMES]
    assert not found, found


def test_the_scan_finds_a_literal_default():
    """The pattern of the scan catches the forms it must (a test of the test)."""
    text = 'x = rotor.get("tip_loss", True)\ny = cfg["wake"].get(\n    "vortex_structure", "betz")\nz = d.get("segment")\n'
    assert [f for _, f in _get_with_default(text)] == ["tip_loss", "vortex_structure"]
    assert {"tip_loss", "vortex_structure", "step_deg", "moving", "hinge_offset_m"} <= DEFAULTED_NAMES


def _literal(node: ast.AST) -> bool:
    """A literal default: a constant other than None, a container display or a signed number."""
    if isinstance(node, ast.Constant):
        return node.value is not None
    if isinstance(node, ast.UnaryOp):
        return _literal(node.operand)
    return isinstance(node, (ast.List, ast.Tuple, ast.Dict, ast.Set))


@pytest.mark.parametrize("path", CLI_FILES, ids=lambda p: p.name)
def test_no_command_option_has_a_literal_default(path):
    """(b) Option defaults come from the schema (``option(ap, flag, field)`` or ``default(field)``)."""
    found = [f"{path.name}:{call.lineno}" for call in ast.walk(ast.parse(path.read_text()))
             if isinstance(call, ast.Call) and getattr(call.func, "attr", "") == "add_argument"
             for kw in call.keywords if kw.arg == "default" and _literal(kw.value)]
    assert not found, found


class _Parsed(Exception):
    def __init__(self, parser):
        self.parser = parser


def _parser_of(command: str, monkeypatch):
    """The argument parser ``python -m nps <command>`` builds (caught at its parse_args); ``command``: a module, or
    "module subcommand"."""
    def capture(self, args=None, namespace=None):
        raise _Parsed(self)

    module, *sub = command.split()
    monkeypatch.setattr(nps.cli._Parser, "parse_args", capture)
    with pytest.raises(_Parsed) as caught:
        importlib.import_module(f"nps.cli.{module}").main(sub)
    return caught.value.parser


def _schema_default(field: str, schema: str = "config"):
    return FIELDS[schema][field].get("default")


@pytest.mark.parametrize("module", CLI_COMMANDS)
def test_every_command_option_of_a_schema_field_defaults_to_the_schema(module, monkeypatch):
    """(b) An option built for a schema field defaults to that field's default (None where the schema
    has none); an option whose name is that of one defaulted config field, too."""
    by_name = {}
    for field, node in FIELDS["config"].items():
        if "default" in node:
            by_name.setdefault(field.rsplit(".", 1)[-1].lower(), []).append(field)
    wrong = []
    for action in _parser_of(module, monkeypatch)._actions:
        field = getattr(action, "schema_field", None)
        if field is None and len(by_name.get(action.dest.lower(), [])) == 1:
            field = by_name[action.dest.lower()][0]
        if field is None:
            continue
        expected = _schema_default(field, getattr(action, "schema_name", "config"))
        if action.const is not None or action.nargs == 0:  # store_true / store_false of a boolean field
            expected = bool(expected)
        if action.default != expected:
            wrong.append(f"{action.option_strings}: default {action.default!r}, schema {field} {expected!r}")
    assert not wrong, wrong


@pytest.mark.parametrize("command", CLI_COMMANDS)
def test_every_command_option_has_a_help_text(command, monkeypatch):
    """``python -m nps <command> --help`` describes every option and argument: a help text that is more than the
    option's own name or its schema field's (the fallback of nps.cli.option when the schema has no description)."""
    import argparse

    bare = []
    for action in _parser_of(command, monkeypatch)._actions:
        names = {action.dest, getattr(action, "schema_field", "").rsplit(".", 1)[-1]}
        text = (action.help or "").strip()
        if text in names | {"", argparse.SUPPRESS}:
            bare.append(f"{action.option_strings or action.dest}: help {action.help!r}")
    assert not bare, bare


def test_the_wake_command_sets_every_wake_option_of_the_workflow(monkeypatch):
    """Every field of the config ``wake`` section (the free wake's included) is an option of ``python -m nps wake``."""
    fields = {getattr(a, "schema_field", None) for a in _parser_of("wake", monkeypatch)._actions}
    wanted = {f for f in FIELDS["config"] if f.startswith("wake.") and f != "wake.free"}
    assert wanted <= fields, sorted(wanted - fields)
    assert {"resolution.wake_revolutions", "resolution.n_psi"} <= fields


def test_ground_options_cover_the_ground_section(monkeypatch):
    """Footprint and certification commands set every ``footprint.ground`` field the workflow passes."""
    wanted = {f for f in FIELDS["config"] if f.startswith("footprint.ground.")}
    for module in ("footprint", "certification"):
        fields = {getattr(a, "schema_field", None) for a in _parser_of(module, monkeypatch)._actions}
        assert wanted <= fields, (module, sorted(wanted - fields))


def _missing_defaults(data, node: dict, root: dict, where: str) -> list[str]:
    """Fields of ``data`` whose schema default is absent, recursively."""
    node = resolve_ref(node, root)
    missing = []
    if isinstance(data, dict):
        extra = node.get("additionalProperties")
        for key, sub in node.get("properties", {}).items():
            if key not in data:
                if "default" in resolve_ref(sub, root):
                    missing.append(f"{where}{key}")
            else:
                missing += _missing_defaults(data[key], sub, root, f"{where}{key}.")
        if isinstance(extra, dict):
            for key in set(data) - set(node.get("properties", {})):
                missing += _missing_defaults(data[key], extra, root, f"{where}{key}.")
    elif isinstance(data, list) and isinstance(node.get("items"), dict):
        for index, item in enumerate(data):
            missing += _missing_defaults(item, node["items"], root, f"{where}[{index}].")
    return missing


def test_the_bundled_campaign_is_loaded_with_every_schema_default():
    """(c) config/config.yaml, its aircraft and mission come back with every default of the schemas;
    the config as written is kept unchanged next to it."""
    written = read_yaml(REPO / "config/config.yaml")
    campaign = load_campaign(written, root=REPO)
    assert not _missing_defaults(campaign.config, SCHEMAS["config"], SCHEMAS["config"], "")
    for name, aircraft in campaign.aircraft.items():
        assert not _missing_defaults(aircraft, SCHEMAS["aircraft"], SCHEMAS["aircraft"], f"{name}: ")
    assert not _missing_defaults(campaign.mission, SCHEMAS["mission"], SCHEMAS["mission"], "")
    assert campaign.written == read_yaml(REPO / "config/config.yaml") == written
    assert campaign.config["wake"]["step_deg"] == 5.0 and campaign.config["wake"]["free"] == {}
    assert "flow_resistivity_kPa_s_m2" not in campaign.as_written("footprint.ground")
    assert campaign.config["footprint"]["ground"]["flow_resistivity_kPa_s_m2"] == 200.0
    assert all(r["tip_loss"] is True and r["hinge_offset_m"] >= 0.0 for r in campaign.aircraft["helicopter"]["rotors"])


def test_fill_defaults_follows_refs_items_and_mappings():
    """Defaults inside ``$ref``'d definitions, array items, ``additionalProperties`` values and a
    ``default: {}`` object are filled; given values and keys without a default are kept as they are."""
    schema = {
        "$defs": {"leaf": {"type": "object", "properties": {"n": {"default": 1}, "m": {}}}},
        "type": "object",
        "properties": {
            "items": {"type": "array", "items": {"$ref": "#/$defs/leaf"}},
            "named": {"type": "object", "additionalProperties": {"$ref": "#/$defs/leaf"}},
            "block": {"type": "object", "default": {}, "properties": {"x": {"default": [0.5]}}},
            "given": {"default": 3},
        },
    }
    data = {"items": [{}, {"n": 2}], "named": {"a": {"m": 5}}, "given": 4}
    filled = fill_defaults(data, schema)
    assert filled == {"items": [{"n": 1}, {"n": 2}], "named": {"a": {"m": 5, "n": 1}}, "given": 4, "block": {"x": [0.5]}}
    assert data == {"items": [{}, {"n": 2}], "named": {"a": {"m": 5}}, "given": 4}  # the input is not changed
    filled["block"]["x"].append(1.0)
    assert fill_defaults({}, schema)["block"] == {"x": [0.5]}  # defaults are copies, never the schema's objects
