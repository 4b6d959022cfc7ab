"""Hostile requests and what the service must answer (issue 5, part 3), shared by
tests/app/test_hostile_input.py and benchmarks/hostile_input_benchmark.py.

Each `Hostile` is one request (method, path, a body built on demand) and the problem the
service documents for it; `Memory` reads a server process's resident and peak memory from /proc.
Limits are the defaults: 1,000,000-byte bodies, N <= 150 stations, <= 50 sweep points.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from tests import study

MAX_BODY_BYTES = 1_000_000
MAX_STATIONS = 150
MAX_SWEEP_POINTS = 50

Body = bytes | Callable[[], Iterable[bytes]]


@dataclass(frozen=True)
class Hostile:
    """A request and the answer it must get: `status`, problem `kind`, and (for invalid input)
    the `fields` the problem must name (a subset check). `status` 200 means it must succeed."""

    name: str
    path: str
    body: Callable[[], Body]
    status: int
    kind: str | None = None
    fields: frozenset[str] = field(default_factory=frozenset)


def _json(value: Any) -> bytes:
    return json.dumps(value).encode()


def _solve(**changes: Any) -> dict[str, Any]:
    """The study's solve request at 10 m/s with top-level members or wing members replaced."""
    body = study.solve_request(10.0)
    for key, value in changes.items():
        if key in body["wing"]:
            body["wing"][key] = value
        elif key in body["flight"]:
            body["flight"][key] = value
        else:
            body[key] = value
    return body


def _replace_token(body: dict[str, Any], marker: float, token: str) -> bytes:
    """JSON text of `body` with the number `marker` written as a raw token (NaN, Infinity...)."""
    text = json.dumps(body)
    assert text.count(repr(marker)) == 1
    return text.replace(repr(marker), token).encode()


def _chunks(total: int, size: int = 1 << 20) -> Callable[[], Iterator[bytes]]:
    def generate() -> Iterator[bytes]:
        for _ in range(total // size):
            yield b" " * size

    return generate


def _nested(depth: int, open_: bytes, close: bytes, inner: bytes = b"") -> bytes:
    return open_ * depth + inner + close * depth


def _numbers(count: int, token: bytes = b"0") -> bytes:
    return b"[" + b",".join([token] * count) + b"]"


def _with_raw_list(member: bytes, raw: bytes) -> bytes:
    """The study's solve request with wing member `member` replaced by raw JSON text."""
    text = _json(_solve(**{member.decode(): 12345.678}))
    return text.replace(b"12345.678", raw)


def _sweep(velocities: Any) -> dict[str, Any]:
    return {"wing": study.wing_json(), "flight": {"alpha": 5.0}, "velocities": velocities}


MARK = 98765.4321  # a number replaced by a raw token in the JSON text

HOSTILE: list[Hostile] = [
    # --- bodies of many megabytes
    Hostile("50MB_declared", "/solve", lambda: b" " * 50_000_000, 413, "body-too-large"),
    Hostile("50MB_chunked", "/solve", lambda: _chunks(50_000_000), 413, "body-too-large"),
    Hostile("1e6_element_array", "/solve", lambda: _with_raw_list(b"y", _numbers(10**6)), 413,
            "body-too-large"),
    Hostile("3e5_element_array", "/solve", lambda: _with_raw_list(b"y", _numbers(300_000)), 422,
            "invalid-input", frozenset({"wing.y"})),
    # --- deeply nested JSON (each under the body limit)
    Hostile("nested_arrays_100k", "/solve", lambda: _nested(100_000, b"[", b"]"), 422,
            "invalid-input", frozenset({"body"})),
    Hostile("nested_in_wing_100k", "/solve",
            lambda: _with_raw_list(b"y", _nested(100_000, b"[", b"]", b"0")), 422,
            "invalid-input", frozenset({"body"})),
    Hostile("nested_objects_50k", "/sweep", lambda: _nested(50_000, b'{"a":', b"}", b"1"), 422,
            "invalid-input", frozenset({"body"})),
    # --- NaN and Infinity tokens where finite numbers belong
    Hostile("NaN_velocity", "/solve",
            lambda: _replace_token(_solve(velocity=MARK), MARK, "NaN"), 422, "invalid-input",
            frozenset({"flight.velocity"})),
    Hostile("minus_Infinity_alpha", "/solve",
            lambda: _replace_token(_solve(alpha=MARK), MARK, "-Infinity"), 422, "invalid-input",
            frozenset({"flight.alpha"})),
    Hostile("1e999_density", "/solve",
            lambda: _replace_token(_solve(density=MARK), MARK, "1e999"), 422, "invalid-input",
            frozenset({"flight.density"})),
    Hostile("Infinity_stiffness", "/solve",
            lambda: _replace_token(_solve(torsional_stiffness=[1e3] * 29 + [MARK]), MARK,
                                   "Infinity"), 422, "invalid-input",
            frozenset({"wing.torsional_stiffness[29]"})),
    Hostile("NaN_tolerance", "/solve",
            lambda: _replace_token(_solve(options={"tolerance": MARK}), MARK, "NaN"), 422,
            "invalid-input", frozenset({"options.tolerance"})),
    Hostile("NaN_initial_twist", "/solve",
            lambda: _replace_token(
                _solve(initial_guess={"heave": [0.0] * 30, "twist": [0.0] * 29 + [MARK]}),
                MARK, "NaN"), 422, "invalid-input", frozenset({"initial_guess.twist[29]"})),
    Hostile("NaN_sweep_velocity", "/sweep",
            lambda: _replace_token(_sweep([10.0, MARK]), MARK, "NaN"), 422, "invalid-input",
            frozenset({"velocities[1]"})),
    # --- strings and other types where numbers belong
    Hostile("word_velocity", "/solve", lambda: _json(_solve(velocity="ten")), 422,
            "invalid-input", frozenset({"flight.velocity"})),
    Hostile("empty_string_chord", "/solve",
            lambda: _json(_solve(chord=[*study.wing_json()["chord"][:29], ""])), 422,
            "invalid-input", frozenset({"wing.chord[29]"})),
    Hostile("object_alpha", "/solve", lambda: _json(_solve(alpha={"value": 5})), 422,
            "invalid-input", frozenset({"flight.alpha"})),
    Hostile("null_y", "/solve", lambda: _json(_solve(y=None)), 422, "invalid-input",
            frozenset({"wing.y"})),
    Hostile("string_wing", "/solve", lambda: _json(_solve(wing="study")), 422, "invalid-input",
            frozenset({"wing"})),
    # --- at the limits and one past
    Hostile("N_150", "/solve", lambda: _json(_solve(wing=study.wing_json(n=MAX_STATIONS))), 200),
    Hostile("N_151", "/solve", lambda: _json(_solve(wing=study.wing_json(n=MAX_STATIONS + 1))), 422,
            "invalid-input", frozenset({"wing.y"})),
    Hostile("sweep_50_points", "/sweep",
            lambda: _json(_sweep(np.linspace(5, 21, MAX_SWEEP_POINTS).tolist())), 200),
    Hostile("sweep_51_points", "/sweep",
            lambda: _json(_sweep(np.linspace(5, 21, MAX_SWEEP_POINTS + 1).tolist())), 422,
            "invalid-input", frozenset({"velocities"})),
    Hostile("sweep_range_50", "/sweep",
            lambda: _json(_sweep({"start": 4, "stop": 20, "count": MAX_SWEEP_POINTS})), 200),
    Hostile("sweep_range_51", "/sweep",
            lambda: _json(_sweep({"start": 4, "stop": 20, "count": MAX_SWEEP_POINTS + 1})), 422,
            "invalid-input", frozenset({"velocities.count"})),
]  # fmt: skip

# Lax coercion: values of the wrong JSON type that pydantic converts instead of rejecting.
WRONG_TYPES: list[Hostile] = [
    Hostile("numeric_string_velocity", "/solve", lambda: _json(_solve(velocity="10")), 422,
            "invalid-input", frozenset({"flight.velocity"})),
    Hostile("numeric_string_in_chord", "/solve",
            lambda: _json(_solve(chord=[*study.wing_json()["chord"][:29], "0.15"])), 422,
            "invalid-input", frozenset({"wing.chord[29]"})),
    Hostile("boolean_velocity", "/solve", lambda: _json(_solve(velocity=True)), 422,
            "invalid-input", frozenset({"flight.velocity"})),
    Hostile("string_max_iterations", "/solve",
            lambda: _json(_solve(options={"max_iterations": "30"})), 422, "invalid-input",
            frozenset({"options.max_iterations"})),
    Hostile("yes_find_fold", "/solve", lambda: _json(_solve(options={"find_fold": "yes"})), 422,
            "invalid-input", frozenset({"options.find_fold"})),
    Hostile("numeric_string_sweep_velocity", "/sweep", lambda: _json(_sweep([10.0, "12"])), 422,
            "invalid-input", frozenset({"velocities[1]"})),
]  # fmt: skip

# 330,000 invalid list items in a 1 MB body: one field error each.
AMPLIFIER = Hostile(
    "330k_invalid_items",
    "/solve",
    lambda: _with_raw_list(b"chord", _numbers(330_000, b"-1")),
    422,
    "invalid-input",
    frozenset({"wing.chord"}),  # too long (app.settings.MAX_ARRAY_LENGTH): items never judged
)
# As many bad items as an array may hold: each is judged, the problem lists the first few.
MANY_INVALID_ITEMS = Hostile(
    "1000_invalid_items",
    "/solve",
    lambda: _with_raw_list(b"chord", _numbers(1000, b"-1")),
    422,
    "invalid-input",
    frozenset({"wing.chord[0]"}),
)
AMPLIFIER_LIMIT_BYTES = 64 * 1024  # a problem naming the first bad items and the count suffices


@dataclass(frozen=True)
class Memory:
    """Resident (VmRSS) and peak (VmHWM) memory of a process, in bytes, from /proc."""

    pid: int

    def _status(self, key: str) -> int:
        for line in Path(f"/proc/{self.pid}/status").read_text().splitlines():
            if line.startswith(key + ":"):
                return int(line.split()[1]) * 1024
        raise KeyError(key)

    @property
    def resident(self) -> int:
        return self._status("VmRSS")

    @property
    def peak(self) -> int:
        return self._status("VmHWM")

    def reset_peak(self) -> None:
        """Start a new peak from the current resident size (Linux >= 4.0, same user)."""
        Path(f"/proc/{self.pid}/clear_refs").write_text("5")
