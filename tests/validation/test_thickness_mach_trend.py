"""Physics check of the tip-speed sweep: the in-plane thickness-noise peak against the tip Mach number.

For a rigid blade the thickness noise is that of its displaced volume (Isom 1975; Ffowcs Williams &
Hawkings 1969, the monopole term with H = 1 inside the blade): p(x, t) = ρ0/(4π) ∂²/∂t² Σ [A dr /
(r |1 − M_r|)]_ret. In hover the law's whole Mach-number dependence is kinematic (1/(1 − M_r) Doppler
factors and the retarded times), so the change of the negative in-plane peak between tip speeds is fixed
by the rotor's geometry alone: evaluated here by direct quadrature (independently of nps: numpy only) for
the bundled helicopter's main rotor at −20 %, 0 and +5 % tip speed (the sweep of
config/studies/tip_speed_blades.yaml), and compared with NPS (nps.Case, dual-compact thickness) within
0.3 dB. The law gives −14.5 dB for −20 % (M_H 0.63 → 0.50), +3.7 dB for +5 %: far steeper than the
M_H³ of the low-Mach limit (−5.8 dB), which is the point of the check.
"""

from __future__ import annotations

import copy
from pathlib import Path

import numpy as np
import pytest
import yaml

import nps
from campaigns import TINY
from nps.app.io import read_table

REPO = Path(__file__).resolve().parents[2]
SCALES = (0.8, 1.0, 1.05)
TOLERANCE_DB = 0.3
R_OBSERVER_R = 10.0


def isom_peak(omega_rad_s: float, radius_m: float, root_m: float, n_blades: int, c_mps: float,
              distance_m: float, n_r: int = 200, n_theta: int = 20001) -> float:
    """Negative peak of Σ_blades ∂²/∂t² ∫ dr / (r_obs |1 − M_r|) (per unit section area and ρ0/4π) at an
    in-plane observer ``distance_m`` from the hub of a hovering rotor (exact geometry, retarded time by
    quadrature over the source azimuth)."""
    radii = np.linspace(root_m, radius_m, n_r)
    theta = np.linspace(0.0, 2.0 * np.pi, n_theta)
    tau = theta / omega_rad_s
    period = 2.0 * np.pi / omega_rad_s
    grid = np.linspace(0.2 * period, 1.2 * period, 40000)
    total = np.zeros_like(grid)
    for r in radii:
        y = np.stack([r * np.cos(theta), r * np.sin(theta)])
        v = np.stack([-r * omega_rad_s * np.sin(theta), r * omega_rad_s * np.cos(theta)])
        d = np.array([distance_m, 0.0])[:, None] - y
        dist = np.hypot(*d)
        mach_r = (v * d).sum(axis=0) / dist / c_mps
        reception = tau + dist / c_mps
        first = np.gradient(1.0 / (dist * (1.0 - mach_r)), tau) / (1.0 - mach_r)
        second = np.gradient(first, tau) / (1.0 - mach_r)
        times, values = np.concatenate([reception - period, reception, reception + period]), np.tile(second, 3)
        for k in range(n_blades):
            total += np.interp((grid + k * period / n_blades - 0.2 * period) % period + 0.2 * period, times, values)
    return float(total.min() * (radii[1] - radii[0]))


@pytest.fixture(scope="module")
def hover_peaks(tmp_path_factory):
    """NPS's negative peak of the main rotor's thickness pressure at the in-plane observer, per tip-speed scale."""
    d = tmp_path_factory.mktemp("hover")
    config = copy.deepcopy(TINY)
    config["campaign"].update(segments=["seg1"], allow_outside_validity=False)
    config["observer_sets"] = {"hemisphere": {"kind": "points_ahead", "radius_R": R_OBSERVER_R, "elevations_deg": [0.0], "moving": True}}
    config["models"].update(bvi=False, hsi=False, bvi_segments=[], broadband=False, absorption=False)
    config["figures"] = {"disk_segments": [], "map_segments": [], "bvi_map_segments": [], "hsi_segments": []}
    config["resolution"] = {"n_psi": 360, "n_r": 50, "wake_revolutions": 2, "samples_per_rev": 4096}
    (d / "config.yaml").write_text(yaml.safe_dump(config))
    (d / "hover.yaml").write_text(yaml.safe_dump({"name": "hover", "segments": [
        {"id": "seg1", "name": "hover", "aircraft": {"helicopter": {"forward_speed_mps": 0.0, "climb_speed_mps": 0.0}}}]}))
    base = yaml.safe_load((REPO / "config/aircraft/helicopter.yaml").read_text())
    peaks = {}
    for scale in SCALES:
        aircraft = copy.deepcopy(base)
        aircraft["rotors"][0]["omega_rad_s"] = 28.0 * scale
        aircraft["rotors"][0]["thrust_axis_body"] = [0.0, 0.0, 1.0]  # observer in the shaft plane
        folder = d / f"scale_{scale}"
        folder.mkdir()
        (folder / "helicopter.yaml").write_text(yaml.safe_dump(aircraft))
        case = nps.Case.from_files(folder / "helicopter.yaml", d / "hover.yaml", d / "config.yaml", cache_dir=d / "cache")
        result = case.run("seg1")
        signals = read_table(Path(result.artifacts["acoustics"]["hemisphere"]["signals"]) / "main.parquet")
        trim = result.trim.set_index("rotor").loc["main"]
        peaks[scale] = (float(signals.loc[signals["group"] == "thickness", "p_Pa"].min()), trim)
    return peaks


def test_in_plane_thickness_peak_follows_the_displaced_volume_law(hover_peaks):
    rotor = yaml.safe_load((REPO / "config/aircraft/helicopter.yaml").read_text())["rotors"][0]
    reference = {}
    for scale, (_, trim) in hover_peaks.items():
        c = float(trim["speed_of_sound_mps"])
        reference[scale] = isom_peak(float(trim["omega_rad_s"]), rotor["radius_m"], rotor["root_cutout_m"], rotor["n_blades"], c,
                                     R_OBSERVER_R * rotor["radius_m"])
    for scale in SCALES:
        nps_db = 20.0 * np.log10(hover_peaks[scale][0] / hover_peaks[1.0][0])
        law_db = 20.0 * np.log10(reference[scale] / reference[1.0])
        assert abs(nps_db - law_db) < TOLERANCE_DB, (scale, nps_db, law_db)
    # the trend is the steep compressible one, not the low-Mach M^3
    assert 20.0 * np.log10(reference[0.8] / reference[1.0]) < -12.0
