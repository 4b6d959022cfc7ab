"""An OpenAeroStruct 2.12 model of a flexwing wing, for `openaerostruct_comparison.py`.

Dev-only: OpenAeroStruct (and OpenMDAO) are an independent reference, never a dependency of
flexwing. Set up as `shared/notes/extended-models.md` items 9-13 say:

- the mesh is built here, not by OAS's generator: the symmetric half is the LEFT half, tip first
  and root last (the clamp is on the last node), row 0 the leading edge, x aft, z up, one
  chordwise panel (2 rows). A swept wing is a sheared mesh: the elastic axis (EA) runs along
  x = |y| tan(sweep) and every section is streamwise, so the planform is flexwing's exactly;
- `fem_model_type "tube"` with `fem_origin` = the EA's chord fraction: the beam nodes sit on the
  EA and the beam elements run along it (swept); a uniform tube whose E and G are chosen so that
  E I = EI and G J = GJ exactly, with I = pi (R^4 - (R - t)^4) / 4 and J = 2 I as OAS computes them
  (the section normal to the beam, as flexwing's EI and GJ);
- aerodynamic loads only: CL0 = CD0 = 0, no viscous or wave drag, no structural weight relief,
  no fuel;
- the coupled group solved by OpenMDAO's Newton with `solve_subsystems=True` and an assembled
  direct linear solver, to an absolute residual of 1e-7 (OAS's residual floor is 3e-11 to 1e-8).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

import numpy as np
import openmdao.api as om
from openaerostruct.integration.aerostruct_groups import AerostructGeometry, AerostructPoint

__all__ = ["OASResult", "OASWing", "oas_mesh"]

NAME = "wing"
POINT = "AS_point_0"
TUBE_RADIUS = 0.05  # [m] any tube will do: only E I and G J matter, and they are matched
TUBE_THICKNESS = 0.01  # [m]


def oas_mesh(
    y: np.ndarray,
    chord: np.ndarray,
    elastic_axis: float,
    sweep_deg: float,
    jig_twist: np.ndarray | float = 0.0,
) -> np.ndarray:
    """(2, N, 3) OAS mesh of flexwing's right half-wing (stations y from the root), mirrored.

    The EA point of station i is (y_i tan(sweep), y_i, 0) as in flexwing; the leading edge is
    elastic_axis * c_i ahead of it and the chord is streamwise. A jig twist [deg] (nose up)
    turns each section about the global y axis through its EA point, as flexwing does.
    """
    y = np.asarray(y, dtype=float)[::-1]  # tip first
    chord = np.asarray(chord, dtype=float)[::-1]
    twist = np.radians(np.broadcast_to(np.asarray(jig_twist, dtype=float), y.shape)[::-1])
    x_ea = y * np.tan(np.radians(sweep_deg))
    mesh = np.zeros((2, y.size, 3))
    for row, fraction in enumerate((-elastic_axis, 1.0 - elastic_axis)):
        mesh[row, :, 0] = x_ea + fraction * chord * np.cos(twist)
        mesh[row, :, 2] = -fraction * chord * np.sin(twist)
    mesh[:, :, 1] = -y
    return mesh


def tube_moduli(ei: float, gj: float) -> tuple[float, float]:
    """(E, G) [Pa] that give the OAS tube exactly these EI and GJ [N m^2]."""
    inner = TUBE_RADIUS - TUBE_THICKNESS
    second_moment = np.pi * (TUBE_RADIUS**4 - inner**4) / 4.0
    return ei / second_moment, gj / (2.0 * second_moment)


def _add_heave_lever(loads_component: om.ExplicitComponent, axis: np.ndarray) -> None:
    """Diagnostic, not OAS: add to each node's torque the lever of its heave, (w e_z x f) . e_s.

    OAS's linear beam carries nodal loads along the UNDEFORMED beam, so a force's lever about
    the elastic axis is only its local arm from its own node, deformed (twist) but without the
    heave of that node relative to the station where the torque is taken. flexwing's torque
    about the undeformed axis (`torque_axis="undeformed"`) takes each force at its heaved point:
    this adds exactly that difference, (0, 0, w_j) x f_j projected on the axis, with w_j the
    heave of node j and f_j its nodal force. Its derivatives are added where OAS's declared
    sparsity has room: all of them at sweep 0; with sweep two of them are missing, and Newton
    converges more slowly.
    """
    comp = loads_component
    original_compute, original_partials = comp.compute, comp.compute_partials
    w2 = comp.w2
    nx, ny = comp.nx, comp.ny
    # the torque term's direction: g = (e_z x f) . e_s = f_x e_y - f_y e_x
    dg_df = np.array([axis[1], -axis[0], 0.0])

    def heave(mesh):
        return ((1 - w2) * mesh[0, :, :] + w2 * mesh[-1, :, :])[:, 2]  # jig nodes at z = 0

    def compute(inputs, outputs):
        original_compute(inputs, outputs)
        force = outputs["loads"][:, :3]
        torque = heave(inputs["def_mesh"]) * (force @ dg_df)
        outputs["loads"][:, 3:] += torque[:, None] * axis[None, :]

    info = comp._subjacs_info
    loads = comp.pathname + ".loads"
    index = {}
    for wrt in ("sec_forces", "def_mesh"):
        meta = info[(loads, comp.pathname + "." + wrt)]
        index[wrt] = {}
        for k, rc in enumerate(zip(meta["rows"], meta["cols"], strict=True)):
            index[wrt].setdefault((int(rc[0]), int(rc[1])), k)

    def add(partials, wrt, row, col, value):
        k = index[wrt].get((row, col))
        if k is not None:
            partials["loads", wrt][k] += value

    def compute_partials(inputs, partials):
        original_partials(inputs, partials)
        mesh, sec = inputs["def_mesh"], inputs["sec_forces"]
        w = heave(mesh)
        force = np.zeros((ny, 3))
        summed = 0.5 * np.sum(sec, axis=0)
        force[:-1] += summed
        force[1:] += summed
        g = force @ dg_df
        for j in range(ny):
            for a in range(3):
                if axis[a] == 0.0:
                    continue
                row = 6 * j + 3 + a
                # d/d heave: mesh rows 0 and nx - 1 at node j, z component
                add(partials, "def_mesh", row, 3 * j + 2, (1 - w2) * g[j] * axis[a])
                add(partials, "def_mesh", row, 3 * ny * (nx - 1) + 3 * j + 2, w2 * g[j] * axis[a])
                # d/d sec_forces of the panels j - 1 and j (every chordwise row)
                for panel in (j - 1, j):
                    if not 0 <= panel < ny - 1:
                        continue
                    for chordwise in range(nx - 1):
                        for k in range(2):
                            col = 3 * ((ny - 1) * chordwise + panel) + k
                            add(partials, "sec_forces", row, col, 0.5 * w[j] * dg_df[k] * axis[a])

    comp.compute = compute
    comp.compute_partials = compute_partials


@dataclass
class OASResult:
    lift: float  # [N] both halves, wind axes
    tip_heave: float  # [m] z displacement of the tip's beam node
    tip_stream_twist: float  # [deg] rotation of the tip about the global y axis (nose up +)
    tip_axis_twist: float  # [deg] rotation of the tip about the elastic axis (nose up +)
    iterations: int
    seconds: float  # wall time of this run_model


class OASWing:
    """One OAS aerostructural problem for a wing; `solve` re-runs it at any V, alpha, rho."""

    def __init__(
        self,
        y: np.ndarray,
        chord: np.ndarray,
        elastic_axis: float,
        ei: float,
        gj: float,
        sweep_deg: float,
        atol: float = 1e-7,
        heave_lever: bool = False,
        jig_twist: np.ndarray | float = 0.0,
    ) -> None:
        """A uniform tube with these EI, GJ [N m^2]; `atol` is Newton's absolute tolerance on
        OAS's residual norm at alpha = 2 deg (`solve` scales it with alpha, since the residuals
        scale with the loads); `heave_lever` is the diagnostic of `_add_heave_lever`."""
        self.sweep = sweep_deg
        self.atol = atol
        self.mesh = oas_mesh(y, chord, elastic_axis, sweep_deg, jig_twist)
        e_mod, g_mod = tube_moduli(ei, gj)
        surface = {
            "name": NAME,
            "symmetry": True,
            "S_ref_type": "projected",
            "mesh": self.mesh.copy(),
            "fem_model_type": "tube",
            "radius_cp": np.full(2, TUBE_RADIUS),
            "thickness_cp": np.full(2, TUBE_THICKNESS),
            "CL0": 0.0,
            "CD0": 0.0,
            "k_lam": 0.05,
            "t_over_c_cp": np.array([0.12]),
            "c_max_t": 0.303,
            "with_viscous": False,
            "with_wave": False,
            "E": e_mod,
            "G": g_mod,
            "yield": 1e30,
            "mrho": 1.0,
            "fem_origin": float(elastic_axis),
            "wing_weight_ratio": 1.0,
            "struct_weight_relief": False,
            "distributed_fuel_weight": False,
            "exact_failure_constraint": False,
        }
        prob = om.Problem(reports=False)
        ivc = om.IndepVarComp()
        ivc.add_output("v", val=10.0, units="m/s")
        ivc.add_output("alpha", val=0.0, units="deg")
        ivc.add_output("beta", val=0.0, units="deg")
        ivc.add_output("Mach_number", val=0.0)
        ivc.add_output("re", val=1.0e6, units="1/m")
        ivc.add_output("rho", val=1.225, units="kg/m**3")
        ivc.add_output("CT", val=1.0e-4, units="1/s")
        ivc.add_output("R", val=1.0e6, units="m")
        ivc.add_output("W0", val=100.0, units="kg")
        ivc.add_output("speed_of_sound", val=340.0, units="m/s")
        ivc.add_output("load_factor", val=1.0)
        ivc.add_output("empty_cg", val=np.zeros(3), units="m")
        prob.model.add_subsystem("prob_vars", ivc, promotes=["*"])
        prob.model.add_subsystem(NAME, AerostructGeometry(surface=surface))
        prob.model.add_subsystem(
            POINT,
            AerostructPoint(surfaces=[surface]),
            promotes_inputs=[
                "v",
                "alpha",
                "beta",
                "Mach_number",
                "re",
                "rho",
                "CT",
                "R",
                "W0",
                "speed_of_sound",
                "empty_cg",
                "load_factor",
            ],
        )
        perf = f"{POINT}.{NAME}_perf"
        coupled = f"{POINT}.coupled.{NAME}"
        for out, target in (
            ("local_stiff_transformed", f"{coupled}.local_stiff_transformed"),
            ("nodes", f"{coupled}.nodes"),
            ("mesh", f"{coupled}.mesh"),
            ("radius", f"{perf}.radius"),
            ("thickness", f"{perf}.thickness"),
            ("nodes", f"{perf}.nodes"),
            ("t_over_c", f"{perf}.t_over_c"),
            ("cg_location", f"{POINT}.total_perf.{NAME}_cg_location"),
            ("structural_mass", f"{POINT}.total_perf.{NAME}_structural_mass"),
        ):
            prob.model.connect(f"{NAME}.{out}", target)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            prob.setup(check=False)
        group = prob.model._get_subsystem(f"{POINT}.coupled")
        newton = om.NewtonSolver(solve_subsystems=True)
        newton.options["maxiter"] = 30
        newton.options["atol"] = atol
        # Near divergence OAS's residual floor rises (ill-conditioning): 2e-9 of the first
        # residual at alpha 0.001 deg and q = 0.98-0.995 q_div. Newton converges quadratically
        # down to it, so either tolerance ends a converged solve.
        newton.options["rtol"] = 1e-8
        newton.options["iprint"] = -1
        newton.options["err_on_non_converge"] = True
        group.nonlinear_solver = newton
        group.linear_solver = om.DirectSolver(assemble_jac=True)
        self.newton = newton
        self.problem = prob
        sweep = np.radians(sweep_deg)
        # the left half's elastic axis, root to tip
        self._axis = np.array([np.sin(sweep), -np.cos(sweep), 0.0])

        # The 3/4 of the structural setup that does not depend on the flight: run it once.
        prob.final_setup()
        if heave_lever:
            _add_heave_lever(prob.model._get_subsystem(f"{POINT}.coupled.{NAME}_loads"), self._axis)
            newton.options["maxiter"] = 100
        self.disp_name = f"{coupled}.disp"
        self.loads_name = f"{POINT}.coupled.{NAME}_loads.loads"
        self._ny = self.mesh.shape[1]

    def check_mesh(self) -> float:
        """max |OAS's mesh - ours| [m] after a run (OAS must leave our mesh as it is), and the
        beam nodes' largest distance from the elastic axis [m]."""
        prob = self.problem
        mesh = prob.get_val(f"{NAME}.mesh")
        nodes = prob.get_val(f"{NAME}.nodes")
        x_ea = -nodes[:, 1] * np.tan(np.radians(self.sweep))
        return float(np.max(np.abs(mesh - self.mesh))), float(
            np.max(np.abs(nodes[:, 0] - x_ea) + np.abs(nodes[:, 2]))
        )

    def stiffness(self) -> tuple[float, float]:
        """(E Iy, G J) of the tube elements as OAS computes them [N m^2] (max over elements)."""
        prob = self.problem
        surface_e = prob.model._get_subsystem(NAME).options["surface"]["E"]
        surface_g = prob.model._get_subsystem(NAME).options["surface"]["G"]
        return (
            float(np.max(surface_e * prob.get_val(f"{NAME}.Iy"))),
            float(np.max(surface_g * prob.get_val(f"{NAME}.J"))),
        )

    def reset(self) -> None:
        """Start the next solve from the jig (zero displacements)."""
        prob = self.problem
        prob.set_val(self.disp_name, np.zeros((self._ny, 6)))
        # The loads component keeps the last equilibrium's loads, and Newton's first pass
        # (solve_subsystems) would rebuild the displacements from them: clear them too.
        prob.set_val(self.loads_name, np.zeros((self._ny, 6)))

    def state(self) -> tuple[np.ndarray, np.ndarray]:
        """The coupled state OAS's Newton starts from: displacements and the loads."""
        prob = self.problem
        return prob.get_val(self.disp_name).copy(), prob.get_val(self.loads_name).copy()

    def restore(self, state: tuple[np.ndarray, np.ndarray]) -> None:
        self.problem.set_val(self.disp_name, state[0])
        self.problem.set_val(self.loads_name, state[1])

    def solve(
        self, velocity: float, alpha: float, density: float, from_jig: bool = True
    ) -> OASResult:
        """The equilibrium at V [m/s], alpha [deg], rho [kg/m^3]: from the jig, or from the
        state the problem holds (the last equilibrium, or a `restore`d one). Raises
        openmdao's AnalysisError when Newton does not converge."""
        prob = self.problem
        if from_jig:
            self.reset()
        self.newton.options["atol"] = self.atol * max(abs(alpha) / 2.0, 1e-6)
        prob.set_val("v", velocity, units="m/s")
        prob.set_val("alpha", alpha, units="deg")
        prob.set_val("rho", density, units="kg/m**3")
        started = time.perf_counter()
        prob.run_model()
        seconds = time.perf_counter() - started
        disp = prob.get_val(self.disp_name)
        tip = disp[0]
        rotation = tip[3:6]
        return OASResult(
            lift=float(prob.get_val(f"{POINT}.{NAME}_perf.L")[0]),
            tip_heave=float(tip[2]),
            tip_stream_twist=float(np.degrees(rotation[1])),
            tip_axis_twist=float(np.degrees(-(rotation @ self._axis))),
            iterations=int(self.newton._iter_count),
            seconds=seconds,
        )
