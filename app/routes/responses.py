"""OpenAPI descriptions of the error responses the routes can return (all problem+json)."""

from __future__ import annotations

from typing import Any

from app.problems import ProblemDetails

__all__ = [
    "CONTROLS_ERRORS",
    "FLUTTER_ERRORS",
    "OPTIMIZE_ERRORS",
    "ROLL_ERRORS",
    "SOLVE_ERRORS",
    "SWEEP_ERRORS",
]


def _problem(description: str) -> dict[str, Any]:
    return {"model": ProblemDetails, "description": description}


SOLVE_ERRORS: dict[int | str, dict[str, Any]] = {
    413: _problem("Request body too large (/problems/body-too-large)."),
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field), no equilibrium "
        "(/problems/no-equilibrium, with `fold_velocity`) or no convergence "
        "(/problems/not-converged)."
    ),
    503: _problem(
        "Overloaded, not ready, or the worker died (/problems/overloaded, /problems/not-ready, "
        "/problems/worker-lost); see Retry-After."
    ),
    504: _problem("The solve exceeded its time budget (/problems/solve-timeout)."),
}

SWEEP_ERRORS: dict[int | str, dict[str, Any]] = SOLVE_ERRORS | {
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field). A speed without "
        "an equilibrium is answered in its point (`status`, `no_equilibrium`), never with a 422."
    ),
    504: _problem("The sweep exceeded its time budget (/problems/solve-timeout)."),
}

OPTIMIZE_ERRORS: dict[int | str, dict[str, Any]] = SOLVE_ERRORS | {
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field), no feasible "
        "optimum (/problems/infeasible-design, `constraint` names which), no equilibrium or no "
        "convergence of the optimal wing (/problems/no-equilibrium, /problems/not-converged)."
    ),
    504: _problem("The optimisation exceeded its time budget (/problems/solve-timeout)."),
}

FLUTTER_ERRORS: dict[int | str, dict[str, Any]] = SOLVE_ERRORS | {
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field: `wing.mass` "
        "without a mass model), or a root that could not be followed (/problems/not-converged). "
        "Airspeeds past a loaded wing's equilibria are answered in their points "
        "(`status` no_equilibrium), never with a 422."
    ),
    504: _problem("The analysis exceeded its time budget (/problems/solve-timeout)."),
}

ROLL_ERRORS: dict[int | str, dict[str, Any]] = SOLVE_ERRORS | {
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field: a wing without "
        "control surfaces, `method` antisymmetric where the response is not exactly "
        "antisymmetric, `free_roll` of a wing without roll damping), no equilibrium (past the "
        "symmetric or the antisymmetric divergence: /problems/no-equilibrium) or no convergence "
        "(/problems/not-converged)."
    ),
}

CONTROLS_ERRORS: dict[int | str, dict[str, Any]] = SOLVE_ERRORS | {
    422: _problem(
        "Invalid input (/problems/invalid-input, `errors` names each bad field: a wing without "
        "control surfaces). A speed without an equilibrium is answered in its point (`status`, "
        "`no_equilibrium`), never with a 422."
    ),
    504: _problem("The sweep exceeded its time budget (/problems/solve-timeout)."),
}
