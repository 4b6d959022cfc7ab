"""solver.inputs.airfoil: NACA 4-digit mean lines, tabulated camber lines, and what is refused."""

from __future__ import annotations

import numpy as np
import pytest

from solver import InvalidInput
from solver.inputs.airfoil import camber_line


def test_the_naca_4412_mean_line_peaks_at_4_percent_at_40_percent_chord():
    line = camber_line("NACA4412")
    x = np.linspace(0.0, 1.0, 1001)
    camber = line.at(x)
    assert camber[0] == 0.0 and abs(camber[-1]) < 1e-15  # on the chord line at both edges
    assert x[np.argmax(camber)] == pytest.approx(0.4, abs=1e-3)
    assert np.max(camber) == pytest.approx(0.04, rel=1e-12)
    assert line.thickness == 0.12


def test_the_naca_mean_line_is_smooth_where_its_two_parabolas_meet():
    """Both parabolas reach m at p with zero slope (Abbott and von Doenhoff, 6.4)."""
    line, h = camber_line("naca2412"), 1e-7
    below, at, above = line.at(np.array([0.4 - h, 0.4, 0.4 + h]))
    assert at == pytest.approx(0.02, rel=1e-12)
    assert (at - below) / h == pytest.approx(0.0, abs=1e-5)
    assert (above - at) / h == pytest.approx(0.0, abs=1e-5)


@pytest.mark.parametrize("spec", [None, "naca0012", "naca0006"], ids=["none", "0012", "0006"])
def test_a_symmetric_section_has_no_camber(spec: str | None):
    assert np.all(camber_line(spec).at(np.linspace(0.0, 1.0, 11)) == 0.0)


def test_a_table_is_linear_between_its_points():
    line = camber_line({"x": [0.0, 0.5, 1.0], "camber": [0.0, 0.02, 0.0]})
    np.testing.assert_allclose(line.at([0.25, 0.5, 0.75]), [0.01, 0.02, 0.01], rtol=1e-15)
    assert line.x.flags.writeable is False and line.camber.flags.writeable is False


def test_equal_lines_have_equal_keys_and_different_ones_do_not():
    assert camber_line("naca4412").key == camber_line("NACA4412").key
    assert camber_line("naca4412").key != camber_line("naca2412").key
    table = {"x": [0.0, 1.0], "camber": [0.0, 0.0]}
    assert camber_line(table).key != camber_line("naca4412").key


@pytest.mark.parametrize(
    ("spec", "reason"),
    [
        ("naca44121", "NACA 4-digit"),
        ("naca4012", "both zero or not"),
        ({"x": [0.0, 1.0], "camber": [0.0]}, "one length"),
        ({"x": [0.1, 1.0], "camber": [0.0, 0.0]}, "from 0 to 1"),
        ({"x": [0.0, 1.0], "camber": [0.0, 0.3]}, "within +-0.2"),
        ({"x": [0.0, 1.0], "camber": [0.0, float("nan")]}, "finite"),
        (42, "must be null"),
    ],
    ids=[
        "five-digits",
        "camber-without-position",
        "lengths",
        "not-from-0",
        "too-much",
        "nan",
        "a-number",
    ],
)
def test_what_cannot_be_a_camber_line_is_invalid_input_naming_the_field(spec, reason):
    with pytest.raises(InvalidInput) as raised:
        camber_line(spec, field="airfoil[3]")
    assert raised.value.field == "airfoil[3]" and reason in raised.value.reason
