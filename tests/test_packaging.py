"""pyproject.toml: what `pip install .` ships."""

from __future__ import annotations

import tomllib

import setuptools

from tests import study


def test_every_package_of_solver_and_app_is_installed() -> None:
    """pyproject finds the packages by pattern: every subpackage of solver/ and app/ (a new one
    included) must match it, or `pip install .` (the Dockerfile) ships code that cannot import
    it."""
    pyproject = tomllib.loads((study.ROOT / "pyproject.toml").read_text())
    include = pyproject["tool"]["setuptools"]["packages"]["find"]["include"]
    shipped = set(setuptools.find_packages(where=str(study.ROOT), include=include))
    present = {
        ".".join(init.parent.relative_to(study.ROOT).parts)
        for top in ("solver", "app")
        for init in (study.ROOT / top).rglob("__init__.py")
    }
    assert len(present) > 10
    assert present <= shipped
    assert not {name for name in shipped if name.split(".")[0] not in ("solver", "app")}
