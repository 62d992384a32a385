"""Configuration files: loading, JSON-schema validation and cross-reference checks.

Schemas live in ``nps/app/schemas/`` (config, aircraft, mission) with the defaults of optional fields, the one
source of defaults: the loaders return the files with every default filled (:func:`fill_defaults`). Every problem is reported
before any computation as a :class:`ConfigError` whose lines read
``<file>: <field path>: <what was expected>``.
"""

from __future__ import annotations

import copy
import difflib
import functools
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Iterable, Iterator, Mapping, Sequence

import jsonschema
import yaml

from nps.app.broadband import broadband_model
from nps.rotor.airfoils import AirfoilError
from nps.rotor.blade import BladeError
from nps.rotor.geometry import RotorGeometry, without_rotor_label

SCHEMA_DIR = Path(__file__).resolve().parent / "schemas"


class ConfigError(ValueError):
    """A configuration file is invalid; the message names file, field and expectation."""


def _field_path(parts) -> str:
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else (f".{part}" if text else str(part))
    return text or "<top level>"


# name patterns of the schemas, in words: names become file names and workflow wildcards
PATTERN_WORDS = {
    "^[a-z][a-z0-9_]*$": "a lower-case letter followed by lower-case letters, digits or '_' (the name becomes "
                         "part of file names and of the workflow's wildcards)",
    "^seg[0-9]+$": "'seg' followed by digits, e.g. seg3 (the id becomes a directory name and a workflow wildcard)",
}


def _describe(error: jsonschema.ValidationError) -> tuple[str, str]:
    """(field path, expectation) for one schema error, in plain words."""
    path = list(error.absolute_path)
    kind = error.validator
    value = error.validator_value
    if "propertyNames" in error.absolute_schema_path:  # a key of the mapping at ``path`` is refused
        if kind == "enum":
            return _field_path(path + [error.instance]), _unknown_key(error.instance, value)
        if kind == "pattern":
            return _field_path(path + [error.instance]), f"expected a name made of {PATTERN_WORDS.get(value, repr(value))}"
    if kind == "additionalProperties":
        allowed = sorted(error.schema.get("properties", {}))
        extra = sorted(set(error.instance) - set(allowed))
        return _field_path(path + [extra[0]] if extra else path), _unknown_key(extra[0] if extra else "", allowed)
    if kind == "required":
        missing = [name for name in value if name not in error.instance]
        return _field_path(path + missing[:1]), "required field is missing"
    if kind == "type":
        return _field_path(path), f"expected {value}, got {type(error.instance).__name__} {error.instance!r}"
    if kind in ("exclusiveMinimum", "minimum", "exclusiveMaximum", "maximum"):
        words = {"exclusiveMinimum": "> ", "minimum": ">= ", "exclusiveMaximum": "< ", "maximum": "<= "}[kind]
        return _field_path(path), f"expected a number {words}{value}, got {error.instance!r}"
    if kind == "enum":
        return _field_path(path), f"expected one of {value}, got {error.instance!r}"
    if kind == "pattern":
        return _field_path(path), f"expected {PATTERN_WORDS.get(value, f'text matching {value!r}')}, got {error.instance!r}"
    if kind in ("minItems", "maxItems"):
        return _field_path(path), f"expected a list with {kind[:3]}imum {value} item(s), got {len(error.instance)}"
    return _field_path(path), error.message


def _unknown_key(key: str, allowed) -> str:
    """Expectation text for an unknown key, with the closest allowed key when it looks like a typo."""
    close = difflib.get_close_matches(str(key), [str(a) for a in allowed], n=1, cutoff=0.75)
    hint = f"did you mean '{close[0]}'? " if close else "typo? "
    return f"unknown key ({hint}allowed keys here: {', '.join(allowed)})"


def _schema_problems(validator: jsonschema.protocols.Validator, data: Any) -> list[tuple[str, str]]:
    """(field, expectation) of every schema error; a required key missing because of a typo is named
    once, by the unknown key that suggests it (``n_azimut``: did you mean 'n_azimuth'?)."""
    problems = [_describe(error) for error in validator.iter_errors(data)]
    typos = set()
    for field, what in problems:
        if what.startswith("unknown key (did you mean '"):
            parent = field.rsplit(".", 1)[0] if "." in field else ""
            suggestion = what.split("'")[1]
            typos.add(f"{parent}.{suggestion}" if parent else suggestion)
    return [(field, what) for field, what in problems if not (what == "required field is missing" and field in typos)]


def _non_finite(node: Any, path: list) -> Iterator[tuple[str, str]]:
    if isinstance(node, float) and not math.isfinite(node):
        yield _field_path(path), f"expected a finite number, got {node!r}"
    elif isinstance(node, dict):
        for key, value in node.items():
            yield from _non_finite(value, path + [key])
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from _non_finite(value, path + [index])


def raise_problems(problems: Iterable[tuple[str | Path, str, str]]) -> None:
    """Raise :class:`ConfigError` with one line per (file, field, expectation), if there is any."""
    lines = [f"{file}: {field}: {what}" for file, field, what in sorted({(str(f), a, b) for f, a, b in problems})]
    if lines:
        raise ConfigError(lines[0] if len(lines) == 1 else f"{len(lines)} problems:\n  " + "\n  ".join(lines))


def _raise(file: str | Path, problems: list[tuple[str, str]]) -> None:
    raise_problems((file, field, what) for field, what in problems)


@functools.lru_cache(maxsize=None)
def load_schema(name: str) -> dict:
    """The schema ``nps/app/schemas/<name>.schema.yaml`` (parsed once per process; callers must not modify it)."""
    with open(SCHEMA_DIR / f"{name}.schema.yaml") as handle:
        return yaml.safe_load(handle)


def schema_default(schema_name: str, field: str) -> Any:
    """The ``default`` the schema declares for a dotted field path, e.g. ``("config", "resolution.n_psi")``.

    The one source of defaults: :func:`fill_defaults` fills validated files with them, the command-line
    options take theirs from here.
    """
    node = load_schema(schema_name)
    for part in field.split("."):
        node = node["properties"][part]
    if "default" not in node:
        raise KeyError(f"{schema_name} schema: field '{field}' declares no default")
    return node["default"]


def resolve_ref(node: dict, root: dict) -> dict:
    """``node`` with a local ``$ref`` (``#/$defs/...``) replaced by its target (one schema file)."""
    while "$ref" in node:
        target = root
        for part in node["$ref"].lstrip("#/").split("/"):
            target = target[part]
        node = target
    return node


def fill_defaults(data: Any, schema: dict, root: dict | None = None) -> Any:
    """A copy of schema-valid ``data`` with every ``default`` of the schema filled in where the key is
    absent, recursively: object properties (a filled ``default: {}`` object gets its own defaults),
    named and ``additionalProperties`` values, array items, local ``$ref``s into ``$defs``.

    The one place defaults are applied: the loaders below return filled configurations, so stages,
    rules and commands read ``cfg["key"]`` and carry no default of their own.
    """
    root = schema if root is None else root
    node = resolve_ref(schema, root)
    if isinstance(data, dict):
        out = {}
        named = node.get("properties", {})
        extra = node.get("additionalProperties")
        for key, value in data.items():
            sub = named.get(key, extra if isinstance(extra, dict) else None)
            out[key] = fill_defaults(value, sub, root) if sub is not None else copy.deepcopy(value)
        for key, sub in named.items():
            sub = resolve_ref(sub, root)
            if key not in out and "default" in sub:
                out[key] = fill_defaults(copy.deepcopy(sub["default"]), sub, root)
        return out
    if isinstance(data, list) and isinstance(node.get("items"), dict):
        return [fill_defaults(item, node["items"], root) for item in data]
    return copy.deepcopy(data)


def _sections(node: dict, root: dict) -> dict:
    """Every object with named fields of a schema node, nested and empty (what :func:`fill_defaults` fills)."""
    node = resolve_ref(node, root)
    return {key: _sections(sub, root) for key, sub in node.get("properties", {}).items()
            if "properties" in resolve_ref(sub, root)}


def schema_defaults(schema_name: str) -> dict:
    """Every default a schema declares, in its place (:func:`fill_defaults` of every section and sub-section present
    and empty); a field without a default is absent. For ``config``: what the per-stage commands plan their jobs
    from, their options written in (nps.cli.settings)."""
    schema = load_schema(schema_name)
    return fill_defaults(_sections(schema, schema), schema)


def field_problem(schema_name: str, field: str, value: Any) -> str | None:
    """What is wrong with ``value`` for the dotted schema field (e.g. ``atmosphere.isa_delta_K``), or None."""
    node = load_schema(schema_name)
    for part in field.split("."):
        node = node["properties"][part]
    return value_problem(node, value, field)


def schema_node(schema_name: str, parts: Sequence[str | int]) -> dict | None:
    """The schema of one field of a document: ``parts`` are keys (a property, else the additional properties)
    and list indices (the items), local ``$ref`` resolved; None where the schema does not describe it."""
    root = load_schema(schema_name)
    node = root
    for part in parts:
        node = resolve_ref(node, root)
        node = node.get("items") if isinstance(part, int) else node.get("properties", {}).get(part, node.get("additionalProperties"))
        if not isinstance(node, dict):
            return None
    return {**resolve_ref(node, root), "$defs": root.get("$defs", {})}


def value_problem(node: dict, value: Any, field: str = "") -> str | None:
    """What is wrong with ``value`` for the schema ``node`` of a field (:func:`schema_node`), or None."""
    problems = [what for _, what in _non_finite(value, [])]
    problems += [what for _, what in _schema_problems(jsonschema.Draft202012Validator(node), value)]
    return problems[0] if problems else ordering_problem(field, value)


# two-element fields whose elements the code needs strictly increasing (not expressible in the schema)
ORDERED_PAIRS = {
    "acoustics.bvispl_harmonics": "[first, last] harmonics with first < last",
    "acoustics.dual_compact_chord_fractions": "[front, rear] with front < rear (two distinct source lines)",
}


def ordering_problem(field: str, value: Any) -> str | None:
    """The ordering a field of :data:`ORDERED_PAIRS` needs, when ``value`` (schema-valid) violates it."""
    if field in ORDERED_PAIRS and not value[0] < value[1]:
        return f"expected {ORDERED_PAIRS[field]}, got {list(value)}"
    return None


def validate(data: Any, schema_name: str | dict, file: str | Path) -> dict:
    """Validate ``data`` against a schema (a name under ``nps/app/schemas/`` or the schema itself);
    raise :class:`ConfigError` listing every problem."""
    _raise(file, schema_problems(data, schema_name))
    return data


def schema_problems(data: Any, schema_name: str | dict) -> list[tuple[str, str]]:
    """(field, expectation) of every way ``data`` breaks a schema (a name under ``nps/app/schemas/`` or the schema)."""
    if not isinstance(data, dict):
        return [("<top level>", f"expected a mapping, got {type(data).__name__}")]
    validator = jsonschema.Draft202012Validator(load_schema(schema_name) if isinstance(schema_name, str) else schema_name)
    return list(_non_finite(data, [])) + _schema_problems(validator, data)


class _UniqueKeyLoader(yaml.SafeLoader):
    """YAML's safe loader refusing a mapping that names one key twice (PyYAML keeps the last silently)."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            first: dict = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue
                key = self.construct_object(key_node, deep=True)
                if key in first:
                    raise yaml.constructor.ConstructorError(
                        None, None, f"duplicate key {key!r} (first at line {first[key].line + 1}); keep one",
                        key_node.start_mark)
                first[key] = key_node.start_mark
        return super().construct_mapping(node, deep=deep)


def read_yaml(path: str | Path) -> Any:
    """Parse a YAML file; a syntax error or a key given twice in one mapping becomes a
    :class:`ConfigError` naming the file, line and column."""
    path = Path(path)
    if not path.exists():
        raise ConfigError(f"{path}: file not found")
    try:
        with open(path) as handle:
            return yaml.load(handle, Loader=_UniqueKeyLoader)
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path}: {yaml_error_text(exc)}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot be read ({exc.__class__.__name__}: {exc})") from None


def yaml_error_text(exc: yaml.YAMLError) -> str:
    """One line for a YAML syntax error: ``line L, column C: not valid YAML: <problem> (<context>)``."""
    mark = getattr(exc, "problem_mark", None)
    where = f"line {mark.line + 1}, column {mark.column + 1}: " if mark is not None else ""
    problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
    context = getattr(exc, "context", None)
    return f"{where}not valid YAML: {problem}" + (f" ({context})" if context else "")


def load_aircraft(path: str | Path, document: Any = None) -> dict:
    """Read and validate one aircraft file, with its own cross checks; schema defaults filled. ``document``:
    the file's content as read (e.g. a design-study variant of it), validated as if read from ``path``."""
    from nps.rotor.control import default_mode

    document = read_yaml(path) if document is None else copy.deepcopy(document)
    rotors = document.get("rotors") if isinstance(document, dict) else None
    given = [isinstance(r, dict) and "control" in r for r in rotors] if isinstance(rotors, list) else []
    data = fill_defaults(validate(document, "aircraft", path), load_schema("aircraft"))
    problems = []
    names = [rotor["name"] for rotor in data["rotors"]]
    for index, rotor in enumerate(data["rotors"]):
        if not given[index]:  # the schema's default, collective, unless the rotor is a teetering tail rotor
            rotor["control"] = default_mode(rotor)
        where = f"rotors[{index}]"
        if names.count(rotor["name"]) > 1:
            problems.append((f"{where}.name", f"expected a unique rotor name, '{rotor['name']}' repeats"))
        if rotor["root_cutout_m"] >= rotor["radius_m"]:
            problems.append((f"{where}.root_cutout_m", f"expected < radius_m ({rotor['radius_m']}), got {rotor['root_cutout_m']}"))
        if rotor["hinge_offset_m"] >= rotor["radius_m"]:
            problems.append((f"{where}.hinge_offset_m", f"expected < radius_m ({rotor['radius_m']})"))
        lift_axis = rotor["thrust_axis_body"]  # a zero axis: _rotor_sections
        if rotor["role"] == "lift" and lift_axis[2] <= 0.0 and math.hypot(*lift_axis) >= AXIS_MIN_LENGTH:
            problems.append((f"{where}.thrust_axis_body", "expected a lift rotor's thrust axis pointing up (z > 0 in the body "
                                                          f"frame: x forward, y port, z up), got {rotor['thrust_axis_body']}"))
        problems += _rotor_sections(rotor, where, Path(path).parent)
    if not problems:  # the rotors' geometry (blade tables resolved) is readable
        problems += solidity_problems(data["rotors"]) or _hub_problems(data["rotors"])
    if not problems:
        problems += disk_crossing_problems(data["rotors"])
    if not problems and "airframe_points_m" in data:
        problems += airframe_clearance_problems(data["rotors"], data["airframe_points_m"])
    if not any(rotor["role"] == "lift" for rotor in data["rotors"]):
        problems.append(("rotors", "expected at least one rotor with role 'lift'"))
    if sum(rotor["role"] == "antitorque" for rotor in data["rotors"]) > 1:
        problems.append(("rotors", "expected at most one rotor with role 'antitorque'"))
    if Path(path).stem != data["name"]:
        problems.append(("name", f"expected the file stem '{Path(path).stem}', got '{data['name']}'"))
    _raise(path, problems)
    return data


def _hub_problems(rotors: list[dict]) -> list[tuple[str, str]]:
    """Rotors whose hub lies inside the disk another rotor's blades sweep: in that rotor's hub plane
    (within one of its chords along its thrust axis) and inside its radius."""
    from nps.rotor.geometry import RotorGeometry  # reference chord of linear blades and blade tables alike

    chords = [RotorGeometry.from_config(rotor).chord_m for rotor in rotors]
    problems, pairs = [], set()
    for i, other in enumerate(rotors):
        axis = [c / math.hypot(*other["thrust_axis_body"]) for c in other["thrust_axis_body"]] \
            if math.hypot(*other["thrust_axis_body"]) > 1e-9 else [0.0, 0.0, 1.0]
        for j, rotor in enumerate(rotors):
            if i == j or frozenset((i, j)) in pairs:
                continue
            d = [a - b for a, b in zip(rotor["hub_position_m"], other["hub_position_m"])]
            axial = sum(a * b for a, b in zip(d, axis))
            in_plane = math.sqrt(max(0.0, sum(a * a for a in d) - axial * axial))
            if abs(axial) < chords[i] and in_plane < other["radius_m"]:
                pairs.add(frozenset((i, j)))
                problems.append((f"rotors[{j}].hub_position_m", (
                    f"hub {rotor['hub_position_m']} lies inside the disk swept by rotor '{other['name']}' "
                    f"({in_plane:.3g} m from its hub in its plane, radius {other['radius_m']} m; {abs(axial):.3g} m along its axis, "
                    f"chord {chords[i]:.3g} m): expected the hub outside the other rotors' blade paths")))
    return problems


SOLIDITY_MAX = 0.5  # blade spacing 2π(0.75 R)/N of at least 3 chords: isolated blade sections (no cascade)
FLAP_MARGIN_RAD = math.radians(15.0)  # nps.app.validity.FLAP_ANGLE_MAX_RAD: the largest flap angle accepted


def solidity_problems(rotors: list[dict], prefix: str = "rotors") -> list[tuple[str, str]]:
    """Rotors whose solidity N c/(π R) exceeds :data:`SOLIDITY_MAX`: blades closer than 3 chords at 75 %
    radius are a cascade, not the isolated sections of blade element theory (a blade count or chord typo);
    the message names that rotor (not the rotor whose trim would fail later)."""
    from nps.rotor.geometry import RotorGeometry

    problems = []
    for index, rotor in enumerate(rotors):
        geometry = RotorGeometry.from_config(rotor)
        if geometry.solidity > SOLIDITY_MAX:
            problems.append((f"{prefix}[{index}]", (
                f"rotor '{rotor['name']}': {geometry.n_blades} blades of chord {geometry.chord_m:.4g} m on radius "
                f"{geometry.radius_m:.4g} m give solidity N c/(pi R) = {geometry.solidity:.3g}: expected <= {SOLIDITY_MAX:g} "
                f"(blades at least 3 chords apart at 75 % radius); check n_blades and chord_m")))
    return problems


def _disk_frame(rotor: dict):
    """(hub (3,), unit thrust axis (3,)) of a rotor in the body frame."""
    import numpy as np

    axis = np.asarray(rotor["thrust_axis_body"], dtype=float)
    return np.asarray(rotor["hub_position_m"], dtype=float), axis / np.linalg.norm(axis)


def _swept_points(rotor: dict, n_azimuth: int = 72, n_radius: int = 8):
    """Points (n, 3, body frame) of the volume a rotor's blades sweep: the disk up to the tip, each radius r
    displaced by ± r sin(FLAP_MARGIN_RAD) along the axis (the largest flapping accepted)."""
    import numpy as np

    hub, axis = _disk_frame(rotor)
    e1 = np.cross(axis, [0.0, 1.0, 0.0] if abs(axis[1]) < 0.9 else [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(axis, e1)
    psi = np.linspace(0.0, 2.0 * np.pi, n_azimuth, endpoint=False)
    r = np.linspace(0.0, float(rotor["radius_m"]), n_radius + 1)[1:]
    rr, pp = np.meshgrid(r, psi, indexing="ij")
    base = hub + rr.reshape(-1, 1) * (np.cos(pp).reshape(-1, 1) * e1 + np.sin(pp).reshape(-1, 1) * e2)
    lift = (rr.reshape(-1, 1) * math.sin(FLAP_MARGIN_RAD)) * axis
    return np.concatenate([base - lift, base, base + lift])


def disk_crossing_problems(rotors: list[dict]) -> list[tuple[str, str]]:
    """Rotors other than lift rotors (a tail rotor) whose swept volume (:func:`_swept_points`, flapping margin
    included) enters another rotor's: within its radius and within r sin(15°) + c/2 of its plane at radius r.
    The rotor blamed is the non-lift one (it is placed relative to the lift rotors). Pairs of lift rotors
    (tandem overlap, coaxial stacks) are designed with phased or stacked blade paths and keep the hub check."""
    import numpy as np

    from nps.rotor.geometry import RotorGeometry

    problems = []
    for j, rotor in enumerate(rotors):
        if rotor["role"] == "lift":
            continue
        points = _swept_points(rotor)
        for other in rotors:
            if other is rotor:
                continue
            hub, axis = _disk_frame(other)
            rel = points - hub
            axial = rel @ axis
            radial = np.linalg.norm(rel - np.outer(axial, axis), axis=1)
            margin = radial * math.sin(FLAP_MARGIN_RAD) + RotorGeometry.from_config(other).chord_m / 2.0
            inside = (radial <= other["radius_m"]) & (np.abs(axial) <= margin)
            if inside.any():
                k = int(np.argmax(inside))
                problems.append((f"rotors[{j}]", (
                    f"the disk rotor '{rotor['name']}' sweeps (radius_m {rotor['radius_m']}, hub_position_m "
                    f"{rotor['hub_position_m']}, flapping margin ±15°) crosses the blade path of rotor '{other['name']}': "
                    f"a point {radial[k]:.3g} m from its axis (radius {other['radius_m']} m), {axial[k]:.3g} m from its "
                    f"plane (margin {margin[k]:.3g} m); expected the disks apart: check rotor '{rotor['name']}' "
                    f"radius_m (a radius in feet?) and hub_position_m")))
    return problems


def airframe_clearance_problems(rotors: list[dict], points: list) -> list[tuple[str, str]]:
    """Airframe points (``airframe_points_m``, body frame) inside the volume a rotor's blades sweep: between its
    root cutout and its radius from its axis, and within r sin(15°) + c/2 (the flapping margin of
    :func:`disk_crossing_problems`) or one chord c of its plane. One problem per point, naming the first rotor."""
    import numpy as np

    from nps.rotor.geometry import RotorGeometry

    problems = []
    for i, point in enumerate(points):
        for rotor in rotors:
            hub, axis = _disk_frame(rotor)
            rel = np.asarray(point, dtype=float) - hub
            axial = float(rel @ axis)
            radial = float(np.linalg.norm(rel - axial * axis))
            chord = RotorGeometry.from_config(rotor).chord_m
            margin = max(radial * math.sin(FLAP_MARGIN_RAD) + chord / 2.0, chord)
            if rotor["root_cutout_m"] <= radial <= rotor["radius_m"] and abs(axial) <= margin:
                problems.append((f"airframe_points_m[{i}]", (
                    f"point {[float(c) for c in point]} lies inside the volume rotor '{rotor['name']}' sweeps: {radial:.3g} m from its "
                    f"axis (blades from {rotor['root_cutout_m']} to {rotor['radius_m']} m), {abs(axial):.3g} m from its plane "
                    f"(margin {margin:.3g} m: ±15° flapping + c/2, at least one chord {chord:.3g} m); expected the airframe "
                    f"clear of the blade paths: check the point and rotor '{rotor['name']}' hub_position_m, radius_m")))
                break
    return problems


def campaign_value_problems(config: dict) -> list[tuple[str, str]]:
    """Ordering constraints of the campaign config the code relies on (not expressible in the schema)."""
    problems = []
    for field in ORDERED_PAIRS:
        section, key = field.split(".")
        problem = ordering_problem(field, config[section][key])
        if problem:
            problems.append((field, problem))
    return problems + observer_set_problems(config["observer_sets"])


def observer_set_problems(sets: dict) -> list[tuple[str, str]]:
    """Ordering constraints of schema-valid ``observer_sets`` (ground-grid ranges increasing)."""
    problems = []
    for name, spec in sets.items():
        for key in ("x_range_m", "y_range_m"):
            if isinstance(spec, dict) and key in spec and not spec[key][0] < spec[key][1]:
                problems.append((f"observer_sets.{name}.{key}", f"expected [low, high] with low < high, got {spec[key]}"))
    return problems


def load_observer_sets(path: str | Path) -> dict:
    """The validated ``observer_sets`` of a campaign config file, defaults filled (for ``python -m nps observers``)."""
    data = read_yaml(path)
    if not isinstance(data, dict) or "observer_sets" not in data:
        raise ConfigError(f"{path}: observer_sets: required field is missing (an observer-set mapping)")
    node = load_schema("config")["properties"]["observer_sets"]
    schema = {"type": "object", "properties": {"observer_sets": node}}
    sets = {"observer_sets": data["observer_sets"]}
    problems = list(_non_finite(sets, []))
    problems += _schema_problems(jsonschema.Draft202012Validator(schema), sets)
    _raise(path, problems)
    _raise(path, observer_set_problems(data["observer_sets"]))
    from nps.app.resources import OBSERVERS_BYTES_PER_OBSERVER, memory_problems, observer_count

    counts = {name: observer_count(spec) for name, spec in data["observer_sets"].items()}
    _raise(path, memory_problems([(f"observer_sets.{name}", f"the observer table of {n:,} observers",
                                   OBSERVERS_BYTES_PER_OBSERVER * n) for name, n in counts.items()]))
    return fill_defaults(data["observer_sets"], node)


# length below which a thrust axis has no direction (NPS normalises the axes it is given)
AXIS_MIN_LENGTH = 1e-9


def axis_problems(vector, field: str) -> list[tuple[str, str]]:
    """(field, problem) when the thrust axis ``vector`` as written has no direction (a zero vector): refused
    before any computation normalises it."""
    if math.hypot(*vector) >= AXIS_MIN_LENGTH:
        return []
    return [(field, f"expected a non-zero vector (the thrust direction; NPS normalises it), got {list(vector)}")]


def _rotor_sections(rotor: dict, where: str, base: Path) -> list[tuple[str, str]]:
    """Cross checks of one rotor's thrust axis, blade and airfoil tables and control fields.

    Table paths are resolved against ``base`` (the aircraft file's directory) and replaced by
    absolute paths in ``rotor``; the tables are then read once so that a malformed file or an
    unknown airfoil name stops here, before any computation.
    """
    problems = axis_problems(rotor["thrust_axis_body"], f"{where}.thrust_axis_body") if "thrust_axis_body" in rotor else []
    if "blade" in rotor:
        for key in ("chord_m", "twist_deg", "thickness_ratio"):
            if key in rotor:
                problems.append((f"{where}.{key}", "expected no linear-blade field next to a blade table (the table gives it)"))
    holders = [("airfoil", rotor.get("airfoil", {}))]
    holders += [(f"airfoils.{name}", foil) for name, foil in rotor.get("airfoils", {}).items()]
    for field, foil in holders:
        if "table" in foil:
            extra = sorted(set(foil) - {"table", "extrapolation", "reynolds"})
            if extra:
                problems.append((f"{where}.{field}.{extra[0]}", "expected no linear-model parameter next to a table"))
        else:
            # a filled linear airfoil carries the schema's extrapolation default, which changes nothing
            extrapolation = load_schema("aircraft")["$defs"]["airfoil"]["properties"]["extrapolation"]["default"]
            for key in ("extrapolation", "reynolds"):
                if key in foil and not (key == "extrapolation" and foil[key] == extrapolation):
                    problems.append((f"{where}.{field}.{key}", "applies to a table only; expected a table"))
    from nps.rotor.control import TRIMMED_PITCH

    mode = rotor["control"]
    if mode in TRIMMED_PITCH and "pitch_deg" in rotor:
        problems.append((f"{where}.pitch_deg", f"expected no pitch_deg with control '{mode}' (the trim sets the pitch)"))
    if mode not in TRIMMED_PITCH and "pitch_deg" not in rotor:
        problems.append((f"{where}.pitch_deg", f"required with control '{mode}'"))
    for field, holder in holders + [("blade", rotor.get("blade", {}))]:
        if "table" in holder:
            table = base / holder["table"]
            if not table.is_file():
                problems.append((f"{where}.{field}.table", f"file not found: {table}"))
            else:
                holder["table"] = str(table.resolve())
    if not problems:
        try:
            RotorGeometry.from_config(rotor)
        except (AirfoilError, BladeError) as exc:
            problems.append((where, str(exc)))
    return problems


def aircraft_rotor(aircraft: dict, name: str, path: str | Path) -> dict:
    """The rotor called ``name`` of a validated aircraft read from ``path``; ConfigError naming the file if absent."""
    rotor = next((r for r in aircraft["rotors"] if r["name"] == name), None)
    if rotor is None:
        raise ConfigError(f"{path}: rotors: no rotor named '{name}'; has {[r['name'] for r in aircraft['rotors']]}")
    return rotor


def load_mission(path: str | Path, document: Any = None) -> dict:
    """Read and validate one mission file; schema defaults filled (``document``: as :func:`load_aircraft`)."""
    document = read_yaml(path) if document is None else copy.deepcopy(document)
    data = fill_defaults(validate(document, "mission", path), load_schema("mission"))
    problems = []
    ids = [segment["id"] for segment in data["segments"]]
    for index, segment in enumerate(data["segments"]):
        if ids.count(segment["id"]) > 1:
            problems.append((f"segments[{index}].id", f"expected a unique id, '{segment['id']}' repeats"))
        for aircraft, speeds in segment["aircraft"].items():
            if "flight_path_deg" in speeds:
                derived = math.degrees(math.atan2(speeds["climb_speed_mps"], speeds["forward_speed_mps"]))
                if abs(derived - speeds["flight_path_deg"]) > 0.5:
                    problems.append((
                        f"segments[{index}].aircraft.{aircraft}.flight_path_deg",
                        f"expected atan2(climb, forward) = {derived:.2f} deg within 0.5 deg, got {speeds['flight_path_deg']}",
                    ))
            if speeds["forward_speed_mps"] == 0 and speeds["climb_speed_mps"] != 0:
                problems.append((f"segments[{index}].aircraft.{aircraft}", "vertical flight without forward speed is not supported"))
    _raise(path, problems)
    return data


# pairs of leg fields of a path of which at most one is given (nps.mission.paths)
PATH_EXCLUSIVE = (("end_speed_mps", "acceleration_mps2"), ("height_change_m", "flight_path_deg"))


def _path_leg_problems(leg: dict, where: str) -> list[tuple[str, str]]:
    """A path leg's form: one of straight/turn; a straight leg's length (distance_m or duration_s); a turn's
    radius_m or bank_deg; at most one field of each :data:`PATH_EXCLUSIVE` pair."""
    kinds = [kind for kind in ("straight", "turn") if kind in leg]
    if len(kinds) != 1:
        return [(where, f"expected exactly one of 'straight' and 'turn', got {kinds or 'neither'}")]
    body, problems = leg[kinds[0]], []
    pair = ("distance_m", "duration_s") if kinds[0] == "straight" else ("radius_m", "bank_deg")
    if (pair[0] in body) == (pair[1] in body):
        problems.append((f"{where}.{kinds[0]}", f"expected exactly one of '{pair[0]}' and '{pair[1]}'"))
    for first, second in PATH_EXCLUSIVE:
        if first in leg and second in leg:
            problems.append((f"{where}.{second}", f"expected at most one of '{first}' and '{second}', got both"))
    return problems


def load_path(path: str | Path, dt_s: float | None = None, document: Any = None) -> dict:
    """Read and validate one flight-path file (``nps/app/schemas/path.schema.yaml``), defaults filled, with the
    legs' form and the limits of what the aircraft can fly checked (:func:`nps.mission.paths.flight_path_history`,
    errors ``<file>: legs[i].<field>: ...``). ``dt_s``: also check that the history has at least two samples."""
    from nps.mission.paths import PathError, flight_path_history, path_spec

    document = read_yaml(path) if document is None else copy.deepcopy(document)
    data = fill_defaults(validate(document, "path", path), load_schema("path"))
    problems = [problem for index, leg in enumerate(data["legs"]) for problem in _path_leg_problems(leg, f"legs[{index}]")]
    receivers = data["receivers"]
    problems += [(f"receivers.microphones.{name}", f"expected a height z >= 0 above the ground, got {xyz[2]!r}")
                 for name, xyz in receivers["microphones"].items() if xyz[2] < 0]
    if "grid" in receivers:
        problems += [(f"receivers.grid.{axis}", f"expected [low, high] with high > low, got {receivers['grid'][axis]}")
                     for axis in ("x_range_m", "y_range_m") if receivers["grid"][axis][1] <= receivers["grid"][axis][0]]
    if Path(path).stem != data["name"]:
        problems.append(("name", f"expected the file stem '{Path(path).stem}', got '{data['name']}'"))
    _raise(path, problems)
    try:
        legs, history = flight_path_history(path_spec(data), dt_s or 1.0)
    except PathError as error:
        raise ConfigError(f"{path}: {error.field}: {error.expected}") from None
    if dt_s is not None and len(history.time_s) < 2:
        raise ConfigError(f"{path}: legs: the path lasts {legs[-1].t0_s + legs[-1].duration_s:.4g} s: expected at least "
                          f"one time step paths.dt_s = {dt_s} s")
    if "terrain" in receivers:
        _raise(path, _terrain_problems(receivers, history))
    return data


def _terrain_problems(receivers: dict, history) -> list[tuple[str, str]]:
    """A path's terrain (``receivers.terrain``): a grid of elevations ≥ 0 (nps.mission.terrain.Terrain) that
    covers the receiver grid (given, or the track's box) and the microphones, and no sample of the path below it."""
    import numpy as np

    from nps.mission.path_noise import track_grid
    from nps.mission.terrain import Terrain, TerrainError

    try:
        terrain = Terrain.from_config(receivers["terrain"])
    except TerrainError as error:
        field, _, expected = str(error).partition(": ")
        return [(f"receivers.terrain.{field}", expected)] if field in ("height_m",) else [("receivers.terrain", str(error))]
    if "grid" in receivers:
        box = (receivers["grid"]["x_range_m"], receivers["grid"]["y_range_m"])
    else:
        grid = track_grid(history.position_m, float(receivers["margin_m"]), float(receivers["spacing_m"]))
        box = (grid.x_range_m, grid.y_range_m)
    extent = (f"x {terrain.x_m[0]:g}..{terrain.x_m[-1]:g} m, y {terrain.y_m[0]:g}..{terrain.y_m[-1]:g} m")
    problems = []
    corners = np.array([(x, y) for x in box[0] for y in box[1]], float)
    if not np.all(terrain.covers(corners[:, 0], corners[:, 1])):
        problems.append(("receivers.terrain", f"expected a grid covering the receiver grid x {box[0][0]:g}..{box[0][1]:g} m, "
                         f"y {box[1][0]:g}..{box[1][1]:g} m; it covers {extent}"))
    problems += [(f"receivers.microphones.{name}", f"expected a position on the terrain grid ({extent}), got {xyz[:2]}")
                 for name, xyz in receivers["microphones"].items() if not terrain.covers(xyz[0], xyz[1])]
    position = np.asarray(history.position_m, float)
    inside = terrain.covers(position[:, 0], position[:, 1])
    clearance = np.full(len(position), np.inf)
    clearance[inside] = position[inside, 2] - terrain.elevation_m(position[inside, 0], position[inside, 1])
    k = int(np.argmin(clearance))
    if clearance[k] < 0.0:
        problems.append((f"legs[{int(history.leg[k])}]", f"the path passes {-clearance[k]:.3g} m below the terrain at "
                         f"x {position[k, 0]:.6g} m, y {position[k, 1]:.6g} m (t = {history.time_s[k]:.4g} s); expected "
                         "heights above the terrain (the path's heights are above the datum z = 0)"))
    return problems


@dataclass(frozen=True)
class Campaign:
    """A validated campaign: the config (schema defaults filled), its aircraft and mission (filled), the
    segment list, and ``written``, the config as written (for metadata that records it, e.g. the
    footprint's ``ground``)."""

    config: dict
    aircraft: dict[str, dict]
    mission: dict
    segments: list[str]
    written: dict
    # flight paths (:meth:`with_paths`): path name → validated path; path name → its trim-state keys (unique, in
    # order of first visit); state key → {"aircraft": {aircraft: speeds entry}, "advance_ratio": μ} (equal states
    # of paths share a key)
    paths: dict[str, dict] = field(default_factory=dict)
    path_keys: dict[str, list[str]] = field(default_factory=dict)
    path_states: dict[str, dict] = field(default_factory=dict)

    def segment(self, segment_id: str) -> dict:
        """A mission segment, or a path state as a segment (``id`` the state key, its speeds per aircraft)."""
        if segment_id in self.path_states:
            return {"id": segment_id, "name": f"path state {segment_id}", **self.path_states[segment_id]}
        return next(s for s in self.mission["segments"] if s["id"] == segment_id)

    def with_paths(self, paths: dict[str, dict]) -> "Campaign":
        """This campaign with the flight ``paths`` (name → validated path, :func:`load_path`) and the trim states
        that cover each (nps.mission.path_states.plan_path in the campaign's atmosphere and ``paths``
        settings). A path's aircraft must be one of the campaign's."""
        from nps.core.atmosphere import isa
        from nps.mission.path_states import plan_path

        atm = self.config["atmosphere"]
        atmosphere = isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"])
        states: dict[str, dict] = {}
        keys: dict[str, list[str]] = {}
        for name, path in paths.items():
            if path["aircraft"] not in self.aircraft:
                raise ConfigError(f"config/paths/{name}.yaml: aircraft: expected an aircraft of the campaign "
                                  f"({', '.join(self.aircraft)}), got '{path['aircraft']}'")
            aircraft = self.aircraft[path["aircraft"]]
            plan = plan_path(aircraft, path, self.config["paths"], atmosphere)
            entries = plan.speeds([r["name"] for r in aircraft["rotors"]])
            advance = dict(zip(reversed(plan.keys), reversed(plan.states.values[:, 0])))  # first visit's μ
            for key, speeds in entries.items():
                state = states.setdefault(key, {"aircraft": {}, "advance_ratio": float(advance[key])})
                state["aircraft"][path["aircraft"]] = speeds
            keys[name] = list(entries)
        return replace(self, paths=dict(paths), path_keys=keys, path_states=states)

    def rotor(self, aircraft: str, rotor: str) -> dict:
        return next(r for r in self.aircraft[aircraft]["rotors"] if r["name"] == rotor)

    def rotor_names(self, aircraft: str) -> list[str]:
        return [r["name"] for r in self.aircraft[aircraft]["rotors"]]

    # Optional segment lists of the config default to every campaign segment (schema descriptions);
    # these methods are the one place that applies those defaults.
    def _listed(self, listed: list[str] | None) -> list[str]:
        return [s for s in self.segments if listed is None or s in listed]

    def observer_sets(self, segment: str) -> list[str]:
        """Observer sets used in ``segment`` (``observer_sets.<name>.segments``, default all)."""
        return [name for name, spec in self.config["observer_sets"].items() if segment in self._listed(spec.get("segments"))]

    def bvi_segments(self) -> list[str]:
        """Segments with the wake and BVI loads (``models.bvi_segments``, default all; none when ``models.bvi`` is off)."""
        models = self.config["models"]
        return self._listed(models.get("bvi_segments")) if models["bvi"] else []

    def hsi_segments(self) -> list[str]:
        """Segments with the HSI post-processing (``models.hsi_segments``, default all; none when ``models.hsi`` is off)."""
        models = self.config["models"]
        return self._listed(models.get("hsi_segments")) if models["hsi"] else []

    def variants(self, segment: str) -> list[str]:
        """Load variants radiated in ``segment``: the trimmed loads ("base") and/or the BVI loads ("bvi").

        Outside the BVI segments only "base"; in a BVI segment "bvi", preceded by "base" where the
        comparison without BVI is asked for (``models.without_bvi_segments``, default every BVI segment).
        A path state (:meth:`with_paths`) radiates "bvi" where ``models.bvi`` is on and its advance ratio is at
        least ``paths.bvi_min_advance_ratio``, else "base".
        """
        if segment in self.path_states:  # a path state: the BVI loads in forward flight, no comparison
            fast = self.path_states[segment]["advance_ratio"] >= self.config["paths"]["bvi_min_advance_ratio"]
            return ["bvi"] if self.config["models"]["bvi"] and fast else ["base"]
        bvi = self.bvi_segments()
        if segment not in bvi:
            return ["base"]
        without = self.config["models"].get("without_bvi_segments")
        return ["base", "bvi"] if without is None or segment in without else ["bvi"]

    def broadband_model(self) -> str:
        """``models.broadband`` as a model name (:func:`broadband_model`)."""
        return broadband_model(self.config["models"]["broadband"])

    def as_written(self, field: str) -> Any:
        """The dotted config ``field`` as the file writes it: its value there, or the schema's default
        unfilled when absent (for metadata that records the configuration as written)."""
        *parents, key = field.split(".")
        node = self.written
        for part in parents:
            node = node[part]
        return copy.deepcopy(node[key]) if key in node else schema_default("config", field)

    def tone_observer_sets(self, segment: str) -> list[str]:
        """Observer sets of ``segment`` with tone tables and spectra (``outputs.tone_observer_sets``, default all)."""
        listed = self.config["outputs"].get("tone_observer_sets")
        return [name for name in self.observer_sets(segment) if listed is None or name in listed]

    def figure_segments(self, kind: str) -> list[str]:
        """Campaign segments listed for a figure family (``figures.<kind>_segments``)."""
        return self._listed(self.config["figures"][f"{kind}_segments"])


def _footprint_problems(config: dict, mission: dict, all_ids: list[str]) -> list[tuple[str, str]]:
    """Cross references of the ``footprint`` and ``certification`` sections (docs/reference/footprint.md)."""
    problems = []
    footprint = config.get("footprint")
    if footprint is not None:
        spec = config["observer_sets"].get(footprint["source_set"])
        if spec is None or spec["kind"] != "hemisphere" or not spec["moving"]:
            problems.append(("footprint.source_set", f"expected a moving hemisphere of observer_sets, got '{footprint['source_set']}'"))
        for index, leg in enumerate(mission.get("profile", [])):
            if leg["segment"] not in all_ids:
                problems.append((f"mission profile[{index}].segment", f"expected one of {all_ids}, got '{leg['segment']}'"))
    certification = config.get("certification")
    if certification is not None:
        if footprint is None:
            problems.append(("certification", "needs the footprint section (its source_set and ground)"))
        for procedure, segment_id in certification["segments"].items():
            if segment_id not in all_ids:
                problems.append((f"certification.segments.{procedure}", f"expected one of {all_ids}, got '{segment_id}'"))
    return problems


def load_campaign(config: dict, config_file: str | Path = "config/config.yaml", root: str | Path = ".",
                  documents: Mapping[str, Any] | None = None, paths: Mapping[str, Any] | None = None) -> Campaign:
    """Validate the campaign configuration and every file it names, with cross references; the
    :class:`Campaign` holds them with every schema default filled (:func:`fill_defaults`). ``documents``
    (optional) replaces files' contents as read: ``{"aircraft": {name: document}, "mission": document}``
    (the variants of a design study, nps.app.designs), validated under the files' names; ``paths`` (optional)
    names files elsewhere than under ``config_dir``: ``{"aircraft": {name: path}, "mission": path}`` (nps.api)."""
    documents, paths = documents or {}, paths or {}
    written = copy.deepcopy(validate(config, "config", config_file))
    config = fill_defaults(written, load_schema("config"))
    _raise(config_file, campaign_value_problems(config))
    root = Path(root)
    config_dir = root / config["campaign"]["config_dir"]
    problems = []
    aircraft = {}
    for index, name in enumerate(config["campaign"]["aircraft"]):
        path = Path(paths["aircraft"][name]) if name in paths.get("aircraft", {}) else config_dir / "aircraft" / f"{name}.yaml"
        if not path.exists():
            problems.append((f"campaign.aircraft[{index}]", f"expected an aircraft file {path}, none exists"))
            continue
        aircraft[name] = load_aircraft(path, documents.get("aircraft", {}).get(name))
    mission_path = Path(paths["mission"]) if "mission" in paths else config_dir / "missions" / f"{config['campaign']['mission']}.yaml"
    if not mission_path.exists():
        problems.append(("campaign.mission", f"expected a mission file {mission_path}, none exists"))
    _raise(config_file, problems)
    mission = load_mission(mission_path, documents.get("mission"))
    all_ids = [segment["id"] for segment in mission["segments"]]
    segments = config["campaign"].get("segments", all_ids)
    for index, segment_id in enumerate(segments):
        if segment_id not in all_ids:
            problems.append((f"campaign.segments[{index}]", f"expected one of the mission's segments {all_ids}, got '{segment_id}'"))
    segment_lists = {f"figures.{key}": value for key, value in config["figures"].items()}
    segment_lists["models.bvi_segments"] = config["models"].get("bvi_segments", [])
    segment_lists["models.hsi_segments"] = config["models"].get("hsi_segments", [])
    segment_lists["models.without_bvi_segments"] = config["models"].get("without_bvi_segments", [])
    for where, listed in segment_lists.items():
        for index, segment_id in enumerate(listed):
            if segment_id not in all_ids:
                problems.append((f"{where}[{index}]", f"expected one of {all_ids}, got '{segment_id}'"))
    for index, set_name in enumerate(config["outputs"].get("tone_observer_sets", [])):
        if set_name not in config["observer_sets"]:
            problems.append((f"outputs.tone_observer_sets[{index}]", f"expected one of {list(config['observer_sets'])}, got '{set_name}'"))
    for set_name, obs in config["observer_sets"].items():
        for index, segment_id in enumerate(obs.get("segments", [])):
            if segment_id not in all_ids:
                problems.append((f"observer_sets.{set_name}.segments[{index}]", f"expected one of {all_ids}, got '{segment_id}'"))
    problems += _footprint_problems(config, mission, all_ids)
    _raise(config_file, problems)
    _raise(config_file, campaign_memory_problems(config, aircraft))
    _raise(config_file, _azimuth_grid_problems(config["resolution"]["n_psi"], {name: a["rotors"] for name, a in aircraft.items()}))
    for index, segment in enumerate(mission["segments"]):
        if segment["id"] not in segments:
            continue
        for name in aircraft:  # aircraft the mission lists and the campaign does not are not run
            if name not in segment["aircraft"]:
                close = difflib.get_close_matches(name, list(segment["aircraft"]), n=1, cutoff=0.75)
                hint = f" (did you mean '{close[0]}'?)" if close else ""
                problems.append((f"segments[{index}].aircraft", f"expected speeds for aircraft '{name}' of the campaign{hint}"))
        for name, speeds in segment["aircraft"].items():
            rotor_names = [r["name"] for r in aircraft[name]["rotors"]] if name in aircraft else None
            for rotor in speeds.get("rotor_omega_scale", {}):
                if rotor_names is not None and rotor not in rotor_names:
                    problems.append((
                        f"segments[{index}].aircraft.{name}.rotor_omega_scale.{rotor}",
                        f"names a rotor that does not exist; {name} has {rotor_names}",
                    ))
    _raise(mission_path, problems)
    return Campaign(config=config, aircraft=aircraft, mission=mission, segments=list(segments), written=written)


def azimuth_grid_problem(n_psi: int, rotor: Mapping, owner: str) -> str | None:
    """Why ``n_psi`` azimuth steps per revolution cannot carry the blades of ``rotor`` (of ``owner``, e.g. an
    aircraft), or None: blade b sits at ψ + 2π b/N on the azimuth grid (nps.noise.sources), so n_psi must be a
    multiple of the blade count N."""
    blades = int(rotor["n_blades"])
    if n_psi % blades == 0:
        return None
    return (f"{n_psi} azimuth steps per revolution, expected a multiple of {blades} (each of the {blades} blades of "
            f"{owner} rotor '{rotor['name']}' sits on the azimuth grid)")


def _azimuth_grid_problems(n_psi: int, rotors: dict[str, list[dict]]) -> list[tuple[str, str]]:
    """``resolution.n_psi`` against every rotor (owner → rotors): :func:`azimuth_grid_problem`."""
    problems = (azimuth_grid_problem(n_psi, rotor, owner) for owner, listed in rotors.items() for rotor in listed)
    return [("resolution.n_psi", what) for what in problems if what]


def campaign_memory_problems(config: dict, aircraft: dict[str, dict]) -> list[tuple[str, str]]:
    """Jobs of the campaign that cannot fit in the memory available, from the configuration alone
    (:func:`nps.app.resources.campaign_estimates`; the largest aircraft's rotor count): refused before the
    first job instead of inside it (or by the kernel)."""
    from nps.app.resources import campaign_estimates, memory_problems

    n_rotors = max((len(a["rotors"]) for a in aircraft.values()), default=1)
    hsi = bool(config["models"]["hsi"])
    return memory_problems(campaign_estimates(config["resolution"], config["observer_sets"], n_rotors, hsi))


def rig_schema() -> dict:
    """The rig schema with the definitions it refers to: the aircraft schema's (the condition's blade
    motion, the rotor) and the config schema's ``wake`` and ``acoustics`` sections."""
    config = load_schema("config")["properties"]
    return {**load_schema("rig"), "$defs": {**load_schema("aircraft")["$defs"], "wake": config["wake"],
                                            "acoustics": config["acoustics"]}}


def rig_settings(rig: dict) -> dict:
    """The campaign-configuration sections the study stages read, for a validated ``rig``: its own
    ``resolution``, ``models``, ``wake`` (with BVI), ``acoustics`` and ``allow_outside_validity``, and the
    config schema's default ``atmosphere`` (the metrics' absorption and broadband atmosphere; both are off
    for a rig). Nothing comes from a campaign file."""
    atmosphere = fill_defaults({}, load_schema("config")["properties"]["atmosphere"])
    sections = {key: rig[key] for key in ("resolution", "models", "wake", "acoustics") if key in rig}
    return {**sections, "atmosphere": atmosphere, "campaign": {"allow_outside_validity": rig["allow_outside_validity"]}}


def rig_disk_problems(rotors: list[dict]) -> list[tuple[str, str]]:
    """Rotors of a rig (``rotors[]``, hubs and axes in G as ``hub_position_m`` / ``thrust_axis_body``) whose disks
    intersect: a point of one flat disk (up to its tip) within the other's radius and within half the sum of their
    chords of its plane; and a non-lift rotor entering another's blade path with the flapping margin
    (:func:`disk_crossing_problems`, the aircraft's rule). The rotor blamed is the later entry."""
    import numpy as np

    problems = []
    for j, rotor in enumerate(rotors):
        hub_j, axis_j = _disk_frame(rotor)
        e1 = np.cross(axis_j, [0.0, 1.0, 0.0] if abs(axis_j[1]) < 0.9 else [1.0, 0.0, 0.0])
        e1 /= np.linalg.norm(e1)
        rr, pp = np.meshgrid(np.linspace(0.0, float(rotor["radius_m"]), 17), np.linspace(0.0, 2.0 * np.pi, 144), indexing="ij")
        points = hub_j + rr.reshape(-1, 1) * (np.cos(pp).reshape(-1, 1) * e1 + np.sin(pp).reshape(-1, 1) * np.cross(axis_j, e1))
        for other in rotors[:j]:
            hub, axis = _disk_frame(other)
            rel = points - hub
            axial = rel @ axis
            radial = np.linalg.norm(rel - np.outer(axial, axis), axis=1)
            gap = (RotorGeometry.from_config(rotor).chord_m + RotorGeometry.from_config(other).chord_m) / 2.0
            inside = (radial <= other["radius_m"]) & (np.abs(axial) <= gap)
            if inside.any():
                problems.append((f"rotors[{j}] '{rotor['name']}'.hub_position_m", (
                    f"the disk of rotor '{rotor['name']}' (radius {rotor['radius_m']} m, hub {rotor['hub_position_m']} "
                    f"in G) intersects the disk of rotor '{other['name']}' (radius {other['radius_m']} m, hub "
                    f"{other['hub_position_m']} in G): expected the disks apart; check hub_position_m and the axes")))
    return problems + [(f"{field} '{rotors[int(field[7:-1])]['name']}'.hub_position_m", what)
                       for field, what in disk_crossing_problems(rotors)]


def _rig_rotor(ref: dict, base: Path, prepare) -> dict:
    """The validated rotor of a rig's rotor reference (``file``, or ``aircraft`` and ``name``; paths relative to
    ``base``), made the stages' rotor by ``prepare`` (the rig's speed, control, placement)."""
    from nps.rotor.control import default_mode

    if "file" in ref:
        rotor_file = base / ref["file"]
        rotor_schema = {"$defs": load_schema("aircraft")["$defs"], "$ref": "#/$defs/rotor"}
        rotor = prepare(read_yaml(rotor_file))
        given = isinstance(rotor, dict) and "control" in rotor
        rotor = fill_defaults(validate(rotor, rotor_schema, rotor_file), rotor_schema)
        if not given:  # as for an aircraft's rotors (load_aircraft)
            rotor["control"] = default_mode(rotor)
    else:
        rotor_file = base / ref["aircraft"]
        rotor = prepare(aircraft_rotor(load_aircraft(rotor_file), ref["name"], rotor_file))
    _raise(rotor_file, [(place, without_rotor_label(place, what)) for field, what in
                        _rotor_sections(rotor, "rotor", rotor_file.parent)
                        for place in [f"rotor '{rotor['name']}'{field[len('rotor'):]}"]])
    _raise(rotor_file, [("rotor", what) for _, what in solidity_problems([rotor])])
    return rotor


def _rig_control_problems(rotor: dict, condition: dict, where: str) -> list[tuple[str, str]]:
    """A rig rotor's control against its condition: the thrust target it needs, the values it cannot use."""
    from nps.rig.case import control_conflicts

    mode, problems = rotor["control"], []
    if mode != "fixed" and "thrust_N" not in condition:
        problems.append((f"{where}.thrust_N", f"required with control '{mode}' (the thrust target)"))
    return problems + control_conflicts(mode, {**condition, "flapping": rotor["flapping"]}, where)


def _rig_form_problems(raw: Any) -> list[tuple[str, str]]:
    """The one-rotor (``rotor``) or several-rotor (``rotors``) form of a rig document as written: exactly one of
    the two, with ``rotors`` no per-rotor field in ``condition``, and each rotor's axis given one way (its
    ``thrust_axis_T`` or its angles, which the defaults fill in)."""
    from nps.rig.case import ENTRY_CONDITION_FIELDS

    if not isinstance(raw, dict):
        return []  # the schema's message
    if ("rotor" in raw) == ("rotors" in raw):
        return [("rotor, rotors", "expected exactly one of rotor (one rotor) and rotors (several), got "
                 + ("both" if "rotor" in raw else "neither"))]
    entries = raw["rotors"] if isinstance(raw.get("rotors"), list) else []
    problems = [(f"rotors[{i}].thrust_axis_T", f"given with {' and '.join(angles)}: expected the axis one way, "
                 "thrust_axis_T or the angles shaft_angle_deg and lateral_angle_deg (thrust_axis_T would override them)")
                for i, entry in enumerate(entries) if isinstance(entry, dict) and "thrust_axis_T" in entry
                for angles in [[key for key in ("shaft_angle_deg", "lateral_angle_deg") if key in entry]] if angles]
    condition = raw.get("condition")
    if "rotors" in raw and isinstance(condition, dict):
        problems += [(f"condition.{key}", f"with rotors, each rotor gives its own {key} (rotors[i].{key}); the condition "
                      "holds only the common tunnel_speed_mps and atmosphere") for key in ENTRY_CONDITION_FIELDS if key in condition]
    return problems


def _rig_rotors(data: dict, path: Path) -> tuple[list[dict], list[dict]]:
    """(rotors, conditions) of a validated rig: the stages' rotor configurations and each rotor's condition
    (:func:`nps.rig.case.rotor_for_rig`, :func:`nps.rig.case.rig_rotor`), checked: controls, unique names,
    disks apart, no ``rpm`` rotor coupled through the free wake."""
    from nps.rig.case import rig_rotor, rotor_condition, rotor_for_rig

    if "rotor" in data:
        rotor = _rig_rotor(data["rotor"], path.parent, lambda r: rotor_for_rig(r, data["condition"]))
        _raise(path, _rig_control_problems(rotor, data["condition"], "condition"))
        return [rotor], [data["condition"]]
    _raise(path, [problem for i, entry in enumerate(data["rotors"]) if "thrust_axis_T" in entry
                  for problem in axis_problems(entry["thrust_axis_T"], f"rotors[{i}].thrust_axis_T")])
    rotors, conditions, problems, seen = [], [], [], {}
    free = data["models"]["bvi"] and data.get("wake", {}).get("model") == "free" and len(data["rotors"]) > 1
    for i, entry in enumerate(data["rotors"]):
        condition = rotor_condition(data["condition"], entry)
        rotor = _rig_rotor(entry["rotor"], path.parent, lambda r: rig_rotor(r, condition, entry))
        where = f"rotors[{i}] '{rotor['name']}'"
        if rotor["name"] in seen:
            problems.append((f"rotors[{i}].name", f"rotor name '{rotor['name']}' is also rotors[{seen[rotor['name']]}]'s: "
                             "expected unique names (give this entry a name)"))
        seen.setdefault(rotor["name"], i)
        problems += _rig_control_problems(rotor, condition, where)
        if free and rotor["control"] == "rpm":
            problems.append((f"{where}.control", "'rpm' is not available for a rotor coupled to others through the free "
                             "wake (wake.model free): its speed is not re-trimmed in their wakes; use collective (a "
                             "thrust target) or fixed (a pitch)"))
        if free and rotor["control"] == "collective_only":
            problems.append((f"{where}.control", "'collective_only' is not available for a rotor coupled to others "
                             "through the free wake (wake.model free): the re-trim in their wakes sets cyclic pitch; "
                             "use fixed (a pitch), or collective_only with a prescribed wake"))
        rotors.append(rotor)
        conditions.append(condition)
    _raise(path, problems)
    _raise(path, rig_disk_problems(rotors))
    return rotors, conditions


def rotor_stations(data: Mapping, rotors: list[dict]) -> tuple[dict[str, list[float]], list[tuple[str, str]]]:
    """(stations, problems) of a validated rig: each rotor's radial stations r/R of the loads-at-station output
    (its ``rotors[].stations_r_over_R``, else the rig's ``stations_r_over_R``; a rotor with neither is left out)
    and the stations outside a rotor's disk-table stations (midpoints of n_r equal elements from root to tip):
    one problem per station of the rig's list (naming the first such rotor), per station of a rotor's own."""
    n_r, common = int(data["resolution"]["n_r"]), data.get("stations_r_over_R")
    entries = data.get("rotors") or [{}]
    stations, problems, blamed = {}, [], set()
    for i, (entry, rotor) in enumerate(zip(entries, rotors)):
        own = entry.get("stations_r_over_R")
        chosen, field = (own, f"rotors[{i}] '{rotor['name']}'.stations_r_over_R") if own else (common, "stations_r_over_R")
        if not chosen:
            continue
        stations[rotor["name"]] = [float(v) for v in chosen]
        radius, root = float(rotor["radius_m"]), float(rotor["root_cutout_m"])
        low, high = (root + (radius - root) / (2 * n_r)) / radius, 1.0 - (radius - root) / (2 * n_r * radius)
        for k, station in enumerate(chosen):
            if not low <= station <= high and f"{field}[{k}]" not in blamed:
                blamed.add(f"{field}[{k}]")
                problems.append((f"{field}[{k}]", (
                    f"r/R {station} outside the disk stations [{low:.4g}, {high:.4g}] of "
                    f"{'the rotor' if own else repr(rotor['name']).join(('rotor ', ''))} (resolution.n_r {n_r}): loads "
                    f"at a station are interpolated between the table's stations")))
    return stations, problems


def _period_problems(data: Mapping, rotors, conditions) -> list[tuple[str, str]]:
    """A rig whose free wake runs over a common period (``wake.free.common_period``) needs its rotors' speeds in a
    common period (nps.core.periods.common_period with the rig's tolerance and longest period)."""
    from nps.core import periods
    from nps.rig.case import omega_of
    from nps.wake.free import FreeWakeModel

    wake = data.get("wake", {})
    if wake.get("model") != "free" or len(rotors) < 2 or not all("omega_rad_s" in c or "rpm" in c for c in conditions):
        return []
    model = FreeWakeModel.from_config(wake.get("free"))  # the schema's bounds hold: the model's defaults fill the rest
    if not model.common_period:
        return []
    try:
        periods.common_period([r["name"] for r in rotors], [omega_of(c) for c in conditions], model.period_tolerance,
                              model.max_period_revolutions)
    except periods.PeriodError as exc:
        return [("wake.free.common_period", str(exc))]
    return []


def load_rig(path: str | Path) -> dict:
    """Read and validate one rig (``config/rigs/*.yaml``, nps.rig.case) with its rotor(s).

    Returns the rig with the schema's defaults filled in, ``rotor_configs`` (the rotors as the stages use them:
    :func:`nps.rig.case.rotor_for_rig` of the one-rotor form, :func:`nps.rig.case.rig_rotor` of each ``rotors[]``
    entry; validated like an aircraft's ``rotors[]`` entries, tables resolved), ``rotor_conditions`` (each rotor's
    condition: the rig's ``condition``, or :func:`nps.rig.case.rotor_condition`), ``rotor_config`` (the first
    rotor), ``rotor_stations`` (each rotor's stations r/R, :func:`rotor_stations`), ``microphones_T`` /
    ``microphone_groups`` (positions in the test frame, group index) and ``settings`` (:func:`rig_settings`).
    """
    from nps.noise.observers import ObserverError
    from nps.rig.case import microphone_positions

    path = Path(path)
    schema = rig_schema()
    raw = read_yaml(path)
    _raise(path, _rig_form_problems(raw))
    data = fill_defaults(validate(raw, schema, path), schema)
    if path.stem != data["name"]:
        _raise(path, [("name", f"expected the file stem '{path.stem}', got '{data['name']}'")])
    rotors, conditions = _rig_rotors(data, path)
    _raise(path, _azimuth_grid_problems(data["resolution"]["n_psi"], {"the rig's": rotors}))
    _raise(path, _period_problems(data, rotors, conditions))
    stations, problems = rotor_stations(data, rotors)
    _raise(path, problems)
    if data["loads_only"] and data["carpet"]:
        _raise(path, [("carpet", "true with loads_only: the carpet is drawn from the acoustics that loads_only leaves "
                                 "out: remove one of them")])
    try:
        positions, groups = microphone_positions(data["microphones"], path.parent)
    except ObserverError as exc:
        raise ConfigError(f"{path}: microphones: {exc}") from None
    return {**data, "rotor_config": rotors[0], "rotor_configs": rotors, "rotor_conditions": conditions,
            "rotor_stations": stations, "microphones_T": positions, "microphone_groups": groups,
            "settings": rig_settings(data)}
