"""Figures: one module per figure family; every function takes arrays or tables and a path."""

from __future__ import annotations

from pathlib import Path


def save_figure(fig, path, dpi: int = 110) -> Path:
    """Write ``fig`` to ``path`` (parents created), close it and return the path."""
    import matplotlib.pyplot as plt

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def segment_title(segment: str, name: str | None = None) -> str:
    """A segment as figure titles name it: its id and, when known, its mission name ("seg3, 6 deg descent (BVI)")."""
    return f"{segment}, {name}" if name else segment


def hemisphere_title(radius_R: float | None = None, radius_m: float | None = None) -> str:
    """The hemisphere as figure titles name it, its radius in reference-rotor radii and metres
    ("hemisphere of radius 10 R = 76.2 m"); "hemisphere" when the radius is not given."""
    if radius_R is None or radius_m is None:
        return "hemisphere"
    return f"hemisphere of radius {radius_R:g} R = {radius_m:.1f} m"
