"""The lattice of one state as numbers: the statics' own panels (`solver.model.geometry.lattice`,
evaluated with numbers instead of symbols), with what the unsteady lattice adds to them: each
strip's trailing edge, where its wake is shed, and the patches its unsteady pressure acts on.

The unsteady pressure. Linearised, the pressure jump across the lattice is

    Delta p = rho (V gamma + d(Delta phi)/dt)

(Katz and Plotkin, Low-Speed Aerodynamics, eq. 13.37): the first term is the horseshoes'
Kutta-Joukowski force, which the static model already carries; the second is the rate of the
potential jump Delta phi, the circulation bound ahead of a point of the strip. With the bound
circulation lumped on each panel's quarter-chord line, Delta phi is piecewise constant along the
strip's chord: the sum of the strip's circulations ahead of the point. Its integral over a panel
is that of two patches, each carrying one constant jump (`Panels.patch_potential`):

    the whole panel              jump: the circulations of the panels ahead of it
    the panel aft of its vortex  jump: its own circulation (3/4 of its area, centre at 5/8)

The panels' corners are recovered from the bound vortices (0.75 front + 0.25 back of each edge)
by walking aft from the leading edge (camber at the leading edge is zero, as every section the
lattice takes has it). Points are (M, 3) [m] in geometry axes (x aft, y right, z up).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import casadi as ca
import numpy as np

from solver.inputs.wing import Wing
from solver.model.geometry import chordwise_nodes, lattice
from solver.model.layout import Layout

__all__ = ["Panels", "panels"]


@dataclass(frozen=True, eq=False)
class Panels:
    """The right half-wing's M = (N - 1) k panels (index i k + j: strip i, chordwise j).

    left, right: (M, 3) [m] bound-vortex vertices; collocation: (M, 3) [m]; normal: (M, 3) [-]
    unit normals; strip: (M,) each panel's strip; chordwise: k; shed_left, shed_right: (N - 1,
    3) [m] each strip's trailing edge at its inboard and outboard station (its wake's first
    spanwise line); patch_point, patch_area: (2M, 3) [m], [m^2] the unsteady pressure's
    patches' centres and vector areas (area times unit normal); patch_potential: (2M, M) [-]
    each patch's potential jump per unit circulation of each panel (module docstring).
    """

    left: np.ndarray
    right: np.ndarray
    collocation: np.ndarray
    normal: np.ndarray
    strip: np.ndarray
    chordwise: int
    shed_left: np.ndarray
    shed_right: np.ndarray
    patch_point: np.ndarray
    patch_area: np.ndarray
    patch_potential: np.ndarray

    @property
    def n_panels(self) -> int:
        return int(self.strip.shape[0])

    @property
    def n_strips(self) -> int:
        return int(self.shed_left.shape[0])

    def strip_sum(self) -> np.ndarray:
        """(N - 1, M) [-]: each strip's total circulation of the panels' (its wake's)."""
        return np.kron(np.eye(self.n_strips), np.ones((1, self.chordwise)))


def panels(wing: Wing, chordwise: int, state: np.ndarray | None = None) -> Panels:
    """The panels of `wing` with `chordwise` panels per strip, deformed by `state` (3N,): the
    structural unknowns (heave [m], slope [-], twist about the elastic axis [deg]) of
    `solver.model.layout`; default the jig."""
    n, k = wing.n_stations, chordwise
    z = np.zeros(3 * n) if state is None else np.asarray(state, dtype=float)[: 3 * n]
    layout = Layout(n, k)
    # The linear beam's lattice: a wing's in-plane stiffness (a lag layout's slot) moves none of
    # these panels.
    values = {
        name: value
        for name, value in layout.wing_values(wing).items()
        if name != "in_plane_bending_stiffness"
    }
    parameters = layout.pack(
        values | {"camber": wing.camber_at(chordwise_nodes(k)), "alpha": 0.0, "deformed_axis": 0.0}
    )
    left, right, collocation, normal, leading_edge = (
        np.array(value).T
        for value in _lattice_function(n, k)(z[:n], z[n : 2 * n], z[2 * n :], parameters)
    )
    strips = n - 1
    front_left, back_left = _walk_aft(leading_edge[:-1], left.reshape(strips, k, 3))
    front_right, back_right = _walk_aft(leading_edge[1:], right.reshape(strips, k, 3))
    area = 0.5 * np.cross(front_right - back_left, front_left - back_right)  # (S, k, 3)
    centre = (front_left + back_left + front_right + back_right) / 4
    aft = (3 * (front_left + front_right) + 5 * (back_left + back_right)) / 16
    m = strips * k
    points = np.concatenate([centre.reshape(m, 3), aft.reshape(m, 3)])
    areas = np.concatenate([area.reshape(m, 3), 0.75 * area.reshape(m, 3)])
    ahead = np.kron(np.eye(strips), np.tril(np.ones((k, k)), -1))
    potential = np.concatenate([ahead, np.eye(m)])
    return Panels(
        left=left,
        right=right,
        collocation=collocation,
        normal=normal,
        strip=np.repeat(np.arange(strips), k),
        chordwise=k,
        shed_left=back_left[:, -1],
        shed_right=back_right[:, -1],
        patch_point=points,
        patch_area=areas,
        patch_potential=potential,
    )


@functools.lru_cache(maxsize=16)
def _lattice_function(n: int, k: int) -> ca.Function:
    """The static model's lattice (`solver.model.geometry.lattice`) of N stations and k
    chordwise panels as a function of numbers: (heave, slope, twist (N each), the model's
    parameter vector (`solver.model.layout`, its slots by name)) -> (left, right, collocation,
    normal (3, M), leading_edge (3, N))."""
    layout = Layout(n, k)
    heave, slope, phi = (ca.SX.sym(name, n) for name in ("u", "du", "phi"))
    p = ca.SX.sym("p", layout.n_parameters)
    grid = lattice(heave, slope, phi, layout.unpack(p), k)
    outputs = [grid.left, grid.right, grid.collocation, grid.normal, grid.leading_edge]
    return ca.Function("unsteady_lattice_panels", [heave, slope, phi, p], outputs)


def _walk_aft(edge: np.ndarray, bound: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(S, k, 3) each: the front and back corners of each strip's panels along one of its
    edges, from the edge's leading edge (S, 3) and bound-vortex vertices (S, k, 3): a vertex is
    0.75 front + 0.25 back, and each panel's back corner is the next one's front."""
    front = np.empty_like(bound)
    back = np.empty_like(bound)
    corner = edge
    for j in range(bound.shape[1]):
        front[:, j] = corner
        corner = 4 * bound[:, j] - 3 * corner
        back[:, j] = corner
    return front, back
