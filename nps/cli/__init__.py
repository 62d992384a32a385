"""Stand-alone command-line entry points, one module per stage (``python -m nps <stage>``)."""
