"""One flight of a multipoint design problem as the optimiser sees it: the design space of
`solver.optimization.design_space` flown at this case's dynamic pressure, with its own angle of
attack as a design variable (a load case's; the design flight's stays fixed) and the wing's own
mass under its load factor (inertia relief, `solver.statics.inertia`).

The design vector of a multipoint problem is v = (twist d, walls t, alpha_1 .. alpha_C): every
case reads the shared twist and walls, and its own alpha. What a case adds to the single-point
space's exact gradients are its explicit derivatives:

- by its alpha: the residual's dr/dalpha = dr0/dalpha + q dr1/dalpha (the compiled model's, the
  mass's cos(alpha) turning included), the lift's dl/dalpha, and the internal loads' (back
  substituted from dr1/dalpha's beam rows);
- by the walls, of the wing's own mass: a sized spar's mass per length rho A(t) loads the beam
  (the inertial bending moment is linear in it: `spar_bending_per_mass`), besides the
  stiffnesses EI(t), GJ(t) every load's beam rows divide by (the single-point space's terms,
  with the net moment).

The mass's rows are those `solve` gives the designed wing (`CoupledSystem.with_inertia`: the
lift's load less n cos(alpha) times the mass's one-g load), so the optimum's stress in each case
is what /solve reports for that case's flight.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np

from solver.inputs.design import DesignProblem
from solver.inputs.options import SolverOptions
from solver.inputs.spar import TubeSpar
from solver.inputs.wing import Wing
from solver.model.beam import DEG_PER_RAD
from solver.model.geometry import arc_length, in_wing_plane
from solver.numerics.evaluation import AlphaTerms
from solver.optimization.design_space import DesignPoint, DesignSpace
from solver.statics.inertia import (
    GRAVITY,
    deformed_rows,
    deformed_stations,
    inertial_loads,
    strip_station_weights,
)

__all__ = ["CaseFlight", "CaseSpace", "spar_bending_per_mass"]


@dataclasses.dataclass(frozen=True)
class CaseFlight:
    """One case's flight as the design space flies it.

    name: the case's; velocity [m/s], density [kg/m^3]; lift [N] to carry; load_factor: n, what
    the wing's own mass weighs in g; alpha [deg]: the fixed angle of attack (the design flight)
    or where its variable starts (a load case); alpha_index: its variable's place in v, or None
    when fixed.
    """

    name: str
    velocity: float
    density: float
    lift: float
    load_factor: float
    alpha: float
    alpha_index: int | None

    @property
    def dynamic_pressure(self) -> float:
        """q = rho V^2 / 2 [Pa] (`solver.inputs.flight.dynamic_pressure`'s arithmetic)."""
        return 0.5 * self.density * self.velocity * self.velocity


def spar_bending_per_mass(wing: Wing, along: np.ndarray | None = None) -> np.ndarray:
    """(N, N) [N m / (kg/m)] the inertial bending moment at one g at each station (row) per unit
    mass per length at each station (column), as `solver.statics.inertia` lumps it: each strip's
    mass, its stations' mean times its length, at its middle on the elastic axis, normal to the
    wing's plane; its arms along the jig axis, or along the stations `along` (N,) [m] (the exact
    beam's deformed stations, `solver.statics.inertia.deformed_stations`). Linear: the moment
    of a spar's own mass rho A is this times rho A."""
    h = np.diff(arc_length(wing))  # the strips' lengths along the (inextensible) axis
    arc = arc_length(wing) if along is None else along
    middle = (arc[:-1] + arc[1:]) / 2
    weight = float(in_wing_plane((0.0, 0.0, -GRAVITY), wing)[2])
    n = wing.n_stations
    out = np.zeros((n, n))
    for i in range(n):
        for k in range(i, n - 1):  # the strips outboard of station i
            arm = weight * h[k] / 2 * (middle[k] - arc[i])
            out[i, k] += arm
            out[i, k + 1] += arm
    return out


class CaseSpace(DesignSpace):
    """The reduced functions of one case of a multipoint problem (module docstring): v ->
    this case's equilibrium -> its lift, drags, stresses, tip heave, with exact gradients."""

    def __init__(
        self,
        wing: Wing,
        problem: DesignProblem,
        options: SolverOptions,
        flight: CaseFlight,
        n_alpha: int,
    ) -> None:
        super().__init__(wing, problem, options, rigid=False)
        self.flight, self.n_alpha = flight, n_alpha
        self.velocity = flight.velocity
        self.q = flight.dynamic_pressure
        self.alpha = flight.alpha
        self.mass = None if wing.mass is None else inertial_loads(wing, self.layout)
        # The exact beam's stations along the jig axis at the last equilibrium: the weight's
        # arms (`solver.statics.inertia`); None on the linear beam, the jig's.
        self.along: np.ndarray | None = None
        if self.mass is not None and self.n_wall:
            assert wing.spar is not None
            self.per_mass = spar_bending_per_mass(wing)
            self.spar_area = wing.spar.area

    @property
    def n_design(self) -> int:
        return self.n_twist + self.n_wall + self.n_alpha

    def alpha_of(self, v: np.ndarray) -> float:
        """[deg] this case's angle of attack in design `v`."""
        index = self.flight.alpha_index
        return self.flight.alpha if index is None else float(v[index])

    # --- the wing's own mass

    def _mass_loads(self, tube: TubeSpar | None) -> tuple[np.ndarray, np.ndarray]:
        """(N,) the mass's one-g bending moment [N m] and torque [N m] of the design's walls."""
        assert self.mass is not None
        bending = self.mass.bending_moment
        if self.n_wall and tube is not None:
            extra = tube.material.density * (tube.area - self.spar_area)
            bending = bending + self.per_mass @ extra
        return bending, self.mass.torque

    def _beam_rows(self, bending: np.ndarray, torque: np.ndarray, tube: TubeSpar | None):
        """(n_unknowns, ...) loads' terms in the beam's rows (`solver.statics.inertia`): linear
        in the loads (vectors, or matrices of their derivatives)."""
        ei, gj = self._stiffness(tube)
        layout, h = self.layout, self.h
        extra = (1,) * (bending.ndim - 1)
        ei, gj = ei.reshape(-1, *extra), gj.reshape(-1, *extra)
        h = h.reshape(-1, *extra)
        rows = np.zeros((layout.n_unknowns, *bending.shape[1:]))
        per = bending / ei
        rows[layout.bending_rows] = -h / 2 * (per[:-1] + per[1:])
        per = torque / gj
        rows[layout.torsion_rows] = -DEG_PER_RAD * h / 2 * (per[:-1] + per[1:])
        return rows

    def _mass_rows(self, tube: TubeSpar | None) -> np.ndarray:
        """(n_unknowns,) the mass's one-g rows in the beam's equations (`InertialLoads.rows`)
        with the design's walls."""
        assert self.mass is not None
        if not self.n_wall:
            return self.mass.rows
        return self._beam_rows(*self._mass_loads(tube), tube)

    def _mass_terms(
        self, x: np.ndarray, tube: TubeSpar | None
    ) -> tuple[np.ndarray, np.ndarray | None]:
        """The mass's one-g rows at x with the design's walls, and their derivative in x
        (n_unknowns, n_unknowns): constant on the linear beam (None), about the deformed
        stations on the exact beam (`solver.statics.inertia`, as `CoupledSystem` loads it)."""
        assert self.mass is not None
        layout = self.layout
        if not layout.exact:
            return self._mass_rows(tube), None
        beta = x[layout.slope]
        if not self.n_wall:
            rows, rows_beta = deformed_rows(self.mass, self.wing, layout, beta)
        else:
            assert tube is not None
            along, along_beta = deformed_stations(self.wing, beta)
            weights = self.mass.station_weights + strip_station_weights(self._spar_force(tube))
            torque = self.mass.torque
            rows = self._beam_rows(weights @ along, np.cos(beta) * torque, tube)
            rows_beta = self._beam_rows(weights @ along_beta, np.diag(-np.sin(beta) * torque), tube)
        rows_x = np.zeros((rows.size, x.size))
        rows_x[:, layout.slope] = rows_beta
        return rows, rows_x

    def _mass_load(
        self, tube: TubeSpar | None, share: float
    ) -> Callable[[np.ndarray], tuple[np.ndarray, np.ndarray | None]]:
        """x -> the mass's rows in r1 (per unit q: `share` = n cos(alpha) / q of the one-g
        rows) and their derivative in x, None where constant (`_mass_terms`)."""

        def load(x: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
            rows, rows_x = self._mass_terms(x, tube)
            return share * rows, None if rows_x is None else share * rows_x

        return load

    def _spar_force(self, tube: TubeSpar) -> np.ndarray:
        """(N-1,) [N] the strips' one-g weight normal to the plane of the design's spar beyond
        the wing's own (its mass per length rho (A - A_wing), lumped as
        `solver.statics.inertia` lumps it)."""
        extra = tube.material.density * (tube.area - self.spar_area)
        weight = float(in_wing_plane((0.0, 0.0, -GRAVITY), self.wing)[2])
        return weight * self.h * (extra[:-1] + extra[1:]) / 2

    def _share(self, alpha: float) -> float:
        """[1/Pa] n cos(alpha) / q: the mass's rows' weight in r1 (`CoupledSystem._loaded`)."""
        return self.flight.load_factor / self.q * math.cos(math.radians(alpha))

    # --- one design

    def _evaluate(self, v: np.ndarray) -> DesignPoint:
        jig, wall = self.split(v)
        tube = self.tube(wall)
        alpha = self.alpha_of(v)
        self.alpha = alpha
        p = self.parameters(jig, tube)
        p[self.layout.slot("alpha")] = alpha
        share = self._share(alpha)
        x = self._equilibrium(p, None if self.mass is None else self._mass_load(tube, share))
        self.evaluations += 1
        self.x = x
        ev, terms = self.system.model.evaluate_with_alpha(x, p)
        if self.mass is not None:
            rows, rows_x = self._mass_terms(x, tube)
            if self.layout.exact:
                self.along = deformed_stations(self.wing, x[self.layout.slope])[0]
            # d(cos(alpha))/d(alpha) per degree: the mass's part of dr1/dalpha.
            n_over_q = self.flight.load_factor / self.q
            turning = -n_over_q * math.sin(math.radians(alpha)) * math.radians(1.0) * rows
            jacobian1 = ev.jacobian1 if rows_x is None else ev.jacobian1 + share * rows_x
            ev = dataclasses.replace(ev, r1=ev.r1 + share * rows, jacobian1=jacobian1)
            terms = dataclasses.replace(terms, r1=terms.r1 + turning)
        point = self._functions(v, x, ev, terms, tube)
        if self.flight.alpha_index is not None:
            # The near field's drag has no alpha derivative from the model: a load case's drag
            # is nothing the problem asks for (the objective is the design flight's).
            point.values.pop("induced_drag")
            point.gradients.pop("induced_drag")
        return point

    def _explicit_rows(self, r_v: np.ndarray, terms: AlphaTerms, tube: TubeSpar | None) -> None:
        index = self.flight.alpha_index
        if index is not None:
            r_v[:, index] = terms.r0 + self.q * terms.r1
        if self.mass is not None and self.n_wall and tube is not None:
            r_v[:, self.walls] += self.q * self._mass_wall_rows(tube)

    def _mass_per_wall(self, tube: TubeSpar) -> np.ndarray:
        """(N, N) [N m / m] d(one-g inertial bending moment)/d(wall thickness), about the
        exact beam's deformed stations at the last equilibrium (`along`)."""
        d_area = math.pi * (tube.outer_diameter - 2 * tube.wall_thickness)  # dA/dt [m]
        per_mass = self.per_mass
        if self.along is not None:
            per_mass = spar_bending_per_mass(self.wing, self.along)
        return per_mass * (tube.material.density * d_area)[None, :]

    def _mass_wall_rows(self, tube: TubeSpar) -> np.ndarray:
        """(n_unknowns, N) d(mass rows in r1)/d(walls) through the spar's own mass, at fixed
        stiffness (per unit q)."""
        d_bending = self._mass_per_wall(tube)
        return self._share(self.alpha) * self._beam_rows(d_bending, np.zeros_like(d_bending), tube)

    def _explicit_lift(self, lift_v: np.ndarray, terms: AlphaTerms) -> None:
        index = self.flight.alpha_index
        if index is not None:
            lift_v[index] = terms.lift_alpha

    def _explicit_loads(
        self,
        moment_v: np.ndarray,
        torque_v: np.ndarray,
        terms: AlphaTerms,
        tube: TubeSpar | None,
    ) -> None:
        index, layout = self.flight.alpha_index, self.layout
        if index is not None:
            ei, gj = self._stiffness(tube)
            moment_v[:, index] = self._back_substitute(terms.r1[layout.bending_rows], ei, 1.0)
            torque_v[:, index] = self._back_substitute(
                terms.r1[layout.torsion_rows], gj, DEG_PER_RAD
            )
        if self.mass is not None and self.n_wall and tube is not None:
            moment_v[:, self.walls] += self._share(self.alpha) * self._mass_per_wall(tube)
