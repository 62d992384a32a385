"""The one error of :mod:`nps.wopwop`: a bad or unsupported PSU-WOPWOP file, in one line."""

from __future__ import annotations


class WopwopError(ValueError):
    """A PSU-WOPWOP file NPS cannot use. The message is one line: the file, then the byte offset
    (binary files) or the namelist block and field (text files), what was found and what was expected."""
