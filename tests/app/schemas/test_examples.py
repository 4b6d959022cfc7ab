"""app.schemas.examples: what /docs pre-fills. Every example is a valid body of its endpoint
(its request model, then the service's own limits) and becomes the solver input it describes;
the study's wing is the design study's to the 10 significant digits it is printed with, and
each example is what its summary says."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import solver
from app.schemas import OptimizeRequest, SolveRequest, SweepRequest
from app.schemas.examples import (
    OPTIMIZE_EXAMPLES,
    SOLVE_EXAMPLES,
    STUDY_SOLVE,
    STUDY_WING,
    SWEEP_EXAMPLES,
)
from app.service import task_of
from app.settings import Settings
from tests import study

ENDPOINTS: dict[str, tuple[dict[str, Any], Any, type]] = {
    "solve": (SOLVE_EXAMPLES, SolveRequest, solver.SolveInput),
    "sweep": (SWEEP_EXAMPLES, SweepRequest, solver.SweepInput),
    "optimize": (OPTIMIZE_EXAMPLES, OptimizeRequest, solver.OptimizeInput),
}
EXAMPLES = [
    (endpoint, name, model, kind)
    for endpoint, (examples, model, kind) in ENDPOINTS.items()
    for name in examples
]


def _task(endpoint: str, name: str) -> Any:
    examples, model, _ = ENDPOINTS[endpoint]
    return model.model_validate(examples[name]["value"]).to_solver()


@pytest.mark.parametrize(
    ("endpoint", "name", "model", "kind"),
    EXAMPLES,
    ids=[f"{endpoint}-{name}" for endpoint, name, _, _ in EXAMPLES],
)
def test_every_example_is_a_valid_body_and_becomes_its_solver_input(
    endpoint: str, name: str, model: Any, kind: type
) -> None:
    example = ENDPOINTS[endpoint][0][name]
    assert example["summary"]
    request = model.model_validate(example["value"])
    task = request.to_solver()
    assert isinstance(task, kind)
    # The service's default limits (stations, points, panels) let every example through.
    assert isinstance(task_of(request, Settings(workers=1)), kind)


def test_the_study_wing_is_the_design_studys_to_ten_significant_digits() -> None:
    """Printed to 10 significant digits: each value within 5e-10 relative of the study's
    (a digit of margin over the 5e-11 of the rounding)."""
    exact = study.study_arrays()
    for name in ("y", "chord", "bending_stiffness", "torsional_stiffness"):
        printed = np.asarray(STUDY_WING[name])
        assert printed.shape == (30,)
        np.testing.assert_allclose(printed, exact[name], rtol=5e-10, atol=0, err_msg=name)
    assert STUDY_WING["elastic_axis"] == exact["elastic_axis"] == 0.4
    wing = _task("solve", "study").wing
    assert wing.semispan == study.SPAN / 2


def test_the_study_example_is_the_studys_flight() -> None:
    flight = _task("solve", "study").flight
    assert (flight.velocity, flight.alpha) == (10.0, study.ALPHA)
    # At sea level: the ISA's 1.225 kg/m^3 (AeroSandbox's, which the study used, is 7e-7 less).
    assert flight.density == solver.ISA_SEA_LEVEL_DENSITY == 1.225
    assert flight.density == pytest.approx(study.DENSITY, rel=1e-6)
    assert STUDY_SOLVE is SOLVE_EXAMPLES["study"]["value"]


def test_the_examples_past_the_fold_ask_for_speeds_beyond_it() -> None:
    """The study's wing folds at 21.44 m/s at 5 deg: the 23 m/s solve has no equilibrium, and
    of the sweep to the fold exactly 22 and 23 m/s lie beyond it."""
    beyond = _task("solve", "beyond_divergence")
    assert beyond.flight.velocity > study.FOLD_VELOCITY and beyond.flight.alpha == study.ALPHA
    sweep = _task("sweep", "to_the_fold")
    assert [v for v in sweep.airspeeds if v > study.FOLD_VELOCITY] == [22.0, 23.0]
    assert _task("sweep", "study").airspeeds == tuple(float(v) for v in sorted(study.SWEEP))


TRIMMED = {
    "solve at its weight": ("solve", "at_its_weight", 300.0),
    "a 2 g pull-up": ("solve", "pull_up", 600.0),
    "the tube spar at 2.5 g": ("solve", "tube_spar", 750.0),
    "sweep at its weight": ("sweep", "at_its_weight", 300.0),
}


@pytest.mark.parametrize(("endpoint", "name", "lift"), list(TRIMMED.values()), ids=list(TRIMMED))
def test_the_trimmed_examples_carry_what_they_say(endpoint: str, name: str, lift: float) -> None:
    flight = _task(endpoint, name).flight
    assert flight.trimmed and flight.required_lift == pytest.approx(lift, rel=1e-15)


def test_the_tube_spar_example_gives_stiffness_from_a_carbon_tube_in_naca_0012() -> None:
    wing = _task("solve", "tube_spar").wing
    assert wing.spar is not None
    np.testing.assert_array_equal(wing.bending_stiffness, wing.spar.bending_stiffness)
    assert wing.spar.material.youngs_modulus == 70e9
    # 80 % of the 12 % thick section: the tube's diameter follows the chord.
    np.testing.assert_allclose(wing.spar.outer_diameter, 0.8 * 0.12 * wing.chord, rtol=1e-12)


def test_the_optimisation_examples_are_the_studys_sketch_and_its_reference() -> None:
    sketch, reference = _task("optimize", "study"), _task("optimize", "aerosandbox_reference")
    assert (sketch.problem.lift, sketch.problem.velocity) == (300.0, 12.0)
    assert sketch.problem.control_points == 6 and sketch.problem.objective == "induced_drag"
    assert reference.problem.control_points is None  # every station, as AeroSandbox
    assert reference.problem.smoothness_weight == 0.01
    assert solver.digest(sketch.wing) == solver.digest(reference.wing)
