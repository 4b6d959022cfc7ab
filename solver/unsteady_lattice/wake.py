"""The wake of harmonic motion: the normalwash at the panels of each strip's wake, shed at its
trailing edge and convected with the stream (frequency domain; Katz and Plotkin, Low-Speed
Aerodynamics, 2nd ed., chapter 13; Hall, AIAA J. 32(12), 1994).

A strip whose total bound circulation is Gamma e^{i omega t} sheds, by Kelvin's theorem, the
spanwise vorticity -(1/V) dGamma/dt, which then travels with the stream: at distance xi behind
the trailing edge the wake carries trailing legs of strength Gamma e^{i omega t - i kappa xi}
(kappa = omega / V) and spanwise vorticity -i kappa Gamma e^{i omega t - i kappa xi} per unit
length. As a superposition of horseshoes H(xi) (bound leg on the trailing edge moved xi aft,
trailing legs to infinity, the static model's shape, `solver.unsteady_lattice.vortices`) it is

    wake = H(0) + int_0^inf (d/dxi e^{-i kappa xi}) H(xi) dxi,

whose first term is the steady lattice's own (its horseshoes' trailing legs, already in the
static influence matrix). What harmonic motion adds is therefore

    W(kappa) = -i kappa int_0^inf e^{-i kappa xi} n . H(xi) dxi     per unit Gamma [1/m],

zero at kappa = 0 (so the unsteady lattice's steady limit is the static lattice exactly), and
-n . H(0) as kappa -> infinity (the shed vorticity cancels the trailing legs at once).

Quadrature: n . H(xi) is sampled on nodes from the trailing edge, geometrically spaced (the
first interval a twentieth of the nearest collocation point's distance, each next one
`_GROWTH` times longer) to `_LENGTH` spans aft; between nodes it is taken linear and the
oscillating factor integrated exactly (Filon's method), so the spacing need not resolve the
wavelength. Beyond the last node n . H falls as 1/xi^2 (a horseshoe seen from far ahead), whose
integral with the oscillating factor is an exponential integral: L E_2(i kappa L) times the
last sample.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.special

from solver.unsteady_lattice.panels import Panels
from solver.unsteady_lattice.vortices import symmetric_horseshoe_velocity

__all__ = ["ShedWake", "shed_wake", "wake_normalwash"]

# Each quadrature interval is this much longer than the one before it.
_GROWTH = 1.04
# The first interval: this fraction of the nearest collocation point's distance to a trailing
# edge (the samples vary on that scale there: a quarter of it left 6e-3 of the wake's 2D
# normalwash at kappa d = 1.25, a twentieth 3e-4; tests/solver/unsteady_lattice/test_wake.py).
_FIRST = 0.05
# The wake is sampled this many times the wing's full span (or chord, if longer) aft; beyond,
# its 1/xi^2 far field is integrated exactly.
_LENGTH = 40.0
# Below this kappa times an interval the Filon weights are taken from their Taylor series.
_SERIES = 0.05


@dataclass(frozen=True, eq=False)
class ShedWake:
    """W(kappa) S at K values of kappa [1/m]: the normalwash at each panel per unit circulation
    of each panel, through its strip's shed wake. kappa: (K,); influence: (K, M, M) [1/m]."""

    kappa: np.ndarray
    influence: np.ndarray


def shed_wake(panels: Panels, kappa: np.ndarray) -> ShedWake:
    """The wake's influence on the panels at each `kappa` [1/m] (np.inf: the infinite-frequency
    limit), per unit circulation of each panel (a strip sheds its panels' sum)."""
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    return ShedWake(kappa, wake_normalwash(panels, kappa) @ panels.strip_sum())


def wake_normalwash(panels: Panels, kappa: np.ndarray) -> np.ndarray:
    """(K, M, N - 1) complex [1/m]: W(kappa) of the module docstring at each of the K
    `kappa` = omega / V [1/m] (np.inf for the infinite-frequency limit): the normalwash at
    each panel's collocation point per unit total circulation of each strip."""
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    nodes = _nodes(panels)
    finite = np.isfinite(kappa)
    weights = np.zeros((nodes.size, int(finite.sum())), dtype=complex)
    for column, value in enumerate(kappa[finite]):
        weights[:, column] = _filon_weights(nodes, float(value))
    tail = np.array([_tail(float(value), nodes[-1]) for value in kappa[finite]], dtype=complex)
    m, s = panels.n_panels, panels.n_strips
    integral = np.zeros((m, s, int(finite.sum())), dtype=complex)
    first = np.zeros((m, s))
    for q, xi in enumerate(nodes):
        sample = _samples(panels, xi)  # (M, S)
        integral += sample[:, :, None] * weights[q]
        if q == 0:
            first = sample
        if q == nodes.size - 1:
            integral += sample[:, :, None] * tail
    result = np.empty((kappa.size, m, s), dtype=complex)
    result[finite] = np.moveaxis(-1j * kappa[finite] * integral, 2, 0)
    result[~finite] = -first
    return result


def _samples(panels: Panels, xi: float) -> np.ndarray:
    """(M, S) [1/m] n . H(xi): each strip's horseshoe moved xi aft, at each collocation point."""
    shift = np.array([xi, 0.0, 0.0])
    velocity = symmetric_horseshoe_velocity(
        panels.collocation[:, None, :],
        (panels.shed_left + shift)[None],
        (panels.shed_right + shift)[None],
    )
    return np.einsum("mc,msc->ms", panels.normal, velocity)


def _nodes(panels: Panels) -> np.ndarray:
    """(Q,) [m] the quadrature nodes from 0 (the trailing edge) aft."""
    # Each collocation point lies mid-strip: its own wake starts at its strip's mean trailing
    # edge (a swept strip's is oblique).
    trailing = ((panels.shed_left[:, 0] + panels.shed_right[:, 0]) / 2)[panels.strip]
    nearest = float(np.min(trailing - panels.collocation[:, 0]))
    span = float(np.ptp(np.concatenate([panels.shed_left[:, 1], panels.shed_right[:, 1]])))
    chord = float(np.max(trailing - panels.left[:, 0]))
    length = _LENGTH * max(2 * span, chord)
    step = _FIRST * max(nearest, 1e-6 * length)
    count = int(np.ceil(np.log1p(length * (_GROWTH - 1) / step) / np.log(_GROWTH)))
    # Interval j is step * growth^j long: node j sits at step (growth^j - 1) / (growth - 1).
    return step * np.expm1(np.arange(count + 1) * np.log(_GROWTH)) / (_GROWTH - 1)


def _filon_weights(nodes: np.ndarray, kappa: float) -> np.ndarray:
    """(Q,) complex [m]: int e^{-i kappa xi} h(xi) dxi = sum_q w_q h(xi_q) for h linear between
    the nodes (Filon's method: the exponential integrated exactly on each interval)."""
    start, width = nodes[:-1], np.diff(nodes)
    c = -1j * kappa * width
    series = np.abs(c) < _SERIES
    safe = np.where(series, 1.0, c)
    # I0 = int_0^1 e^{ct} dt, I1 = int_0^1 t e^{ct} dt
    i0 = np.where(series, 1 + c / 2 + c**2 / 6 + c**3 / 24 + c**4 / 120, np.expm1(safe) / safe)
    i1 = np.where(
        series,
        0.5 + c / 3 + c**2 / 8 + c**3 / 30 + c**4 / 144,
        (safe * np.exp(safe) - np.expm1(safe)) / safe**2,
    )
    scale = np.exp(-1j * kappa * start) * width
    weights = np.zeros(nodes.size, dtype=complex)
    weights[:-1] += scale * (i0 - i1)
    weights[1:] += scale * i1
    return weights


def _tail(kappa: float, length: float) -> complex:
    """[m] int_L^inf e^{-i kappa xi} (L / xi)^2 dxi = L E_2(i kappa L)."""
    if kappa == 0:
        return length
    z = 1j * kappa * length
    return complex(length * (np.exp(-z) - z * scipy.special.exp1(z)))
