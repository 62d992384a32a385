"""Rotor aerodynamics: blade and airfoil tables, blade element theory, control modes, aircraft trim.

Layer 1: imports only :mod:`nps.core`.

- :mod:`nps.rotor.blade`, :mod:`nps.rotor.airfoils`: blade geometry tables, section polars (C81, CSV).
- :mod:`nps.rotor.geometry`: :class:`RotorGeometry`, :class:`OperatingPoint`, :class:`RotorMotion`.
- :mod:`nps.rotor.bet`: blade loads over the disk (BET, linear inflow, rigid flapping) and the rotor trim.
- :mod:`nps.rotor.control`: what each rotor trims, and with which control.
- :mod:`nps.rotor.trim`: the aircraft's steady-flight force and moment balance.
"""

from typing import TYPE_CHECKING

from nps.core.lazy import lazy_face

if TYPE_CHECKING:  # imported on first use (nps.core.lazy): a job imports only the modules its stage runs
    from nps.rotor.airfoils import LinearAirfoil, read_airfoil
    from nps.rotor.bet import Controls, DiskGrid, TrimError, rotor_loads, trim_rotor
    from nps.rotor.blade import BladeTable, blade_from_config
    from nps.rotor.control import RotorControl, solve_rotor
    from nps.rotor.geometry import OperatingPoint, RotorGeometry, RotorMotion
    from nps.rotor.trim import AircraftTrimError, FlightCondition, trim_aircraft

__getattr__, __dir__, __all__ = lazy_face(__name__, {
    "nps.rotor.airfoils": ("LinearAirfoil", "read_airfoil"),
    "nps.rotor.bet": ("Controls", "DiskGrid", "TrimError", "rotor_loads", "trim_rotor"),
    "nps.rotor.blade": ("BladeTable", "blade_from_config"),
    "nps.rotor.control": ("RotorControl", "solve_rotor"),
    "nps.rotor.geometry": ("OperatingPoint", "RotorGeometry", "RotorMotion"),
    "nps.rotor.trim": ("AircraftTrimError", "FlightCondition", "trim_aircraft"),
})
