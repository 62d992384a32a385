"""Core: what every model shares — coordinate frames, the atmosphere and the numba kernel options.

Layer 0 (docs/reference/architecture.md): imports nothing else of NPS.

- :mod:`nps.core.frames`: ground G, body B and hub H frames, rotations (docs/reference/conventions.md).
- :mod:`nps.core.atmosphere`: ISA state and ISO 9613-1 atmospheric absorption.
- :mod:`nps.core.jit`: :func:`~nps.core.jit.kernel`, the one way NPS compiles a numba kernel.
- :mod:`nps.core.solvers`: the root finders of the trims, with their named tolerances.
"""

from typing import TYPE_CHECKING

from nps.core.lazy import lazy_face

if TYPE_CHECKING:  # imported on first use (nps.core.lazy): a job imports only the modules its stage runs
    from nps.core.atmosphere import AtmosphereState, absorption_db_per_m, isa
    from nps.core.frames import observer_direction, rot_x, rot_y, rot_z
    from nps.core.jit import kernel, prange
    from nps.core.solvers import ConvergenceError, forward_difference_jacobian, limited_secant, newton, newton_fd, secant

__getattr__, __dir__, __all__ = lazy_face(__name__, {
    "nps.core.atmosphere": ("AtmosphereState", "absorption_db_per_m", "isa"),
    "nps.core.frames": ("observer_direction", "rot_x", "rot_y", "rot_z"),
    "nps.core.jit": ("kernel", "prange"),
    "nps.core.solvers": ("ConvergenceError", "forward_difference_jacobian", "limited_secant", "newton", "newton_fd",
                         "secant"),
})
