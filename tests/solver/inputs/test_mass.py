"""solver.inputs.mass: the wing's mass model, validated like every input, and the sections' inertia
about the elastic axis (the parallel-axis theorem, the spar's own mass)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import solver
from solver import InvalidInput
from solver.fields import Spec, digest
from solver.inputs.mass import ConcentratedMass, MassModel, section_inertia
from tests.flutter_reference import GOLAND, goland_mass

N = 5


def test_one_number_is_every_station_and_the_arrays_are_read_only():
    mass = MassModel.create(N, 35.71, 0.43, 7.45)
    for array in (mass.mass_per_length, mass.center_of_gravity, mass.inertia_per_length):
        assert array.shape == (N,)
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 1.0
    np.testing.assert_array_equal(mass.center_of_gravity, np.full(N, 0.43))


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        pytest.param({"mass_per_length": -1.0}, "mass.mass_per_length", id="negative-mass"),
        pytest.param({"center_of_gravity": 1.2}, "mass.center_of_gravity", id="cg-off-chord"),
        pytest.param({"center_of_gravity": -0.1}, "mass.center_of_gravity", id="cg-ahead"),
        pytest.param({"inertia_per_length": -0.5}, "mass.inertia_per_length", id="neg-inertia"),
        pytest.param({"inertia_per_length": [1.0] * 4}, "mass.inertia_per_length", id="length"),
        pytest.param({"mass_per_length": math.nan}, "mass.mass_per_length", id="nan"),
        pytest.param({"mass_per_length": "heavy"}, "mass.mass_per_length", id="text"),
    ],
)
def test_an_invalid_mass_model_names_the_field(changes: dict, field: str):
    values = {"mass_per_length": 35.71, "center_of_gravity": 0.43, "inertia_per_length": 7.45}
    with pytest.raises(InvalidInput) as raised:
        MassModel.create(N, **{**values, **changes})
    assert raised.value.field == field


@pytest.mark.parametrize(
    ("arguments", "field"),
    [
        pytest.param((4.5, 10.0, 1.0, 0.1), "station", id="fractional-station"),
        pytest.param((-1, 10.0, 1.0, 0.1), "station", id="negative-station"),
        pytest.param((4, 0.0, 1.0, 0.1), "mass", id="no-mass"),
        pytest.param((4, 10.0, -1.0, 0.1), "inertia", id="negative-inertia"),
        pytest.param((4, 10.0, 1.0, math.inf), "offset", id="infinite-offset"),
    ],
)
def test_an_invalid_concentrated_mass_names_the_field(arguments: tuple, field: str):
    with pytest.raises(InvalidInput) as raised:
        ConcentratedMass.create(*arguments, path="store.")
    assert raised.value.field == f"store.{field}"


def test_a_concentrated_mass_must_sit_at_a_station_of_the_wing():
    store = ConcentratedMass.create(N, 10.0, 1.0, 0.1)  # one past the tip
    with pytest.raises(InvalidInput) as raised:
        MassModel.create(N, 35.71, 0.43, 7.45, (store,))
    assert raised.value.field == "mass.concentrated[0].station"


def test_every_field_is_declared_with_its_unit_and_limits():
    """The API's schema is derived from these declarations (solver.fields)."""
    for cls in (MassModel, ConcentratedMass):
        for field in dataclasses.fields(cls):
            if field.name == "concentrated":
                continue
            spec = field.metadata["input"]
            assert isinstance(spec, Spec) and spec.unit and spec.description
    units = {f.name: f.metadata["input"].unit for f in dataclasses.fields(ConcentratedMass)}
    assert units == {"station": "-", "mass": "kg", "inertia": "kg m^2", "offset": "m"}


def test_the_inertia_about_the_elastic_axis_adds_the_parallel_axis_term():
    """Goland's 8.64 kg m is about its elastic axis (Goland 1945 as tabulated by Eastep:
    1.943 slug ft^2/ft), with the centre of gravity 10 % chord aft of it; about the centre of
    gravity that is 7.446 kg m, a radius of gyration of 0.2497 chord, the 25 % the classical
    descriptions of the wing give."""
    mass = goland_mass(N)
    chord = np.full(N, GOLAND["chord"])
    inertia = section_inertia(mass, chord, np.full(N, GOLAND["elastic_axis"]))
    np.testing.assert_allclose(inertia.inertia, GOLAND["inertia_about_elastic_axis"], rtol=1e-14)
    np.testing.assert_allclose(inertia.static_moment, 35.71 * 0.1 * GOLAND["chord"], rtol=1e-14)
    gyration = math.sqrt(mass.inertia_per_length[0] / GOLAND["mass"]) / GOLAND["chord"]
    assert gyration == pytest.approx(0.25, abs=5e-4)


def test_on_a_swept_wing_the_offset_is_normal_to_the_axis():
    mass = MassModel.create(N, 10.0, 0.5, 1.0)
    chord, axis = np.full(N, 2.0), np.full(N, 0.3)
    swept = section_inertia(mass, chord, axis, sweep_deg=30.0)
    np.testing.assert_allclose(swept.static_moment, 10.0 * 0.2 * 2.0 * math.cos(math.radians(30)))


def test_a_tube_spar_adds_its_own_mass_on_the_elastic_axis():
    """density x wall area per unit length, and its polar inertia density x pi/32 (D^4 - d^4);
    the static moment is the non-structural mass's alone."""
    material = solver.Material(70e9, 27e9, 2700.0, 300e6)
    wing = solver.Wing.create(
        np.linspace(0, 4, N), 1.0, 0.35, spar=solver.SparDesign(0.08, 0.004, material)
    )
    spar = wing.spar
    assert spar is not None
    mass = MassModel.create(N, 2.0, 0.45, 0.05)
    inertia = section_inertia(mass, wing.chord, wing.elastic_axis, spar=spar)
    outer, inner = 0.08, 0.072
    area = math.pi / 4 * (outer**2 - inner**2)
    polar = math.pi / 32 * (outer**4 - inner**4)
    np.testing.assert_allclose(inertia.mass, 2.0 + 2700.0 * area, rtol=1e-12)
    np.testing.assert_allclose(inertia.static_moment, 2.0 * 0.1, rtol=1e-12)
    np.testing.assert_allclose(inertia.inertia, 0.05 + 2.0 * 0.1**2 + 2700.0 * polar, rtol=1e-12)


@pytest.mark.parametrize(
    ("mass", "inertia", "field"),
    [
        (0.0, 1.0, "mass.mass_per_length"),
        (10.0, 0.0, "mass.inertia_per_length"),
    ],
    ids=["massless-section", "no-inertia-about-the-centre-of-gravity"],
)
def test_a_section_without_mass_or_inertia_is_refused_for_vibration(
    mass: float, inertia: float, field: str
):
    """Its motion would need no force: the mass matrix would be singular."""
    model = MassModel.create(N, mass, 0.4, inertia)
    with pytest.raises(InvalidInput) as raised:
        section_inertia(model, np.ones(N), np.full(N, 0.3))
    assert raised.value.field == field


def test_equal_numbers_have_one_key():
    """The caches key a mass model by `solver.fields.digest`, as every input."""
    key = digest(MassModel.create(N, 35.71, 0.43, 7.45))
    assert digest(MassModel.create(N, [35.71] * N, 0.43, 7.45)) == key
    assert digest(MassModel.create(N, 35.71, 0.44, 7.45)) != key
    store = ConcentratedMass.create(4, 10.0, 1.0, 0.1)
    assert digest(MassModel.create(N, 35.71, 0.43, 7.45, (store,))) != key
