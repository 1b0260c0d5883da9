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
    ("base", {"errors", "i18n", "_version", "io", "progress", "extras", "offline"}),
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


# geo/ holds the ground and the geometry; the constraints are evaluated at every photo's own
# height in rules/terrain.py and the two are joined in project/terraincheck.py. geo/ ranks
# above rules/ in LAYERS (so an import would not be upward), hence this check of its own.
GEO_MAY_NOT_IMPORT = ("scanplan.rules",)


def rules_imports_of_geo(text: str, name: str, is_package: bool = False) -> list[str]:
    """The imports of ``rules`` (lazy ones and TYPE_CHECKING ones included) in geo module
    ``name``."""
    return [f"{name}:{line} imports {target} (geo/ keeps the ground and the geometry; "
            "evaluate constraints in rules/terrain.py)"
            for line, target in imports_of(text, name, is_package)
            if target.startswith(GEO_MAY_NOT_IMPORT)]


GEO_MODULES = [p for p in MODULES if _top(_module_name(p)) == "geo"]


@pytest.mark.parametrize("path", GEO_MODULES, ids=lambda p: str(p.relative_to(PKG)))
def test_geo_imports_nothing_of_rules(path):
    problems = rules_imports_of_geo(path.read_text(encoding="utf-8"), _module_name(path),
                                    path.name == "__init__.py")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("line", ["from ..rules.results import UavInputs",
                                  "    from ..rules.uav import ground_resolution_m",
                                  "import scanplan.rules.film",
                                  "from .. import rules"])
def test_the_geo_guard_fails_on_a_rules_import(line):
    """The check can fail: a rules import added to geo/terrain.py (at any depth) is found."""
    text = (PKG / "geo" / "terrain.py").read_text(encoding="utf-8")
    body = f"\ndef _probe():\n{line}\n" if line.startswith(" ") else f"\n{line}\n"
    assert rules_imports_of_geo(text + body, "scanplan.geo.terrain")


# -- no import circle inside a package, no private name imported from outside it ----------

#: Every package and sub-package of scanplan (found from the sources, ``scanplan`` itself
#: included) is kept free of import circles (lazy imports counted): a circle makes the
#: import order matter and hides which module is below which.
#: Packages whose private names (``_name``) a module outside them never uses: what another
#: package needs is a public name (``core/checks.py`` holds the core's input checks). Every
#: top-level package and module of scanplan, and these sub-packages:
SEALED_SUBPACKAGES = ("scanplan.core.mtf", "scanplan.geo.export")
#: … except these, each with the reason it is not sealed yet.
NOT_YET_SEALED: dict[str, str] = {}


def _inside(module: str, package: str) -> bool:
    return module == package or module.startswith(package + ".")


def _from_target(node: ast.ImportFrom, name: str, is_package: bool) -> str:
    """The absolute module a ``from … import`` in module ``name`` reads from."""
    if not node.level:
        return node.module or ""
    parts = (name if is_package else name.rpartition(".")[0]).split(".")
    return ".".join(parts[: len(parts) - (node.level - 1)] + ([node.module] if node.module
                                                              else []))


def import_graph(sources: dict[str, tuple[str, bool]]) -> dict[str, set[str]]:
    """module → the modules of ``sources`` it imports anywhere (lazy imports included);
    ``sources`` is module → (source text, whether it is a package's ``__init__``).
    ``from P import m`` imports the module ``P.m`` when there is one, else ``P``."""
    graph: dict[str, set[str]] = {}
    for name, (text, is_package) in sources.items():
        found = []
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.ImportFrom):
                target = _from_target(node, name, is_package)
                found += [f"{target}.{a.name}" if f"{target}.{a.name}" in sources else target
                          for a in node.names]
            elif isinstance(node, ast.Import):
                found += [a.name for a in node.names]
        targets = set()
        for target in found:
            while target not in sources and "." in target:
                target = target.rpartition(".")[0]
            if target in sources and target != name:
                targets.add(target)
        graph[name] = targets
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import circles of ``graph``: its strongly connected parts of two or more
    modules (Tarjan's algorithm, iterative), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found: list[list[str]] = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                part = []
                while True:
                    top = stack.pop()
                    part.append(top)
                    if top == node:
                        break
                if len(part) > 1:
                    found.append(sorted(part))
    return found


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_imports(sources: dict[str, tuple[str, bool]], package: str) -> list[str]:
    """Where a module outside ``package`` uses a private name (``_x``) of a module in it:
    imports it (``from scanplan.core.flight import _positive``) or reads it from the module
    (``from scanplan.norms import cells; cells._fail``) —
    ``"scanplan.reports.x:12 imports scanplan.core.flight._positive"``."""
    out = []
    for name, (text, is_package) in sources.items():
        if _inside(name, package):
            continue
        tree = ast.parse(text)
        modules: dict[str, str] = {}  # a local name bound to a module of the package
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                target = _from_target(node, name, is_package)
                for alias in node.names:
                    if _inside(f"{target}.{alias.name}", package) \
                            and f"{target}.{alias.name}" in sources:
                        modules[alias.asname or alias.name] = f"{target}.{alias.name}"
                if _inside(target, package):
                    out += [f"{name}:{node.lineno} imports {target}.{alias.name}"
                            for alias in node.names if _private(alias.name)]
            elif isinstance(node, ast.Import):
                modules.update({alias.asname: alias.name for alias in node.names
                                if alias.asname and _inside(alias.name, package)})
        out += [f"{name}:{node.lineno} reads {modules[node.value.id]}.{node.attr}"
                for node in ast.walk(tree)
                if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                and node.value.id in modules and _private(node.attr)]
    return out


SOURCES = {_module_name(p): (p.read_text(encoding="utf-8"), p.name == "__init__.py")
           for p in MODULES}


PACKAGES = sorted(name for name, (_, is_package) in SOURCES.items() if is_package)
CHECKED = PACKAGES


def package_circles(sources: dict[str, tuple[str, bool]], package: str) -> list[list[str]]:
    """The import circles among the modules of ``package`` (lazy imports counted)."""
    inside = {name: source for name, source in sources.items() if _inside(name, package)}
    return circles(import_graph(inside))


@pytest.mark.parametrize("package", CHECKED)
def test_no_import_circle_inside_the_package(package):
    found = package_circles(SOURCES, package)
    assert found == [], "\n".join(" ↔ ".join(c) for c in found)


def test_the_packages_are_found_from_the_sources():
    """Every sub-package is checked, not a hand list: core/mtf, geo/export, rules, web …"""
    assert {"scanplan", "scanplan.core.mtf", "scanplan.geo.export", "scanplan.rules",
            "scanplan.project", "scanplan.web", "scanplan.norms", "scanplan.reports",
            "scanplan.reports.views", "scanplan.reports.excel", "scanplan.i18n"} <= set(CHECKED)


@pytest.mark.parametrize("package", ["scanplan.web", "scanplan"])
def test_the_package_guard_sees_a_lazy_circle(package):
    """The check can fail: a function-level import added to web/mapdata.py that reads
    back from web/jobs.py (which calls it) is a circle of web/ and of scanplan."""
    sources = dict(SOURCES)
    text, is_package = sources["scanplan.web.mapdata"]
    sources["scanplan.web.mapdata"] = (text + "\n\ndef _probe():\n    from .jobs import "
                                       "PROJECT_NAME\n", is_package)
    assert package_circles(SOURCES, package) == []
    assert package_circles(sources, package) == [["scanplan.web.jobs", "scanplan.web.mapdata"]]


SEALED = sorted({".".join(name.split(".")[:2]) for name in SOURCES} - set(NOT_YET_SEALED)
                - {"scanplan"}) + list(SEALED_SUBPACKAGES)


@pytest.mark.parametrize("package", SEALED)
def test_no_private_name_is_used_from_outside_the_package(package):
    problems = private_imports(SOURCES, package)
    assert not problems, "\n".join(problems)


def test_the_guards_see_a_lazy_circle_and_a_private_import():
    """The checks can fail: a circle closed by a function-level import, and a private
    name of core imported by a report module."""
    sources = {
        "scanplan.io.a": ("from .b import x\n", False),
        "scanplan.io.b": ("def x():\n    from .c import y\n", False),
        "scanplan.io.c": ("def y():\n    from scanplan.io import a\n", False),
        "scanplan.io.d": ("from .a import z\n", False),
    }
    assert circles(import_graph(sources)) == [["scanplan.io.a", "scanplan.io.b",
                                               "scanplan.io.c"]]
    sources["scanplan.io.c"] = ("def y():\n    pass\n", False)
    assert circles(import_graph(sources)) == []
    report = {"scanplan.reports.x": ("from ..core.flight import _first_bad, MAX_BLUR_PX\n"
                                     "from ..core import checks as c\n"
                                     "def f():\n    return c._first_bad, c.finite\n",
                                     False),
              "scanplan.core.checks": ("def _first_bad(): pass\n", False),
              "scanplan.core.flight": ("from .checks import _first_bad\n", False)}
    assert private_imports(report, "scanplan.core") == [
        "scanplan.reports.x:1 imports scanplan.core.flight._first_bad",
        "scanplan.reports.x:4 reads scanplan.core.checks._first_bad"]
    assert private_imports(report, "scanplan.reports") == []


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
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.func.id == "getattr" and len(node.args) >= 2 \
                and isinstance(node.args[1], ast.Constant) and node.args[1].value in _RAW:
            # getattr(project, "get", None): the loaded file's reader, looked up by name
            found.append(f"{name}:{node.lineno} looks up the TOML reader "
                         f"{node.args[1].value!r} with getattr")
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.args and isinstance(node.args[0], ast.Constant) \
                and isinstance(node.args[0].value, str) \
                and node.args[0].value.split(".")[0] in _SECTIONS \
                and node.func.id in _RAW:
            found.append(f"{name}:{node.lineno} reads [{node.args[0].value}] through a "
                         f"bound {node.func.id}()")
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
                                  'x = p.get("norms.gsd_limits", "reason")',
                                  'get = getattr(spec.project, "get", None)',
                                  'x = get("uav", key)'])
def test_the_toml_guard_fails_on_a_read(line):
    """The check can fail: a TOML read added to a report module is reported."""
    text = (PKG / "reports" / "text.py").read_text(encoding="utf-8") + f"\n{line}\n"
    assert toml_reads(text, "scanplan.reports.text")
