"""Draws docs/figures/tail_rotor_own_wake.png and prints the numbers of
docs/decisions/2026-12-04-tail-rotor-own-wake-peak.md: the tail rotor of config/rigs/bo105_main_tail_rig.yaml,
section c_n at 0.97 R over its first turn of the common period, trimmed (no wake) and with the wakes for the
rig's model and for the candidate causes of its own-wake peak; and the height of the vortex that makes the peak
against its age (free wake and Beddoes). Run: python docs/figures/tail_rotor_own_wake.py (about 2 min)."""

import dataclasses
import math
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.app.config import load_rig
from nps.app.io import read_table
from nps.rotor.geometry import RotorGeometry
from nps.rotor.station_loads import station_loads
from nps.stages import loads as loads_stage
from nps.stages import rig as rig_stage
from nps.wake import bvi, interaction
from nps.wake import free as freewake
from nps.wake import prescribed as wake

REPO = Path(__file__).resolve().parents[2]
RIG = REPO / "config" / "rigs" / "bo105_main_tail_rig.yaml"
STATION = 0.97
# candidates: (label, changes to the rig's wake block, changes to its free block)
VARIANTS = (
    ("free wake (rig)", {}, {}),
    ("loads core 0.14 c + Squire growth", {"core_radius_chords": 0.14, "core_growth": True}, {}),
    ("node-kinematics core floor 2 c", {}, {"core_floor_chords": 2.0}),
    ("far wake 3 rev", {}, {"far_revolutions": 3.0}),
    ("relaxation grid 72 steps/rev", {}, {"steps_per_rev": 72}),
)


def _inputs(out: Path):
    """Set-up and trimmed loads of the rig in ``out``: (rig, rotor configs, trim, disks, summaries)."""
    rig = load_rig(RIG)
    rotors = {r["name"]: r for r in rig["rotor_configs"]}
    res = rig["settings"]["resolution"]
    rig_stage.run({"config": str(RIG)}, {"trim": str(out / "trim.parquet"), "observers": str(out / "mics.parquet")}, {})
    loads_stage.run({"trim": str(out / "trim.parquet")}, {"loads": str(out / "loads")},
                    {"rotors": rotors, "n_psi": res["n_psi"], "n_r": res["n_r"], "aircraft": "rigs", "segment": rig["name"]})
    disks = {n: read_table(out / "loads" / f"{n}.parquet") for n in rotors}
    summaries = {n: read_table(out / "loads" / f"{n}_summary.parquet") for n in rotors}
    return rig, rotors, read_table(out / "trim.parquet"), disks, summaries


def _cn(disk, trim, rotor="tail"):
    row = trim.set_index("rotor").loc[rotor]
    table = station_loads(disk, rotor, float(row["radius_m"]), float(row["density_kg_m3"]),
                          float(row["speed_of_sound_mps"]), [STATION])
    return table["psi_rad"].to_numpy(), table["cn"].to_numpy()


def _coupled(rig, rotors, trim, disks, summaries, wake_changes, free_changes, wake_revolutions=None):
    """The rig's coupled free-wake loads with its wake and free blocks changed (``wake_revolutions``: the wake age
    kept, default the rig's)."""
    settings = rig["settings"]
    block = {**settings["wake"], **wake_changes}
    model = wake.WakeModel.from_config(block, wake_revolutions or settings["resolution"]["wake_revolutions"],
                                       settings["resolution"]["n_psi"])
    free = freewake.FreeWakeModel.from_config({**block["free"], **free_changes})
    return interaction.aircraft_bvi_loads(trim, rotors, disks, summaries, model, free,
                                          controls={n: r["control"] for n, r in rotors.items()})


def _closest_vortex(solution, disk, psi_deg):
    """(blade, age index, distance m, height above the station m) of the tail's own vortex closest to the 0.97 R
    station when blade 0 is at ``psi_deg`` (blade 0's own vortex younger than 60° left out)."""
    n_r = disk["r_m"].nunique()
    beta = disk["beta_rad"].to_numpy().reshape(-1, n_r)
    r = disk["r_m"].to_numpy()[:n_r]
    radius = float(solution.rotors[solution.index("tail")].state.radius_m)
    b = np.interp(STATION * radius, r, beta[int(round(psi_deg)) % beta.shape[0]])
    point = wake.blade_points(np.radians([psi_deg]), np.array([STATION * radius]), np.array([[b]]))[0, 0]
    nodes = freewake.wake_snapshot(solution, "tail", math.radians(psi_deg)).nodes_m
    d = np.linalg.norm(nodes - point, axis=-1)
    d[0, : int(round(math.radians(60.0) / solution.beddoes.dphi_rad))] = np.inf
    k, j = np.unravel_index(np.argmin(d), d.shape)
    return k, j, d[k, j], nodes[k, j, 2] - point[2], nodes, point


def main(path=Path(__file__).with_name("tail_rotor_own_wake.png")):
    with tempfile.TemporaryDirectory() as scratch:
        rig, rotors, trim, disks, summaries = _inputs(Path(scratch))
    chord = float(rotors["tail"]["chord_m"])
    n_psi = rig["settings"]["resolution"]["n_psi"]
    psi, base = _cn(disks["tail"], trim)
    fig, (loads_ax, height_ax) = plt.subplots(1, 2, figsize=(13, 5))
    loads_ax.plot(np.degrees(psi), base, "k--", lw=1.2, label="trimmed, no wake")
    print(f"tail c_n at {STATION} R, first turn: trimmed swing {np.ptp(base):.3f}, max {base.max():.3f} "
          f"at {np.degrees(psi[base.argmax()]):.0f} deg")
    default = None
    for label, wake_changes, free_changes in VARIANTS:
        result = _coupled(rig, rotors, trim, disks, summaries, wake_changes, free_changes)
        p, cn = _cn(result.results["tail"].disk, trim)
        turn = cn[:n_psi]
        k, j, dist, dz, _, _ = _closest_vortex(result.solution, disks["tail"], np.degrees(p[turn.argmax()]))
        print(f"{label:36s} swing {np.ptp(cn):.3f} (turn 1 {np.ptp(turn):.3f}), max {turn.max():.3f} at "
              f"{np.degrees(p[turn.argmax()]):.0f} deg (+{turn.max() - base[turn.argmax()]:.3f} over trimmed); "
              f"closest own vortex: blade {k}, age {np.degrees(j * result.solution.beddoes.dphi_rad):.0f} deg, "
              f"{dist / chord:.2f} c away, {dz / chord:+.2f} c above")
        loads_ax.plot(np.degrees(p[:n_psi]), turn, lw=2.0 if default is None else 1.0, label=label)
        default = default or result
    # the tail rotor alone in its Beddoes wake (vortices where the prescribed wake puts them)
    settings = rig["settings"]
    block = {**settings["wake"], "model": "beddoes"}
    model = wake.WakeModel.from_config(block, settings["resolution"]["wake_revolutions"], n_psi)
    row = trim.set_index("rotor").loc["tail"].to_dict()
    row["rotor"] = "tail"
    beddoes = bvi.bvi_loads(disks["tail"], row, RotorGeometry.from_config(rotors["tail"]),
                            bvi.summary_value(summaries["tail"], "ct", "tail loads summary"), model)
    p, cn = _cn(beddoes.disk, trim)
    print(f"{'tail alone, Beddoes wake':36s} swing {np.ptp(cn):.3f}, max {cn.max():.3f} at "
          f"{np.degrees(p[cn.argmax()]):.0f} deg (+{cn.max() - base[cn.argmax()]:.3f} over trimmed)")
    loads_ax.plot(np.degrees(p), cn, ":", lw=1.5, label="tail alone, Beddoes wake")
    loads_ax.set(xlabel="tail blade azimuth ψ (deg)", ylabel=f"c_n at r/R = {STATION}", xlim=(0, 360),
                 xticks=range(0, 361, 45), title="tail rotor, first turn of the common period")
    loads_ax.grid(alpha=0.3)
    loads_ax.legend(fontsize=8)
    # height of the vortex that makes the peak, free wake against Beddoes, along its age
    solution = default.solution
    p, cn = _cn(default.results["tail"].disk, trim)
    peak = np.degrees(p[cn[:n_psi].argmax()])
    k, j, _, _, nodes, point = _closest_vortex(solution, disks["tail"], peak)
    flat = dataclasses.replace(solution, distortion_m=np.zeros_like(solution.distortion_m))
    prescribed = freewake.wake_snapshot(flat, "tail", math.radians(peak)).nodes_m
    age = np.degrees(np.arange(nodes.shape[1]) * solution.beddoes.dphi_rad)
    keep = age <= 360.0
    height_ax.plot(age[keep], nodes[k, keep, 2] / chord, lw=2, label=f"free wake (blade {k}'s vortex)")
    height_ax.plot(age[keep], prescribed[k, keep, 2] / chord, "--", label="Beddoes geometry")
    height_ax.axhline(point[2] / chord, color="k", lw=0.8)
    height_ax.plot(age[j], point[2] / chord, "kv", label=f"0.97 R station at ψ = {peak:.0f}°")
    height_ax.set(xlabel="vortex age when blade 0 is at the peak (deg)", ylabel="height z/c in the hub frame",
                  title="the vortex that makes the peak")
    height_ax.grid(alpha=0.3)
    height_ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
