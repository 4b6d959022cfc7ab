"""The indicial functions of unsteady thin-airfoil theory as exponential sums, and their
state-space realisations (aerodynamic states).

Distance travelled in semichords s = V t / b. A section whose three-quarter-chord upwash
steps by one (Wagner's problem) builds its circulatory lift as Wagner's function phi(s); a
section flying into a sharp-edged gust builds it as Kuessner's function psi(s) (the gust's
front at the leading edge at s = 0). Their classical approximations:

- Wagner, R. T. Jones (NACA Report 681, 1940, eq. 12; Bisplinghoff, Ashley and Halfman,
  Aeroelasticity, 1955, eq. 5-333; Fung, An Introduction to the Theory of Aeroelasticity,
  section 6.8): phi(s) = 1 - 0.165 e^{-0.0455 s} - 0.335 e^{-0.300 s}, phi(0) = 1/2.
- Kuessner, Sears and Sparks (J. Aeronaut. Sci. 8, 1941, p. 64; Fung section 6.9;
  Bisplinghoff et al. eq. 5-339): psi(s) = 1 - 0.500 e^{-0.130 s} - 0.500 e^{-1.000 s},
  psi(0) = 0.

A function f(s) = 1 - sum_i A_i e^{-b_i s} is the step response of the filter

    x_i' = -(b_i V / b) x_i + u,   y = (1 - sum A_i) u + sum_i A_i (b_i V / b) x_i,

two states per filtered signal, and its transfer function is
F(p) = 1 - sum_i A_i p / (p + b_i V / b) (p the Laplace variable [1/s]); at p = i omega
Wagner's is R. T. Jones' approximation of Theodorsen's C(k) and Kuessner's of Sears' function
(without its phase of the gust's arrival at mid-chord: here the gust is timed at the leading
edge), tested against both (`tests/solver/gusts/test_indicial.py`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["KUESSNER", "WAGNER", "Indicial"]


@dataclass(frozen=True)
class Indicial:
    """f(s) = 1 - sum_i amplitude_i exp(-rate_i s), s in semichords travelled."""

    name: str
    amplitude: tuple[float, ...]
    rate: tuple[float, ...]  # per semichord

    @property
    def direct(self) -> float:
        """f(0) [-]: the share of a step felt at once."""
        return 1.0 - sum(self.amplitude)

    def __call__(self, s: np.ndarray | float) -> np.ndarray:
        """f(s) [-] at distances s >= 0 [semichords]."""
        s = np.asarray(s, dtype=float)
        value = np.ones_like(s)
        for a, b in zip(self.amplitude, self.rate, strict=True):
            value = value - a * np.exp(-b * s)
        return value

    def poles(self, velocity: float, semichord: np.ndarray) -> np.ndarray:
        """(len(semichord), terms) [1/s] the decay rates b_i V / b of each section."""
        return np.outer(velocity / np.asarray(semichord, dtype=float), self.rate)

    def output_weights(self, velocity: float, semichord: np.ndarray) -> np.ndarray:
        """(len(semichord), terms) [1/s]: y = direct u + sum_i weight_i x_i."""
        return self.poles(velocity, semichord) * np.asarray(self.amplitude)

    def transfer(self, p: np.ndarray, velocity: float, semichord: float) -> np.ndarray:
        """F(p) [-] at Laplace variables p [1/s] for a section of `semichord` [m]."""
        p = np.asarray(p, dtype=complex)
        value = np.ones_like(p)
        for a, b in zip(self.amplitude, self.rate, strict=True):
            value = value - a * p / (p + b * velocity / semichord)
        return value


WAGNER = Indicial("Wagner (R. T. Jones)", (0.165, 0.335), (0.0455, 0.300))
KUESSNER = Indicial("Kuessner (Sears and Sparks)", (0.500, 0.500), (0.130, 1.000))
