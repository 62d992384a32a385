"""HART-II baseline case (tests/data/hart_ii/README.md): rotor, trim, BVI loads and the data.

Geometry and operating condition from the OpenCOPTER set-up of the test: R = 2 m, B = 4,
c = 0.121 m, −8° linear twist, root cutout 0.44 m, Ω = 109.12 rad/s, V = 32.9 m/s, shaft
4.3° aft (free stream up through the disk: μ_z < 0), T = 3300 N, hub moments 20 / −20 N·m,
ρ = 1.2055 kg/m³, c0 = 341.7 m/s, Lock number 8. Assumptions (not in the data): NACA 23012
lift slope 6.0 /rad and zero-lift angle −1.2°, equivalent flap-hinge offset 0.29 m
(Bo105 hingeless rotor, ≈ 14.5 % R).

Measured blade motion (:func:`case_setup`): the elastic twist, and the flap as the tip height
over the hub plane, z_tip(ψ) = R sin β_p + z_el(ψ) cos β_p with the 2.5° precone β_p
(opencopter_hart_ii_geometry.json5, "Coning angle") and the measured elastic tip deflection
z_el = 1.575 m · tan f(ψ) (f: the "flap hinge" Fourier series of opencopter_hart_ii_params.json5,
which OpenCOPTER fitted to the HART-II tip deflection data 100 z/R as atan(z/1.575 m) about its
equivalent hinge 0.425 m from the hub), given to NPS as the flap angle β = asin(z_tip/R)
(``RotorGeometry.prescribed_flap_harmonics``).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from nps.rotor import bet, station_loads

from nps.wake import bvi

from nps.wake import free as freewake

from nps.wake import interaction

from nps.wake import prescribed as wake
from nps.rotor.airfoils import LinearAirfoil
from nps.rotor.geometry import OperatingPoint, RotorGeometry

from multirotor_case import placed

DATA = Path(__file__).resolve().parents[1] / "data" / "hart_ii"
RADIUS_M, OMEGA, SPEED, SHAFT_RAD = 2.0, 109.12, 32.9, np.radians(4.3)
RHO, C0, CHORD = 1.2055, 341.7, 0.121
R_OVER_R = 0.87

GEOMETRY = RotorGeometry(
    name="hart_ii", n_blades=4, radius_m=RADIUS_M, chord_m=CHORD, root_cutout_m=0.44,
    twist_rad=np.radians(-8.0), thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29,
    rotation_sign=1, airfoil=LinearAirfoil(lift_slope_per_rad=6.0, alpha0_rad=np.radians(-1.2)),
)
MU_X = SPEED * np.cos(SHAFT_RAD) / (OMEGA * RADIUS_M)
MU_Z = -SPEED * np.sin(SHAFT_RAD) / (OMEGA * RADIUS_M)
OPERATING_POINT = OperatingPoint(
    omega_rad_s=OMEGA, mu_x=MU_X, mu_y=0.0, mu_z=MU_Z, density_kg_m3=RHO, speed_of_sound_mps=C0,
    thrust_N=3300.0, roll_moment_Nm=20.0, pitch_moment_Nm=-20.0,
)
TRIM_ROW = dict(
    n_blades=4, radius_m=RADIUS_M, omega_rad_s=OMEGA, rotation_sign=1, mu_x=MU_X, mu_y=0.0, mu_z=MU_Z,
    density_kg_m3=RHO, speed_of_sound_mps=C0,
)


@dataclass(frozen=True)
class Case:
    """One HART-II condition (opencopter_hart_ii_params.json5, shared validation set): shaft angle
    (deg, aft), ρ, c0, Ω, targets T, M_x, M_y, the 3/rev HHC θ3 cos(3ψ − ψ3), the measured
    elastic-twist harmonics (n, cos, sin) in rad (tip values, linear along the span) and the
    measured flap-hinge harmonics f(ψ) (n, cos, sin) in rad (module doc)."""

    name: str
    shaft_deg: float
    rho: float
    c0: float
    omega: float
    thrust: float
    roll: float
    pitch: float
    theta3_deg: float
    psi3_deg: float
    elastic_twist: tuple
    flap: tuple


def _harmonics(cos, sin):
    return tuple((n, c, sin[n - 1] if 1 <= n <= len(sin) else 0.0) for n, c in enumerate(cos))


CASES = {
    "BL": Case("BL", 4.3, 1.2055, 341.7, 109.12, 3300.0, 20.0, -20.0, 0.0, 300.0, _harmonics(
        [-0.009037, 0.002961, -0.009796, 0.0005252, 0.001129, -0.0006439, -0.0001786, -0.0004622],
        [-0.003797, 5.21e-06, -0.000541, 0.001793, 0.0003353, -2.835e-05, -0.00036]), _harmonics(
        [-0.007672, 0.002095, -0.0008852, -0.001253, -0.0001377], [-0.009844, -0.0004784, 0.001229, -1.665e-06])),
    "MN": Case("MN", 4.3, 1.1931, 342.2, 109.01, 3300.0, 30.0, -30.0, 0.8, 300.0, _harmonics(
        [-0.009094, 0.003301, -0.007287, 0.02032, 0.001536, 0.0007229, -0.001406],
        [-0.00368, -0.001816, 0.009208, -0.001166, 0.0009517, 0.0008305]), _harmonics(
        [-0.007885, 0.004178, -0.002791, -0.005694, 7.409e-05, 0.0002689, 8.953e-05, 0.0001174, 8.001e-05],
        [-0.01148, 0.002682, 0.003662, -8.164e-05, -9.473e-05, -6.167e-05, -6.646e-05, 7.512e-05])),
    "MV": Case("MV", 4.5, 1.1868, 343.0, 109.01, 3290.0, 20.0, -30.0, 0.8, 180.0, _harmonics(
        [-0.008342, 0.00214, -0.01411, -0.002624, -0.0006886, -0.0007247, -3.277e-05],
        [-0.001991, 0.0008361, -0.02615, 0.001571, 0.001287, -6.494e-05]), _harmonics(
        [-0.00689, 0.001587, 0.002895, 0.003974, -0.0002329, -0.0002362, -6.413e-05, -7.967e-05, 1.073e-05],
        [-0.0103, -0.001023, 0.003785, 3.528e-05, 3.088e-05, 9.54e-06, -0.0001532, 3.409e-05])),
}


PRECONE_RAD = np.radians(2.5)
FLAP_ARM_M = 1.575  # tip to OpenCOPTER's equivalent flap hinge (0.075 + 0.35 m from the hub)


def tip_flap_harmonics(case: Case, n_max: int = 8, n_psi: int = 360) -> tuple:
    """NPS flap harmonics (n, cos, sin) in rad of the measured tip height (module doc)."""
    psi = 2.0 * np.pi * np.arange(n_psi) / n_psi
    f = sum(c * np.cos(n * psi) + s * np.sin(n * psi) for n, c, s in case.flap)
    z_tip = RADIUS_M * np.sin(PRECONE_RAD) + FLAP_ARM_M * np.tan(f) * np.cos(PRECONE_RAD)
    spectrum = np.fft.rfft(np.arcsin(z_tip / RADIUS_M)) / n_psi
    return tuple((n, float((1.0 if n == 0 else 2.0) * spectrum[n].real), float(-2.0 * spectrum[n].imag))
                 for n in range(n_max + 1))


def case_setup(case: Case, measured_flap: bool = True):
    """(geometry with the prescribed blade motion, operating point, trim row) of a condition;
    ``measured_flap`` False keeps NPS's rigid-flap solution instead of the measured tip motion."""
    from dataclasses import replace

    geometry = replace(GEOMETRY, elastic_twist_harmonics=case.elastic_twist,
                       prescribed_flap_harmonics=tip_flap_harmonics(case) if measured_flap else (),
                       higher_harmonic_pitch=((3, np.radians(case.theta3_deg), np.radians(case.psi3_deg)),)
                       if case.theta3_deg else ())
    shaft = np.radians(case.shaft_deg)
    mu_x = SPEED * np.cos(shaft) / (case.omega * RADIUS_M)
    mu_z = -SPEED * np.sin(shaft) / (case.omega * RADIUS_M)
    op = OperatingPoint(omega_rad_s=case.omega, mu_x=mu_x, mu_y=0.0, mu_z=mu_z, density_kg_m3=case.rho,
                        speed_of_sound_mps=case.c0, thrust_N=case.thrust, roll_moment_Nm=case.roll,
                        pitch_moment_Nm=case.pitch)
    row = dict(n_blades=4, radius_m=RADIUS_M, omega_rad_s=case.omega, rotation_sign=1, mu_x=mu_x, mu_y=0.0, mu_z=mu_z,
               density_kg_m3=case.rho, speed_of_sound_mps=case.c0)
    return geometry, op, row


@dataclass(frozen=True)
class HartResult:
    trim: bet.RotorTrim
    bvi: bvi.BVIResult
    state: wake.WakeState
    psi_deg: np.ndarray
    cn_base: np.ndarray
    cn_bvi: np.ndarray
    r_station_m: float


def cn_m2(fz_N_per_m, rho: float = RHO, c0: float = C0):
    """M²C_n = F_n / (½ ρ c0² c), F_n ≈ F_z (normal force per span): :func:`nps.rotor.station_loads.m2cn`, the
    station-loads output's definition."""
    return station_loads.m2cn(fz_N_per_m, rho, c0, CHORD)


def run(n_psi: int = 360, n_r: int = 50, model: wake.WakeModel | None = None, bvi_model: bvi.BVIModel = bvi.BVIModel()) -> HartResult:
    trim = bet.trim_rotor(GEOMETRY, OPERATING_POINT, bet.DiskGrid(n_psi, n_r))
    model = model or wake.WakeModel(steps_per_rev=n_psi)
    res = bvi.bvi_loads(trim.disk, TRIM_ROW, GEOMETRY, trim.totals.ct, model, bvi_model)
    grid = bvi.disk_grid(res.disk)
    j = int(np.argmin(np.abs(grid.r_m / RADIUS_M - R_OVER_R)))
    fz0 = trim.disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
    fz1 = res.disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
    state = bvi.wake_state(trim.disk, TRIM_ROW, trim.totals.ct)
    return HartResult(trim, res, state, np.degrees(grid.psi_rad), cn_m2(fz0), cn_m2(fz1), float(grid.r_m[j]))


def measured_cn(case: str = "BL"):
    """(ψ deg, M²C_n) measured at r/R = 0.87, 2048 samples, of condition BL, MN or MV."""
    values = np.loadtxt(DATA / f"CnM2_{case}_ca.tec", skiprows=3)
    return np.arange(values.size) * 360.0 / values.size, values


def read_piv(name: str, inboard: bool = False) -> np.ndarray:
    """Rows (psi_deg, x_m, y_m, z_m) of a DNW PIV vortex-position file (hub frame): the tip
    vortices, or with ``inboard`` only the zones titled "inboard vortex" (MV's advancing side: the
    opposite-sign vortex trailed inboard of a negatively loaded tip, which NPS's single tip
    vortex per blade does not represent)."""
    rows, in_inboard_zone = [], False
    for line in (DATA / name).read_text().splitlines():
        if line.lstrip().startswith("ZONE"):
            in_inboard_zone = "inboard vortex" in line
        parts = line.split()
        if (len(parts) == 6 and not line.lstrip().startswith(("TITLE", "VARIABLES", "ZONE"))
                and in_inboard_zone == inboard):
            rows.append([float(p) for p in parts[2:]])
    return np.array(rows)


def high_pass(values: np.ndarray, lowest: int = 10) -> np.ndarray:
    """Periodic signal with harmonics below ``lowest`` removed (BVI content is ≳ 10/rev)."""
    spectrum = np.fft.rfft(values)
    spectrum[:lowest] = 0.0
    return np.fft.irfft(spectrum, n=values.size)


def window_metrics(psi_deg, values, lo, hi):
    """(ψ of the steepest high-passed change, peak-to-peak) inside [lo, hi] deg."""
    hp = high_pass(values)
    slope = np.gradient(hp, psi_deg)
    inside = (psi_deg >= lo) & (psi_deg <= hi)
    i = np.flatnonzero(inside)[np.argmax(np.abs(slope[inside]))]
    return float(psi_deg[i]), float(np.ptp(hp[inside])), float(slope[i])


def piv_miss_distances(state: wake.WakeState, model: wake.WakeModel, case: str = "BL") -> list[tuple]:
    """For each PIV tip vortex of condition ``case``: (side, ψ, y, measured x, z, predicted x, z,
    miss distance in the cut plane y = y_meas), matching the nearest predicted crossing of any
    blade's vortex."""
    return _miss_distances(lambda psi: wake.wake_snapshot(state, model, psi).nodes_m, case)


def _miss_distances(nodes_at, case: str = "BL") -> list[tuple]:
    """PIV comparison for a wake given as blade-0 azimuth (rad) → nodes (B, N, 3) in H' (m)."""
    out = []
    for side, name in (("advancing", f"dnw_adv_{case.lower()}53.tec"), ("retreating", f"dnw_ret_{case.lower()}53.tec")):
        data = read_piv(name)
        for psi_deg in np.unique(data[:, 0]):
            nodes = nodes_at(np.radians(psi_deg))
            for p, x, y, z in data[data[:, 0] == psi_deg]:
                cross = wake.filament_plane_crossings(nodes, 1, y)
                d = np.hypot(cross[:, 0] - x, cross[:, 2] - z)
                k = int(np.argmin(d))
                out.append((side, psi_deg, y, x, z, cross[k, 0], cross[k, 2], float(d[k])))
    return out


def convection_spacings(records: list[tuple], radius_m: float = RADIUS_M, omega: float = OMEGA,
                        speed_mps: float = SPEED, shaft_rad: float = SHAFT_RAD) -> np.ndarray:
    """Streamwise spacing of consecutive vortices in the front half of each PIV cut, measured and
    predicted, as fractions of the free stream's advance in one blade passage V cos α_s 2π/(BΩ)
    (rows (measured, predicted); records of :func:`piv_miss_distances`). Consecutive vortices of
    one cut are a blade passage apart in age, so the spacing measures the convection speed free
    of any origin or height offset. Left out: the cuts at |y| > 0.875 R (near the lateral edge
    the tip path runs along x, and the spacing measures the filaments' lateral drift), pairs
    closer than half a passage (the same vortex listed twice) and pairs whose predicted spacing
    exceeds 1.5 passages (the nearest-crossing match skipped a vortex)."""
    advance = speed_mps * np.cos(shaft_rad) * 2.0 * np.pi / (GEOMETRY.n_blades * omega)
    cuts: dict = {}
    for r in records:
        cuts.setdefault((r[0], r[1], round(r[2], 1)), []).append(r)
    out = []
    for rows in cuts.values():
        rows = sorted(rows, key=lambda r: r[3])
        for a, b in zip(rows[:-1], rows[1:]):
            measured, predicted = (b[3] - a[3]) / advance, (b[5] - a[5]) / advance
            if a[3] < 0.0 and abs(a[2]) <= 0.875 * radius_m and 0.5 < measured < 1.5 and predicted < 1.5:
                out.append((measured, predicted))
    return np.array(out).T


def paired_height_changes(base: list[tuple], other: list[tuple], max_dx_m: float = 0.2) -> list[tuple]:
    """Vortex height changes between two conditions' PIV comparisons (records of
    :func:`piv_miss_distances`): each vortex of ``base`` paired with the vortex of ``other`` in the
    same cut (ψ, y within 0.1 m) nearest in x (within ``max_dx_m``): (side, measured Δz,
    predicted Δz) in m, the predicted heights being those of the crossings matched to each."""
    out = []
    for side, psi, y, x, z, _, z_pred, _ in base:
        same_cut = [r for r in other if r[1] == psi and abs(r[2] - y) < 0.1 and abs(r[3] - x) < max_dx_m]
        if same_cut:
            match = min(same_cut, key=lambda r: abs(r[3] - x))
            out.append((side, match[4] - z, match[6] - z_pred))
    return out


WINDOWS_DEG = ((30, 80), (280, 330))


def window_comparison(psi_deg, cn) -> list[tuple]:
    """Per BVI window (advancing, retreating): (lo, hi, lag deg, ρ, model p2p, measured p2p)."""
    pm, cm = measured_cn()
    out = []
    for lo, hi in WINDOWS_DEG:
        lag, rho = window_lag(psi_deg, cn, pm, cm, lo, hi)
        out.append((lo, hi, lag, rho, window_metrics(psi_deg, cn, lo, hi)[1], window_metrics(pm, cm, lo, hi)[1]))
    return out


def window_lag(psi_model_deg, model, psi_meas_deg, meas, lo, hi, max_lag_deg=15.0):
    """Lag (deg, + = model later) maximising the correlation of the high-passed signals in
    [lo, hi], and that correlation coefficient. The model is interpolated (periodic) to the
    measured azimuths."""
    hp_model = high_pass(model)
    hp_meas = high_pass(meas)
    step = psi_meas_deg[1] - psi_meas_deg[0]
    inside = (psi_meas_deg >= lo) & (psi_meas_deg <= hi)
    best = (0.0, -2.0)
    for lag in np.arange(-max_lag_deg, max_lag_deg + step / 2, step):
        shifted = np.interp(psi_meas_deg[inside] + lag, psi_model_deg, hp_model, period=360.0)
        rho = float(np.corrcoef(shifted, hp_meas[inside])[0, 1])
        if rho > best[1]:
            best = (float(lag), rho)
    return best


def event_offsets(psi_model_deg, model, psi_meas_deg, meas, lo, hi, prominence=0.3) -> list[tuple]:
    """Timing of the individual BVI events: for each extremum of the high-passed measurement in
    [lo, hi] (peaks and troughs with a prominence ≥ ``prominence`` × the window's largest |value|),
    the nearest model extremum of the same kind (same prominence rule, window ± 3°):
    (kind ±1, ψ measured, ψ model, offset deg, + = model later).

    The best-correlation lag (:func:`window_lag`) measures where the whole event train lies, and
    with events ≈ 10° apart it can hop by one spacing when the model's envelope (which events are
    strong) differs from the measured one; the offsets measure each event. Both are reported.
    """
    from scipy.signal import find_peaks

    def extrema(psi, values, kind):
        values = high_pass(values)
        inside = (psi >= lo - 3.0) & (psi <= hi + 3.0)
        idx, _ = find_peaks(kind * values[inside], prominence=prominence * np.abs(values[inside]).max())
        return psi[inside][idx]

    out = []
    for kind in (1, -1):
        model_psi = extrema(np.asarray(psi_model_deg, dtype=float), model, kind)
        for psi_m in extrema(np.asarray(psi_meas_deg, dtype=float), meas, kind):
            if lo <= psi_m <= hi and model_psi.size:
                nearest = float(model_psi[np.argmin(np.abs(model_psi - psi_m))])
                out.append((kind, float(psi_m), nearest, nearest - float(psi_m)))
    return out


@dataclass(frozen=True)
class HartFreeResult:
    trim: bet.RotorTrim
    result: interaction.AircraftBVI
    psi_deg: np.ndarray
    cn_bvi: np.ndarray


def run_free(n_psi: int = 360, n_r: int = 50, free_model: freewake.FreeWakeModel = freewake.FreeWakeModel(),
             wake_model: wake.WakeModel | None = None, case: Case | None = None,
             measured_flap: bool = True) -> HartFreeResult:
    """The baseline (or ``case`` with its measured blade motion, :func:`case_setup`) with the free
    wake: :func:`nps.wake.interaction.aircraft_bvi_loads` on a one-rotor aircraft (hub at the origin,
    hub frame = G axes)."""
    import pandas as pd

    geometry, op, trim_row = (case_setup(case, measured_flap) if case is not None
                              else (GEOMETRY, OPERATING_POINT, TRIM_ROW))
    trim = bet.trim_rotor(geometry, op, bet.DiskGrid(n_psi, n_r))
    row = placed(dict(trim_row, rotor="hart_ii", ct=trim.totals.ct, thrust_N=op.thrust_N,
                      roll_moment_Nm=op.roll_moment_Nm, pitch_moment_Nm=op.pitch_moment_Nm))
    config = dict(name="hart_ii", n_blades=4, radius_m=RADIUS_M, chord_m=CHORD, root_cutout_m=0.44, twist_deg=-8.0,
                  thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29, rotation="ccw",
                  airfoil=dict(lift_slope_per_rad=6.0, alpha0_deg=-1.2),
                  higher_harmonic_pitch=[dict(n=n, amplitude_deg=np.degrees(a), phase_deg=np.degrees(p))
                                         for n, a, p in geometry.higher_harmonic_pitch],
                  elastic_twist_harmonics=_degrees(geometry.elastic_twist_harmonics),
                  prescribed_flap=_degrees(geometry.prescribed_flap_harmonics))
    result = interaction.aircraft_bvi_loads(pd.DataFrame([row]), {"hart_ii": config}, {"hart_ii": trim.disk},
                                            {"hart_ii": trim.summary()}, wake_model or wake.WakeModel(steps_per_rev=n_psi),
                                            free_model)
    disk = result.results["hart_ii"].disk
    grid = bvi.disk_grid(disk)
    j = int(np.argmin(np.abs(grid.r_m / RADIUS_M - R_OVER_R)))
    fz = disk["fz_N_per_m"].to_numpy().reshape(grid.shape)[:, j]
    return HartFreeResult(trim, result, np.degrees(grid.psi_rad), cn_m2(fz, op.density_kg_m3, op.speed_of_sound_mps))


def _degrees(harmonics) -> list[dict]:
    """Config entries ``[{n, cos_deg, sin_deg}]`` of harmonics (n, cos rad, sin rad)."""
    return [dict(n=n, cos_deg=np.degrees(c), sin_deg=np.degrees(s)) for n, c, s in harmonics]


def piv_miss_distances_free(solution: freewake.FreeWakeSolution, case: str = "BL") -> list[tuple]:
    """As :func:`piv_miss_distances` for the relaxed free wake as the blade loads see it
    (:func:`nps.wake.free.wake_snapshot`: the Beddoes model's age grid and length, 1° over 4
    revolutions, free and far wake, the last distortion kept beyond them)."""
    return _miss_distances(lambda psi: freewake.wake_snapshot(solution, solution.rotors[0].name, psi).nodes_m, case)
