"""solver.unsteady_lattice.vortices: the horseshoe in numbers is the static model's kernel."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.vortices import horseshoe_velocity, symmetric_horseshoe_velocity


@pytest.mark.parametrize(
    ("sweep", "twist", "airfoil", "chordwise"),
    [(0.0, 0.0, None, 1), (25.0, 3.0, "naca4412", 3)],
    ids=["flat-unswept", "swept-twisted-cambered"],
)
def test_the_panels_influence_matrix_is_the_static_models(sweep, twist, airfoil, chordwise):
    """n_i . v_ij of every horseshoe and its mirror image at every collocation point is the
    static model's tangency-row derivative in the circulation (its exact Jacobian J0): the
    same kernel, evaluated in float64 both ways (round-off, 1e-13 of the largest)."""
    wing = solver.Wing.create(
        np.linspace(0, 4, 9), np.linspace(1.2, 0.6, 9), 0.35, 1e5, 1e4,
        sweep=sweep, jig_twist=twist, airfoil=airfoil,
    )  # fmt: skip
    options = solver.SolverOptions(chordwise_panels=chordwise)
    system = CoupledSystem.of(wing, 0.0, options)
    layout = system.layout
    influence = at_rest(system).evaluation.jacobian0[layout.tangency_rows, layout.circulation]
    grid = panels(wing, chordwise)
    velocity = symmetric_horseshoe_velocity(
        grid.collocation[:, None, :], grid.left[None], grid.right[None]
    )
    ours = np.einsum("ic,ijc->ij", grid.normal, velocity)
    np.testing.assert_allclose(ours, influence, rtol=0, atol=1e-13 * np.abs(influence).max())


def test_a_horseshoe_induces_what_biot_savart_gives_its_three_straight_legs():
    """Behind the middle of a bound leg of length 2 h, at distance d, unit circulation (x aft,
    circulating so as to lift): the bound leg's (1 / 4 pi d) 2 h / sqrt(h^2 + d^2) and each
    trailing leg's (1 / 4 pi h)(1 + d / sqrt(h^2 + d^2)), all downward (to 1e-9: behind a long
    bound leg the kernel's |a||b| + a.b sums nearly opposite terms)."""
    d, h = 0.1, 50.0
    velocity = horseshoe_velocity(
        np.array([d, 0.0, 0.0]), np.array([0.0, -h, 0.0]), np.array([0.0, h, 0.0])
    )
    root = np.hypot(h, d)
    bound = 2 * h / root / (4 * np.pi * d)
    trailing = 2 * (1 + d / root) / (4 * np.pi * h)
    assert velocity[2] == pytest.approx(-(bound + trailing), rel=1e-9)
    assert velocity[0] == 0 and velocity[1] == 0


def test_a_point_on_the_bound_leg_sees_only_the_trailing_legs():
    """The static model masks the bound leg's 0/0 at its own midpoint (`bound_weight`): the
    trailing legs' 2 / (4 pi h) remains, h the half-length."""
    velocity = horseshoe_velocity(
        np.zeros(3), np.array([0.0, -1.0, 0.0]), np.array([0.0, 1.0, 0.0])
    )
    assert velocity[2] == pytest.approx(-2 / (4 * np.pi), rel=1e-12)
