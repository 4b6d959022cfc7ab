"""Divergence of swept wings: flexwing's lattice against classical strip theory.

    python benchmarks/swept_divergence_benchmark.py

The classical result (Bisplinghoff, Ashley and Halfman, section 7-3; Hodges and Pierce, chapter
4): on a swept wing an upward bending slope w' changes the streamwise incidence by -w' sin(sweep),
so aft sweep couples bending into wash-out and raises the divergence pressure, until a few degrees
of sweep (depending on EI/GJ) remove divergence altogether; forward sweep lowers it. Strip theory
here is the textbook model written on flexwing's kinematics: a uniform cantilever along the
elastic axis (length l = semispan / cos(sweep)), streamwise incidence a_s = theta cos(sweep) - w'
sin(sweep), lift per unit length q c a a_s cos(sweep) with a = 2 pi, acting e = (x_ea - 1/4) c
ahead of the axis (e cos(sweep) normal to it). With the cantilever's Green's functions
(torsion min(s, sigma)/GJ; bending slope s (2 sigma - s) / 2EI for s < sigma, sigma^2 / 2EI
beyond) the incidence obeys a_s = q K a_s + forcing, and q_D = 1 / (largest positive real
eigenvalue of K).

flexwing's number is the linear divergence pressure of its lattice (`solver.
linear_divergence_pressure`) for the same wing: a high-aspect-ratio rectangle (semispan 10 m,
chord 1 m, elastic axis 40 % chord), uniform EI and GJ normal to the axis. Both are printed as
ratios to their unswept values (the lattice's 3D lift slope is below 2 pi, so the absolute values
differ by ~10 % at this aspect ratio; the trend is what the classical result is about).
"""

from __future__ import annotations

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import math

import numpy as np

import solver

SEMISPAN = 10.0  # [m]
CHORD = 1.0  # [m]
ELASTIC_AXIS = 0.4  # [-] of the chord
LIFT_SLOPE = 2 * math.pi  # [1/rad] strip theory's section lift slope
SWEEPS = [-30.0, -20.0, -10.0, -5.0, 0.0, 2.5, 5.0, 7.5, 10.0, 15.0, 20.0]
STIFFNESS = [(2e5, 2e4), (2e6, 2e4)]  # (EI, GJ) [N m^2]: EI/GJ = 10 and 100


def strip_theory_pressure(
    sweep_deg: float, ei: float, gj: float, points: int = 400
) -> float | None:
    """[Pa] divergence pressure of the uniform swept strip-theory wing, or None (no divergence)."""
    sweep = math.radians(sweep_deg)
    length = SEMISPAN / math.cos(sweep)
    ds = length / points
    s = (np.arange(points) + 0.5) * ds  # midpoint collocation along the axis
    sigma = s[None, :]
    at = s[:, None]
    torsion = np.minimum(at, sigma) / gj
    slope = np.where(at < sigma, at * (2 * sigma - at), sigma**2) / (2 * ei)
    lever = (ELASTIC_AXIS - 0.25) * CHORD * math.cos(sweep)  # [m] normal to the axis
    lift_per_incidence = CHORD * LIFT_SLOPE * math.cos(sweep)  # [m] per unit q and unit s
    kernel = (
        math.cos(sweep) * torsion * lever * lift_per_incidence
        - math.sin(sweep) * slope * lift_per_incidence
    ) * ds
    eigenvalues = np.linalg.eigvals(kernel)
    real = eigenvalues[
        (np.abs(eigenvalues.imag) < 1e-9 * np.abs(eigenvalues).max())
        & (eigenvalues.real > 1e-12 * np.abs(eigenvalues).max())
    ].real
    return None if real.size == 0 else float(1.0 / real.max())


def lattice_pressure(sweep_deg: float, ei: float, gj: float) -> float | None:
    wing = solver.Wing.create(
        np.linspace(0, SEMISPAN, 40), CHORD, ELASTIC_AXIS, ei, gj, sweep=sweep_deg
    )
    return solver.linear_divergence_pressure(wing)


def _ratio(value: float | None, base: float) -> str:
    if value is None:
        return "     none"
    ratio = value / base
    return f"{ratio:9.3f}" if ratio < 1e3 else "   >1000"


def main() -> None:
    for ei, gj in STIFFNESS:
        print(
            f"\nrectangular wing, semispan {SEMISPAN:g} m, chord {CHORD:g} m, EI {ei:g}, GJ {gj:g}"
        )
        strip0, lattice0 = strip_theory_pressure(0.0, ei, gj), lattice_pressure(0.0, ei, gj)
        assert strip0 is not None and lattice0 is not None
        print(f"unswept q_D: strip theory {strip0:.1f} Pa, flexwing's lattice {lattice0:.1f} Pa")
        print(f"{'sweep [deg]':>12} {'strip q_D/q_D0':>15} {'lattice q_D/q_D0':>17}")
        for sweep in SWEEPS:
            strip = strip_theory_pressure(sweep, ei, gj)
            lattice = lattice_pressure(sweep, ei, gj)
            print(f"{sweep:12.1f} {_ratio(strip, strip0):>15} {_ratio(lattice, lattice0):>17}")


if __name__ == "__main__":
    main()
