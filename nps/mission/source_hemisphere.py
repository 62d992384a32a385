"""Source hemispheres as a product: per-observer 1/3-octave band levels at the reference radius.

One table per aircraft × segment (``results/{aircraft}/{segment}/source_hemisphere.parquet``),
one row per hemisphere observer × source × band, the RNM idea: the levels a fixed tool needs to
fly the aircraft's noise along any path (nps.mission.propagation). Schema (units in the names):

| column | type | meaning |
| --- | --- | --- |
| ``observer`` | int32 | hemisphere observer id (observers artifact) |
| ``azimuth_deg``, ``elevation_deg`` | float64 | map direction (docs/reference/conventions.md), from the centre |
| ``source`` | str | ``thickness``, ``loading``, ``hsi`` (when HSI-processed), ``broadband``, ``total`` |
| ``band`` | int32 | 1/3-octave band number n (f_m = 1000·10^(n/10) Hz), −20 (10 Hz) … 10 (10 kHz) |
| ``center_hz`` | float64 | exact mid-band frequency |
| ``level_db`` | float64 | band level, dB re 20 µPa, at ``radius_m``, **without** air absorption |
| ``radius_m`` | float64 | reference radius of the levels (10 R of the reference rotor) |
| ``vel_x_mps``, ``vel_z_mps`` | float64 | aircraft horizontal and climb speed when computed |
| ``speed_of_sound_mps`` | float64 | sound speed of the computation |

The observers move with the aircraft (no Doppler shift in the table); nps.mission.propagation maps a
fixed receiver's emission direction n to the table's direction d = (n − M)/|n − M|,
M = (vel_x, 0, vel_z)/c. Empty bands are at the level floor (−100 dB).

Absorption: the metrics stage absorbs each rotor's tonal signal line by line over that rotor's
hub-observer distance and the broadband bands at mid-band frequency; band levels cannot be
un-absorbed exactly afterwards (a band holds lines with different α, rotors have different
distances). The product is therefore built from the unabsorbed signals with the metrics
stage's own function (:func:`nps.noise.metrics.metrics_tables` with ``atmosphere=None``), so tonal,
HSI and broadband levels are exactly those of the metrics artifacts without absorption.

Radius: one hemisphere stands for all rotors about one centre, exact only in the far field of
the whole rotor system. At 10 R the helicopter's tail rotor (1.3 R behind the main hub) is seen
from a direction up to 7° off and 5 % nearer than from the centre; the direct-F1A cross-check
(tests/validation/test_footprint_f1a.py, docs/reference/footprint.md) misses by up to 1.8 dB with a 10 R
hemisphere and by at most 0.6 dB with a 20 R one. The product is therefore computed on a
far-field hemisphere (20 R, observer set ``source`` of config/config.yaml) and referred back to
the 10 R reference by spherical spreading (``reference_radius_m``).
"""

from __future__ import annotations

from typing import Mapping

import numpy as np
import pandas as pd

from nps.core.frames import observer_direction
from nps.noise.metrics import metrics_tables
from nps.mission.propagation import Hemisphere
from nps.noise.spectra import LEVEL_FLOOR_DB

PRODUCT_BANDS = np.arange(-20, 11)
"""Bands of the product: 10 Hz (−20) to 10 kHz (10)."""

COLUMNS = ("observer", "azimuth_deg", "elevation_deg", "source", "band", "center_hz", "level_db", "radius_m",
           "vel_x_mps", "vel_z_mps", "speed_of_sound_mps")


def hemisphere_radius_m(observers: pd.DataFrame) -> float:
    """Radius (m) of a hemisphere observer set: least-squares fit of x_i = c + r d(az_i, el_i)."""
    d = observer_direction(np.radians(observers["azimuth_deg"].to_numpy(float)),
                           np.radians(observers["elevation_deg"].to_numpy(float)))
    x = observers[["x_m", "y_m", "z_m"]].to_numpy(float)
    n = len(observers)
    a = np.zeros((3 * n, 4))
    for i in range(3):
        a[i::3, i] = 1.0
        a[i::3, 3] = d[:, i]
    solution, *_ = np.linalg.lstsq(a, x.reshape(-1), rcond=None)
    radius = float(solution[3])
    if not radius > 0 or np.abs(a @ solution - x.reshape(-1)).max() > 1e-6 * radius:
        raise ValueError("observers: not a hemisphere about one centre (x = c + r d does not fit)")
    return radius


def source_hemisphere_table(
    signals: Mapping[str, pd.DataFrame],
    observers: pd.DataFrame,
    trim: pd.DataFrame,
    solidity: Mapping[str, float],
    hsi_signals: Mapping[str, pd.DataFrame] | None = None,
    broadband_on: bool = True,
    reference_radius_m: float | None = None,
    tone_sum: str = "coherent",
    broadband_msp: Mapping[str, np.ndarray] | None = None,
) -> pd.DataFrame:
    """Source-hemisphere product (module doc) from the hemisphere set's signals of every rotor.

    Arguments as :func:`nps.noise.metrics.metrics_tables` (signals without absorption are computed
    there with ``atmosphere=None``); ``observers`` must be a hemisphere moving with the aircraft.
    ``reference_radius_m``: when given, the levels heard at the observers' radius r are referred
    to this radius by spherical spreading (+20 log10(r / r_ref); bands at the floor stay there).
    ``tone_sum``: how the rotors' tones add (``coherent`` or ``incoherent``, nps.noise.signals.TONE_SUMS).
    ``broadband_msp``: the rotors' BPM band MSP (the others get Pegg's), as in ``metrics_tables``.
    """
    for col in ("vx_mps", "vy_mps", "vz_mps"):
        if col not in observers.columns:
            raise ValueError(f"observers: missing column '{col}'")
    velocity = trim.iloc[0][["vel_x_mps", "vel_y_mps", "vel_z_mps"]].to_numpy(float)
    if not np.allclose(observers[["vx_mps", "vy_mps", "vz_mps"]].to_numpy(float), velocity[None, :], atol=1e-9):
        raise ValueError("observers: a source hemisphere needs observers moving with the aircraft (moving: true)")
    radius = hemisphere_radius_m(observers)
    _, bands, _ = metrics_tables(signals, observers, trim, solidity, None, hsi_signals, broadband_on,
                                 broadband_msp=broadband_msp, tone_sum=tone_sum)
    keep = bands[(bands["band"] >= PRODUCT_BANDS[0]) & (bands["band"] <= PRODUCT_BANDS[-1])].copy()
    if reference_radius_m is not None:
        if not (np.isfinite(reference_radius_m) and reference_radius_m > 0):
            raise ValueError(f"reference_radius_m must be positive, got {reference_radius_m}")
        level = keep["level_db"].to_numpy()
        keep["level_db"] = np.where(level > LEVEL_FLOOR_DB, level + 20.0 * np.log10(radius / reference_radius_m), level)
        radius = float(reference_radius_m)
    angles = observers.set_index("observer")[["azimuth_deg", "elevation_deg"]]
    out = keep.join(angles, on="observer")
    out = out.assign(radius_m=radius, vel_x_mps=float(velocity[0]), vel_z_mps=float(velocity[2]),
                     speed_of_sound_mps=float(trim.iloc[0]["speed_of_sound_mps"]))
    out["source"] = out["source"].astype(str)
    out["band"] = out["band"].astype(np.int32)
    return out[list(COLUMNS)].reset_index(drop=True)


def hemisphere_from_table(table: pd.DataFrame, source: str = "total", what: str = "source hemisphere") -> Hemisphere:
    """Product table → :class:`nps.mission.propagation.Hemisphere` of one ``source`` (regular grid check)."""
    missing = [c for c in COLUMNS if c not in table.columns]
    if missing:
        raise ValueError(f"{what}: missing column(s) {missing}")
    rows = table[table["source"] == source]
    if rows.empty:
        raise ValueError(f"{what}: no rows for source '{source}'; has {sorted(table['source'].unique())}")
    el = np.unique(rows["elevation_deg"].to_numpy(float))
    az = np.unique(np.round(rows["azimuth_deg"].to_numpy(float), 9) % 360.0)
    bands = np.unique(rows["band"].to_numpy())
    if len(rows) != el.size * az.size * bands.size:
        raise ValueError(f"{what}: observers must form a full (elevation x azimuth) grid with every band "
                         f"({el.size} x {az.size} x {bands.size} != {len(rows)} rows)")
    ie = np.searchsorted(el, rows["elevation_deg"].to_numpy(float))
    ia = np.searchsorted(az, np.round(rows["azimuth_deg"].to_numpy(float), 9) % 360.0)
    ib = np.searchsorted(bands, rows["band"].to_numpy())
    levels = np.full((el.size, az.size, bands.size), np.nan)
    levels[ie, ia, ib] = rows["level_db"].to_numpy(float)
    first = rows.iloc[0]
    return Hemisphere(el, az, bands.astype(np.int64), levels, float(first["radius_m"]),
                      np.array([float(first["vel_x_mps"]), 0.0, float(first["vel_z_mps"])]),
                      float(first["speed_of_sound_mps"]))
