"""flexwing's numerical core: static aeroelastic equilibrium of a flexible wing.

A vortex lattice (one chordwise panel per strip) and a cantilever beam share the heave and twist
unknowns; the coupled equations are solved as one nonlinear system by Newton's method on an exact
CasADi Jacobian, compiled once per mesh size. See the design study in shared/seed/.
"""

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
