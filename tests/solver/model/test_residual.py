"""solver.model.residual: the coupled residual r0 + q r1 and its exact Jacobians J0, J1, on the
lattice and on strip theory."""

from __future__ import annotations

import dataclasses
import importlib

import numpy as np
import pytest

import solver
import solver.statics.jig
from solver.model import residual
from solver.statics.system import CoupledSystem, Flow
from tests.study import study_wing, tapered_forward_ea


def _swept_cambered_twisted() -> solver.Wing:
    """Everything at once: N = 9, taper, 25 deg aft sweep, NACA 2412 camber, washout."""
    n = 9
    chord = 1.0 - 0.5 * np.linspace(0, 1, n)
    return solver.Wing.create(
        np.linspace(0, 4, n),
        chord,
        0.35,
        2e4 * chord**2,
        2e3 * chord,
        sweep=25.0,
        jig_twist=np.linspace(0, -3, n),
        airfoil="naca2412",
    )


def _with_surfaces(deflection: float = 4.0, in_plane: float | None = None) -> solver.Wing:
    """N = 9, k = 3 (nodes on 0.25 and 0.75), a flap and an aileron, 10 deg aft sweep; with
    `in_plane` [N m^2] an in-plane (lag) bending stiffness."""
    n = 9
    chord = 1.0 - 0.4 * np.linspace(0, 1, n)
    lag = {} if in_plane is None else {"in_plane_bending_stiffness": in_plane * chord**2}
    return solver.Wing.create(
        np.linspace(0, 4, n),
        chord,
        0.4,
        2e4 * chord**2,
        2e3 * chord,
        sweep=10.0,
        control_surfaces=[
            {"name": "flap", "start": 0.0, "end": 0.45, "hinge": 0.75, "deflection": 6.0},
            {
                "name": "aileron",
                "start": 0.55,
                "end": 0.95,
                "hinge": 0.75,
                "deflection": deflection,
                "kind": "aileron",
            },
        ],
        **lag,
    )


# Soft enough in its plane (4 times its flap stiffness) that lag moves the loads at first order.
IN_PLANE = 8e4


def _massive() -> solver.Wing:
    """N = 7, forward swept and dihedral, bending-torsion coupled, a mass whose centre of
    gravity lies aft of the elastic axis, and a store ahead of it at station 4."""
    n = 7
    store = solver.ConcentratedMass.create(4, 30.0, 2.0, -0.15)
    return solver.Wing.create(
        np.linspace(0, 3, n),
        0.8,
        0.45,
        1e4,
        900.0,
        sweep=-20.0,
        dihedral=6.0,
        bending_torsion_coupling=800.0,
        mass=solver.MassModel.create(n, np.linspace(12.0, 4.0, n), 0.6, 0.1, [store]),
    )


ROTATION = Flow.along(1, 2, image=-1.0, image_jacobian=-1.0, roll_rate=0.05)
EXACT = "geometrically_exact"

SYSTEMS = {
    "tapered_forward_ea": lambda: CoupledSystem(tapered_forward_ea(), 6.0),
    "antisymmetric_rolling_k3": lambda: CoupledSystem(
        _with_surfaces(), 0.0, 3, False, flow=ROTATION
    ),
    "symmetric_flap_k3_deformed_axis": lambda: CoupledSystem(
        _with_surfaces(), 3.0, 3, True, flow=Flow.along(0, 2)
    ),
    "swept_k3_deformed_axis": lambda: CoupledSystem(_swept_cambered_twisted(), 4.0, 3, True),
    "forward_swept_k2": lambda: CoupledSystem(
        solver.Wing.create(np.linspace(0, 3, 7), 0.8, 0.45, 1e4, 900.0, sweep=-20.0), 5.0, 2
    ),
    "strip_tapered_forward_ea": lambda: CoupledSystem(
        tapered_forward_ea(), 6.0, aerodynamics="strip"
    ),
    "strip_swept_k3_deformed_axis": lambda: CoupledSystem(
        _swept_cambered_twisted(), 4.0, 3, True, "strip"
    ),
    # The geometrically exact beam (solver.model.exact_beam), at rotations up to 0.6 rad.
    "exact_swept_k3": lambda: CoupledSystem(
        _swept_cambered_twisted(), 4.0, 3, structure="geometrically_exact"
    ),
    "exact_coupled_dihedral": lambda: CoupledSystem(
        solver.Wing.create(
            np.linspace(0, 3, 7),
            0.8,
            0.45,
            1e4,
            900.0,
            sweep=-20.0,
            dihedral=6.0,
            bending_torsion_coupling=800.0,
        ),
        5.0,
        2,
        structure="geometrically_exact",
    ),
    "exact_antisymmetric_rolling_k3": lambda: CoupledSystem(
        _with_surfaces(), 0.0, 3, False, flow=ROTATION, structure="geometrically_exact"
    ),
    # With lag (solver.model.lag_beam): the flow model's image carries the lag unknowns too.
    "exact_lag_antisymmetric_rolling_k3": lambda: CoupledSystem(
        _with_surfaces(in_plane=IN_PLANE), 0.0, 3, False, flow=ROTATION, structure=EXACT
    ),
    "exact_lag_symmetric_flap_k3_deformed_axis": lambda: CoupledSystem(
        _with_surfaces(in_plane=IN_PLANE), 3.0, 3, True, flow=Flow.along(0, 2), structure=EXACT
    ),
    "exact_strip_tapered_forward_ea": lambda: CoupledSystem(
        tapered_forward_ea(), 6.0, aerodynamics="strip", structure="geometrically_exact"
    ),
    # The wing's weight about the deformed stations (solver.statics.inertia), at 2.5 g.
    "exact_mass_coupled_dihedral_2.5g": lambda: CoupledSystem(
        _massive(), 5.0, 2, structure="geometrically_exact", load_per_q=2.5 / 800.0
    ),
}


def _deformed_state(system: CoupledSystem, seed: int) -> np.ndarray:
    layout, n = system.layout, system.layout.n
    rng = np.random.default_rng(seed)
    x = np.zeros(layout.n_unknowns)
    x[layout.heave] = rng.uniform(-0.2, 0.2, n)  # [m]
    rotation = 0.6 if layout.exact else 0.05  # the exact beam's slope: its rotation [rad]
    x[layout.slope] = rng.uniform(-rotation, rotation, n)  # [-]
    x[layout.twist] = rng.uniform(-5.0, 5.0, n)  # [deg]
    x[layout.circulation] = rng.uniform(0.0, 0.1, layout.n_panels)  # [m]
    if layout.lag:
        x[layout.lag_displacement] = rng.uniform(-0.1, 0.1, n)  # [m]
        x[layout.lag_rotation] = rng.uniform(-0.3, 0.3, n)  # [rad]
    return x


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_the_exact_jacobian_matches_central_finite_differences(name: str):
    """J0 and J1 against central differences at a random, moderately deformed state.

    Step 1e-5: truncation ~h^2 and round-off ~1e-16/h are both ~1e-11 relative (observed
    5e-11 row-wise). 1e-7 leaves a margin of 1000 and still catches any missing chain-rule
    path, whose terms are 1e-3 to 1 of a row's largest entry.
    """
    system = SYSTEMS[name]()
    x = _deformed_state(system, 20240611)
    exact = system.evaluate(x)
    step = 1e-5
    fd0 = np.zeros_like(exact.jacobian0)
    fd1 = np.zeros_like(exact.jacobian1)
    for k in range(x.size):
        dx = np.zeros_like(x)
        dx[k] = step
        plus, minus = system.evaluate(x + dx), system.evaluate(x - dx)
        fd0[:, k] = (plus.r0 - minus.r0) / (2 * step)
        fd1[:, k] = (plus.r1 - minus.r1) / (2 * step)
    for jacobian, finite_difference in ((exact.jacobian0, fd0), (exact.jacobian1, fd1)):
        row_scale = np.max(np.abs(jacobian), axis=1, keepdims=True)
        loaded = row_scale[:, 0] > 0
        error = np.abs(jacobian - finite_difference)
        assert np.max(error[loaded] / row_scale[loaded]) < 1e-7
        assert np.max(np.abs(finite_difference[~loaded]), initial=0.0) < 1e-9


@pytest.mark.parametrize("seed", [1, 2])
def test_the_residual_alone_equals_the_residual_with_jacobians(seed: int):
    system = CoupledSystem(study_wing(), 5.0)
    x = _deformed_state(system, seed)
    r0, r1 = system.residual(x)
    evaluation = system.evaluate(x)
    np.testing.assert_allclose(r0, evaluation.r0, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(r1, evaluation.r1, rtol=1e-13, atol=1e-15)


def test_the_loads_enter_only_the_bending_and_torsion_rows():
    """r1 and J1 vanish outside the load rows: what makes the stability eigenproblem small."""
    system = CoupledSystem(study_wing(), 5.0)
    evaluation = system.evaluate(_deformed_state(system, 3))
    others = np.setdiff1d(np.arange(system.layout.n_unknowns), system.layout.load_rows)
    assert np.all(evaluation.r1[others] == 0)
    assert np.all(evaluation.jacobian1[others] == 0)
    assert np.all(np.any(evaluation.jacobian1[system.layout.load_rows] != 0, axis=1))


@pytest.mark.parametrize("name", list(SYSTEMS))
def test_the_alpha_derivatives_and_the_lift_gradient_match_finite_differences(name: str):
    """What a trimmed solve adds: dr/dalpha, the lift per unit q and its gradients."""
    system = SYSTEMS[name]()
    x = _deformed_state(system, 7)
    _evaluation, terms = system.evaluate_with_alpha(x)
    step = 1e-5  # [deg]
    up, down = (system.at_alpha(system.alpha + s).evaluate_with_alpha(x) for s in (step, -step))
    np.testing.assert_allclose(terms.r0, (up[0].r0 - down[0].r0) / (2 * step), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(terms.r1, (up[0].r1 - down[0].r1) / (2 * step), rtol=1e-6, atol=1e-9)
    # Strip theory's lift at fixed circulation does not depend on alpha at all (the freestream
    # alone turns its forces): the difference quotient is then round-off, eps |lift| / step.
    assert terms.lift_alpha == pytest.approx(
        (up[1].lift - down[1].lift) / (2 * step), rel=1e-6, abs=1e-9 * abs(terms.lift)
    )
    gradient = np.zeros_like(x)
    for k in range(x.size):
        dx = np.zeros_like(x)
        dx[k] = 1e-6
        gradient[k] = (
            system.evaluate_with_alpha(x + dx)[1].lift - system.evaluate_with_alpha(x - dx)[1].lift
        ) / 2e-6
    np.testing.assert_allclose(
        terms.lift_x, gradient, rtol=1e-5, atol=1e-8 * np.abs(gradient).max()
    )


def test_the_model_version_follows_the_code_not_its_documentation(tmp_path, monkeypatch):
    """Compiled libraries are named by it: a change to how the equations are written makes a
    new library, an edit of a docstring does not."""
    monkeypatch.syspath_prepend(str(tmp_path))
    versions = {}
    sources = {
        "plain": 'def f(x):\n    """Doubles."""\n    return 2 * x\n',
        "reworded": 'def f(x):\n    """Twice x, in words."""\n    # a comment\n    return 2 * x\n',
        "changed": 'def f(x):\n    """Doubles."""\n    return x + x\n',
    }
    for name, source in sources.items():
        (tmp_path / f"graph_{name}.py").write_text(source)
        module = importlib.import_module(f"graph_{name}")
        versions[name] = residual._graph_source_digest(module)
    assert versions["plain"] == versions["reworded"] != versions["changed"]
    assert len(residual.MODEL_VERSION) == 12
    # The parameter table too: a new compiled wing field moves the slots after it, with no
    # line of the model changed.
    plain = importlib.import_module("graph_plain")
    table = (("y", "station"), ("sweep", "scalar"), ("camber", "camber"))
    moved = (("y", "station"), ("sweep", "scalar"), ("dihedral", "scalar"), ("camber", "camber"))
    assert residual._graph_source_digest(plain, table=table) != residual._graph_source_digest(
        plain, table=moved
    )


CONTROL_SYSTEMS = {
    "flap": lambda wing: CoupledSystem(wing, 3.0, 3, True, flow=Flow.along(0, 2)),
    "aileron_antisymmetric": lambda wing: CoupledSystem(wing, 0.0, 3, False, flow=ROTATION),
    "exact_lag_flap": lambda wing: CoupledSystem(
        wing, 3.0, 3, True, flow=Flow.along(0, 2), structure=EXACT
    ),
    "exact_lag_aileron_antisymmetric": lambda wing: CoupledSystem(
        wing, 0.0, 3, False, flow=ROTATION, structure=EXACT
    ),
}


@pytest.mark.parametrize("name", list(CONTROL_SYSTEMS))
def test_the_control_derivatives_are_the_derivatives_in_the_deflection(name: str):
    """r0, r1, the lift and the rolling moment along the control direction against central
    differences in the surface's deflection (0.01 deg: truncation ~1e-9, round-off ~1e-12
    relative)."""
    build = CONTROL_SYSTEMS[name]
    in_plane = IN_PLANE if "lag" in name else None
    system = build(_with_surfaces(in_plane=in_plane))
    x = _deformed_state(system, 11)
    _, _, controls = system.evaluate_with_controls(x)
    surface = 0 if name.endswith("flap") else 1
    step = 0.01  # [deg]
    deflection = system.wing.control_surfaces[surface].deflection
    moved = []
    for sign in (1, -1):
        wing = _with_surfaces(deflection + sign * step, in_plane) if surface == 1 else None
        if wing is None:  # the flap: rebuild it deflected
            surfaces = list(system.wing.control_surfaces)
            surfaces[0] = dataclasses.replace(surfaces[0], deflection=6.0 + sign * step)
            wing = dataclasses.replace(system.wing, control_surfaces=tuple(surfaces))
        moved.append(build(wing))
    h = 2 * np.radians(step)
    up, down = (m.evaluate_with_controls(x) for m in moved)
    np.testing.assert_allclose(controls.r0, (up[0].r0 - down[0].r0) / h, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(controls.r1, (up[0].r1 - down[0].r1) / h, rtol=1e-6, atol=1e-9)
    assert controls.lift == pytest.approx((up[1].lift - down[1].lift) / h, rel=1e-6)
    assert controls.roll_control == pytest.approx((up[2].roll - down[2].roll) / h, rel=1e-6)


def test_the_roll_rate_derivatives_and_the_rolling_moments_gradient_are_exact():
    """The antisymmetric flow's rolling moment: its gradient in x and its derivatives in the
    roll rate p / V against central differences (steps 1e-6 in x, 1e-6 rad/m)."""
    system = SYSTEMS["antisymmetric_rolling_k3"]()
    x = _deformed_state(system, 13)
    _, _, controls = system.evaluate_with_controls(x)
    gradient = np.zeros_like(x)
    for k in range(x.size):
        dx = np.zeros_like(x)
        dx[k] = 1e-6
        gradient[k] = (
            system.residual_with_roll(x + dx)[2] - system.residual_with_roll(x - dx)[2]
        ) / 2e-6
    np.testing.assert_allclose(
        controls.roll_x, gradient, rtol=1e-5, atol=1e-8 * np.abs(gradient).max()
    )
    rate = system.flow.roll_rate
    up, down = (
        system.with_flow(
            dataclasses.replace(system.flow, roll_rate=rate + s)
        ).evaluate_with_controls(x)
        for s in (1e-6, -1e-6)
    )
    np.testing.assert_allclose(
        controls.rate_r0, (up[0].r0 - down[0].r0) / 2e-6, rtol=1e-6, atol=1e-9
    )
    np.testing.assert_allclose(
        controls.rate_r1, (up[0].r1 - down[0].r1) / 2e-6, rtol=1e-6, atol=1e-9
    )
    assert controls.roll_rate == pytest.approx((up[2].roll - down[2].roll) / 2e-6, rel=1e-6)
    assert controls.roll == pytest.approx(system.residual_with_roll(x)[2], rel=1e-13)


def test_at_the_flat_unloaded_jig_the_linearised_antisymmetric_flow_is_the_antisymmetric_flow():
    """On a flat wing (no camber, twist or deflection) at rest (x = 0) the mirror and the
    rotation place the image alike and nothing circulates, so the antisymmetric block of the
    full-span Jacobian (image +1, its own derivatives turned) is the rotated model's exact
    Jacobian, control and roll-rate columns included, to round-off."""
    wing = _with_surfaces(0.0)
    flat = dataclasses.replace(
        wing,
        control_surfaces=tuple(
            dataclasses.replace(c, deflection=0.0) for c in wing.control_surfaces
        ),
    )
    rotated = CoupledSystem(
        flat, 0.0, 3, False, flow=Flow.along(1, 2, image=-1.0, image_jacobian=-1.0)
    )
    turned = CoupledSystem(flat, 0.0, 3, False, flow=Flow.along(1, 2, image_jacobian=-1.0))
    x = np.zeros(rotated.layout.n_unknowns)
    (a, _, ca_), (b, _, cb) = rotated.evaluate_with_controls(x), turned.evaluate_with_controls(x)
    for ours, theirs in (
        (a.jacobian0, b.jacobian0),
        (a.jacobian1, b.jacobian1),
        (ca_.r0, cb.r0),
        (ca_.r1, cb.r1),
        (ca_.rate_r0, cb.rate_r0),
        (ca_.roll_x, cb.roll_x),
    ):
        np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-13 * np.max(np.abs(theirs)))
    symmetric = CoupledSystem(flat, 0.0, 3).evaluate(x)
    tangency = rotated.layout.tangency_rows, rotated.layout.circulation
    assert np.max(np.abs(symmetric.jacobian0[tangency] - a.jacobian0[tangency])) > 1e-3


def _camber(system: CoupledSystem) -> np.ndarray:
    return np.asarray(system.layout.unpack(system.parameters).camber)


@pytest.mark.parametrize(
    "name",
    [
        "symmetric_flap_k3_deformed_axis",
        "tapered_forward_ea",
        "exact_lag_symmetric_flap_k3_deformed_axis",
    ],
)
def test_with_its_own_left_half_in_step_the_full_span_model_is_the_symmetric_model(name: str):
    system = SYSTEMS[name]().with_flow(Flow())
    x = _deformed_state(system, 17)
    full_span = system.model.full_span()
    r0, r1, *_ = (
        np.array(v).ravel() for v in full_span(x, x, system.flow_parameters, _camber(system))
    )
    ours0, ours1 = system.residual(x)
    np.testing.assert_allclose(r0, ours0, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(r1, ours1, rtol=1e-12, atol=1e-14)


# The linear beam's, and the exact beam with lag: the left half's lag the right half's mirrored.
BEAMS = {"linear": ("linear", None), "exact_lag": (EXACT, IN_PLANE)}


@pytest.mark.parametrize("beam", list(BEAMS))
def test_the_antisymmetric_linearisation_is_the_full_span_models_antisymmetric_derivative(beam):
    """At a deformed, loaded symmetric state (flap and aileron deflected, alpha 3 deg, swept,
    torque about the heaved axis), the model with the image's own derivatives turned gives
    d/de r(x + e d, x - e d) of the full-span model whose left half moves on its own: J0, J1,
    the aileron's column (its camber +c on the right, -c on the left), the roll rate's column
    and the rolling moment's gradient (2 d/de of the right half's). Central differences, step
    1e-6: truncation and round-off ~1e-10 of each row's scale; 1e-7 leaves a margin of 1000."""
    structure, in_plane = BEAMS[beam]
    wing = _with_surfaces(in_plane=in_plane)
    system = CoupledSystem(
        wing, 3.0, 3, True, flow=Flow.along(1, 2, image_jacobian=-1.0), structure=structure
    )
    x = _deformed_state(system, 19)
    evaluation, _, controls = system.evaluate_with_controls(x)
    p, camber = system.flow_parameters, _camber(system)
    full_span = system.model.full_span()

    def outputs(right, left, p=p, image_camber=camber):
        r0, r1, _, _, roll, *_ = (np.array(v) for v in full_span(right, left, p, image_camber))
        return r0.ravel(), r1.ravel(), 2 * float(roll.sum())

    step, n = 1e-6, x.size
    columns = [np.zeros((n, n)), np.zeros((n, n))]
    roll_x = np.zeros(n)
    for k in range(n):
        dx = np.zeros(n)
        dx[k] = step
        plus, minus = outputs(x + dx, x - dx), outputs(x - dx, x + dx)
        for c in range(2):
            columns[c][:, k] = (plus[c] - minus[c]) / (2 * step)
        roll_x[k] = (plus[2] - minus[2]) / (2 * step)
    direction = np.asarray(system.layout.unpack(p).control)
    camber_slot = system.layout.slot("camber")
    p_plus, p_minus = p.copy(), p.copy()
    p_plus[camber_slot] += step * direction
    p_minus[camber_slot] -= step * direction
    plus = outputs(x, x, p_plus, camber - step * direction)
    minus = outputs(x, x, p_minus, camber + step * direction)
    control = [(plus[c] - minus[c]) / (2 * step) for c in range(2)]
    rate = system.layout.slot("roll_rate")
    p_plus, p_minus = p.copy(), p.copy()
    p_plus[rate] += step
    p_minus[rate] -= step
    plus, minus = outputs(x, x, p_plus), outputs(x, x, p_minus)
    rate_columns = [(plus[c] - minus[c]) / (2 * step) for c in range(2)]

    def close(ours, theirs):
        ours, theirs = np.atleast_2d(ours), np.atleast_2d(theirs)
        scale = np.max(np.abs(ours), axis=-1, keepdims=True)
        scale[scale == 0] = 1.0
        assert np.max(np.abs(ours - theirs) / scale) < 1e-7

    close(evaluation.jacobian0, columns[0])
    close(evaluation.jacobian1, columns[1])
    close(controls.r0, control[0])
    close(controls.r1, control[1])
    close(controls.rate_r0, rate_columns[0])
    close(controls.rate_r1, rate_columns[1])
    close(controls.roll_x, roll_x)


@pytest.mark.parametrize("beam", list(BEAMS))
def test_the_linearised_panel_loads_are_the_full_span_models_antisymmetric_derivative(beam):
    """The panel loads' and force points' derivatives along a direction dx in the unknowns
    (a parameter) plus the aileron's column, with the image's own derivatives turned: d/de of
    the full-span model's right-half loads at (x + e dx, x - e dx), camber +-e c. Central
    differences, step 1e-6: ~1e-10 of each load's scale; 1e-7 leaves a margin of 1000."""
    structure, in_plane = BEAMS[beam]
    wing = _with_surfaces(in_plane=in_plane)
    system = CoupledSystem(
        wing, 3.0, 3, True, flow=Flow.along(1, 2, image_jacobian=-1.0), structure=structure
    )
    x = _deformed_state(system, 23)
    dx = np.random.default_rng(29).normal(size=x.size) * np.abs(x).max() * 0.1
    parameters = system.parameters.copy()
    parameters[system.layout.slot("direction")] = dx
    _, _, terms = system.model.evaluate_with_controls(x, parameters)
    base, camber = system.with_flow(Flow()).flow_parameters, _camber(system)
    direction = np.asarray(system.layout.unpack(system.parameters).control)
    camber_slot, step = system.layout.slot("camber"), 1e-6
    full_span = system.model.full_span()

    def loads(sign: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        p = base.copy()
        p[camber_slot] += sign * step * direction
        _, _, force, torque, _, center, *_ = (
            np.array(v)
            for v in full_span(
                x + sign * step * dx, x - sign * step * dx, p, camber - sign * step * direction
            )
        )
        return force, torque.ravel(), center

    (f1, t1, c1), (f0, t0, c0) = loads(1.0), loads(-1.0)
    along = terms.loads_along + terms.loads_control
    for ours, theirs in (
        (along[:3], (f1 - f0) / (2 * step)),
        (along[4], (t1 - t0) / (2 * step)),
        (terms.center_along + terms.center_control, (c1 - c0) / (2 * step)),
    ):
        assert np.max(np.abs(ours - theirs)) < 1e-7 * np.max(np.abs(ours))
