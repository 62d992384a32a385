"""HTML pages of the report: tables a reader can copy (no pictures of tables), self-contained fragments.

Each page is one ``<div class="nps-page">`` with its own scoped style, no ``<html>`` or ``<head>``: the
same file opens on its own in a browser, inside Snakemake's report viewer, and embedded in the report's
front page (``workflow/report/workflow.rst`` inserts it). Directions are named in the map convention of
docs/reference/conventions.md ("Observer azimuth"), the straight-down point once
(:func:`nps.plots.maps.direction_name`).
"""

from __future__ import annotations

import html
import os
from pathlib import Path
from typing import Mapping, Sequence

import pandas as pd

STYLE = """<style>
.nps-page { font-family: sans-serif; font-size: 13px; }
.nps-page table { border-collapse: collapse; margin: 0.4em 0 1.2em 0; }
.nps-page th, .nps-page td { border: 1px solid #bbb; padding: 2px 6px; vertical-align: top; }
.nps-page th { background: #eee; text-align: left; }
.nps-page td.num { text-align: right; white-space: nowrap; }
.nps-page td.bad { background: #fcbba1; }
.nps-page td.good { background: #c7e9c0; }
.nps-page .scroll { overflow-x: auto; max-width: 100%; }
.nps-page .note { color: #444; }
.prose:has(.nps-page) { max-width: 75rem; }
</style>"""
# the last rule widens the column of Snakemake's report front page that holds an inserted page (32rem otherwise)


def _cell(value, css: str = "") -> str:
    if isinstance(value, float):
        text, css = f"{value:.1f}", css or "num"
    else:
        text = html.escape(str(value)).replace("\n", "<br>")
    return f'<td class="{css}">{text}</td>' if css else f"<td>{text}</td>"


def html_table(table: pd.DataFrame, columns: Mapping[str, str], classes: Mapping[str, Sequence[str]] | None = None) -> str:
    """An HTML table of ``table``'s ``columns`` (column → header), floats to 0.1; ``classes``: column →
    one CSS class per row (e.g. ``good``/``bad`` for margins)."""
    classes = dict(classes or {})
    head = "".join(f"<th>{html.escape(h)}</th>" for h in columns.values())
    rows = []
    for i, (_, row) in enumerate(table.iterrows()):
        cells = "".join(_cell(row[c], classes[c][i] if c in classes else "") for c in columns)
        rows.append(f"<tr>{cells}</tr>")
    body = "\n".join(rows)  # a row per line: the report's reStructuredText parser limits the line length
    return f'<div class="scroll"><table><thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table></div>'


def write_page(title: str, sections: Sequence[tuple[str, str]], path: str | os.PathLike, intro: str = "") -> Path:
    """Write an HTML fragment page: ``title``, an ``intro`` paragraph (text), then ``sections`` (heading,
    HTML body) in order; returns the path."""
    body = [f'<div class="nps-page">{STYLE}', '<meta charset="utf-8">', f"<h2>{html.escape(title)}</h2>"]
    if intro:
        body.append(f'<p class="note">{html.escape(intro)}</p>')
    for heading, section in sections:
        body.append(f"<h3>{html.escape(heading)}</h3>\n{section}")
    body.append("</div>")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(body) + "\n", encoding="utf-8")
    return path
