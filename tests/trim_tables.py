"""Hand-made trim artifacts for stage tests: the columns a test sets, the rest of
:data:`nps.rotor.trim.TRIM_COLUMNS` filled with the values of a level rotor in still air."""

import numpy as np
import pandas as pd

from nps.rotor.trim import TRIM_COLUMNS

NEUTRAL = {
    "role": "lift", "rotation_sign": np.int8(1), "n_blades": np.int32(4), "radius_m": 2.0, "omega_rad_s": 28.0,
    "density_kg_m3": 1.225, "speed_of_sound_mps": 340.294, "trim_iterations": np.int32(1),
    **{f"r_gh_{i}{j}": (-1.0 if i == j < 2 else float(i == j)) for i in range(3) for j in range(3)},
}


def complete_trim(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with every missing trim column added (NEUTRAL value, else 0), in the artifact's column order."""
    out = table.copy()
    for column in TRIM_COLUMNS:
        if column not in out.columns:
            out[column] = NEUTRAL.get(column, 0.0)
    return out[list(TRIM_COLUMNS)]
