"""Draws docs/figures/main_wake_at_tail_rotor.png and prints the numbers of
docs/validation/main_wake_at_tail_rotor.md: the main rotor's wake at the tail rotor of
config/rigs/bo105_main_tail_rig.yaml (free wake of both rotors over the common period: one main-rotor turn, five
tail-rotor turns). For the rig and for variants of what could weaken the main rotor's wake there (far-field
grouping, far-wake length, wake truncation, the vortex structure and the loads core of the main rotor's vortex
at the tail rotor), the tail rotor's c_n at 0.97 R turn by turn and the main rotor's ΔU_P there; where the main
rotor's tip vortices cross the tail rotor's disk plane; the main rotor's vortex heights against HART-II's PIV
behind the hub. Run: python docs/figures/main_wake_at_tail_rotor.py (about 2 min)."""

import contextlib
import dataclasses
import math
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from nps.wake import bvi
from nps.wake import free as freewake

HERE = Path(__file__).resolve().parent
TESTS = HERE.parents[1] / "tests"
sys.path[:0] = [str(HERE), str(TESTS / "validation"), str(TESTS)]
import hart_ii_case  # noqa: E402  (the HART-II PIV data and their comparison with a wake)
import tail_rotor_own_wake as rig_case  # noqa: E402  (the rig's set-up, coupled loads and c_n extraction)

STATION = rig_case.STATION


@contextlib.contextmanager
def _tail_sees(change):
    """Within the block, the tail rotor's blade loads see the main rotor's lifting-line vortex changed by
    ``change(sources, q_main, tail_state)`` (a diagnostic of the evaluation only; the relaxation is untouched)."""
    lifting_line, disk_velocity = freewake._lifting_line_sources, freewake.disk_induced_velocity

    def velocity(solution, target, *args):
        if target != "tail" or len(solution.rotors) < 2:
            return disk_velocity(solution, target, *args)
        tail_state = solution.rotors[solution.index("tail")].state

        def sources(rotors, beddoes, distortion, timing):
            base = lifting_line(rotors, beddoes, distortion, timing)
            return change(base, [r.name for r in rotors].index("main"), tail_state, beddoes)

        freewake._lifting_line_sources = sources
        try:
            return disk_velocity(solution, target, *args)
        finally:
            freewake._lifting_line_sources = lifting_line

    freewake.disk_induced_velocity = velocity
    try:
        yield
    finally:
        freewake.disk_induced_velocity = disk_velocity


def _point_vortex(sources, q, tail_state, beddoes):
    profiles = sources.profiles.copy()
    profiles[q] = 0.0
    profiles[q, :, 0] = 1.0  # structure factor T ≡ 1
    return dataclasses.replace(sources, profiles=profiles)


def _receiver_core(sources, q, tail_state, beddoes):
    core = sources.core.copy()
    core[q, 0] = beddoes.vortex.core_radius_chords * tail_state.chord_m
    return dataclasses.replace(sources, core=core)


def _without_main(sources, q, tail_state, beddoes):
    gamma = sources.gamma.copy()
    gamma[q] = 0.0
    return dataclasses.replace(sources, gamma=gamma)


# (label, wake-block changes, free-block changes, wake revolutions or None, lifting-line change or None)
VARIANTS = (
    ("rig as bundled", {}, {}, None, None),
    ("no far-field grouping", {}, {"far_group_deg": 0.0}, None, None),
    ("free far wake 1 -> 3 revolutions", {}, {"far_revolutions": 3.0}, None, None),
    ("wake truncated at 6 revolutions (4)", {}, {}, 6, None),
    ("main's vortex a point vortex", {}, {}, None, _point_vortex),
    ("main's vortex with the tail's loads core", {}, {}, None, _receiver_core),
    ("tail loads without the main's vortices", {}, {}, None, _without_main),
)


def _main_dup(result, disks):
    """The main rotor's ΔU_P (m/s, blade frame, + up through the disk) at the tail's 0.97 R over the period."""
    solution = result.solution
    m = solution.revolutions(solution.index("tail"))
    tiled = bvi.tile_disk(disks["tail"], m)
    grid = bvi.disk_grid(tiled, "tail", common_period=True)
    beta = tiled["beta_rad"].to_numpy(float).reshape(grid.shape)
    v = freewake.disk_induced_velocity(solution, "tail", grid.psi_rad, grid.r_m, beta)
    j = int(np.argmin(np.abs(grid.r_m / grid.r_m.max() - STATION)))
    return bvi.blade_frame_increments(v[solution.index("main")], grid.psi_rad, beta)[1][:, j]


def turn_statistics(cn, dup, n_psi):
    """Turn-to-turn variation of the tail's c_n (largest range over the turns at one ψ, RMS deviation from
    the mean turn) and of the main rotor's ΔU_P (m/s)."""
    turns, dups = cn.reshape(-1, n_psi), dup.reshape(-1, n_psi)
    return {"swing": float(np.ptp(cn)), "cn_range": float(np.ptp(turns, axis=0).max()),
            "cn_rms": float(np.sqrt(np.mean((turns - turns.mean(axis=0)) ** 2))),
            "dup_max": float(np.abs(dup).max()), "dup_range": float(np.ptp(dups, axis=0).max())}


def tail_plane_crossings(solution, psi_deg=range(0, 90, 3)):
    """(age deg, Δx m, Δz m) of each crossing of the tail rotor's disk plane (y = 0) by a main-rotor tip vortex
    within 2 tail radii of the tail hub, relative to the hub in the main rotor's hub frame H' (x aft, z up the
    shaft), for main-rotor blade azimuths ``psi_deg`` (the wake is periodic in a quarter turn)."""
    main, tail = solution.rotors[solution.index("main")], solution.rotors[solution.index("tail")]
    hub = main.to_common.T @ (np.asarray(tail.hub_position_m, float) - np.asarray(main.hub_position_m, float))
    out = []
    for psi in psi_deg:
        nodes = freewake.wake_snapshot(solution, "main", math.radians(psi)).nodes_m
        for k in range(nodes.shape[0]):
            y = nodes[k, :, 1]
            for j in np.nonzero(np.sign(y[:-1]) != np.sign(y[1:]))[0]:
                f = y[j] / (y[j] - y[j + 1])
                rel = nodes[k, j] + f * (nodes[k, j + 1] - nodes[k, j]) - hub
                if math.hypot(rel[0], rel[2]) < 2.0 * tail.state.radius_m:
                    out.append((math.degrees((j + f) * solution.beddoes.dphi_rad), rel[0], rel[2]))
    return np.array(out), hub, tail.state.radius_m


def piv_heights(solution, x_min_m=0.8):
    """HART-II BL PIV vortices at x ≥ ``x_min_m`` (behind the hub, toward the tail rotor): (x, measured z,
    predicted − measured z) with the nearest predicted crossing of the measured vortex's cut plane, m, H'
    (``hart_ii_case.piv_miss_distances_free``; the main rotor is the rig's first)."""
    return np.array([(x, z, z_pred - z) for _, _, _, x, z, _, z_pred, _ in
                     hart_ii_case.piv_miss_distances_free(solution, "BL") if x >= x_min_m])


def run_variant(inputs, variant):
    """One of :data:`VARIANTS` on the rig's set-up ``inputs`` (``rig_case._inputs``): (coupled result, ψ of the
    tail over the period (rad), its c_n at :data:`STATION`, the main rotor's ΔU_P there, :func:`turn_statistics`)."""
    rig, _, trim, disks, _ = inputs
    _, wake_changes, free_changes, revolutions, change = variant
    with _tail_sees(change) if change else contextlib.nullcontext():
        result = rig_case._coupled(*inputs, wake_changes, free_changes, revolutions)
        dup = _main_dup(result, disks)
    psi, cn = rig_case._cn(result.results["tail"].disk, trim)
    return result, psi, cn, dup, turn_statistics(cn, dup, rig["settings"]["resolution"]["n_psi"])


def main(path=HERE / "main_wake_at_tail_rotor.png"):
    with tempfile.TemporaryDirectory() as scratch:
        inputs = rig_case._inputs(Path(scratch))
    n_psi = inputs[0]["settings"]["resolution"]["n_psi"]
    runs = {variant[0]: run_variant(inputs, variant) for variant in VARIANTS}
    for label, (*_, s) in runs.items():
        print(f"{label:42s} c_n swing {s['swing']:.3f}, turn-to-turn range {s['cn_range']:.3f}, RMS "
              f"{s['cn_rms']:.4f}; main's dU_P max {s['dup_max']:.2f} m/s, turn-to-turn range {s['dup_range']:.2f} m/s")
    result, psi, cn, dup, _ = runs["rig as bundled"]
    crossings, _, radius = tail_plane_crossings(result.solution)
    young = crossings[:, 0] < 360.0
    print(f"main-rotor vortex crossings of the tail plane within {2 * radius:.2f} m of its hub: ages "
          f"{crossings[young, 0].min():.0f}-{crossings[young, 0].max():.0f} deg (trailed behind the hub) and "
          f"{crossings[~young, 0].min():.0f}-{crossings[~young, 0].max():.0f} deg (trailed ahead of it); "
          f"height below the tail hub {-crossings[:, 2].max():.2f}-{-crossings[:, 2].min():.2f} m")
    piv = piv_heights(result.solution)
    print(f"HART-II BL PIV behind the hub (x >= 0.8 m, {len(piv)} vortices): predicted - measured height "
          f"mean {piv[:, 2].mean():+.3f} m, range {piv[:, 2].min():+.3f} to {piv[:, 2].max():+.3f} m")

    fig, (cn_ax, dup_ax, plane_ax) = plt.subplots(1, 3, figsize=(17, 5))
    turns, dups = cn.reshape(-1, n_psi), dup.reshape(-1, n_psi)
    deg = np.degrees(psi[:n_psi])
    for i, (turn, d) in enumerate(zip(turns, dups)):
        cn_ax.plot(deg, turn, lw=1.0, label=f"tail turn {i + 1}")
        dup_ax.plot(deg, d, lw=1.0, label=f"tail turn {i + 1}")
    alone = runs["tail loads without the main's vortices"][2].reshape(-1, n_psi)
    cn_ax.plot(deg, alone.mean(axis=0), "k:", lw=1.5, label="mean turn without the main's vortices")
    cn_ax.set(xlabel="tail blade azimuth ψ (deg)", ylabel=f"c_n at r/R = {STATION}", xlim=(0, 360),
              xticks=range(0, 361, 45), title="tail rotor, five turns of the common period")
    dup_ax.set(xlabel="tail blade azimuth ψ (deg)", ylabel="ΔU_P from the main rotor's wake (m/s)", xlim=(0, 360),
               xticks=range(0, 361, 45), title=f"main rotor's wake at the tail's {STATION} R")
    for ax in (cn_ax, dup_ax):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    theta = np.linspace(0.0, 2.0 * np.pi, 200)
    plane_ax.plot(radius * np.cos(theta), radius * np.sin(theta), "k-", lw=1.0, label="tail disk")
    plane_ax.plot(STATION * radius * np.cos(theta), STATION * radius * np.sin(theta), "k--", lw=0.8,
                  label=f"{STATION} R station")
    points = plane_ax.scatter(crossings[:, 1], crossings[:, 2], c=crossings[:, 0], s=10, cmap="viridis")
    fig.colorbar(points, ax=plane_ax, label="main-rotor vortex age (deg)")
    plane_ax.text(0.02, 0.03, f"HART-II PIV behind the hub: NPS's vortices {-piv[:, 2].mean():.3f} m low",
                  transform=plane_ax.transAxes, fontsize=7, color="r")
    plane_ax.set(xlabel="Δx from the tail hub, aft (m)", ylabel="Δz from the tail hub, up the main shaft (m)",
                 aspect="equal", title="main-rotor vortices in the tail's disk plane")
    plane_ax.grid(alpha=0.3)
    plane_ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
