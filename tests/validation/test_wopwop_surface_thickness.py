"""``nps wopwop run`` on a blade surface patch against the full-surface F1A thickness reference.

Case: that of tests/validation/test_acoustics_thickness_surface.py (1/7-scale UH-1H in hover: B = 2, R = 1.045 m,
c = 0.0762 m, NACA 0012 with a closed trailing edge, zero pitch, root cut-out 0.2 R, observer 3.09 R from the hub in
the rotor plane and 30° below it), written as a PSU-WOPWOP case (:mod:`wopwop_cases`): one constant, structured,
node-centred geometry zone per blade, a closed wrap around the section (i: trailing edge → upper surface → leading
edge → lower surface → trailing edge, cosine-spaced; j: uniform span stations from 0.2 R to R), outward unit normals
(so the runner builds face-centred quadrilaterals from the nodes), no loading file; the blade container under a
rotor container turning at Omega (KnownFunction), a second blade container turned by π; one stationary observer
container holding both observers; dTau = T/256. The runner takes its periodic path.

Reference (independent of nps): ``full_surface_pressure`` of that file, Farassat 1A's thickness surface integral in
numpy (cosine-spaced chordwise strips × uniform spanwise strips per side, exact ∫ v_n dS per panel at its centroid,
1024 source steps, linear interpolation onto the observer grid); compared: the negative peak and the pulse width
(``negative_pulse``) and the pointwise max |difference| over the reference's peak-to-peak.

Convergence measured against the reference at 80 × 80 panels per side and 8192 steps (M 0.88 in plane; peak,
width, pointwise): runner 8 × 20 panels per side −4.1 %, +1.0 %, 3.7 %; 12 × 30 −1.7 %, +0.39 %, 1.6 %;
16 × 40 −0.90 %, +0.17 %, 0.84 %; 24 × 60 −0.30 %, +0.01 %, 0.29 % (second order in the panel size); 256, 512 or
1024 source steps change the runner's result by < 0.001 %. The reference's own default (24 × 60, 1024 steps) is
−0.31 %, +0.02 %, 0.30 % from its 80 × 80 result. Used here: 16 × 40 panels per side, 256 steps (≈ 4 s a Mach
number).
"""

import numpy as np
import pytest

import wopwop_cases as wc
from test_acoustics_thickness_surface import (
    B, C0, CHORD, N_OUT, RADIUS, RHO0, ROOT, THICKNESS_RATIO, _half_thickness, _observer, full_surface_pressure,
    negative_pulse)

N_CHORD, N_SPAN, STEPS_PER_REV = 16, 40, 256
ELEVATIONS_DEG = (0.0, -30.0)
MACHS = (0.3, 0.88)


def chord_stations(n_chord: int) -> np.ndarray:
    """Cosine-spaced chord fractions 0 … 1 (n_chord + 1), as the reference's panel edges."""
    return 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, n_chord + 1)))


def outward_normal(x: np.ndarray, side: np.ndarray) -> np.ndarray:
    """Unit outward normal (chord offset toward the leading edge, z) of the NACA 00xx surface at chord fraction x
    (side +1 upper, −1 lower): ∝ (y_t'(x), ±1), written as √x (y_t', ±1) to stay finite at the leading edge."""
    root_x = np.sqrt(x)
    slope = 5 * THICKNESS_RATIO * (0.2969 / 2 - root_x * (0.1260 + 2 * 0.3516 * x - 3 * 0.2843 * x**2 + 4 * 0.1036 * x**3))
    normal = np.stack([slope, side * root_x], axis=-1)
    return normal / np.linalg.norm(normal, axis=-1, keepdims=True)


def section_point(r_m, x, side) -> np.ndarray:
    """Blade-frame position (e_r, e_t toward the leading edge, z) of the surface at radius r, chord fraction x,
    side ±1; the pitch axis at the quarter chord, as in the reference."""
    r_m, x, side = np.broadcast_arrays(r_m, x, side)
    return np.stack([r_m, (0.25 - x) * CHORD, side * _half_thickness(x) * CHORD], axis=-1)


def blade_surface(n_chord: int, n_span: int):
    """The blade as one closed wrap: nodes (n_span + 1, 2 n_chord + 1), outward unit normals (module doc)."""
    x = chord_stations(n_chord)
    x_wrap = np.concatenate([x[::-1], x[1:]])
    side = np.concatenate([np.ones(n_chord + 1), -np.ones(n_chord)])
    r = np.linspace(ROOT, RADIUS, n_span + 1)[:, None]
    normal = np.broadcast_to(outward_normal(x_wrap, side), (n_span + 1, x_wrap.size, 2))
    normals = np.concatenate([np.zeros(normal.shape[:2] + (1,)), normal], axis=-1)
    return wc.structured_zone("blade", section_point(r, x_wrap, side), normals)


def end_face(name: str, r_m: float, outward: float, n_chord: int):
    """A flat blade end at radius r (tip: outward +1, root: −1): j = lower, upper surface; unit normals ±e_r."""
    x = chord_stations(n_chord)
    nodes = np.stack([section_point(r_m, x, s) for s in (-1.0, 1.0)])
    normals = np.zeros_like(nodes)
    normals[..., 0] = outward
    return wc.structured_zone(name, nodes, normals)


def run_hover(directory, mach_tip: float, zones) -> np.ndarray:
    """Thickness pressure (Pa, (2 observers, N_OUT)) of the two-blade rotor made of ``zones``, on the reference's
    grid t_k = k T/N_OUT; checks that nothing went to the loading output and that the periodic path was taken (the
    second blade radiated as a copy of the first, shifted by T/2, or on its own)."""
    omega = mach_tip * C0 / RADIUS
    period = 2 * np.pi / omega
    observers = [wc.observer_groups("observers", [_observer(e) for e in ELEVATIONS_DEG], 0.0,
                                    (N_OUT - 1) * period / N_OUT, N_OUT)]
    sources = wc.rotor_groups(omega, B, period / STEPS_PER_REV, "blade.dat")
    case = wc.write_case(directory, observers, sources, C0, RHO0, {"blade.dat": wc.geometry_file(zones)})
    (result,) = wc.run(case)
    pressure = result.pressure_pa["rotor"]
    assert np.all(pressure[:, 1] == 0.0) and set(result.modes.values()) <= {"periodic", "periodic (copy)"}
    return pressure[:, 0]


@pytest.fixture(scope="module")
def surface_runs(tmp_path_factory):
    """Runner thickness pressure of the blade surface, per M_tip: (2 observers, N_OUT)."""
    return {m: run_hover(tmp_path_factory.mktemp(f"surface_{m}"), m, [blade_surface(N_CHORD, N_SPAN)]) for m in MACHS}


def compare(p, reference, mach_tip, label):
    """(peak, width, pointwise) relative differences of ``p`` against ``reference``, printed."""
    dt = 2 * np.pi * RADIUS / (mach_tip * C0) / N_OUT
    (peak, width), (ref_peak, ref_width) = negative_pulse(p, dt), negative_pulse(reference, dt)
    out = peak / ref_peak - 1, width / ref_width - 1, np.abs(p - reference).max() / np.ptp(reference)
    print(f"{label}: reference {ref_peak:.4g} Pa, {ref_width * 1e6:.1f} us; peak {out[0]:+.3%}, width {out[1]:+.3%}, "
          f"max |difference| / p2p {out[2]:.3%}")
    return out


@pytest.mark.parametrize("mach_tip", MACHS)
def test_surface_patch_same_panels_as_reference(surface_runs, mach_tip):
    """The reference on the runner's own panels (16 × 40 per side, 1024 steps): peak, width and pointwise within
    0.1 %. Same panel edges and exact panel fluxes in both, so what is left is the reference's linear
    interpolation in time and its centroid z (y_t at the mid chord, the runner the mean of the four nodes):
    measured ≤ 0.01 %. Catches any error of the runner's panels (area ½ d1 × d2, orientation from the node
    normals, centres), of the thickness source Q = ρ0 v·A or of the blade containers (a wrong turn or rotation
    sign), down to 0.1 %."""
    for k, elevation in enumerate(ELEVATIONS_DEG):
        reference = full_surface_pressure(mach_tip, _observer(elevation), N_CHORD, N_SPAN, 1024)
        errors = compare(surface_runs[mach_tip][k], reference, mach_tip, f"M {mach_tip} el {elevation:+.0f} same panels")
        assert max(abs(e) for e in errors) < 0.001


@pytest.mark.parametrize("mach_tip", MACHS)
def test_surface_patch_vs_full_surface(surface_runs, mach_tip):
    """Against the reference at its own resolution (24 × 60, within 0.3 % of converged): peak and pointwise within
    1 %, width within 0.5 %. Measured (peak, width, pointwise): M 0.88 in plane −0.59 %, +0.15 %, 0.54 %
    (−171.4 Pa, 224 µs), −30° −0.45 %, +0.08 %, 0.39 %; M 0.3 −0.36 %, +0.01 %, 0.24 %. The gap is the runner's
    coarser panelling (module doc). Catches a discretisation that does not converge to the surface integral."""
    for k, elevation in enumerate(ELEVATIONS_DEG):
        reference = full_surface_pressure(mach_tip, _observer(elevation))
        peak, width, pointwise = compare(surface_runs[mach_tip][k], reference, mach_tip,
                                         f"M {mach_tip} el {elevation:+.0f} full surface")
        assert abs(peak) < 0.01 and abs(width) < 0.005 and pointwise < 0.01


@pytest.mark.parametrize("mach_tip", MACHS)
def test_open_blade_ends_matter_little(surface_runs, tmp_path, mach_tip):
    """The tip and root faces (open in the blade patch and in the reference) as their own zones: their noise is
    what closing the blade adds. In hover v_n = −Ω d on an end face (d the chord offset from the pitch axis), so
    each face carries a net flux ∓ρ0 Ω ∫ d dA and the pair forms a small radial dipole. Between 0.2 % and 1.5 %
    of the open blade's peak-to-peak; measured 0.67 % (M 0.88, both observers; negative peak −0.66 % in plane,
    −0.40 % at −30°) and 0.91–0.95 % (M 0.3). Catches end faces that radiate nothing (zones dropped) or that
    matter (then the open patch would not be the blade)."""
    ends = run_hover(tmp_path, mach_tip, [end_face("tip", RADIUS, 1.0, N_CHORD), end_face("root", ROOT, -1.0, N_CHORD)])
    for k, elevation in enumerate(ELEVATIONS_DEG):
        blade = surface_runs[mach_tip][k]
        share = np.abs(ends[k]).max() / np.ptp(blade)
        peak = negative_pulse(blade + ends[k], 1.0)[0] / negative_pulse(blade, 1.0)[0] - 1
        print(f"M {mach_tip} el {elevation:+.0f}: end faces max {share:.3%} of p2p, closed blade's peak {peak:+.3%}")
        assert 0.002 < share < 0.015


@pytest.mark.slow
def test_surface_patch_converges(tmp_path):
    """M 0.88 in plane against the reference at 80 × 80 panels per side, 8192 steps (≈ 30 s): halving the panel
    size (8 × 20 → 16 × 40 per side) cuts every difference at least 3× (measured 4.4–6×, second order) and
    16 × 40 is within 1.2 % (measured −0.90 %, +0.17 %, 0.84 %). Catches a panel scheme that stalls (a first-order
    or biased centre or area)."""
    reference = full_surface_pressure(0.88, _observer(0.0), 80, 80, 8192)
    coarse, fine = (compare(run_hover(tmp_path / f"{n}", 0.88, [blade_surface(n, 5 * n // 2)])[0], reference, 0.88,
                            f"{n} x {5 * n // 2} vs 80 x 80") for n in (8, 16))
    assert all(abs(c) > 3 * abs(f) for c, f in zip(coarse, fine))
    assert max(abs(f) for f in fine) < 0.012
