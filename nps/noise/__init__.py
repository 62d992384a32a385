"""Noise: the compact F1A solver, rotor sources, observers, signals, spectra, metrics, broadband, HSI.

Layer 2 (beside :mod:`nps.wake`, which it does not import): imports :mod:`nps.rotor` and :mod:`nps.core`.
The solver, :mod:`nps.noise.acoustics`, knows no rotor: :mod:`nps.noise.sources` turns a rotor's disk
table into its compact sources.

- :mod:`nps.noise.acoustics`: compact Farassat 1A with dual-compact thickness.
- :mod:`nps.noise.sources`: rotor → compact sources; :mod:`nps.noise.signals`: the signal tables.
- :mod:`nps.noise.observers`: hemispheres, points, ground grids.
- :mod:`nps.noise.spectra`, :mod:`nps.noise.tones`, :mod:`nps.noise.metrics`: bands, tones, OASPL … EPNL.
- :mod:`nps.noise.broadband`: Pegg's rotor spectrum, BPM airfoil self-noise and BPM over a rotor.
- :mod:`nps.noise.hsi`: the high-speed-impulsive post-processor (kernels in :mod:`nps.noise.hsi_kernels`).
"""

from typing import TYPE_CHECKING

from nps.core.lazy import lazy_face

if TYPE_CHECKING:  # imported on first use (nps.core.lazy): a job imports only the modules its stage runs
    from nps.noise.acoustics import Observers, TimeGrid, radiate_arrays
    from nps.noise.metrics import a_weighting_db, metrics_tables
    from nps.noise.observers import hemisphere, observer_set
    from nps.noise.sources import radiate_rotor, rotor_sources
    from nps.noise.spectra import narrowband_msp, third_octave_bands

__getattr__, __dir__, __all__ = lazy_face(__name__, {
    "nps.noise.acoustics": ("Observers", "TimeGrid", "radiate_arrays"),
    "nps.noise.metrics": ("a_weighting_db", "metrics_tables"),
    "nps.noise.observers": ("hemisphere", "observer_set"),
    "nps.noise.sources": ("radiate_rotor", "rotor_sources"),
    "nps.noise.spectra": ("narrowband_msp", "third_octave_bands"),
})
