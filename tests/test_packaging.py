"""pyproject.toml: what `pip install .` ships."""

from __future__ import annotations

import tomllib

from tests import study


def test_every_app_package_is_installed() -> None:
    """pyproject lists packages explicitly: a new subpackage of app/ must be added there, or
    `pip install .` (the Dockerfile) ships an app that cannot import it."""
    pyproject = tomllib.loads((study.ROOT / "pyproject.toml").read_text())
    listed = set(pyproject["tool"]["setuptools"]["packages"])
    app_dir = study.ROOT / "app"
    found = {
        ".".join(init.parent.relative_to(study.ROOT).parts) for init in app_dir.rglob("__init__.py")
    }
    assert found <= listed
