"""What the solver can be asked: one row per operation, the one place an operation is listed.

A row names the operation, its input type (which holds everything its answer depends on and
answers itself with `run()`; its result type is `run()`'s), the kind of question it is, how its
answer is described, which time budget it runs in, what its progress counts and the domain
answers it can give besides its result. The web service derives everything from this table: the
route POST /{name}, its request and response models, its OpenAPI tag, summary, description and
error responses, its job, its time budget and its metric label. A new operation is its input
type, its physics and one row here.
"""

from __future__ import annotations

import typing
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Literal, Protocol

from solver.errors import (
    ConvergenceError,
    DynamicInstability,
    InfeasibleDesign,
    NoEquilibrium,
    SolverError,
)
from solver.operations.controls import ControlsInput, RollInput
from solver.operations.design import OptimizeInput
from solver.operations.dynamics import FlutterInput
from solver.operations.gust import GustInput
from solver.operations.sizing import LoadsInput
from solver.operations.statics import SolveInput, SweepInput
from solver.results.quantities import Progress

__all__ = [
    "OPERATIONS",
    "OPERATION_TABLE",
    "TAGS",
    "Operation",
    "OperationInput",
    "SpreadInput",
]

Budget = Literal["solve", "sweep", "optimize", "flutter", "loads"]

# The kinds of question, in the order the documentation lists them: tag -> what it is.
TAGS: dict[str, str] = {
    "equilibrium": "Solve for aeroelastic equilibria.",
    "design": "Optimise a wing's jig twist and spar.",
    "dynamics": "Vibration modes and flutter.",
    "controls": "Flaps and ailerons: roll, control effectiveness, reversal.",
    "loads": "Sizing loads: load cases, the flight and loads envelopes.",
    "gusts": "Gust loads: the flexible wing in 1-cos gusts and continuous turbulence.",
}


class OperationInput(Protocol):
    """What every operation's input is: frozen, checked when made, its answers cached by `key`
    (equal questions, equal keys), answered by `run`."""

    @property
    def key(self) -> bytes: ...

    def run(self, progress: Progress | None = None) -> Any: ...


class SpreadInput(OperationInput, Protocol):
    """An input whose parts are inputs of their own, answered apart: `plan` (its row's
    `parts`) lists them, each answered by its `run()` in any process, and `assemble` answers
    the whole from their answers, in `plan`'s order (what `run()` does in one process)."""

    @property
    def plan(self) -> tuple[Any, ...]: ...

    def assemble(self, answers: Sequence[Any]) -> Any: ...


@dataclass(frozen=True)
class Operation:
    """One operation: `input` answers it (`input(...).run(progress)`).

    tag: a key of `TAGS`; summary: one line; description: what it answers and how (the route's
    documentation); refusals: besides invalid input, how it answers what has no answer (the
    422 responses' description); budget: which time budget it runs in (the service's
    FLEXWING_<BUDGET>_TIMEOUT); answered: what a success is counted as; parts: the input's
    attribute whose length (or value: a count) its progress counts (None: one part); answers:
    the typed domain answers (solver errors) it can give instead of a result; requires: the
    optional parts of its input it cannot answer without (dotted paths: "wing.mass"); spread:
    its input is a `SpreadInput`, whose parts the service answers on several workers at once.
    """

    name: str
    input: type[OperationInput]
    tag: str
    summary: str
    description: str
    refusals: str
    budget: Budget
    answered: str
    parts: str | None = None
    answers: tuple[type[SolverError], ...] = (NoEquilibrium, ConvergenceError)
    requires: tuple[str, ...] = ()
    spread: bool = False

    @property
    def result(self) -> type:
        """The result type: what `input.run()` returns."""
        result: type = typing.get_type_hints(self.input.run)["return"]
        return result

    def count_parts(self, task: object) -> int:
        """[-] how many parts `task` (an `input`) reports progress in."""
        if self.parts is None:
            return 1
        parts = getattr(task, self.parts)
        return parts if isinstance(parts, int) else len(parts)


_PAST_THE_FOLD = (
    "A speed without an equilibrium is answered in its point (`status` no_equilibrium)."
)

OPERATION_TABLE: tuple[Operation, ...] = (
    Operation(
        name="solve",
        input=SolveInput,
        tag="equilibrium",
        summary="Static aeroelastic equilibrium of a wing at one flight condition",
        description="""Deformation, loads, totals and stability of the wing's equilibrium.

The answer is the equilibrium on the branch from the jig shape at this condition, followed in
dynamic pressure from the jig: it depends on the request only, never on what was asked before. A
repeated request is answered from the result cache (the same numbers). Past torsional divergence
there is no equilibrium: 422 `/problems/no-equilibrium` with the fold speed. `validity` says
where the answer leaves the model's validity.""",
        refusals="no equilibrium (/problems/no-equilibrium, with `fold_velocity`) or no "
        "convergence (/problems/not-converged).",
        budget="solve",
        answered="equilibrium",
    ),
    Operation(
        name="sweep",
        input=SweepInput,
        tag="equilibrium",
        summary="Equilibria of a wing over airspeeds, and its torsional divergence",
        description="""Solves the airspeeds, answered in the given order, each on its own.

At a fixed alpha the branch from the jig is traced to its fold first and each point is Newton
from the branch's state at its dynamic pressure; trimmed (`flight.lift` or `flight.weight`) each
point is trimmed at its speed. Either way a point depends on its own speed only, never on the
order or on the other speeds, and agrees with /solve there.

A point without equilibrium (beyond the fold) is reported in place with the reason; the response
still succeeds. `divergence` holds three estimates: linear (eigenvalue at the unloaded jig), fit
(the study's 1/A against q extrapolation) and fold (where the branch ends), each null with a
reason when it does not exist; `validity` says from which airspeed on each finding about the
points appears.""",
        refusals=_PAST_THE_FOLD,
        budget="sweep",
        answered="completed",
        parts="airspeeds",
        answers=(),
    ),
    Operation(
        name="optimize",
        input=OptimizeInput,
        tag="design",
        summary="Optimal jig twist (and spar wall) of a flexible wing carrying a lift",
        description="""Minimises the deformed wing's induced drag (near field or Trefftz plane) or
its spar's mass while it carries the lift, by IPOPT on exact gradients of the coupled
equilibrium.

Answers the optimal design, the optimal wing's equilibrium (as /solve answers it), every
constraint with its activity, span efficiencies and the rigid wing's optimum. With
`load_cases` (a multipoint design) one jig twist and spar for the design flight and every case,
each trimmed at its own angle of attack, the spar's stress held at every station of every case;
the objective is the design flight's, and each case's equilibrium is answered. No feasible
optimum: 422 `/problems/infeasible-design` naming the constraint (and the case). Long problems
can run as jobs (`POST /jobs` with operation `optimize`).""",
        refusals="no feasible optimum (/problems/infeasible-design, `constraint` names which, "
        "`case` in which load case), no equilibrium or no convergence of the optimal wing, or "
        "a design stopped by the optimizer's iteration limit "
        "(/problems/no-equilibrium, /problems/not-converged); more load cases than "
        "FLEXWING_MAX_LOAD_CASES is invalid input naming `load_cases`.",
        budget="optimize",
        answered="optimum",
        answers=(InfeasibleDesign, NoEquilibrium, ConvergenceError),
    ),
    Operation(
        name="flutter",
        input=FlutterInput,
        tag="dynamics",
        summary="Vibration modes, V-g and V-f diagrams, flutter and divergence speeds of a wing",
        description="""The p-k method (Hassig) over the airspeeds: damping and frequency of every
mode at each (`points`), the flutter speed and frequency (the first crossing to negative damping;
damping = -Re(s)/|s|, positive decays) and the mode that flutters, the divergence speed (the
zero-frequency root: the static linear divergence about the jig, the fold or the trimmed limit
about a loaded wing), and the natural modes with their shapes.

Linearised about the static equilibrium of `flight` at each airspeed (its tangent stiffness,
aerodynamic stiffness included), or about the unloaded jig (`flutter.about`).
`options.aerodynamics`: strip (Theodorsen's strip theory, the model of the published results),
lattice (the lattice's steady 3D circulation with Theodorsen's lag) or unsteady_lattice (the
lattice's panels with their wake shed and convected in the frequency domain: 3D unsteady
aerodynamics); `aerodynamic_model` says which gave the answer. Needs `wing.mass` (422 naming it
without). No flutter in the range: `status` `no_flutter_in_range`, with the least damped mode.""",
        refusals="`wing.mass` is required (invalid input naming it without); a root that could "
        "not be followed (/problems/not-converged). Airspeeds past a loaded wing's equilibria are "
        "answered in their points (`status` no_equilibrium).",
        budget="flutter",
        answered="analysed",
        parts="airspeeds",
        answers=(ConvergenceError,),
        requires=("wing.mass",),
    ),
    Operation(
        name="roll",
        input=RollInput,
        tag="controls",
        summary="The antisymmetric response to the ailerons: rolling moment, both halves, free "
        "roll",
        description="""Both wings' heave, twist and loads with the ailerons deflected (the right
wing's trailing edge down for a positive deflection, the left's up) and a steady roll rate; the
rolling moment about the x axis through the root chord (positive raising the right wing) elastic
and rigid; the hinge moments; with `free_roll`, the roll rate at which the rolling moment
vanishes and its helix angle pb/2V.

`method`: at alpha 0 with sections symmetric in z (no camber at the chordwise nodes, no jig
twist, no flap deflected) the exact antisymmetric equilibrium; elsewhere the symmetric
equilibrium (flaps included; trimmed, the one carrying the lift) with the antisymmetric
disturbance linearised about it, as Nastran's antisymmetric subcase does about the jig.""",
        refusals="a wing without control surfaces, `method` antisymmetric where the response is "
        "not exactly antisymmetric, `free_roll` of a wing without roll damping and strip "
        "aerodynamics (roll is the lattice's) are invalid input; no equilibrium (past the "
        "symmetric or the antisymmetric divergence: /problems/no-equilibrium) or no "
        "convergence (/problems/not-converged).",
        budget="solve",
        answered="rolled",
        requires=("wing.control_surfaces",),
    ),
    Operation(
        name="controls",
        input=ControlsInput,
        tag="controls",
        summary="Control effectiveness against airspeed, reversal and which comes first",
        description="""For every control surface at each airspeed: the rigid and the elastic
control derivative (a flap's lift, an aileron's rolling moment, per degree), their ratio (the
effectiveness: 1 rigid, 0 at reversal) and the hinge moment; for each surface the reversal speed
as the eigenvalue of the exact Jacobians at the unloaded jig (Nastran SOL 144's question) and
again where the sweep's derivative changes sign, the divergence of its problem (symmetric for a
flap, antisymmetric for an aileron) and which comes first. A speed without an equilibrium is
answered in its point (`status` no_equilibrium).""",
        refusals="a wing without control surfaces and strip aerodynamics (the control "
        "derivatives are the lattice's) are invalid input. " + _PAST_THE_FOLD,
        budget="sweep",
        answered="completed",
        parts="airspeeds",
        answers=(),
        requires=("wing.control_surfaces",),
    ),
    Operation(
        name="loads",
        input=LoadsInput,
        tag="loads",
        summary="Sizing loads: every load case of the flexible wing and their envelope",
        description="""Every load case flown as one equilibrium of the flexible wing, trimmed, the
wing's own mass (`wing.mass`) weighing n g against the lift (inertia relief): the cases given
(a weight and load factor, an airspeed and an altitude; a rolling pull-out with the ailerons and
a roll rate), and those a flight envelope derives (the corners and gust points of its V-n
diagrams, CS-23 or CS-25, at every weight and altitude).

Answers each case's loads or why it has none (past divergence, past the lift it can carry: a
typed status for that case, never a failure of the others), the envelope along the span (the
largest and smallest shear, bending moment and torque, each with its case), the correlated
loads at chosen stations with their convex hull, a tube spar's margins at limit and ultimate
load (1.5), and the V-n diagrams. The cases run spread over the workers.""",
        refusals="more cases than FLEXWING_MAX_LOAD_CASES (given and derived) is invalid "
        "input naming `cases`; a case that cannot be flown is answered in its place (`status`).",
        budget="loads",
        answered="completed",
        parts="case_count",
        answers=(),
        spread=True,
    ),
    Operation(
        name="gust",
        input=GustInput,
        tag="gusts",
        summary="Gust loads of the flexible wing: 1-cos gusts, the tuned gust, continuous "
        "turbulence",
        description="""The aircraft's plunge (its weight's mass; `gust.clamped` holds the root)
and the wing's lowest natural modes, with strip aerodynamics lagged by Wagner's function (R. T.
Jones' approximation) for the motion and Kuessner's (Sears and Sparks') for the gust, the
lattice's steady spanwise loading as the 3D correction (`options.aerodynamics` lattice, the
default, or strip), each strip meeting the gust when it reaches its leading edge, linearised
about the 1 g trim of `flight`. With `options.aerodynamics` unsteady_lattice the 3D unsteady
lattice's transfer functions of the modes and of the gust (each panel meeting it at its own
time) instead, answered in the frequency domain and transformed to time (as MSC Nastran's SOL
146): the same answer's form.

Answers the CS-25.341(a) 1-cos gusts, U_ds = U_ref F_g (H / 107 m)^(1/6), at every gradient H
(default 20 from 9 to 107 m): each one's load factor, incremental shear, bending moment and
torque envelopes along the span and time histories, the tuned gust of each load quantity, the
total loads (1 g plus gust, up and down); continuous turbulence (CS-25.341(b), von Karman, L =
762 m): A-bar and the design loads P_1g +- U_sigma A-bar; Pratt's K_g beside the model's load
factor. Needs `wing.mass` and `flight.weight`. Past flutter or divergence there is no gust
response: 422 `/problems/unstable`.""",
        refusals="a wing without mass or a flight without weight is invalid input naming the "
        "field; past flutter or divergence (/problems/unstable, with the growth rate); no "
        "trimmed equilibrium (/problems/no-equilibrium, /problems/not-converged).",
        budget="flutter",
        answered="analysed",
        answers=(DynamicInstability, NoEquilibrium, ConvergenceError),
        requires=("wing.mass",),
    ),
)

# Operation name -> its input type; `run()` answers each.
OPERATIONS: dict[str, type[OperationInput]] = {op.name: op.input for op in OPERATION_TABLE}
