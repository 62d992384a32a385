"""PSU-WOPWOP files: read and write its cases, run them with NPS's F1A solver, write NPS cases for it.

Layer 4 (beside :mod:`nps.app`, which it does not import): an exchange-format package. It reads and writes
PSU-WOPWOP's own files (binary patch and functional data files, namelists, output files) with plain file
I/O and imports only the physics packages (:mod:`nps.noise` for the F1A kernel, :mod:`nps.rotor` for the
exported rotors). Stages and commands sit above it (``nps wopwop run | export``).

- :mod:`nps.wopwop.errors`: the one error type, one line naming the file and the byte or field.
- :mod:`nps.wopwop.binary`: geometry (patch) and functional (loading) files, both byte orders.
- :mod:`nps.wopwop.namelist`: Fortran namelist text; :mod:`nps.wopwop.case`: the case model (environment,
  observers, container tree, change-of-base blocks).
- :mod:`nps.wopwop.motion`: change-of-base kinematics (positions, velocities, accelerations of a CB chain).
- :mod:`nps.wopwop.output`: output files (pressure, OASPL, spectra) and WOPWOP's spectral conventions.

Facts about the formats and where they were confirmed: docs/reference/wopwop.md.
"""
