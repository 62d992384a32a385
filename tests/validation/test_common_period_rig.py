"""The bundled 5:1 main + tail rotor rig over its common period (docs/reference/wake_bvi.md "Common period").

Set-up and loads through the rig's stages, then the free wake and BVI loads of both rotors
(:func:`nps.wake.interaction.aircraft_bvi_loads`, the rig's wake settings, common period on). Physics checked:

- the period is one main-rotor turn and five tail-rotor turns; the tail rotor's table holds the five;
- the tail rotor's loads differ from one turn to the next, and that rev-to-rev part follows the slower rotor's
  wake: it is anticorrelated (more downwash through the disk, less lift) with the rev-to-rev part of the
  velocity the main rotor's wake induces at the tail rotor's blades, more strongly than with its own wake's;
- the main rotor (one turn in the period) keeps one turn, and an evaluation of the main rotor's wake at the
  tail over the period repeats after the period (the tables are periodic in it).
"""

import shutil
from pathlib import Path

import numpy as np
import pytest

from nps.app.config import load_rig
from nps.app.io import read_table
from nps.stages import loads as loads_stage
from nps.stages import rig as rig_stage
from nps.wake import bvi, interaction
from nps.wake import free as freewake
from nps.wake import prescribed as wake

REPO = Path(__file__).resolve().parents[2]
RIG = REPO / "config" / "rigs" / "main_tail_rig.yaml"
TURNS, N_PSI = 5, 36


@pytest.fixture(scope="module")
def coupled(tmp_path_factory):
    out = tmp_path_factory.mktemp("main_tail")
    rig = load_rig(RIG)
    assert rig["settings"]["wake"]["free"]["common_period"] is True
    rotors = {r["name"]: r for r in rig["rotor_configs"]}
    res = rig["settings"]["resolution"]
    rig_stage.run({"config": str(RIG)}, {"trim": str(out / "trim.parquet"), "observers": str(out / "mics.parquet")}, {})
    loads_stage.run({"trim": str(out / "trim.parquet")}, {"loads": str(out / "loads")},
                    {"rotors": rotors, "n_psi": res["n_psi"], "n_r": res["n_r"], "aircraft": "rigs", "segment": rig["name"]})
    trim = read_table(out / "trim.parquet")
    disks = {n: read_table(out / "loads" / f"{n}.parquet") for n in rotors}
    summaries = {n: read_table(out / "loads" / f"{n}_summary.parquet") for n in rotors}
    model = wake.WakeModel.from_config(rig["settings"]["wake"], res["wake_revolutions"], res["n_psi"])
    free = freewake.FreeWakeModel.from_config(rig["settings"]["wake"]["free"])
    return interaction.aircraft_bvi_loads(trim, rotors, disks, summaries, model, free,
                                          controls={n: r["control"] for n, r in rotors.items()})


def _rev_to_rev(values):
    """The part of a field over the period (TURNS·N_PSI, n_r) that changes from turn to turn."""
    turns = values.reshape(TURNS, N_PSI, -1)
    return turns - turns.mean(axis=0)


def test_the_period_and_the_tables(coupled):
    solution = coupled.solution
    assert solution.timing.periods[0].revolutions == (1, TURNS) and solution.timing.periods[0].exact
    assert len(coupled.results["main"].disk) == N_PSI * 12
    assert len(coupled.results["tail"].disk) == TURNS * N_PSI * 12
    record = solution.period_record(solution.index("tail"), N_PSI)
    assert record["revolutions"] == TURNS and record["blade_shift_steps"][0] == 0
    assert record["period_s"] == pytest.approx(2.0 * np.pi / 100.0, rel=1e-12)


def test_the_tail_rotors_turns_differ_as_the_main_rotors_wake_says(coupled):
    solution, tail = coupled.solution, coupled.results["tail"].disk
    grid = bvi.disk_grid(tail, "tail", common_period=True)
    beta = tail["beta_rad"].to_numpy().reshape(grid.shape)
    v = freewake.disk_induced_velocity(solution, "tail", grid.psi_rad, grid.r_m, beta)
    d_up_main = bvi.blade_frame_increments(v[solution.index("main")], grid.psi_rad, beta)[1]
    d_up_own = bvi.blade_frame_increments(v[solution.index("tail")], grid.psi_rad, beta)[1]
    fz = tail["fz_N_per_m"].to_numpy().reshape(grid.shape)
    varying = _rev_to_rev(fz)
    assert np.sqrt(np.mean(varying ** 2)) > 5e-3 * fz.std()  # the turns differ (≈ 1.3 % measured)
    with_main = np.corrcoef(varying.ravel(), _rev_to_rev(d_up_main).ravel())[0, 1]
    with_own = np.corrcoef(varying.ravel(), _rev_to_rev(d_up_own).ravel())[0, 1]
    assert with_main < -0.6 and abs(with_own) < abs(with_main), (with_main, with_own)  # measured −0.75, −0.28


def test_the_wake_repeats_after_the_period(coupled):
    """The main rotor's wake at the tail rotor's stations one period later: the same velocity (the tables
    are periodic in the period, not in one tail turn)."""
    solution, tail = coupled.solution, coupled.results["tail"].disk
    grid = bvi.disk_grid(tail, "tail", common_period=True)
    psi = grid.psi_rad[:: N_PSI // 4]
    beta = np.zeros((psi.size, grid.r_m.size))
    now = freewake.disk_induced_velocity(solution, "tail", psi, grid.r_m, beta)
    later = freewake.disk_induced_velocity(solution, "tail", psi + 2.0 * np.pi * TURNS, grid.r_m, beta)
    next_turn = freewake.disk_induced_velocity(solution, "tail", psi + 2.0 * np.pi, grid.r_m, beta)
    scale = np.abs(now).max()
    np.testing.assert_allclose(later, now, atol=1e-9 * scale)
    assert np.abs(next_turn - now).max() > 1e-3 * scale
