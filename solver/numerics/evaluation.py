"""What the numerics need from the model at one state, without CasADi or threads."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["AlphaTerms", "ControlTerms", "Evaluation"]


@dataclass(frozen=True)
class Evaluation:
    """r = r0 + q r1 and J = J0 + q J1 at one state x; arrays owned by the caller.

    r0, r1: (n,) residual parts; jacobian0, jacobian1: (n, n) their exact Jacobians in x.
    The residual is affine in the dynamic pressure q [Pa], so one evaluation serves every q.
    """

    r0: np.ndarray
    r1: np.ndarray
    jacobian0: np.ndarray
    jacobian1: np.ndarray

    def residual(self, q: float) -> np.ndarray:
        return self.r0 + q * self.r1

    def jacobian(self, q: float) -> np.ndarray:
        return self.jacobian0 + q * self.jacobian1

    @property
    def nbytes(self) -> int:
        return self.r0.nbytes + self.r1.nbytes + self.jacobian0.nbytes + self.jacobian1.nbytes

    def read_only(self) -> Evaluation:
        """This evaluation with its arrays made read-only (it is kept in a cache and shared by
        every answer that starts from it), returned for chaining."""
        for array in (self.r0, self.r1, self.jacobian0, self.jacobian1):
            array.setflags(write=False)
        return self


@dataclass(frozen=True)
class AlphaTerms:
    """What trimmed flight and design add at one state x, per degree of alpha or per unit q.

    r0, r1: (n,) d(r0)/d(alpha), d(r1)/d(alpha); lift: [m^2] lift of both halves per unit q;
    lift_x: (n,) its gradient in x; lift_alpha: [m^2/deg] its derivative in alpha; drag: [m^2]
    near-field induced drag of both halves per unit q; drag_x: (n,) its gradient in x.
    """

    r0: np.ndarray
    r1: np.ndarray
    lift: float
    lift_x: np.ndarray
    lift_alpha: float
    drag: float
    drag_x: np.ndarray


@dataclass(frozen=True)
class ControlTerms:
    """What control surfaces and roll add at one state x (`solver.model.residual`).

    Along the model's control direction (d(camber)/d(deflection), per radian of deflection):
    r0, r1: (n,) d(r0), d(r1); lift: [m^2/rad] d(lift per unit q) (both halves).
    roll: [m^3] the rolling moment about x per unit q (twice the right half's: both halves' in
    the antisymmetric flow); roll_x: (n,) its gradient in x; roll_control: [m^3/rad] its
    derivative along the control direction.
    Per unit roll rate p / V [rad/m]: rate_r0, rate_r1: (n,) d(r0), d(r1); roll_rate: [m^4]
    d(roll).
    The panel loads' derivatives, (6, M) per unit q in `solver.model.residual`'s order (Fx, Fy, Fz,
    Fz (r . e_s), (r x F) . e_s, (r x F) . e_x): loads_along along the model's direction
    parameter in x, loads_control along the control, loads_rate along p / V; the force points'
    (3, M) [m] center_along and center_control; the stations' (3, N) [m] leading_edge_along and
    quarter_chord_along (along the direction; the camber moves neither).
    """

    r0: np.ndarray
    r1: np.ndarray
    lift: float
    roll: float
    roll_x: np.ndarray
    roll_control: float
    rate_r0: np.ndarray
    rate_r1: np.ndarray
    roll_rate: float
    loads_along: np.ndarray
    loads_control: np.ndarray
    loads_rate: np.ndarray
    center_along: np.ndarray
    center_control: np.ndarray
    leading_edge_along: np.ndarray
    quarter_chord_along: np.ndarray
