"""The unsteady lattice's transfer functions: the aerodynamic loads of harmonic motion of a
wing's natural modes and of a vertical gust at a set of reduced frequencies, about the jig or
a static equilibrium (`solver.dynamics.lattice_loads`): what a frequency-domain gust or loads
analysis needs, as Nastran's generalised aerodynamic matrices of the modes and of a gust's
upwash (MSC Nastran Aeroelastic Analysis User's Guide, section 2.5).

A gust w_g e^{i omega (t - x / V)} meets each panel at its own collocation point's delay, so a
long wing or a swept one is not met everywhere at once.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from solver.dynamics.lattice_loads import lattice_loads
from solver.dynamics.modes import Structure, largest_edge_displacement, mode_shape, structure
from solver.errors import InvalidInput, numerical_failures_as
from solver.fields import is_number
from solver.inputs.mass import MassModel
from solver.inputs.options import SolverOptions
from solver.inputs.wing import Wing
from solver.results.aerodynamic_forces import GeneralisedAerodynamicForces
from solver.results.equilibrium import Equilibrium
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem
from solver.unsteady_lattice.panels import panels
from solver.unsteady_lattice.wake import shed_wake

__all__ = ["MAX_REDUCED_FREQUENCY", "MAX_TRANSFER_FREQUENCIES", "generalised_aerodynamic_forces"]

# The largest reduced frequency answered: past it a lattice of at most 8 chordwise panels
# resolves no wave on the chord (FlutterOptions.max_reduced_frequency's limit).
MAX_REDUCED_FREQUENCY = 10.0
# The most reduced frequencies in one call (each is one solve of the lattice).
MAX_TRANSFER_FREQUENCIES = 200


def generalised_aerodynamic_forces(
    wing: Wing,
    reduced_frequencies: Sequence[float],
    *,
    mass: MassModel | None = None,
    modes: int | None = None,
    options: SolverOptions | None = None,
    equilibrium: Equilibrium | None = None,
) -> GeneralisedAerodynamicForces:
    """The unsteady lattice's loads of harmonic motion of the lowest `modes` natural modes of
    `wing` with `mass` (default: six, or all of a mesh with fewer) and of a unit vertical gust
    angle, at each of `reduced_frequencies` (k = omega b / V, b half the mean chord; 0 is the
    static lattice's loads), about the unloaded jig or the static `equilibrium` of the same
    wing and `options` (chordwise panels, torque axis; the aerodynamics is the lattice's).

    Raises `InvalidInput` for reduced frequencies outside 0 to `MAX_REDUCED_FREQUENCY` or more
    than `MAX_TRANSFER_FREQUENCIES` of them, a mode count beyond the mesh's, or no mass."""
    reduced = _reduced(reduced_frequencies)
    options = options or SolverOptions()
    beam = structure(wing, mass)
    count = min(6, beam.n_dof) if modes is None else modes
    if not (isinstance(count, int) and 1 <= count <= beam.n_dof):
        raise InvalidInput("modes", f"must be a whole number from 1 to {beam.n_dof}")
    if equilibrium is None:
        system = CoupledSystem.of(wing, 0.0, options)
        evaluation = at_rest(system).evaluation
    else:
        system = CoupledSystem.of(wing, equilibrium.totals.alpha, options)
        evaluation = system.evaluate(equilibrium.state)
    semichord = wing.mean_chord / 2
    with numerical_failures_as(0.0):
        jig = panels(wing, options.chordwise_panels)
        loads = lattice_loads(beam, system.layout, evaluation, jig)
        shapes, scales, frequencies = _modes(beam, count)
        wake = shed_wake(jig, reduced / semichord)
        dof = loads.modal(wake, shapes)  # (K, n, r): loads, left = identity
    kappa = reduced / semichord
    harmonic = dof.stiffness + 1j * kappa[:, None, None] * dof.damping
    harmonic = harmonic - kappa[:, None, None] ** 2 * dof.inertia + loads.geometric @ shapes
    _, _, left = beam.modes
    left = left[:, :count] / scales  # left.T M shapes = I
    return GeneralisedAerodynamicForces(
        reduced_frequency=reduced,
        reference_semichord=semichord,
        modes=[mode_shape(beam, shapes[:, i], float(frequencies[i])) for i in range(count)],
        modal=left.T @ harmonic,
        modal_gust=dof.gust @ left,
        loads=harmonic,
        gust_loads=dof.gust,
    )


def _reduced(values: Sequence[float]) -> np.ndarray:
    """(K,) the reduced frequencies, checked."""
    items = list(values)
    if not 1 <= len(items) <= MAX_TRANSFER_FREQUENCIES:
        raise InvalidInput(
            "reduced_frequencies", f"must list 1 to {MAX_TRANSFER_FREQUENCIES} reduced frequencies"
        )
    for index, value in enumerate(items):
        if not (is_number(value) and 0.0 <= value <= MAX_REDUCED_FREQUENCY):
            raise InvalidInput(
                f"reduced_frequencies[{index}]",
                f"must be a number from 0 to {MAX_REDUCED_FREQUENCY:g}",
            )
    return np.array(items, dtype=float)


def _modes(beam: Structure, count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The lowest `count` modes' shapes (n, r), each scaled to a largest edge displacement of
    1 m (`solver.dynamics.modes.natural_modes`), the scales applied (r,) and the frequencies
    (r,) [rad/s]."""
    omega2, right, _ = beam.modes
    scales = np.array([1.0 / largest_edge_displacement(beam, right[:, i]) for i in range(count)])
    return right[:, :count] * scales, scales, np.sqrt(omega2[:count])
