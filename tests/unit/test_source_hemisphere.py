"""Source-hemisphere product (nps.mission.source_hemisphere): unabsorbed band levels at 10 R, round trip."""

import numpy as np
import pandas as pd
import pytest

from nps.noise.observers import hemisphere
from nps.mission.source_hemisphere import COLUMNS, PRODUCT_BANDS, hemisphere_from_table, hemisphere_radius_m, source_hemisphere_table
from nps.noise.spectra import P_REF_PA


def _trim(velocity):
    eye = np.eye(3)
    row = {"rotor": "main", "n_blades": 4, "radius_m": 5.0, "omega_rad_s": 30.0, "thrust_N": 5.0e4, "ct": 0.005,
           "hub_x_m": 0.0, "hub_y_m": 0.0, "hub_z_m": 0.0, "speed_of_sound_mps": 340.29, "density_kg_m3": 1.225,
           "vel_x_mps": velocity[0], "vel_y_mps": velocity[1], "vel_z_mps": velocity[2]}
    row.update({f"r_gh_{i}{j}": eye[i, j] for i in range(3) for j in range(3)})
    return pd.DataFrame([row])


def test_product_levels_unabsorbed_and_round_trip():
    """A 1.5 Pa amplitude tone at harmonic 25 of the revolution frequency (119.4 Hz, 1/3-octave
    band −9) at every observer gives 10 log10(1.5²/2/p_ref²) = 94.5 dB in that band, exactly,
    although ISO 9613-1 absorption over 50 m would remove 0.03 dB: the product is unabsorbed.
    The observers' azimuth depends on the level so the round trip to the (el, az) grid is checked;
    the radius is the observer set's 10 R = 50 m; referred to 25 m every audible band gains 6.02 dB."""
    velocity = (40.0, 0.0, -2.0)
    obs = hemisphere([0.0, 0.0, 0.0], 50.0, 4, 8, velocity)
    period = 2 * np.pi / 30.0
    n = 256
    time = np.arange(n) * period / n
    amp = 1.5 * (1.0 + obs["azimuth_deg"].to_numpy() / 360.0)
    p = amp[:, None] * np.cos(2 * np.pi * 25 * time / period)[None, :]
    rows = []
    for group, scale in (("thickness", 0.0), ("loading", 1.0)):
        for i, o in enumerate(obs["observer"]):
            rows.append(pd.DataFrame({"observer": np.int32(o), "group": group, "time_s": time, "p_Pa": scale * p[i]}))
    table = source_hemisphere_table({"main": pd.concat(rows, ignore_index=True)}, obs, _trim(velocity), {"main": 0.08},
                                    broadband_on=False)
    assert list(table.columns) == list(COLUMNS)
    assert set(table["band"]) == set(PRODUCT_BANDS.tolist())
    assert hemisphere_radius_m(obs) == pytest.approx(50.0, rel=1e-12)
    total = table[(table["source"] == "total") & (table["band"] == -9)].sort_values("observer")
    expected = 10 * np.log10(amp**2 / 2 / P_REF_PA**2)
    assert total["level_db"].to_numpy() == pytest.approx(expected, abs=1e-9)
    hemi = hemisphere_from_table(table)
    assert hemi.radius_m == pytest.approx(50.0) and hemi.velocity_mps.tolist() == [40.0, 0.0, -2.0]
    assert hemi.elevation_deg.tolist() == [-90.0, -60.0, -30.0, 0.0]
    j = list(PRODUCT_BANDS).index(-9)
    assert hemi.levels_db[3, :, j] == pytest.approx(10 * np.log10((1.5 * (1 + np.arange(8) / 8)) ** 2 / 2 / P_REF_PA**2))
    near = source_hemisphere_table({"main": pd.concat(rows, ignore_index=True)}, obs, _trim(velocity), {"main": 0.08},
                                   broadband_on=False, reference_radius_m=25.0)
    assert near["radius_m"].iloc[0] == 25.0
    moved = near["level_db"].to_numpy() - table["level_db"].to_numpy()
    audible = table["level_db"].to_numpy() > -100.0
    assert moved[audible] == pytest.approx(20 * np.log10(2.0)) and np.all(moved[~audible] == 0.0)
    with pytest.raises(ValueError, match="moving with the aircraft"):
        source_hemisphere_table({"main": pd.concat(rows)}, hemisphere([0.0, 0.0, 0.0], 50.0, 4, 8), _trim(velocity),
                                {"main": 0.08}, broadband_on=False)
    with pytest.raises(ValueError, match="full"):
        hemisphere_from_table(table.drop(index=total.index[0]))
