"""flexwing's numerical core: static aeroelastic equilibrium of a flexible wing.

A vortex lattice (one chordwise panel per strip) and a cantilever beam share the heave and twist
unknowns; the coupled equations are solved as one nonlinear system by Newton's method on an exact
CasADi Jacobian, compiled once per mesh size. See the design study in shared/seed/.

Importing the package before numpy sets OPENBLAS_NUM_THREADS=1 unless it is already set: the
solver's dense systems are small (119 x 119 at N = 30), and threaded OpenBLAS on a shared machine
makes them 100x slower (measured: 0.3 ms single-threaded, up to 460 ms threaded during a compile).
"""

import os

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from solver.divergence import (
    DivergenceSummary,
    FitDivergence,
    Fold,
    LinearDivergence,
    divergence_summary,
    find_fold,
    fit_divergence,
    linear_divergence,
)
from solver.equilibrium import (
    Equilibrium,
    SolverOptions,
    Stability,
    linear_divergence_pressure,
    solve,
)
from solver.errors import ConvergenceError, NoEquilibrium, SolverError
from solver.sweep import SweepPoint, SweepResult, sweep
from solver.wing import FlightCondition, InvalidInput, Wing

__all__ = [
    "ConvergenceError",
    "DivergenceSummary",
    "Equilibrium",
    "FitDivergence",
    "FlightCondition",
    "Fold",
    "InvalidInput",
    "LinearDivergence",
    "NoEquilibrium",
    "SolverError",
    "SolverOptions",
    "Stability",
    "SweepPoint",
    "SweepResult",
    "Wing",
    "divergence_summary",
    "find_fold",
    "fit_divergence",
    "linear_divergence",
    "linear_divergence_pressure",
    "solve",
    "sweep",
]
