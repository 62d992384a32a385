"""NPS: noise prediction system for the conceptual design of rotorcraft.

Frames, units and artifact columns are defined in ``docs/reference/conventions.md``.
"""

__version__ = "0.1.0"
