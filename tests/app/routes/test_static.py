"""The page's files, without a browser: served from the app, no inline code, licences beside the
vendored libraries, a strict Content-Security-Policy (tests/app/routes/test_page.py runs the
page)."""

from __future__ import annotations

import re
from html.parser import HTMLParser

import httpx
import pytest

from app.routes.page import STATIC_DIR

PAGES = {"/": "index.html", "/docs": "docs.html"}


class _Assets(HTMLParser):
    """What an HTML file loads, and any inline code or style in it."""

    def __init__(self) -> None:
        super().__init__()
        self.urls: list[str] = []
        self.inline: list[str] = []
        self._in_script = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        values = dict(attrs)
        for name, value in attrs:
            if name.startswith("on") or name == "style":
                self.inline.append(f"<{tag} {name}=...>")
            if name in ("src", "href") and value and tag in ("script", "link", "img"):
                self.urls.append(value)
        if tag == "style":
            self.inline.append("<style>")
        self._in_script = tag == "script" and "src" not in values

    def handle_data(self, data: str) -> None:
        if self._in_script and data.strip():
            self.inline.append(f"<script>{data.strip()[:40]}")

    def handle_endtag(self, tag: str) -> None:
        self._in_script = False


def _assets(name: str) -> _Assets:
    parser = _Assets()
    parser.feed((STATIC_DIR / name).read_text())
    return parser


@pytest.mark.parametrize("name", sorted(PAGES.values()))
def test_no_inline_code_or_style(name: str) -> None:
    assert _assets(name).inline == []


def test_no_eval_in_the_page_scripts() -> None:
    for path in sorted((STATIC_DIR / "js").rglob("*.js")):
        text = path.read_text()
        assert not re.search(r"\beval\(|new Function\(|setTimeout\(\s*[\"'`]", text), path


@pytest.mark.parametrize("path", sorted(PAGES))
def test_pages_and_their_assets_are_served_from_the_app(client: httpx.Client, path: str) -> None:
    page = client.get(path)
    assert page.status_code == 200
    assert page.headers["content-type"].startswith("text/html")
    assert "default-src 'self'" in page.headers["content-security-policy"]
    assert client.head(path).status_code == 200
    urls = _assets(PAGES[path]).urls
    assert urls
    for url in urls:
        assert not re.match(r"^(https?:)?//", url), f"{url} is not served by the app"
        asset = client.get("/" + url)
        assert asset.status_code == 200, url
        kind = asset.headers["content-type"]
        expected = {".js": "javascript", ".css": "text/css", ".svg": "svg", ".png": "image/png"}
        assert expected[url[url.rindex(".") :]] in kind, (url, kind)


# Every static import: `import ... from "x";` (over several lines too) and `import "x";`.
IMPORT = re.compile(r"""^import\s+(?:[^"';]*?\s+from\s+)?"([^"]+)";""", re.M | re.S)


def test_modules_import_only_files_of_the_app(client: httpx.Client) -> None:
    """Every module in js/ and its folders imports only modules of the app, by a relative path
    that is served (a module of a folder imports from its parent as "../x.js")."""
    root = STATIC_DIR / "js"
    imported = set()
    for path in sorted(root.rglob("*.js")):
        for target in IMPORT.findall(path.read_text()):
            assert target.startswith(("./", "../")), (path.name, target)
            resolved = (path.parent / target).resolve()
            assert resolved.is_relative_to(root), (path.name, target)
            url = resolved.relative_to(STATIC_DIR).as_posix()
            assert client.get(f"/static/{url}").status_code == 200, (path.name, target)
            imported.add(resolved)
    # Every module but the entry points (main.js, and swagger-init.js of /docs) is imported.
    entries = {root / "main.js", root / "swagger-init.js"}
    assert set(root.rglob("*.js")) - entries <= imported


def test_redoc_is_gone_and_the_page_routes_are_not_in_the_api(in_process: httpx.Client) -> None:
    assert in_process.get("/redoc").status_code == 404
    paths = in_process.get("/openapi.json").json()["paths"]
    assert not {"/", "/docs", "/static"} & set(paths)


def test_every_vendored_library_has_its_licence_and_a_line_in_the_readme() -> None:
    vendor = STATIC_DIR / "vendor"
    readme = (vendor / "README.md").read_text()
    folders = [p for p in vendor.iterdir() if p.is_dir()]
    assert {p.name for p in folders} == {"chart.js-4.6.1", "swagger-ui-dist-5.35.0"}
    for folder in folders:
        assert any(p.name.startswith("LICENSE") for p in folder.iterdir()), folder
        assert f"`{folder.name}/`" in readme
