"""Index arithmetic of one mesh: where each unknown, equation and parameter sits.

N structural stations, k chordwise panels per strip, M = (N - 1) k panels on the right half.

Unknowns x (3N + M, or 5N + M with lag), in this order:
    u (N) [m]          heave at stations
    du (N) [-]         slope du/ds along the elastic axis
    phi (N) [deg]      twist about the elastic axis
    v (N) [m]          with lag: the lag displacement along e_c = e_s x n (in the wing's plane)
    psi (N) [rad]      with lag: the lag rotation about the wing's normal n
    g (M) [m]          circulation per unit airspeed of each right-half panel, Gamma / V
Equations (as many), in this order:
    root clamps (3), heave kinematics (N - 1), bending (N - 1), torsion (N - 1),
    with lag: lag clamps (2), lag kinematics (N - 1), lag bending (N - 1);
    flow tangency (M)

The beam's size is `Layout.n_structure` (3N, or 5N with lag): its unknowns `structure` and its
rows `structure_rows` both. Lag (`Layout.lag`, `solver.model.lag_beam`) exists only on the
geometrically exact beam of a wing with `in_plane_bending_stiffness`; its slot
(`LAG_SLOTS`) sits in the lag layouts' parameter vectors only, after the wing's, so every other
layout's table, and each of its libraries' numbers, is today's to the bit.

Parameters p: named slots, one table (`Slot`, `MODEL_SLOTS`, `FLOW_SLOTS`). The wing's slots
are its fields declared `compiled` (`solver.fields.parameter`, `solver.inputs.wing.Wing`), in
their declaration order, each named after its field; the model's own follow (`MODEL_OWN`: the
camber at the chordwise nodes, alpha, the torque axis). The flow model (control surfaces and
roll, `solver.model.flow`) appends its slots (`FLOW_SLOTS`) after the model's, so a slot sits
at the same place in either vector. Nothing outside this module knows where a slot sits: code
asks for `Layout.slot(name)`, packs a vector from values by name (`Layout.pack`) and reads one
by name (`Layout.unpack`, numeric or CasADi-symbolic alike). A new compiled wing field is
declared once, on the wing, and takes its slot by itself; the model version (`solver.model.version`)
digests the table, so a library compiled for another table is never loaded.

The aerodynamics (`Layout.aerodynamics`) and the beam (`Layout.beam`: "linear" or
"geometrically_exact", `solver.model.exact_beam`, whose slope unknown is the bending rotation
beta [rad]) change what the rows say, never where anything sits. The aerodynamics: "lattice"
(the horseshoe lattice, every panel seeing every horseshoe) or "strip"
(strip theory: each strip a two-dimensional airfoil, `solver.model.strip`).
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Literal

import numpy as np

from solver.fields import specs
from solver.inputs.wing import Wing

__all__ = [
    "AERODYNAMICS",
    "STRUCTURES",
    "FLOW_SLOTS",
    "LAG_SLOTS",
    "MODEL_OWN",
    "MODEL_SLOTS",
    "WING_SLOTS",
    "Aerodynamics",
    "Layout",
    "Parameters",
    "Slot",
    "Structure",
]

Aerodynamics = Literal["lattice", "strip"]
AERODYNAMICS: tuple[Aerodynamics, ...] = ("lattice", "strip")
Structure = Literal["linear", "geometrically_exact"]
STRUCTURES: tuple[Structure, ...] = ("linear", "geometrically_exact")

# How many numbers a slot holds: one per station (N), the camber's N (k + 1) (station-major:
# station i's k + 1 chordwise nodes at i (k + 1) ..), one, or one per unknown (3N + M).
Size = Literal["station", "camber", "scalar", "unknowns"]


@dataclass(frozen=True)
class Slot:
    """One named part of the compiled model's parameter vector: its size kind (`Size`), unit
    and description."""

    name: str
    size: Size
    unit: str
    description: str


# A compiled wing field's form -> its slot's size.
_SIZE_OF_FORM: dict[str, Size] = {
    "positions": "station",
    "per_station": "station",
    "number": "scalar",
}


def _wing_slots() -> tuple[Slot, ...]:
    """The wing's fields declared `compiled`, in declaration order."""
    slots = []
    for name, spec in specs(Wing).items():
        if not spec.compiled:
            continue
        if spec.form not in _SIZE_OF_FORM:
            raise TypeError(f"Wing.{name}: a compiled field is a number or per station")
        slots.append(Slot(name, _SIZE_OF_FORM[spec.form], spec.unit, spec.description))
    return tuple(slots)


WING_SLOTS = _wing_slots()
MODEL_OWN = (
    Slot(
        "camber",
        "camber",
        "-",
        "camber / chord at each station's chordwise nodes (the airfoil and the flaps; the "
        "flow model's antisymmetric right half adds its ailerons')",
    ),
    Slot("alpha", "scalar", "deg", "angle of attack"),
    Slot(
        "deformed_axis",
        "scalar",
        "-",
        "0: torque about the undeformed elastic axis, 1: about the heaved one",
    ),
)
MODEL_SLOTS = WING_SLOTS + MODEL_OWN


def _lag_slots() -> tuple[Slot, ...]:
    """The wing's in-plane stiffness, a slot of the lag layouts only (`Layout.lag`)."""
    spec = specs(Wing)["in_plane_bending_stiffness"]
    return (Slot("in_plane_bending_stiffness", "station", spec.unit, spec.description),)


LAG_SLOTS = _lag_slots()
FLOW_SLOTS = (
    Slot(
        "image",
        "scalar",
        "-",
        "+1 the mirror (symmetric flow), -1 the rotation about x (antisymmetric flow)",
    ),
    Slot(
        "image_jacobian",
        "scalar",
        "-",
        "the weight of the image's own derivatives: equal to image for the exact Jacobian "
        "(`solver.model.flow_vlm`)",
    ),
    Slot(
        "roll_rate",
        "scalar",
        "rad/m",
        "p / V, a steady roll rate about x per unit airspeed",
    ),
    Slot(
        "control",
        "camber",
        "1/rad",
        "the direction d(camber)/d(deflection) of the control derivatives, station-major",
    ),
    Slot(
        "direction",
        "unknowns",
        "-",
        "a direction in the unknowns along which the panel loads' derivatives are returned "
        "(a roll answer's linearised loads)",
    ),
)


class Parameters:
    """A parameter vector's slots by name, as attributes (`Layout.unpack`): numpy views of a
    numeric vector or slices of a CasADi symbol. A per-station slot is (N,), the camber and the
    control (N (k + 1),) station-major, a scalar one a number (a 1 x 1 symbol)."""

    def __init__(self, values: Mapping[str, Any]) -> None:
        self.__dict__.update(values)

    def __getattr__(self, name: str) -> Any:
        raise AttributeError(f"the parameters have no slot {name!r}")

    def replace(self, **values: Any) -> Parameters:
        """The same slots, some given anew (an image half's own camber)."""
        unknown = set(values) - set(self.__dict__)
        if unknown:
            raise KeyError(f"no parameter slot {sorted(unknown)[0]!r}")
        return Parameters(self.__dict__ | values)


@dataclass(frozen=True)
class Layout:
    """The mesh of N structural stations and its (N - 1) k panels, and the aerodynamics on it."""

    n: int
    chordwise: int = 1
    aerodynamics: Aerodynamics = "lattice"
    beam: Structure = "linear"
    # Lag (in-plane) bending: two more unknowns and row sets per station
    # (`solver.model.lag_beam`); the exact beam's only.
    lag: bool = False

    def __post_init__(self) -> None:
        if self.lag and self.beam != "geometrically_exact":
            raise ValueError("lag bending is the geometrically exact beam's")

    @property
    def exact(self) -> bool:
        """The geometrically exact beam (`solver.model.exact_beam`): the slope unknown is the
        bending rotation [rad], the heave's kinematics and the load rows exact."""
        return self.beam == "geometrically_exact"

    @property
    def n_panels(self) -> int:
        """M: panels of the right half-wing."""
        return (self.n - 1) * self.chordwise

    @property
    def n_strips(self) -> int:
        return self.n - 1

    @property
    def n_structure(self) -> int:
        """The beam's unknowns and rows: 3N (u, beta, phi), 5N with lag (and v, psi)."""
        return (5 if self.lag else 3) * self.n

    @property
    def n_unknowns(self) -> int:
        return self.n_structure + self.n_panels

    @property
    def tag(self) -> str:
        """The mesh's name in the compiled functions' names: N_k, and _strip for strip theory."""
        strip = "_strip" if self.aerodynamics == "strip" else ""
        exact = "_exact" if self.exact else ""
        lag = "_lag" if self.lag else ""
        return f"{self.n}_{self.chordwise}{strip}{exact}{lag}"

    # Unknowns
    @property
    def heave(self) -> slice:
        return slice(0, self.n)

    @property
    def slope(self) -> slice:
        return slice(self.n, 2 * self.n)

    @property
    def twist(self) -> slice:
        """The twist about the elastic axis, phi [deg]."""
        return slice(2 * self.n, 3 * self.n)

    @property
    def lag_displacement(self) -> slice:
        """With lag: v [m] along e_c (`solver.model.lag_beam`); empty without."""
        return slice(3 * self.n, 4 * self.n) if self.lag else slice(3 * self.n, 3 * self.n)

    @property
    def lag_rotation(self) -> slice:
        """With lag: psi [rad] about the wing's normal; empty without."""
        return slice(4 * self.n, 5 * self.n) if self.lag else slice(3 * self.n, 3 * self.n)

    @property
    def circulation(self) -> slice:
        return slice(self.n_structure, self.n_structure + self.n_panels)

    @property
    def structure(self) -> slice:
        """Unknowns of the beam: heave, slope and twist (and with lag v, psi)."""
        return slice(0, self.n_structure)

    # Equations
    @property
    def bending_rows(self) -> slice:
        return slice(3 + self.n_strips, 3 + 2 * self.n_strips)

    @property
    def torsion_rows(self) -> slice:
        return slice(3 + 2 * self.n_strips, 3 + 3 * self.n_strips)

    @property
    def lag_kinematics_rows(self) -> slice:
        """With lag: v_{i+1} - v_i - (r_{i+1} - r_i) . e_c (after the lag clamps); empty
        without."""
        start = 3 * self.n + 2
        return slice(start, start + self.n_strips) if self.lag else slice(3 * self.n, 3 * self.n)

    @property
    def lag_bending_rows(self) -> slice:
        """With lag: psi_{i+1} - psi_i - h_i/2 (psi'_i + psi'_{i+1}); empty without."""
        start = 3 * self.n + 2 + self.n_strips
        return slice(start, start + self.n_strips) if self.lag else slice(3 * self.n, 3 * self.n)

    @property
    def structure_rows(self) -> slice:
        """Equations of the beam: clamps, kinematics, bending, torsion (and the lag's)."""
        return slice(0, self.n_structure)

    @property
    def tangency_rows(self) -> slice:
        return slice(self.n_structure, self.n_structure + self.n_panels)

    @cached_property
    def load_rows(self) -> np.ndarray:
        """Equations in which the aerodynamic loads appear (J1's only non-zero rows): bending
        and torsion, and with lag the lag bending rows; read-only, built once per layout (every
        stability verdict reads it)."""
        # The torsion rows follow the bending rows.
        load_rows = np.arange(self.bending_rows.start, self.torsion_rows.stop)
        if self.lag:
            rows = self.lag_bending_rows
            load_rows = np.concatenate([load_rows, np.arange(rows.start, rows.stop)])
        load_rows.setflags(write=False)
        return load_rows

    # Parameters
    def size(self, slot: Slot) -> int:
        """How many numbers `slot` holds on this mesh."""
        return {
            "station": self.n,
            "camber": self.n * (self.chordwise + 1),
            "scalar": 1,
            "unknowns": self.n_unknowns,
        }[slot.size]

    @cached_property
    def _places(self) -> dict[str, slice]:
        """Every slot's place, the model's then the flow model's."""
        places, start = {}, 0
        for slot in self.table(flow=True):
            places[slot.name] = slice(start, start + self.size(slot))
            start += self.size(slot)
        return places

    def slot(self, name: str) -> slice:
        """Where slot `name` sits (in the model's vector, and at the same place in the flow
        model's)."""
        place = self._places.get(name)
        if place is None:
            raise KeyError(f"no parameter slot {name!r}")
        return place

    def length(self, name: str) -> int:
        """How many numbers slot `name` holds on this mesh."""
        place = self.slot(name)
        return place.stop - place.start

    @property
    def n_parameters(self) -> int:
        """The length of the model's parameter vector."""
        return self._places[MODEL_OWN[-1].name].stop

    @property
    def n_flow_parameters(self) -> int:
        """How many parameters the flow model adds after the model's."""
        return self._places[FLOW_SLOTS[-1].name].stop - self.n_parameters

    def table(self, flow: bool = False) -> tuple[Slot, ...]:
        """The slots of the model's parameter vector (with `flow`: the flow model's), in order:
        the wing's, with lag its in-plane stiffness (`LAG_SLOTS`), the model's own."""
        model = WING_SLOTS + (LAG_SLOTS if self.lag else ()) + MODEL_OWN
        return model + FLOW_SLOTS if flow else model

    @staticmethod
    def wing_values(wing: Wing) -> dict[str, Any]:
        """The wing's compiled fields by name, what `pack` takes of a wing (with its in-plane
        stiffness when it has one: a lag layout's slot)."""
        values = {slot.name: getattr(wing, slot.name) for slot in WING_SLOTS}
        if wing.in_plane_bending_stiffness is not None:
            values["in_plane_bending_stiffness"] = wing.in_plane_bending_stiffness
        return values

    def pack(self, values: Mapping[str, Any], flow: bool = False) -> np.ndarray:
        """(n_parameters,), or with `flow` the flow model's (n_parameters + n_flow_parameters,),
        from every slot's value by name (a scalar slot a number or a flag, an array slot any
        shape of its size: the camber (N, k + 1) is laid station-major). Raises `KeyError`
        naming a missing or an unknown slot, `ValueError` one of the wrong size."""
        table = self.table(flow)
        names = {slot.name for slot in table}
        unknown = set(values) - names
        if unknown:
            raise KeyError(f"no parameter slot {sorted(unknown)[0]!r}")
        missing = [slot.name for slot in table if slot.name not in values]
        if missing:
            raise KeyError(f"parameter slot {missing[0]!r} is not given")
        p = np.empty(self._places[table[-1].name].stop)
        for slot in table:
            value = np.ravel(np.asarray(values[slot.name], dtype=float))
            if value.size != self.size(slot):
                raise ValueError(
                    f"parameter slot {slot.name!r} holds {self.size(slot)} numbers, "
                    f"given {value.size}"
                )
            p[self._places[slot.name]] = value
        return p

    def unpack(self, p: Any) -> Parameters:
        """The slots of a parameter vector (numpy, or a CasADi SX or MX column) by name: the
        model's, and the flow model's when `p` is the flow model's."""
        length = int(p.shape[0])
        if length not in (self.n_parameters, self.n_parameters + self.n_flow_parameters):
            raise ValueError(f"a parameter vector of this mesh has no length {length}")
        table = self.table(length > self.n_parameters)
        values = {}
        for slot in table:
            place = self._places[slot.name]
            values[slot.name] = p[place.start] if slot.size == "scalar" else p[place]
        return Parameters(values)

    # The positional forms the parameter vector had before its slots were named: kept for a
    # release, each warns (the Python package's public API changes by addition).

    def parameters(
        self,
        arrays: tuple[np.ndarray, ...],
        camber: np.ndarray,
        alpha_deg: float,
        sweep_deg: float,
        deformed_axis: bool,
    ) -> np.ndarray:
        """Deprecated (`pack`): the parameter vector from the six station arrays y, chord,
        elastic_axis, EI, GJ, jig_twist, the camber (N, k + 1), alpha and sweep [deg] and the
        torque axis; every other compiled field at its default."""
        _deprecated("Layout.parameters(...)", "Layout.pack({name: value, ...})")
        positional: tuple[str, ...] = ("y", "chord", "elastic_axis", "bending_stiffness")
        positional += ("torsional_stiffness", "jig_twist")
        values: dict[str, Any] = {
            slot.name: np.full(self.size(slot), _default(slot.name)) for slot in WING_SLOTS
        }
        values |= dict(zip(positional, arrays, strict=True))
        values |= {"sweep": sweep_deg, "camber": camber, "alpha": alpha_deg}
        return self.pack(values | {"deformed_axis": 1.0 if deformed_axis else 0.0})

    def split(self, p):  # type: ignore[no-untyped-def]
        """Deprecated (`unpack`): y, chord, elastic_axis, EI, GJ, jig (N each), camber
        (N (k + 1)), alpha, sweep, deformed_axis."""
        _deprecated("Layout.split(p)", "Layout.unpack(p)")
        part = self.unpack(p[: self.n_parameters])
        return (
            part.y,
            part.chord,
            part.elastic_axis,
            part.bending_stiffness,
            part.torsional_stiffness,
            part.jig_twist,
            part.camber,
            part.alpha,
            part.sweep,
            part.deformed_axis,
        )

    def flow_parameters(
        self,
        image: float = 1.0,
        image_jacobian: float = 1.0,
        roll_rate: float = 0.0,
        control: np.ndarray | None = None,
        direction: np.ndarray | None = None,
    ) -> np.ndarray:
        """Deprecated (`pack(..., flow=True)`): the flow model's part of its parameter vector,
        control and direction default zero."""
        _deprecated("Layout.flow_parameters(...)", "Layout.pack({...}, flow=True)")
        start, stop = self.n_parameters, self.n_parameters + self.n_flow_parameters
        values: dict[str, Any] = {slot.name: np.zeros(self.size(slot)) for slot in MODEL_SLOTS}
        values |= {"image": image, "image_jacobian": image_jacobian, "roll_rate": roll_rate}
        values["control"] = np.zeros(self.length("control")) if control is None else control
        values["direction"] = np.zeros(self.n_unknowns) if direction is None else direction
        return self.pack(values, flow=True)[start:stop]

    def split_flow(self, p):  # type: ignore[no-untyped-def]
        """Deprecated (`unpack`): image, image_jacobian, roll_rate, control, direction."""
        _deprecated("Layout.split_flow(p)", "Layout.unpack(p)")
        part = self.unpack(p)
        return part.image, part.image_jacobian, part.roll_rate, part.control, part.direction

    @property
    def alpha_index(self) -> int:
        """Deprecated (`slot("alpha")`): where alpha [deg] sits."""
        _deprecated("Layout.alpha_index", 'Layout.slot("alpha")')
        return self.slot("alpha").start

    @property
    def roll_rate_index(self) -> int:
        """Deprecated (`slot("roll_rate")`): where p / V [rad/m] sits."""
        _deprecated("Layout.roll_rate_index", 'Layout.slot("roll_rate")')
        return self.slot("roll_rate").start

    @property
    def control_slice(self) -> slice:
        """Deprecated (`slot("control")`)."""
        _deprecated("Layout.control_slice", 'Layout.slot("control")')
        return self.slot("control")

    @property
    def direction_slice(self) -> slice:
        """Deprecated (`slot("direction")`)."""
        _deprecated("Layout.direction_slice", 'Layout.slot("direction")')
        return self.slot("direction")

    @property
    def camber_slice(self) -> slice:
        """Deprecated (`slot("camber")`)."""
        _deprecated("Layout.camber_slice", 'Layout.slot("camber")')
        return self.slot("camber")


def _default(name: str) -> float:
    """A compiled wing field's default, for the deprecated positional forms."""
    field = next(f for f in dataclasses.fields(Wing) if f.name == name)
    return 0.0 if field.default is dataclasses.MISSING or field.default is None else field.default


def _deprecated(old: str, new: str) -> None:
    warnings.warn(f"{old} is deprecated: use {new}", DeprecationWarning, stacklevel=3)
