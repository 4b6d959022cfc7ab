"""The page (GET /) and the API documentation (GET /docs) in a real browser.

Headless Chromium (Debian's /usr/bin/chromium, which .ci/run installs) is driven by Playwright
against the session's real server. What the figures drew is read from the page's own record of
it (window.__flexwing.figures: each series as x/y arrays, each marked value), never from pixels.
Every request the browser makes is recorded: none may leave the app's origin. Both pages are
served with a strict Content-Security-Policy (no eval), so the waits below pass functions, not
strings, to Playwright (a string predicate is evaluated with eval, which the policy refuses).
"""

from __future__ import annotations

import contextlib
import csv
import json
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import httpx
import pytest
from playwright.sync_api import Browser, ConsoleMessage, Page, Request, sync_playwright

from tests import study
from tests.app.conftest import Server

CHROMIUM = Path("/usr/bin/chromium")
# Without the background-networking flags Chromium's own connections are refused on this machine
# (and would count as requests outside the app's origin).
CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
DESKTOP = {"width": 1280, "height": 800}
PHONE = {"width": 390, "height": 844}
TIMEOUT_MS = 30_000

pytestmark = [
    pytest.mark.browser,
    pytest.mark.skipif(
        not CHROMIUM.exists(),
        reason="/usr/bin/chromium is absent: install Debian's chromium package (.ci/run does)",
    ),
]


@dataclass
class Visit:
    """A browser tab on the server, with everything it logged and requested."""

    page: Page
    origin: str
    requests: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    def outside(self) -> list[str]:
        """Requests to anywhere but the app's origin (data: URLs load nothing)."""
        return [
            url
            for url in self.requests
            if not url.startswith("data:") and _origin(url.removeprefix("blob:")) != self.origin
        ]

    def errors_but(self, status: int) -> list[str]:
        """The errors logged, less Chromium's own line for each answer of `status` (it logs
        every 4xx response the page fetched, including the 422 a test provokes)."""
        expected = (
            f"console: Failed to load resource: the server responded with a status of {status}"
        )
        return [e for e in self.errors if not e.startswith(expected)]

    def ready(self) -> None:
        """Wait until the page has solved and swept the preloaded wing."""
        self.page.wait_for_function("() => window.__flexwing && window.__flexwing.ready")

    def runs(self) -> dict[str, int]:
        return dict(self.page.evaluate("({...window.__flexwing.state.runs})"))

    def figure(self, number: str) -> dict[str, Any]:
        return dict(self.page.evaluate(f"window.__flexwing.figures['{number}']"))

    def total(self, key: str) -> str:
        return self.page.inner_text(f'#totals [data-total="{key}"] dd')

    def load_json(self, text: str) -> None:
        """Paste `text` into the JSON box (opened if it is closed) and load it."""
        if not self.page.is_visible("#json-text"):
            self.page.click("#json-io summary")
        self.page.fill("#json-text", text)
        self.page.click("#json-load")

    def solved(self, press: str | None = None) -> dict[str, Any]:
        """Solve (Enter in the field `press`, else the Solve button) and wait for the answer;
        returns the /solve request body the page sent."""
        with self.page.expect_request(lambda r: r.url.endswith("/solve")) as sent:
            before = self.runs()
            if press is None:
                self.page.click("#solve-button")
            else:
                self.page.press(press, "Enter")
            self.wait_runs("solve", before)
        return dict(sent.value.post_data_json)

    def swept(self, outcome: str = "sweep", press: str | None = None) -> dict[str, Any]:
        """Sweep (Enter in the field `press`, else the Sweep button) and wait for a run of
        `outcome` ("sweep" or "failed"); returns the POST /jobs body the page sent."""
        with self.page.expect_request(
            lambda r: r.url.endswith("/jobs") and r.method == "POST"
        ) as sent:
            before = self.runs()
            if press is None:
                self.page.click("#sweep-button")
            else:
                self.page.press(press, "Enter")
            self.wait_runs(outcome, before)
        return dict(sent.value.post_data_json)

    def wait_runs(self, kind: str, before: dict[str, int]) -> None:
        """Wait until one more run of `kind` ("solve", "sweep" or "failed") has finished."""
        self.page.wait_for_function(
            "([kind, n]) => window.__flexwing.state.runs[kind] > n"
            " && !window.__flexwing.state.busy",
            arg=[kind, before[kind]],
        )


def _origin(url: str) -> str:
    parts = urlsplit(url)
    return f"{parts.scheme}://{parts.netloc}"


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=str(CHROMIUM), args=CHROMIUM_ARGS)
        yield browser
        browser.close()


@contextlib.contextmanager
def visits(browser: Browser, base_url: str) -> Iterator[Callable[..., Visit]]:
    """Open paths of the server at `base_url`, each in a fresh context (own cache and storage)
    at a viewport size, recording console errors and every request; the page itself must load
    with 200 (it needs no key)."""
    contexts = []

    def open_(path: str = "/", viewport: dict[str, int] = DESKTOP, **wait: Any) -> Visit:
        context = browser.new_context(viewport=viewport, accept_downloads=True)
        context.set_default_timeout(TIMEOUT_MS)
        contexts.append(context)
        page = context.new_page()
        tab = Visit(page, base_url)

        def console(message: ConsoleMessage) -> None:
            if message.type == "error":
                tab.errors.append(f"console: {message.text} at {message.location}")

        def request(r: Request) -> None:
            tab.requests.append(r.url)

        context.on("request", request)
        page.on("console", console)
        page.on("pageerror", lambda error: tab.errors.append(f"page error: {error}"))
        response = page.goto(base_url + path, **wait)
        assert response is not None and response.status == 200
        return tab

    try:
        yield open_
    finally:
        for context in contexts:
            context.close()


@pytest.fixture
def visit(browser: Browser, server: Server) -> Iterator[Callable[..., Visit]]:
    with visits(browser, server.base_url) as open_:
        yield open_


def test_page_loads_clean_and_draws_every_figure(visit: Callable[..., Visit]) -> None:
    tab = visit("/")
    tab.ready()
    headers = tab.page.evaluate("fetch('/').then(r => r.headers.get('content-security-policy'))")
    assert "default-src 'self'" in headers
    # The study's wing is preloaded, solved and swept as the page opens.
    assert tab.page.input_value("#f-velocity") == "10"
    assert tab.page.input_value("#f-alpha") == "5"
    assert tab.page.input_value("#cell-chord-0") == "1.414213562"

    spanwise = tab.figure("14.2")
    assert spanwise["state"] == "drawn"
    for key, n in (("lift_rigid", 29), ("lift_flexible", 29), ("twist", 30), ("heave", 30)):
        series = spanwise["series"][key]
        assert len(series["x"]) == len(series["y"]) == n, key
    rigid, flexible = (
        spanwise["series"]["lift_rigid"]["y"],
        spanwise["series"]["lift_flexible"]["y"],
    )
    assert all(f > r > 0 for f, r in zip(flexible, rigid, strict=True))  # wash-in: more lift
    assert spanwise["series"]["twist"]["y"][-1] == pytest.approx(1.708, abs=1e-3)
    assert "rigid_lift_per_span" in tab.page.inner_text("#rigid-note")

    loads = tab.figure("14.3")
    assert len(loads["series"]["bending_moment"]["y"]) == len(loads["series"]["torque"]["y"]) == 30
    assert loads["marks"]["root_bending_moment"] == pytest.approx(325.17, abs=0.01)
    assert loads["marks"]["root_torque"] == pytest.approx(23.385, abs=1e-3)
    assert loads["labels"] == ["root: 325 N·m", "root: 23.4 N·m"]

    sweep = tab.figure("14.4")
    assert len(sweep["series"]["amplification"]["x"]) >= 5
    assert len(sweep["series"]["amplification_fit"]["x"]) == 300
    # The fit drawn in the sweep's own q (its density from the fit's divergence point, right at
    # any altitude): at 92 % of its divergence speed, 1 / (intercept (1 - 0.92^2)).
    ending = sweep["series"]["amplification_fit"]["y"][-1]
    intercept = sweep["marks"]["fit_intercept"]
    assert ending == pytest.approx(1 / (intercept * (1 - 0.92**2)), rel=1e-9)
    assert sweep["marks"]["fold_velocity"] == pytest.approx(21.44, abs=0.01)

    shape = tab.figure("14.5")
    for view in ("top", "front", "side"):
        for which in ("jig", "deformed"):
            assert len(shape["series"][f"{view}_{which}"]["x"]) > 100, (view, which)
    assert tab.page.get_attribute("#fig-14-5", "data-state") == "drawn"

    assert tab.errors == []
    assert tab.outside() == []
    assert any(url.endswith("/solve") for url in tab.requests)


def test_solving_the_preloaded_wing_shows_the_study_numbers(visit: Callable[..., Visit]) -> None:
    tab = visit("/")
    tab.ready()
    before = tab.runs()
    tab.page.click("#solve-button")
    tab.wait_runs("solve", before)
    assert tab.page.inner_text("#totals-title") == "Totals at 10 m/s, alpha 5 deg, 1.225 kg/m^3"
    assert tab.total("lift") == "304.1 N"
    assert tab.total("tip_twist") == "+1.71 deg"
    assert tab.total("rigid_lift") == "259.4 N"
    assert tab.total("lift_amplification") == "1.173"
    assert tab.total("root_bending_moment") == "325.2 N·m"
    assert tab.total("margin") == "0.148 (stable)"
    assert tab.errors == []


def test_a_sweep_draws_the_amplification_curve_and_marks_the_fold(
    visit: Callable[..., Visit],
) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.fill("#f-sweep_start", "6")
    page.fill("#f-sweep_stop", "22")
    page.fill("#f-sweep_count", "9")
    # Record the busy state as it changes (a sweep takes ~50 ms: too quick to poll).
    page.evaluate(
        """() => {
        const results = document.getElementById("results");
        window.__busy = [];
        new MutationObserver(() => window.__busy.push({
            busy: results.getAttribute("aria-busy"),
            progress: !document.getElementById("progress").hidden,
            sweepDisabled: document.getElementById("sweep-button").disabled,
        })).observe(results, {attributes: true, attributeFilter: ["aria-busy"]});
    }"""
    )
    # ... and the progress bar's determinate value, as the job reports it.
    page.evaluate(
        """() => {
        const bar = document.getElementById("progress");
        window.__progress = [];
        new MutationObserver(() => window.__progress.push({
            value: bar.getAttribute("value"), max: bar.getAttribute("max"), hidden: bar.hidden,
        })).observe(bar, {attributes: true});
    }"""
    )
    sent: list[tuple[str, str]] = []
    page.on("request", lambda r: sent.append((r.method, r.url.removeprefix(tab.origin))))
    before = tab.runs()
    tab.swept(press="#f-sweep_count")  # Enter in a sweep field sweeps
    assert tab.runs()["solve"] == before["solve"]
    # Issue 14: the sweep runs as a job (POST /jobs, then GET /jobs/{id} until it ends).
    assert ("POST", "/sweep") not in sent
    assert sent[0] == ("POST", "/jobs")
    polled = [url for method, url in sent if method == "GET" and url.startswith("/jobs/")]
    assert polled and len(set(polled)) == 1
    busy = page.evaluate("window.__busy")
    assert busy[0] == {"busy": "true", "progress": True, "sweepDisabled": True}
    progress = page.evaluate("window.__progress")
    determinate = [p for p in progress if p["value"] is not None]
    assert determinate and determinate[-1]["value"] == determinate[-1]["max"] == "9"
    assert progress[-1]["hidden"] is True  # and the bar is gone once the sweep is drawn
    assert busy[-1]["busy"] is None and not page.is_disabled("#sweep-button")

    figure = tab.figure("14.4")
    speeds = figure["series"]["amplification"]["x"]
    assert speeds == [6, 8, 10, 12, 14, 16, 18, 20]
    amplification = figure["series"]["amplification"]["y"]
    assert amplification == sorted(amplification) and amplification[0] > 1
    assert amplification[-1] == pytest.approx(2.40, abs=0.01)  # the study's 2.40 at 20 m/s
    assert figure["series"]["tip_twist"]["y"][-1] == pytest.approx(13.65, abs=0.01)
    assert figure["series"]["no_equilibrium"]["x"] == [22]
    # The fitted law 1/A = intercept + slope q, drawn from 0 to 92 % of its divergence speed.
    marks = figure["marks"]
    fit_v, fit_a = (
        figure["series"]["amplification_fit"]["x"],
        figure["series"]["amplification_fit"]["y"],
    )
    assert fit_v[-1] == pytest.approx(0.92 * marks["fit_velocity"])
    q = 0.5 * 1.225 * fit_v[150] ** 2
    assert fit_a[150] == pytest.approx(1 / (marks["fit_intercept"] + marks["fit_slope"] * q))
    assert marks["fold_velocity"] == pytest.approx(21.44, abs=0.01)
    assert marks["linear_velocity"] == pytest.approx(24.22, abs=0.01)
    assert "fold, 21.44 m/s" in page.inner_text("#sweep-note")
    rows = page.locator("#sweep-table tbody tr")
    assert rows.count() == 9
    assert rows.nth(8).get_attribute("data-status") == "no_equilibrium"
    # Figure 14.5 now shows the sweep's fastest equilibrium, as the study does (20 m/s).
    assert page.input_value("#shape-of") == "sweep-7"
    assert tab.figure("14.5")["marks"]["tip_twist"] == pytest.approx(13.65, abs=0.01)
    assert tab.errors == []


def test_findings_show_next_to_the_figures_they_concern(visit: Callable[..., Visit]) -> None:
    """Issue 15: at 10 m/s the study's wing is within the model; at 20 m/s its sections are
    past stall (marked on the lift chart, said under Figure 14.2), its twist and slope too
    large, and it is near divergence (said beside the totals); the sweep says from which
    airspeed on, under Figure 14.4."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    assert page.get_attribute("#validity", "data-state") == "clear"
    assert "Within the model's validity" in page.inner_text("#validity-summary")
    assert page.locator("#findings-14-2 li").count() == 0
    assert tab.figure("14.2")["findings"] == []
    # The preloaded sweep (4 to 22 m/s): stall from 18 m/s on, the rest from 20.
    onsets = page.locator("#fig-14-4 #findings-14-4 li")
    assert [onsets.nth(i).get_attribute("data-code") for i in range(onsets.count())] == [
        "large_deflection",
        "large_twist",
        "section_stall",
        "near_divergence",
    ]
    assert "from 18 m/s on" in page.inner_text('#findings-14-4 li[data-code="section_stall"]')
    assert {o["code"]: o["velocity"] for o in tab.figure("14.4")["onsets"]}["section_stall"] == 18
    rows = page.locator("#sweep-table tbody tr")
    assert rows.nth(7).locator("td").last.inner_text() == "stall"  # 18 m/s
    assert rows.nth(0).locator("td").last.inner_text() == "-"  # 4 m/s

    page.fill("#f-velocity", "20")
    before = tab.runs()
    page.press("#f-velocity", "Enter")
    tab.wait_runs("solve", before)
    stall = page.locator('#fig-14-2 #findings-14-2 li[data-code="section_stall"]')
    assert stall.is_visible()
    assert "1.70" in stall.inner_text() and "1.20" in stall.inner_text()
    for code in ("large_deflection", "large_twist"):
        assert page.locator(f'#findings-14-2 li[data-code="{code}"]').is_visible()
    near = page.locator('#findings-totals li[data-code="near_divergence"]')
    assert near.is_visible() and "times the rigid wing's" in near.inner_text()
    assert page.get_attribute("#validity", "data-state") == "findings"
    assert "Beyond the model's validity" in page.inner_text("#validity-summary")
    spanwise = tab.figure("14.2")
    assert spanwise["findings"] == [
        "large_deflection",
        "large_twist",
        "section_stall",
        "near_divergence",
    ]
    # The stalled strips (15 to 28) are marked on the lift chart, at their lift.
    lift = spanwise["series"]["lift_flexible"]
    assert spanwise["series"]["beyond_lift"]["x"] == lift["x"][15:29]
    assert spanwise["series"]["beyond_lift"]["y"] == lift["y"][15:29]
    assert len(spanwise["series"]["beyond_twist"]["x"]) > 0
    assert "Beyond the model's validity" in page.inner_text("#shape-note")
    assert tab.errors == []


def test_a_negative_chord_is_reported_next_to_its_cell(visit: Callable[..., Visit]) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.click("#stations-details summary")
    cell = page.locator("#cell-chord-3")
    cell.fill("-0.5")
    assert page.is_checked("#mode-table")  # editing a cell switches to the table
    before = tab.runs()
    cell.press("Enter")  # Enter in any field solves
    tab.wait_runs("failed", before)
    assert cell.get_attribute("aria-invalid") == "true"
    error_id = cell.get_attribute("aria-describedby")
    assert error_id is not None
    error = page.locator(f"#{error_id}")
    assert error.is_visible()
    assert "greater than or equal to 0.001" in error.inner_text()
    # Next to that input: in the same table cell, right after it.
    assert page.evaluate(
        "id => document.getElementById(id).previousElementSibling.id", error_id
    ) == ("cell-chord-3")
    problem = page.inner_text("#problem")
    assert "Check the highlighted inputs" in problem and "wing.chord[3]" in problem
    # No other input is marked.
    assert page.locator("[aria-invalid=true]").count() == 1
    assert tab.errors_but(422) == []


def test_a_negative_root_chord_in_the_planform_is_reported_there(
    visit: Callable[..., Visit],
) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.select_option("#f-taper", "linear")
    page.fill("#f-root_chord", "-1")
    before = tab.runs()
    page.press("#f-root_chord", "Enter")
    tab.wait_runs("failed", before)
    assert page.get_attribute("#f-root_chord", "aria-invalid") == "true"
    assert "station 0 (chord): Input should be greater than or equal to 0.001" in page.inner_text(
        "#f-root_chord-error"
    )
    assert tab.errors_but(422) == []


def test_beyond_the_fold_the_page_says_so_in_plain_words(visit: Callable[..., Visit]) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.fill("#f-velocity", "23")
    before = tab.runs()
    page.press("#f-velocity", "Enter")
    tab.wait_runs("failed", before)
    problem = page.inner_text("#problem")
    assert "No equilibrium at 23 m/s" in problem
    assert "fold speed, 21.44 m/s" in problem
    assert page.get_attribute("#problem", "data-type") == "/problems/no-equilibrium"
    assert tab.errors_but(422) == []


def test_pasted_json_loads_and_solves(visit: Callable[..., Visit], server: Server) -> None:
    body = httpx.get(server.base_url + "/openapi.json").json()
    example = body["paths"]["/solve"]["post"]["requestBody"]["content"]["application/json"]
    request = example["examples"]["study"]["value"]
    request["flight"]["velocity"] = 12
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(request))
    assert page.is_checked("#mode-table")
    assert page.input_value("#f-velocity") == "12"
    before = tab.runs()
    page.click("#solve-button")
    tab.wait_runs("solve", before)
    assert tab.total("tip_twist") == "+2.67 deg"  # the study's 12 m/s point
    tab.load_json("{not json")
    assert "Not valid JSON" in page.inner_text("#json-error")


def test_downloads_results_and_figures(visit: Callable[..., Visit]) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    with page.expect_download() as info:
        page.click("#download-stations")
    lines = Path(info.value.path()).read_text().splitlines()
    assert lines[0].startswith("y [m],heave [m],slope [-],twist [deg]")
    assert len(lines) == 31
    with page.expect_download() as info:
        page.click("#download-sweep")
    assert Path(info.value.path()).read_text().splitlines()[0].startswith("velocity [m/s],status")
    with page.expect_download() as info:
        page.click("#download-json")
    results = json.loads(Path(info.value.path()).read_text())
    assert results["solve"]["response"]["totals"]["lift"] == pytest.approx(304.125, abs=1e-3)
    rigid_panels = results["solve"]["rigid"]["panels"]
    assert (
        rigid_panels["lift_per_span"]
        == results["solve"]["response"]["panels"]["rigid_lift_per_span"]
    )
    page.click("#json-io summary")
    with page.expect_download() as info:
        page.click("#json-download")
    assert json.loads(Path(info.value.path()).read_text())["flight"]["velocity"] == 10
    for figure in ("fig-14-2", "fig-14-3", "fig-14-4", "fig-14-5"):
        with page.expect_download() as info:
            page.click(f'button.export-png[data-figure="{figure}"]')
        assert info.value.suggested_filename == f"flexwing-{figure.replace('fig-', 'figure-')}.png"
        assert Path(info.value.path()).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert tab.errors == []
    assert tab.outside() == []


def test_every_input_is_labelled_and_the_page_fits_a_phone(visit: Callable[..., Visit]) -> None:
    tab = visit("/", PHONE)
    tab.ready()
    unlabelled = tab.page.evaluate(
        """[...document.querySelectorAll("input, select, textarea")]
            .filter(e => !(e.labels?.length || e.getAttribute("aria-labelledby")
                           || e.getAttribute("aria-label")))
            .map(e => e.id || e.outerHTML)"""
    )
    assert unlabelled == []
    width = tab.page.evaluate("document.documentElement.scrollWidth")
    assert width <= PHONE["width"]
    assert tab.errors == []


def test_screenshots(
    visit: Callable[..., Visit],
    tmp_path_factory: pytest.TempPathFactory,
    capsys: pytest.CaptureFixture[str],
) -> None:
    out = tmp_path_factory.mktemp("page-screenshots")
    for name, viewport in (("desktop-1280x800", DESKTOP), ("phone-390x844", PHONE)):
        tab = visit("/", viewport)
        tab.ready()
        tab.page.wait_for_timeout(100)  # the three-view's equal-axis redraw
        tab.page.screenshot(path=out / f"{name}.png")
        tab.page.screenshot(path=out / f"{name}-full.png", full_page=True)
        assert tab.errors == []
    for png in out.iterdir():
        assert png.stat().st_size > 10_000, png
    with capsys.disabled():
        print(f"\npage screenshots (1280x800 and 390x844): {out}")


def test_optional_fields_appear_when_the_api_has_them(browser: Browser, server: Server) -> None:
    """A later API's wing.sweep [deg]: shown, with its description, when /openapi.json has it."""
    document = httpx.get(server.base_url + "/openapi.json").json()
    document["components"]["schemas"]["Wing"]["properties"]["sweep"] = {
        "type": "number",
        "description": "[deg] leading-edge sweep.",
    }
    context = browser.new_context(viewport=DESKTOP)
    try:
        page = context.new_page()
        page.route("**/openapi.json", lambda route: route.fulfill(json=document))
        page.goto(server.base_url + "/")
        page.wait_for_function("() => window.__flexwing && window.__flexwing.ready")
        assert page.inner_text('label[for="f-sweep_angle"]') == "Sweep [deg]"
        assert page.inner_text("#f-sweep_angle ~ .hint") == "[deg] leading-edge sweep."
    finally:
        context.close()


def test_docs_render_swagger_ui_offline(visit: Callable[..., Visit]) -> None:
    tab = visit("/docs")
    page = tab.page
    page.wait_for_selector(".opblock-summary-path >> text=/solve")
    assert page.locator(".opblock").count() >= 4
    # The study's example runs from the page.
    page.click(".opblock-post:has-text('/solve') .opblock-summary")
    page.click("button.try-out__btn")
    page.click("button.execute")
    page.wait_for_selector(".live-responses-table .response-col_status >> text=200")
    assert tab.errors == []
    assert tab.outside() == []


def test_trimming_to_a_weight_solves_for_the_angle_of_attack(visit: Callable[..., Visit]) -> None:
    """Issue 14: the flight panel flies at an angle of attack or trimmed to a weight; the request
    carries exactly one of them, and the trimmed answer's alpha is among the totals."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    assert page.is_checked("#flight-mode-alpha")
    assert page.is_visible("#f-alpha") and not page.is_visible("#f-weight")
    page.focus("#flight-mode-alpha")
    page.keyboard.press("ArrowRight")  # a radio group: the keyboard moves the choice
    assert page.is_checked("#flight-mode-weight")
    assert page.is_visible("#f-weight") and page.is_visible("#f-load_factor")
    assert not page.is_visible("#f-alpha")
    assert "weight" in page.inner_text("#sweep legend")
    page.fill("#f-velocity", "12")
    page.fill("#f-weight", "300")
    page.fill("#f-load_factor", "1")
    body = tab.solved("#f-weight")
    flight = body["flight"]
    assert flight == {"velocity": 12, "weight": 300, "load_factor": 1, "density": 1.225}
    assert tab.total("alpha") == "3.14 deg"  # the solver's 3.1436806542 deg
    assert tab.total("lift") == "300.0 N"
    assert tab.total("rigid_alpha") == "4.01 deg"
    assert tab.total("lift_effectiveness") == "1.270"
    assert page.locator('#totals [data-total="lift_amplification"]').count() == 0
    assert "trimmed: alpha 3.14 deg" in page.inner_text("#totals-title")
    # Back at an angle of attack the request carries alpha, not the weight.
    page.check("#flight-mode-alpha")
    page.fill("#f-velocity", "10")
    body = tab.solved()
    assert body["flight"] == {"velocity": 10, "alpha": 5, "density": 1.225}
    assert tab.total("lift") == "304.1 N"
    assert page.locator('#totals [data-total="alpha"]').count() == 0
    assert tab.errors == []


def test_a_trimmed_sweep_draws_points_and_its_stability_limit(
    visit: Callable[..., Visit],
) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.check("#flight-mode-weight")
    page.fill("#f-sweep_start", "6")
    page.fill("#f-sweep_stop", "22")
    page.fill("#f-sweep_count", "9")
    body = tab.swept()
    assert body["operation"] == "sweep"
    flight = body["request"]["flight"]
    assert flight == {"weight": 300, "density": 1.225}  # no load factor given: none sent
    figure = tab.figure("14.4")
    assert figure["amplification"] == "lift_effectiveness"
    speeds = figure["series"]["amplification"]["x"]
    assert len(speeds) >= 5 and speeds[0] == 6
    assert all(a is not None and a > 1 for a in figure["series"]["amplification"]["y"])
    assert figure["marks"]["fold_kind"] == "trimmed_stability_limit"
    assert "loses static stability" in page.inner_text("#sweep-note")
    head = page.inner_text("#sweep-table thead")
    assert "alpha [deg]" in head and "L / L_rigid" not in head
    assert tab.errors == []


def test_a_tube_spar_draws_its_stresses_and_the_laws_solve_as_before(
    visit: Callable[..., Visit],
) -> None:
    tab = visit("/")
    tab.ready()
    page = tab.page
    assert page.get_attribute("#fig-stress", "hidden") is not None  # no spar, no stress figure
    assert not page.is_visible("#f-spar_outer_diameter")
    page.check("#stiffness-spar")
    assert page.is_visible("#f-spar_outer_diameter") and not page.is_visible("#f-ei_k")
    assert page.input_value("#f-spar_outer_diameter") == "0.05"
    assert page.input_value("#f-spar_wall_thickness") == "0.002"
    body = tab.solved("#f-spar_wall_thickness")
    assert "bending_stiffness" not in body["wing"] and "torsional_stiffness" not in body["wing"]
    assert body["wing"]["spar"]["outer_diameter"] == 0.05
    assert body["wing"]["spar"]["material"]["yield_stress"] == 6e8
    assert body["options"] == {"safety_factor": 1.5}
    assert page.is_visible("#fig-stress")
    stress = tab.figure("stress")
    assert stress["state"] == "drawn"
    for key in ("von_mises", "bending"):
        assert len(stress["series"][key]["x"]) == len(stress["series"][key]["y"]) == 30, key
    von_mises = stress["series"]["von_mises"]["y"]
    assert max(von_mises) == pytest.approx(stress["marks"]["max_von_mises"])
    assert 0 < max(von_mises) < stress["marks"]["allowable"] == pytest.approx(400)
    assert tab.total("failure_margin").startswith("+") and "holds" in tab.total("failure_margin")
    assert tab.total("spar_mass").endswith(" kg")
    assert "MPa" in tab.total("max_von_mises_stress")
    # Back to the EI/GJ laws: the study's wing, as before, and no stress figure.
    page.check("#stiffness-laws")
    assert page.is_visible("#f-ei_k")
    body = tab.solved()
    assert "spar" not in body["wing"] and "options" not in body
    assert tab.total("lift") == "304.1 N"
    assert page.locator('#totals [data-total="failure_margin"]').count() == 0
    assert not page.is_visible("#fig-stress")
    assert tab.errors == []


def test_a_negative_chord_in_a_sweep_is_reported_next_to_its_cell(
    visit: Callable[..., Visit],
) -> None:
    """The job's 422 names `request.wing.chord[3]`; the page marks the sweep's input."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.click("#stations-details summary")
    cell = page.locator("#cell-chord-3")
    cell.fill("-0.5")
    with page.expect_response(lambda r: r.url.endswith("/jobs")) as answered:
        tab.swept("failed")
    assert answered.value.status == 422
    assert cell.get_attribute("aria-invalid") == "true"
    error = page.locator(f"#{cell.get_attribute('aria-describedby')}")
    assert "greater than or equal to 0.001" in error.inner_text()
    problem = page.inner_text("#problem")
    assert "Check the highlighted inputs" in problem and "wing.chord[3]" in problem
    assert "request.wing" not in problem
    assert page.locator("[aria-invalid=true]").count() == 1
    assert page.inner_text("#status-text") == "Sweep failed."
    assert tab.errors_but(422) == []


def test_cancelling_a_sweep_cancels_its_job_and_leaves_the_page_usable(
    visit: Callable[..., Visit], server: Server
) -> None:
    """The job's GET is answered "running, 7 of 50" by the test (page.route) for as long as the
    page asks, so Cancel always finds the sweep running: no race with the real job's speed."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    jobs: list[str] = []

    def running(route: Any) -> None:
        if route.request.method != "GET":
            route.continue_()
            return
        job_id = route.request.url.rsplit("/", 1)[1]
        jobs.append(job_id)
        body = {
            "id": job_id,
            "operation": "sweep",
            "status": "running",
            "progress": {"done": 7, "total": 50, "problems": 0},
        }
        route.fulfill(status=200, content_type="application/json", body=json.dumps(body))

    page.route("**/jobs/*", running)
    page.fill("#f-sweep_count", "50")
    before = tab.runs()
    page.click("#sweep-button")
    page.wait_for_function(
        "() => { const bar = document.getElementById('progress');"
        " return !bar.hidden && bar.max === 50 && bar.value === 7; }"
    )
    assert page.is_visible("#cancel") and page.is_disabled("#sweep-button")
    assert "7 of 50" in page.inner_text("#status-text")
    # The page's DELETE is best effort and not awaited (the page moves on at once), so the test
    # waits for its answer before asking the server what became of the job.
    with page.expect_response(lambda r: r.request.method == "DELETE") as deleted:
        page.click("#cancel")
        tab.wait_runs("failed", before)
    assert deleted.value.url.endswith(f"/jobs/{jobs[0]}") and deleted.value.status == 200
    assert page.inner_text("#status-text") == "Sweep cancelled."
    assert not page.is_visible("#progress") and not page.is_visible("#cancel")
    assert tab.runs()["sweep"] == before["sweep"]
    # The job was cancelled, or had finished before the DELETE came (a finished job stays so).
    assert deleted.value.json()["status"] in {"cancelled", "succeeded"}
    job = httpx.get(f"{server.base_url}/jobs/{jobs[0]}").json()
    assert job["status"] == deleted.value.json()["status"]
    # The page is usable: the next sweep (answered for real) is drawn.
    page.unroute("**/jobs/*")
    page.fill("#f-sweep_count", "9")
    tab.swept()
    assert len(tab.figure("14.4")["series"]["amplification"]["x"]) == 8
    assert tab.errors == []


def test_a_trimmed_flight_without_equilibrium_says_why(visit: Callable[..., Visit]) -> None:
    """A weight the wing cannot carry is not a divergence: the page shows the solver's reason."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.check("#flight-mode-weight")
    page.fill("#f-velocity", "4.5")  # 300 N needs 31.2 deg of the rigid wing (tests/solver)
    page.fill("#f-weight", "300")
    before = tab.runs()
    page.press("#f-weight", "Enter")
    tab.wait_runs("failed", before)
    problem = page.inner_text("#problem")
    assert "No equilibrium at 4.5 m/s" in problem
    assert "diverges" not in problem
    assert "needs alpha = 31.2" in problem and "beyond +-30 deg" in problem
    assert page.get_attribute("#problem", "data-type") == "/problems/no-equilibrium"
    assert tab.errors_but(422) == []


def test_loaded_json_keeps_what_the_editor_cannot_show_and_its_options(
    visit: Callable[..., Visit],
) -> None:
    """A camber table and solver options loaded from JSON are sent as given (a text field once
    showed the table as "[object Object]", and every option but the safety factor was dropped);
    a later body without them clears them."""
    camber = {"x": [0.0, 0.5, 1.0], "camber": [0.0, 0.04, 0.0]}
    body = study.solve_request(12.0, options={"chordwise_panels": 4, "torque_axis": "deformed"})
    body["wing"]["airfoil"] = camber
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(body))
    assert page.input_value("#f-airfoil") == ""
    note = page.inner_text("#planform-note")
    assert "airfoil" in note and "options.chordwise_panels" in note
    sent = tab.solved()
    assert sent["wing"]["airfoil"] == camber
    assert sent["options"] == {"chordwise_panels": 4, "torque_axis": "deformed"}
    assert tab.errors_but(0) == []
    tab.load_json(json.dumps(study.solve_request(12.0)))
    again = tab.solved()
    assert "airfoil" not in again["wing"] and "options" not in again


def test_a_surface_given_in_metres_stays_in_metres(visit: Callable[..., Visit]) -> None:
    """A loaded surface whose extent is in metres shows so in its row and is sent so (the
    table once had no such column: 2.75-4.75 m went out as fractions of the semispan, a 422
    for a wing it did not describe); what it leaves out is the API's default, not the table's
    new-row values (it once became a 5 deg deflection)."""
    aileron = {"name": "aileron", "start": 2.75, "end": 4.75, "extent_unit": "m", "kind": "aileron"}
    body = study.solve_request(12.0, options={"chordwise_panels": 4})
    body["wing"]["control_surfaces"] = [aileron]
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(body))
    assert page.input_value("#surface-extent_unit-0") == "m"
    assert page.input_value("#surface-end-0") == "4.75"
    sent = tab.solved()["wing"]["control_surfaces"]
    assert sent == [aileron | {"hinge": 0.75, "deflection": 0}]  # ControlSurface's defaults
    assert tab.errors_but(0) == []


def test_a_sweep_polled_into_a_rate_limit_waits_and_draws_its_answer(
    visit: Callable[..., Visit],
) -> None:
    """Two of the job's GETs are refused with 429 (by the test, page.route): the page waits for
    their Retry-After and asks again; it once reported the sweep failed while the job ran on."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    refused: list[str] = []

    def rate_limited(route: Any) -> None:
        if route.request.method == "GET" and len(refused) < 2:
            refused.append(route.request.url)
            problem = {"type": "/problems/rate-limited", "title": "Too many", "status": 429}
            route.fulfill(
                status=429,
                headers={"retry-after": "1", "content-type": "application/problem+json"},
                body=json.dumps(problem),
            )
            return
        route.continue_()

    page.route("**/jobs/*", rate_limited)
    page.fill("#f-sweep_count", "9")
    tab.swept()
    assert len(refused) == 2
    assert len(tab.figure("14.4")["series"]["amplification"]["x"]) == 8
    assert "Sweep failed" not in page.inner_text("#status-text")
    assert tab.errors_but(429) == []


def _ran(tab: Visit, kind: str, button: str, outcome: str | None = None) -> dict[str, Any]:
    """Click `button` (a controls or flutter run) and wait for a run of `outcome` (default:
    `kind`); returns the POST /jobs body the page sent."""
    with tab.page.expect_request(lambda r: r.url.endswith("/jobs") and r.method == "POST") as sent:
        before = tab.runs()
        tab.page.click(button)
        tab.wait_runs(outcome or kind, before)
    body = dict(sent.value.post_data_json)
    assert body["operation"] == kind
    return body


def test_an_aileron_sweeps_its_effectiveness_and_reverses_before_divergence(
    visit: Callable[..., Visit],
) -> None:
    """Issue 25: the study's aileron (55-95 % of the semispan, hinge at 75 %) on 4 chordwise
    panels loses its effectiveness as the airspeed rises and reverses at ~20.6 m/s, before the
    wing diverges; too few panels for its hinge is reported next to the hinge's cell."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    assert page.is_hidden("#controls-button")  # no surfaces, no controls sweep
    page.click("#surfaces-details summary")
    page.click("#add-surface")
    assert [page.input_value(f"#surface-{key}-0") for key in ("name", "start", "end", "hinge")] == [
        "aileron",
        "0.55",
        "0.95",
        "0.75",
    ]
    assert page.input_value("#surface-kind-0") == "aileron"
    assert page.input_value("#f-chordwise_panels") == "4"
    assert "needs at least 3" in page.inner_text("#chordwise-note")
    page.fill("#f-sweep_start", "6")
    page.fill("#f-sweep_stop", "20")
    page.fill("#f-sweep_count", "5")
    body = _ran(tab, "controls", "#controls-button")
    request = body["request"]
    assert request["wing"]["control_surfaces"] == [
        {
            "name": "aileron",
            "start": 0.55,
            "end": 0.95,
            "extent_unit": "fraction",
            "hinge": 0.75,
            "deflection": 5,
            "kind": "aileron",
        }
    ]
    assert request["options"] == {"chordwise_panels": 4}
    assert request["velocities"] == {"start": 6, "stop": 20, "count": 5}

    figure = tab.figure("controls")
    assert figure["state"] == "drawn"
    curve = figure["series"]["effectiveness_aileron"]
    assert curve["x"] == [6, 9.5, 13, 16.5, 20]
    assert curve["y"] == sorted(curve["y"], reverse=True) and 0 < curve["y"][0] < 1
    marks = figure["marks"]
    assert marks["reversal"]["aileron"] == pytest.approx(20.6, abs=0.1)
    assert marks["symmetric_divergence"] == pytest.approx(23.9, abs=0.1)
    assert marks["first"]["aileron"] == "reversal"
    verdict = page.inner_text("#controls-first")
    assert "reversal comes first, at 20.62 m/s" in verdict
    # Chart.js sizes its canvas on its own frame after the figure is shown: wait for it (a
    # check at one instant raced it on a loaded CI machine).
    chart = page.locator("#fig-controls canvas#chart-effectiveness")
    chart.wait_for(state="visible", timeout=10_000)
    # The curve as a CSV: a row per airspeed, the surface's columns named with its unit.
    with page.expect_download() as info:
        page.click("#download-controls")
    rows = list(csv.DictReader(Path(info.value.path()).read_text().splitlines()))
    assert [float(r["velocity [m/s]"]) for r in rows] == curve["x"]
    assert [float(r["aileron effectiveness [-]"]) for r in rows] == pytest.approx(curve["y"])
    assert all(r["aileron derivative [N m/deg]"] for r in rows)
    # A solve of the wing carries the surface (and its panels); figure 14.5 outlines it on both
    # halves, in every view (its hinge line and deflected trailing edge, closed).
    solved = tab.solved()
    assert solved["options"] == {"chordwise_panels": 4}
    shape = tab.figure("14.5")["series"]
    for view in ("top", "front", "side"):
        outline = [x for x in shape[f"{view}_surfaces"]["x"] if x is not None]
        assert len(outline) == 2 * (2 * 14 + 1)  # 12 stations inside 55-95 %, and its ends

    # Two panels leave no whole panel aft of a hinge at 75 %: the 422 names the hinge's cell.
    page.fill("#f-chordwise_panels", "2")
    _ran(tab, "controls", "#controls-button", outcome="failed")
    error = page.inner_text("#surface-hinge-0-error")
    assert "chordwise_panels >= 3" in error
    assert page.get_attribute("#surface-hinge-0", "aria-invalid") == "true"
    assert page.is_visible("#surface-hinge-0")
    assert tab.errors_but(422) == []


def _goland(stations: int = 12) -> dict[str, Any]:
    """The Goland wing (app/schemas/examples.py) on a small mesh, its stations as a list."""
    semispan = 6.096
    return {
        "wing": {
            "y": [round(semispan * i / (stations - 1), 10) for i in range(stations)],
            "chord": 1.8288,
            "elastic_axis": 0.33,
            "bending_stiffness": 9.77e6,
            "torsional_stiffness": 0.987e6,
            "mass": {
                "mass_per_length": 35.71,
                "center_of_gravity": 0.43,
                "inertia_per_length": 7.446,
            },
        },
        "flight": {"alpha": 0.0, "density": 1.225},
        "velocities": {"start": 100.0, "stop": 180.0, "count": 9},
        "options": {"aerodynamics": "strip"},
    }


def test_a_flutter_run_draws_v_g_and_v_f_with_the_flutter_speed(
    visit: Callable[..., Visit], server: Server
) -> None:
    """Issue 26: the Goland wing, loaded as a /flutter body, flutters at ~137 m/s with strip
    theory: the damping of one mode crosses zero there (V-g), its frequency is marked (V-f), and
    the page says so in words."""
    body = _goland()
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(body))
    assert page.is_checked("#mass-on")
    assert page.input_value("#f-mass_per_length") == "35.71"
    assert page.input_value("#f-flutter_count") == "9"
    sent = _ran(tab, "flutter", "#flutter-button")["request"]
    assert sent["wing"]["mass"] == body["wing"]["mass"]
    assert sent["options"] == {"aerodynamics": "strip"}
    assert sent["velocities"] == body["velocities"]
    with server.client() as client:
        expected = client.post("/flutter", json=sent).json()
    onset = expected["flutter"]
    assert onset["velocity"] == pytest.approx(137, abs=3)

    figure = tab.figure("flutter")
    assert figure["state"] == "drawn"
    marks = figure["marks"]
    assert marks["status"] == "flutter"
    assert marks["flutter_velocity"] == pytest.approx(onset["velocity"])
    assert marks["flutter_frequency"] == pytest.approx(onset["frequency"])
    assert marks["divergence_velocity"] == pytest.approx(expected["divergence"]["velocity"])
    modes = figure["modes"]
    assert modes == len(expected["modes"]) >= 2
    for m in range(modes):
        assert figure["series"][f"damping_{m}"]["x"] == [100 + 10 * i for i in range(9)]
        assert len(figure["series"][f"frequency_{m}"]["y"]) == 9
    # The fluttering mode's damping changes sign around the flutter speed (V-g).
    damping = figure["series"][f"damping_{onset['mode']}"]
    below = [g for v, g in zip(damping["x"], damping["y"], strict=True) if v < onset["velocity"]]
    above = [g for v, g in zip(damping["x"], damping["y"], strict=True) if v > onset["velocity"]]
    assert below[-1] > 0 > above[0]
    assert len(figure["series"]["shape_heave_0"]["x"]) == 12  # the first modes' shapes
    # V-g and V-f as a CSV: a row per airspeed, two columns per mode.
    with page.expect_download() as info:
        page.click("#download-flutter")
    rows = list(csv.DictReader(Path(info.value.path()).read_text().splitlines()))
    assert [float(r["velocity [m/s]"]) for r in rows] == damping["x"]
    column = f"mode {onset['mode'] + 1} damping [-]"
    assert [float(r[column]) for r in rows] == pytest.approx(damping["y"])
    assert f"mode {modes} frequency [rad/s]" in rows[0]
    words = page.inner_text("#flutter-status")
    assert f"Flutter at {onset['velocity']:.2f} m/s" in words and "Flutter comes first" in words
    assert page.get_attribute("#fig-flutter", "data-status") == "flutter"
    assert tab.errors_but(0) == []


def test_a_tip_store_goes_into_its_table_and_moves_the_flutter_speed(
    visit: Callable[..., Visit], server: Server
) -> None:
    """A loaded concentrated mass (the Goland wing's tip store, 50 kg, 0.2 m aft) shows in the
    concentrated-mass table and is sent with the uniform mass; the page's flutter speed is the
    API's for that body, ~151 m/s against the clean wing's ~137 m/s (the continuous reference
    with this store: 150.9 m/s, tests/solver/test_flutter.py); a row added by the button goes
    to the tip."""
    body = _goland()
    store = {"station": 11, "mass": 50.0, "inertia": 5.0, "offset": 0.2}
    body["wing"]["mass"]["concentrated"] = [store]
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(body))
    assert page.is_checked("#mass-on")
    assert [page.input_value(f"#concentrated-{k}-0") for k in store] == ["11", "50", "5", "0.2"]
    assert page.inner_text("#concentrated-count") == "1"
    sent = _ran(tab, "flutter", "#flutter-button")["request"]
    assert sent["wing"]["mass"] == body["wing"]["mass"]
    with server.client() as client:
        expected = client.post("/flutter", json=sent).json()
    assert expected["flutter"]["velocity"] == pytest.approx(151, abs=4)  # 12 stations, strip
    marks = tab.figure("flutter")["marks"]
    assert marks["flutter_velocity"] == pytest.approx(expected["flutter"]["velocity"])
    page.click("#add-concentrated")
    assert page.input_value("#concentrated-station-1") == "11"  # the tip of 12 stations
    page.click("#remove-concentrated")
    page.click("#remove-concentrated")
    assert page.inner_text("#concentrated-count") == "none"
    assert tab.errors_but(0) == []


def test_the_study_wing_with_mass_does_not_flutter_in_range_and_says_so(
    visit: Callable[..., Visit],
) -> None:
    """The study's wing with the light mass of the flutter examples (1 kg/m, CG at 42 %, 0.02 kg
    m): no flutter from 2 to 21 m/s, the fold beyond; without a mass the page asks for one."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.click("#flutter-button")  # no mass yet: the page says what is missing, sends nothing
    assert "needs the wing's mass" in page.inner_text("#problem")
    page.check("#mass-on")
    assert [page.input_value(f"#f-{k}") for k in ("mass_per_length", "center_of_gravity")] == [
        "1",
        "0.42",
    ]
    page.fill("#f-flutter_count", "8")
    sent = _ran(tab, "flutter", "#flutter-button")["request"]
    assert sent["wing"]["mass"] == {
        "mass_per_length": 1,
        "center_of_gravity": 0.42,
        "inertia_per_length": 0.02,
    }
    assert sent["flight"] == {"alpha": 5, "density": 1.225}
    marks = tab.figure("flutter")["marks"]
    assert marks["status"] == "no_flutter_in_range" and marks["flutter_velocity"] is None
    assert marks["divergence_velocity"] == pytest.approx(21.44, abs=0.05)
    words = page.inner_text("#flutter-status")
    assert words.startswith("No flutter between 2.00 and 21.00 m/s")
    assert "beyond the airspeeds analysed" in words
    assert page.get_attribute("#fig-flutter", "data-status") == "no_flutter_in_range"
    assert tab.errors == []


def _example(server: Server, path: str, name: str) -> dict[str, Any]:
    """POST `path`'s example `name` from the live server's OpenAPI document."""
    document = httpx.get(server.base_url + "/openapi.json").json()
    content = document["paths"][path]["post"]["requestBody"]["content"]["application/json"]
    return dict(content["examples"][name]["value"])


def test_sizing_loads_of_an_envelope_draw_its_v_n_diagrams_and_loads_envelope(
    visit: Callable[..., Visit], server: Server
) -> None:
    """The loads panel: the /loads envelope example (two weights of the study's wing, CS-23
    normal) is sent as pasted; the V-n figure draws the answer's boundaries and every case at
    its equivalent airspeed and load factor, the envelope figure the answer's extremes along the
    span with the critical case named, and the potato plot each correlated station's cases and
    hull; the cases' table has a row per case, and the envelope's CSV its numbers."""
    body = _example(server, "/loads", "envelope")
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(body))
    assert page.is_checked("#f-loads_envelope")
    assert page.input_value("#f-env_weights") == "250, 300"
    assert page.locator("#cases-table tbody tr").count() == 0
    sent = _ran(tab, "loads", "#loads-button")["request"]
    assert sent["envelope"] == body["envelope"] and "cases" not in sent
    with server.client() as client:
        expected = client.post("/loads", json=sent).json()
    assert expected["info"]["answered"] == len(expected["cases"]) == 20

    vn = tab.figure("vn")
    assert vn["state"] == "drawn" and vn["marks"]["diagrams"] == len(expected["vn"]) == 2
    for i, diagram in enumerate(expected["vn"]):
        assert vn["series"][f"boundary_{i}"]["x"] == pytest.approx(diagram["airspeed"])
        assert vn["series"][f"boundary_{i}"]["y"] == pytest.approx(diagram["load_factor"])
        assert vn["points"][i] == diagram["points"]
    cases = vn["series"]["cases"]
    assert cases["x"] == pytest.approx([c["equivalent_airspeed"] for c in expected["cases"]])
    assert cases["y"] == pytest.approx([c["load_factor"] for c in expected["cases"]])
    rows = page.locator("#vn-table tbody tr")
    assert rows.count() == 20
    assert rows.nth(0).get_attribute("data-case") == expected["cases"][0]["name"]

    envelope = expected["envelope"]
    drawn = tab.figure("envelope")
    assert drawn["state"] == "drawn" and page.is_visible("#fig-envelope")
    for key in ("shear", "bending_moment", "torque"):
        for side in ("max", "min"):
            series = drawn["series"][f"{side}_{key}"]
            assert series["x"] == pytest.approx(envelope["y"])
            assert series["y"] == pytest.approx(envelope[f"{side}_{key}"])
    critical = expected["cases"][envelope["max_bending_moment_case"][0]]["name"]
    assert drawn["marks"]["root_max_bending_moment_case"] == critical
    assert critical in page.inner_text("#vn-verdict")
    # Hovering the root of the bending moment envelope names the case that gives each extreme.
    tooltip = page.evaluate(
        """() => { const chart = Chart.getChart('chart-envelope-moment');
        const point = chart.getDatasetMeta(0).data[0];
        chart.tooltip.setActiveElements([{datasetIndex: 0, index: 0}, {datasetIndex: 1, index: 0}],
          {x: point.x, y: point.y});
        chart.update();
        return chart.tooltip.body.flatMap(b => b.lines); }"""
    )
    lowest = expected["cases"][envelope["min_bending_moment_case"][0]]["name"]
    assert tooltip[0].startswith(f"{critical} (largest bending moment"), tooltip
    assert tooltip[1].startswith(f"{lowest} (smallest bending moment"), tooltip
    for station in expected["correlated"]:
        potato = drawn["series"][f"correlated_{station['station']}"]
        assert potato["x"] == pytest.approx(station["bending_moment"])
        hull = drawn["series"][f"hull_{station['station']}"]
        assert len(hull["x"]) == len(station["hull"]) + 1  # closed
        assert hull["x"][0] == hull["x"][-1]
    # The envelope as a CSV: a row per station, each extreme with the case that gives it.
    with page.expect_download() as info:
        page.click("#download-loads")
    csv_rows = list(csv.DictReader(Path(info.value.path()).read_text().splitlines()))
    assert [float(r["y [m]"]) for r in csv_rows] == pytest.approx(envelope["y"])
    assert csv_rows[0]["max_bending_moment_case"] == critical
    assert tab.errors == []


def test_gust_loads_draw_the_tuned_gust_its_histories_and_the_envelopes(
    visit: Callable[..., Visit], server: Server
) -> None:
    """The gust panel: the /gust study example (the study wing with its mass at 12 m/s, 300 N)
    is sent as pasted (no `gust`: the API's defaults); the time figure draws the tuned gust's
    load factor and tip deflection, and another gradient when chosen; the envelope figure the 1 g
    loads, the 1-cos gusts' totals and turbulence's design loads along the span; the tuned-gust
    figure each gradient's peak load factor and root bending moment, the tuned one and Pratt's
    load factor marked; the numbers table and the CSVs the answer's numbers."""
    body = _example(server, "/gust", "study")
    tab = visit("/")
    tab.ready()
    page = tab.page
    assert page.evaluate("window.__flexwing.operations")["gust"] == {
        "figures": ["gust-time", "gust-envelope", "gust-tuned"]
    }
    assert page.get_attribute("#f-gust_max_gradient", "max") == "10000"
    tab.load_json(json.dumps(body))
    page.wait_for_function("() => !window.__flexwing.state.busy")
    page.click("#gust-details summary")
    sent = _ran(tab, "gust", "#gust-button")["request"]
    assert "gust" not in sent and sent["flight"] == body["flight"]
    with server.client() as client:
        expected = client.post("/gust", json=sent).json()
    tuned = expected["tuned_load_factor"]
    gusts = expected["gusts"]

    timed = tab.figure("gust-time")
    assert timed["state"] == "drawn" and timed["marks"]["case"] == tuned and timed["marks"]["tuned"]
    for key in ("load_factor", "tip_heave", "tip_twist", "root_bending_moment"):
        assert timed["series"][key]["x"] == pytest.approx(gusts[tuned]["time"])
        assert timed["series"][key]["y"] == pytest.approx(gusts[tuned][key])
    other = (tuned + 3) % len(gusts)
    page.select_option("#gust-case", str(other))
    timed = tab.figure("gust-time")
    assert timed["marks"]["gradient"] == pytest.approx(gusts[other]["gradient"])
    assert timed["series"]["load_factor"]["y"] == pytest.approx(gusts[other]["load_factor"])

    drawn = tab.figure("gust-envelope")
    assert drawn["state"] == "drawn" and expected["turbulence"] is not None
    for key in ("shear", "bending_moment", "torque"):
        assert drawn["series"][f"one_g_{key}"]["y"] == pytest.approx(expected[f"one_g_{key}"])
        for side in ("max", "min"):
            discrete = drawn["series"][f"discrete_{side}_{key}"]
            assert discrete["x"] == pytest.approx(expected["y"])
            assert discrete["y"] == pytest.approx(expected["envelope"][f"{side}_{key}"])
            turbulence = drawn["series"][f"turbulence_{side}_{key}"]["y"]
            assert turbulence == pytest.approx(expected["turbulence"][f"{side}_{key}"])
    # The total envelope holds the 1 g loads (the model is linear: up and down are symmetric).
    root = drawn["marks"]
    assert root["root_discrete_max_bending_moment"] >= expected["one_g_bending_moment"][0]
    assert root["root_discrete_min_bending_moment"] <= expected["one_g_bending_moment"][0]

    search = tab.figure("gust-tuned")
    assert search["series"]["load_factor"]["x"] == pytest.approx([g["gradient"] for g in gusts])
    assert search["series"]["load_factor"]["y"] == pytest.approx(
        [g["max_load_factor"] for g in gusts]
    )
    assert search["marks"]["tuned_load_factor"] == max(g["max_load_factor"] for g in gusts)
    assert search["marks"]["tuned_gradient"] == gusts[tuned]["gradient"]
    assert search["marks"]["pratt_load_factor"] == pytest.approx(expected["pratt_load_factor"])
    # The numbers table: each value as the answer's, shown to 5 significant digits.
    cells = page.eval_on_selector_all(
        "#gust-tuned-table tbody tr",
        "rows => rows.map(r => [r.cells[0].textContent, Number(r.cells[1].textContent)])",
    )
    shown = dict(cells)
    for label, value in [
        ("mass ratio mu_g", expected["mass_ratio"]),
        ("Pratt's K_g", expected["pratt_alleviation"]),
        ("Pratt's load factor", expected["pratt_load_factor"]),
        ("tuned gradient H (load factor)", gusts[tuned]["gradient"]),
        ("max load factor n", gusts[tuned]["max_load_factor"]),
    ]:
        assert shown[label] == pytest.approx(value, rel=1e-4), label
    assert f"n = {gusts[tuned]['max_load_factor']:.3f}" in page.inner_text("#gust-time-verdict")
    with page.expect_download() as info:
        page.click("#download-gust-envelope")
    rows = list(csv.DictReader(Path(info.value.path()).read_text().splitlines()))
    assert [float(r["y [m]"]) for r in rows] == pytest.approx(expected["y"])
    assert float(rows[0]["gust_max_bending_moment [N m]"]) == pytest.approx(
        expected["envelope"]["max_bending_moment"][0]
    )
    with page.expect_download() as info:
        page.click("#download-gusts")
    rows = list(csv.DictReader(Path(info.value.path()).read_text().splitlines()))
    assert [float(r["max_load_factor"]) for r in rows] == pytest.approx(
        [g["max_load_factor"] for g in gusts]
    )
    assert tab.errors == []


def test_load_cases_typed_in_the_table_are_sent_as_typed(
    visit: Callable[..., Visit], server: Server
) -> None:
    """The page's own cases (no envelope): an empty cell is not sent, the answer's cases are the
    table's rows in order, and a case the wing cannot fly (an aileron on a wing without one) is
    answered in its place, its status in the table, the others drawn."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    page.click("#loads-details summary")
    assert page.locator("#cases-table tbody tr").count() == 3  # the page's default cases
    # Each column says what it takes (the API's description), an empty cell stays empty.
    assert "load factor" in (page.get_attribute("#case-col-load_factor", "title") or "").lower()
    assert page.input_value("#case-aileron-0") == ""
    page.click("#add-case")
    page.fill("#case-name-3", "rolling")
    page.fill("#case-aileron-3", "5")
    sent = _ran(tab, "loads", "#loads-button")["request"]
    assert "envelope" not in sent and "flight" not in sent
    assert sent["cases"][0] == {
        "name": "pull-up",
        "flight": {"velocity": 12, "weight": 300, "load_factor": 2.5},
    }
    assert sent["cases"][1] == {"name": "cruise", "flight": {"velocity": 14, "weight": 300}}
    assert sent["cases"][3]["aileron"] == 5
    statuses = page.locator("#vn-table tbody tr")
    assert [statuses.nth(i).get_attribute("data-case") for i in range(4)] == [
        "pull-up",
        "cruise",
        "push-over",
        "rolling",
    ]
    assert statuses.nth(3).get_attribute("data-status") == "invalid"
    vn = tab.figure("vn")
    assert vn["series"]["cases"]["y"] == pytest.approx([2.5, 1.0, -1.0])
    assert tab.figure("envelope")["state"] == "drawn"
    assert tab.errors == []


def test_the_flutter_panel_chooses_the_aerodynamics_and_says_which_gave_the_answer(
    visit: Callable[..., Visit],
) -> None:
    """Issue 42: a loaded body's options.aerodynamics shows in the flutter panel's choice; the
    lattice chosen there is sent, and the V-g and V-f diagrams name the model that answered
    (the answer's aerodynamic_model)."""
    tab = visit("/")
    tab.ready()
    page = tab.page
    tab.load_json(json.dumps(_goland()))
    assert page.input_value("#f-flutter_aerodynamics") == "strip"
    _ran(tab, "flutter", "#flutter-button")
    assert tab.figure("flutter")["aerodynamic_model"] == "strip_theory"
    page.select_option("#f-flutter_aerodynamics", "lattice")
    sent = _ran(tab, "flutter", "#flutter-button")["request"]
    assert sent["options"] == {"aerodynamics": "lattice"}
    figure = tab.figure("flutter")
    assert figure["aerodynamic_model"] == "quasi_3d_lattice"
    titles = page.evaluate(
        "['chart-vg', 'chart-vf'].map(id => Chart.getChart(id).options.plugins.title.text)"
    )
    assert all("(quasi-3D lattice)" in title for title in titles), titles
    assert "lagged strip by strip" in page.inner_text("#flutter-note")
    assert tab.errors_but(0) == []


def test_an_operation_the_page_has_no_panel_for_runs_in_a_generic_one(
    browser: Browser, server: Server
) -> None:
    """A new operation of the API (here `echo`, added to the served document, its job answered
    by the test) gets a panel of its own: listed with its figure, it sends the editor's wing
    and flight with a loaded body's other keys, and shows the answer's numbers and its arrays
    along the span."""
    document = httpx.get(server.base_url + "/openapi.json").json()
    body = document["paths"]["/jobs"]["post"]["requestBody"]["content"]["application/json"]
    solve = next(
        document["components"]["schemas"][m["$ref"].rsplit("/", 1)[1]]
        for m in body["schema"]["oneOf"]
        if m["$ref"].endswith("/SolveJobSubmission")
    )
    request_schema = {
        "type": "object",
        "properties": {**_properties(document, solve), "gust_length": {"type": "number"}},
    }
    document["components"]["schemas"]["EchoJobSubmission"] = {
        "type": "object",
        "properties": {"operation": {"const": "echo"}, "request": request_schema},
    }
    body["schema"]["oneOf"].append({"$ref": "#/components/schemas/EchoJobSubmission"})
    document["paths"]["/echo"] = {"post": {"summary": "Echo: a new operation"}}
    answer = {"y": [0.0, 2.5, 5.0], "shear": [30.0, 10.0, 0.0], "totals": {"peak": 42.0}}
    sent: list[dict[str, Any]] = []

    def jobs(route: Any) -> None:
        submitted = route.request.post_data_json if route.request.method == "POST" else {}
        if submitted.get("operation") == "echo":
            sent.append(submitted["request"])
            route.fulfill(json={"id": "echo-1", "status": "succeeded", "result": answer})
        else:
            route.continue_()

    context = browser.new_context(viewport=DESKTOP)
    context.set_default_timeout(TIMEOUT_MS)
    try:
        page = context.new_page()
        tab = Visit(page, server.base_url)
        page.on("pageerror", lambda error: tab.errors.append(f"page error: {error}"))
        page.on("console", lambda m: m.type == "error" and tab.errors.append(m.text))
        page.route("**/openapi.json", lambda route: route.fulfill(json=document))
        page.route("**/jobs", jobs)
        page.goto(server.base_url + "/")
        tab.ready()
        assert page.evaluate("window.__flexwing.operations")["echo"] == {"figures": ["op-echo"]}
        assert "Echo: a new operation" in page.inner_text("#op-echo-details summary")
        loaded = study.solve_request(12.0)
        tab.load_json(json.dumps({**loaded, "gust_length": 7.5}))
        page.wait_for_function("() => !window.__flexwing.state.busy")
        _ran(tab, "echo", "#op-echo-button")
        assert sent[0]["gust_length"] == 7.5
        assert sent[0]["wing"]["chord"][0] == loaded["wing"]["chord"][0]
        assert sent[0]["flight"]["velocity"] == 12.0
        figure = tab.figure("op-echo")
        assert figure["state"] == "drawn" and figure["over"] == "y"
        assert figure["series"]["shear"] == {
            "label": "shear",
            "x": answer["y"],
            "y": answer["shear"],
        }
        assert "totals.peak" in page.inner_text("#op-echo-table")
        assert tab.errors == []
    finally:
        context.close()


def _properties(document: dict[str, Any], submission: dict[str, Any]) -> dict[str, Any]:
    """The properties of a job submission's request (its schema followed by $ref)."""
    request = submission["properties"]["request"]
    while "$ref" in request:
        request = document["components"]["schemas"][request["$ref"].rsplit("/", 1)[1]]
    return dict(request["properties"])
