"""Mission and ground analysis: flight paths, propagation to the ground, footprints, certification.

Layer 3 (beside :mod:`nps.rig`): imports :mod:`nps.noise`, :mod:`nps.rotor` and :mod:`nps.core`.

- :mod:`nps.mission.trajectory`: the mission's flight profile and the Chapter 8 reference procedures.
- :mod:`nps.mission.source_hemisphere`: per-observer band levels at the reference radius.
- :mod:`nps.mission.propagation`: hemispheres along a trajectory to fixed receivers (RNM method).
- :mod:`nps.mission.footprint`: L_A(t), L_Amax, SEL and contour areas; :mod:`nps.mission.certification`: EPNL.
"""

from nps.mission.certification import certify
from nps.mission.footprint import mission_footprint
from nps.mission.propagation import propagate
from nps.mission.trajectory import mission_path

__all__ = ["certify", "mission_footprint", "propagate", "mission_path"]
