"""Wakes: the tip vortex, the Beddoes prescribed wake, the free wake of all rotors, BVI loads.

Layer 2 (beside :mod:`nps.noise`, which it does not import): imports :mod:`nps.rotor` and :mod:`nps.core`.

- :mod:`nps.wake.vortex`: the vortex itself, shared by both wakes — core radius and growth, Vatistas
  profile, Betz roll-up structure, Biot–Savart kernels of straight segments.
- :mod:`nps.wake.prescribed`: Beddoes' prescribed tip-vortex geometry (thesis ch. 5).
- :mod:`nps.wake.free`: the free-vortex tip wake of every rotor of an aircraft, relaxed together.
- :mod:`nps.wake.bvi`: the wake's induced velocity at the blades added to the BET loads.
- :mod:`nps.wake.interaction`: every rotor loaded in all rotors' free wakes.
"""

from typing import TYPE_CHECKING

from nps.core.lazy import lazy_face

if TYPE_CHECKING:  # imported on first use (nps.core.lazy): a job imports only the modules its stage runs
    from nps.wake.prescribed import WAKE_COLUMNS, WakeModel
    from nps.wake.vortex import VortexModel

__getattr__, __dir__, __all__ = lazy_face(__name__, {
    "nps.wake.prescribed": ("WAKE_COLUMNS", "WakeModel"),
    "nps.wake.vortex": ("VortexModel",),
})
