"""Benchmark: free wake + BVI loads of all rotors of one aircraft in segment 3 (6° descent) at the
campaign resolution (issue 12 targets on the 2-core machine: coaxial < 20 s, helicopter < 10 s).

The inputs are made as the workflow makes them (``nps.rotor.trim.trim_aircraft`` for the segment, then
``nps.rotor.bet.trim_rotor`` per rotor on the config's n_psi × n_r disk, the config's ``wake:`` block and
``resolution``), then :func:`nps.wake.interaction.aircraft_bvi_loads` is timed: wake relaxation (all
rotors together), every rotor's disk velocity from every rotor's wake, re-trims, section loads.
Prints the first call (including numba's cache load or compilation), then the best of 3 runs
(wall time and the process CPU time of that run: on the shared machine the wall time depends on
the other users' load, the CPU time over the 2 threads bounds the idle-machine wall time), the
relaxation iterations and the interaction summary.
``--exact`` also runs without the far-field grouping of the other rotors' wakes
(``FreeWakeModel(far_group_deg=0)``, every 1° segment) and prints, per rotor, the change of
peak and RMS BVI ΔU_P, of the rotor thrust and of the largest section-load change that the grouping
makes (docs/reference/wake_bvi.md, "Performance").
Run from the repository root: ``python benchmarks/bench_freewake.py [--exact] [aircraft ...]``.
"""

import argparse
import os
import time

import numba
import numpy as np
import pandas as pd
import yaml

from nps.rotor import bet

from nps.wake import free as freewake

from nps.wake import interaction

from nps.wake import prescribed as wake
from nps.core.atmosphere import isa
from nps.app.config import load_aircraft, load_mission
from nps.rotor.geometry import OperatingPoint, RotorGeometry
from nps.rotor.trim import FlightCondition, trim_aircraft


def segment_inputs(aircraft_name: str, segment: str = "seg3"):
    """(trim table, rotor configs, disks, summaries, wake model) as the workflow makes them."""
    config = yaml.safe_load(open("config/config.yaml"))
    aircraft = load_aircraft(f"config/aircraft/{aircraft_name}.yaml")
    mission = load_mission(f"config/missions/{config['campaign']['mission']}.yaml")
    speeds = next(s for s in mission["segments"] if s["id"] == segment)["aircraft"][aircraft_name]
    atm = config["atmosphere"]
    flight = FlightCondition(speeds["forward_speed_mps"], speeds["climb_speed_mps"],
                             isa(atm["altitude_m"], atm["isa_delta_K"], atm["relative_humidity_pct"]))
    trim = trim_aircraft(aircraft, flight, speeds.get("rotor_omega_scale"))
    res = config["resolution"]
    configs, disks, summaries = {}, {}, {}
    for rotor in aircraft["rotors"]:
        row = trim[trim["rotor"] == rotor["name"]].iloc[0]
        loads = bet.trim_rotor(RotorGeometry.from_config(rotor), OperatingPoint.from_trim_row(row),
                               bet.DiskGrid(res["n_psi"], res["n_r"]))
        configs[rotor["name"]], disks[rotor["name"]], summaries[rotor["name"]] = rotor, loads.disk, loads.summary()
    model = wake.WakeModel.from_config(config["wake"], res["wake_revolutions"], res["n_psi"])
    return trim, configs, disks, summaries, model


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("aircraft", nargs="*", default=["coaxial", "helicopter"])
    ap.add_argument("--exact", action="store_true", help="compare with the ungrouped (every segment) evaluation")
    args = ap.parse_args(argv)
    pd.set_option("display.width", 200)
    print(f"numba threads: {numba.get_num_threads()}")
    for name in args.aircraft:
        inputs = segment_inputs(name)
        start = time.perf_counter()
        done = interaction.aircraft_bvi_loads(*inputs)
        first = time.perf_counter() - start
        wall, cpu = min(_timed(inputs) for _ in range(3))
        print(f"{name} seg3: free wake + BVI loads of {len(inputs[1])} rotors: first {first:.2f} s, best {wall:.2f} s "
              f"wall ({cpu:.2f} s CPU, load average {os.getloadavg()[0]:.1f}); relaxation {done.solution.iterations} "
              f"iterations, last node change {done.solution.residual_history[-1]:.4f} R")
        print(done.summary.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
        if args.exact:
            wall_exact, cpu_exact = _timed(inputs, freewake.FreeWakeModel(far_group_deg=0.0))
            exact = interaction.aircraft_bvi_loads(*inputs, freewake.FreeWakeModel(far_group_deg=0.0))
            print(f"  ungrouped: {wall_exact:.2f} s wall ({cpu_exact:.2f} s CPU)")
            print(_accuracy(done, exact).to_string(index=False, float_format=lambda v: f"{v:.3g}"))


def _accuracy(grouped: interaction.AircraftBVI, exact: interaction.AircraftBVI) -> pd.DataFrame:
    """Per rotor: peak and RMS |ΔU_P| (m/s) ungrouped, their relative change with the grouping,
    the relative thrust change and the largest |ΔF_z| change relative to the peak |F_z|."""
    rows = []
    for name, ref in exact.results.items():
        new = grouped.results[name]
        fz_ref, fz_new = ref.disk["fz_N_per_m"].to_numpy(), new.disk["fz_N_per_m"].to_numpy()
        dr = ref.disk["dr_m"].to_numpy()
        peak_ref, rms_ref = np.abs(ref.d_up_mps).max(), np.sqrt(np.mean(ref.d_up_mps ** 2))
        rows.append({
            "rotor": name, "peak_dup_mps": peak_ref, "peak_change": np.abs(new.d_up_mps).max() / peak_ref - 1.0,
            "rms_dup_mps": rms_ref, "rms_change": np.sqrt(np.mean(new.d_up_mps ** 2)) / rms_ref - 1.0,
            "max_dup_change_mps": np.abs(new.d_up_mps - ref.d_up_mps).max(),
            "thrust_change": np.sum(fz_new * dr) / np.sum(fz_ref * dr) - 1.0,
            "max_fz_change_of_peak": np.abs(fz_new - fz_ref).max() / np.abs(fz_ref).max(),
        })
    return pd.DataFrame(rows)


def _timed(inputs, free_model: freewake.FreeWakeModel = freewake.FreeWakeModel()) -> tuple[float, float]:
    """(wall s, CPU s of this process) of one call."""
    cpu0, start = os.times(), time.perf_counter()
    interaction.aircraft_bvi_loads(*inputs, free_model)
    cpu1 = os.times()
    return time.perf_counter() - start, (cpu1.user - cpu0.user) + (cpu1.system - cpu0.system)


if __name__ == "__main__":
    main()
