"""The circulation of harmonic motion: flow tangency on the static lattice with the wake of
`solver.unsteady_lattice.wake`.

At each collocation point the normal velocity of the air relative to the panel vanishes. Per
unit airspeed, with g = Gamma / V the panels' circulations (the static model's unknowns), D the
static influence matrix (the tangency rows' derivative in g, `solver.model.residual`), S the
strips' sums (`Panels.strip_sum`) and e the normalwash of whatever moves the flow (a deformation,
its rate, a gust):

    (D + W(kappa) S) g = -e.

At kappa = 0, W = 0: g = -D^{-1} e is the static model's circulation, exactly (its tangency
rows' linearisation). A gust w_g e^{i omega (t - x / V)} (the air moving up, meeting each point
x of the wing x / V later than x = 0) brings the normalwash e_p = (w_g / V) n_z,p e^{-i kappa
x_p}, each panel at its own collocation point's delay.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg

from solver.unsteady_lattice.panels import Panels
from solver.unsteady_lattice.wake import ShedWake

__all__ = ["HarmonicLattice", "gust_normalwash", "harmonic_lattice"]


@dataclass(frozen=True, eq=False)
class HarmonicLattice:
    """The lattice's circulation at each of K values kappa = omega / V [1/m] (np.inf: the
    infinite-frequency limit): the factors of D + W(kappa) S."""

    kappa: np.ndarray
    factors: tuple[tuple[np.ndarray, np.ndarray], ...]

    def circulation(self, index: int, normalwash: np.ndarray) -> np.ndarray:
        """(M, ...) complex [m] g at `kappa[index]` of the normalwash (M, ...) [-] per unit V
        (flow tangency: (D + W S) g = -e)."""
        return -scipy.linalg.lu_solve(self.factors[index], normalwash.astype(complex))


def harmonic_lattice(influence: np.ndarray, wake: ShedWake) -> HarmonicLattice:
    """The circulation problem of the panels whose static influence matrix is `influence` (M,
    M) [1/m] (the tangency rows' derivative in g at the state) with `wake`, at each of its
    kappa."""
    factors = tuple(scipy.linalg.lu_factor(influence + shed) for shed in wake.influence)
    return HarmonicLattice(wake.kappa, factors)


def gust_normalwash(panels: Panels, kappa: float) -> np.ndarray:
    """(M,) complex [-]: the normalwash of a unit vertical gust angle w_g / V (module
    docstring), phase zero where the gust meets x = 0 (the elastic axis at the root)."""
    x = panels.collocation[:, 0]
    phase = np.exp(-1j * kappa * x) if np.isfinite(kappa) else np.zeros(x.shape)
    return panels.normal[:, 2] * phase
