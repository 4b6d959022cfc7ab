"""solver.sizing.cases: every point of every V-n diagram as a load case, at its weight,
altitude, equivalent and true airspeed, named apart."""

from __future__ import annotations

import math

import pytest

from solver.inputs.envelope import FlightEnvelope
from solver.sizing import cases as sizing_cases
from solver.sizing import vn
from tests.solver.sizing.aircraft import G0, LIGHT, RHO0, RHO_3000


def test_the_load_cases_are_every_point_at_every_weight_and_altitude():
    envelope = FlightEnvelope(**{**LIGHT, "weights": [1100.0 * G0, 900.0 * G0]})
    cases = sizing_cases.load_cases(envelope)
    diagrams = vn.vn_diagrams(envelope)
    assert len(diagrams) == 4
    assert len(cases) == sum(len(d.points) for d in diagrams) == 4 * 10
    names = [case.name for case in cases]
    assert len(set(names)) == len(names)
    assert names[0] == "A+ at V_A, 1 100 kg, 0 m"
    assert "gust C- at V_C, 900 kg, 3 000 m" in names
    high = [case for case in cases if case.altitude == 3000.0]
    for case in high:
        # rho V_TAS^2 = rho0 V_EAS^2, rho the ISA's at 3,000 m (table, 5 digits).
        assert case.density == pytest.approx(RHO_3000, rel=1e-5)
        assert case.density * case.true_airspeed**2 == pytest.approx(
            RHO0 * case.equivalent_airspeed**2, rel=1e-14
        )
    light_g = next(c for c in cases if c.name == "G- at V_G, 900 kg, 0 m")
    assert light_g.weight == 900.0 * G0 and light_g.kind == "manoeuvre"
    # V_A at each weight (V_S sqrt(n)); V_C and V_D from the maximum take-off weight.
    a = {c.weight: c.equivalent_airspeed for c in cases if c.point == "A+" and c.altitude == 0}
    assert a[900.0 * G0] == pytest.approx(a[1100.0 * G0] * math.sqrt(900 / 1100), rel=1e-14)


def test_close_weights_are_named_apart():
    envelope = FlightEnvelope(**{**LIGHT, "weights": [1100.0 * G0, 1100.4 * G0]})
    names = {case.name.split(", ")[1] for case in sizing_cases.load_cases(envelope)}
    assert names == {"1 100.0 kg", "1 100.4 kg"}
