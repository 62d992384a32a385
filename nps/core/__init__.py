"""Core: what every model shares — coordinate frames, the atmosphere and the numba kernel options.

Layer 0 (docs/reference/architecture.md): imports nothing else of NPS.

- :mod:`nps.core.frames`: ground G, body B and hub H frames, rotations (docs/reference/conventions.md).
- :mod:`nps.core.atmosphere`: ISA state and ISO 9613-1 atmospheric absorption.
- :mod:`nps.core.jit`: :func:`~nps.core.jit.kernel`, the one way NPS compiles a numba kernel.
- :mod:`nps.core.solvers`: the root finders of the trims, with their named tolerances.
"""

from nps.core.atmosphere import AtmosphereState, absorption_db_per_m, isa
from nps.core.frames import observer_direction, rot_x, rot_y, rot_z
from nps.core.jit import kernel, prange
from nps.core.solvers import ConvergenceError, forward_difference_jacobian, limited_secant, newton, newton_fd, secant

__all__ = ["AtmosphereState", "absorption_db_per_m", "isa", "observer_direction", "rot_x", "rot_y", "rot_z",
           "kernel", "prange", "ConvergenceError", "forward_difference_jacobian", "limited_secant", "newton",
           "newton_fd", "secant"]
