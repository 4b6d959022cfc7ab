"""One wing at one angle of attack, as modelled: the compiled model bound to the wing's parameters.

Everything above this module speaks of a `CoupledSystem`: evaluate r0, r1, J0, J1 at a state,
the residual alone, the panel loads, and the scaled coordinates its continuation uses. Its
`flow` says which flow the image half carries (`solver.model.flow_vlm`): the symmetric flow by
default, the antisymmetric one or the antisymmetric linearisation for roll (`solver.roll`),
with a roll rate and the control direction of one surface. The model's parameter vector is
packed from the wing's compiled fields by name (`solver.model.layout`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from solver.inputs.control_surfaces import antisymmetric_camber, camber_rate
from solver.inputs.options import SolverOptions, check_lag, require_flow_model
from solver.inputs.wing import Wing
from solver.model.geometry import chordwise_nodes
from solver.model.layout import Aerodynamics, Layout, Structure
from solver.numerics.branch_points import branch_scales
from solver.numerics.cache import cached, model_for
from solver.numerics.compiled import CompiledModel
from solver.numerics.evaluation import AlphaTerms, ControlTerms, Evaluation
from solver.statics.inertia import (
    InertialLoads,
    deformed_rows,
    inertial_loads,
    lag_deformed_rows,
)

__all__ = ["SYMMETRIC", "CoupledSystem", "Flow"]


@dataclass(frozen=True)
class Flow:
    """What the model's image half carries, and what disturbs the flow (`solver.model.flow_vlm`).

    image: +1 the mirror image (symmetric flow), -1 the rotation about x (exactly
        antisymmetric flow: the right half's camber then includes the ailerons'; valid for
        sections symmetric in z at alpha 0, `solver.roll`).
    image_jacobian: the weight of the image's own derivatives: equal to `image` for the exact
        Jacobian; -1 with image +1 for the antisymmetric block at a symmetric state.
    roll_rate: [rad/m] p / V, a steady roll rate about x (positive raises the right wing).
    control: the direction of the model's control derivatives
        (`solver.numerics.evaluation.ControlTerms`): one weight per control surface of the wing,
        d(deflection_i)/d(parameter) (e_j for surface j alone; the ailerons' deflections [rad]
        for their combined disturbance), or None.
    """

    image: float = 1.0
    image_jacobian: float = 1.0
    roll_rate: float = 0.0
    control: tuple[float, ...] | None = None

    @classmethod
    def along(cls, index: int, count: int, **kwargs: float) -> Flow:
        """The flow whose control direction is surface `index`'s alone, of `count`."""
        return cls(control=tuple(1.0 if i == index else 0.0 for i in range(count)), **kwargs)

    @property
    def key(self) -> tuple[float, float, float, tuple[float, ...]]:
        return (
            self.image + 0.0,
            self.image_jacobian + 0.0,
            self.roll_rate + 0.0,
            () if self.control is None else tuple(w + 0.0 for w in self.control),
        )


SYMMETRIC = Flow()


@dataclass(frozen=True, eq=False)
class CoupledSystem:
    """The residual r(x; q) = r0(x) + q r1(x) of `wing` at `alpha` [deg], with `chordwise`
    panels per strip, the torque about the heaved elastic axis if `deformed_axis`, and the
    lattice's or strip theory's `aerodynamics` (`solver.model.layout`)."""

    wing: Wing
    alpha: float
    chordwise: int = 1
    deformed_axis: bool = False
    aerodynamics: Aerodynamics = "lattice"
    flow: Flow = SYMMETRIC
    # [1/Pa] the load factor n over the dynamic pressure q* of the flight: the wing's own mass
    # loads the beam with n times its weight at q*, carried along the path from the jig in
    # proportion to q (every point of the path from q = 0 to q* balances q/q* of both the lift
    # and the inertial load; at q* the flight's). 0: no inertial load (`solver.statics.inertia`).
    load_per_q: float = 0.0
    # The beam (`solver.model.exact_beam`): "linear" or "geometrically_exact".
    structure: Structure = "linear"

    @classmethod
    def of(
        cls, wing: Wing, alpha: float, options: SolverOptions, flow: Flow = SYMMETRIC
    ) -> CoupledSystem:
        """The system `options` model. The unsteady lattice's steady limit is the lattice
        itself: statics with it are the lattice's, on the lattice's compiled model."""
        aerodynamics: Aerodynamics = "strip" if options.aerodynamics == "strip" else "lattice"
        return cls(
            wing,
            alpha,
            options.chordwise_panels,
            options.torque_axis == "deformed",
            aerodynamics,
            flow,
            structure=options.structure,
        )

    def with_inertia(self, load_factor: float | None, dynamic_pressure: float) -> CoupledSystem:
        """The same wing with its own mass loaded by `load_factor` (None: none) at the flight's
        `dynamic_pressure` [Pa]; unchanged without `wing.mass`."""
        if load_factor is None or self.wing.mass is None:
            return self
        return dataclasses.replace(self, load_per_q=load_factor / dynamic_pressure)

    @property
    def unloaded(self) -> CoupledSystem:
        """The same wing without its inertial load (what the wing at rest is cached as)."""
        return self if self.load_per_q == 0.0 else dataclasses.replace(self, load_per_q=0.0)

    @property
    def inertia(self) -> InertialLoads | None:
        """The wing's inertial loads at one g, when its own mass loads the beam."""
        if self.load_per_q == 0.0:
            return None
        return inertial_loads(self.wing, self.layout)

    def _loaded(self, r1: np.ndarray, x: np.ndarray) -> np.ndarray:
        """r1 with the wing's inertial load per unit q at x: the apparent weight acts against
        the lift, normal to the flight path, so the wing's plane carries cos(alpha) of it
        (`solver.statics.inertia`); constant rows on the linear beam, about the deformed
        stations on the exact one."""
        if self.inertia is None:
            return r1
        return r1 + self.load_per_q * math.cos(math.radians(self.alpha)) * self._inertia_rows(x)[0]

    def _inertia_rows(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """The one-g inertial rows at x (n_unknowns,) and their derivative in x (n_unknowns,
        n_unknowns), None where they are constant (the linear beam)."""
        inertia = self.inertia
        assert inertia is not None
        if not self.layout.exact:
            return inertia.rows, None
        if self.layout.lag:
            return lag_deformed_rows(inertia, self.wing, self.layout, x)
        slope = self.layout.slope
        rows, rows_beta = deformed_rows(inertia, self.wing, self.layout, x[slope])
        rows_x = np.zeros((rows.size, x.size))
        rows_x[:, slope] = rows_beta
        return rows, rows_x

    def _loaded_evaluation(self, evaluation: Evaluation, x: np.ndarray) -> Evaluation:
        """The evaluation with the inertial load per unit q in r1 and its derivative in J1."""
        rows, rows_x = self._inertia_rows(x)
        share = self.load_per_q * math.cos(math.radians(self.alpha))
        r1 = evaluation.r1 + share * rows
        if rows_x is None:
            return dataclasses.replace(evaluation, r1=r1)
        return dataclasses.replace(
            evaluation, r1=r1, jacobian1=evaluation.jacobian1 + share * rows_x
        )

    def with_flow(self, flow: Flow) -> CoupledSystem:
        """The same wing and alpha with another `flow`."""
        return dataclasses.replace(self, flow=flow)

    def at_alpha(self, alpha: float) -> CoupledSystem:
        """The same wing and model at `alpha` [deg], sharing what does not depend on it (the
        model and every other parameter: a trimmed solve changes alpha at every iteration)."""
        other = dataclasses.replace(self, alpha=alpha)
        for name in ("parameters", "flow_parameters"):
            if name == "parameters" or name in self.__dict__:
                parameters = getattr(self, name).copy()
                parameters[self.layout.slot("alpha")] = alpha
                other.__dict__[name] = parameters
        other.__dict__["layout"] = self.layout
        for name in ("model", "flow_model"):
            if name in self.__dict__:
                other.__dict__[name] = self.__dict__[name]
        return other

    @cached_property
    def layout(self) -> Layout:
        """The mesh, with lag when the exact beam's wing has an in-plane stiffness
        (`solver.model.lag_beam`)."""
        stiffness = self.wing.in_plane_bending_stiffness
        check_lag(stiffness, SolverOptions(structure=self.structure), "")
        lag = self.structure == "geometrically_exact" and stiffness is not None
        return Layout(self.wing.n_stations, self.chordwise, self.aerodynamics, self.structure, lag)

    @cached_property
    def model(self) -> CompiledModel:
        """The mesh's model: the symmetric one for the symmetric flow, else its flow model."""
        # Looked up once per system (a system lives for one request): the model swaps compiled
        # code in by itself, and `model_for` picks up a library another process compiled.
        return self.flow_model if self.flow != SYMMETRIC else model_for(self.layout)

    @cached_property
    def flow_model(self) -> CompiledModel:
        """The mesh's flow model (`solver.numerics.compiled`), whatever the flow: the
        lattice's (control derivatives, antisymmetric flow, roll); strip theory has none."""
        require_flow_model(self.aerodynamics)
        return model_for(self.layout, flow=True)

    @cached_property
    def parameters(self) -> np.ndarray:
        """(n_parameters,) the parameter vector of `model`, read-only. Kept in the solver's
        cache: a request builds a new system, and assembling the vector costs ~0.05 ms at N =
        30."""
        if self.flow != SYMMETRIC:
            return self.flow_parameters
        return cached(("parameters", *self.key), self._assemble_parameters, _nbytes)

    @cached_property
    def flow_parameters(self) -> np.ndarray:
        """The flow model's parameter vector (`solver.model.layout`), read-only."""
        return cached(("flow_parameters", *self.key), self._assemble_flow_parameters, _nbytes)

    def _model_values(self, camber: np.ndarray) -> dict[str, object]:
        """The model's parameters by name (`solver.model.layout`): the wing's compiled fields,
        the camber at the chordwise nodes (N, k + 1), alpha and the torque axis."""
        return self.layout.wing_values(self.wing) | {
            "camber": camber,
            "alpha": self.alpha,
            "deformed_axis": self.deformed_axis,
        }

    def _assemble_parameters(self) -> np.ndarray:
        camber = self.wing.camber_at(chordwise_nodes(self.chordwise))
        parameters = self.layout.pack(self._model_values(camber))
        parameters.setflags(write=False)
        return parameters

    def _assemble_flow_parameters(self) -> np.ndarray:
        wing, flow, nodes = self.wing, self.flow, chordwise_nodes(self.chordwise)
        camber = wing.camber_at(nodes)
        if flow.image < 0:  # the right half as it is: its ailerons deflected too
            camber = camber + antisymmetric_camber(wing.control_surfaces, wing.y, nodes)
        control = np.zeros((wing.n_stations, self.chordwise + 1))
        if flow.control is not None:
            surfaces = wing.control_surfaces
            if len(flow.control) != len(surfaces):
                raise ValueError("the flow's control direction needs one weight per surface")
            control = sum(
                (
                    weight * camber_rate(surfaces, i, wing.y, nodes)
                    for i, weight in enumerate(flow.control)
                    if weight != 0.0
                ),
                control,
            )
        flow_values = {
            "image": flow.image,
            "image_jacobian": flow.image_jacobian,
            "roll_rate": flow.roll_rate,
            "control": control,
            "direction": np.zeros(self.layout.n_unknowns),
        }
        parameters = self.layout.pack(self._model_values(camber) | flow_values, flow=True)
        parameters.setflags(write=False)
        return parameters

    @property
    def model_key(self) -> tuple:  # type: ignore[type-arg]
        """The identity of the wing as modelled, whatever the alpha: what the wing at rest and
        its linear divergence are cached by (the flow's only when it is not the symmetric)."""
        key: tuple = (self.wing.key, self.chordwise, self.deformed_axis, self.aerodynamics)  # type: ignore[type-arg]
        if self.structure != "linear":
            key = (*key, self.structure)
        return key if self.flow == SYMMETRIC else (*key, self.flow.key)

    @property
    def key(self) -> tuple:  # type: ignore[type-arg]
        """The canonical identity of the wing at this alpha, as modelled (-0.0 and 0.0 alike);
        the flow's only when it is not the symmetric one."""
        key: tuple = (  # type: ignore[type-arg]
            self.wing.key,
            self.alpha + 0.0,
            self.chordwise,
            self.deformed_axis,
            self.aerodynamics,
        )
        if self.structure != "linear":
            key = (*key, self.structure)
        if self.load_per_q != 0.0:
            key = (*key, "inertia", self.load_per_q)
        return key if self.flow == SYMMETRIC else (*key, self.flow.key)

    def evaluate(self, x: np.ndarray) -> Evaluation:
        evaluation = self.model.evaluate(x, self.parameters)
        if self.inertia is None:
            return evaluation
        return self._loaded_evaluation(evaluation, x)

    def evaluate_with_alpha(self, x: np.ndarray) -> tuple[Evaluation, AlphaTerms]:
        evaluation, terms = self.model.evaluate_with_alpha(x, self.parameters)
        if self.inertia is None:
            return evaluation, terms
        # d(cos(alpha))/d(alpha) per degree: the trimmed system's exact alpha column.
        turning = -self.load_per_q * math.sin(math.radians(self.alpha)) * math.radians(1.0)
        return (
            self._loaded_evaluation(evaluation, x),
            dataclasses.replace(terms, r1=terms.r1 + turning * self._inertia_rows(x)[0]),
        )

    def residual(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        r0, r1 = self.model.residual(x, self.parameters)
        return r0, self._loaded(r1, x)

    def residual_with_lift(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(r0, r1) and the lift of both halves per unit q [m^2] at x."""
        r0, r1, lift = self.model.residual_with_lift(x, self.parameters)
        return r0, self._loaded(r1, x), lift

    def evaluate_with_controls(self, x: np.ndarray) -> tuple[Evaluation, AlphaTerms, ControlTerms]:
        """The flow model's evaluation at x, with what control surfaces and roll add."""
        return self.flow_model.evaluate_with_controls(x, self.flow_parameters)

    def residual_with_roll(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
        """(r0, r1) and the rolling moment per unit q [m^3] at x (`ControlTerms.roll`)."""
        return self.flow_model.residual_with_roll(x, self.flow_parameters)

    def flow_panel_loads(self, x: np.ndarray) -> list[np.ndarray]:
        """The flow model's `panel_loads` (with the stations' leading edges)."""
        return self.flow_model.panel_loads(x, self.flow_parameters)

    def panel_loads(self, x: np.ndarray) -> list[np.ndarray]:
        """[force (3, M) per unit q, torque (1, M) per unit q, center (3, M), quarter_chord
        (3, N), leading_edge (3, N)]."""
        return self.model.panel_loads(x, self.parameters)

    def scale(self, q_scale: float) -> np.ndarray:
        """(n + 1,) scaled coordinates of states and q, with q measured in q_scale [Pa]."""
        return branch_scales(self.layout, self.wing.semispan, self.wing.mean_chord, q_scale)


def _nbytes(array: np.ndarray) -> int:
    return array.nbytes
