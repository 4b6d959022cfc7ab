"""A published flexible-wing gust response: SHARPy's prismatic AR 16 cantilever in a 1-cos gust
(Palacios and Cesnik, Dynamics of Flexible Aircraft, 2023, example 9.1; the script and its
output in ImperialCollegeLondon/sharpy_cases, AR16wing/dynamic_gust.py and
output/dynamic_gust/WriteVariablesTime/struct_pos_node21.dat): chord 1 m, semispan 16 m, elastic
axis and centre of gravity at mid-chord, EI 2e4 N m^2, GJ 1e4 N m^2, 0.75 kg/m, 0.1 kg m, at
5 m/s, rho = 1 kg/m^3, alpha 10 deg, clamped; a 1-cos gust 20 m long (H = 10 m) of 0.5 m/s.
SHARPy (geometrically exact beam, UVLM): the tip rises from 4.820 m to 5.634 m, +0.814 m, its
peak at step 83 of 0.04 s (3.32 s).

The model differs: a linear beam about an equilibrium whose tip is 26 % of the semispan up
(SHARPy's 30 %; past the 10 % of the `large_deflection` finding), the lattice's quasi-steady
loading with the strips' Wagner and Kuessner lags for SHARPy's unsteady wake. The peak's time is
the gust's and the first mode's (2.24 rad/s) and is held to 2 %; its height to 20 % (measured
+13.7 %, the linear beam's missing geometric stiffening at that deflection: the two static
tips themselves differ by 13 %)."""

from __future__ import annotations

import numpy as np
import pytest

import solver
from solver.gusts.discrete import discrete_response, peaks
from solver.gusts.model import gust_model

SHARPY_TIP_RISE = 5.633716 - 4.819825  # [m]
SHARPY_PEAK_TIME = 83 * 0.04  # [s]


def test_the_ar16_wings_tip_rises_as_sharpy_computed() -> None:
    wing = solver.Wing.create(
        np.linspace(0.0, 16.0, 33),
        1.0,
        0.5,
        2e4,
        1e4,
        mass={"mass_per_length": 0.75, "center_of_gravity": 0.5, "inertia_per_length": 0.1},
    )
    model = gust_model(wing, solver.FlightCondition(5.0, 10.0, 1.0), None, 4, clamped=True)
    model.check_stable()
    response = discrete_response(model, 10.0, 0.5)
    tip = response.outputs[model.output_slices["tip_heave"]]
    assert peaks(tip)[0] == pytest.approx(SHARPY_TIP_RISE, rel=0.20)
    assert response.time[np.argmax(tip)] == pytest.approx(SHARPY_PEAK_TIME, rel=0.02)
