"""solver.inputs.design: a design problem, validated where it is built.

- Every part refuses what it cannot mean and names the field (from the part that refuses it;
  "" for the part as a whole, whose rule the reason states), so a request's path is the
  prefix where it is built plus this name.
- The properties the optimiser reads are the problem's own values (the lift to carry, the
  design flight, the twist and wall bounds, the constraints).
- `for_the_rigid_wing` is the same problem with the twist alone and no tip-heave limit."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import pytest

import solver
from solver.inputs.design import DESIGN_FLIGHT_RULE

_LOAD_CASE = solver.DesignLoadCase(
    "pull-up", solver.FlightCondition(12.0, weight=300.0, load_factor=2.5)
)

REFUSED: dict[str, tuple[Callable[[], object], str]] = {
    # the design flight
    "no airspeed": (lambda: solver.DesignCondition(0.0, lift=300.0), "velocity"),
    "mach 3": (lambda: solver.DesignCondition(1001.0, lift=300.0), "velocity"),
    "negative lift": (lambda: solver.DesignCondition(12.0, lift=-1.0), "lift"),
    "a negative weight": (lambda: solver.DesignCondition(12.0, weight=-300.0), "weight"),
    "no load factor": (
        lambda: solver.DesignCondition(12.0, weight=300.0, load_factor=0.0),
        "load_factor",
    ),
    "a stalled alpha": (lambda: solver.DesignCondition(12.0, lift=300.0, alpha=31.0), "alpha"),
    "a vacuum": (lambda: solver.DesignCondition(12.0, lift=300.0, density=0.0), "density"),
    "neither lift nor weight": (lambda: solver.DesignCondition(12.0), ""),
    "lift and weight": (lambda: solver.DesignCondition(12.0, lift=300.0, weight=300.0), ""),
    "a load factor on a lift": (
        lambda: solver.DesignCondition(12.0, lift=300.0, load_factor=2.0),
        "",
    ),
    # the twist
    "one control point": (lambda: solver.TwistDesign(control_points=1), "control_points"),
    "51 control points": (lambda: solver.TwistDesign(control_points=51), "control_points"),
    "a fractional count": (lambda: solver.TwistDesign(control_points=2.5), "control_points"),  # type: ignore[arg-type]
    "a twist below -45": (lambda: solver.TwistDesign(lower=-46.0), "lower"),
    "a twist above 45": (lambda: solver.TwistDesign(upper=46.0), "upper"),
    "inverted twist bounds": (lambda: solver.TwistDesign(lower=5.0, upper=-5.0), ""),
    "equal twist bounds": (lambda: solver.TwistDesign(lower=2.0, upper=2.0), ""),
    # the walls
    "a wall under 10 um": (lambda: solver.WallDesign(lower=1e-6), "lower"),
    "a wall over 5 m": (lambda: solver.WallDesign(upper=6.0), "upper"),
    "inverted wall bounds": (lambda: solver.WallDesign(lower=0.01, upper=0.001), ""),
    # the constraints
    "no tip heave": (lambda: solver.DesignConstraints(max_tip_heave=0.0), "max_tip_heave"),
    "a margin at divergence": (
        lambda: solver.DesignConstraints(max_stability_margin=1.0),
        "max_stability_margin",
    ),
    # the problem
    "a negative smoothness weight": (
        lambda: solver.DesignProblem(
            solver.DesignCondition(12.0, lift=300.0), smoothness_weight=-0.1
        ),
        "smoothness_weight",
    ),
    "another objective": (
        lambda: solver.DesignProblem(solver.DesignCondition(12.0, lift=300.0), objective="lift"),  # type: ignore[arg-type]
        "objective",
    ),
    "spar mass without sizing": (
        lambda: solver.DesignProblem(
            solver.DesignCondition(12.0, lift=300.0), objective="spar_mass"
        ),
        "objective",
    ),
    # the load cases
    "a load case at a given alpha": (
        lambda: solver.DesignLoadCase("pull-up", solver.FlightCondition(12.0, 5.0)),
        "flight",
    ),
    "a load case without an airspeed": (
        lambda: solver.DesignLoadCase("pull-up", solver.FlightCondition(weight=300.0)),
        "flight",
    ),
    "a load case named as the design flight": (
        lambda: solver.DesignLoadCase("flight", solver.FlightCondition(12.0, weight=300.0)),
        "name",
    ),
    "two load cases of one name": (
        lambda: solver.DesignProblem(
            solver.DesignCondition(12.0, lift=300.0),
            load_cases=(_LOAD_CASE, _LOAD_CASE),
        ),
        "load_cases[1].name",
    ),
    "a load case that is not one": (
        lambda: solver.DesignProblem(
            solver.DesignCondition(12.0, lift=300.0),
            load_cases=(solver.FlightCondition(12.0, weight=300.0),),  # type: ignore[arg-type]
        ),
        "load_cases[0]",
    ),
}


@pytest.mark.parametrize(("pose", "field"), list(REFUSED.values()), ids=list(REFUSED))
def test_every_part_refuses_what_it_cannot_mean_naming_the_field(
    pose: Callable[[], object], field: str
) -> None:
    with pytest.raises(solver.InvalidInput) as raised:
        pose()
    assert raised.value.field == field
    assert raised.value.reason


def test_a_design_flight_given_neither_way_states_the_rule() -> None:
    with pytest.raises(solver.InvalidInput) as raised:
        solver.DesignCondition(12.0)
    assert raised.value.reason == DESIGN_FLIGHT_RULE


def test_the_limits_themselves_are_accepted() -> None:
    """The declared limits are inclusive: each extreme is a problem that can be posed."""
    flight = solver.DesignCondition(1000.0, lift=1e9, alpha=30.0, density=2000.0)
    twist = solver.TwistDesign(control_points=50, lower=-45.0, upper=45.0)
    walls = solver.WallDesign(lower=1e-5, upper=5.0)
    constraints = solver.DesignConstraints(max_tip_heave=1e-6, max_stability_margin=0.999)
    problem = solver.DesignProblem(
        flight,
        solver.Design(twist, walls),
        objective="spar_mass",
        smoothness_weight=1e3,
        constraints=constraints,
    )
    assert problem.size_spar and problem.control_points == 50


# ------------------------------------------------------------- what the optimiser reads


def _problem(**changes: object) -> solver.DesignProblem:
    base = solver.DesignProblem(
        solver.DesignCondition(12.0, weight=200.0, load_factor=2.5, alpha=1.5, density=1.0),
        solver.Design(
            solver.TwistDesign(control_points=8, lower=-4.0, upper=6.0),
            solver.WallDesign(lower=1e-3, upper=0.02),
        ),
        objective="spar_mass",
        smoothness_weight=0.02,
        constraints=solver.DesignConstraints(max_tip_heave=0.4, max_stability_margin=0.8),
    )
    return dataclasses.replace(base, **changes)  # type: ignore[arg-type]


def test_the_optimiser_reads_the_problems_own_values() -> None:
    problem = _problem()
    assert problem.lift == pytest.approx(500.0, rel=1e-15)  # load_factor * weight
    assert (problem.velocity, problem.alpha, problem.density) == (12.0, 1.5, 1.0)
    assert problem.dynamic_pressure == pytest.approx(0.5 * 1.0 * 12.0**2, rel=1e-15)
    assert problem.control_points == 8
    assert problem.twist_bounds == (-4.0, 6.0)
    assert problem.size_spar is True
    assert problem.wall_thickness_bounds == (1e-3, 0.02)
    assert problem.max_tip_heave == 0.4
    assert problem.max_stability_margin == 0.8


@pytest.mark.parametrize(
    ("flight", "lift"),
    [
        (solver.DesignCondition(12.0, lift=300.0), 300.0),
        (solver.DesignCondition(12.0, weight=300.0), 300.0),
        (solver.DesignCondition(12.0, weight=300.0, load_factor=3.0), 900.0),
    ],
    ids=["lift", "weight", "weight-at-3g"],
)
def test_the_lift_to_carry_is_the_lift_or_the_load_factor_times_the_weight(
    flight: solver.DesignCondition, lift: float
) -> None:
    assert solver.DesignProblem(flight).lift == pytest.approx(lift, rel=1e-15)
    assert flight.required_lift == pytest.approx(lift, rel=1e-15)


def test_the_defaults_are_the_studys_sketch() -> None:
    """Six control points within +-15 deg, the near-field drag, no penalty, no sizing, no
    tip-heave limit, a 0.95 stability margin, the jig at 0 deg, sea-level air."""
    problem = solver.DesignProblem(solver.DesignCondition(12.0, lift=300.0))
    assert problem.control_points == 6 and problem.twist_bounds == (-15.0, 15.0)
    assert problem.objective == "induced_drag" and problem.smoothness_weight == 0.0
    assert problem.size_spar is False and problem.max_tip_heave is None
    assert problem.max_stability_margin == 0.95
    assert problem.alpha == 0.0 and problem.density == solver.ISA_SEA_LEVEL_DENSITY
    # Unsized, the wall bounds read are WallDesign's defaults (the optimiser never uses them).
    assert problem.wall_thickness_bounds == (
        solver.WallDesign().lower,
        solver.WallDesign().upper,
    )


# ---------------------------------------------------------------------- the rigid wing


@pytest.mark.parametrize(
    ("objective", "rigid_objective"),
    [("spar_mass", "induced_drag"), ("trefftz_drag", "trefftz_drag")],
    ids=["spar-mass", "trefftz-drag"],
)
def test_the_rigid_wings_problem_is_the_twist_alone_without_a_tip_heave_limit(
    objective: str, rigid_objective: str
) -> None:
    problem = _problem(objective=objective)
    rigid = problem.for_the_rigid_wing()
    assert rigid.size_spar is False and rigid.design.wall_thickness is None
    assert rigid.max_tip_heave is None
    assert rigid.objective == rigid_objective  # a rigid wing has no spar to lighten
    # Everything else as it was.
    assert rigid.flight == problem.flight
    assert rigid.design.jig_twist == problem.design.jig_twist
    assert rigid.smoothness_weight == problem.smoothness_weight
    assert rigid.max_stability_margin == problem.max_stability_margin
    # And the problem itself is unchanged (frozen: a new problem is made).
    assert problem.size_spar and problem.max_tip_heave == 0.4 and problem.objective == objective


def test_the_rigid_wings_problem_of_a_twist_problem_is_the_same_problem() -> None:
    problem = solver.DesignProblem(solver.DesignCondition(12.0, lift=300.0))
    assert problem.for_the_rigid_wing() == problem


def test_load_cases_make_the_problem_multipoint_and_the_rigid_wing_flies_the_design_flight():
    problem = _problem(load_cases=[_LOAD_CASE])
    assert problem.load_cases == (_LOAD_CASE,)  # a list is taken as the tuple it means
    assert problem.multipoint and not _problem().multipoint
    assert _LOAD_CASE.inertial_load_factor == 2.5
    assert problem.for_the_rigid_wing().load_cases == ()
