"""The page and the documentation in a real browser when the service has API keys (issue 16):
the page asks for a key, refuses a wrong one, and with the right one solves and sweeps; Swagger
UI takes a key through Authorize. Both under the strict Content-Security-Policy, nothing loaded
from elsewhere. (tests/app/routes/test_page.py drives the page without keys.)"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import pytest
from playwright.sync_api import Browser

from app.security.keys import add_key
from tests.app.conftest import Server
from tests.app.routes.test_page import Visit, browser, pytestmark, visits

__all__ = ["browser", "pytestmark"]  # the fixture and the marks of tests/app/routes/test_page.py


@pytest.fixture(scope="module")
def key(tmp_path_factory: pytest.TempPathFactory) -> tuple[str, str]:
    """(the key file, alice's key)."""
    file = tmp_path_factory.mktemp("keys") / "keys.txt"
    return str(file), add_key(file, "alice")


@pytest.fixture(scope="module")
def keyed_server(
    make_server: Callable[..., Server],
    key: tuple[str, str],
    tmp_path_factory: pytest.TempPathFactory,
) -> Server:
    tmp = tmp_path_factory.mktemp("keyed_page")
    return make_server(
        "keyed_page_server",
        FLEXWING_API_KEYS_FILE=key[0],
        FLEXWING_JOBS_DB=str(tmp / "jobs.sqlite3"),
        FLEXWING_COMPILE="0",
        FLEXWING_CACHE_DIR=str(tmp / "cache"),
        FLEXWING_WORKERS="1",
    )


@pytest.fixture
def visit(browser: Browser, keyed_server: Server) -> Iterator[Callable[..., Visit]]:
    """A path of the keyed server in a fresh browser context (own storage)."""
    with visits(browser, keyed_server.base_url) as open_:
        yield open_


def test_the_page_asks_for_a_key_and_works_with_the_right_one(
    visit: Callable[..., Visit], key: tuple[str, str]
) -> None:
    tab = visit("/")
    tab.ready()  # its first solve and sweep were refused
    page = tab.page
    assert page.get_attribute("#problem", "data-type") == "/problems/key-missing"
    assert page.is_visible("#api-key")
    assert "needs an API key" in page.inner_text("#problem")

    before = tab.runs()
    page.fill("#api-key", "fw_" + "x" * 43)
    page.click("#api-key-form button[type=submit]")
    page.wait_for_function(
        "(n) => window.__flexwing.state.runs.failed >= n + 2 && !window.__flexwing.state.busy",
        arg=before["failed"],
    )
    assert page.get_attribute("#problem", "data-type") == "/problems/key-invalid"

    before = tab.runs()
    page.fill("#api-key", key[1])
    page.click("#api-key-form button[type=submit]")
    tab.wait_runs("sweep", before)
    assert tab.runs()["solve"] == before["solve"] + 1
    assert tab.total("lift") == "304.1 N"
    assert tab.figure("14.4")["marks"]["fold_velocity"] == pytest.approx(21.44, abs=0.01)
    # Kept for this tab only: never in localStorage, a cookie or a URL.
    assert key[1] not in page.evaluate("() => JSON.stringify(localStorage)")
    assert page.context.cookies() == []
    assert not any(key[1] in url for url in tab.requests)
    assert tab.errors_but(401) == []
    assert tab.outside() == []


def test_the_docs_take_a_key_through_authorize(
    visit: Callable[..., Visit], key: tuple[str, str]
) -> None:
    tab = visit("/docs")
    page = tab.page
    page.wait_for_selector(".opblock-summary-path >> text=/solve")
    page.click("button.authorize")
    page.fill(".modal-ux-content input", key[1])
    page.click(".modal-ux-content button.modal-btn.authorize")
    page.click(".modal-ux-content button.btn-done")
    page.click(".opblock-post:has-text('/solve') .opblock-summary")
    page.click("button.try-out__btn")
    page.click("button.execute")
    page.wait_for_selector(".live-responses-table .response-col_status >> text=200")
    assert tab.errors == []
    assert tab.outside() == []
