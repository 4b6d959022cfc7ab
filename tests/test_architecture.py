"""The import graph: solver/ in one direction, layer by layer, app/ on solver's public face only,
no cycles, and no import hidden inside a function."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import solver

ROOT = Path(__file__).resolve().parents[1]

# solver/, bottom first: a module may import only from the layers before its own. Packages
# follow the flow (inputs -> model -> numerics -> results -> the analyses -> operations), each
# package's modules on floors of their own; a subpackage's __init__ is its docstring only.
SOLVER_LAYERS: list[list[str]] = [
    ["errors"],
    ["fields"],
    ["inputs.airfoil", "inputs.spar", "inputs.control_surfaces", "inputs.atmosphere"],
    ["inputs.mass"],
    ["inputs.wing", "inputs.flight", "inputs.options", "inputs.envelope"],
    ["inputs.design", "inputs.load_case", "inputs.gust"],
    ["model.layout"],
    ["model.geometry", "model.horseshoe"],
    ["model.vlm", "model.flow_vlm", "model.aerodynamics", "model.beam"],
    ["model.exact_beam"],
    ["model.lag_beam"],
    ["model.strip", "model.symbols"],
    ["model.induced"],
    ["model.flow"],
    ["model.residual"],
    ["numerics.evaluation", "numerics.factors"],
    ["numerics.compiled"],
    ["numerics.newton", "numerics.stability", "numerics.branch_points"],
    ["numerics.continuation"],
    ["numerics.path"],
    ["numerics.cache"],
    ["numerics.warm"],
    ["unsteady_lattice.vortices"],
    ["unsteady_lattice.panels"],
    ["unsteady_lattice.wake"],
    ["unsteady_lattice.circulation"],
    ["results.quantities"],
    ["results.findings"],
    ["results.equilibrium"],
    ["results.sweep", "results.flutter"],
    [
        "results.design",
        "results.controls",
        "results.aerodynamic_forces",
        "results.sizing",
        "results.gusts",
    ],
    ["statics.inertia"],
    ["statics.system"],
    ["statics.trefftz"],
    ["statics.loads"],
    ["statics.jig"],
    ["statics.branch", "statics.validity"],
    ["statics.verdict"],
    ["statics.divergence", "statics.recovery"],
    ["statics.trim"],
    ["statics.solve"],
    ["statics.airspeed_sweep"],
    ["optimization.design_space", "optimization.nlp", "optimization.report"],
    ["optimization.case_space"],
    ["optimization.multipoint"],
    ["optimization.optimize"],
    ["dynamics.modes"],
    ["dynamics.unsteady", "dynamics.lattice_loads"],
    ["dynamics.reduced", "dynamics.aerodynamic_forces"],
    ["dynamics.pk", "dynamics.linearisation"],
    ["dynamics.onset"],
    ["dynamics.flutter"],
    ["controls.antisymmetric", "controls.hinge_moments", "controls.superposition"],
    ["controls.roll"],
    ["controls.effectiveness"],
    ["sizing.regulations", "sizing.gusts"],
    ["sizing.vn"],
    ["sizing.cases", "sizing.envelope"],
    ["sizing.case_loads"],
    ["gusts.indicial", "gusts.profiles"],
    ["gusts.model"],
    ["gusts.discrete", "gusts.turbulence", "gusts.lattice_model"],
    ["gusts.frequency_response"],
    ["gusts.analysis"],
    ["operations.common"],
    ["operations.statics", "operations.design", "operations.dynamics", "operations.controls"],
    ["operations.sizing", "operations.gust"],
    ["operations.table", "deprecated"],
    ["__init__"],
]
SUBPACKAGES = sorted(
    {name.split(".")[0] for layer in SOLVER_LAYERS for name in layer if "." in name}
)


def _modules(package: str) -> dict[str, Path]:
    base = ROOT / package
    return {
        ".".join(path.relative_to(base).with_suffix("").parts): path
        for path in sorted(base.rglob("*.py"))
    }


def _imports(path: Path) -> tuple[set[str], list[int]]:
    """Modules imported at the top level, and the lines of imports anywhere else."""
    tree = ast.parse(path.read_text())
    top: set[str] = set()
    for node in tree.body:
        if isinstance(node, ast.Import):
            top.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            top.add(node.module)
            top.update(f"{node.module}.{alias.name}" for alias in node.names)
    nested = [
        node.lineno
        for node in ast.walk(tree)
        if isinstance(node, ast.Import | ast.ImportFrom) and node not in tree.body
    ]
    return top, nested


def _internal(imported: set[str], package: str, modules: dict[str, Path]) -> set[str]:
    prefix = package + "."
    return {name[len(prefix) :] for name in imported if name[len(prefix) :] in modules}


def test_every_solver_module_has_a_layer():
    layered = {name for layer in SOLVER_LAYERS for name in layer}
    package_faces = {f"{package}.__init__" for package in SUBPACKAGES}
    assert set(_modules("solver")) == layered | package_faces


@pytest.mark.parametrize("package", SUBPACKAGES)
def test_a_solver_subpackage_is_its_modules_and_a_docstring(package: str):
    """Imports go to the module that defines a name, never through a package's face: the layers
    above are then the whole import graph."""
    tree = ast.parse((ROOT / "solver" / package / "__init__.py").read_text())
    assert ast.get_docstring(tree), f"solver.{package} says what it holds"
    assert len(tree.body) == 1, f"solver/{package}/__init__.py holds more than its docstring"


@pytest.mark.parametrize("module", sorted(name for layer in SOLVER_LAYERS for name in layer))
def test_a_solver_module_imports_only_from_the_layers_below(module: str):
    modules = _modules("solver")
    level = {name: i for i, layer in enumerate(SOLVER_LAYERS) for name in layer}
    imported, _ = _imports(modules[module])
    upward = {
        name for name in _internal(imported, "solver", modules) if level[name] >= level[module]
    }
    assert not upward, f"solver.{module} imports {sorted(upward)} from its own layer or above"


@pytest.mark.parametrize("package", ["solver", "app"])
def test_no_module_imports_inside_a_function(package: str):
    for name, path in _modules(package).items():
        _, nested = _imports(path)
        assert not nested, f"{package}.{name} imports inside a function at lines {nested}"


@pytest.mark.parametrize("package", ["solver", "app"])
def test_no_module_imports_relatively(package: str):
    """The layer and public-face checks read absolute imports only: a relative one would pass
    them unseen."""
    for name, path in _modules(package).items():
        relative = [
            node.lineno
            for node in ast.walk(ast.parse(path.read_text()))
            if isinstance(node, ast.ImportFrom) and node.level > 0
        ]
        assert not relative, f"{package}.{name} imports relatively at lines {relative}"


@pytest.mark.parametrize("module", sorted(_modules("app")))
def test_app_uses_only_the_solvers_public_face(module: str):
    imported, _ = _imports(_modules("app")[module])
    private = {name for name in imported if name.startswith("solver.")}
    # `from solver import X` records solver.X: allowed when X is a public name.
    private -= {f"solver.{name}" for name in solver.__all__}
    assert not private, f"app.{module} imports solver internals {sorted(private)}"


def test_app_has_no_import_cycle():
    modules = _modules("app")
    graph = {
        name: {
            other
            for other in _internal(_imports(path)[0], "app", modules)
            if other != name and not name.startswith(other + ".")
        }
        for name, path in modules.items()
    }
    visiting: set[str] = set()
    done: set[str] = set()

    def visit(node: str, trail: list[str]) -> None:
        if node in done:
            return
        assert node not in visiting, "import cycle: " + " -> ".join([*trail, node])
        visiting.add(node)
        for neighbour in sorted(graph[node]):
            visit(neighbour, [*trail, node])
        visiting.discard(node)
        done.add(node)

    for name in sorted(graph):
        visit(name, [])


def test_the_architecture_document_lists_every_module() -> None:
    """docs/architecture.md names every module of solver/ (as `package/module.py` in its
    table) and of app/ (by file name), so it cannot drift from the code."""
    text = (ROOT / "docs" / "architecture.md").read_text()
    unlisted = [
        str(path.relative_to(ROOT / "solver"))
        for path in sorted((ROOT / "solver").rglob("*.py"))
        if path.name != "__init__.py" or path.parent.name == "solver"
        if f"`{path.relative_to(ROOT / 'solver')}`" not in text
    ]
    unlisted += [
        str(path.relative_to(ROOT))
        for path in sorted((ROOT / "app").rglob("*.py"))
        if path.name != "__init__.py" and path.name not in text
    ]
    assert not unlisted, f"docs/architecture.md does not list {unlisted}"
