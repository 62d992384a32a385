"""Rigs: rotors on a test stand or in a wind tunnel, with hub-fixed microphones (config/rigs/).

Layer 3 (beside :mod:`nps.mission`): a rig case replaces the aircraft and its trim; the study's stages
then run on what :mod:`nps.rig.case` writes.
"""

from nps.rig.case import RIG_AIRCRAFT, microphone_table, rig_trim

__all__ = ["RIG_AIRCRAFT", "microphone_table", "rig_trim"]
