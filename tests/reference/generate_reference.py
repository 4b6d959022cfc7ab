"""Regenerate a reference file with AeroSandbox, exactly as the design study formulates the wing.

DEV-ONLY. AeroSandbox is never a runtime dependency of flexwing; run this with a separate
environment that has it (AeroSandbox 4.2.10, casadi 3.8.2, IPOPT):

    /tmp/asbenv/bin/python tests/reference/generate_reference.py CASE.json OUT.json

The formulation is the study's (shared/seed/, chapter 14), line for line: an ``asb.Opti`` with
heave ``u`` and twist ``theta`` [deg] as variables and the airspeed as a parameter; ``make_wing``
places each section's elastic-axis point at x = 0, twists it about the y axis, then heaves it;
``VortexLatticeMethod`` with ``spanwise_resolution=1``, ``chordwise_resolution=1`` and
``xyz_ref=[0, 0, 0]``; internal loads by the outboard sums S, M, T; ``opti.derivative_of`` and
``opti.constrain_derivative`` (trapezoidal) for EI u'' = M and GJ theta' = T; clamped root
u = u' = theta = 0. Velocities are solved in the listed order, each warm-started from the last
converged equilibrium (``set_initial_from_sol``); the first from the jig shape.

The extended model (sweep, chordwise panels, camber, jig twist, torque axis, trim; project issues
10 and 11) and the jig-twist design problem (issue 12) are written in the same Opti pattern. With
sweep 0, one chordwise panel, no jig twist and the undeformed torque axis they build exactly the
study's expressions (same CasADi graph), so a case without the extended keys regenerates bit for
bit with today's output format. See tests/reference/CONVENTIONS.md for every convention.

Input: a case file (JSON object)
    name              str, optional
    span              [m] full span; stations are y = linspace(0, span / 2, N)
    chords            (N,) [m] chord at each station (streamwise)
    x_ea_over_chord   [-] elastic-axis position as a fraction of chord (one number)
    EI, GJ            (N,) [N m^2] bending and torsional stiffness at each station
    alpha_deg         [deg] angle of attack of the jig shape (the initial guess when trimmed)
    velocities        [m/s] airspeeds, solved in this order
    fail_velocities   [m/s], optional: airspeeds expected to have no equilibrium; attempted after
                      `velocities`, in order, and recorded under `failures` if IPOPT fails
    airfoil           str, optional, default "dae11" (the study's). Without the extended keys
                      below it must have zero camber at x/c = 0 and 1 (dae11, naca0012, ...) for
                      flexwing's flat-plate model; with them any AeroSandbox airfoil (its camber
                      is recorded).
  Extended keys (any one of them switches the output to the extended format, below):
    sweep_deg             [deg] sweep of the elastic axis, positive aft (default 0). The elastic
                          axis is the line x = y tan(sweep) in the wing plane; sections stay
                          streamwise; the beam runs along the axis, arc length s = y / cos(sweep).
    dihedral_deg          [deg] dihedral of the wing's plane, tips up (default 0): the flat
                          (swept) half-wing, heave and twist included, is turned about the x axis
                          through the root, every section's xyz_le R_x(dihedral) of the flat
                          one; `span` and the stations y are along the wing's plane (the
                          projected semispan is span / 2 cos(dihedral)). The beam lives in the
                          plane: e_s = (sin(sweep), cos(sweep) cos(dihedral), cos(sweep)
                          sin(dihedral)), n = (0, -sin(dihedral), cos(dihedral)) the heave's
                          direction, and S, M use the panels' normal force F . n
    chordwise_resolution  int 1..8, chordwise panels per strip (default 1; cosine spacing)
    jig_twist_deg         (N,) [deg] built-in streamwise twist of the jig (default zeros)
    torque_axis           "undeformed" (default) or "deformed": the load arms are measured from
                          the undeformed elastic-axis point (y tan(sweep), y, 0) or from the
                          heaved one (y tan(sweep), y, u)
    trim                  {"lift": W}: alpha becomes a variable with aero["L"] == W [N, both
                          halves]; the rigid jig's trim alpha at each velocity is solved separately
    ipopt_tol             IPOPT `tol` and `constr_viol_tol` (default: AeroSandbox's defaults, i.e.
                          IPOPT's tol 1e-8, as the study; every new case sets 1e-10)
  Design mode (issue 12): a case with key "optimize" (see `generate_design`):
    optimize              {"velocity": V, "lift": W, "smoothness_weight": w [N/deg^2],
                           "alpha_deg": 0}: jig twist per station as variables, total streamwise
                          twist tw with tw[0] == tw[1], L == W, minimise D + w sum(diff(tw, 2)^2),
                          for the flexible wing and for the rigid jig.

Output: a reference file (JSON object, indent 1)
    case          the input case, verbatim
    rho           [kg/m^3] air density AeroSandbox used (sea-level ISA, 1.2249991558876672)
    ys            (N,) [m] station positions
    rigid         the jig shape's VLM at the first velocity:
                  velocity [m/s], L, D [N], CL [-] (on S_ref), Fz (N-1,) [N] vertical force of
                  each right-half panel (root to tip), S_ref [m^2] jig planform area (both halves)
    equilibria[]  one per converged velocity, in solve order:
                  velocity [m/s]; solve_s [s] IPOPT wall time; iterations (IPOPT);
                  u [m], theta_deg [deg], du [-] (slope u') at stations (N,);
                  Fz [N], tau [N m] per right-half panel (N-1,), root to tip (tau: torque about
                  the elastic axis = y-moment about the origin);
                  S [N], M [N m], T [N m] internal shear, bending moment, torque at stations (N,);
                  L, D [N] both halves; CL, CD, Cm [-] as AeroSandbox reports them, i.e. on the
                  DEFORMED wing's planform area (Cm also on its mean aerodynamic chord);
                  tip_heave [m], tip_twist_deg [deg]
    failures[]    {velocity, solved: false, message}: velocities where IPOPT found no solution
  Extended format (additions; per-panel arrays hold all P = (N-1) k right-half panels in
  AeroSandbox's order, panel p = i k + j: strip i root to tip, chordwise j leading to trailing
  edge):
    format        "extended-1"
    model         sweep_deg, chordwise_resolution, airfoil, torque_axis, jig_twist_deg (N,),
                  s (N,) [m] beam arc length y / cos(sweep), ea_x (N,) [m] y tan(sweep),
                  e_s: the axis direction (sin, cos, 0) (turned by the dihedral), ipopt_options;
                  dihedral_deg and n (the wing plane's normal) when the case gives a dihedral
    camber_line   {"x": (k+1,) chordwise node positions x/c, "camber": (k+1,) camber/c that
                  AeroSandbox places there (Airfoil.local_camber, from its coordinates); the same
                  at every station (one airfoil); placed along the section's scaled normal,
                  see CONVENTIONS.md}
    rigid         adds alpha_deg, Fx, Fy (P,), Fz is (P,), vortex_centers (P, 3), strip_Fz (N-1,)
    rigid_trim[]  (trim only) {velocity, alpha_deg, L, D, CL, iterations, solve_s}: the jig's trim
    equilibria[]  each adds: alpha_deg (the trimmed alpha when trimmed); phi_deg (N,) twist about
                  the elastic axis (the structural unknown, identical to theta_deg, which keeps
                  its old meaning); elastic_stream_twist_deg (N,) phi cos(sweep) - degrees(du)
                  sin(sweep);
                  stream_twist_deg (N,) the WingXSec twist the flow sees = elastic + jig;
                  xyz_le (N, 3) deformed leading edges; camber_scale (N,) AeroSandbox's
                  sqrt(2 / (1 + cos)) factor on the camber at each section;
                  Fx, Fy, Fz, tau (P,) per panel (tau: torque of the panel's force about the
                  undeformed elastic axis, ((r_p - EA_i) x F_p) . e_s, i.e. moment about the origin
                  dotted with e_s); vortex_centers (P, 3) deformed force points;
                  strip_Fx, strip_Fy, strip_Fz, strip_tau (N-1,) sums over each strip's panels;
                  S, M, T (N,) with the arms of `torque_axis`; tip_stream_twist_deg;
                  return_status, inf_pr (IPOPT's final unscaled constraint violation)
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import aerosandbox as asb
import aerosandbox.numpy as np
import casadi

# AeroSandbox 4.2.10 relies on casadi's legacy numpy interplay: keep it, minus casadi 3.8's notice.
if hasattr(casadi.GlobalOptions, "setNumpyMode"):
    casadi.GlobalOptions.setNumpyMode(-1)

EXTENDED_KEYS = (
    "sweep_deg",
    "dihedral_deg",
    "chordwise_resolution",
    "jig_twist_deg",
    "torque_axis",
    "trim",
    "ipopt_tol",
)


def _floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def _rows(values) -> list[list[float]]:
    return [[float(x) for x in row] for row in np.asarray(values, dtype=float)]


class WingModel:
    """The study's wing generalised to sweep, chordwise panels, camber and jig twist.

    At sweep 0 every expression below is the study's own (the generalisations are guarded by
    Python branches, not multiplied by cos 0 = 1 and sin 0 = 0), so the CasADi graph and the IPOPT
    iterates are identical to the study's.
    """

    def __init__(self, case: dict):
        self.case = case
        self.chords = np.array(case["chords"], dtype=float)
        self.N = N = len(self.chords)
        self.span = float(case["span"])
        self.ys = np.linspace(0, self.span / 2, N)
        self.x_ea_over_chord = float(case["x_ea_over_chord"])
        self.EI = np.array(case["EI"], dtype=float)
        self.GJ = np.array(case["GJ"], dtype=float)
        self.alpha = float(case["alpha_deg"])
        self.airfoil_name = case.get("airfoil", "dae11")
        self.airfoil = asb.Airfoil(self.airfoil_name)
        if len(self.EI) != N or len(self.GJ) != N:
            raise ValueError("chords, EI and GJ must have the same length")

        self.sweep_deg = float(case.get("sweep_deg", 0.0))
        if not -60.0 < self.sweep_deg < 60.0:
            raise ValueError("sweep_deg must lie in (-60, 60)")
        lam = np.radians(self.sweep_deg)
        self.swept = self.sweep_deg != 0.0
        self.sin_l = float(np.sin(lam))
        self.cos_l = float(np.cos(lam))
        self.tan_l = float(np.tan(lam))
        # Beam arc length along the elastic axis; at sweep 0 exactly the study's ys.
        self.s = self.ys / self.cos_l if self.swept else self.ys
        self.ea_x = self.ys * self.tan_l if self.swept else np.zeros(N)

        self.dihedral_deg = float(case.get("dihedral_deg", 0.0))
        if not -45.0 < self.dihedral_deg < 45.0:
            raise ValueError("dihedral_deg must lie in (-45, 45)")
        # At dihedral 0 every expression below is the flat wing's (Python branches, as sweep).
        self.turned = self.dihedral_deg != 0.0
        gamma = np.radians(self.dihedral_deg)
        self.cos_d, self.sin_d = float(np.cos(gamma)), float(np.sin(gamma))
        # The axis direction and the wing plane's normal (the heave's direction), turned.
        self.e_s = np.array([self.sin_l, self.cos_l * self.cos_d, self.cos_l * self.sin_d])
        self.normal = np.array([0.0, -self.sin_d, self.cos_d])

        self.nc = int(case.get("chordwise_resolution", 1))
        if not 1 <= self.nc <= 8:
            raise ValueError("chordwise_resolution must be an integer in 1..8")
        self.n_right = (N - 1) * self.nc

        jig = case.get("jig_twist_deg")
        self.jig = None if jig is None else np.array(jig, dtype=float)
        if self.jig is not None and len(self.jig) != N:
            raise ValueError("jig_twist_deg must have one value per station")

        self.torque_axis = case.get("torque_axis", "undeformed")
        if self.torque_axis not in ("undeformed", "deformed"):
            raise ValueError('torque_axis must be "undeformed" or "deformed"')

        # [i, p]: 1 if right-half panel p (strip p // nc) is outboard of station i. For nc = 1
        # this is the study's matrix, value for value.
        self.outboard = (
            (np.arange(self.n_right) // self.nc)[None, :] >= np.arange(N)[:, None]
        ).astype(float)

    # -- geometry ---------------------------------------------------------------------------
    def make_wing(self, heave=None, twist=None) -> asb.Wing:
        """The study's make_wing: jig + heave [m] + streamwise twist [deg] about the EA point.

        `twist` is the WingXSec twist, i.e. everything the flow sees (elastic + jig).
        """
        N = self.N
        if heave is None:
            heave = np.zeros(N)
        if twist is None:
            twist = np.zeros(N)
        xsecs = []
        for i in range(N):
            xyz_le = np.array([-self.chords[i] * self.x_ea_over_chord, self.ys[i], 0])
            xyz_le = np.rotation_matrix_3D(angle=np.radians(twist[i]), axis="y") @ xyz_le
            xyz_le += np.array([0, 0, heave[i]])
            if self.swept:  # the elastic-axis point moves to (y tan(sweep), y, 0)
                xyz_le += np.array([self.ea_x[i], 0, 0])
            if self.turned:  # the flat half-wing turned about x through the root
                turn = np.rotation_matrix_3D(angle=np.radians(self.dihedral_deg), axis="x")
                xyz_le = turn @ xyz_le
            xsecs.append(
                asb.WingXSec(
                    xyz_le=xyz_le, chord=self.chords[i], twist=twist[i], airfoil=self.airfoil
                )
            )
        return asb.Wing(symmetric=True, xsecs=xsecs)

    def make_vlm(self, wing, velocity, alpha=None) -> asb.VortexLatticeMethod:
        return asb.VortexLatticeMethod(
            airplane=asb.Airplane(wings=[wing], xyz_ref=[0, 0, 0]),
            op_point=asb.OperatingPoint(
                velocity=velocity, alpha=self.alpha if alpha is None else alpha
            ),
            spanwise_resolution=1,
            chordwise_resolution=self.nc,
        )

    def xsec_twist(self, stream_elastic):
        """WingXSec twist = elastic streamwise twist + jig twist (jig omitted when not given)."""
        return stream_elastic if self.jig is None else stream_elastic + self.jig

    def stream_twist(self, phi, du):
        """Elastic streamwise section rotation [deg]: phi cos(sweep) - degrees(du) sin(sweep)."""
        if not self.swept:
            return phi
        return phi * self.cos_l - np.degrees(du) * self.sin_l

    # -- loads ------------------------------------------------------------------------------
    def loads(self, vlm, heave=None) -> dict:
        """Per-panel forces and the outboard sums S, M, T at the stations."""
        n = self.n_right
        F = vlm.forces_geometry[:n, :]
        Fz = vlm.forces_geometry[:n, 2]
        r = vlm.vortex_centers[:n, :]
        if self.turned:
            # The beam in the wing's plane: arms and torque along the turned e_s, the shear and
            # bending from the force normal to the plane (EA_i = s_i e_s, as unturned).
            m = vlm.moments_geometry
            tau = m[:n, 0] * self.e_s[0] + m[:n, 1] * self.e_s[1] + m[:n, 2] * self.e_s[2]
            s_panel = r[:, 0] * self.e_s[0] + r[:, 1] * self.e_s[1] + r[:, 2] * self.e_s[2]
            s_station = self.s
            Fn = F[:, 1] * self.normal[1] + F[:, 2] * self.normal[2]  # F . n
        elif self.swept:
            # Torque about the undeformed axis through the origin along e_s: moment about the
            # origin dotted with e_s (the axis point's own term vanishes: EA_i is parallel to e_s).
            m = vlm.moments_geometry
            tau = m[:n, 0] * self.sin_l + m[:n, 1] * self.cos_l
            s_panel = r[:, 0] * self.sin_l + r[:, 1] * self.cos_l  # r_p . e_s
            s_station = self.s  # EA_i . e_s = y_i / cos(sweep)
        else:
            tau = vlm.moments_geometry[:n, 1]
            s_panel = vlm.vortex_centers[:n, 1]
            s_station = self.ys
        if not self.turned:
            Fn = Fz  # the plane's normal is z
        S = self.outboard @ Fn
        M = self.outboard @ (Fn * s_panel) - s_station * S
        T = self.outboard @ tau
        if self.torque_axis == "deformed":
            # Arms from (EA_i + u_i n): T_i -= u_i sum (n x F_p) . e_s = u_i sum F_p . (e_s x n);
            # M unchanged (n . e_s = 0).
            if self.turned:
                across = np.cross(self.e_s, self.normal)
                F_perp = F[:, 0] * across[0] + F[:, 1] * across[1] + F[:, 2] * across[2]
            elif self.swept:
                F_perp = F[:, 0] * self.cos_l - F[:, 1] * self.sin_l
            else:
                F_perp = F[:, 0]
            T = T - heave * (self.outboard @ F_perp)
        return {
            "F": F,
            "Fz": Fz,
            "tau": tau,
            "r": r,
            "S": S,
            "M": M,
            "T": T,
            "heave": heave if heave is not None else np.zeros(self.N),
        }

    def check_panel_order(self, vortex_centers, legacy: bool) -> None:
        """AeroSandbox's panel order: right half first, p = i nc + j (strip i root to tip, j LE
        to TE), then the left half, mirrored."""
        N, nc, n = self.N, self.nc, self.n_right
        vc = np.asarray(vortex_centers, dtype=float)
        if legacy:
            if not np.all(np.diff(vc[: N - 1, 1]) > 0):
                raise RuntimeError("the VLM did not order the right half-wing's panels root to tip")
            return
        strips = np.arange(n) // nc
        # Along the wing's plane (the points turned back by the dihedral).
        along = vc[:n, 1] * self.cos_d + vc[:n, 2] * self.sin_d if self.turned else vc[:n, 1]
        ok = np.all(along > self.ys[strips]) and np.all(along < self.ys[strips + 1])
        for i in range(N - 1):
            ok = ok and bool(np.all(np.diff(vc[i * nc : (i + 1) * nc, 0]) > 0))
        ok = ok and bool(np.all(np.abs(vc[n:, 1] + vc[:n, 1]) < 1e-12))  # left half mirrors
        if not ok:
            raise RuntimeError("unexpected VLM panel order (expected strip-major, LE to TE)")

    def camber_line(self) -> dict:
        x = np.cosspace(0, 1, self.nc + 1)  # VortexLatticeMethod's chordwise_spacing_function
        return {"x": _floats(x), "camber": _floats(self.airfoil.local_camber(x_over_c=x))}


def _camber_scale(wing: asb.Wing) -> list[float]:
    """AeroSandbox's camber scaling sqrt(2 / (1 + cos)) at each section (norm of its zg_local)."""
    out = []
    for i in range(len(wing.xsecs)):
        _, _, zg = wing._compute_frame_of_WingXSec(i)
        out.append(float(np.linalg.norm(np.asarray(zg, dtype=float))))
    return out


def _ipopt_options(case: dict) -> dict | None:
    if "ipopt_tol" not in case:
        return None
    tol = float(case["ipopt_tol"])
    return {"ipopt.tol": tol, "ipopt.constr_viol_tol": tol}


def _solve(opti, parameter_mapping, options):
    if options is None:  # exactly the study's call
        return opti.solve(parameter_mapping=parameter_mapping, verbose=False)
    return opti.solve(parameter_mapping=parameter_mapping, verbose=False, options=options)


def _final_inf_pr(sol) -> float | None:
    try:
        return float(sol.stats()["iterations"]["inf_pr"][-1])
    except (KeyError, IndexError, TypeError):
        return None


def generate(case: dict, model_class: type[WingModel] = WingModel) -> dict:
    """The reference of `case`; `model_class` builds its wing (a subclass gives each section
    an airfoil of its own: `generate_controls_reference.py`)."""
    if "optimize" in case:
        return generate_design(case)
    extended = any(key in case for key in EXTENDED_KEYS)
    model = model_class(case)
    N, nc, n = model.N, model.nc, model.n_right
    ys = model.ys
    options = _ipopt_options(case)
    trim = case.get("trim")
    if trim is not None:
        W = float(trim["lift"])

    # Velocities keep their JSON spelling (10 stays 10) in the output.
    attempts = list(case["velocities"]) + list(case.get("fail_velocities", []))

    # Rigid baseline: the jig shape at the first velocity.
    wing_jig = model.make_wing(twist=model.jig)
    vlm_rigid = model.make_vlm(wing_jig, velocity=float(attempts[0]))
    aero_rigid = vlm_rigid.run()
    model.check_panel_order(vlm_rigid.vortex_centers, legacy=not extended)
    rigid = {
        "velocity": attempts[0],
        "L": float(aero_rigid["L"]),
        "CL": float(aero_rigid["CL"]),
        "D": float(aero_rigid["D"]),
        "Fz": _floats(vlm_rigid.forces_geometry[:n, 2]),
        "S_ref": float(wing_jig.area()),
    }
    if extended:
        Fr = np.asarray(vlm_rigid.forces_geometry[:n, :], dtype=float)
        rigid.update(
            {
                "alpha_deg": model.alpha,
                "Fx": _floats(Fr[:, 0]),
                "Fy": _floats(Fr[:, 1]),
                "vortex_centers": _rows(vlm_rigid.vortex_centers[:n, :]),
                "strip_Fz": _floats(Fr[:, 2].reshape(N - 1, nc).sum(axis=1)),
            }
        )
    rho = float(vlm_rigid.op_point.atmosphere.density())

    rigid_trim = None
    if trim is not None:
        rigid_trim = _rigid_trim(model, wing_jig, W, attempts, options)

    # The coupled problem (study section 14.4).
    opti = asb.Opti()
    u = opti.variable(init_guess=np.zeros(N))  # heave [m]
    theta = opti.variable(init_guess=np.zeros(N))  # twist about the elastic axis [deg] (phi)
    velocity = opti.parameter(value=float(attempts[0]))  # [m/s]
    alpha = None
    if trim is not None:
        alpha = opti.variable(init_guess=model.alpha)  # [deg]

    du = None
    if model.swept:  # the flow angle needs the slope: declare it before the wing
        du = opti.derivative_of(u, with_respect_to=model.s, derivative_init_guess=np.zeros(N))
    stream_elastic = model.stream_twist(theta, du)
    xsec_twist = model.xsec_twist(stream_elastic)

    wing = model.make_wing(heave=u, twist=xsec_twist)
    vlm = model.make_vlm(wing, velocity=velocity, alpha=alpha)
    aero = vlm.run()

    loads = model.loads(vlm, heave=u)
    Fz, tau, S, M, T = loads["Fz"], loads["tau"], loads["S"], loads["M"], loads["T"]

    if du is None:
        du = opti.derivative_of(u, with_respect_to=model.s, derivative_init_guess=np.zeros(N))
    opti.constrain_derivative(variable=du, with_respect_to=model.s, derivative=M / model.EI)
    opti.constrain_derivative(
        variable=theta, with_respect_to=model.s, derivative=np.degrees(T / model.GJ)
    )
    opti.subject_to([u[0] == 0, du[0] == 0, theta[0] == 0])
    if trim is not None:
        opti.subject_to(aero["L"] == W)

    jacobian = None
    if extended:
        # Square system's Jacobian, to compare det signs with the unloaded structure (q -> 0).
        jacobian = casadi.Function("J", [opti.x, opti.p], [casadi.jacobian(opti.g, opti.x)])

    equilibria = []
    failures = []
    last_sol = None
    for V in attempts:
        if last_sol is not None:
            opti.set_initial_from_sol(last_sol)
        started = time.perf_counter()
        try:
            sol = _solve(opti, {velocity: float(V)}, options)
        except RuntimeError as error:
            message = str(error).splitlines()[-1] if str(error) else repr(error)
            failures.append({"velocity": V, "solved": False, "message": message})
            print(f"V = {V:g} m/s: FAILED ({message})", file=sys.stderr)
            continue
        solve_s = time.perf_counter() - started
        last_sol = sol
        u_sol = sol(u)
        theta_sol = sol(theta)
        eq = {
            "velocity": V,
            "solve_s": solve_s,
            "iterations": int(sol.stats()["iter_count"]),
            "u": _floats(u_sol),
            "theta_deg": _floats(theta_sol),
            "du": _floats(sol(du)),
            "Fz": _floats(sol(Fz)),
            "tau": _floats(sol(tau)),
            "S": _floats(sol(S)),
            "M": _floats(sol(M)),
            "T": _floats(sol(T)),
            "L": float(sol(aero["L"])),
            "D": float(sol(aero["D"])),
            "CL": float(sol(aero["CL"])),
            "CD": float(sol(aero["CD"])),
            "Cm": float(sol(aero["Cm"])),
            "tip_heave": float(u_sol[-1]),
            "tip_twist_deg": float(theta_sol[-1]),
        }
        if extended:
            eq.update(
                _extended_fields(
                    model, sol, wing, vlm, loads, aero, alpha, stream_elastic, xsec_twist, theta
                )
            )
            eq["jacobian_det_sign_vs_unloaded"] = _det_sign_vs_unloaded(jacobian, sol, opti, V)
        equilibria.append(eq)
        extra = f", alpha = {eq['alpha_deg']:.6g} deg" if trim is not None else ""
        print(
            f"V = {V:g} m/s: L = {eq['L']:.6g} N, tip twist = "
            f"{theta_sol[-1]:.6g} deg{extra} ({eq['iterations']} IPOPT iterations, "
            f"{solve_s:.1f} s)",
            file=sys.stderr,
        )

    out = {
        "case": case,
        "rho": rho,
        "ys": _floats(ys),
        "rigid": rigid,
        "equilibria": equilibria,
        "failures": failures,
    }
    if extended:
        out["format"] = "extended-1"
        out["model"] = _model_fields(model, options)
        out["camber_line"] = model.camber_line()
        if rigid_trim is not None:
            out["rigid_trim"] = rigid_trim
    return out


def _model_fields(model: WingModel, options) -> dict:
    dihedral = {}
    if "dihedral_deg" in model.case:
        dihedral = {"dihedral_deg": model.dihedral_deg, "n": _floats(model.normal)}
    return dihedral | {
        "sweep_deg": model.sweep_deg,
        "chordwise_resolution": model.nc,
        "airfoil": model.airfoil_name,
        "torque_axis": model.torque_axis,
        "jig_twist_deg": _floats(model.jig if model.jig is not None else np.zeros(model.N)),
        "s": _floats(model.s),
        "ea_x": _floats(model.ea_x),
        "e_s": _floats(model.e_s) if model.turned else [model.sin_l, model.cos_l, 0.0],
        "ipopt_options": options or {},
    }


def _extended_fields(model, sol, wing, vlm, loads, aero, alpha, stream_elastic, xsec_twist, phi):
    N, nc = model.N, model.nc
    F = np.asarray(sol(loads["F"]), dtype=float)
    tau = np.asarray(sol(loads["tau"]), dtype=float).ravel()
    vc = np.asarray(sol(loads["r"]), dtype=float)
    model.check_panel_order(sol(vlm.vortex_centers), legacy=False)  # the deformed mesh too
    stream = np.asarray(sol(xsec_twist), dtype=float).ravel()
    wing_num = sol(wing)  # the deformed wing, numeric
    stats = sol.stats()
    _check_loads(
        model,
        F,
        vc,
        np.asarray(sol(loads["S"]), dtype=float).ravel(),
        np.asarray(sol(loads["M"]), dtype=float).ravel(),
        np.asarray(sol(loads["T"]), dtype=float).ravel(),
        np.asarray(sol(loads["heave"]), dtype=float).ravel(),
    )
    return {
        "alpha_deg": float(sol(alpha)) if alpha is not None else model.alpha,
        "phi_deg": _floats(sol(phi)),
        "elastic_stream_twist_deg": _floats(sol(stream_elastic)),
        "stream_twist_deg": _floats(stream),
        "tip_stream_twist_deg": float(stream[-1]),
        "xyz_le": _rows([np.asarray(x.xyz_le, dtype=float).ravel() for x in wing_num.xsecs]),
        "camber_scale": _camber_scale(wing_num),
        "Fx": _floats(F[:, 0]),
        "Fy": _floats(F[:, 1]),
        "vortex_centers": _rows(vc),
        "strip_Fx": _floats(F[:, 0].reshape(N - 1, nc).sum(axis=1)),
        "strip_Fy": _floats(F[:, 1].reshape(N - 1, nc).sum(axis=1)),
        "strip_Fz": _floats(F[:, 2].reshape(N - 1, nc).sum(axis=1)),
        "strip_tau": _floats(tau.reshape(N - 1, nc).sum(axis=1)),
        "S_ref": float(sol(wing.area())),
        "return_status": stats.get("return_status"),
        "inf_pr": _final_inf_pr(sol),
    }


def _det_sign_vs_unloaded(jacobian, sol, opti, V) -> int:
    """sign(det J(x*, V)) * sign(det J(x*, V -> 0)): +1 if no real eigenvalue of the coupled
    Jacobian has crossed zero between the unloaded structure and this equilibrium (no fold
    between them), -1 otherwise."""
    x = sol.value(opti.x)
    signs = []
    for v in (float(V), 1e-6):
        J = np.array(jacobian(x, v), dtype=float)
        sign, _ = np.linalg.slogdet(J)
        signs.append(sign)
    return int(signs[0] * signs[1])


def _check_loads(model: WingModel, F, r, S, M, T, heave) -> None:
    """Recompute S, M, T from the numeric panel forces with the literal definitions (a check on
    the symbolic shortcuts): for station i, the panels of strips >= i, e_s = (sin, cos, 0) and
    n = (0, 0, 1) turned by the dihedral about x, r_i = R_x (y_i tan(sweep), y_i, 0) (+ u_i n
    for the deformed torque axis), S_i = sum F . n, M_i = sum (F . n) ((r_p - r_i) . e_s),
    T_i = sum ((r_p - r_i) x F_p) . e_s."""
    e_s = np.array([model.sin_l, model.cos_l, 0.0]) if not model.turned else model.e_s
    normal = np.array([0.0, 0.0, 1.0]) if not model.turned else model.normal
    turn = np.rotation_matrix_3D(angle=np.radians(model.dihedral_deg), axis="x")
    strips = np.arange(model.n_right) // model.nc
    scale = max(1.0, float(np.max(np.abs(F))) * float(np.max(np.abs(r))))
    for i in range(model.N):
        sel = strips >= i
        r_i = np.asarray(turn, dtype=float) @ np.array([model.ea_x[i], model.ys[i], 0.0])
        if model.torque_axis == "deformed":
            r_i = r_i + heave[i] * normal
        arm = r[sel] - r_i
        S_i = float(np.sum(F[sel] @ normal))
        M_i = float(np.sum((F[sel] @ normal) * (arm @ e_s)))
        T_i = float(np.sum(np.cross(arm, F[sel]) @ e_s))
        err = max(abs(S_i - S[i]), abs(M_i - M[i]), abs(T_i - T[i]))
        if err > 1e-10 * scale * max(1, model.n_right):
            raise RuntimeError(f"load check failed at station {i}: {err:g}")


def _rigid_trim(model: WingModel, wing_jig, W: float, attempts, options) -> list[dict]:
    """The jig shape's trim alpha for lift W at each velocity (a separate small problem)."""
    opti = asb.Opti()
    alpha = opti.variable(init_guess=model.alpha)
    velocity = opti.parameter(value=float(attempts[0]))
    aero = model.make_vlm(wing_jig, velocity=velocity, alpha=alpha).run()
    opti.subject_to(aero["L"] == W)
    out = []
    last = None
    for V in attempts:
        if last is not None:
            opti.set_initial_from_sol(last)
        started = time.perf_counter()
        sol = _solve(opti, {velocity: float(V)}, options)
        solve_s = time.perf_counter() - started
        last = sol
        out.append(
            {
                "velocity": V,
                "alpha_deg": float(sol(alpha)),
                "L": float(sol(aero["L"])),
                "D": float(sol(aero["D"])),
                "CL": float(sol(aero["CL"])),
                "iterations": int(sol.stats()["iter_count"]),
                "solve_s": solve_s,
            }
        )
        print(f"rigid trim V = {V:g} m/s: alpha = {out[-1]['alpha_deg']:.6g} deg", file=sys.stderr)
    return out


def generate_design(case: dict) -> dict:
    """Issue 12: the jig twist that minimises drag of the flying wing at L == W.

    Variables: jig twist per station [deg] (+ heave u, twist phi, slope du for the flexible wing).
    Total streamwise twist tw = elastic streamwise twist + jig (at sweep 0: phi + jig; rigid: jig).
    Constraints: tw[0] == tw[1] (zero slope at the centreline), aero["L"] == W, the beam equations
    and clamps (flexible). Objective: aero["D"] + w * sum((tw[i+1] - 2 tw[i] + tw[i-1])^2).
    Solved for the rigid jig first, then the flexible wing from zeros; if that fails, again from
    the rigid optimum (recorded under "attempts").
    """
    spec = case["optimize"]
    V = float(spec["velocity"])
    W = float(spec["lift"])
    w = float(spec.get("smoothness_weight", 0.01))
    alpha_deg = float(spec.get("alpha_deg", 0.0))
    model_case = dict(case)
    model_case["alpha_deg"] = alpha_deg
    model_case.pop("jig_twist_deg", None)
    model = WingModel(model_case)
    options = _ipopt_options(case)
    N = model.N

    def smoothness(tw):
        d2 = tw[2:] - 2 * tw[1:-1] + tw[:-2]
        return np.sum(d2**2)

    def build(flexible: bool):
        opti = asb.Opti()
        jig = opti.variable(init_guess=np.zeros(N))  # [deg]
        out = {"opti": opti, "jig": jig}
        if flexible:
            u = opti.variable(init_guess=np.zeros(N))
            phi = opti.variable(init_guess=np.zeros(N))
            du = None
            if model.swept:
                du = opti.derivative_of(
                    u, with_respect_to=model.s, derivative_init_guess=np.zeros(N)
                )
            tw = model.stream_twist(phi, du) + jig
            wing = model.make_wing(heave=u, twist=tw)
        else:
            tw = jig
            wing = model.make_wing(twist=tw)
        vlm = model.make_vlm(wing, velocity=V, alpha=alpha_deg)
        aero = vlm.run()
        if flexible:
            loads = model.loads(vlm, heave=u)
            if du is None:
                du = opti.derivative_of(
                    u, with_respect_to=model.s, derivative_init_guess=np.zeros(N)
                )
            opti.constrain_derivative(
                variable=du, with_respect_to=model.s, derivative=loads["M"] / model.EI
            )
            opti.constrain_derivative(
                variable=phi, with_respect_to=model.s, derivative=np.degrees(loads["T"] / model.GJ)
            )
            opti.subject_to([u[0] == 0, du[0] == 0, phi[0] == 0])
            out.update({"u": u, "phi": phi, "du": du, "loads": loads})
        opti.subject_to([tw[0] == tw[1], aero["L"] == W])
        penalty = w * smoothness(tw)
        opti.minimize(aero["D"] + penalty)
        out.update({"tw": tw, "aero": aero, "penalty": penalty, "wing": wing})
        return out

    def run(prob, label):
        started = time.perf_counter()
        try:
            sol = _solve(prob["opti"], {}, options)
        except RuntimeError as error:
            message = str(error).splitlines()[-1] if str(error) else repr(error)
            elapsed = time.perf_counter() - started
            print(f"{label}: FAILED ({message}) after {elapsed:.1f} s", file=sys.stderr)
            return None, {
                "label": label,
                "solved": False,
                "message": message,
                "solve_s": time.perf_counter() - started,
            }
        solve_s = time.perf_counter() - started
        stats = sol.stats()
        aero = prob["aero"]
        res = {
            "label": label,
            "solved": True,
            "solve_s": solve_s,
            "iterations": int(stats["iter_count"]),
            "return_status": stats.get("return_status"),
            "inf_pr": _final_inf_pr(sol),
            "jig_twist_deg": _floats(sol(prob["jig"])),
            "total_twist_deg": _floats(sol(prob["tw"])),
            "L": float(sol(aero["L"])),
            "D": float(sol(aero["D"])),
            "CL": float(sol(aero["CL"])),
            "CD": float(sol(aero["CD"])),
            "penalty": float(sol(prob["penalty"])),
            "objective": float(sol(aero["D"] + prob["penalty"])),
            "S_ref": float(sol(prob["wing"].area())),
        }
        if "u" in prob:
            loads = prob["loads"]
            res.update(
                {
                    "u": _floats(sol(prob["u"])),
                    "phi_deg": _floats(sol(prob["phi"])),
                    "du": _floats(sol(prob["du"])),
                    "S": _floats(sol(loads["S"])),
                    "M": _floats(sol(loads["M"])),
                    "T": _floats(sol(loads["T"])),
                }
            )
        print(
            f"{label}: D = {res['D']:.8g} N, L = {res['L']:.8g} N, tip total twist = "
            f"{res['total_twist_deg'][-1]:.6g} deg ({res['iterations']} iterations, "
            f"{solve_s:.1f} s)",
            file=sys.stderr,
        )
        return sol, res

    rigid_prob = build(flexible=False)
    rigid_sol, rigid_res = run(rigid_prob, "rigid")

    flex_prob = build(flexible=True)
    attempts = []
    flex_sol, flex_res = run(flex_prob, "flexible (from zeros)")
    attempts.append(
        {k: flex_res[k] for k in ("label", "solved", "solve_s") if k in flex_res}
        | {k: flex_res[k] for k in ("message", "iterations") if k in flex_res}
    )
    if flex_sol is None and rigid_sol is not None:
        flex_prob["opti"].set_initial(flex_prob["jig"], rigid_sol(rigid_prob["jig"]))
        flex_sol, flex_res = run(flex_prob, "flexible (from the rigid optimum)")
        attempts.append(
            {k: flex_res[k] for k in ("label", "solved", "solve_s") if k in flex_res}
            | {k: flex_res[k] for k in ("message", "iterations") if k in flex_res}
        )

    return {
        "case": case,
        "format": "design-1",
        "model": _model_fields(model, options),
        "camber_line": model.camber_line(),
        "ys": _floats(model.ys),
        "rho": float(model.make_vlm(model.make_wing(), velocity=V).op_point.atmosphere.density()),
        "rigid": rigid_res,
        "flexible": flex_res,
        "attempts": attempts,
    }


def main(argv: list[str]) -> int:
    if len(argv) != 3:
        print(__doc__.split("\n\n")[2], file=sys.stderr)
        print(f"usage: {argv[0]} CASE.json OUT.json", file=sys.stderr)
        return 2
    case = json.loads(Path(argv[1]).read_text())
    reference = generate(case)
    Path(argv[2]).write_text(json.dumps(reference, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
