"""How the wing is modelled and solved: the solver's options (aerodynamics, chordwise panels,
the torque axis, tolerances, the fold), the limits of the validity findings, and a caller's
starting deformation, each field declared once (`solver.fields`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from solver import fields
from solver.errors import InvalidInput
from solver.fields import parameter, spec_of

__all__ = [
    "LAG_FIELD",
    "check_lag",
    "refuse_lag",
    "require_flow_model",
    "MAX_CHORDWISE_PANELS",
    "InitialGuess",
    "SolverOptions",
    "ValidityLimits",
]
MAX_CHORDWISE_PANELS = 8


@dataclass(frozen=True)
class InitialGuess:
    """A deformation to start Newton from (e.g. `stations` of an earlier response), N values
    each. If Newton reaches another equilibrium than the one on the branch from the jig shape,
    that one is returned, flagged `stability.branch = "other"`; otherwise the answer is the same
    as without a guess."""

    heave: tuple[float, ...] = parameter(
        "m",
        "heave at each station",
        ge=-1e4,
        le=1e4,
        why="a starting deformation",
        form="deformation",
    )
    twist: tuple[float, ...] = parameter(
        "deg",
        "twist at each station, positive nose-up",
        ge=-360.0,
        le=360.0,
        why="a starting deformation",
        form="deformation",
    )
    slope: tuple[float, ...] | None = parameter(
        "-",
        "slope du/dy at each station (default: zeros)",
        ge=-1e3,
        le=1e3,
        why="a starting deformation",
        form="deformation",
        default=None,
    )

    def state(self, n: int, chordwise: int) -> np.ndarray:
        """(3N + M,) the solver state of this deformation on N stations with k chordwise panels
        per strip (unknowns as in `solver.model.layout`); circulations start at zero (Newton's first
        step, on the exact Jacobian, sets them)."""
        state = np.zeros(3 * n + (n - 1) * chordwise)
        for part, name in enumerate(("heave", "slope", "twist")):
            values = getattr(self, name)
            if values is None:
                continue
            spec = spec_of(InitialGuess, name)
            array = fields.stations(name, list(values), None, spec)
            if array.shape[0] != n:
                raise InvalidInput(name, f"has {array.shape[0]} values but y has {n}")
            state[part * n : (part + 1) * n] = array
        return state


def _limits(cls: type, instance: object) -> None:
    """Check every number, count, flag and choice of `instance` against its declaration."""
    for name, spec in fields.specs(cls).items():
        value = getattr(instance, name)
        if spec.form == "number":
            fields.number(name, value, spec)
        elif spec.form == "integer":
            fields.integer(name, value, spec)
        elif spec.form == "flag" and not isinstance(value, bool):
            raise InvalidInput(name, "must be true or false")
        elif spec.form == "choice" and value not in spec.choices:
            raise InvalidInput(name, "must be one of " + ", ".join(map(repr, spec.choices)))


@dataclass(frozen=True)
class ValidityLimits:
    """Where an answer leaves the model's validity (the response's `validity`): the limits each
    finding is judged against (`solver.statics.validity`). They change what is said about an answer,
    never its numbers.

    The model is a linear, small-displacement beam whose torque is taken about the elastic axis
    without its deformation (the study's; `torque_axis = "deformed"` follows its heave, never its
    twist), coupled to an inviscid lattice that never stalls (the design study, 14.7). Each
    default is where that idealisation starts to cost more than a few percent, or where a real
    wing would behave otherwise; the descriptions give the reasons (heave fraction: Afonso et
    al., Prog. Aerosp. Sci. 89, 2017; cl_max: Abbott and von Doenhoff, Theory of Wing Sections).
    """

    heave_fraction: float = parameter(
        "-",
        "largest |heave| over the semispan (large_deflection); default 0.1: geometrically "
        "nonlinear effects become significant beyond tip deflections of about 10 % of the "
        "semispan, the usual bound of linear aeroelastic analysis",
        ge=1e-4,
        le=10.0,
        why="a hair's breadth to ten semispans",
        default=0.1,
    )
    slope: float = parameter(
        "-",
        "largest |bending slope du/ds| (large_deflection); default 0.1 (5.7 deg): the linear "
        "beam takes sin and tan of the slope as the slope and its cosine as 1, off by 0.2 to "
        "0.5 % at 0.1 and growing with its square",
        ge=1e-4,
        le=10.0,
        why="from 0.006 deg to 84 deg",
        default=0.1,
    )
    twist: float = parameter(
        "deg",
        "largest |twist about the elastic axis| (large_twist); default 10: the beam's torsion is "
        "linear and uncoupled from bending about axes that stay put, while a twisted section "
        "turns its principal axes (sin 10 deg = 0.17) and cos 10 deg = 1 is off by 1.5 %",
        ge=0.01,
        le=180.0,
        why="a hundredth of a degree to a half turn",
        default=10.0,
    )
    cl_max: float = parameter(
        "-",
        "the sections' maximum lift coefficient where the wing gives none (wing.cl_max), for "
        "section_stall; default 1.2: thin sections (NACA 0006 to 0012) reach 0.9 to 1.6 with "
        "thickness and Reynolds number (Abbott and von Doenhoff), 1.2 is a middle value for "
        "small wings (Reynolds numbers 1e5 to 1e6)",
        ge=0.1,
        le=10.0,
        why="a stalled flat plate's to past any high-lift system's",
        default=1.2,
    )
    divergence_margin: float = parameter(
        "-",
        "stability margin q / lambda beyond which the answer is near_divergence; default 0.5: "
        "with one torsion mode the lift goes as 1 / (1 - m), so a relative error in the "
        "torsional stiffness, lift slope or q is amplified by m / (1 - m) in the lift, more than "
        "one for one past m = 0.5",
        ge=0.01,
        le=1.0,
        why="1: only at divergence itself",
        default=0.5,
    )

    def __post_init__(self) -> None:
        _limits(ValidityLimits, self)


@dataclass(frozen=True)
class SolverOptions:
    """How to model and how to solve; the defaults suit almost every wing."""

    tolerance: float = parameter(
        "mixed units",
        "max-norm of the residual at convergence: heave rows in m, twist rows in deg, "
        "flow-tangency rows per unit airspeed",
        ge=1e-14,
        le=1e-3,
        why="round-off to a rough answer",
        default=1e-10,
    )
    max_iterations: int = parameter(
        "-",
        "Newton iterations of one attempt",
        ge=1,
        le=200,
        why="one step to far more than quadratic convergence needs",
        form="integer",
        default=30,
    )
    find_fold: bool = parameter(
        "",
        "also locate the fold of the equilibrium branch from the jig shape (where torsional "
        "divergence ends it) and report it in `fold`; costs a continuation run",
        form="flag",
        default=False,
    )
    chordwise_panels: int = parameter(
        "-",
        "panels per strip, cosine spaced (AeroSandbox's default): more resolve the camber's "
        "pitching moment; 1 is the design study's model. At most FLEXWING_MAX_PANELS (default "
        "240) panels on each half wing, (N - 1) k",
        ge=1,
        le=MAX_CHORDWISE_PANELS,
        why="the lattice's camber resolution, within a mesh the service can solve",
        form="integer",
        default=1,
    )
    safety_factor: float = parameter(
        "-",
        "factor on the spar's largest von Mises stress in its failure margin, "
        "yield / (safety_factor * max von Mises) - 1",
        ge=1.0,
        le=10.0,
        why="none to very conservative",
        default=1.0,
    )
    torque_axis: Literal["undeformed", "deformed"] = parameter(
        "",
        "axis of the torque the structure carries: 'undeformed' (the design study's, and "
        "AeroSandbox-comparable) or 'deformed' (arms from the heaved elastic-axis point, as "
        "codes that load the deformed beam do)",
        form="choice",
        choices=("undeformed", "deformed"),
        default="undeformed",
    )
    validity: ValidityLimits = parameter(
        "",
        "the limits of the findings in the response's `validity` (large deflection, large "
        "twist, section stall, near divergence); each default is documented with its reason",
        form="nested",
        given=ValidityLimits,
        default_factory=ValidityLimits,
    )
    aerodynamics: Literal["lattice", "strip", "unsteady_lattice"] = parameter(
        "",
        "the aerodynamic model: 'lattice' (the horseshoe vortex lattice, the design study's), "
        "'strip' (strip theory: each strip a two-dimensional airfoil, lift slope 2 pi, no "
        "induced velocities from the other strips or the wake; the model of the classical "
        "divergence and flutter results) or 'unsteady_lattice' (the same lattice with its wake "
        "shed and convected in harmonic motion: its steady limit is the lattice, so every "
        "static operation answers as with 'lattice'; flutter gets 3D unsteady loads); every "
        "operation runs on each",
        form="choice",
        choices=("lattice", "strip", "unsteady_lattice"),
        default="lattice",
    )
    structure: Literal["linear", "geometrically_exact"] = parameter(
        "",
        "the beam: 'linear' (the design study's small-deflection beam, the default) or "
        "'geometrically_exact' (finite bending rotations in the plane of the elastic axis and "
        "the wing's normal and torsion about the deformed axis, Reissner's inextensible "
        "elastica: the lattice sits on the deformed wing, its loads follow it, the torque is "
        "about the deformed axis; `stations.slope` is then the sine of the bending rotation, "
        "still du/ds). For wings that bend past the large_deflection finding's limits",
        form="choice",
        choices=("linear", "geometrically_exact"),
        default="linear",
    )

    def __post_init__(self) -> None:
        _limits(SolverOptions, self)
        if not isinstance(self.validity, ValidityLimits):
            raise InvalidInput("validity", "must be a solver.ValidityLimits")
        if self.aerodynamics not in ("lattice", "strip", "unsteady_lattice"):
            raise InvalidInput("aerodynamics", "must be 'lattice', 'strip' or 'unsteady_lattice'")
        if self.structure not in ("linear", "geometrically_exact"):
            raise InvalidInput("structure", "must be 'linear' or 'geometrically_exact'")


LAG_FIELD = "wing.in_plane_bending_stiffness"


def refuse_lag(what: str) -> None:
    """Refuse a wing with lag bending (`solver.model.lag_beam`) for `what` (a phrase naming
    the operation or the part of it), naming `wing.in_plane_bending_stiffness`: lag is taken
    by the statics, flutter, the controls and the load cases only for now."""
    raise InvalidInput(
        LAG_FIELD,
        "lag (in-plane) bending is taken by /solve, /sweep, /flutter, /controls, /roll and "
        f"/loads' cases for now: {what} does not take it yet; leave the field out (the wing "
        "rigid in its plane)",
    )


def check_lag(in_plane_bending_stiffness: object, options: SolverOptions | None, what: str) -> None:
    """A wing's in-plane stiffness refused where it cannot act: under the linear beam (it
    needs options.structure = geometrically_exact), and for `what` (an operation that does not
    take lag yet; "" for one that does), naming the field."""
    if in_plane_bending_stiffness is None:
        return
    if (options or SolverOptions()).structure != "geometrically_exact":
        raise InvalidInput(
            LAG_FIELD,
            "needs options.structure = geometrically_exact (the linear beam is rigid in the "
            "wing's plane)",
        )
    if what:
        refuse_lag(what)


def require_flow_model(aerodynamics: str) -> None:
    """Refuse strip theory (`aerodynamics`, as options name it) where the lattice's flow model
    is needed: control derivatives, roll and the antisymmetric flow (naming
    `options.aerodynamics`)."""
    if aerodynamics == "strip":
        raise InvalidInput(
            "options.aerodynamics",
            "control surfaces' derivatives, roll and the antisymmetric flow are the lattice's: "
            "strip theory answers the symmetric statics and flutter only",
        )
