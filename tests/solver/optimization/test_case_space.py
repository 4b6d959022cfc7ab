"""solver.optimization.case_space: one case of a multipoint design, its alpha a design variable and
the wing's own mass under its load factor.

- Every function's exact gradient, the alpha's and the spar's own mass's explicit terms
  included, agrees with central differences (swept, with dihedral: the mass's weight normal to
  the plane).
- The spar's own mass enters the inertial bending moment linearly, as `solver.statics.inertia`
  lumps it (`spar_bending_per_mass` against two walls' inertial loads).
- A case's equilibrium is the one /solve answers for its flight at that alpha: the same lift,
  tip heave and von Mises stress at every station, inertia relief included.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import solver
from solver.model.layout import Layout
from solver.optimization.case_space import CaseFlight, CaseSpace, spar_bending_per_mass
from solver.statics.inertia import inertial_loads
from tests.study import study_wing

CARBON = solver.Material(
    youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=600e6
)
N = 30


# 1/50 of the carbon's moduli: the exact beam's pull-up bends the wing to 0.45 rad at the tip,
# where the weight's deformed arms and their derivative matter.
SOFT = dataclasses.replace(CARBON, youngs_modulus=1.4e9, shear_modulus=0.54e9)


def _massive_wing(material: solver.Material = CARBON) -> solver.Wing:
    """The study's planform with a tube spar, its own mass (centre of gravity ahead of the
    elastic axis: a torque too), sweep and dihedral."""
    base = study_wing(n=N)
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, material)
    mass = solver.MassModel.create(N, np.linspace(3.0, 0.5, N), 0.35, 0.01)
    return solver.Wing.create(
        base.y, base.chord, 0.4, airfoil="naca0012", spar=spar, mass=mass, sweep=5.0, dihedral=3.0
    )


def _problem() -> solver.DesignProblem:
    return solver.DesignProblem(
        solver.DesignCondition(14.0, lift=600.0),
        design=solver.Design(wall_thickness=solver.WallDesign()),
        smoothness_weight=0.01,
        constraints=solver.DesignConstraints(max_tip_heave=1.0),
    )


# The design flight (alpha fixed) and a 2.5 g load case (its alpha the last variable).
FLIGHTS = [
    CaseFlight("flight", 14.0, 1.225, 600.0, 1.0, 0.0, None),
    CaseFlight("pull-up", 16.0, 1.1, 1500.0, 2.5, 4.0, 6 + N),
]


# The beams: the linear one, and the geometrically exact one, whose weight is taken about the
# deformed stations (rows that depend on the state: `solver.statics.inertia`).
STRUCTURES = ["linear", "geometrically_exact"]


@pytest.mark.parametrize("structure", STRUCTURES)
@pytest.mark.parametrize("flight", FLIGHTS, ids=[f.name for f in FLIGHTS])
def test_a_cases_gradients_are_exact(flight: CaseFlight, structure: str):
    """Central differences, step 1e-6 along a random direction: error ~1e-8 of the gradient,
    1e-5 the bound (as the single-point space's test). The exact beam on the soft spar (tip
    rotation 0.06 and 0.45 rad): 1e-7 at most measured."""
    options = solver.SolverOptions(structure=structure)
    wing = _massive_wing(SOFT if structure == "geometrically_exact" else CARBON)
    space = CaseSpace(wing, _problem(), options, flight, n_alpha=1)
    v = np.concatenate([np.linspace(3.0, 1.0, 6), np.full(N, 0.002), [4.0]])
    direction = np.random.default_rng(7).normal(size=v.size)
    direction[6 : 6 + N] *= 1e-4  # walls in metres
    step = 1e-6
    point = space.at(v)
    plus, minus = space._evaluate(v + step * direction), space._evaluate(v - step * direction)
    assert set(point.gradients) >= {"lift", "von_mises", "tip_heave", "spar_mass"}
    for name, gradient in point.gradients.items():
        finite = (plus.values[name] - minus.values[name]) / (2 * step)
        exact = gradient @ direction
        scale = max(np.max(np.abs(exact)), 1e-9)
        assert np.max(np.abs(finite - exact)) <= 1e-5 * scale, name


def test_the_spar_mass_bends_the_wing_linearly_as_inertia_lumps_it():
    wing = _massive_wing()
    assert wing.spar is not None
    thicker = dataclasses.replace(
        wing, spar=solver.TubeSpar(wing.spar.outer_diameter, np.full(N, 0.003), CARBON)
    )
    layout = Layout(N, 1, "lattice")
    before = inertial_loads(wing, layout)
    after = inertial_loads(thicker, layout)
    assert before is not None and after is not None
    added = CARBON.density * (thicker.spar.area - wing.spar.area)  # type: ignore[union-attr]
    predicted = spar_bending_per_mass(wing) @ added
    change = after.bending_moment - before.bending_moment
    # Two sums of the same terms in another order: round-off of the moment, ~1e-15 of it.
    assert np.max(np.abs(change - predicted)) <= 1e-12 * np.max(np.abs(change))
    np.testing.assert_array_equal(after.torque, before.torque)  # the spar is on the axis


@pytest.mark.parametrize("structure", STRUCTURES)
def test_a_cases_equilibrium_is_what_solve_answers_for_its_flight(structure: str):
    wing = _massive_wing()
    options = solver.SolverOptions(structure=structure)
    space = CaseSpace(wing, _problem(), options, FLIGHTS[1], n_alpha=1)
    v = np.concatenate([np.linspace(3.0, 1.0, 6), np.linspace(0.003, 0.001, N), [4.0]])
    point = space.at(v)
    flight = solver.FlightCondition(16.0, 4.0, 1.1, load_factor=2.5)
    solved = solver.solve(space.design_wing(v), flight, options=options)
    assert solved.totals.wing_mass is not None  # inertia relief in both
    allowable = CARBON.yield_stress  # safety factor 1
    stress = solved.stations.von_mises_stress
    assert stress is not None
    # Both converge Newton to 1e-10 on the same residual from different starts: 1e-9 relative.
    usage = point.values["von_mises"] + 1.0  # (stress / allowable)^2 at stations 0 .. N-2
    np.testing.assert_allclose(np.sqrt(usage), stress[:-1] / allowable, rtol=1e-9)
    assert point.values["lift"][0] == pytest.approx(solved.totals.lift, rel=1e-9)
    assert point.values["tip_heave"][0] == pytest.approx(solved.totals.tip_heave, rel=1e-9)
