"""Free-vortex wake (nps.wake.free): initial guess, guards, errors, frames."""

from dataclasses import replace

import numpy as np
import pytest

from nps.rotor import bet

from nps.wake import bvi

from nps.wake import free as freewake

from nps.wake import prescribed as wake
from nps.wake import vortex
from nps.rotor.geometry import OperatingPoint, RotorGeometry

R, OMEGA = 2.0, 109.12
GEOMETRY = RotorGeometry(name="demo", n_blades=4, radius_m=R, chord_m=0.121, root_cutout_m=0.44,
                         twist_rad=np.radians(-8.0), thickness_ratio=0.12, lock_number=8.0, hinge_offset_m=0.29)
ROW = dict(n_blades=4, radius_m=R, omega_rad_s=OMEGA, rotation_sign=1, mu_x=0.15, mu_y=0.0, mu_z=-0.0113)
BEDDOES = wake.WakeModel(steps_per_rev=72, revolutions=2.0)


@pytest.fixture(scope="module")
def rotor():
    op = OperatingPoint(OMEGA, ROW["mu_x"], 0.0, ROW["mu_z"], 1.2055, 341.7, 3300.0)
    trim = bet.trim_rotor(GEOMETRY, op, bet.DiskGrid(72, 12))
    state = bvi.wake_state(trim.disk, ROW, trim.totals.ct)
    return trim.disk, freewake.RotorPlacement("demo", state, np.zeros(3), np.eye(3))


def test_zero_distortion_is_the_beddoes_wake(rotor):
    """The initial guess (distortion 0) gives bit for bit the prescribed wake's disk velocity."""
    disk, placement = rotor
    grid = bvi.disk_grid(disk)
    beta = disk["beta_rad"].to_numpy().reshape(grid.shape)
    model = freewake.FreeWakeModel()
    table = freewake._node_table(placement, BEDDOES, model)
    zero = freewake.FreeWakeSolution((placement,), BEDDOES, model, np.zeros_like(table)[None], 0, np.array([]))
    v_free = freewake.disk_induced_velocity(zero, "demo", grid.psi_rad, grid.r_m, beta)
    v_beddoes = wake.disk_induced_velocity(placement.state, BEDDOES, grid.psi_rad, grid.r_m, beta)
    assert v_free.shape == (1,) + v_beddoes.shape
    assert np.array_equal(v_free[0], v_beddoes)


def test_relaxation_converges_and_moves_the_wake(rotor):
    """Converged: the last node change is below 1 % R, all nodes finite, the wake moved from
    the Beddoes guess (by more than the tolerance), the release node stays at the blade tip."""
    _, placement = rotor
    solution = freewake.relax([placement], BEDDOES)
    assert solution.residual_history[-1] < 0.01
    assert np.isfinite(solution.distortion_m).all()
    assert np.abs(solution.distortion_m).max() > 0.01 * R
    assert np.array_equal(solution.distortion_m[0, :, 0], np.zeros((36, 3)))


def test_non_convergence_is_a_clear_error(rotor):
    """Too few iterations: FreeWakeError naming the rotor, the iteration count and the residual."""
    _, placement = rotor
    with pytest.raises(freewake.FreeWakeError, match=r"rotor 'demo', 2 iterations, node change [0-9.]+ R"):
        freewake.relax([placement], BEDDOES, freewake.FreeWakeModel(max_iterations=2))


def test_marginal_case_stops_with_an_error(rotor):
    """A forced marginal case — the measured thin core (0.14 c) with the discretisation floor at
    that core, no core growth, no under-relaxation — does not settle on the 10° grid: the solver
    raises FreeWakeError instead of returning a wandering wake."""
    _, placement = rotor
    thin = replace(freewake.FREE_WAKE_VORTEX, core_growth=False)
    marginal = freewake.FreeWakeModel(vortex=thin, core_floor_chords=thin.core_radius_chords, relaxation=1.0,
                                      max_iterations=40)
    with pytest.raises(freewake.FreeWakeError, match="rotor 'demo'"):
        freewake.relax([placement], BEDDOES, marginal)


def test_non_finite_nodes_are_caught(rotor, monkeypatch):
    """A non-finite velocity anywhere stops the relaxation with the rotor named."""
    _, placement = rotor

    def broken(rotors, beddoes, model, base, distortion, timing):
        v = np.zeros((base[0].shape[0], model.n_age + 1, 3))
        v[3, 5, 2] = np.nan
        return [v for _ in rotors]

    monkeypatch.setattr(freewake, "_node_velocities", broken)
    with pytest.raises(freewake.FreeWakeError, match="non-finite node positions of rotor 'demo'"):
        freewake.relax([placement], BEDDOES)


def test_invalid_model_and_inputs_are_named():
    with pytest.raises(ValueError, match="relaxation"):
        freewake.FreeWakeModel(relaxation=0.0)
    with pytest.raises(ValueError, match="steps_per_rev"):
        freewake.FreeWakeModel(steps_per_rev=4)
    with pytest.raises(ValueError, match="at least one rotor"):
        freewake.relax([], BEDDOES)


def test_bad_placement_is_named(rotor):
    _, placement = rotor
    with pytest.raises(ValueError, match="rotor 'x': hub_position_m"):
        freewake.RotorPlacement("x", placement.state, np.array([0.0, np.nan, 0.0]), np.eye(3))
    with pytest.raises(ValueError, match="rotor 'x': r_gh"):
        freewake.RotorPlacement("x", placement.state, np.zeros(3), 2.0 * np.eye(3))


def test_wake_table_of_the_free_wake(rotor):
    """The free wake writes the wake artifact with the Beddoes table's columns and node count;
    with a zero distortion the positions equal the Beddoes table's."""
    from nps.rotor.geometry import RotorMotion

    _, placement = rotor
    motion = RotorMotion(np.zeros(3), np.array([-32.9, 0.0, 0.0]), np.eye(3), OMEGA, 1, 4)
    psi = np.radians([0.0, 5.0])
    model = freewake.FreeWakeModel()
    zero = freewake.FreeWakeSolution((placement,), BEDDOES, model,
                                     np.zeros_like(freewake._node_table(placement, BEDDOES, model))[None], 0, np.array([]))
    beddoes = wake.wake_table(placement.state, BEDDOES, psi, motion)
    free = wake.wake_table(placement.state, BEDDOES, psi, motion, snapshot=lambda p: freewake.wake_snapshot(zero, "demo", p))
    assert list(free.columns) == list(wake.WAKE_COLUMNS) and len(free) == len(beddoes)
    assert np.array_equal(free[["x_h_m", "y_h_m", "z_h_m"]].to_numpy(), beddoes[["x_h_m", "y_h_m", "z_h_m"]].to_numpy())


def test_model_from_config():
    assert freewake.FreeWakeModel.from_config(None) == freewake.FreeWakeModel()
    assert freewake.FreeWakeModel.from_config({"steps_per_rev": 72}).steps_per_rev == 72
    with pytest.raises(ValueError, match="unknown field"):
        freewake.FreeWakeModel.from_config({"steps": 72})
    model = freewake.FreeWakeModel.from_config({"core_radius_chords": 0.2, "core_growth": False, "vatistas_n": 1.5,
                                                "core_floor_chords": 0.5})
    assert model.vortex == replace(freewake.FREE_WAKE_VORTEX, core_radius_chords=0.2, core_growth=False, vatistas_n=1.5)
    assert model.kinematics_vortex.core_radius_chords == 0.5
    with pytest.raises(ValueError, match="vortex"):
        freewake.FreeWakeModel(vortex=replace(freewake.FREE_WAKE_VORTEX, vortex_structure="betz"))


def _bounds(prop: dict) -> list[tuple[float, bool]]:
    """(value, valid) on and just beside each bound of one numeric schema property."""
    step = 1 if prop["type"] == "integer" else 1e-3
    pairs = []
    for key, sense, on_is_valid in (("minimum", -1, True), ("exclusiveMinimum", 1, False), ("maximum", 1, True),
                                    ("exclusiveMaximum", -1, False)):
        if key in prop:
            beside = prop[key] + sense * step  # outside an inclusive bound, inside an exclusive one
            pairs += [(prop[key], on_is_valid), (beside, not on_is_valid)]
    return pairs


def test_model_checks_the_schema_bounds():
    """FreeWakeModel refuses exactly what the config schema (``wake.free``, the one source of
    the bounds) refuses: every numeric bound, on and just beside it."""
    from nps.app.config import load_schema

    free = load_schema("config")["properties"]["wake"]["properties"]["free"]["properties"]
    checked = 0
    for key, prop in free.items():
        for value, valid in _bounds(prop) if prop["type"] in ("number", "integer") else ():
            checked += 1
            if valid:
                freewake.FreeWakeModel.from_config({key: value})
            else:
                with pytest.raises(ValueError, match=key):
                    freewake.FreeWakeModel.from_config({key: value})
    assert checked >= 20


def test_ring_velocity_is_the_exact_ring_field():
    """One ring: Γ/(2a) at its centre along the axis (right-handed), and at an off-axis point
    the same velocity as a 2000-segment polygon of the ring (Biot–Savart, no core)."""
    axis = np.array([0.0, 0.0, 1.0])
    centre = freewake._ring_velocity(np.zeros((1, 3)), np.zeros((1, 3)), axis, 2.0, np.array([1.0]), 0.0)[0]
    assert centre == pytest.approx([0.0, 0.0, 0.25], abs=1e-12)
    theta = np.linspace(0.0, 2.0 * np.pi, 2001)
    polygon = np.stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)], axis=1)
    point = np.array([[0.3, 0.2, 0.5]])
    exact = vortex.segment_induced_velocity(point, polygon[:-1], polygon[1:], np.ones(2000), 0.0)[0]
    ring = freewake._ring_velocity(point, np.zeros((1, 3)), axis, 1.0, np.array([1.0]), 0.0)[0]
    assert ring == pytest.approx(exact, rel=1e-5)


def test_continuation_is_a_semi_infinite_cylinder():
    """Hover continuation rings of a 4-bladed rotor against the exact on-axis velocity of a
    semi-infinite vortex cylinder, w = (γ/2)(1 − h/√(h² + a²)) at height h above its start
    (γ = B Γ̄/L): within 1.5 %; the advance per revolution L satisfies Glauert's momentum
    relation at C_T,Γ = B Γ̄/(2π Ω R²) (hover: L = 2π R √(C_T,Γ/2))."""
    gamma_v, radius, omega = 1.0, 1.0, 100.0
    state = wake.WakeState(radius_m=radius, n_blades=4, chord_m=0.07, omega_rad_s=omega, rotation_sign=1, mu_x=0.0,
                           mu_y=0.0, mu_z=0.0, ct=0.005, gamma_table_m2_s=np.full(8, gamma_v),
                           beta_table_rad=np.zeros(8))
    placement = freewake.RotorPlacement("r", state, np.zeros(3), np.eye(3))
    a = 0.8
    last_turn = np.stack([a * np.cos(np.linspace(0, 2 * np.pi, 36, endpoint=False)),
                          a * np.sin(np.linspace(0, 2 * np.pi, 36, endpoint=False)), np.full(36, -2.0)], axis=1)
    x = np.stack([last_turn, last_turn], axis=1)
    centres, ring_radius, circulation, _ = freewake._continuation_rings(placement, x, state.gamma_table_m2_s, 0.0,
                                                                       freewake.FreeWakeModel(continuation_radii=50.0))
    ct_gamma = 4 * gamma_v / (2.0 * np.pi * omega * radius**2)
    per_rev = 2.0 * np.pi * radius * np.sqrt(ct_gamma / 2.0)
    assert ring_radius == pytest.approx(a)
    assert np.diff(centres[:, 2])[0] == pytest.approx(-per_rev * (1 + 1.25) / 8)
    gamma_sheet = 4 * gamma_v / per_rev
    for h in (0.0, 0.3, 1.0):
        w = freewake._ring_velocity(np.array([[0.0, 0.0, -2.0 + h]]), centres, np.array([0.0, 0.0, 1.0]), ring_radius,
                                    circulation, 0.0)[0]
        exact = -0.5 * gamma_sheet * (1.0 - h / np.hypot(h, a))
        assert w[2] == pytest.approx(exact, rel=0.015)
        assert np.abs(w[:2]).max() < 1e-9
