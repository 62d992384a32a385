"""Design studies: variants of a base campaign (``config/studies/<name>.yaml``, docs/reference/studies.md).

A study names design variables as paths into the documents of a campaign, their values, how they combine
(full factorial, one at a time, or a seeded Latin hypercube), fields linked to a variable by a power law and
constraints that drop variants. Each variant (a :class:`Design`) is the base campaign with those fields
set, validated like any campaign (:func:`nps.app.config.load_campaign`); its id is a digest of the variable
values alone, so adding a value or a variable leaves the other variants' ids, and their artifacts, as
they are.

A study is validated as a whole before any variant is made (:func:`check_study`): each problem is one line
naming the file that writes the field (the study, or the study it extends), the field and what was
expected. The number of designs and the estimated cost of their jobs are known then, and a study estimated
above its ``max_cost_core_h`` is refused with both. :func:`expand` makes the variants and validates each;
:func:`load_study` is the two.

Paths (``<...>`` are names of the base campaign):

* ``aircraft.<aircraft>.rotors.<rotor>.<field>[.<subfield>]``: a rotor field, e.g. ``omega_rad_s``, ``n_blades``;
* ``aircraft.<aircraft>.<field>``: an aircraft field, e.g. ``gross_weight_kg``;
* ``mission.<segment>.<field>``: a segment's field for every aircraft, ``mission.<segment>.<aircraft>.<field>``
  for one (setting a speed drops that entry's ``flight_path_deg`` check, which the new speeds would fail; link
  ``climb_speed_mps`` to ``forward_speed_mps`` with exponent 1 to hold the flight-path angle);
* ``[config.]<section>.<key>[.<subkey>]``: a campaign-configuration field, e.g. ``resolution.n_psi``;
* ``paths.<path>.<key>[.<index or key>...]``: a field of a flight path the study flies (``base.paths``, a procedure
  study), list items by their index, e.g. ``paths.helicopter_approach_6deg.legs.1.flight_path_deg``.

Inside, a path names one or more fields, each a tuple: ``("aircraft", <aircraft>, ..., <key>)``,
``("mission", <segment>, <aircraft>, <key>)``, ``("config", <section>, ..., <key>)`` or ``("paths", <path>, <key or
index>, ...)``; two paths that name the
same field (``resolution.n_psi`` and ``config.resolution.n_psi``) are the same variable.
"""

from __future__ import annotations

import copy
import dataclasses
import hashlib
import itertools
import math
import re
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np

from nps.app.config import (Campaign, ConfigError, azimuth_grid_problem, fill_defaults, load_campaign, load_path,
                            load_schema, raise_problems, read_yaml, schema_node, schema_problems, value_problem)
from nps.app.resources import BUNDLED_OBSERVERS, BUNDLED_RESOLUTION, BUNDLED_ROTORS, observer_count
from nps.app.trade import trade_columns

# Resolution of the preview fidelity (docs/reference/studies.md "Preview fidelity"): a 1.5 deg azimuth step
# (240 steps: a whole number per blade passage for 2 to 6 blades; BVI needs it), 24 radial stations, 3 wake
# revolutions, the campaign's 1024 observer samples per revolution and observer sets. Its error against the
# campaign resolution on the bundled study: docs/reference/studies.md.
PREVIEW_RESOLUTION = {"n_psi": 240, "n_r": 24, "wake_revolutions": 3, "samples_per_rev": 1024}
SPEED_FIELDS = ("forward_speed_mps", "climb_speed_mps")
# trade-table columns (nps.app.trade.case_row) a variable label must not take
RESERVED_COLUMNS = ("design", "aircraft", "segment", "segment_name", "power_W", "validity_warnings", "pareto", "path",
                    "path_description", "duration_s", "distance_m", "energy_J", "n_states", "footprint_open")
RESERVED_PATTERN = (r"[a-z0-9_]*(max_\w+|_(thrust_N|torque_Nm|power_W|ct|ct_sigma|omega_rad_s|tip_speed_mps|tip_mach))"
                    r"|(sel|lamax|epnl)_\w+_db|\w+_area_km2")
# Job time (s) of one case (an aircraft of two rotors in one segment) at the bundled resolution with the
# 360-observer hemisphere, by what it scales with: measured by benchmarks/bench_studies.py (docs/reference/
# studies.md "Performance": 4.5 s a case, the wake 2.5 s in each BVI segment); :func:`case_seconds`.
CASE_SECONDS = {"fixed": 1.1, "disk": 0.32, "wake": 2.5, "radiation": 1.49, "signal": 0.32}
VARIANT_VALIDATION_S = 0.009  # validating one variant's campaign (load_campaign), measured
PROGRESS_MIN_VARIANTS = 200  # studies of this many variants or more report their validation on stderr


@dataclass(frozen=True)
class Variable:
    """A design variable: its ``path``, trade-table ``label``, ``values`` and the base campaign's value;
    ``fields`` it names, ``given`` the study field its values come from (``variables[0].scale``) and, for a range
    a Latin hypercube samples, ``interval`` (low, high, rounded to integers) with ``values`` its ends."""

    path: str
    label: str
    values: tuple
    base_value: Any
    fields: tuple = ()
    given: str = ""
    interval: tuple | None = None

    def probes(self) -> tuple:
        """Values that bound what the variable takes: its values, or its range's ends (and 0 inside it)."""
        if self.interval is None:
            return self.values
        low, high = self.values
        return (low, high, 0) if low < 0 < high else (low, high)

    def integers(self) -> Iterable[int]:
        """Every value of an integer variable: its values, or each integer of its range (lazily)."""
        return self.values if self.interval is None else range(int(self.values[0]), int(self.values[1]) + 1)


@dataclass(frozen=True)
class Link:
    """Fields set by a power law of a variable: ``fields`` ((field, base value), ...), the index of the variable
    they follow and the exponent."""

    path: str
    fields: tuple
    leader: int
    exponent: float


@dataclass(frozen=True)
class Constraint:
    """A constraint: ``terms`` ((field, exponent), ...) whose product of powers must lie in [low, high]."""

    name: str
    terms: tuple
    low: float
    high: float


@dataclass(frozen=True)
class Design:
    """One variant: ``id`` (digest of ``values``), ``values`` (label → value of each variable),
    ``assignment`` (field, dotted → value of every field set, linked ones included) and its validated campaign."""

    id: str
    values: dict
    assignment: dict
    campaign: Campaign


@dataclass(frozen=True)
class DesignStudy:
    """A validated study: its spec (schema defaults filled), base campaign, variables, the variants kept,
    the ones a constraint dropped (``(values, constraint name)``) and the estimated job time of one design
    (core-seconds, :func:`case_seconds` over its aircraft and segments)."""

    name: str
    file: str
    spec: dict
    base: Campaign
    variables: tuple[Variable, ...]
    designs: tuple[Design, ...]
    dropped: tuple = field(default=())
    design_cost_s: float = 0.0

    @property
    def aircraft(self) -> list[str]:
        """The aircraft of the study's jobs: the campaign's, or in a procedure study those flying its paths."""
        if self.base.paths:
            return list(dict.fromkeys(path["aircraft"] for path in self.base.paths.values()))
        return list(self.base.aircraft)

    @property
    def segments(self) -> list[str]:
        return list(self.base.segments)

    def design(self, design_id: str) -> Design:
        found = next((d for d in self.designs if d.id == design_id), None)
        if found is None:
            raise KeyError(f"{self.file}: design '{design_id}' is not one of the study's {len(self.designs)} designs")
        return found

    def describe(self) -> str:
        """One line: the study file, its size and estimated cost (:func:`size_text`)."""
        return f"{self.file}: {size_text(len(self.designs), self.base, self.design_cost_s)}"


def design_id(values: Mapping[str, Any]) -> str:
    """``d`` + 10 hex digits of the SHA-256 of the variable values (label → value, sorted)."""
    text = repr(sorted((str(k), repr(v)) for k, v in values.items()))
    return "d" + hashlib.sha256(text.encode()).hexdigest()[:10]


def _clean(value: Any) -> Any:
    """Floats to 12 significant digits (0.8 x 28 → 22.4), integers and strings as they are."""
    if isinstance(value, (float, np.floating)):
        return float(f"{float(value):.12g}")
    if isinstance(value, np.integer):
        return int(value)
    return value


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float, np.number)) and not isinstance(value, (bool, np.bool_))


def _text(field: tuple) -> str:
    return ".".join(map(str, field))


def _overlap(a: tuple, b: tuple) -> bool:
    """Whether two fields share a value: the same field, or one inside the other."""
    n = min(len(a), len(b))
    return a[:n] == b[:n]


class _Documents:
    """The documents of a campaign as written (config, aircraft, mission, flight paths by name) and filled (the
    campaign, its ``paths`` validated): the fields a design path names, their values and schemas, and setting them
    in the written documents."""

    def __init__(self, config: dict, aircraft: dict, mission: dict, filled: Campaign, paths: dict | None = None):
        self.config, self.aircraft, self.mission, self.filled = config, aircraft, mission, filled
        self.paths = paths or {}

    def copy(self) -> "_Documents":
        """The written documents copied (a variant sets its fields there), the filled campaign shared."""
        return _Documents(copy.deepcopy(self.config), copy.deepcopy(self.aircraft), copy.deepcopy(self.mission),
                          self.filled, copy.deepcopy(self.paths))

    def fields(self, path: str) -> tuple[tuple, ...]:
        """The fields ``path`` names; KeyError (the reason) when it names none or one the campaign does not run."""
        parts = path.split(".")
        campaign = self.filled
        if parts[0] == "aircraft" and len(parts) >= 3:
            name, rest = parts[1], parts[2:]
            if name not in campaign.aircraft:
                raise KeyError(f"aircraft '{name}' is not in the campaign ({list(campaign.aircraft)})")
            if rest[0] == "rotors" and len(rest) < 3:
                raise KeyError("expected aircraft.<aircraft>.rotors.<rotor>.<field>")
            if rest[0] == "rotors" and rest[1] not in campaign.rotor_names(name):
                raise KeyError(f"rotor '{rest[1]}' is not one of {campaign.rotor_names(name)}")
            fields = [("aircraft", *parts[1:])]
        elif parts[0] == "mission" and len(parts) >= 3:
            if parts[1] not in campaign.segments:
                raise KeyError(f"segment '{parts[1]}' is not one of the campaign's segments ({campaign.segments})")
            entries = campaign.segment(parts[1])["aircraft"]
            if parts[2] in entries and parts[2] not in campaign.aircraft:
                raise KeyError(f"aircraft '{parts[2]}' is not in the campaign ({list(campaign.aircraft)})")
            names, rest = ([parts[2]], parts[3:]) if parts[2] in entries else (list(campaign.aircraft), parts[2:])
            if len(rest) != 1:
                raise KeyError("expected mission.<segment>[.<aircraft>].<field>")
            fields = [("mission", parts[1], name, rest[0]) for name in names]
        elif parts[0] == "paths":
            if len(parts) < 3 or parts[1] not in campaign.paths:
                raise KeyError(f"expected paths.<path>.<field> of a path of base.paths ({list(campaign.paths)})")
            fields = [("paths", parts[1], *(int(p) if p.isdigit() else p for p in parts[2:]))]
        else:
            parts = parts[1:] if parts[0] == "config" else parts
            if len(parts) < 2 or parts[0] not in load_schema("config")["properties"]:
                raise KeyError("expected aircraft..., mission..., paths... or a configuration section and key")
            fields = [("config", *parts)]
        for found in fields:
            self._place(found, filled=True)
        return tuple(fields)

    def _place(self, field: tuple, filled: bool) -> tuple[dict | list, str | int]:
        """(container, key) of a field in the filled documents or the written ones."""
        kind, name, *keys = field
        if kind == "config":
            return _descend(self.filled.config if filled else self.config, [name, *keys], filled)
        if kind == "paths":
            return _descend(self.filled.paths[name] if filled else self.paths[name], keys, filled)
        if kind == "mission":
            segments = (self.filled.mission if filled else self.mission)["segments"]
            return _descend(next(s for s in segments if s["id"] == name)["aircraft"][keys[0]], keys[1:], filled)
        node = self.filled.aircraft[name] if filled else self.aircraft[name]
        if keys[0] == "rotors":
            node, keys = next(r for r in node["rotors"] if r["name"] == keys[1]), keys[2:]
        return _descend(node, keys, filled)

    def value(self, field: tuple) -> Any:
        container, key = self._place(field, filled=True)
        return container[key]

    def schema(self, field: tuple) -> dict:
        """The field's schema ({} where its schema does not describe it)."""
        kind, name, *keys = field
        if kind == "config":
            node = schema_node("config", [name, *keys])
        elif kind == "paths":
            node = schema_node("path", keys)
        elif kind == "mission":
            node = schema_node("mission", ["segments", 0, "aircraft", *keys])
        else:
            node = schema_node("aircraft", ["rotors", 0, *keys[2:]] if keys[0] == "rotors" else keys)
        return node or {}

    def set(self, field: tuple, value: Any) -> None:
        container, key = self._place(field, filled=False)
        container[key] = value
        if key in SPEED_FIELDS:
            container.pop("flight_path_deg", None)


def _descend(node: Any, keys: list, filled: bool) -> tuple[dict | list, str | int]:
    """(container, last key) of ``keys`` (mapping keys, list indices) below ``node``; written documents get
    missing sections of mappings created, filled ones must hold every key."""
    def holds(container: Any, key: str | int) -> bool:
        if isinstance(key, int):
            return isinstance(container, list) and key < len(container)
        return isinstance(container, dict) and (not filled or key in container)

    for key in keys[:-1]:
        if not holds(node, key):
            raise KeyError(f"no field '{key}'")
        node = node[key] if isinstance(key, int) else node.setdefault(key, {})
    if not holds(node, keys[-1]):
        raise KeyError(f"no field '{keys[-1]}'")
    return node, keys[-1]


class _Refusal:
    """Raises a study's problems ((field, expectation), :func:`nps.app.config.raise_problems`), each line naming
    the file that writes the field: the study, or the study it extends."""

    def __init__(self, path: Path, origins: Mapping[tuple, Path]):
        self.path, self.origins = path, origins

    def file(self, field: str) -> Path:
        names = re.match(r"([A-Za-z_]\w*)(?:\.([A-Za-z_]\w*))?", field)
        if names is None:
            return self.path
        return self.origins.get(names.groups(), self.origins.get(names.groups()[:1], self.path))

    def __call__(self, problems: Iterable[tuple[str, str]]) -> None:
        raise_problems((self.file(where), where, what) for where, what in problems)


def _study_document(path: Path, seen: tuple = ()) -> tuple[Any, dict]:
    """A study file's content with the fields of the study it ``extends`` (same directory) under its own (a
    mapping merged key by key, other fields replaced), and the file that writes each field and each key of a
    mapping field (``{("design",): file, ("design", "samples"): file, ...}``)."""
    document = read_yaml(path)
    if not isinstance(document, dict):
        return document, {}
    origins = {(key,): path for key in document}
    origins.update({(key, sub): path for key, value in document.items() if isinstance(value, dict) for sub in value})
    if "extends" not in document:
        return document, origins
    parent = path.with_name(f"{document['extends']}.yaml")
    if not parent.is_file() or parent in seen:
        raise ConfigError(f"{path}: extends: expected another study's name in {path.parent} (no cycle), "
                          f"got '{document['extends']}'")
    merged, inherited = _study_document(parent, seen + (path,))
    merged = dict(merged) if isinstance(merged, dict) else {}
    for key, value in document.items():
        merged[key] = {**merged[key], **value} if isinstance(value, dict) and isinstance(merged.get(key), dict) else value
    merged.pop("extends")
    return merged, {**inherited, **origins}


def _form_problems(document: dict, spec: dict, path: Path) -> list[tuple[str, str]]:
    """Fields that another field makes meaningless or required: the name, the design kind's fields, bounds."""
    problems = []
    if "variables" not in spec:
        problems.append(("variables", "required field is missing (here or in the study it extends)"))
    if spec["name"] != path.stem:
        problems.append(("name", f"expected the file stem '{path.stem}', got '{spec['name']}'"))
    written, kind = document.get("design", {}), spec["design"]["kind"]
    if kind == "latin_hypercube":
        if "samples" not in written:
            problems.append(("design.samples", "required with kind 'latin_hypercube'"))
        problems += [(f"variables[{i}].range.num", "not used by a latin_hypercube, which samples the range (design.samples "
                      "sets the count); expected no num")
                     for i, v in enumerate(spec.get("variables", [])) if "num" in v.get("range", {})]
    else:
        stated = "" if "kind" in written else " (the default)"
        problems += [(f"design.{key}", f"only a latin_hypercube uses it, the design kind is '{kind}'{stated}; expected "
                      f"kind: latin_hypercube, or no {key}") for key in ("samples", "seed") if key in written]
    for index, item in enumerate(spec["constraints"]):
        if "min" not in item and "max" not in item:
            problems.append((f"constraints[{index}]", "expected min or max (a constraint without bounds drops nothing)"))
        elif item.get("min", -math.inf) > item.get("max", math.inf):
            problems.append((f"constraints[{index}].min", f"expected min <= max, got min {item['min']} and max {item['max']}"))
    return problems


def _nested(field: str, prefix: str, error: ConfigError) -> list[tuple[str, str]]:
    """A study problem at ``field`` for each line of a campaign's error (its "N problems:" line left out)."""
    lines = str(error).splitlines()
    return [(field, prefix + line.strip()) for line in (lines[1:] if len(lines) > 1 else lines)]


def _base_campaign(spec: dict, refuse: _Refusal, root: Path, resolution: Mapping | None) -> tuple[Campaign, _Documents, Path]:
    """The base campaign as the study runs it (its aircraft and segments, the fidelity's and ``resolution``'s
    fields), its documents as written and the configuration file; an error names the study's base field."""
    config_file = root / spec["base"]["config"]
    if not config_file.is_file():
        refuse([("base.config", f"expected a campaign configuration file, {config_file} does not exist")])
    try:
        written = read_yaml(config_file)
        campaign = load_campaign(written, config_file, root)
    except ConfigError as error:
        refuse(_nested("base.config", "", error))
    refuse((f"base.{key}[{index}]", f"expected one of the {key} of {config_file} {allowed}, got '{name}'")
           for key, allowed in (("aircraft", list(campaign.aircraft)), ("segments", campaign.segments))
           for index, name in enumerate(spec["base"].get(key, [])) if name not in allowed)
    written = copy.deepcopy(written)
    subsets = {key: list(spec["base"][key]) for key in ("aircraft", "segments") if key in spec["base"]}
    written.setdefault("campaign", {}).update(subsets)
    if spec["fidelity"] == "preview":
        written["resolution"] = {**written.get("resolution", {}), **PREVIEW_RESOLUTION}
    if resolution:
        written["resolution"] = {**written.get("resolution", {}), **resolution}
    try:
        campaign = load_campaign(written, config_file, root)
    except ConfigError as error:
        given = f" and the resolution {dict(resolution)} of the call" if resolution else ""
        refuse(_nested("fidelity", f"the {spec['fidelity']} resolution{given}: ", error))
    config_dir = root / campaign.config["campaign"]["config_dir"]
    aircraft = {name: read_yaml(config_dir / "aircraft" / f"{name}.yaml") for name in campaign.aircraft}
    mission = read_yaml(config_dir / "missions" / f"{campaign.config['campaign']['mission']}.yaml")
    paths = _base_paths(spec, campaign, config_dir, refuse)
    campaign = _with_paths(campaign, paths, config_dir, refuse, "base.paths")
    return campaign, _Documents(written, aircraft, mission, campaign, paths), config_file


def _base_paths(spec: dict, campaign: Campaign, config_dir: Path, refuse: _Refusal) -> dict:
    """The flight paths a procedure study flies (``base.paths``: name → document as written), refused where a file
    is missing or its aircraft is not one of the study's, or where two paths name different microphones (the
    trade table's columns)."""
    names = spec["base"].get("paths", [])
    files = {name: config_dir / "paths" / f"{name}.yaml" for name in names}
    refuse((f"base.paths[{i}]", f"expected a flight path of {config_dir / 'paths'}, {files[name]} does not exist")
           for i, name in enumerate(names) if not files[name].is_file())
    paths = {name: read_yaml(files[name]) for name in names}
    problems = [(f"base.paths[{i}]", f"{files[name]} flies '{paths[name].get('aircraft')}': expected one of the study's "
                 f"aircraft {list(campaign.aircraft)}") for i, name in enumerate(names)
                if paths[name].get("aircraft") not in campaign.aircraft]
    microphones = {name: sorted((paths[name].get("receivers") or {}).get("microphones") or {}) for name in names}
    problems += [("base.paths", f"{names[0]} and {name} name the microphones {microphones[names[0]]} and {microphones[name]}: "
                  "expected the same microphones (one trade-table column per microphone and metric)")
                 for name in names[1:] if microphones[name] != microphones[names[0]]]
    refuse(problems)
    return paths


def _with_paths(campaign: Campaign, paths: Mapping[str, dict], config_dir: Path, refuse: _Refusal | None,
                where: str) -> Campaign:
    """``campaign`` with the flight ``paths`` (name → document) validated (:func:`nps.app.config.load_path`) and
    planned (:meth:`Campaign.with_paths`); a problem is refused at ``where`` (``refuse`` given) or raised."""
    if not paths:
        return campaign
    try:
        validated = {name: load_path(config_dir / "paths" / f"{name}.yaml", campaign.config["paths"]["dt_s"], document)
                     for name, document in paths.items()}
        return campaign.with_paths(validated)
    except ConfigError as error:
        if refuse is None:
            raise
        refuse(_nested(where, "", error))


def _product_problems(spec: dict, base: Campaign) -> list[tuple[str, str]]:
    """Products and observer sets the base configuration cannot give, a procedure study's products (procedure
    alone, with base.paths) and the Pareto front's columns (:func:`nps.app.trade.trade_columns`)."""
    config = spec["base"]["config"]
    problems = []
    procedure = "procedure" in spec["products"]
    if procedure != bool(base.paths) or (procedure and len(spec["products"]) > 1):
        problems.append(("products", f"a procedure study flies base.paths and has one row per design x path: expected "
                         f"products [procedure] with base.paths, or other products without; got {spec['products']} "
                         f"and base.paths {list(base.paths)}"))
    elif procedure and "footprint" not in base.config:
        problems.append(("products", f"'procedure' needs the footprint section in {config} (the states' source set, ground)"))
    else:
        names = sorted(trade_columns(spec["products"], base, spec["observer_sets"]))
        problems += [(f"pareto.{key}", f"expected a trade-table column of the study's products ({', '.join(names)}), got "
                      f"'{column}'") for key, column in spec.get("pareto", {}).items() if column not in names]
    if "certification" in spec["products"] and "certification" not in base.config:
        problems.append(("products", f"'certification' needs the certification section in {config}"))
    if "footprint" in spec["products"] and ("footprint" not in base.config or "profile" not in base.mission):
        problems.append(("products", f"'footprint' needs the footprint section in {config} and a profile in the mission"))
    unknown = [name for name in spec["observer_sets"] if name not in base.config["observer_sets"]]
    if unknown:
        problems.append(("observer_sets", f"{unknown} are not observer sets of {config} ({list(base.config['observer_sets'])})"))
    return problems


def _variable(index: int, item: dict, documents: _Documents, kind: str) -> tuple[Variable | None, list]:
    """A variable of the study (None when its path names nothing) and its problems: scale or range of a
    non-numeric field, low >= high, repeated values, values its field's schema refuses."""
    try:
        fields = documents.fields(item["path"])
    except KeyError as error:
        return None, [(f"variables[{index}].path", f"{error.args[0]}; got '{item['path']}'")]
    base_value, node = _clean(documents.value(fields[0])), documents.schema(fields[0])
    integer = node.get("type") == "integer"
    label = item["label"] if "label" in item else ".".join(item["path"].split(".")[-2:])
    source = next(key for key in ("values", "scale", "range") if key in item)
    given, interval = f"variables[{index}].{source}", None
    if source == "values":
        values = tuple(_clean(int(v) if integer and isinstance(v, float) and v.is_integer() else v) for v in item["values"])
    elif not _is_number(base_value):
        return None, [(given, f"scale and range need a numeric field, {_text(fields[0])} is {base_value!r}")]
    elif source == "scale":
        values = tuple(_clean(round(base_value * s) if integer else base_value * s) for s in item["scale"])
    else:
        low, high, rounded = item["range"]["low"], item["range"]["high"], integer or item["range"]["integer"]
        if not low < high:
            return None, [(given, f"expected low < high, got [{low}, {high}]")]
        interval = (low, high, rounded) if kind == "latin_hypercube" else None
        ends = (low, high) if interval else np.linspace(low, high, item["range"].get("num", 2))
        values = tuple(_clean(int(round(v)) if rounded else v) for v in ends)
    variable = Variable(item["path"], label, values, base_value, fields, given, interval)
    keys = [(isinstance(v, bool), v) for v in values]
    repeated = [v for v, key in zip(values, keys) if keys.count(key) > 1]
    if repeated:
        rounding = " (an integer field: the values are rounded)" if integer and source != "values" else ""
        return variable, [(given, f"gives {list(values)}, {repeated[0]!r} more than once{rounding}; expected distinct values "
                           "(a repeated value repeats the designs)")]
    suffix = (lambda j: "") if interval else (lambda j: f"[{j}]")
    return variable, [(f"{given}{suffix(j)}", f"{problem} for {_text(fields[0])}") for j, value in enumerate(values)
                      for problem in [value_problem(node, value)] if node and problem]


def _variables(spec: dict, documents: _Documents, refuse: _Refusal) -> tuple[Variable, ...]:
    """The study's variables, refused with every problem: their own, labels repeated or reserved, a field set by
    two variables."""
    found = [_variable(index, item, documents, spec["design"]["kind"]) for index, item in enumerate(spec["variables"])]
    refuse(problem for _, problems in found for problem in problems)
    variables = tuple(variable for variable, _ in found)
    labels = [v.label for v in variables]
    problems = [] if len(set(labels)) == len(labels) else [("variables", f"expected unique labels, got {labels}")]
    problems += [(f"variables[{index}].label", f"'{label}' is a trade-table column; expected another name (e.g. one "
                  "with a '.', like the default main.omega_rad_s)") for index, label in enumerate(labels)
                 if "." not in label and (label in RESERVED_COLUMNS or re.fullmatch(RESERVED_PATTERN, label))]
    problems += [(f"variables[{j}].path", f"'{b.path}' sets {_text(shared)}, as variables[{i}].path does; expected each "
                  "field in one variable (the later would override the earlier's values)")
                 for (i, a), (j, b) in itertools.combinations(enumerate(variables), 2)
                 for shared in [next((f for f in b.fields if any(_overlap(f, g) for g in a.fields)), None)] if shared]
    refuse(problems)
    return variables


def _power_problem(ratio: float, exponent: float) -> str | None:
    """Why ``ratio ** exponent`` has no finite real value, with what is expected; None when it has one."""
    if ratio == 0 and exponent < 0:
        return "divides by zero; expected values other than 0 with a negative exponent"
    if ratio < 0 and not float(exponent).is_integer():
        return "has no real value (a fractional power of a negative number); expected an integer exponent or values of one sign"
    try:
        finite = math.isfinite(abs(ratio) ** exponent)
    except OverflowError:
        finite = False
    return None if finite else "overflows; expected a smaller exponent or values nearer the base value"


def _link_problems(where: str, item: dict, fields: tuple, documents: _Documents, leader: Variable) -> list:
    """A link's problems: a non-numeric variable or linked field, a variable's base value 0, a power without a
    finite real value, linked values the field's schema refuses (checked at the variable's bounding values)."""
    exponent = item["exponent"]
    if not all(_is_number(v) for v in leader.values) or not _is_number(leader.base_value) or leader.base_value == 0:
        return [(f"{where}.follows", f"'{leader.path}' has the base value {leader.base_value!r} and the values "
                 f"{list(leader.values)}: expected numbers and a base value other than 0 (value = base value × "
                 "(variable / its base value)^exponent)")]
    integer = {f: documents.schema(f).get("type") == "integer" for f in fields}
    problems = [(f"{where}.path", f"{_text(f)} is {documents.value(f)!r}{' (an integer field)' if integer[f] else ''}: "
                 "expected a real-valued field (a power law gives fractions)")
                for f in fields if not _is_number(documents.value(f)) or integer[f]]
    if problems:
        return problems
    for x in leader.probes():
        reason = _power_problem(x / leader.base_value, exponent)
        if reason:
            return [(f"{where}.exponent", f"({leader.label} {x} / its base value {leader.base_value})^{exponent} {reason}")]
    return [(f"{where}.path", f"{_text(f)} = {documents.value(f)} × ({x} / {leader.base_value})^{exponent} = {value} at "
             f"{leader.label} {x}: {problem}") for f in fields for x in leader.probes()
            for value in [_clean(documents.value(f) * (x / leader.base_value) ** exponent)]
            for problem in [value_problem(documents.schema(f), value)] if documents.schema(f) and problem]


def _links(spec: dict, documents: _Documents, variables: tuple[Variable, ...], refuse: _Refusal) -> tuple[Link, ...]:
    """The study's linked fields, refused with every problem (:func:`_link_problems`, a field a variable or
    another link sets, a ``follows`` that is no variable)."""
    problems, links = [], []
    for index, item in enumerate(spec["linked"]):
        where = f"linked[{index}]"
        try:
            follows = documents.fields(item["follows"])
        except KeyError:
            follows = ()
        leader = next((k for k, v in enumerate(variables) if v.fields == follows), None)
        if leader is None:
            problems.append((f"{where}.follows", f"expected the path of a variable, got '{item['follows']}'"))
            continue
        try:
            fields = documents.fields(item["path"])
        except KeyError as error:
            problems.append((f"{where}.path", f"{error.args[0]}; got '{item['path']}'"))
            continue
        setters = [(f"variables[{k}].path", v.fields) for k, v in enumerate(variables)]
        setters += [(f"linked[{k}].path", tuple(f for f, _ in link.fields)) for k, link in enumerate(links)]
        clash = next(((name, f) for name, taken in setters for f in fields if any(_overlap(f, g) for g in taken)), None)
        if clash:
            problems.append((f"{where}.path", f"'{item['path']}' sets {_text(clash[1])}, as {clash[0]} does; expected a field "
                             "no variable or other link sets (the link would override its values)"))
            continue
        found = _link_problems(where, item, fields, documents, variables[leader])
        problems += found
        if not found:
            links.append(Link(item["path"], tuple((f, documents.value(f)) for f in fields), leader, item["exponent"]))
    refuse(problems)
    return tuple(links)


def _field_probes(field: tuple, documents: _Documents, variables: tuple[Variable, ...], links: tuple[Link, ...]) -> tuple:
    """Values that bound what a field takes over the designs: a variable's probes, a linked field's at them, or
    its base value."""
    for variable in variables:
        if field in variable.fields:
            return variable.probes()
    for link in links:
        leader = variables[link.leader]
        for linked, base in link.fields:
            if linked == field:
                return tuple(base * (x / leader.base_value) ** link.exponent for x in leader.probes())
    return (documents.value(field),)


def _constraints(spec: dict, documents: _Documents, variables: tuple[Variable, ...], links: tuple[Link, ...],
                 refuse: _Refusal) -> tuple[Constraint, ...]:
    """The study's constraints, refused with every problem: a term that names no field or several, a
    non-numeric field, a power without a finite real value."""
    problems, constraints = [], []
    for index, item in enumerate(spec["constraints"]):
        terms = []
        for term, exponent in item["terms"].items():
            where = f"constraints[{index}].terms.{term}"
            try:
                fields = documents.fields(term)
            except KeyError as error:
                problems.append((f"constraints[{index}].terms", f"{error.args[0]}; got '{term}'"))
                continue
            if len(fields) > 1:
                problems.append((where, f"names {len(fields)} fields ({', '.join(map(_text, fields))}); expected one, e.g. "
                                 f"{_text(fields[0])}"))
                continue
            probes = _field_probes(fields[0], documents, variables, links)
            wrong = [v for v in probes if not _is_number(v)]
            reason = None if wrong else next(filter(None, (_power_problem(v, exponent) for v in probes)), None)
            if wrong:
                problems.append((where, f"{_text(fields[0])} takes {wrong[0]!r}: expected a numeric field"))
            elif reason:
                problems.append((where, f"{_text(fields[0])} to the power {exponent} {reason}"))
            terms.append((fields[0], exponent))
        constraints.append(Constraint(item["name"], tuple(terms), item.get("min", -math.inf), item.get("max", math.inf)))
    refuse(problems)
    return tuple(constraints)


def _grid_problems(base: Campaign, variables: tuple[Variable, ...]) -> list[tuple[str, str]]:
    """Blade counts the variables give against the azimuth steps (n_psi a multiple of each rotor's blades,
    :func:`nps.app.config.azimuth_grid_problem`), blamed on the blades' variable, else on n_psi's."""
    def setter(field: tuple) -> Variable | None:
        return next((v for v in variables if field in v.fields), None)

    n_psi = setter(("config", "resolution", "n_psi"))
    problems = []
    for name, aircraft in base.aircraft.items():
        for rotor in aircraft["rotors"]:
            blades = setter(("aircraft", name, "rotors", rotor["name"], "n_blades"))
            if blades is None and n_psi is None:
                continue
            steps = n_psi.integers() if n_psi else (base.config["resolution"]["n_psi"],)
            pairs = itertools.product(blades.integers() if blades else (rotor["n_blades"],), steps)
            problem = next(filter(None, (azimuth_grid_problem(n, {**rotor, "n_blades": b}, name) for b, n in pairs)), None)
            if problem:
                problems.append(((blades or n_psi).given, f"with resolution.n_psi {problem}"))
    return problems


def case_seconds(config: Mapping, n_rotors: int, bvi: bool, observer_sets: Sequence[str]) -> float:
    """Estimated job time (s) of one case, an aircraft of ``n_rotors`` rotors in one segment (``bvi``: with the wake
    and BVI loads) radiating to ``observer_sets`` under a campaign configuration: :data:`CASE_SECONDS`, each part
    scaled by its work against the bundled campaign's (disk n_psi n_r; wake n_psi² revolutions; radiation
    observers n_psi n_r; signals observers samples_per_rev; all per rotor)."""
    res, ref = config["resolution"], BUNDLED_RESOLUTION
    observers = sum(observer_count(config["observer_sets"][name]) for name in observer_sets) / BUNDLED_OBSERVERS
    disk = res["n_psi"] * res["n_r"] / (ref["n_psi"] * ref["n_r"])
    wake = bvi * res["wake_revolutions"] * res["n_psi"] ** 2 / (ref["wake_revolutions"] * ref["n_psi"] ** 2)
    signal = observers * res["samples_per_rev"] / ref["samples_per_rev"]
    per_rotor = (CASE_SECONDS["disk"] * disk + CASE_SECONDS["wake"] * wake + CASE_SECONDS["radiation"] * observers * disk
                 + CASE_SECONDS["signal"] * signal)
    return CASE_SECONDS["fixed"] + per_rotor * n_rotors / BUNDLED_ROTORS


def _design_cost_s(base: Campaign, variables: tuple[Variable, ...], observer_sets: Sequence[str]) -> float:
    """Estimated job time of one design (core-seconds): :func:`case_seconds` over its aircraft and segments (a
    procedure study: over each path's trim states of the base design, with the wake, to the footprint's source
    set), with each numeric configuration variable at its largest value (a bound over the designs)."""
    config = copy.deepcopy(base.config)
    for variable in variables:
        kind, *keys = variable.fields[0]
        if kind == "config" and all(isinstance(v, (int, float)) for v in variable.probes()):
            container, key = _descend(config, keys, filled=True)
            container[key] = max(variable.probes())
    if base.paths:
        source = [config["footprint"]["source_set"]]
        return sum(len(base.path_keys[name]) * case_seconds(config, len(base.aircraft[path["aircraft"]]["rotors"]), True, source)
                   for name, path in base.paths.items())
    bvi = dataclasses.replace(base, config=config).bvi_segments()
    return sum(case_seconds(config, len(aircraft["rotors"]), segment in bvi, observer_sets)
               for aircraft in base.aircraft.values() for segment in base.segments)


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.2g} s"
    return f"{seconds / 60:.3g} min" if seconds < 7200 else f"{seconds / 3600:.3g} h"


def size_text(n_designs: int, base: Campaign, design_cost_s: float) -> str:
    """The size of a study and its estimated cost: designs × aircraft × segments = cases, the core-hours of their
    jobs and the time validating the variants takes before them."""
    n_aircraft, n_segments = len(base.aircraft), len(base.segments)
    cost = (f"estimated {n_designs * design_cost_s / 3600:.3g} core-hours of jobs (after about "
            f"{_duration(n_designs * VARIANT_VALIDATION_S)} validating the variants)")
    if base.paths:
        n_states = sum(len(keys) for keys in base.path_keys.values())
        return (f"{n_designs} designs × {len(base.paths)} paths = {n_designs * len(base.paths)} procedures ({n_states} trim "
                f"states in the base design's paths; a state another design flies is computed once), {cost}")
    return f"{n_designs} designs × {n_aircraft} aircraft × {n_segments} segments = {n_designs * n_aircraft * n_segments} cases, {cost}"


@dataclass(frozen=True)
class StudyPlan:
    """A study validated before expansion (:func:`check_study`): the spec (schema defaults filled), the base
    campaign, its documents and configuration file, the variables, links and constraints, the number of design
    points (before a constraint drops any) and the estimated job time of one design (core-seconds)."""

    name: str
    file: str
    spec: dict
    base: Campaign
    documents: _Documents
    config_file: Path
    root: Path
    refuse: _Refusal
    variables: tuple[Variable, ...]
    links: tuple[Link, ...]
    constraints: tuple[Constraint, ...]
    n_points: int
    design_cost_s: float

    def describe(self) -> str:
        return f"{self.file}: {size_text(self.n_points, self.base, self.design_cost_s)}"


def _point_count(design: Mapping, variables: tuple[Variable, ...]) -> int:
    """Design points of the study before the constraints (one at a time: the base point once)."""
    if design["kind"] == "factorial":
        return math.prod(len(v.values) for v in variables)
    if design["kind"] == "one_at_a_time":
        return 1 + sum(value != v.base_value for v in variables for value in v.values)
    return design["samples"]


def check_study(path: str | Path, root: str | Path = ".", resolution: Mapping | None = None) -> StudyPlan:
    """The one validation of a study file, before any variant is made: its schema and the fields others make
    meaningless or required; the base campaign (``resolution`` overrides fields of its resolution after the
    fidelity preset); the variables (the fields they name, their values against the fields' schemas, each field
    set once), links and constraints (real, finite powers); blade counts against the azimuth steps; then its
    size and estimated cost, refused above ``max_cost_core_h``. Every problem is one line naming the file that
    writes the field, the field and what was expected (:class:`ConfigError`)."""
    path, root = Path(path), Path(root)
    document, origins = _study_document(path)
    refuse, schema = _Refusal(path, origins), load_schema("study")
    refuse(schema_problems(document, schema))
    spec = fill_defaults(document, schema)
    refuse(_form_problems(document, spec, path))
    base, documents, config_file = _base_campaign(spec, refuse, root, resolution)
    refuse(_product_problems(spec, base))
    variables = _variables(spec, documents, refuse)
    links = _links(spec, documents, variables, refuse)
    constraints = _constraints(spec, documents, variables, links, refuse)
    refuse(_grid_problems(base, variables))
    plan = StudyPlan(spec["name"], str(path), spec, base, documents, config_file, root, refuse, variables, links,
                     constraints, _point_count(spec["design"], variables), _design_cost_s(base, variables, spec["observer_sets"]))
    cost_core_h = plan.n_points * plan.design_cost_s / 3600
    if cost_core_h > spec["max_cost_core_h"]:
        refuse([("design.samples" if spec["design"]["kind"] == "latin_hypercube" else "variables",
                 f"{size_text(plan.n_points, base, plan.design_cost_s)}: above max_cost_core_h {spec['max_cost_core_h']}; "
                 f"expected fewer designs, or max_cost_core_h: {math.ceil(cost_core_h)} in the study to run them")])
    return plan


def _latin_hypercube(variables: tuple[Variable, ...], samples: int, seed: int) -> list[tuple]:
    """``samples`` points, one per stratum of every variable (ranges: uniform within the stratum; value lists:
    the stratum's element), permutations from ``numpy.random.default_rng(seed)``."""
    rng = np.random.default_rng(seed)
    columns = []
    for variable in variables:
        u = (rng.permutation(samples) + rng.random(samples)) / samples
        if variable.interval:
            low, high, rounded = variable.interval
            columns.append([_clean(int(round(v)) if rounded else v) for v in low + u * (high - low)])
        else:
            n = len(variable.values)
            columns.append([variable.values[i] for i in np.minimum((u * n).astype(int), n - 1)])
    return list(zip(*columns))


def _points(plan: StudyPlan) -> list[tuple]:
    """The design points (one value per variable); a Latin hypercube that repeats a point is refused."""
    design, variables = plan.spec["design"], plan.variables
    if design["kind"] == "factorial":
        return list(itertools.product(*(v.values for v in variables)))
    if design["kind"] == "one_at_a_time":
        base = tuple(v.base_value for v in variables)
        points = [base] + [base[:i] + (value,) + base[i + 1:] for i, v in enumerate(variables) for value in v.values]
        return list(dict.fromkeys(points))
    points = _latin_hypercube(variables, design["samples"], design["seed"])
    distinct = len(set(points))
    if distinct < len(points):
        plan.refuse([("design.samples", f"{len(points)} samples of seed {design['seed']} give {distinct} distinct designs (the "
                      "variables take few values: a value list, an integer range); expected fewer samples, or ranges of "
                      "real values")])
    return points


def _assignment(plan: StudyPlan, point: tuple) -> dict:
    """Field → value of every field a design point sets: the variables' and the linked fields'."""
    assignment = {}
    for variable, value in zip(plan.variables, point):
        assignment.update(dict.fromkeys(variable.fields, value))
    for link in plan.links:
        factor = (point[link.leader] / plan.variables[link.leader].base_value) ** link.exponent
        assignment.update({f: _clean(base * factor) for f, base in link.fields})
    return assignment


def _constraint_value(documents: _Documents, assignment: dict, terms: tuple) -> float:
    return math.prod(float(assignment[f] if f in assignment else documents.value(f)) ** e for f, e in terms)


def _design(documents: _Documents, assignment: dict, config_file: Path, root: Path) -> Campaign:
    variant = documents.copy()
    for target, value in assignment.items():
        variant.set(target, value)
    campaign = load_campaign(variant.config, config_file, root, {"aircraft": variant.aircraft, "mission": variant.mission})
    return _with_paths(campaign, variant.paths, root / campaign.config["campaign"]["config_dir"], None, "")


def _stderr_progress(file: str, total: int) -> Callable[[int, int], None]:
    """Progress of validating ``total`` variants on stderr, every tenth of them, when there are
    :data:`PROGRESS_MIN_VARIANTS` or more."""
    step, start = max(1, math.ceil(total / 10)), time.perf_counter()

    def report(done: int, total: int) -> None:
        if total >= PROGRESS_MIN_VARIANTS and (done % step == 0 or done == total):
            sys.stderr.write(f"{file}: {done} of {total} variants validated ({time.perf_counter() - start:.0f} s)\n")
    return report


def expand(plan: StudyPlan, progress: Callable[[int, int], None] | None = None) -> DesignStudy:
    """The variants of a checked study: each design point's fields set (variables and linked fields), the points a
    constraint drops listed, each other one validated like a campaign; ``progress(done, total)`` is called after
    each (default: a line on stderr every tenth, :func:`_stderr_progress`)."""
    labels = [v.label for v in plan.variables]
    kept, dropped = [], []
    for point in _points(plan):
        values, assignment = dict(zip(labels, point)), _assignment(plan, point)
        violated = next((c.name for c in plan.constraints
                         if not c.low <= _constraint_value(plan.documents, assignment, c.terms) <= c.high), None)
        if violated is None:
            kept.append((values, assignment))
        else:
            dropped.append((values, violated))
    if not kept:
        plan.refuse([("constraints", f"every variant is dropped ({len(dropped)} variants)")])
    report = progress or _stderr_progress(plan.file, len(kept))
    designs = []
    for done, (values, assignment) in enumerate(kept, start=1):
        try:
            campaign = _design(plan.documents, assignment, plan.config_file, plan.root)
        except ConfigError as error:
            raise ConfigError(f"{plan.file}: variant {values}: {error}") from None
        designs.append(Design(design_id(values), values, {_text(f): v for f, v in assignment.items()}, campaign))
        report(done, len(kept))
    return DesignStudy(plan.name, plan.file, plan.spec, plan.base, plan.variables, tuple(designs), tuple(dropped),
                       plan.design_cost_s)


def load_study(path: str | Path, root: str | Path = ".", resolution: Mapping | None = None,
               progress: Callable[[int, int], None] | None = None) -> DesignStudy:
    """Read, validate (:func:`check_study`) and expand (:func:`expand`) a study file: every problem found before
    any variant is made, every variant validated before anything runs; errors name the study file and the
    field (or the variant's campaign file) and what was expected. ``resolution`` (optional) overrides fields
    of the variants' ``resolution`` section after the fidelity preset."""
    return expand(check_study(path, root, resolution), progress)


def campaign_for_files(aircraft: str | Path, mission: str | Path, config: str | Path,
                       resolution: Mapping | None = None) -> Campaign:
    """The campaign of one aircraft file in one mission file under a campaign configuration file (its
    ``campaign`` section's aircraft and mission replaced by these, every segment of the mission;
    ``resolution`` overrides fields of its ``resolution`` section). Errors name the file and field."""
    aircraft, mission, config = Path(aircraft), Path(mission), Path(config)
    document = copy.deepcopy(read_yaml(config))
    if not isinstance(document, dict):
        raise ConfigError(f"{config}: expected a campaign configuration mapping")
    section = document.setdefault("campaign", {})
    section.update(aircraft=[aircraft.stem], mission=mission.stem)
    section.pop("segments", None)
    if resolution:
        document["resolution"] = {**document.get("resolution", {}), **resolution}
    root = config.parent.parent if config.parent.name == "config" else Path(".")
    return load_campaign(document, config, root=root, paths={"aircraft": {aircraft.stem: aircraft}, "mission": mission})
