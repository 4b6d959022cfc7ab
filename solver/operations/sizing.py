"""The sizing question: the loads envelope of a wing over its load cases (`LoadsInput`): the
cases given, and those an envelope description derives (every corner and gust point of its V-n
diagrams, at every weight and altitude). Each case is one equilibrium of the flexible wing
(`CaseInput`, what a worker runs), and the envelope is assembled from their loads: the service
spreads the cases over its workers, and `run()` answers the whole in one process."""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from solver import fields
from solver.errors import DynamicInstability, InvalidInput, NoEquilibrium, SolverError
from solver.fields import parameter
from solver.gusts.analysis import gust_analysis
from solver.inputs.atmosphere import SEA_LEVEL_DENSITY
from solver.inputs.envelope import FlightEnvelope
from solver.inputs.flight import FlightCondition
from solver.inputs.gust import GustCondition
from solver.inputs.load_case import FlightCase
from solver.inputs.options import SolverOptions, check_lag
from solver.inputs.wing import Wing
from solver.operations.common import check_meshed
from solver.results.quantities import Progress
from solver.results.sizing import (
    CaseKind,
    CaseLoads,
    CaseStatus,
    LoadsEnvelope,
    LoadsInfo,
    VnBoundary,
)
from solver.sizing.case_loads import case_loads
from solver.sizing.cases import load_cases
from solver.sizing.envelope import correlated_loads, spanwise_envelope, spar_envelope
from solver.sizing.vn import vn_diagrams
from solver.statics.jig import at_rest
from solver.statics.system import CoupledSystem

__all__ = ["CaseInput", "GustCaseInput", "LoadsInput"]

# [1/rad] thin-airfoil theory's 2 pi: only to count a V-n diagram's points (`case_count`).
_NOMINAL_LIFT_SLOPE = 2.0 * math.pi


@dataclass(frozen=True, eq=False)
class CaseInput:
    """One load case to fly: what a worker runs of a `LoadsInput` (`run` gives its
    `CaseLoads`)."""

    wing: Wing
    name: str
    kind: CaseKind
    flight: FlightCondition  # trimmed, or at alpha 0: the zero-lift alpha's (no lift to trim to)
    weight: float  # [N]
    options: SolverOptions
    aileron: float = 0.0  # [deg]
    roll_rate: float = 0.0  # [rad/s]

    @cached_property
    def key(self) -> bytes:
        described = (self.wing, self.name, self.kind, self.flight, self.weight, self.options)
        return fields.digest((*described, self.aileron, self.roll_rate))

    def run(self, progress: Progress | None = None) -> CaseLoads:
        return case_loads(
            self.wing,
            self.name,
            self.kind,
            self.flight,
            self.options,
            weight=self.weight,
            aileron=self.aileron,
            roll_rate=self.roll_rate,
        )


@dataclass(frozen=True, eq=False)
class GustCaseInput:
    """One side of a gust condition: what a worker runs of a `LoadsInput`'s `gusts` (`run`
    gives its `CaseLoads`: the 1-cos gusts' total loads, each station's largest (`up`) or
    smallest (down) over every gradient and time, kind gust_dynamic)."""

    wing: Wing
    condition: GustCondition
    up: bool
    options: SolverOptions

    @property
    def name(self) -> str:
        return f"{self.condition.name} {'up' if self.up else 'down'}"

    @property
    def kind(self) -> CaseKind:
        return "gust_dynamic"

    @cached_property
    def key(self) -> bytes:
        return fields.digest((self.wing, self.condition, self.up, self.options))

    def run(self, progress: Progress | None = None) -> CaseLoads:
        started = time.perf_counter()
        flight = self.condition.flight
        velocity = flight.velocity or 0.0
        described = CaseLoads(
            name=self.name,
            kind=self.kind,
            status="equilibrium",
            velocity=velocity,
            equivalent_airspeed=velocity * math.sqrt(flight.density / SEA_LEVEL_DENSITY),
            density=flight.density,
            weight=flight.weight or 0.0,
            load_factor=1.0,
        )
        try:
            result = gust_analysis(self.wing, flight, self.condition.gust, self.options)
        except SolverError as error:
            status: CaseStatus = (
                "unstable"
                if isinstance(error, DynamicInstability)
                else "no_equilibrium"
                if isinstance(error, NoEquilibrium)
                else "not_converged"
            )
            return dataclasses.replace(
                described,
                status=status,
                reason=str(error),
                solve_time=time.perf_counter() - started,
            )
        side = "max" if self.up else "min"
        envelope = result.envelope
        factors = [c.max_load_factor if self.up else c.min_load_factor for c in result.gusts]
        return dataclasses.replace(
            described,
            load_factor=max(factors) if self.up else min(factors),
            alpha=result.alpha,
            shear=getattr(envelope, f"{side}_shear"),
            bending_moment=getattr(envelope, f"{side}_bending_moment"),
            torque=getattr(envelope, f"{side}_torque"),
            solve_time=time.perf_counter() - started,
        )


@dataclass(frozen=True, eq=False)
class LoadsInput:
    """Sizing loads: every case flown on the flexible wing (its own mass under the load factor
    with `wing.mass`), the envelope along the span, correlated loads, the spar's margins."""

    wing: Wing = parameter(
        "", "the wing, with its mass for inertia relief", form="nested", given=Wing
    )
    cases: tuple[FlightCase, ...] = parameter(
        "",
        "load cases as given, each a named trimmed flight (at most FLEXWING_MAX_LOAD_CASES, "
        "with the envelope's)",
        form="items",
        given=FlightCase,
        default=(),
    )
    envelope: FlightEnvelope | None = parameter(
        "",
        "a flight envelope: its V-n diagrams' corners and gust points, at every weight and "
        "altitude, are cases too",
        form="nested",
        given=FlightEnvelope,
        default=None,
        example={
            "weights": [300.0],
            "altitudes": [0.0],
            "category": "normal",
            "cl_max": 1.2,
            "cl_min": -0.6,
            "cruise_speed": 12.0,
            "dive_speed": 16.0,
        },
    )
    gusts: tuple[GustCondition, ...] = parameter(
        "",
        "flights whose flexible-wing 1-cos gust loads (as POST /gust answers them: 1 g plus "
        "the gusts of every gradient, up and down) join the envelope as two cases each, "
        "'<name> up' and '<name> down' (kind gust_dynamic); needs wing.mass",
        form="items",
        given=GustCondition,
        default=(),
    )
    stations: tuple[int, ...] | None = parameter(
        "-",
        "stations whose bending moment and torque are correlated over the cases (indices, 0 "
        "the root; null: the root and mid-span)",
        form="indices",
        default=None,
        example=[0, 10],
    )
    options: SolverOptions | None = parameter(
        "", "optional solver options", form="nested", given=SolverOptions, default=None
    )

    def __post_init__(self) -> None:
        check_meshed(self.wing, self.options)
        check_lag(
            self.wing.in_plane_bending_stiffness,
            self.options,
            "the gust conditions' loads (/loads' gusts)" if self.gusts else "",
        )
        if not self.cases and self.envelope is None and not self.gusts:
            raise InvalidInput("cases", "give load cases, an envelope, or both")
        if self.gusts and self.wing.mass is None:
            raise InvalidInput("wing.mass", "is required: gust loads need the wing's mass")
        names = [case.name for case in self.cases]
        for i, gust in enumerate(self.gusts):
            if gust.name in [g.name for g in self.gusts[:i]]:
                raise InvalidInput(f"gusts[{i}].name", f"{gust.name!r} names another too")
        for i, name in enumerate(names):
            if name in names[:i]:
                raise InvalidInput(f"cases[{i}].name", f"{name!r} names another case too")
        # Counting the cases draws the V-n diagrams: an envelope that does not fit this wing is
        # refused here, before any work.
        _ = self.case_count
        n = self.wing.n_stations
        for i, station in enumerate(self.correlated_stations):
            if not 0 <= station < n:
                raise InvalidInput(f"stations[{i}]", f"must be a station index below {n}")

    @property
    def modelled(self) -> SolverOptions:
        return self.options or SolverOptions()

    @property
    def correlated_stations(self) -> tuple[int, ...]:
        return self.stations or (0, (self.wing.n_stations - 1) // 2)

    @cached_property
    def key(self) -> bytes:
        described = (self.wing, self.cases, self.envelope, self.correlated_stations)
        # Without gust conditions the key is what it was before they existed.
        gusts = (self.gusts,) if self.gusts else ()
        return fields.digest((*described, self.modelled, *gusts))

    @cached_property
    def case_count(self) -> int:
        """[-] how many cases `plan` holds, given and derived, without the work of deriving
        them: which points a V-n diagram has does not depend on the lift slope (only where its
        gust points are), so a nominal one counts them."""
        if self.envelope is None:
            return len(self.cases) + 2 * len(self.gusts)
        wing = self.wing
        derived = load_cases(
            self.envelope,
            wing_area=wing.planform_area,
            mean_chord=wing.mean_chord,
            lift_slope=self.envelope.lift_slope or _NOMINAL_LIFT_SLOPE,
        )
        return len(self.cases) + len(derived) + 2 * len(self.gusts)

    @cached_property
    def plan(self) -> tuple[CaseInput | GustCaseInput, ...]:
        """Every case to fly, given, derived, then the gust conditions' (up, down), in order."""
        given = [
            CaseInput(
                self.wing,
                case.name,
                "given",
                case.flight,
                case.flight.weight or case.flight.required_lift or 0.0,
                self.modelled,
                case.aileron,
                case.roll_rate,
            )
            for case in self.cases
        ]
        gusts = [
            GustCaseInput(self.wing, condition, up, self.modelled)
            for condition in self.gusts
            for up in (True, False)
        ]
        return (*given, *self._derived(), *gusts)

    def _derived(self) -> list[CaseInput]:
        if self.envelope is None:
            return []
        wing = self.wing
        derived = []
        for case in load_cases(
            self.envelope,
            wing_area=wing.planform_area,
            mean_chord=wing.mean_chord,
            lift_slope=self.lift_slope,
        ):
            if case.load_factor == 0:  # no lift to trim to: the rigid wing's zero-lift alpha
                flight = FlightCondition(case.true_airspeed, 0.0, case.density)
            else:
                flight = FlightCondition(
                    case.true_airspeed,
                    density=case.density,
                    weight=case.weight,
                    load_factor=case.load_factor,
                )
            kind: CaseKind = "gust" if case.kind == "gust" else "manoeuvre"
            derived.append(CaseInput(wing, case.name, kind, flight, case.weight, self.modelled))
        return derived

    @cached_property
    def lift_slope(self) -> float:
        """[1/rad] the rigid wing's lift-curve slope at alpha 0 (the lattice's, both halves
        over the planform area): what Pratt's gust factors take where the envelope gives none."""
        rest = at_rest(CoupledSystem.of(self.wing, 0.0, self.modelled))
        return float(rest.lift_gradient @ rest.sin_state) / self.wing.planform_area

    def run(self, progress: Progress | None = None) -> LoadsEnvelope:
        """The answer, every case flown here in turn (`progress(done, total)` as each is)."""
        answers = []
        for done, piece in enumerate(self.plan, start=1):
            answers.append(piece.run())
            if progress is not None:
                progress(done, len(self.plan))
        return self.assemble(answers)

    def assemble(self, answers: Sequence[CaseLoads]) -> LoadsEnvelope:
        """The envelope of the cases' loads `answers` (one per case of `plan`, in order, each
        its `run()`, wherever it ran)."""
        started = time.perf_counter()
        cases = list(answers)
        y = self.wing.y
        diagrams = []
        if self.envelope is not None:
            for diagram in vn_diagrams(
                self.envelope,
                wing_area=self.wing.planform_area,
                mean_chord=self.wing.mean_chord,
                lift_slope=self.lift_slope,
            ):
                diagrams.append(
                    VnBoundary(
                        weight=diagram.weight,
                        altitude=diagram.altitude,
                        airspeed=np.asarray(diagram.boundary_airspeed),
                        load_factor=np.asarray(diagram.boundary_load_factor),
                        points=[p.name for p in diagram.points],
                        point_airspeed=np.array([p.airspeed for p in diagram.points]),
                        point_load_factor=np.array([p.load_factor for p in diagram.points]),
                    )
                )
        return LoadsEnvelope(
            cases=cases,
            envelope=spanwise_envelope(y, cases),
            correlated=list(correlated_loads(y, cases, self.correlated_stations)),
            spar=spar_envelope(self.wing, cases),
            vn=diagrams,
            info=LoadsInfo(
                cases=len(cases),
                answered=sum(case.answered for case in cases),
                solve_time=sum(case.solve_time for case in cases) + time.perf_counter() - started,
            ),
        )
