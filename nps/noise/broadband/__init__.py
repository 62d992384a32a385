"""Broadband noise: Pegg's semi-empirical rotor spectrum and Brooks–Pope–Marcolini airfoil self-noise.

- :mod:`nps.noise.broadband.pegg`: Pegg (NASA TM-80200, 1979), the thesis' model.
- :mod:`nps.noise.broadband.bpm`: BPM (NASA RP-1218, 1989) 1/3-octave spectra of one airfoil section.
- :mod:`nps.noise.broadband.rotor`: BPM blade elements as rotating compact sources over a revolution.
"""
