"""Fortran namelist text, as PSU-WOPWOP's case files use it: parse it into groups, write groups back.

Grammar (Fortran 2008 §10.11 namelist input, the subset PSU-WOPWOP's case files use):

- A group starts at ``&name`` and ends at ``/`` or ``&end``; between groups only blanks and comments.
- Inside a group: ``name = values`` items, ``name(i) = values`` for one array element (i ≥ 1; a list after it
  fills i, i+1, ...). Names are case-insensitive (returned lower case).
- Values are separated by commas and/or blanks and may span lines: quoted strings ('...' or "...", a doubled
  quote inside stands for one), logicals (.true. .false. T F .t. .f. true false, any case), integers, reals
  (``1.5``, ``-2.``, ``.5``, Fortran exponents ``1.0d0``, ``1.0E-3``, ``1e+3``), repeat counts ``3*0.0``.
- ``!`` starts a comment to the end of the line (outside quotes).

Refused, one line ``path: line N: &group: field: what, expected`` (:class:`~nps.wopwop.errors.WopwopError`):
unquoted text (PSU-WOPWOP asks for quoted strings, Main.f90 CheckString), null values (``a = 1,,2``, ``3*``),
array sections and derived-type components, a field assigned twice (Fortran would keep the last value; a
repeated name in a case file is a mistake NPS does not guess about), an unterminated string or group, text
outside a group.

A parsed value is a ``str``, ``bool``, ``int`` or ``float``; several values, or any indexed assignment, give a
``tuple`` (``None`` at indices never assigned).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Iterable, Union

import numpy as np

from nps.wopwop.errors import WopwopError

Scalar = Union[str, bool, int, float]
Value = Union[Scalar, tuple]

_INT = re.compile(r"[+-]?\d+\Z")
_REAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?\Z")
_LOGICAL = {".true.": True, ".false.": False, ".t.": True, ".f.": False, "t": True, "f": False,
            "true": True, "false": False}
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*")
_INDEX = re.compile(r"\(\s*(\d+)\s*\)")
_DELIMITERS = " \t\r\n,/!&=()'\""


@dataclass(frozen=True)
class Group:
    """One namelist group. ``name``: without '&' (lower case when parsed); ``fields``: values by field name (lower
    case when parsed), in file order; ``line``: 1-based line of the '&name'."""

    name: str
    fields: dict = field(default_factory=dict)
    line: int = field(default=0, compare=False)


class _Text:
    """A cursor over the namelist text that knows its line number."""

    def __init__(self, text: str, path: str):
        self.text, self.path, self.pos, self.line = text, path, 0, 1
        self.group = "?"

    def fail(self, what: str, field_name: str | None = None) -> WopwopError:
        where = f"&{self.group}: " + (f"{field_name}: " if field_name else "")
        return WopwopError(f"{self.path}: line {self.line}: {where}{what}")

    def peek(self) -> str:
        return self.text[self.pos] if self.pos < len(self.text) else ""

    def advance(self, n: int = 1) -> str:
        chunk = self.text[self.pos:self.pos + n]
        self.line += chunk.count("\n")
        self.pos += n
        return chunk

    def skip_blanks(self, commas: bool = False) -> None:
        """Skip blanks, line ends and comments (and commas when ``commas``)."""
        while self.pos < len(self.text):
            ch = self.text[self.pos]
            if ch == "!":
                end = self.text.find("\n", self.pos)
                self.advance((len(self.text) if end < 0 else end) - self.pos)
            elif ch in " \t\r\n" or (commas and ch == ","):
                self.advance()
            else:
                return

    def word(self) -> str:
        """The run of characters up to the next delimiter."""
        start = self.pos
        while self.pos < len(self.text) and self.text[self.pos] not in _DELIMITERS:
            self.pos += 1
        return self.text[start:self.pos]

    def quoted(self, field_name: str) -> str:
        """A quoted string starting at the cursor; a doubled quote stands for one."""
        quote, out = self.advance(), []
        while True:
            ch = self.peek()
            if ch in ("", "\n"):
                raise self.fail(f"unterminated string {quote}{''.join(out)[:40]}, expected a closing {quote} on the "
                                "same line", field_name)
            self.advance()
            if ch == quote:
                if self.peek() != quote:
                    return "".join(out)
                self.advance()
            out.append(ch)

    def at_group_end(self) -> bool:
        if self.peek() == "/":
            return True
        return (self.peek() in "&$" and self.text[self.pos + 1:self.pos + 4].lower() == "end"
                and not _NAME.match(self.text[self.pos + 4:self.pos + 5]))

    def starts_item(self) -> bool:
        """A name followed by '=' or '(' (the next item), not a value."""
        match = _NAME.match(self.text, self.pos)
        if not match:
            return False
        rest = self.text[match.end():match.end() + 200].lstrip(" \t")
        return rest[:1] in ("=", "(")


def _scalar(token: str, text: _Text, field_name: str) -> Scalar:
    """A non-string value token."""
    if _INT.match(token):
        return int(token)
    if _REAL.match(token):
        return float(token.replace("d", "e").replace("D", "e"))
    logical = _LOGICAL.get(token.lower())
    if logical is not None:
        return logical
    raise text.fail(f"unquoted text '{token[:40]}', expected a quoted string, a number or a logical (.true./.false.)",
                    field_name)


def _values(text: _Text, field_name: str) -> list[Scalar]:
    """The values of one item, up to the next item or the end of the group."""
    values: list[Scalar] = []
    while True:
        text.skip_blanks()
        if text.peek() == ",":
            if not values:
                raise text.fail("null value (nothing before ','), expected a value", field_name)
            text.advance()
            text.skip_blanks()
            if text.peek() == ",":
                raise text.fail("null value (',,'), expected a value between the commas", field_name)
        ch = text.peek()
        if ch == "" or text.at_group_end() or ch in "&$" or (values and text.starts_item()):
            break
        values.extend(_one_value(text, field_name))
    if not values:
        raise text.fail("no value after '=', expected at least one value", field_name)
    return values


def _one_value(text: _Text, field_name: str) -> list[Scalar]:
    """One value token, a repeat ``r*value`` giving r copies."""
    if text.peek() in "'\"":
        return [text.quoted(field_name)]
    token = text.word()
    if not token:
        raise text.fail(f"unexpected '{text.peek()}', expected a value", field_name)
    if "*" not in token:
        return [_scalar(token, text, field_name)]
    count, _, rest = token.partition("*")
    if not count.isdigit() or int(count) < 1:
        raise text.fail(f"repeat count '{count}*', expected a positive integer before '*'", field_name)
    if rest:
        return [_scalar(rest, text, field_name)] * int(count)
    if text.peek() in "'\"":
        return [text.quoted(field_name)] * int(count)
    raise text.fail(f"null repeated value '{token}', expected a value after '*'", field_name)


def _item(text: _Text, assigned: dict) -> None:
    """One ``name = values`` or ``name(i) = values`` item into ``assigned`` (name -> (index | None, values))."""
    match = _NAME.match(text.text, text.pos)
    if not match and text.peek() in "&$":
        raise text.fail(f"a new group '{text.text[text.pos:text.pos + 20].split()[0]}' starts before this one is "
                        "closed, expected '/' first")
    if not match:
        raise text.fail(f"unexpected text '{text.text[text.pos:text.pos + 20].splitlines()[0]}', expected "
                        "'name = value' or the group end '/'")
    name = text.advance(match.end() - text.pos).lower()
    text.skip_blanks()
    index = None
    if text.peek() == "(":
        sub = _INDEX.match(text.text, text.pos)
        if not sub or int(sub.group(1)) < 1:
            raise text.fail("array section or bad index, expected a single index (i) with i >= 1", name)
        index = int(sub.group(1))
        text.advance(sub.end() - text.pos)
        text.skip_blanks()
    if text.peek() != "=":
        raise text.fail(f"'{text.peek() or 'end of file'}' after the name, expected '='", name)
    text.advance()
    values = _values(text, name)
    previous = assigned.setdefault(name, [])
    if (index is None and previous) or any(i is None for i, _ in previous):
        raise text.fail("assigned twice in this group, expected one assignment per field", name)
    previous.append((index, values))


def _collect(assigned: dict, text: _Text) -> dict:
    """Field values: a scalar for one plain value, else a tuple by index (None where never assigned)."""
    fields = {}
    for name, items in assigned.items():
        if len(items) == 1 and items[0][0] is None:
            values = items[0][1]
            fields[name] = values[0] if len(values) == 1 else tuple(values)
            continue
        slots: dict[int, Scalar] = {}
        for start, values in items:
            for offset, value in enumerate(values):
                if start + offset in slots:
                    raise text.fail(f"element ({start + offset}) assigned twice, expected one assignment per "
                                    "element", name)
                slots[start + offset] = value
        fields[name] = tuple(slots.get(i) for i in range(1, max(slots) + 1))
    return fields


def _group(text: _Text) -> Group:
    """The group starting at the cursor ('&' or '$')."""
    line = text.line
    text.advance()
    match = _NAME.match(text.text, text.pos)
    if not match:
        raise text.fail("'&' without a group name, expected '&name'")
    name = text.advance(match.end() - text.pos).lower()
    text.group = name
    if name == "end":
        raise text.fail("'&end' outside a group, expected '&name' first")
    assigned: dict = {}
    while True:
        text.skip_blanks(commas=True)
        if text.peek() == "":
            raise text.fail(f"the file ends inside &{name} (opened at line {line}), expected '/' to close it")
        if text.at_group_end():
            text.advance(1 if text.peek() == "/" else 4)
            return Group(name, _collect(assigned, text), line)
        _item(text, assigned)


def parse_namelist(text: str, path: str) -> tuple[Group, ...]:
    """The groups of a namelist text, in file order. ``path``: the file named in error messages."""
    cursor = _Text(text, str(path))
    groups = []
    while True:
        cursor.skip_blanks()
        ch = cursor.peek()
        if ch == "":
            return tuple(groups)
        if ch not in "&$":
            cursor.group = groups[-1].name if groups else "?"
            snippet = cursor.text[cursor.pos:cursor.pos + 30].splitlines()[0]
            raise WopwopError(f"{cursor.path}: line {cursor.line}: text outside a namelist group '{snippet}', "
                              "expected '&name' or a '!' comment")
        groups.append(_group(cursor))


def format_value(value: Value) -> str:
    """A value as namelist text that :func:`parse_namelist` reads back equal (floats with ``repr`` precision);
    numpy scalars are written as the Python scalars they equal."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bool):
        return ".true." if value else ".false."
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if value != value or value in (float("inf"), float("-inf")):
            raise ValueError(f"{value} has no namelist spelling")
        return repr(value)
    if isinstance(value, str):
        if "\n" in value or "\r" in value:
            raise ValueError(f"a namelist string cannot hold a line break: {value!r}")
        return "'" + value.replace("'", "''") + "'"
    if isinstance(value, tuple) and value and None not in value:
        return ", ".join(format_value(v) for v in value)
    raise ValueError(f"{value!r} is not a namelist value (a scalar or a non-empty tuple)")


def format_namelist(groups: Iterable[Group]) -> str:
    """Namelist text of ``groups``, one field per line; tuples with unassigned (None) elements are written one
    element per line as ``name(i) = value``. Names are written as given."""
    lines = []
    for group in groups:
        lines.append(f"&{group.name}")
        for name, value in group.fields.items():
            if isinstance(value, tuple) and None in value:
                lines.extend(f"  {name}({i}) = {format_value(v)}" for i, v in enumerate(value, 1) if v is not None)
            else:
                lines.append(f"  {name} = {format_value(value)}")
        lines.append("/")
    return "\n".join(lines) + "\n"
