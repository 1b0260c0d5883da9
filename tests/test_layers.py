"""Import guard for the whole package (as prysm guards its core): each layer of
docs/architecture.md may import only from its own layer and the layers below it.

Every ``import`` and ``from … import`` in every module is read with :mod:`ast` —
function-level (lazy) imports included — so an upward import added anywhere fails here.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import scanplan

PKG = Path(scanplan.__file__).parent

# bottom → top; a module's layer is found by its first name below ``scanplan``
LAYERS: list[tuple[str, set[str]]] = [
    ("base", {"errors", "messages", "messages_archive", "messages_terrain", "_version", "journal",
              "messages_outputs", "messages_uav",
              "outpaths", "safeio"}),
    ("core", {"core"}),
    ("rules", {"rules"}),
    ("norms", {"norms"}),
    ("geo", {"geo"}),
    ("project", {"project"}),
    ("reports", {"reports"}),
    ("api", {"api"}),
    ("web", {"web"}),
    ("cli", {"cli", "__main__", "__init__"}),
]
RANK = {name: i for i, (_, names) in enumerate(LAYERS) for name in names}


def _top(module: str) -> str:
    """'scanplan.core.mtf.chain' → 'mtf'; 'scanplan' (the package itself) → '__init__'."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(PKG.parent).with_suffix("").parts)
    if parts[-1] == "__init__" and len(parts) > 1:
        parts = parts[:-1]
    return ".".join(parts)


def imports_of(text: str, name: str, is_package: bool = False) -> list[tuple[int, str]]:
    """(line, absolute scanplan module) for every import of a scanplan module in the source
    ``text`` of module ``name``."""
    package = name if is_package else name.rpartition(".")[0]
    out = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target == "scanplan":  # from . import x / from scanplan import x
                out += [(node.lineno, f"scanplan.{a.name}") for a in node.names]
            elif target.startswith("scanplan"):
                out.append((node.lineno, target))
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names if a.name.startswith("scanplan")]
    return out


def upward_imports(text: str, name: str, is_package: bool = False) -> list[str]:
    """The imports in module ``name`` (source ``text``) that point to a higher layer."""
    own = _top(name)
    return [f"{name}:{line} imports {target} "
            f"({LAYERS[RANK[_top(target)]][0]} is above {LAYERS[RANK[own]][0]})"
            for line, target in imports_of(text, name, is_package)
            if _top(target) in RANK and RANK[_top(target)] > RANK[own]]


MODULES = sorted(PKG.rglob("*.py"))


def test_every_module_has_a_layer():
    tops = {_top(_module_name(p)) for p in MODULES}
    assert not tops - set(RANK), f"add these to LAYERS: {sorted(tops - set(RANK))}"


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PKG)))
def test_imports_point_down(path):
    problems = upward_imports(path.read_text(encoding="utf-8"), _module_name(path),
                              path.name == "__init__.py")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("line", ["from ..reports import write_atomic",
                                  "from scanplan.cli.main import main",
                                  "import scanplan.project.spec",
                                  "from ..reports import text",
                                  "from .. import geo"])
def test_the_guard_fails_on_an_upward_import(line):
    """The check can fail: an upward import added to a core module is reported."""
    text = (PKG / "core" / "formulas.py").read_text(encoding="utf-8") + f"\n{line}\n"
    assert upward_imports(text, "scanplan.core.formulas")


# -- the project file is read once, in scanplan/project/ ---------------------------------------

ABOVE_PROJECT = [p for p in MODULES
                 if RANK[_top(_module_name(p))] > RANK["project"]]
_SECTIONS = {"project", "map", "norms", "film", "uav", "area", "flight", "terrain", "site",
             "schedule"}
_RAW = {"values", "get", "number", "has", "lines"}  # the loaded file's dict and its readers


def toml_reads(text: str, name: str) -> list[str]:
    """Where module ``name`` (source ``text``) reads the project file's TOML: a
    ``X.get("section", "key")`` call on a project-file section, or the loaded file's
    ``values``/``get``/``number``/``has``/``lines`` read through ``….project``; a layer above
    :mod:`scanplan.project` reads the parsed model (:mod:`scanplan.project.model`) instead."""
    found = []
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr == "get" and len(node.args) >= 2 \
                and all(isinstance(a, ast.Constant) and isinstance(a.value, str)
                        for a in node.args[:2]) \
                and node.args[0].value.split(".")[0] in _SECTIONS:
            found.append(f"{name}:{node.lineno} reads {node.args[0].value}."
                         f"{node.args[1].value} from the TOML")
        if isinstance(node, ast.Attribute) and node.attr in _RAW:
            owner = node.value
            last = owner.attr if isinstance(owner, ast.Attribute) else getattr(owner, "id", "")
            if last == "project":
                found.append(f"{name}:{node.lineno} reads project.{node.attr} (the TOML dict)")
    return found


@pytest.mark.parametrize("path", ABOVE_PROJECT, ids=lambda p: str(p.relative_to(PKG)))
def test_nothing_above_the_project_layer_reads_the_toml(path):
    problems = toml_reads(path.read_text(encoding="utf-8"), _module_name(path))
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("line", ['x = result.project.values["map"]["scale"]',
                                  'x = spec.project.get("map", "scale")',
                                  'x = p.get("project", "purpose")',
                                  'x = result.project.number("site", "lat_deg", -90, 90)',
                                  'x = p.get("norms.gsd_limits", "reason")'])
def test_the_toml_guard_fails_on_a_read(line):
    """The check can fail: a TOML read added to a report module is reported."""
    text = (PKG / "reports" / "text.py").read_text(encoding="utf-8") + f"\n{line}\n"
    assert toml_reads(text, "scanplan.reports.text")


def _circles(package: str) -> list[set[str]]:
    """The import circles (strongly connected modules, lazy imports counted) inside
    ``package``."""
    graph = {}
    for p in MODULES:
        name = _module_name(p)
        if name.startswith(package + "."):
            graph[name] = {t for _, t in imports_of(p.read_text(encoding="utf-8"), name,
                                                    p.name == "__init__.py")}

    def reach(start: str) -> set[str]:
        seen, todo = set(), [start]
        while todo:
            for t in graph.get(todo.pop(), ()):
                if t in graph and t not in seen:
                    seen.add(t)
                    todo.append(t)
        return seen

    reached = {n: reach(n) for n in graph}
    circles: list[set[str]] = []
    for n in graph:
        circle = {m for m in reached[n] if n in reached[m]} | {n}
        if len(circle) > 1 and circle not in circles:
            circles.append(circle)
    return circles


KNOWN_CIRCLES = [
    # the user's [project] defaults are checked with the project file's own type checks
    {"scanplan.project.file", "scanplan.project.userconfig"},
]


def test_no_import_circle_inside_the_project_layer():
    """The specification, the survey design and the records import one way (results ←
    design ← spec); the one circle left is named in KNOWN_CIRCLES."""
    assert [c for c in _circles("scanplan.project") if c not in KNOWN_CIRCLES] == []
