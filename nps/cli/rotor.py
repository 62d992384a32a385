"""``python -m nps rotor``: thrust, torque, power and noise of one isolated rotor at one condition.

The rotor comes from a rotor YAML (``--rotor-file``, one ``rotors[]`` entry of an aircraft file) or an
aircraft file (``--aircraft`` with ``--rotor``); or give a whole rig with ``--rig``
(config/rigs/NAME.yaml). The condition: rotor speed, control mode (``fixed``: given pitch and speed;
``rpm``: pitch given, speed trimmed to ``--thrust-n``; ``collective``: pitch trimmed to ``--thrust-n``;
``collective_only``: collective alone, no cyclic, teeter free),
shaft angle (positive aft) and wind-tunnel speed (0: hover), atmosphere given directly. Microphones in
the hub-fixed test frame T (x_T downstream, z_T up, y_T = z_T × x_T; docs/reference/rigs.md): ``--mic X Y Z``
(repeatable), ``--mic-file`` (CSV x_m,y_m,z_m or YAML), ``--arc-radius-m`` with ``--arc-angles-deg``.

Runs the stages rig, loads and acoustics into ``--out-dir`` for every rotor of the rig, with the rig's settings
(from the options: the schema defaults of the rig's acoustics section) and the workflow's params of them
(nps.app.plan), and prints each rotor's speed, the thrust, torque, power and C_T of the loads it radiates (the
loads stage's, not the target), its BPF, and at each microphone the OASPL of all rotors and each rotor's
BPF-harmonic levels (also written to ``levels.csv``; with several rotors the harmonic columns carry the rotor's
name). A rig with ``models.bvi`` is radiated with its trimmed loads; its wake and BVI loads come from the
workflow (``snakemake -j2 NAME``), as the output says. With ``--rig`` the rig file gives the rotor, condition,
microphones and resolution: an option that would set them is refused.
"""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd
import yaml

from nps.cli import default, fail, option, parser, run_stage, same_path_problem
from nps.core.atmosphere import isa

N_HARMONICS = 5  # BPF harmonics listed in the printed table and levels.csv (an output choice, no rig field)
ARC_PLANE = "xz"  # plane of an --arc-radius-m arc when --arc-plane is not given: the tunnel's vertical plane
RENAMED = {"--test": "--rig"}  # former option names -> their names now
WITH_RIG = ("help", "debug", "rig", "harmonics", "out_dir")  # the options a --rig run reads (the file gives the rest)


def _rig_from_options(args) -> dict:
    """A rig mapping (nps/app/schemas/rig.schema.yaml) from the options."""
    if bool(args.rotor_file) == bool(args.aircraft):
        raise ValueError("give exactly one of --rotor-file, --aircraft (with --rotor), --rig")
    rotor = {"file": str(Path(args.rotor_file).resolve())} if args.rotor_file else \
        {"aircraft": str(Path(args.aircraft).resolve()), "name": args.rotor}
    sea_level = isa(0.0)  # the atmosphere where density or speed of sound is not given
    density = sea_level.density_kg_m3 if args.density_kg_m3 is None else args.density_kg_m3
    speed_of_sound = sea_level.speed_of_sound_mps if args.speed_of_sound_mps is None else args.speed_of_sound_mps
    condition = {"atmosphere": {"density_kg_m3": density, "speed_of_sound_mps": speed_of_sound,
                                "viscosity_Pa_s": args.viscosity_pa_s},
                 "shaft_angle_deg": args.shaft_angle_deg, "tunnel_speed_mps": args.speed_mps}
    condition.update({k: v for k, v in (("rpm", args.rpm), ("omega_rad_s", args.omega_rad_s), ("control", args.control),
                                        ("pitch_deg", args.pitch_deg), ("thrust_N", args.thrust_n)) if v is not None})
    if args.no_flapping:
        condition["flapping"] = False
    mics = [{"kind": "point", "positions_m": args.mic}] if args.mic else []
    mics += [{"kind": "file", "path": str(Path(args.mic_file).resolve())}] if args.mic_file else []
    if args.arc_radius_m is not None:
        mics.append({"kind": "arc", "radius_m": args.arc_radius_m, "angles_deg": args.arc_angles_deg or [],
                     "plane": args.arc_plane})
    if not mics:
        raise ValueError("microphones: give at least one of --mic, --mic-file, --arc-radius-m")
    resolution = {"n_psi": args.n_psi, "n_r": args.n_r, "samples_per_rev": args.samples_per_rev}
    acoustics = {key: default(f"acoustics.{key}") for key in ("dual_compact_chord_fractions", "bvispl_harmonics")}
    return {"name": "rotor", "description": "python -m nps rotor", "rotor": rotor, "condition": condition,
            "microphones": mics, "resolution": resolution, "acoustics": acoustics,
            "allow_outside_validity": bool(args.allow_outside_validity),
            **({"loads_only": True} if args.loads_only else {})}


def main(argv: list[str]) -> int:
    ap = parser("rotor", __doc__, validity=True)  # --allow-outside-validity: the rig's allow_outside_validity
    ap.add_argument("--rig", help="a rig YAML instead of the rotor and condition options")
    ap.add_argument("--rotor-file", help="rotor YAML (one rotors[] entry)")
    ap.add_argument("--aircraft", help="aircraft YAML holding the rotor")
    ap.add_argument("--rotor", help="rotor name in --aircraft")
    speed = ap.add_mutually_exclusive_group()
    speed.add_argument("--rpm", type=float, help="rotor speed (rev/min)")
    speed.add_argument("--omega-rad-s", type=float, help="rotor speed (rad/s)")
    ap.add_argument("--control", choices=["collective", "collective_only", "rpm", "fixed"], help="default: the rotor's")
    ap.add_argument("--pitch-deg", type=float, help="blade pitch at 75 %% radius (control rpm, fixed)")
    ap.add_argument("--thrust-n", type=float, help="thrust target (control collective, collective_only, rpm)")
    ap.add_argument("--no-flapping", action="store_true", help="rigid blades")
    ap.add_argument("--loads-only", action="store_true", help="set-up and loads only, no acoustics (the rig's loads_only)")
    option(ap, "--shaft-angle-deg", "condition.shaft_angle_deg", schema="rig")
    option(ap, "--speed-mps", "condition.tunnel_speed_mps", schema="rig")
    ap.add_argument("--density-kg-m3", type=float, help="air density (default: ISA sea level, 1.225)")
    ap.add_argument("--speed-of-sound-mps", type=float, help="speed of sound (default: ISA sea level, 340.294)")
    option(ap, "--viscosity-pa-s", "condition.atmosphere.viscosity_Pa_s", schema="rig")
    ap.add_argument("--mic", type=float, nargs=3, action="append", metavar=("X", "Y", "Z"), help="microphone in T (m)")
    ap.add_argument("--mic-file", help="microphone file in T: CSV x_m,y_m,z_m or YAML")
    ap.add_argument("--arc-radius-m", type=float, help="microphone arc about the hub")
    ap.add_argument("--arc-angles-deg", type=float, nargs="+", help="arc angles (any spacing)")
    ap.add_argument("--arc-plane", choices=["xz", "yz", "xy"], default=ARC_PLANE,
                    help=f"plane of the arc in T: xz (r cos a, 0, r sin a), yz, xy (default {ARC_PLANE})")
    ap.add_argument("--harmonics", type=int, default=N_HARMONICS, help=f"BPF harmonics listed (default {N_HARMONICS})")
    for key in ("n_psi", "n_r", "samples_per_rev"):
        option(ap, f"--{key.replace('_', '-')}", f"resolution.{key}", schema="rig")
    ap.add_argument("--out-dir", required=True, help="output directory")
    renamed = next((old for old in RENAMED if any(a == old or a.startswith(f"{old}=") for a in argv)), None)
    if renamed:
        return fail(f"{ap.prog}: {renamed}: unknown option; did you mean {RENAMED[renamed]}? (its former name)")
    args = ap.parse_args(argv)
    if args.rig:
        ignored = [a.option_strings[0] for a in ap._actions if a.dest not in WITH_RIG and getattr(args, a.dest) != a.default]
        if ignored:
            return fail(f"{ignored[0]}: the rig file --rig {args.rig} gives the rotor, its condition, the microphones and "
                        f"the resolution: remove {ignored[0]}, or change the rig file")
    out = Path(args.out_dir)
    rig_file = Path(args.rig) if args.rig else out / "rotor.yaml"
    inputs = {"--rig": args.rig, "--rotor-file": args.rotor_file, "--aircraft": args.aircraft, "--mic-file": args.mic_file}
    clash = same_path_problem({k: v for k, v in inputs.items() if v}, {"--out-dir": out, "--out-dir rotor.yaml": rig_file}
                              if not args.rig else {"--out-dir": out})
    if clash:
        return fail(clash)
    rig = None
    if not args.rig:
        try:
            rig = _rig_from_options(args)
        except ValueError as error:
            return fail(str(error))
    created = [d for d in (out, *out.parents) if not d.exists()]
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        return fail(f"--out-dir {out}: {error.strerror} (a file is where the output directory must go)")
    if rig is not None:
        rig_file.write_text(yaml.safe_dump(rig, sort_keys=False))
    status = run_rig(rig_file, out, args.harmonics, args.debug, options=rig is not None)
    if status:  # refused before any artifact: leave nothing behind
        if rig is not None:
            rig_file.unlink(missing_ok=True)
        for d in created:
            if d.is_dir() and not any(d.iterdir()):
                d.rmdir()
    return status


# rig fields the options set -> the option (the messages of a rig built from the options name the option)
OPTION_OF_FIELD = {"condition.thrust_N": "--thrust-n", "condition.pitch_deg": "--pitch-deg", "condition.rpm": "--rpm",
                   "condition.omega_rad_s": "--omega-rad-s", "condition.atmosphere.density_kg_m3": "--density-kg-m3",
                   "condition.atmosphere.speed_of_sound_mps": "--speed-of-sound-mps",
                   "condition.tunnel_speed_mps": "--speed-mps", "condition.shaft_angle_deg": "--shaft-angle-deg"}


def option_names(message: str) -> str:
    """``message`` with the rig fields set by options followed by their option (``condition.thrust_N`` →
    ``condition.thrust_N (--thrust-n)``)."""
    for field, flag in OPTION_OF_FIELD.items():
        if field in message and flag not in message:
            message = message.replace(field, f"{field} ({flag})", 1)
    return message


def rotor_levels(signals: dict, bpf_hz: dict, n_harmonics: int) -> pd.DataFrame:
    """Per observer the OASPL of every rotor's signals summed and each rotor's BPF-harmonic levels of its own signals
    at its own BPF (:func:`nps.rig.case.tone_levels`); the harmonic columns ``bpf{m}_hz``, ``bpf{m}_db`` are prefixed
    with the rotor's name (and its own ``oaspl_db`` added) when there are several rotors."""
    from nps.rig.case import tone_levels

    several = len(signals) > 1
    parts = [tone_levels(signals, next(iter(bpf_hz.values())), 0)]
    for name, table in signals.items():
        own = tone_levels({name: table}, bpf_hz[name], n_harmonics)
        own = own.drop(columns=["observer"] if several else ["observer", "oaspl_db"])
        parts.append(own.add_prefix(f"{name}_" if several else ""))
    return pd.concat(parts, axis=1)


def run_rig(rig_file: Path, out: Path, n_harmonics: int, debug: bool = False, options: bool = False) -> int:
    """Set-up, loads and acoustics of ``rig_file`` into ``out`` for every rotor of the rig, with the workflow's
    params (nps.app.plan.stage_params of the rig's rotors and settings, the jobs of aircraft ``rigs``, segment
    NAME, variant base); print each rotor's loads (thrust, torque, power and C_T of the loads radiated) and the
    levels. A rig with ``loads_only`` stops after the loads (no acoustics, no levels). The set-up (stage ``rig``) applies every check of the three stages before it writes
    (nps.stages.rig). ``options``: the rig was built from the options (messages name them)."""
    from nps.app.config import ConfigError, load_rig
    from nps.app.io import read_signals, read_table, rotor_path
    from nps.app.plan import CaseConfig, stage_params
    from nps.rig.case import RIG_AIRCRAFT

    try:
        rig = load_rig(rig_file)
    except ConfigError as error:
        return fail(option_names(str(error)) if options else str(error))
    case = CaseConfig({"rotors": rig["rotor_configs"]}, rig["settings"])
    where = {"aircraft": RIG_AIRCRAFT, "segment": rig["name"]}
    trim, mics, loads = str(out / "trim.parquet"), str(out / "microphones.parquet"), out / "loads"
    steps = [
        ("rig", {"config": str(rig_file)}, {"trim": trim, "observers": mics}, {}),
        ("loads", {"trim": trim}, {"loads": str(loads)}, {**stage_params("loads", case), **where}),
        ("acoustics", {"disks": str(loads), "trim": trim, "observers": mics}, {"signals": str(out / "acoustics")},
         {**stage_params("acoustics", case), "obsset": "microphones", "variant": "base", **where}),
    ]
    for stage, inputs, outputs, params in steps[:2] if rig["loads_only"] else steps:
        status = run_stage(stage, inputs, outputs, params, debug)
        if status:
            return status
    names = list(case.rotors)
    rows = read_table(trim).set_index("rotor")
    bpf_hz = {name: rows.loc[name, "n_blades"] * rows.loc[name, "omega_rad_s"] / (2.0 * math.pi) for name in names}
    if not rig["loads_only"]:
        levels = rotor_levels(read_signals(out / "acoustics", names), bpf_hz, n_harmonics)
        levels = read_table(mics)[["observer", "x_T_m", "y_T_m", "z_T_m"]].merge(levels, on="observer")
        levels.to_csv(out / "levels.csv", index=False, float_format="%.6g")
    print()
    for name in names:
        summary = read_table(rotor_path(loads, name, "_summary")).set_index("quantity")["value"]
        omega = rows.loc[name, "omega_rad_s"]
        print(f"rotor {name}: omega {omega:.6g} rad/s ({omega * 30 / math.pi:.6g} rpm), thrust {summary['thrust_N']:.6g} N, "
              f"torque {summary['torque_Nm']:.6g} N m, power {summary['power_W']:.6g} W, C_T {summary['ct']:.5g}, "
              f"BPF {bpf_hz[name]:.6g} Hz")
    if rig["loads_only"]:
        print(f"loads only (loads_only): no acoustics; written: {loads}")
        return 0
    if rig["models"]["bvi"]:
        print(f"note: the trimmed loads are radiated (variant base); the rig's wake and BVI loads (models.bvi): "
              f"snakemake -j2 {rig['name']}")
    prefix = {name: f"{name}_" if len(names) > 1 else "" for name in names}
    harmonics = [f"{prefix[name]}bpf{m}_db" for name in names for m in range(1, n_harmonics + 1)]
    print(levels[["observer", "x_T_m", "y_T_m", "z_T_m", "oaspl_db"] + harmonics]
          .to_string(index=False, float_format=lambda v: f"{v:.2f}"))
    print(f"written: {out / 'levels.csv'}")
    return 0
