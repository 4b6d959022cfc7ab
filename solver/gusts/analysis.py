"""The gust loads of one flight condition: the model (`solver.gusts.model`), the CS-25.341(a)
1-cos gusts over the gradients with the tuned ones (`solver.gusts.discrete`), continuous
turbulence (`solver.gusts.turbulence`); with the unsteady lattice the frequency-domain model
(`solver.gusts.lattice_model`) and its responses (`solver.gusts.frequency_response`); the 1 g
trimmed loads they add to, and Pratt's K_g beside the model's load factor.

The search for the tuned gust evaluates every gradient asked (20 from 9 to 107 m by default)
and reports, per load quantity, the one giving its largest value: a grid search, as Nastran's
and LoadsKernel's users run it; the gradient spacing (5.2 m by default) bounds how far the
tuned gradient can be from the true one, and the peak load is flat there (it is a maximum).
"""

from __future__ import annotations

import math
import time

import numpy as np

from solver.dynamics.aerodynamic_forces import MAX_REDUCED_FREQUENCY
from solver.gusts.discrete import DiscreteResponse, discrete_response, peaks, profile_response
from solver.gusts.frequency_response import (
    lattice_a_bar,
    lattice_discrete_responses,
    lattice_profile_response,
    resolved_frequency,
    top_frequency,
)
from solver.gusts.lattice_model import LatticeGustModel, lattice_gust_model
from solver.gusts.model import GustModel, gust_model
from solver.gusts.profiles import (
    GRADIENT_RANGE,
    design_gust_velocity,
    flight_profile_alleviation,
    reference_gust_velocity,
    turbulence_intensity,
)
from solver.gusts.turbulence import a_bar
from solver.inputs.atmosphere import SEA_LEVEL_DENSITY
from solver.inputs.flight import FlightCondition
from solver.inputs.gust import GustSettings
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.results.gusts import GustCase, GustLoadCase, GustResult, TurbulenceLoads
from solver.sizing.gusts import gust_alleviation_factor, gust_mass_ratio, sharp_edged_gust_increment

__all__ = ["gust_analysis", "gust_load_cases"]

_HISTORY = 200  # samples kept of each time history
# [rad] a gust angle past which attached, linear lift is no longer a fair model (~10 deg).
_LINEAR_ANGLE = 0.17
# The share of A-bar from the lattice's unresolved frequencies past which the answer says so.
_UNRESOLVED = 0.05


def gust_analysis(
    wing: Wing,
    flight: FlightCondition,
    settings: GustSettings | None = None,
    options: SolverOptions | None = None,
) -> GustResult:
    """The gust loads of `wing` (with its mass) in `flight` (trimmed to the aircraft's weight)
    for the gusts of `settings` (`GustResult`). Raises `DynamicInstability` past flutter or
    divergence, `InvalidInput` without mass or weight."""
    started = time.perf_counter()
    check_lag(wing.in_plane_bending_stiffness, options, "gust loads")
    settings = settings or GustSettings()
    unsteady = (options or SolverOptions()).aerodynamics == "unsteady_lattice"
    model: GustModel | LatticeGustModel
    if unsteady:
        top = top_frequency(flight.velocity or 1.0, settings.min_gradient)
        model = lattice_gust_model(
            wing, flight, options, settings.modes, settings.clamped, top_frequency=top
        )
    else:
        model = gust_model(wing, flight, options, settings.modes, settings.clamped)
    model.check_stable()
    eas = model.velocity * math.sqrt(model.density / SEA_LEVEL_DENSITY)
    to_true = math.sqrt(SEA_LEVEL_DENSITY / model.density)  # EAS -> TAS
    dive = settings.speed == "dive"
    reference = reference_gust_velocity(settings.altitude, dive)
    alleviation = settings.alleviation
    if settings.weights is not None and settings.max_altitude is not None:
        takeoff, landing, zero_fuel = settings.weights
        alleviation = flight_profile_alleviation(
            takeoff, landing, zero_fuel, settings.max_altitude, settings.altitude
        )
    gradients = np.linspace(settings.min_gradient, settings.max_gradient, settings.gradients)
    slices = model.output_slices
    n = wing.n_stations
    stations = model.equilibrium.stations
    one_g = np.r_[stations.shear, stations.bending_moment, stations.torque]
    cases = []
    upper, lower = np.full(3 * n, -np.inf), np.full(3 * n, np.inf)
    amplitudes = [
        design_gust_velocity(gradient, reference, alleviation) * to_true for gradient in gradients
    ]
    if isinstance(model, LatticeGustModel):
        responses = lattice_discrete_responses(model, gradients, np.array(amplitudes))
    else:
        responses = [
            discrete_response(model, float(gradient), amplitude)
            for gradient, amplitude in zip(gradients, amplitudes, strict=True)
        ]
    for gradient, response in zip(gradients, responses, strict=True):
        high, low = peaks(response.outputs)
        upper = np.maximum(upper, np.maximum(high[: 3 * n], -low[: 3 * n]))
        lower = np.minimum(lower, np.minimum(low[: 3 * n], -high[: 3 * n]))
        name = f"1-cos H = {gradient:.3g} m up at {eas:.4g} m/s EAS"
        cases.append(_case(model, response, high, low, name))
    profile = None
    if settings.profile_time is not None and settings.profile_velocity is not None:
        given = np.array(settings.profile_time), np.array(settings.profile_velocity)
        response = (
            lattice_profile_response(model, *given)
            if isinstance(model, LatticeGustModel)
            else profile_response(model, *given)
        )
        high, low = peaks(response.outputs)
        # A given gust is answered as given (not mirrored: it need not be symmetric).
        upper = np.maximum(upper, high[: 3 * n])
        lower = np.minimum(lower, low[: 3 * n])
        profile = _case(model, response, high, low, f"given profile at {eas:.4g} m/s EAS")
    root_moment = [float(case.max_bending_moment[0]) for case in cases]
    root_torque = [max(abs(case.max_torque[0]), abs(case.min_torque[0])) for case in cases]
    tuned_n = int(np.argmax([case.max_load_factor for case in cases]))
    envelope = GustLoadCase(
        name=f"1-cos gusts at {eas:.4g} m/s EAS",
        y=wing.y,
        max_shear=one_g[:n] + upper[:n],
        min_shear=one_g[:n] + lower[:n],
        max_bending_moment=one_g[n : 2 * n] + upper[n : 2 * n],
        min_bending_moment=one_g[n : 2 * n] + lower[n : 2 * n],
        max_torque=one_g[2 * n :] + upper[2 * n :],
        min_torque=one_g[2 * n :] + lower[2 * n :],
    )
    wing_loading = model.weight / wing.planform_area
    chord = wing.mean_chord
    mass_ratio = gust_mass_ratio(wing_loading, model.density, chord, model.lift_slope)
    k_g = gust_alleviation_factor(mass_ratio)
    tuned = cases[tuned_n]
    pratt = 1.0 + sharp_edged_gust_increment(
        wing_loading, eas, tuned.gust_velocity / to_true, model.lift_slope, k_g
    )
    turbulence = None
    findings = _findings(settings, max(c.gust_velocity for c in cases) / model.velocity)
    if isinstance(model, LatticeGustModel) and model.dropped:
        findings.append(
            f"{model.dropped} of the modes asked for left out: their reduced frequencies lie "
            f"past the unsteady lattice's largest ({MAX_REDUCED_FREQUENCY:g}), where it "
            "resolves no aerodynamics"
        )
    if settings.turbulence:
        if isinstance(model, LatticeGustModel):
            abar = lattice_a_bar(model)
            findings += _unresolved(model, abar)
        else:
            abar = a_bar(model)
        intensity = turbulence_intensity(settings.altitude, dive) * alleviation
        spread = intensity * abar[: 3 * n]
        turbulence = TurbulenceLoads(
            intensity=intensity,
            load_factor=float(abar[slices["load_factor"]]),  # type: ignore[index]
            shear=abar[:n],
            bending_moment=abar[n : 2 * n],
            torque=abar[2 * n : 3 * n],
            max_shear=one_g[:n] + spread[:n],
            min_shear=one_g[:n] - spread[:n],
            max_bending_moment=one_g[n : 2 * n] + spread[n : 2 * n],
            min_bending_moment=one_g[n : 2 * n] - spread[n : 2 * n],
            max_torque=one_g[2 * n :] + spread[2 * n :],
            min_torque=one_g[2 * n :] - spread[2 * n :],
        )
    return GustResult(
        velocity=model.velocity,
        equivalent_airspeed=eas,
        density=model.density,
        weight=model.weight,
        alpha=model.equilibrium.totals.alpha,
        clamped=model.clamped,
        reference_velocity=reference,
        alleviation=alleviation,
        lift_slope=model.lift_slope,
        mass_ratio=mass_ratio,
        pratt_alleviation=k_g,
        pratt_load_factor=pratt,
        frequencies=model.frequencies,
        y=wing.y,
        one_g_shear=stations.shear,
        one_g_bending_moment=stations.bending_moment,
        one_g_torque=stations.torque,
        gusts=cases,
        profile=profile,
        tuned_load_factor=tuned_n,
        tuned_bending_moment=int(np.argmax(root_moment)),
        tuned_torque=int(np.argmax(root_torque)),
        envelope=envelope,
        turbulence=turbulence,
        findings=findings,
        solve_time=time.perf_counter() - started,
    )


def _unresolved(model: LatticeGustModel, abar: np.ndarray) -> list[str]:
    """A finding when continuous turbulence's A-bar of the load factor takes more than
    `_UNRESOLVED` of its value from gusts shorter than the lattice resolves (four chordwise
    panels per wavelength: past that the lattice's gust lift does not fall as Sears' does)."""
    limit = resolved_frequency(model)
    within = lattice_a_bar(model, limit)
    index = model.output_slices["load_factor"]
    full, resolved = float(abar[index]), float(within[index])  # type: ignore[index]
    if full <= 0 or resolved >= (1 - _UNRESOLVED) * full:
        return []
    return [
        f"continuous turbulence: {1 - resolved / full:.0%} of the load factor's A-bar comes "
        f"from frequencies above {limit:.3g} rad/s, gusts shorter than four chordwise panels "
        "of the unsteady lattice: more chordwise panels resolve them"
    ]


def _case(
    model: GustModel | LatticeGustModel,
    response: DiscreteResponse,
    high: np.ndarray,
    low: np.ndarray,
    name: str,
) -> GustCase:
    n = model.wing.n_stations
    s = model.output_slices
    times, outputs = response.time, response.outputs
    keep = np.unique(np.linspace(0, times.size - 1, min(_HISTORY, times.size)).astype(int))
    nf, th, tw = s["load_factor"], s["tip_heave"], s["tip_twist"]
    return GustCase(
        name=name,
        gradient=float(response.gradient),
        gust_velocity=float(response.amplitude),
        max_load_factor=1.0 + float(high[nf]),  # type: ignore[index]
        min_load_factor=1.0 + float(low[nf]),  # type: ignore[index]
        max_shear=high[:n],
        min_shear=low[:n],
        max_bending_moment=high[n : 2 * n],
        min_bending_moment=low[n : 2 * n],
        max_torque=high[2 * n : 3 * n],
        min_torque=low[2 * n : 3 * n],
        max_tip_heave=float(high[th]),  # type: ignore[index]
        time=times[keep],
        load_factor=1.0 + outputs[nf, keep],  # type: ignore[index]
        tip_heave=outputs[th, keep],  # type: ignore[index]
        tip_twist=outputs[tw, keep],  # type: ignore[index]
        root_shear=outputs[0, keep],
        root_bending_moment=outputs[n, keep],
        root_torque=outputs[2 * n, keep],
    )


def _findings(settings: GustSettings, gust_angle: float) -> list[str]:
    """What the answer says of itself: gusts outside the regulation's gradients, a clamped
    root, gust angles past linear aerodynamics (the model is linear in the gust)."""
    low, high = GRADIENT_RANGE
    findings = []
    if gust_angle > _LINEAR_ANGLE:
        findings.append(
            f"largest gust angle U_ds / V = {gust_angle:.3g} rad: past the linear "
            f"aerodynamics (about {_LINEAR_ANGLE:g} rad; a real wing may stall), the loads "
            "scale linearly with the gust"
        )
    if settings.min_gradient < low or settings.max_gradient > high:
        findings.append(
            f"gust gradients outside CS-25.341(a)'s {low:g} to {high:g} m: answered, outside "
            "the regulation"
        )
    if settings.clamped:
        findings.append("clamped root: a wind-tunnel model, not the free aircraft's loads")
    return findings


def gust_load_cases(
    wing: Wing,
    flight: FlightCondition,
    gust: GustSettings | None = None,
    options: SolverOptions | None = None,
) -> tuple[GustLoadCase, ...]:
    """The loads envelope's gust cases: the 1-cos gusts' total loads (1 g plus the tuned gusts,
    up and down) and, when asked, continuous turbulence's design loads, each with y and its
    max and min shear, bending moment and torque."""
    result = gust_analysis(wing, flight, gust, options)
    cases = [result.envelope]
    if result.turbulence is not None:
        t = result.turbulence
        cases.append(
            GustLoadCase(
                name=f"continuous turbulence at {result.equivalent_airspeed:.4g} m/s EAS",
                y=result.y,
                max_shear=t.max_shear,
                min_shear=t.min_shear,
                max_bending_moment=t.max_bending_moment,
                min_bending_moment=t.min_bending_moment,
                max_torque=t.max_torque,
                min_torque=t.min_torque,
            )
        )
    return tuple(cases)
