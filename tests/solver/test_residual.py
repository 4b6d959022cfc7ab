"""solver.residual: the coupled residual r0 + q r1 and its exact Jacobians J0, J1, on the
lattice and on strip theory."""

from __future__ import annotations

import importlib
import math

import numpy as np
import pytest

import solver
import solver.jig
from solver import residual
from solver.system import CoupledSystem
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


SYSTEMS = {
    "tapered_forward_ea": lambda: CoupledSystem(tapered_forward_ea(), 6.0),
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
}


def _deformed_state(system: CoupledSystem, seed: int) -> np.ndarray:
    layout, n = system.layout, system.layout.n
    rng = np.random.default_rng(seed)
    x = np.zeros(layout.n_unknowns)
    x[layout.heave] = rng.uniform(-0.2, 0.2, n)  # [m]
    x[layout.slope] = rng.uniform(-0.05, 0.05, n)  # [-]
    x[layout.twist] = rng.uniform(-5.0, 5.0, n)  # [deg]
    x[layout.circulation] = rng.uniform(0.0, 0.1, layout.n_panels)  # [m]
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


@pytest.mark.parametrize("k", [1, 2, 4])
def test_strip_theory_gives_a_flat_plate_the_thin_airfoils_lift(k: int):
    """Each strip a two-dimensional airfoil normal to its bound vortices: a rigid flat strip of a
    swept wing lifts 2 pi q c dy sin(alpha) cos(sweep), thin-airfoil theory (which the discrete
    vortex airfoil, vortices at the panels' quarter points, reproduces for a flat plate with any
    number of panels) with the independence principle's cos(sweep). The lattice's 3D lift on the
    same wing is 20 % lower. Round-off only: 1e-12. (On a tapered wing the chordwise panels'
    quarter lines are not parallel, and the strip is two-dimensional only to O(taper^2).)"""
    n, sweep = 9, 20.0
    wing = solver.Wing.create(np.linspace(0, 4, n), 0.8, 0.4, 1e4, 1e3, sweep=sweep)
    alpha = 3.0
    angle = math.radians(alpha)
    strip = CoupledSystem(wing, alpha, k, aerodynamics="strip")
    force = strip.panel_loads(solver.jig.at_rest(strip).rigid_state(alpha))[0]  # per unit q
    strip_lift = (force[2] * math.cos(angle) - force[0] * math.sin(angle)).reshape(-1, k).sum(1)
    thin_airfoil = (
        2 * math.pi * 0.8 * np.diff(wing.y) * math.sin(angle) * math.cos(math.radians(sweep))
    )
    np.testing.assert_allclose(strip_lift, thin_airfoil, rtol=1e-12)
    lattice = CoupledSystem(wing, alpha, k)
    lattice_force = lattice.panel_loads(solver.jig.at_rest(lattice).rigid_state(alpha))[0]
    lattice_lift = np.sum(lattice_force[2] * math.cos(angle) - lattice_force[0] * math.sin(angle))
    assert lattice_lift < 0.85 * thin_airfoil.sum()


def test_under_strip_theory_no_strip_sees_another():
    """The tangency rows of a strip involve only its own circulations, and the deformation of its
    own two stations and their neighbours (whose heave tilts the sections' local span axes, as
    AeroSandbox frames them): the influence block is block diagonal (k x k per strip), and
    nothing but the beam couples strips further apart."""
    system = CoupledSystem(_swept_cambered_twisted(), 4.0, 3, aerodynamics="strip")
    layout = system.layout
    jacobian = system.evaluate(_deformed_state(system, 5)).jacobian0
    tangency = jacobian[layout.tangency_rows]
    k = layout.chordwise
    for p in range(layout.n_panels):
        strip = p // k
        others = np.ones(layout.n_panels, dtype=bool)
        others[strip * k : strip * k + k] = False
        assert np.all(tangency[p, layout.circulation][others] == 0)
        assert np.any(tangency[p, layout.circulation][~others] != 0)
        stations = np.ones(layout.n, dtype=bool)
        stations[max(strip - 1, 0) : strip + 3] = False
        for part in (layout.heave, layout.slope, layout.twist):
            assert np.all(tangency[p, part][stations] == 0)
