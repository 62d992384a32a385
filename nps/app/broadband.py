"""The broadband model a campaign's ``models.broadband`` names, per rotor: what the metrics, source-hemisphere
and summary stages read from their params. Kept apart from :mod:`nps.app.config` (which re-exports it), so that
those jobs import neither the configuration code nor its YAML and JSON-schema libraries: the configuration is
validated once, when the workflow starts, and the jobs get the validated values.
"""

from __future__ import annotations

BROADBAND_MODELS = ("pegg", "bpm", "none", "auto")


def broadband_model(value) -> str:
    """The broadband model named by a ``models.broadband`` value: ``pegg``, ``bpm``, ``none`` or ``auto`` (per
    rotor, :func:`rotor_broadband_models`); the boolean spelling of earlier configurations maps true → ``pegg``, false → ``none``."""
    if value is True or value is False:
        return "pegg" if value else "none"
    if value not in BROADBAND_MODELS:
        raise ValueError(f"models.broadband: expected one of {list(BROADBAND_MODELS)} (or true/false), got {value!r}")
    return str(value)


BROADBAND_AUTO = "auto"  # per rotor: BPM outside Pegg's data range, Pegg inside (docs/decisions, broadband auto)


def rotor_broadband_models(value, trim, rotors) -> dict[str, str]:
    """Rotor → broadband model (``pegg``, ``bpm``, ``none``) of one aircraft in one segment: the model
    ``value`` names (:func:`broadband_model`) for every rotor, or for ``auto`` (:data:`BROADBAND_AUTO`)
    BPM for each rotor of the trim table ``trim`` outside Pegg's data range
    (:func:`nps.app.validity.pegg_range_notes`) and Pegg for the others."""
    if value != BROADBAND_AUTO:
        return {name: broadband_model(value) for name in rotors}
    from nps.app.validity import pegg_range_notes

    return {name: "bpm" if pegg_range_notes(trim, [name]) else "pegg" for name in rotors}
