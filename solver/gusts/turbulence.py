"""Continuous turbulence in the frequency domain (CS-25.341(b)): each output's transfer
function from the same state-space model, H(i omega) = C (i omega - A)^{-1} B g(omega) + D
g(omega), g_j = K_j(i omega) e^{-i omega tau_j} / V each strip's Kuessner-lagged gust angle
per unit gust velocity (Sears and Sparks' approximation of Sears' function, the gust timed at
the strip's leading edge), and

    A-bar^2 = integral_0^inf |H(i omega)|^2 Phi(omega) d omega,

Phi the von Karman spectrum of unit intensity (`solver.gusts.profiles.von_karman`), by the
trapezoidal rule on a logarithmic grid from a thousandth of the slowest root to fifty times
the fastest mode (the spectrum falls as omega^(-5/3), the response as omega^(-2) past the
modes: what lies beyond is below 1e-4 of A-bar^2).
"""

from __future__ import annotations

import numpy as np

from solver.gusts.indicial import KUESSNER
from solver.gusts.model import GustModel
from solver.gusts.profiles import von_karman

__all__ = ["a_bar", "frequency_response"]

_POINTS = 1500


def frequency_response(model: GustModel, frequency: np.ndarray) -> np.ndarray:
    """(n_out, F) complex: the outputs per unit gust velocity [per m/s] at `frequency` (F,)
    [rad/s]."""
    p = 1j * np.asarray(frequency, dtype=float)
    lag = np.array([KUESSNER.transfer(p, model.velocity, b) for b in model.semichord])
    gust = lag * np.exp(-np.outer(model.delay, p)) / model.velocity  # (m, F)
    roots, vectors, inverse = model.eigen
    modal = (inverse @ model.b @ gust) / (p[None, :] - roots[:, None])
    return model.c @ vectors @ modal + model.d @ gust


def a_bar(model: GustModel) -> np.ndarray:
    """(n_out,) A-bar: each output's rms per unit rms gust velocity [per m/s]."""
    roots = model.eigen[0]
    slowest = max(float(np.abs(roots).min()), 1e-6)
    fastest = max(float(np.abs(roots).max()), float(model.frequencies.max()))
    omega = np.geomspace(1e-3 * slowest, 50 * fastest, _POINTS)
    response = frequency_response(model, omega)
    spectrum = von_karman(omega, model.velocity)
    return np.sqrt(np.trapezoid(np.abs(response) ** 2 * spectrum, omega, axis=1))
