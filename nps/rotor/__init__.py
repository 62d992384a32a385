"""Rotor aerodynamics: blade and airfoil tables, blade element theory, control modes, aircraft trim.

Layer 1: imports only :mod:`nps.core`.

- :mod:`nps.rotor.blade`, :mod:`nps.rotor.airfoils`: blade geometry tables, section polars (C81, CSV).
- :mod:`nps.rotor.geometry`: :class:`RotorGeometry`, :class:`OperatingPoint`, :class:`RotorMotion`.
- :mod:`nps.rotor.bet`: blade loads over the disk (BET, linear inflow, rigid flapping) and the rotor trim.
- :mod:`nps.rotor.control`: what each rotor trims, and with which control.
- :mod:`nps.rotor.trim`: the aircraft's steady-flight force and moment balance.
"""

from nps.rotor.airfoils import LinearAirfoil, read_airfoil
from nps.rotor.bet import Controls, DiskGrid, TrimError, rotor_loads, trim_rotor
from nps.rotor.blade import BladeTable, blade_from_config
from nps.rotor.control import RotorControl, solve_rotor
from nps.rotor.geometry import OperatingPoint, RotorGeometry, RotorMotion
from nps.rotor.trim import AircraftTrimError, FlightCondition, trim_aircraft

__all__ = ["LinearAirfoil", "read_airfoil", "Controls", "DiskGrid", "TrimError", "rotor_loads", "trim_rotor",
           "BladeTable", "blade_from_config", "RotorControl", "solve_rotor", "OperatingPoint", "RotorGeometry",
           "RotorMotion", "AircraftTrimError", "FlightCondition", "trim_aircraft"]
