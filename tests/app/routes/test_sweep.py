"""POST /sweep against a live server: the study's sweep, its divergence estimates, the fold."""

from __future__ import annotations

import httpx
import pytest

from tests import study


def _sweep(client: httpx.Client, velocities: object, **extra: object) -> dict:
    body = {"wing": study.wing_json(), "flight": {"alpha": 5.0, "density": study.DENSITY}}
    response = client.post("/sweep", json=body | {"velocities": velocities} | extra)
    assert response.status_code == 200, response.text
    return response.json()


def test_study_sweep_cl_twist_and_divergence(client: httpx.Client) -> None:
    order = [10, 6, 12, 15, 18, 20]  # the study's V_all, in its order
    result = _sweep(client, order)
    points = result["points"]
    assert [p["velocity"] for p in points] == order
    for point in points:
        assert point["status"] == "equilibrium"
        cl, twist = study.SWEEP[point["velocity"]]
        totals = point["equilibrium"]["totals"]
        # The study prints CL to 3 decimals (on the deformed area) and twist to 2.
        assert totals["CL_deformed_area"] == pytest.approx(cl, abs=0.0005)
        assert totals["tip_twist"] == pytest.approx(twist, abs=0.005)
        assert point["equilibrium"]["stability"]["stable"] is True
    divergence = result["divergence"]
    # The study's fit over these six points: intercept 0.998, q_div 419 Pa, V_div 26.2 m/s.
    fit = divergence["fit"]
    assert fit["points_used"] == 6
    assert fit["intercept"] == pytest.approx(0.998, abs=0.0005)
    assert fit["dynamic_pressure"] == pytest.approx(419, abs=0.5)
    assert fit["velocity"] == pytest.approx(26.2, abs=0.05)
    # Linear divergence at the jig: 359.3 Pa, 24.22 m/s; the fold between 21.43 and 21.45 m/s.
    assert divergence["linear"]["dynamic_pressure"] == pytest.approx(359.3, abs=0.05)
    assert divergence["linear"]["velocity"] == pytest.approx(24.22, abs=0.005)
    assert 21.43 < divergence["fold"]["velocity"] < 21.45
    assert divergence["fold"]["reason"] is None


def test_points_past_the_fold_say_no_equilibrium(client: httpx.Client) -> None:
    result = _sweep(client, [20, 21, 22, 23])
    statuses = [p["status"] for p in result["points"]]
    assert statuses == ["equilibrium", "equilibrium", "no_equilibrium", "no_equilibrium"]
    fold = result["divergence"]["fold"]["velocity"]
    for point in result["points"][2:]:
        assert point["equilibrium"] is None
        assert point["no_equilibrium"]["fold_velocity"] == fold
        assert "fold" in point["no_equilibrium"]["reason"]
    # The study's reference: tip twist 18.17 deg at 21 m/s.
    assert result["points"][1]["equilibrium"]["totals"]["tip_twist"] == pytest.approx(
        18.17, abs=0.005
    )


def test_velocity_range_and_cache(client: httpx.Client) -> None:
    first = _sweep(client, {"start": 6, "stop": 18, "count": 5})
    assert [p["velocity"] for p in first["points"]] == [6, 9, 12, 15, 18]
    assert first["solver"]["cached"] is False
    again = _sweep(client, [6, 9, 12, 15, 18])
    assert again["solver"]["cached"] is True
    assert again["points"] == first["points"]


def test_a_sweep_point_is_the_equilibrium_a_solve_gives(client: httpx.Client) -> None:
    wing = study.wing_json(stiffness_scale=1 - 4e-11)
    flight = {"alpha": 5.0, "density": study.DENSITY}
    response = client.post("/sweep", json={"wing": wing, "flight": flight, "velocities": [8, 16]})
    assert response.status_code == 200
    point = response.json()["points"][1]["equilibrium"]
    solved = client.post("/solve", json={"wing": wing, "flight": flight | {"velocity": 16}})
    assert solved.status_code == 200
    assert solved.json()["totals"]["lift"] == pytest.approx(point["totals"]["lift"], rel=1e-9)
