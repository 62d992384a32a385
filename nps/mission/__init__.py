"""Mission and ground analysis: flight paths, propagation to the ground, footprints, certification.

Layer 3 (beside :mod:`nps.rig`): imports :mod:`nps.noise`, :mod:`nps.rotor` and :mod:`nps.core`.

- :mod:`nps.mission.trajectory`: the mission's flight profile and the Chapter 8 reference procedures.
- :mod:`nps.mission.paths`: 3-D flight paths and their time history; :mod:`nps.mission.path_states`: the
  quasi-static trim states that cover a path.
- :mod:`nps.mission.source_hemisphere`: per-observer band levels at the reference radius.
- :mod:`nps.mission.propagation`: hemispheres along a trajectory to fixed receivers (RNM method).
- :mod:`nps.mission.footprint`: L_A(t), L_Amax, SEL and contour areas; :mod:`nps.mission.certification`: EPNL.
"""

from typing import TYPE_CHECKING

from nps.core.lazy import lazy_face

if TYPE_CHECKING:  # imported on first use (nps.core.lazy): a job imports only the modules its stage runs
    from nps.mission.certification import certify
    from nps.mission.footprint import mission_footprint
    from nps.mission.propagation import propagate
    from nps.mission.trajectory import mission_path

__getattr__, __dir__, __all__ = lazy_face(__name__, {
    "nps.mission.certification": ("certify",),
    "nps.mission.footprint": ("mission_footprint",),
    "nps.mission.propagation": ("propagate",),
    "nps.mission.trajectory": ("mission_path",),
})
