"""IPOPT on a design problem's reduced functions: the objective and constraints of a design
vector, with their exact gradients, handed to IPOPT as CasADi callbacks (a limited-memory
Hessian: no second derivatives are formed).

What the functions are is the caller's (`Problem`: the single-point problem's in
`solver.optimization.optimize`, the multipoint one's in `solver.optimization.multipoint`); here
only how IPOPT sees them and how it is run.
"""

from __future__ import annotations

import math
import time
from typing import Any, Protocol

import casadi as ca
import numpy as np

from solver.results.design import OptimizerInfo

__all__ = ["MAX_ITERATIONS", "Problem", "run_ipopt", "stopped_by_a_limit", "succeeded"]

# IPOPT's iteration limit: the problems of the study converge in 20-110 iterations (measured).
MAX_ITERATIONS = 500


class Problem(Protocol):
    """What IPOPT asks of a design problem, in its scaled variables (`variable_scale`)."""

    size: int  # how many constraint values
    variable_scale: np.ndarray  # (nv,) physical design = scaled * variable_scale

    def point(self, scaled: np.ndarray) -> Any | None:
        """The design's evaluation (None: no equilibrium there; IPOPT steps back)."""

    def objective(self, point: Any) -> float: ...

    def objective_gradient(self, point: Any) -> np.ndarray: ...

    def values(self, point: Any) -> np.ndarray: ...

    def jacobian(self, point: Any) -> np.ndarray: ...


class _Functions(ca.Callback):
    """v -> (objective, constraints) for IPOPT, from a `Problem`."""

    def __init__(self, n_design: int, constraints: Problem) -> None:
        ca.Callback.__init__(self)
        self.n_design, self.constraints = n_design, constraints
        self.jacobian_callback: _Jacobian | None = None
        self.construct("flexwing_design", {})

    def get_n_in(self) -> int:
        return 1

    def get_n_out(self) -> int:
        return 2

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(self.n_design, 1)

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        return ca.Sparsity.dense(1, 1) if i == 0 else ca.Sparsity.dense(self.constraints.size, 1)

    def eval(self, arg: Any) -> list[Any]:  # type: ignore[override]
        point = self.constraints.point(np.array(arg[0]).ravel())
        if point is None:
            return [ca.DM(math.nan), ca.DM.nan(self.constraints.size, 1)]
        return [ca.DM(self.constraints.objective(point)), ca.DM(self.constraints.values(point))]

    def has_jacobian(self) -> bool:
        return True

    def get_jacobian(self, name: str, inames: Any, onames: Any, opts: Any) -> ca.Function:
        self.jacobian_callback = _Jacobian(name, self.n_design, self.constraints, opts)
        return self.jacobian_callback


class _Jacobian(ca.Callback):
    def __init__(self, name: str, n_design: int, constraints: Problem, opts: Any) -> None:
        ca.Callback.__init__(self)
        self.n_design, self.constraints = n_design, constraints
        self.construct(name, opts)

    def get_n_in(self) -> int:
        return 3

    def get_n_out(self) -> int:
        return 2

    def get_sparsity_in(self, i: int) -> ca.Sparsity:
        sizes = (self.n_design, 1, self.constraints.size)
        return ca.Sparsity.dense(sizes[i], 1)

    def get_sparsity_out(self, i: int) -> ca.Sparsity:
        rows = 1 if i == 0 else self.constraints.size
        return ca.Sparsity.dense(rows, self.n_design)

    def eval(self, arg: Any) -> list[Any]:  # type: ignore[override]
        point = self.constraints.point(np.array(arg[0]).ravel())
        nv = self.n_design
        if point is None:
            return [ca.DM.nan(1, nv), ca.DM.nan(self.constraints.size, nv)]
        return [
            ca.DM(self.constraints.objective_gradient(point)[None, :]),
            ca.DM(self.constraints.jacobian(point)),
        ]


def run_ipopt(
    constraints: Problem,
    start: np.ndarray,
    bounds: tuple[np.ndarray, np.ndarray],
    constraint_bounds: tuple[np.ndarray, np.ndarray],
    tolerance: float,
    history: int,
    evaluations: Any,
    update: str = "bfgs",
) -> tuple[np.ndarray, OptimizerInfo]:
    """IPOPT from `start` within `bounds` (each (nv,), physical units), the constraints within
    `constraint_bounds` (scaled as `constraints.values`), to `tolerance`, with an L-BFGS history
    of `history` pairs updated by `update` ("bfgs", or "sr1": its approximation may be
    indefinite, as a constrained problem's Lagrangian is). `evaluations()`: how many equilibria
    were solved (read at the end).
    Returns the last design (physical units) and what IPOPT did."""
    started = time.perf_counter()
    n_design = start.size
    functions = _Functions(n_design, constraints)
    v = ca.MX.sym("v", n_design)
    objective, g = functions(v)
    nlp = {"x": v, "f": objective, "g": g}
    options: dict[str, Any] = {
        "ipopt.hessian_approximation": "limited-memory",
        "ipopt.limited_memory_max_history": history,
        "ipopt.limited_memory_update_type": update,
        "ipopt.tol": tolerance,
        "ipopt.constr_viol_tol": tolerance,
        "ipopt.max_iter": MAX_ITERATIONS,
        # Stop three iterations after the error is below 1e-8 (default: fifteen below 1e-6):
        # the optimum then holds to ~1e-9 in drag and ~1e-7 deg in twist.
        "ipopt.acceptable_tol": 1e-8,
        "ipopt.acceptable_iter": 3,
        "ipopt.print_level": 0,
        "ipopt.sb": "yes",
        "print_time": False,
        "show_eval_warnings": False,  # a design without equilibrium: a NaN IPOPT steps back from
    }
    ipopt = ca.nlpsol("flexwing_design", "ipopt", nlp, options)  # type: ignore[arg-type]
    lbg, ubg = constraint_bounds
    scale = constraints.variable_scale
    lower_v, upper_v = bounds
    result = ipopt(x0=start / scale, lbx=lower_v / scale, ubx=upper_v / scale, lbg=lbg, ubg=ubg)
    stats = ipopt.stats()
    info = OptimizerInfo(
        iterations=int(stats.get("iter_count", 0)),
        evaluations=int(evaluations()),
        status=str(stats.get("return_status", "unknown")),
        seconds=time.perf_counter() - started,
    )
    return np.array(result["x"]).ravel() * scale, info


def succeeded(info: OptimizerInfo) -> bool:
    """IPOPT met its optimality test (to its tolerance, or to its acceptable one)."""
    return info.status.startswith("Solve_Succeeded") or "Acceptable" in info.status


def stopped_by_a_limit(info: OptimizerInfo) -> bool:
    """IPOPT stopped at its iteration (or time) limit: the last design is not judged."""
    return info.status.startswith("Maximum_")
