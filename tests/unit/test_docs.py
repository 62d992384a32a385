"""Documentation as reference: no page titled by an issue number, no lab-notebook wording, a
changelog with an Unreleased section, and every relative markdown link pointing to a file that exists."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md")) + [ROOT / "README.md", ROOT / "CHANGELOG.md"]
LINKED_PAGES = sorted(DOCS.rglob("*.md")) + [ROOT / "README.md"]

HEADING = re.compile(r"^\s{0,3}#{1,6}\s+(?P<title>.*)$")
ISSUE_IN_TITLE = re.compile(r"\bissues?\s*#?\s*\d+", re.IGNORECASE)
FORBIDDEN = ("session", "this revision")  # "since this revision" contains the second
LINK = re.compile(r"!?\[[^\]]*\]\((?P<target>[^)\s]+)(?:\s+\"[^\"]*\")?\)")
FENCE = re.compile(r"^\s*(```|~~~)")


def _prose_lines(path: Path) -> list[tuple[int, str]]:
    """(line number, text) of the lines outside fenced code blocks."""
    lines, fenced = [], False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            lines.append((number, line))
    return lines


def _name(path: Path) -> str:
    return str(path.relative_to(ROOT))


@pytest.mark.parametrize("path", PAGES, ids=_name)
def test_no_heading_names_an_issue(path):
    assert path.exists(), f"{_name(path)} is missing"
    bad = [f"{_name(path)}:{n}: {line.strip()}" for n, line in _prose_lines(path)
           if (m := HEADING.match(line)) and ISSUE_IN_TITLE.search(m.group("title"))]
    assert not bad, "headings titled by an issue number:\n" + "\n".join(bad)


@pytest.mark.parametrize("path", PAGES, ids=_name)
def test_no_lab_notebook_words(path):
    text = path.read_text(encoding="utf-8").lower()
    bad = [f"{_name(path)}:{text[:text.index(word)].count(chr(10)) + 1}: '{word}'"
           for word in FORBIDDEN if word in text]
    assert not bad, "words that belong to a lab notebook, not to reference docs:\n" + "\n".join(bad)


def test_changelog_has_an_unreleased_section():
    changelog = ROOT / "CHANGELOG.md"
    assert changelog.exists(), "CHANGELOG.md is missing"
    headings = [m.group("title").strip() for _, line in _prose_lines(changelog) if (m := HEADING.match(line))]
    assert any(re.fullmatch(r"\[?Unreleased\]?", h, re.IGNORECASE) for h in headings), headings


@pytest.mark.parametrize("path", LINKED_PAGES, ids=_name)
def test_relative_links_point_to_existing_files(path):
    broken = []
    for number, line in _prose_lines(path):
        for match in LINK.finditer(line):
            target = match.group("target")
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.IGNORECASE) or target.startswith("#"):
                continue  # URL, mailto or an anchor in the same page
            file_part = target.split("#", 1)[0]
            if not (path.parent / file_part).exists():
                broken.append(f"{_name(path)}:{number}: {target}")
    assert not broken, "links to files that do not exist:\n" + "\n".join(broken)
