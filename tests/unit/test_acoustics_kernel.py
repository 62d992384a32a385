"""Observer-blocked F1A kernel: an observer's signal must not depend on the other observers of its block."""

import numpy as np
import pytest

from nps.noise.acoustics import OBSERVER_BLOCK, Observers, TimeGrid
from nps.noise.sources import radiate_rotor
from nps.noise.sources import ThicknessModel
from tests.unit.test_acoustics_stage import hover_disk, trim_rows


@pytest.mark.parametrize("kind", ["dual_compact", "compact_monopole"])
@pytest.mark.parametrize("moving", [True, False])
def test_blocked_result_equals_one_observer_at_a_time(kind, moving):
    """OBSERVER_BLOCK + 3 observers at 15…400 m (very different retarded windows, a partial last block), with
    the aircraft moving at 40 m/s: all at once equals one by one to 1e-12 of the peak (periodic and
    direct paths, dual-compact and monopole thickness)."""
    rng = np.random.default_rng(1)
    n = OBSERVER_BLOCK + 3
    direction = rng.normal(size=(n, 3))
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    position = direction * np.geomspace(15.0, 400.0, n)[:, None]
    trim = trim_rows().iloc[0].to_dict()
    trim["vel_x_mps"] = 40.0
    velocity = np.tile([40.0 if moving else 0.0, 0.0, 0.0], (n, 1))
    grid = TimeGrid(0.7, 2 * np.pi / 28.0, 96)
    model = ThicknessModel(kind)
    together = radiate_rotor(hover_disk(), trim, Observers(position, velocity), grid, thickness=model)
    alone = np.concatenate([radiate_rotor(hover_disk(), trim, Observers(position[k:k + 1], velocity[k:k + 1]), grid,
                                          thickness=model) for k in range(n)])
    assert np.abs(together).max() > 0
    assert np.abs(together - alone).max() <= 1e-12 * np.abs(together).max()
