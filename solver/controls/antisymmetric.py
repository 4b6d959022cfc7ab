"""The two models of the antisymmetric response: whether a wing's response to its ailerons is
exactly antisymmetric (symmetric sections, alpha 0, no dihedral) or must be linearised about the
symmetric equilibrium, and the antisymmetric system of the first (the right half, the image
half's flow mirrored)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.model.geometry import chordwise_nodes
from solver.statics.system import CoupledSystem, Flow

__all__ = [
    "aileron_direction",
    "antisymmetric_system",
    "is_antisymmetric",
    "without_aileron_deflections",
]


def is_antisymmetric(wing: Wing, alpha: float, chordwise: int) -> bool:
    """Whether the wing's aileron response at `alpha` [deg] is exactly antisymmetric: alpha 0,
    no dihedral (the left half is then the right one turned about x), no camber at the chordwise
    nodes (airfoil and flaps), no jig twist."""
    if alpha != 0.0 or wing.dihedral != 0.0:
        return False
    jig_twist = wing.jig_twist
    if jig_twist is not None and np.any(jig_twist != 0.0):
        return False
    return not np.any(wing.camber_at(chordwise_nodes(chordwise)) != 0.0)


def without_aileron_deflections(wing: Wing) -> Wing:
    """The wing with its ailerons neutral: the symmetric base the linearisation starts from."""
    surfaces = tuple(
        s if s.symmetric else dataclasses.replace(s, deflection=0.0) for s in wing.control_surfaces
    )
    return dataclasses.replace(wing, control_surfaces=surfaces)


def aileron_direction(wing: Wing) -> tuple[float, ...]:
    """The ailerons' deflections [rad] as the flow's control weights (flaps 0): the
    linearised disturbance of all of them at once."""
    return tuple(0.0 if s.symmetric else math.radians(s.deflection) for s in wing.control_surfaces)


def antisymmetric_system(
    wing: Wing,
    options: SolverOptions,
    roll_rate: float = 0.0,
    control: tuple[float, ...] | None = None,
) -> CoupledSystem:
    """The exactly antisymmetric model of `wing` at alpha 0 (image rotated about x), at a roll
    rate p / V [rad/m], with control direction `control` (`solver.statics.system.Flow`)."""
    flow = Flow(image=-1.0, image_jacobian=-1.0, roll_rate=roll_rate, control=control)
    return CoupledSystem.of(wing, 0.0, options, flow)
