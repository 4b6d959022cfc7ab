"""Static aeroelastic stability from the residual's affine structure in q.

With loads proportional to the dynamic pressure q, the Jacobian at a state x is
J(x, q) = J0(x) + q J1(x). The local divergence pressure at x is the smallest positive real
lambda for which J0 + lambda J1 is singular,

    J0 v = -lambda J1 v,

and an equilibrium at q is statically stable when lambda > q (the margin q / lambda is below 1).
J1 is non-zero only in the m load rows (bending and torsion: the loads enter nowhere else), so
with E selecting those rows (J1 = E K) the non-zero eigenvalues mu = 1/lambda of -J0^{-1} J1 are
those of the m x m matrix G = -K J0^{-1} E.

G is built block by block. The unknowns split into the structure's (heave, slope, twist) and the
circulations, the equations into the structure's (clamps, kinematics, bending, torsion) and flow
tangency; in J0 the structure's equations do not involve the circulations, so

    J0 = [[A, 0], [T_s, T_g]],   G = -(K_s - K_g T_g^{-1} T_s) A^{-1} E_s,

where A (the clamped beam, a function of the mesh alone) gives the beam's response
P = A^{-1} E_s once per wing, and each verdict needs only the small tangency block T_g (the
lattice's influence matrix) factorised: 3-5 times fewer operations than with all of J0.

The eigenvalue that matters is the largest positive real mu. For a wing that can diverge it is
almost always also the largest in modulus, which power iteration on G finds in a few dozen cheap
products; the full nonsymmetric eigenvalue solve runs only when power iteration cannot vouch for
its answer (the dominant eigenvalue is negative, complex, or not separated from the next one).

Meaningfully positive: mu must exceed `NEGLIGIBLE` times ||G|| (Frobenius). 1 / ||G|| is the
dynamic pressure at which the loads become comparable to the wing's stiffness in its most
compliant coupling (usually bending); a divergence pressure more than 1e9 times beyond it is
round-off (a wing whose elastic axis lies exactly on its quarter chord has every mu at ~1e-30),
and is reported as none, never as 1e29 Pa or infinity.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from solver.model.layout import Layout
from solver.numerics.evaluation import Evaluation

__all__ = ["NEGLIGIBLE", "beam_response", "divergence_pressure", "reversal_pressure"]

NEGLIGIBLE = 1e-9
# An eigenvalue counts as real when its imaginary part is this small relative to ||G||.
_REAL_TOLERANCE = 1e-8
_PRODUCTS_PER_CHECK = 4
_POWER_CHECKS = 16  # up to 64 products with G
# Power iteration is trusted once its eigen-residual is this small relative to ||G||.
_POWER_RESIDUAL = 1e-11


def beam_response(evaluation: Evaluation, layout: Layout) -> np.ndarray:
    """P = A^{-1} E_s (n_structure, m): the clamped beam's deformation per unit load-row
    residual. A is the same at every state and airspeed: compute it once per wing."""
    a = evaluation.jacobian0[layout.structure_rows, layout.structure]
    rows = layout.load_rows - (layout.structure_rows.start or 0)
    selector = np.zeros((a.shape[0], rows.size))
    selector[rows, np.arange(rows.size)] = 1.0
    return np.linalg.solve(a, selector)


def divergence_pressure(
    evaluation: Evaluation, layout: Layout, beam: np.ndarray | None = None
) -> float | None:
    """Smallest positive real lambda [Pa] with J0 + lambda J1 singular, or None if there is none.

    `beam`: `beam_response` of this wing (computed here when not given).
    """
    j0, j1 = evaluation.jacobian0, evaluation.jacobian1
    return _smallest_pressure(
        j0, j1, layout, layout.circulation, layout.tangency_rows, beam, evaluation
    )


def reversal_pressure(
    evaluation: Evaluation,
    layout: Layout,
    control0: np.ndarray,
    control1: np.ndarray,
    measure_x: np.ndarray,
    measure_control: float,
    beam: np.ndarray | None = None,
) -> float | None:
    """Smallest positive real q [Pa] at which a control's elastic derivative vanishes (control
    reversal), or None if there is none.

    The elastic derivative of a measure m (lift, rolling moment) per unit q is
    D(q) = m_c + m_x . dx with (J0 + q J1) dx = -(c0 + q c1): c0, c1 (n,) the control's
    columns of r0 and r1 (`solver.numerics.evaluation.ControlTerms`), m_x (n,) and m_c its gradient
    and its own derivative. The bordered matrix [[J0 + q J1, c0 + q c1], [m_x, m_c]] has
    determinant det(J) D(q), so reversal is where it is singular: the generalised eigenvalue
    problem of divergence with the control's column and the measure's row added. c0 lives in
    the tangency rows and c1 in the load rows (the camber moves the lattice only), so the
    border joins the circulations' block and the eigenproblem keeps its size.
    """
    n = layout.n_unknowns
    j0, j1 = np.zeros((n + 1, n + 1)), np.zeros((n + 1, n + 1))
    j0[:n, :n], j0[:n, n], j0[n, :n], j0[n, n] = (
        evaluation.jacobian0,
        control0,
        measure_x,
        measure_control,
    )
    j1[:n, :n], j1[:n, n] = evaluation.jacobian1, control1
    if np.any(control0[layout.structure_rows]) or np.any(np.delete(control1, layout.load_rows)):
        raise ValueError("a control column must leave the beam's equations alone")
    free = np.r_[np.arange(layout.circulation.start, layout.circulation.stop), n]
    free_rows = np.r_[np.arange(layout.tangency_rows.start, layout.tangency_rows.stop), n]
    return _smallest_pressure(j0, j1, layout, free, free_rows, beam, evaluation)


def _smallest_pressure(
    j0: np.ndarray,
    j1: np.ndarray,
    layout: Layout,
    free: np.ndarray | slice,
    free_rows: np.ndarray | slice,
    beam: np.ndarray | None,
    evaluation: Evaluation,
) -> float | None:
    """Smallest positive real lambda with j0 + lambda j1 singular, where j1 lives in the load
    rows and j0's beam rows touch only the structure's unknowns: the structure's block is
    reduced away (module docstring), `free` and `free_rows` the other unknowns and equations
    (the circulations and tangency, slices; a border's too, index arrays)."""
    structure = layout.structure
    try:
        if beam is None:
            beam = beam_response(evaluation, layout)
        block = (
            j0[free_rows, free]
            if isinstance(free, slice) and isinstance(free_rows, slice)
            else j0[np.ix_(np.asarray(free_rows), np.asarray(free))]
        )
        # F^{-1} F_s: how the free unknowns answer a deformation.
        response = np.linalg.solve(block, j0[free_rows, structure])
    except np.linalg.LinAlgError:
        return None
    loads = j1[layout.load_rows]
    coupling = loads[:, structure] - loads[:, free] @ response
    g = -coupling @ beam
    scale = float(np.linalg.norm(g))
    if not math.isfinite(scale) or scale == 0.0:
        return None
    mu = _dominant_positive_eigenvalue(g, scale)
    if mu is None:
        mu = _largest_positive_real_eigenvalue(g, scale)
    if mu is None or mu <= NEGLIGIBLE * scale:
        return None
    return 1.0 / mu


def _dominant_positive_eigenvalue(g: np.ndarray, scale: float) -> float | None:
    """The eigenvalue of largest modulus by power iteration, if it is real, positive and
    converged; None when power iteration cannot tell (then the full solve decides).

    The iteration runs on H = G / ||G|| (||H|| = 1: its products cannot overflow), renormalises
    and vouches for its iterate (Rayleigh quotient and eigen-residual) only every
    `_PRODUCTS_PER_CHECK` products: the products are cheap, the checks are not. An iterate that
    vanishes (all of G's eigenvalues negligible) leaves the verdict to the full solve.
    """
    h = g / scale
    vector = _start_vector(g.shape[0])
    image = h @ vector
    for _ in range(_POWER_CHECKS):
        mu = float(vector @ image)  # Rayleigh quotient (vector has unit length)
        if _length(image - mu * vector) <= _POWER_RESIDUAL:
            return mu * scale if mu > 0 else None
        for _ in range(_PRODUCTS_PER_CHECK - 1):
            image = h @ image
        norm = _length(image)
        if norm == 0.0 or not math.isfinite(norm):
            return None
        vector = image / norm
        image = h @ vector
    return None


def _length(vector: np.ndarray) -> float:
    """Euclidean norm, the same number as np.linalg.norm without its per-call overhead (the
    power iteration calls it twice per check)."""
    return math.sqrt(float(vector @ vector))


@functools.lru_cache(maxsize=64)
def _start_vector(m: int) -> np.ndarray:
    """A fixed pseudo-random unit vector: deterministic, and almost surely not orthogonal to the
    dominant eigenvector (as a symmetric start such as all-ones could be)."""
    vector = np.random.default_rng(1).standard_normal(m)
    vector /= np.linalg.norm(vector)
    vector.setflags(write=False)
    return vector


def _largest_positive_real_eigenvalue(g: np.ndarray, scale: float) -> float | None:
    try:
        mu = np.linalg.eigvals(g)
    except np.linalg.LinAlgError:
        return None
    real_positive = mu[(np.abs(mu.imag) <= _REAL_TOLERANCE * scale) & (mu.real > 0)].real
    return float(np.max(real_positive)) if real_positive.size else None
