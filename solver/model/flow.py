"""The flow model's outputs: what control surfaces and roll add to the coupled function.

The flow model (`flow=True` in `solver.model.residual`'s builders; `solver.controls.roll`,
`solver.controls.effectiveness`) is the same model with the image half's flow as parameters
(`solver.model.flow_vlm`: the mirror or the rotation about x, and the image's derivatives exact
or turned), a steady roll rate p, which adds (p / V) (0, z, -y) to the unit freestream at the
collocation and force points (the air seen from a wing rolling about x,
`solver.model.aerodynamics.onset`), and more outputs: the derivatives of r0, r1, the lift and
the rolling moment along a control direction (a d(camber)/d(deflection) parameter) and in the
roll rate, the rolling moment's gradient, and the panel loads' derivatives along a direction in
the unknowns. Its functions are separate (built with Python branches, so `flow=False` builds
exactly the symmetric model's graph): the flow kernels and the outputs would cost every
symmetric Jacobian ~15 % (measured), and the flow model lives in a library of its own
(`solver.numerics.compiled`), compiled when first used.
"""

from __future__ import annotations

import casadi as ca

from solver.model.induced import Kernel, induced_derivative
from solver.model.symbols import Symbols

__all__ = ["flow_outputs"]


def flow_outputs(
    sym: Symbols,
    flow_lattice: list[ca.MX],
    flow_aero: list[ca.MX],
    loads: ca.MX,
    loads_x: ca.MX,
    loads_ind: ca.MX,
    tangency_kernel: Kernel,
    forces_kernel: Kernel,
    center_z: ca.MX,
) -> dict[str, ca.MX]:
    """The flow model's outputs (`solver.model.residual.build_coupled_function`), by name."""
    layout, m = sym.layout, sym.m
    heave, deformed = sym.heave, sym.parameters.deformed_axis
    left_c, right_c, collocation_c, center_c, leading_edge_z, quarter_chord_z = flow_lattice
    tangency_c, loads_c, tangency_p, loads_p = flow_aero
    # Along the control direction: the geometry's own part, and the induced velocities' by the
    # chain rule through the lattice's points (as for z).
    tangency_c = tangency_c + induced_derivative(
        *tangency_kernel, collocation_c, left_c, right_c, m, 1
    )
    loads_c = loads_c + ca.mtimes(
        loads_ind, induced_derivative(*forces_kernel, center_c, left_c, right_c, m)
    )

    def r0_along(tangency_along: ca.MX) -> ca.MX:
        return ca.vertcat(ca.MX(layout.n_structure, 1), tangency_along)

    def r1_along(loads_along: ca.MX) -> ca.MX:
        return sym.placed(sym.beam.load_rows(loads_along, heave, deformed))

    direction = sym.parameters.direction
    structure_direction = direction[layout.structure]
    return {
        "r0_control": r0_along(tangency_c),
        "r1_control": r1_along(loads_c),
        "lift_control": sym.lift(loads_c),
        "roll": sym.roll(loads),
        "roll_x": sym.roll(loads_x),
        "roll_control": sym.roll(loads_c),
        "r0_rate": r0_along(tangency_p),
        "r1_rate": r1_along(loads_p),
        "roll_rate": sym.roll(loads_p),
        "loads_along": ca.mtimes(loads_x, direction),
        "loads_control": loads_c,
        "loads_rate": loads_p,
        "center_along": ca.mtimes(center_z, structure_direction),
        "center_control": center_c,
        "leading_edge_along": ca.mtimes(leading_edge_z, structure_direction),
        "quarter_chord_along": ca.mtimes(quarter_chord_z, structure_direction),
    }
