"""Design studies: variants of a base campaign (``config/studies/<name>.yaml``, docs/reference/studies.md).

A study names design variables as paths into the documents of a campaign, their values, how they combine
(full factorial, one at a time, or a seeded Latin hypercube), fields linked to a variable by a power law and
constraints that drop variants. Each variant (a :class:`Design`) is the base campaign with those fields
set, validated like any campaign (:func:`nps.app.config.load_campaign`); its id is a digest of the variable
values alone, so adding a value or a variable leaves the other variants' ids, and their artifacts, as
they are.

Paths (``<...>`` are names of the base campaign):

* ``aircraft.<aircraft>.rotors.<rotor>.<field>[.<subfield>]``: a rotor field, e.g. ``omega_rad_s``, ``n_blades``;
* ``aircraft.<aircraft>.<field>``: an aircraft field, e.g. ``gross_weight_kg``;
* ``mission.<segment>.<field>``: a segment's field for every aircraft, ``mission.<segment>.<aircraft>.<field>``
  for one (setting a speed drops that entry's ``flight_path_deg`` check, which the new speeds would fail; link
  ``climb_speed_mps`` to ``forward_speed_mps`` with exponent 1 to hold the flight-path angle);
* ``[config.]<section>.<key>[.<subkey>]``: a campaign-configuration field, e.g. ``resolution.n_psi``.
"""

from __future__ import annotations

import copy
import hashlib
import itertools
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from nps.app.config import Campaign, ConfigError, fill_defaults, load_campaign, load_schema, read_yaml, validate

# Resolution of the preview fidelity (docs/reference/studies.md "Preview fidelity"): a 1.5 deg azimuth step
# (240 steps: a whole number per blade passage for 2 to 6 blades; BVI needs it), 24 radial stations, 3 wake
# revolutions, the campaign's 1024 observer samples per revolution and observer sets. Its error against the
# campaign resolution on the bundled study: docs/reference/studies.md.
PREVIEW_RESOLUTION = {"n_psi": 240, "n_r": 24, "wake_revolutions": 3, "samples_per_rev": 1024}
SPEED_FIELDS = ("forward_speed_mps", "climb_speed_mps")
# trade-table columns (nps.app.trade.case_row) a variable label must not take
RESERVED_COLUMNS = ("design", "aircraft", "segment", "segment_name", "power_W", "validity_warnings", "pareto")
RESERVED_PATTERN = r"[a-z0-9_]*(max_\w+|_(thrust_N|torque_Nm|power_W|ct|ct_sigma|omega_rad_s|tip_speed_mps|tip_mach))"


@dataclass(frozen=True)
class Variable:
    """A design variable: its ``path``, trade-table ``label``, ``values`` and the base campaign's value."""

    path: str
    label: str
    values: tuple
    base_value: Any


@dataclass(frozen=True)
class Design:
    """One variant: ``id`` (digest of ``values``), ``values`` (label → value of each variable),
    ``assignment`` (path → value of every field set, linked ones included) and its validated campaign."""

    id: str
    values: dict
    assignment: dict
    campaign: Campaign


@dataclass(frozen=True)
class DesignStudy:
    """A validated study: its spec (schema defaults filled), base campaign, variables, the variants kept
    and the ones a constraint dropped (``(values, constraint name)``)."""

    name: str
    file: str
    spec: dict
    base: Campaign
    variables: tuple[Variable, ...]
    designs: tuple[Design, ...]
    dropped: tuple = field(default=())

    @property
    def aircraft(self) -> list[str]:
        return list(self.base.aircraft)

    @property
    def segments(self) -> list[str]:
        return list(self.base.segments)

    def design(self, design_id: str) -> Design:
        return next(d for d in self.designs if d.id == design_id)


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


class _Documents:
    """The documents of a campaign as written (config, aircraft, mission) and filled (the campaign), with
    get/set by design path."""

    def __init__(self, config: dict, aircraft: dict, mission: dict, filled: Campaign):
        self.config, self.aircraft, self.mission, self.filled = config, aircraft, mission, filled

    def _locate(self, path: str, filled: bool):
        """(container, key) of each place ``path`` names, in the written (or filled) documents."""
        parts = path.split(".")
        campaign = self.filled
        if parts[0] == "aircraft" and len(parts) >= 3:
            name = parts[1]
            if name not in campaign.aircraft:
                raise KeyError(f"aircraft '{name}' is not in the campaign ({list(campaign.aircraft)})")
            node = campaign.aircraft[name] if filled else self.aircraft[name]
            rest = parts[2:]
            if rest[0] == "rotors":
                if len(rest) < 3:
                    raise KeyError("expected aircraft.<aircraft>.rotors.<rotor>.<field>")
                node = next((r for r in node["rotors"] if r["name"] == rest[1]), None)
                if node is None:
                    raise KeyError(f"rotor '{rest[1]}' is not one of {campaign.rotor_names(name)}")
                rest = rest[2:]
            return [_descend(node, rest, filled)]
        if parts[0] == "mission" and len(parts) >= 3:
            segments = (campaign.mission if filled else self.mission)["segments"]
            segment = next((s for s in segments if s["id"] == parts[1]), None)
            if segment is None:
                raise KeyError(f"segment '{parts[1]}' is not in the mission ({[s['id'] for s in segments]})")
            names = [parts[2]] if parts[2] in segment["aircraft"] else list(campaign.aircraft)
            rest = parts[3:] if parts[2] in segment["aircraft"] else parts[2:]
            if len(rest) != 1:
                raise KeyError("expected mission.<segment>[.<aircraft>].<field>")
            return [_descend(segment["aircraft"][name], rest, filled) for name in names]
        parts = parts[1:] if parts[0] == "config" else parts
        if parts[0] not in load_schema("config")["properties"] or len(parts) < 2:
            raise KeyError("expected aircraft..., mission... or a configuration section and key")
        return [_descend(campaign.config if filled else self.config, parts, filled)]

    def get(self, path: str) -> Any:
        container, key = self._locate(path, filled=True)[0]
        return container[key]

    def set(self, path: str, value: Any) -> None:
        for container, key in self._locate(path, filled=False):
            container[key] = value
            if key in SPEED_FIELDS:
                container.pop("flight_path_deg", None)


def _descend(node: Any, keys: list[str], filled: bool) -> tuple[dict, str]:
    """(container, last key) of ``keys`` below ``node``; written documents get missing sections created,
    filled ones must hold every key."""
    for key in keys[:-1]:
        if not isinstance(node, dict) or (filled and key not in node):
            raise KeyError(f"no field '{key}'")
        node = node.setdefault(key, {})
    if not isinstance(node, dict) or (filled and keys[-1] not in node):
        raise KeyError(f"no field '{keys[-1]}'")
    return node, keys[-1]


def _variable_values(spec: dict, base_value: Any, where: str) -> tuple:
    if "values" in spec:
        return tuple(_clean(v) for v in spec["values"])
    if not isinstance(base_value, (int, float)) or isinstance(base_value, bool):
        raise ConfigError(f"{where}: scale and range need a numeric field, the base value is {base_value!r}")
    if "scale" in spec:
        values = [base_value * s for s in spec["scale"]]
        return tuple(_clean(round(v) if isinstance(base_value, int) else v) for v in values)
    low, high = spec["range"]["low"], spec["range"]["high"]
    if not low < high:
        raise ConfigError(f"{where}.range: expected low < high, got [{low}, {high}]")
    values = np.linspace(low, high, spec["range"].get("num", 2))
    return tuple(_clean(int(round(v)) if spec["range"]["integer"] else v) for v in values)


def _latin_hypercube(variables: list[Variable], specs: list[dict], samples: int, seed: int) -> list[tuple]:
    """``samples`` points, one per stratum of every variable (ranges: uniform within the stratum; value lists:
    the stratum's element), permutations from ``numpy.random.default_rng(seed)``."""
    rng = np.random.default_rng(seed)
    columns = []
    for variable, spec in zip(variables, specs):
        u = (rng.permutation(samples) + rng.random(samples)) / samples
        if "range" in spec:
            low, high = spec["range"]["low"], spec["range"]["high"]
            values = low + u * (high - low)
            columns.append([_clean(int(round(v)) if spec["range"]["integer"] else v) for v in values])
        else:
            columns.append([variable.values[min(int(x * len(variable.values)), len(variable.values) - 1)] for x in u])
    return list(zip(*columns))


def _combinations(variables: list[Variable], specs: list[dict], design: dict, where: str) -> list[tuple]:
    kind = design["kind"]
    if kind == "factorial":
        return list(itertools.product(*(v.values for v in variables)))
    if kind == "one_at_a_time":
        base = tuple(v.base_value for v in variables)
        points = [base]
        for index, variable in enumerate(variables):
            points += [base[:index] + (value,) + base[index + 1:] for value in variable.values]
        return list(dict.fromkeys(points))
    if "samples" not in design:
        raise ConfigError(f"{where}: design.samples: required with kind 'latin_hypercube'")
    return _latin_hypercube(variables, specs, design["samples"], design["seed"])


def _base_campaign(spec: dict, study_file: Path, root: Path, resolution: Mapping | None) -> tuple[Campaign, _Documents]:
    config_file = root / spec["base"]["config"]
    if not config_file.is_file():
        raise ConfigError(f"{study_file}: base.config: expected a campaign configuration file, {config_file} does not exist")
    written = read_yaml(config_file)
    campaign_section = written.setdefault("campaign", {}) if isinstance(written, dict) else {}
    for key in ("aircraft", "segments"):
        if key in spec["base"]:
            campaign_section[key] = list(spec["base"][key])
    if spec["fidelity"] == "preview" and isinstance(written, dict):
        written["resolution"] = {**written.get("resolution", {}), **PREVIEW_RESOLUTION}
    if resolution and isinstance(written, dict):
        written["resolution"] = {**written.get("resolution", {}), **resolution}
    campaign = load_campaign(written, config_file, root)
    config_dir = root / campaign.config["campaign"]["config_dir"]
    aircraft = {name: read_yaml(config_dir / "aircraft" / f"{name}.yaml") for name in campaign.aircraft}
    mission = read_yaml(config_dir / "missions" / f"{campaign.config['campaign']['mission']}.yaml")
    return campaign, _Documents(written, aircraft, mission, campaign)


def _design(documents: _Documents, assignment: dict, config_file: Path, root: Path) -> Campaign:
    variant = _Documents(copy.deepcopy(documents.config), copy.deepcopy(documents.aircraft),
                         copy.deepcopy(documents.mission), documents.filled)
    for path, value in assignment.items():
        variant.set(path, value)
    return load_campaign(variant.config, config_file, root, {"aircraft": variant.aircraft, "mission": variant.mission})


def _constraint_value(documents: _Documents, assignment: dict, terms: Mapping[str, float]) -> float:
    return math.prod(float(assignment[p] if p in assignment else documents.get(p)) ** e for p, e in terms.items())


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


def _study_document(path: Path, seen: tuple = ()) -> Any:
    """A study file's content with the fields of the study it ``extends`` (same directory) under its own."""
    document = read_yaml(path)
    if not isinstance(document, dict) or "extends" not in document:
        return document
    parent = path.with_name(f"{document['extends']}.yaml")
    if not parent.is_file() or parent in seen:
        raise ConfigError(f"{path}: extends: expected another study's name in {path.parent} (no cycle), "
                          f"got '{document['extends']}'")
    merged = {**_study_document(parent, seen + (path,)), **document}
    merged.pop("extends")
    return merged


def load_study(path: str | Path, root: str | Path = ".", resolution: Mapping | None = None) -> DesignStudy:
    """Read, validate and expand a study file: every variant validated before anything runs; errors name
    the study file and the field (or the variant's campaign file) and what was expected. ``resolution``
    (optional) overrides fields of the variants' ``resolution`` section after the fidelity preset."""
    path, root = Path(path), Path(root)
    schema = load_schema("study")
    spec = fill_defaults(validate(_study_document(path), schema, path), schema)
    if "variables" not in spec:
        raise ConfigError(f"{path}: variables: required field is missing (here or in the study it extends)")
    if spec["name"] != path.stem:
        raise ConfigError(f"{path}: name: expected the file stem '{path.stem}', got '{spec['name']}'")
    base, documents = _base_campaign(spec, path, root, resolution)
    if "certification" in spec["products"] and "certification" not in base.config:
        raise ConfigError(f"{path}: products: 'certification' needs the certification section in {spec['base']['config']}")
    if "footprint" in spec["products"] and ("footprint" not in base.config or "profile" not in base.mission):
        raise ConfigError(f"{path}: products: 'footprint' needs the footprint section in {spec['base']['config']} "
                          "and a profile in the mission")
    unknown = [name for name in spec["observer_sets"] if name not in base.config["observer_sets"]]
    if unknown:
        raise ConfigError(f"{path}: observer_sets: {unknown} are not observer sets of {spec['base']['config']} "
                          f"({list(base.config['observer_sets'])})")
    config_file = root / spec["base"]["config"]
    variables, specs = [], spec["variables"]
    for index, item in enumerate(specs):
        where = f"{path}: variables[{index}]"
        try:
            base_value = documents.get(item["path"])
        except KeyError as error:
            raise ConfigError(f"{where}.path: {error.args[0]}; got '{item['path']}'") from None
        label = item["label"] if "label" in item else ".".join(item["path"].split(".")[-2:])
        variables.append(Variable(item["path"], label, _variable_values(item, base_value, where), _clean(base_value)))
    labels = [v.label for v in variables]
    if len(set(labels)) < len(labels):
        raise ConfigError(f"{path}: variables: expected unique labels, got {labels}")
    for index, label in enumerate(labels):
        if "." not in label and (label in RESERVED_COLUMNS or re.fullmatch(RESERVED_PATTERN, label)):
            raise ConfigError(f"{path}: variables[{index}].label: '{label}' is a trade-table column; expected another "
                              "name (e.g. one with a '.', like the default main.omega_rad_s)")
    by_path = {v.path: v for v in variables}
    for index, link in enumerate(spec["linked"]):
        if link["follows"] not in by_path:
            raise ConfigError(f"{path}: linked[{index}].follows: expected the path of a variable, got '{link['follows']}'")
        try:
            documents.get(link["path"])
        except KeyError as error:
            raise ConfigError(f"{path}: linked[{index}].path: {error.args[0]}; got '{link['path']}'") from None
    for index, constraint in enumerate(spec["constraints"]):
        for term in constraint["terms"]:
            try:
                documents.get(term)
            except KeyError as error:
                raise ConfigError(f"{path}: constraints[{index}].terms: {error.args[0]}; got '{term}'") from None
    designs, dropped = {}, []
    for point in _combinations(variables, specs, spec["design"], str(path)):
        values = dict(zip(labels, point))
        assignment = {v.path: value for v, value in zip(variables, point)}
        for link in spec["linked"]:
            leader = by_path[link["follows"]]
            factor = (assignment[leader.path] / leader.base_value) ** link["exponent"]
            assignment[link["path"]] = _clean(documents.get(link["path"]) * factor)
        violated = [c["name"] for c in spec["constraints"]
                    if not c.get("min", -math.inf) <= _constraint_value(documents, assignment, c["terms"]) <= c.get("max", math.inf)]
        if violated:
            dropped.append((values, violated[0]))
            continue
        identifier = design_id(values)
        if identifier not in designs:
            try:
                campaign = _design(documents, assignment, config_file, root)
            except ConfigError as error:
                raise ConfigError(f"{path}: variant {values}: {error}") from None
            designs[identifier] = Design(identifier, values, assignment, campaign)
    if not designs:
        raise ConfigError(f"{path}: constraints: every variant is dropped ({len(dropped)} variants)")
    return DesignStudy(spec["name"], str(path), spec, base, tuple(variables), tuple(designs.values()), tuple(dropped))
