"""The two wings' answer from the symmetric and antisymmetric parts: right = symmetric +
antisymmetric, left = symmetric - antisymmetric (stations and strips, each part scaled), and the
roll response assembled from them."""

from __future__ import annotations

import dataclasses
from typing import Literal

import numpy as np

from solver.inputs.flight import OperatingPoint
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.controls import HingeMoment, RollResponse, RollStability
from solver.results.equilibrium import Equilibrium, Panels, SolveInfo, Stations
from solver.statics.validity import roll_findings

__all__ = ["roll_response", "scaled_panels", "scaled_stations"]


def scaled_stations(stations: Stations, factor: float) -> Stations:
    """The stations' deformation and loads times `factor` (a linear part's, per unit of it)."""
    return dataclasses.replace(
        stations,
        heave=factor * stations.heave,
        slope=factor * stations.slope,
        twist=factor * stations.twist,
        axis_twist=factor * stations.axis_twist,
        shear=factor * stations.shear,
        bending_moment=factor * stations.bending_moment,
        torque=factor * stations.torque,
        **{name: factor * value for name, value in _lag_fields(stations).items()},
        bending_stress=None,
        shear_stress=None,
        von_mises_stress=None,
    )


_LAG = ("lag", "lag_rotation", "lag_bending_moment")


def _lag_fields(stations: Stations) -> dict[str, np.ndarray]:
    """The stations' lag fields that are given (a wing bending in its plane: `Stations.lag`)."""
    return {name: getattr(stations, name) for name in _LAG if getattr(stations, name) is not None}


def scaled_panels(panels: Panels, factor: float) -> Panels:
    """The strips' loads times `factor`."""
    return dataclasses.replace(
        panels,
        lift=factor * panels.lift,
        lift_per_span=factor * panels.lift_per_span,
        torque=factor * panels.torque,
        rigid_lift_per_span=factor * panels.rigid_lift_per_span,
    )


def _combined(
    wing: Wing,
    symmetric: tuple[Stations, Panels],
    antisymmetric: tuple[Stations, Panels],
    sign: float,
) -> tuple[Stations, Panels]:
    """One wing: the symmetric part plus `sign` times the antisymmetric part (the right wing
    +1, the left wing -1, in its mirrored frame); its spar's stresses when it has one."""
    s, a = symmetric[0], antisymmetric[0]
    stations = Stations(
        y=wing.y,
        heave=s.heave + sign * a.heave,
        slope=s.slope + sign * a.slope,
        twist=s.twist + sign * a.twist,
        axis_twist=s.axis_twist + sign * a.axis_twist,
        shear=s.shear + sign * a.shear,
        bending_moment=s.bending_moment + sign * a.bending_moment,
        torque=s.torque + sign * a.torque,
        bending_stiffness=wing.bending_stiffness,
        torsional_stiffness=wing.torsional_stiffness,
        **{
            name: value + sign * _lag_fields(a)[name]
            for name, value in _lag_fields(s).items()
            if name in _lag_fields(a)
        },
    )
    if wing.spar is not None:
        stress = wing.spar.stresses(
            stations.bending_moment,
            stations.torque,
            stations.lag_bending_moment,
            wing.in_plane_bending_stiffness,
        )
        stations = dataclasses.replace(
            stations,
            bending_stress=stress.bending,
            shear_stress=stress.shear,
            von_mises_stress=stress.von_mises,
        )
    sp, ap = symmetric[1], antisymmetric[1]
    panels = Panels(
        y=ap.y if not np.any(sp.lift) else sp.y,
        lift=sp.lift + sign * ap.lift,
        lift_per_span=sp.lift_per_span + sign * ap.lift_per_span,
        torque=sp.torque + sign * ap.torque,
        rigid_lift_per_span=sp.rigid_lift_per_span + sign * ap.rigid_lift_per_span,
    )
    return stations, panels


def roll_response(
    wing: Wing,
    flight: OperatingPoint,
    options: SolverOptions,
    *,
    method: Literal["antisymmetric", "linearised"],
    antisymmetric_state: np.ndarray,
    symmetric: Equilibrium | None,
    rate: float,
    free: bool,
    moment: float,
    rigid_moment: float,
    lift: float,
    symmetric_parts: tuple[Stations, Panels],
    antisymmetric_parts: tuple[Stations, Panels],
    hinge: list[HingeMoment],
    stability: RollStability,
    info: SolveInfo,
) -> RollResponse:
    right, right_panels = _combined(wing, symmetric_parts, antisymmetric_parts, 1.0)
    left, left_panels = _combined(wing, symmetric_parts, antisymmetric_parts, -1.0)
    q = flight.dynamic_pressure
    span = 2 * wing.semispan
    response = RollResponse(
        wing=wing,
        flight=flight,
        options=options,
        antisymmetric_state=antisymmetric_state,
        symmetric=symmetric,
        method=method,
        roll_rate=rate * flight.velocity,
        helix_angle=rate * wing.semispan,
        free_roll=free,
        rolling_moment=moment,
        rolling_moment_coefficient=moment / (q * wing.planform_area * span),
        rigid_rolling_moment=rigid_moment,
        lift=lift,
        right=right,
        left=left,
        right_panels=right_panels,
        left_panels=left_panels,
        hinge_moments=hinge,
        stability=stability,
        solver=info,
    )
    return dataclasses.replace(response, validity=roll_findings(response, options.validity))
