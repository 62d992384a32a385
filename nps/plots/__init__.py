"""Figures: one module per figure family; every function takes arrays or tables and a path."""
