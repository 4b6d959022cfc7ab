"""solver.optimization.multipoint: one jig twist and spar for the design flight and every load
case, in one IPOPT problem.

- The optimum is feasible in every case: each case's equilibrium, as /solve answers its flight,
  carries its lift and keeps the spar's von Mises stress within the allowable (to what IPOPT's
  tolerance leaves, below).
- More cases can only cost mass: the spar sized for a set of cases is at least as heavy as the
  one sized for any of its subsets (the design flight alone, or with one case).
- A load case the design flight already is (the same flight) leaves the optimum as the
  single-point problem's.
- The wing's own mass relieves the pull-up: with it, the sized spar is lighter.
- Failures are typed and say where: a case the wing cannot fly names the case; IPOPT's
  iteration limit is not-converged (`OptimizerNotConverged`), never infeasible.

Tolerances: IPOPT stops at 1e-10 (or three iterations below 1e-8, its acceptable level) on its
scaled problem, in which the stress constraint is (sigma / allowable)^2 - 1 <= 0 at each
station: sigma exceeds the allowable by at most half that, ~5e-9 of it. 1e-8 is the bound (IPOPT
may scale a constraint down by its gradient, measured: nothing beyond 2e-11 here). The masses of
optima compared to one another hold to the same level: 1e-8 relative.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
import pytest

import solver
import solver.optimization.nlp as nlp
from tests.study import study_wing

CARBON = solver.Material(youngs_modulus=70e9, shear_modulus=27e9, density=1600.0, yield_stress=30e6)
STRESS = 1e-8  # relative excess of the allowable IPOPT's stop leaves (module docstring)
MASS = 1e-8  # relative, between optima


def _spar_wing(massive: bool = False) -> solver.Wing:
    base = study_wing()
    spar = solver.SparDesign(solver.ThicknessFraction(0.8), 0.002, CARBON)
    mass = (
        # on the elastic axis: it relieves the bending and adds no torque
        solver.MassModel.create(30, np.linspace(3.0, 0.5, 30), 0.4, 0.01) if massive else None
    )
    return solver.Wing.create(base.y, base.chord, 0.4, airfoil="naca0012", spar=spar, mass=mass)


def _case(name: str, load_factor: float, velocity: float = 14.0) -> solver.DesignLoadCase:
    flight = solver.FlightCondition(velocity, weight=300.0, load_factor=load_factor)
    return solver.DesignLoadCase(name, flight)


PULL_UP, PUSH_OVER = _case("pull-up", 2.5), _case("push-over", -1.0)
SIZING = solver.DesignProblem(
    solver.DesignCondition(14.0, weight=300.0),
    design=solver.Design(wall_thickness=solver.WallDesign(5e-4, 0.01)),
    objective="spar_mass",
)


@functools.cache
def _sized(cases: tuple[str, ...], massive: bool = False) -> solver.OptimalDesign:
    chosen = {"pull-up": PULL_UP, "push-over": PUSH_OVER}
    problem = dataclasses.replace(SIZING, load_cases=tuple(chosen[name] for name in cases))
    return solver.optimize(_spar_wing(massive), problem)


def test_the_optimum_carries_every_case_within_the_allowable_stress():
    design = _sized(("pull-up", "push-over"))
    assert design.cases is not None
    assert [case.name for case in design.cases] == ["flight", "pull-up", "push-over"]
    required = {"flight": 300.0, "pull-up": 750.0, "push-over": -300.0}
    for case in design.cases:
        totals = case.equilibrium.totals
        assert case.lift == required[case.name]
        assert totals.lift == pytest.approx(case.lift, rel=1e-8), case.name
        assert totals.max_von_mises_stress is not None
        assert totals.max_von_mises_stress <= CARBON.yield_stress * (1 + STRESS), case.name
        assert case.equilibrium.stability.stable
    # The design flight flies at its jig alpha; the cases at their own, of the lift's sign.
    alphas = {case.name: case.alpha for case in design.cases}
    assert alphas["flight"] == 0.0 and alphas["pull-up"] > 0 > alphas["push-over"]
    # Both manoeuvres size the spar: each has a station at the allowable.
    active = {(c.name, c.case) for c in design.constraints if c.active}
    assert {("von_mises", "pull-up"), ("von_mises", "push-over")} <= active


def test_every_constraint_names_its_case():
    design = _sized(("pull-up",))
    named = {(c.name, c.case) for c in design.constraints}
    assert named == {
        ("lift", "flight"),
        ("jig_twist", None),  # the bounds hold for every case
        ("von_mises", "flight"),
        ("stability_margin", "flight"),
        ("lift", "pull-up"),
        ("von_mises", "pull-up"),
        ("stability_margin", "pull-up"),
    }


@pytest.mark.parametrize(
    ("cases", "subsets"),
    [
        (("pull-up",), [()]),
        (("push-over",), [()]),
        (("pull-up", "push-over"), [(), ("pull-up",), ("push-over",)]),
    ],
    ids=["pull-up", "push-over", "both"],
)
def test_more_cases_never_make_a_lighter_spar(cases, subsets):
    """Each case adds constraints on the same variables: the feasible designs of a set of cases
    are among those of each subset, so its lightest spar is no lighter."""
    heavier = _sized(cases).spar_mass
    for subset in subsets:
        assert heavier >= _sized(subset).spar_mass * (1 - MASS), subset


def test_the_pull_up_costs_spar_mass():
    """Measured: 2.281 kg for the design flight alone, 2.448 kg with the pull-up, 3.490 kg with
    the push-over too (benchmarks/RESULTS.md): the design flight's stress is not active alone."""
    alone, pulled = _sized(()).spar_mass, _sized(("pull-up",)).spar_mass
    assert alone is not None and pulled is not None
    assert pulled > alone * 1.01


def test_a_case_the_design_flight_already_is_leaves_the_single_point_optimum():
    """The study's design (twist alone, induced drag) with the same flight once more as a load
    case: the case's alpha is the design flight's, its constraints are the design flight's, and
    IPOPT stops at the same optimum within what its tolerance holds (the drag to ~1e-9, the twist
    to ~1e-7 deg, `solver.optimization.nlp`; measured 1e-14 and 3e-7 deg)."""
    plain = solver.DesignProblem(solver.DesignCondition(12.0, lift=300.0))
    same = solver.DesignLoadCase("same", solver.FlightCondition(12.0, lift=300.0))
    single = solver.optimize(study_wing(), plain)
    multi = solver.optimize(study_wing(), dataclasses.replace(plain, load_cases=(same,)))
    assert multi.induced_drag == pytest.approx(single.induced_drag, rel=1e-9)
    assert np.max(np.abs(multi.jig_twist - single.jig_twist)) <= 1e-5
    assert multi.cases is not None and abs(multi.cases[1].alpha) <= 1e-6
    assert single.cases is None and all(c.case is None for c in single.constraints)


def test_a_sizing_with_a_case_it_already_is_sizes_the_single_points_spar():
    """The design flight a 2.5 g pull-up (its stress active at the root), and that flight once
    more as a load case: its constraints repeat the design flight's, the spar is the same."""
    pulling = solver.DesignCondition(14.0, weight=300.0, load_factor=2.5)
    plain = dataclasses.replace(SIZING, flight=pulling)
    same = solver.DesignLoadCase("same", PULL_UP.flight)
    single = solver.optimize(_spar_wing(), plain)
    multi = solver.optimize(_spar_wing(), dataclasses.replace(plain, load_cases=(same,)))
    assert any(c.name == "von_mises" and c.active for c in single.constraints)
    assert multi.spar_mass == pytest.approx(single.spar_mass, rel=MASS)
    assert multi.wall_thickness is not None and single.wall_thickness is not None
    # The walls hold to what the mass does over the walls' share of it: 1e-8 of the thickest.
    np.testing.assert_allclose(multi.wall_thickness, single.wall_thickness, atol=1e-8 * 0.01)


def test_the_wings_own_mass_relieves_the_pull_up():
    """Mass on the elastic axis, distributed like the chord, weighs n g against the lift in
    every case: the spar carries less bending, and is sized lighter."""
    bare, relieved = _sized(("pull-up",)), _sized(("pull-up",), massive=True)
    assert relieved.cases is not None
    for case in relieved.cases:
        assert case.equilibrium.totals.wing_mass is not None  # inertia relief in each case
        # q (n / q): the load factor the solve carries, to round-off
        assert case.equilibrium.totals.load_factor == pytest.approx(case.load_factor, rel=1e-12)
    assert relieved.spar_mass < bare.spar_mass


def test_a_case_the_wing_cannot_fly_is_an_infeasible_design_naming_it():
    """10 g at 6 m/s is past what the rigid wing carries at any alpha within 30 deg."""
    problem = dataclasses.replace(SIZING, load_cases=(_case("too-much", 10.0, velocity=6.0),))
    with pytest.raises(solver.InfeasibleDesign) as raised:
        solver.optimize(_spar_wing(), problem)
    assert raised.value.case == "too-much"
    assert "too-much" in str(raised.value)


def test_the_iteration_limit_is_not_converged_never_infeasible(monkeypatch):
    """A feasible problem stopped after two iterations: IPOPT could not judge it."""
    monkeypatch.setattr(nlp, "MAX_ITERATIONS", 2)
    problem = dataclasses.replace(SIZING, load_cases=(PULL_UP,))
    with pytest.raises(solver.ConvergenceError) as raised:
        solver.optimize(_spar_wing(), problem)
    assert isinstance(raised.value, solver.OptimizerNotConverged)
    assert not isinstance(raised.value, solver.InfeasibleDesign)
