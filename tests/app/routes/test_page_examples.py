"""Every example of every operation in the OpenAPI document loads into the page and runs there
(issue 40): the page takes every body the API takes.

Generated from the document, never written by hand: the operations are those POST /jobs runs
(its body's `operation` constants), and their examples are those of POST /<operation> (pasted as
/docs shows them) and of POST /jobs (a job's body, pasted whole); a new operation's examples are
picked up without an edit here, and fail until the page has a panel that runs them. The cases
are named from the committed document (tests/app/routes/test_health.py holds it equal to the
app's); each takes its body from the live server's /openapi.json.

Each example is pasted into "Request JSON" of one tab (opened once for the module: the page's
opening solve and sweep run once), then its operation's button (button[data-operation]) is
clicked. The page must

- send the example's own computation: the body it sent and the example build the same solver
  input (its `key`, "equal for equal numbers": thirty 0.4s are `elastic_axis=0.4`, the table's
  stations are {semispan, stations}), checked in this process from the app's own validation of a
  POST /jobs body, so it costs no second solve;
- answer as the API does: drawn (each figure of the operation drawn again, no problem shown), or,
  where the API's answer to the example is itself a problem (a solve past the fold), that
  problem's type shown;
- log no error in the browser's console (but Chromium's line for that problem's status).
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import httpx
import pytest
from fastapi.routing import APIRoute
from playwright.sync_api import Browser
from pydantic import BaseModel

from app.main import app
from app.schemas.derive import RequestModel
from tests.app.conftest import Server
from tests.app.routes.test_page import Visit, browser, pytestmark, visits

__all__ = ["browser", "pytestmark"]  # the fixture and the marks of tests/app/routes/test_page.py

DOCUMENT = json.loads((Path(__file__).parents[3] / "openapi" / "openapi.json").read_text())


def _json_body(operation: dict[str, Any]) -> dict[str, Any]:
    content: dict[str, Any] = operation.get("requestBody", {}).get("content", {})
    return content.get("application/json", {})


def _resolve(node: dict[str, Any], document: dict[str, Any]) -> dict[str, Any]:
    while "$ref" in node:
        node = document["components"]["schemas"][node["$ref"].rsplit("/", 1)[1]]
    return node


def job_operations(document: dict[str, Any]) -> list[str]:
    """The operations POST /jobs runs: the `operation` constant of each member of its body."""
    body = _json_body(document["paths"]["/jobs"]["post"])["schema"]
    members = (_resolve(m, document) for m in body["oneOf"])
    return [m["properties"]["operation"]["const"] for m in members]


def examples(document: dict[str, Any]) -> list[tuple[str, str, str]]:
    """(operation, path, example name) of every example of every operation: POST /<operation>'s,
    and POST /jobs's (whose body names its operation)."""
    found = []
    for operation in job_operations(document):
        post = document["paths"].get(f"/{operation}", {}).get("post", {})
        names = _json_body(post).get("examples", {})
        found += [(operation, f"/{operation}", name) for name in names]
    for name, example in _json_body(document["paths"]["/jobs"]["post"])["examples"].items():
        found.append((example["value"]["operation"], "/jobs", name))
    return found


CASES = examples(DOCUMENT)


# ----------------------------------------------------------- what the page sent, in this process


def _routes(routes: list[Any]) -> Iterator[APIRoute]:
    """Every API route of the app, those of included routers too."""
    for route in routes:
        if isinstance(route, APIRoute):
            yield route
        included = getattr(route, "original_router", None)  # an include_router wrapper
        if included is not None:
            yield from _routes(included.routes)


_JOBS = next(r for r in _routes(app.routes) if r.path == "/jobs" and r.methods == {"POST"})


def _identity(value: Any) -> Any:
    """What a validated request computes: each operation input's solver key (equal for equal
    numbers, whatever form they were given in), field by field for a body of several (a batch)."""
    if isinstance(value, RequestModel):
        return value.to_solver().key
    if isinstance(value, BaseModel):
        return {name: _identity(getattr(value, name)) for name in type(value).model_fields}
    if isinstance(value, list):
        return [_identity(item) for item in value]
    return value


def computation(operation: str, request: Any) -> Any:
    """The identity of `request` run as `operation`, as the service validates a POST /jobs body."""
    assert _JOBS.body_field is not None
    submission, errors = _JOBS.body_field.validate(
        {"operation": operation, "request": request}, {}, loc=("body",)
    )
    assert not errors, errors
    return _identity(submission.request)


# ------------------------------------------------------------------------------- the one tab


@pytest.fixture(scope="module")
def document(server: Server) -> dict[str, Any]:
    """The live server's document (the examples are taken from it)."""
    return dict(httpx.get(server.base_url + "/openapi.json").json())


@pytest.fixture(scope="module")
def tab(browser: Browser, server: Server) -> Iterator[Visit]:
    """One tab for every example: the page opens (and solves and sweeps) once."""
    with visits(browser, server.base_url) as open_:
        tab = open_("/")
        tab.ready()
        yield tab


def test_the_cases_are_every_example_of_the_live_document(document: dict[str, Any]) -> None:
    assert sorted(examples(document)) == sorted(CASES)
    assert {operation for operation, _, _ in CASES} == set(job_operations(document))


def _run(tab: Visit, operation: str) -> dict[str, Any]:
    """Click `operation`'s button and wait for its run to end; the body POSTed (a job's request)."""
    page = tab.page
    before = tab.runs()

    def posted(request: Any) -> bool:
        return request.method == "POST" and request.url.endswith(("/jobs", f"/{operation}"))

    button = page.locator(f'button[data-operation="{operation}"]')
    button.evaluate("b => b.closest('details')?.setAttribute('open', '')")  # a user opens it
    with page.expect_request(posted) as sent:
        button.click()
    page.wait_for_function(
        "([operation, done, failed]) => { const s = window.__flexwing.state;"
        " return !s.busy && (s.runs[operation] > done || s.runs.failed > failed); }",
        arg=[operation, before[operation], before["failed"]],
    )
    body = dict(sent.value.post_data_json)
    return dict(body["request"]) if sent.value.url.endswith("/jobs") else body


def _answer(server: Server, operation: str, request: Any) -> tuple[int, dict[str, Any]]:
    """The API's own answer to `request` (status, body), run as a job to its end."""
    with server.client() as client:
        job = client.post("/jobs", json={"operation": operation, "request": request}).json()
        while job["status"] in ("queued", "running"):
            time.sleep(0.05)
            job = client.get(f"/jobs/{job['id']}").json()
    if job["status"] == "succeeded":
        return 200, job["result"]
    return int(job["problem"]["status"]), job["problem"]


@pytest.mark.parametrize(
    ("operation", "path", "name"), CASES, ids=[f"{path} {name}" for _, path, name in CASES]
)
def test_every_example_loads_into_the_page_and_runs_there(
    tab: Visit,
    document: dict[str, Any],
    server: Server,
    operation: str,
    path: str,
    name: str,
) -> None:
    page = tab.page
    pasted = _json_body(document["paths"][path]["post"])["examples"][name]["value"]
    request = pasted["request"] if path == "/jobs" else pasted
    panels = page.evaluate("window.__flexwing.operations")
    assert operation in panels, f"the page has no panel that runs {operation}"
    figures = panels[operation]["figures"]
    drawn = {figure: tab.figure(figure).get("drawn", 0) for figure in figures}
    errors = len(tab.errors)

    loads = page.evaluate("window.__flexwing.state.loads")
    tab.load_json(json.dumps(pasted))
    page.wait_for_function(
        "n => { const s = window.__flexwing.state;"
        " return (s.loads > n && !s.busy) || !document.getElementById('json-error').hidden; }",
        arg=loads,
    )
    assert page.is_hidden("#json-error"), page.inner_text("#json-error")
    sent = _run(tab, operation)

    differ = sorted(k for k in {*sent, *request} if sent.get(k) != request.get(k))
    assert computation(operation, sent) == computation(operation, request), (
        f"the page sent another computation; as JSON, {differ} differ"
    )
    if page.is_hidden("#problem"):
        # Every figure of the operation on show was drawn from this answer (a solve's spar
        # stresses are hidden without a spar), and at least one.
        shown = [f for f in figures if page.is_visible(f"#fig-{f.replace('.', '-')}")]
        assert shown, figures
        for figure in shown:
            record = tab.figure(figure)
            assert record["state"] == "drawn" and record["drawn"] > drawn[figure], figure
            assert any(series["x"] for series in record["series"].values()), figure
        assert tab.errors[errors:] == []
    else:
        # Not the page's failing: the API answers this example with the problem shown.
        status, answer = _answer(server, operation, request)
        assert page.get_attribute("#problem", "data-type") == answer.get("type"), answer
        logged = f"status of {status}"
        assert [e for e in tab.errors[errors:] if logged not in e] == []
