"""solver.numerics.continuation: the branch from the jig, traced by pseudo-arclength continuation,
is the same however far and in what order it is asked for."""

from __future__ import annotations

import numpy as np
import pytest

from solver import FlightCondition, NoEquilibrium, Wing, solve
from solver.numerics.continuation import BranchTracer, _turning_point
from solver.statics.branch import pressure_scale
from solver.statics.jig import jig
from solver.statics.system import CoupledSystem
from tests.study import DENSITY, study_wing


def _tracer(system: CoupledSystem) -> BranchTracer:
    start = jig(system)
    return BranchTracer(
        system.evaluate,
        system.residual,
        np.array(start.state),
        system.scale(pressure_scale(system)),
    )


@pytest.fixture(scope="module")
def system() -> CoupledSystem:
    return CoupledSystem(study_wing(), 5.0)


def _same(a, b) -> None:
    assert len(a.points) == len(b.points)
    assert a.folded == b.folded and a.reason == b.reason and a.evaluations == b.evaluations
    for p, q in zip(a.points, b.points, strict=True):
        np.testing.assert_array_equal(p.state, q.state)
        np.testing.assert_array_equal(p.tangent, q.tangent)
        assert p.dynamic_pressure == q.dynamic_pressure and p.arclength == q.arclength


@pytest.mark.parametrize("first_limit", [20.0, 100.0, 250.0], ids=["20Pa", "100Pa", "250Pa"])
def test_a_branch_extended_later_is_the_branch_traced_at_once(system, first_limit):
    """The prefix property that makes cached branches harmless: a trace to 100 Pa later
    extended to the fold holds the same bits as one traced to the fold at once, and a view to
    100 Pa of the longer trace is the shorter trace."""
    at_once = _tracer(system)
    full = at_once.view(0.5 * DENSITY * 30.0**2)
    in_steps = _tracer(system)
    short = in_steps.view(first_limit)
    _same(short, at_once.view(first_limit))
    _same(in_steps.view(0.5 * DENSITY * 30.0**2), full)
    assert full.folded


def test_the_branch_rises_in_q_until_its_fold(system):
    branch = _tracer(system).view(0.5 * DENSITY * 30.0**2)
    pressures = [point.dynamic_pressure for point in branch.points]
    assert pressures[0] == 0.0
    assert np.all(np.diff(pressures) > 0)
    assert branch.fold is not None and branch.fold.dq_ds == pytest.approx(0.0, abs=1e-5)


def test_a_continuation_step_evaluates_its_jacobians_once(system):
    """Chord start from the previous point, one Newton correction on Jacobians evaluated at the
    first corrected point, then a chord correction on the same factors: one evaluation per
    step on the study wing (the fold's own trials are located on fresh Jacobians). A step whose
    correction does not contract is retried shorter, on fresh Jacobians: whether one does sits
    on a threshold that round-off of another machine may cross, so one retry is allowed."""
    branch = _tracer(system).view(0.5 * DENSITY * 21.0**2)
    assert branch.fold is None and len(branch.points) > 5
    steps = np.diff([point.evaluations for point in branch.points])
    assert np.all(steps >= 1) and np.sum(steps - 1) <= 1, steps


def test_each_branch_points_tangent_spans_the_augmented_jacobians_null_space(system):
    """A branch point's tangent t (unit, scaled coordinates) solves [J scale_x, r1 scale_q] t = 0
    with the Jacobians it carries (evaluated up to two corrections away: a continuation step
    finishes with a chord correction), and the orientation taken from the tangent solve's LU
    factors is the sign of det [[J, r1], [t^T]] itself."""
    tracer = _tracer(system)
    branch = tracer.view(0.5 * DENSITY * 25.0**2)
    scale = branch.scale
    for point in branch.points[1:]:
        evaluation = system.evaluate(point.state)
        q = point.dynamic_pressure
        augmented = np.column_stack(
            [evaluation.jacobian(q) * scale[:-1], evaluation.r1 * scale[-1]]
        )
        t = point.tangent
        assert np.linalg.norm(t) == pytest.approx(1.0, abs=1e-14)
        # Jacobians from up to two corrections back (~1e-4 scaled): measured <= 7.5e-7 here.
        assert np.linalg.norm(augmented @ t) < 1e-5 * np.linalg.norm(augmented)
        sign, _ = np.linalg.slogdet(np.vstack([augmented, t]))
        assert sign == tracer._orientation


@pytest.mark.parametrize(
    ("width", "turn"), [(1.5, 1.0), (1.0, 0.3), (4.0, 3.9)], ids=["middle", "early", "late"]
)
def test_the_folds_first_trial_is_where_a_quadratic_q_turns(width: float, turn: float):
    """Near a fold q(sigma) is quadratic, q = sigma (2 turn - sigma): the cubic through both
    bracket ends' q and dq/dsigma is that parabola, and turns exactly at its vertex."""
    rise = width * (2 * turn - width)
    start, end = 2 * turn, 2 * (turn - width)
    assert _turning_point(width, rise, start, end) == pytest.approx(turn, rel=1e-12)


def test_the_folds_first_trial_needs_a_bracket():
    assert _turning_point(1.0, 0.5, 1.0, 0.5) is None  # q still rising at the far end
    assert _turning_point(1.0, 0.5, -1.0, -2.0) is None  # falling from the start
    assert _turning_point(0.0, 0.0, 1.0, -1.0) is None  # no width


def test_the_hermite_start_lies_within_one_newton_step_of_the_branch(system):
    branch = _tracer(system).view(0.5 * DENSITY * 25.0**2)
    q = 0.5 * DENSITY * 14.3**2
    start = branch.start_for(q)
    r0, r1 = system.residual(start)
    # O(ds^4) interpolation error: the residual there is small but not yet converged.
    assert np.max(np.abs(r0 + q * r1)) < 1e-3


# Found by fuzzing (benchmarks/fuzz_benchmark.py, seed 1): locating this wing's fold, the regula
# falsi's bracket lost all its width in floating point and the next trial divided by zero; the
# request was answered "not converged" instead of "beyond the fold". The fold lies far below the
# requested 19.5 m/s, so the outcome does not hang on round-off.
_SOFT_TORSION_WING = dict(
    y=[
        0.0,
        0.029177817187118562,
        0.05810669952580521,
        0.08653983599198287,
        0.11423464509056369,
        0.14095484447523324,
        0.1664724668261184,
        0.19056980478658175,
        0.21304126836562656,
        0.23369513895921137,
        0.2523552050257814,
        0.2688622654610106,
        0.28307548784549125,
        0.2948736099772799,
        0.30415597443824893,
        0.31084338736768685,
        0.3148787941163951,
        0.316227766016838,
    ],
    chord=[
        1.0,
        0.9756058192604785,
        0.9514197610698808,
        0.927648172348925,
        0.9044938639109523,
        0.8821543801515763,
        0.8608203136695518,
        0.8406736791979234,
        0.8218863607184999,
        0.8046186450083258,
        0.7890178541294152,
        0.7752170885288631,
        0.7633340914727603,
        0.753470244502163,
        0.7457097024815298,
        0.7401186756190905,
        0.7367448645846951,
        0.7356170535445167,
    ],
    elastic_axis=[
        0.3783655271500469,
        0.19825171784791623,
        0.11358605110263822,
        0.25,
        0.6987791094627086,
        0.22643717468999236,
        0.07891383191124546,
        0.4616259295241118,
        0.31799429370002624,
        0.6860528653192718,
        0.18006554116353718,
        0.05000000000000001,
        0.5293164896464619,
        0.2348149265829645,
        0.6811232819527553,
        0.3783655271500469,
        0.0648987270960077,
        0.49768614614575457,
    ],
    bending_stiffness=[
        3008300.658046023,
        377855.9368966219,
        587508.2000470519,
        587508.2000470519,
        587508.3613254534,
        5875083.613119256,
        1044754.0221467053,
        587508.3613119256,
        566424.459512546,
        82354.06206352643,
        587508.3613119256,
        2793000.989738237,
        124365.45116695223,
        587508.3613119256,
        587508.3613119256,
        169287.91383648725,
        642717.1779291007,
        587508.3613119256,
    ],
    torsional_stiffness=[
        0.4008860409431095,
        2.936453624066127,
        1.7884740928568144,
        7.982701315358857,
        1.1727808742137231,
        0.8016620421890874,
        0.637877848641455,
        4.422673768875449,
        1.7556394054333968,
        0.06303482490063382,
        0.5427668081215467,
        0.5158470406783666,
        0.443338734050563,
        0.386679932383093,
        0.4146764589363579,
        0.40541899250848873,
        0.3998999519612162,
        1.5571334076370578,
    ],
)


def test_a_fold_whose_bracket_collapses_still_ends_the_branch(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    monkeypatch.setenv("FLEXWING_COMPILE", "0")  # an odd mesh size: no C compilation for it
    wing = Wing.create(**{k: np.array(v) for k, v in _SOFT_TORSION_WING.items()})
    flight = FlightCondition(19.504710329614248, -6.8773130332784, 0.9405306201215876)
    with pytest.raises(NoEquilibrium) as raised:
        solve(wing, flight)
    # Nose-down alpha, soft torsion: the branch folds at 8.157 m/s (continuation, 95 evaluations).
    assert raised.value.fold_velocity == pytest.approx(8.1568, rel=1e-4)
