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

Input: a case file (JSON object)
    name              str, optional
    span              [m] full span; stations are y = linspace(0, span / 2, N)
    chords            (N,) [m] chord at each station
    x_ea_over_chord   [-] elastic-axis position as a fraction of chord (one number)
    EI, GJ            (N,) [N m^2] bending and torsional stiffness at each station
    alpha_deg         [deg] angle of attack of the jig shape
    velocities        [m/s] airspeeds, solved in this order
    fail_velocities   [m/s], optional: airspeeds expected to have no equilibrium; attempted after
                      `velocities`, in order, and recorded under `failures` if IPOPT fails
    airfoil           str, optional, default "dae11" (the study's). It must have zero camber at
                      x/c = 0 and 1 (dae11, naca0012, ...): flexwing does not model camber, which
                      the one-panel mesh would see only at those two points.

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


def _floats(values) -> list[float]:
    return [float(v) for v in np.asarray(values, dtype=float).ravel()]


def generate(case: dict) -> dict:
    chords = np.array(case["chords"], dtype=float)
    N = len(chords)
    span = float(case["span"])
    ys = np.linspace(0, span / 2, N)
    x_ea_over_chord = float(case["x_ea_over_chord"])
    EI = np.array(case["EI"], dtype=float)
    GJ = np.array(case["GJ"], dtype=float)
    alpha = float(case["alpha_deg"])
    airfoil = asb.Airfoil(case.get("airfoil", "dae11"))
    if len(EI) != N or len(GJ) != N:
        raise ValueError("chords, EI and GJ must have the same length")

    def make_wing(heave=None, twist=None) -> asb.Wing:
        """The study's make_wing: jig shape + heave [m] + twist [deg] about the elastic axis."""
        if heave is None:
            heave = np.zeros(N)
        if twist is None:
            twist = np.zeros(N)
        xsecs = []
        for i in range(N):
            xyz_le = np.array([-chords[i] * x_ea_over_chord, ys[i], 0])
            xyz_le = np.rotation_matrix_3D(angle=np.radians(twist[i]), axis="y") @ xyz_le
            xyz_le += np.array([0, 0, heave[i]])
            xsecs.append(
                asb.WingXSec(xyz_le=xyz_le, chord=chords[i], twist=twist[i], airfoil=airfoil)
            )
        return asb.Wing(symmetric=True, xsecs=xsecs)

    def make_vlm(wing, velocity) -> asb.VortexLatticeMethod:
        return asb.VortexLatticeMethod(
            airplane=asb.Airplane(wings=[wing], xyz_ref=[0, 0, 0]),
            op_point=asb.OperatingPoint(velocity=velocity, alpha=alpha),
            spanwise_resolution=1,
            chordwise_resolution=1,
        )

    # Velocities keep their JSON spelling (10 stays 10) in the output.
    attempts = list(case["velocities"]) + list(case.get("fail_velocities", []))

    # Rigid baseline: the jig shape at the first velocity.
    wing_jig = make_wing()
    vlm_rigid = make_vlm(wing_jig, velocity=float(attempts[0]))
    aero_rigid = vlm_rigid.run()
    if not np.all(np.diff(vlm_rigid.vortex_centers[: N - 1, 1]) > 0):
        raise RuntimeError("the VLM did not order the right half-wing's panels root to tip")
    rigid = {
        "velocity": attempts[0],
        "L": float(aero_rigid["L"]),
        "CL": float(aero_rigid["CL"]),
        "D": float(aero_rigid["D"]),
        "Fz": _floats(vlm_rigid.forces_geometry[: N - 1, 2]),
        "S_ref": float(wing_jig.area()),
    }
    rho = float(vlm_rigid.op_point.atmosphere.density())

    # The coupled problem (study section 14.4).
    opti = asb.Opti()
    u = opti.variable(init_guess=np.zeros(N))  # heave [m]
    theta = opti.variable(init_guess=np.zeros(N))  # twist [deg]
    velocity = opti.parameter(value=float(attempts[0]))  # [m/s]

    vlm = make_vlm(make_wing(heave=u, twist=theta), velocity=velocity)
    aero = vlm.run()

    Fz = vlm.forces_geometry[: N - 1, 2]
    tau = vlm.moments_geometry[: N - 1, 1]
    y_panel = vlm.vortex_centers[: N - 1, 1]
    outboard = (np.arange(N - 1)[None, :] >= np.arange(N)[:, None]).astype(float)
    S = outboard @ Fz
    M = outboard @ (Fz * y_panel) - ys * S
    T = outboard @ tau

    du = opti.derivative_of(u, with_respect_to=ys, derivative_init_guess=np.zeros(N))
    opti.constrain_derivative(variable=du, with_respect_to=ys, derivative=M / EI)
    opti.constrain_derivative(variable=theta, with_respect_to=ys, derivative=np.degrees(T / GJ))
    opti.subject_to([u[0] == 0, du[0] == 0, theta[0] == 0])

    equilibria = []
    failures = []
    last_sol = None
    for V in attempts:
        if last_sol is not None:
            opti.set_initial_from_sol(last_sol)
        started = time.perf_counter()
        try:
            sol = opti.solve(parameter_mapping={velocity: float(V)}, verbose=False)
        except RuntimeError as error:
            message = str(error).splitlines()[-1] if str(error) else repr(error)
            failures.append({"velocity": V, "solved": False, "message": message})
            print(f"V = {V:g} m/s: FAILED ({message})", file=sys.stderr)
            continue
        solve_s = time.perf_counter() - started
        last_sol = sol
        u_sol = sol(u)
        theta_sol = sol(theta)
        equilibria.append(
            {
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
        )
        print(
            f"V = {V:g} m/s: L = {equilibria[-1]['L']:.6g} N, tip twist = "
            f"{theta_sol[-1]:.6g} deg ({equilibria[-1]['iterations']} IPOPT iterations)",
            file=sys.stderr,
        )

    return {
        "case": case,
        "rho": rho,
        "ys": _floats(ys),
        "rigid": rigid,
        "equilibria": equilibria,
        "failures": failures,
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
