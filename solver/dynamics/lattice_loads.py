"""The unsteady lattice's loads of small oscillations about a state of the static model, on the
structure's degrees of freedom (`solver.dynamics.modes.Structure`), and its generalised
aerodynamic forces at reduced frequencies, for modes and for a gust.

The steady part is the static model's own, from its exact Jacobian at the state (J0 + q J1 of
`solver.model.residual`), as in `solver.dynamics.unsteady`: T the tangency rows' derivative in
the structure's unknowns, K_s and K_g the load rows'. What harmonic motion w e^{st} (s = i
omega, kappa = omega / V) adds is the wake's lag and the potential's rate
(`solver.unsteady_lattice`):

    normalwash      e = (T + (s / V) N) w             N: minus each collocation point's
                                                      vertical displacement (its motion)
    circulation     g = -(D + W(kappa) S)^{-1} e      (`solver.unsteady_lattice.circulation`)
    loads           f = q (K_s w + (K_g + (s / V) P) g)

P the unsteady pressure rho dPhi/dt of `solver.unsteady_lattice.panels` per unit q and s / V
(2 times the patches' equivalent strip loads: rho s V Gamma = 2 q (s / V) g). At kappa = 0 the
loads are q (K_s - K_g D^{-1} T) w, the static model's aerodynamic stiffness exactly. Grouped
by powers of s / V, on a basis w = R c with the equations taken along L:

    L^T f = q [geometric + A0(kappa) + (s / V) A1(kappa) + (s / V)^2 A2(kappa)] c,

and, harmonic (s / V = i kappa = i k / b), the generalised aerodynamic forces Q(ik) = A0 +
i (k / b) A1 - (k / b)^2 A2 (+ geometric) per unit dynamic pressure, Nastran's Q_hh (MSC
Nastran Aeroelastic Analysis User's Guide, section 2.5).

Wake and patches are those of the unloaded jig: a loaded state moves them by its deflection,
a second-order change of the unsteady increments (as the doublet lattice's, computed on the
undeformed geometry); the steady part is the state's own.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.dynamics.modes import Structure
from solver.model.geometry import chordwise_nodes
from solver.model.layout import Layout
from solver.numerics.evaluation import Evaluation
from solver.unsteady_lattice.circulation import gust_normalwash, harmonic_lattice
from solver.unsteady_lattice.panels import Panels
from solver.unsteady_lattice.wake import ShedWake, shed_wake

__all__ = ["LatticeLoads", "ModalLoads", "lattice_loads"]


@dataclass(frozen=True)
class ModalLoads:
    """The loads on a basis at K values of kappa [1/m] (module docstring), each (K, r, r)
    complex per unit q; gust: (K, r) complex per unit q and unit gust angle w_g / V."""

    kappa: np.ndarray
    stiffness: np.ndarray  # A0
    damping: np.ndarray  # A1 [m]
    inertia: np.ndarray  # A2 [m^2]
    gust: np.ndarray


@dataclass(frozen=True, eq=False)
class LatticeLoads:
    """The operators of the module docstring about one state, on n = 2 (N - 1) degrees of
    freedom and M panels: geometric (n, n) K_s Z; circulation_loads (n, M) K_g; pressure_loads
    (n, M) P; deformation (M, n) T Z; motion (M, n) N Z; influence (M, M) D; panels: the
    jig's (wake and patches)."""

    geometric: np.ndarray
    circulation_loads: np.ndarray
    pressure_loads: np.ndarray
    deformation: np.ndarray
    motion: np.ndarray
    influence: np.ndarray
    panels: Panels

    def stiffness(self) -> np.ndarray:
        """(n, n) per unit q: the zero-frequency loads of w, the static model's aerodynamic
        stiffness."""
        return self.geometric - self.circulation_loads @ np.linalg.solve(
            self.influence, self.deformation
        )

    def wake(self, kappa: np.ndarray) -> ShedWake:
        """The jig's wake at each `kappa` [1/m] (np.inf: the infinite-frequency limit)."""
        return shed_wake(self.panels, kappa)

    def modal(
        self, wake: ShedWake, right: np.ndarray, left: np.ndarray | None = None
    ) -> ModalLoads:
        """The loads on the basis `right` (n, r), along `left` (n, r) (default: the loads
        themselves, n rows), at each kappa of `wake` (`wake`)."""
        flow = harmonic_lattice(self.influence, wake)
        deformation, motion = self.deformation @ right, self.motion @ right
        rows = (lambda loads: loads) if left is None else (lambda loads: left.T @ loads)
        circulation, pressure = rows(self.circulation_loads), rows(self.pressure_loads)
        count = wake.kappa.shape[0]
        shape = (count, circulation.shape[0], right.shape[1])
        a0, a1, a2 = (np.zeros(shape, dtype=complex) for _ in range(3))
        gust = np.zeros(shape[:2], dtype=complex)
        r = right.shape[1]
        for i, value in enumerate(flow.kappa):
            # One solve for the deformation's, the motion's and the gust's normalwash.
            gust_wash = gust_normalwash(self.panels, value)[:, None]
            g = flow.circulation(i, np.hstack([deformation, motion, gust_wash]))
            g_deformation, g_motion, g_gust = g[:, :r], g[:, r : 2 * r], g[:, 2 * r]
            a0[i] = circulation @ g_deformation
            a1[i] = circulation @ g_motion + pressure @ g_deformation
            a2[i] = pressure @ g_motion
            rate = 1j * value if np.isfinite(value) else 0.0
            gust[i] = (circulation + rate * pressure) @ g_gust
        return ModalLoads(flow.kappa, a0, a1, a2, gust)


def lattice_loads(
    structure: Structure, layout: Layout, evaluation: Evaluation, panels: Panels
) -> LatticeLoads:
    """The unsteady lattice's operators about the state whose exact Jacobians `evaluation`
    holds (J0, J1 of the static lattice on `layout`), with the jig's `panels`."""
    z_of_w = structure.states  # (3N, n); (5N, n) with lag
    j0, j1 = evaluation.jacobian0, evaluation.jacobian1
    tangency, circulation = layout.tangency_rows, layout.circulation
    load_rows = j1[layout.load_rows]
    patches = structure.point_loads(
        panels.patch_point, panels.patch_area, np.concatenate([panels.strip, panels.strip])
    )
    return LatticeLoads(
        geometric=structure.strip_loads_of(load_rows[:, layout.structure] @ z_of_w),
        circulation_loads=structure.strip_loads_of(load_rows[:, circulation]),
        pressure_loads=2.0 * patches @ panels.patch_potential,
        deformation=j0[tangency, layout.structure] @ z_of_w,
        motion=_motion(structure, layout),
        influence=j0[tangency, circulation],
        panels=panels,
    )


def _motion(structure: Structure, layout: Layout) -> np.ndarray:
    """(M, n) N of the module docstring: minus the vertical displacement of each panel's
    collocation point (its strip's mean of its two stations' sections, at its chordwise place,
    turned about the elastic axis by the streamwise pitch) per unit w."""
    nodes = chordwise_nodes(layout.chordwise)
    place = nodes[:-1] + 0.75 * np.diff(nodes)  # (k,) chord fraction of the collocation points
    return -structure.strip_points_motion(place).reshape(layout.n_panels, -1)
