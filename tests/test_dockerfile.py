"""The Dockerfile's Python one-liners name what the package really exports.

No Docker engine runs in CI, so a renamed function would otherwise break the image's build
unnoticed (the compile step once imported `solver.numerics.compiled.compile_now`, long gone). Each
`python -c "..."` is parsed, never run: every module it imports must import, and every name it
takes from a module (`from m import f`, `m.f`) must exist there.
"""

from __future__ import annotations

import ast
import importlib
import re
from pathlib import Path

import pytest

DOCKERFILE = Path(__file__).resolve().parents[1] / "Dockerfile"
# Shell form (RUN python -c "...") and exec form (["python", "-c", "..."]).
ONE_LINERS = re.findall(r'python"?,? "?-c"?,? "([^"]+)"', DOCKERFILE.read_text())


def test_the_dockerfile_has_its_one_liners():
    # The compile step and the health check.
    assert len(ONE_LINERS) >= 2


@pytest.mark.parametrize("code", ONE_LINERS, ids=[code[:40] for code in ONE_LINERS])
def test_every_name_a_dockerfile_one_liner_uses_exists(code: str):
    tree = ast.parse(code)
    modules: dict[str, object] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                # `import a.b` binds a (and a.b must exist); `import a.b as c` binds a.b.
                module = importlib.import_module(alias.name)
                if alias.asname is None:
                    modules[alias.name.split(".")[0]] = importlib.import_module(
                        alias.name.split(".")[0]
                    )
                else:
                    modules[alias.asname] = module
        elif isinstance(node, ast.ImportFrom) and node.module is not None:
            module = importlib.import_module(node.module)
            for alias in node.names:
                assert hasattr(module, alias.name), f"{node.module} has no {alias.name}"
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
            owner = modules.get(node.value.id)
            if owner is not None:
                assert hasattr(owner, node.attr), f"{node.value.id} has no {node.attr}"
