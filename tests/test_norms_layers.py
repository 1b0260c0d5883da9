"""The norms package's layering: each module imports only the modules below it, no cycle,
and nothing in it (nor the file readers and atomic writers of io/) reaches up into reports
or the CLI."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import scanplan

PKG = Path(scanplan.__file__).parent
NORMS = PKG / "norms"

# Bottom first: a module may import only the modules listed before it.
ORDER = ("schema", "paths", "citations", "control", "airspace", "aircraft", "limits",
         "recovery", "records", "store", "cells", "grid",
         "sheetscan", "xlsx",
         "csvfile", "importer", "writer", "export", "template")
# scanplan modules above the norms layer (reports, project files, the CLI and the API).
ABOVE = ("reports", "cli", "cli_norms", "cli_cameras", "cli_init", "spec", "api",
         "serialize", "project", "cameras_io")


def _imports(path: Path) -> tuple[set[str], set[str]]:
    """(sibling modules imported with ``from . import`` / ``from .x``, scanplan modules
    imported with ``from ..x``), anywhere in the module (lazy imports included)."""
    siblings: set[str] = set()
    parents: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, ast.ImportFrom):
            continue
        if node.level == 1:
            if node.module:
                siblings.add(node.module.split(".")[0])
            else:
                siblings |= {a.name for a in node.names}
        elif node.level == 2 and node.module:
            parents.add(node.module.split(".")[0])
        elif node.level == 0 and node.module and node.module.startswith("scanplan."):
            parents.add(node.module.split(".")[1])
    return siblings, parents


def test_every_module_is_in_the_order():
    present = {p.stem for p in NORMS.glob("*.py")} - {"__init__"}
    assert present == set(ORDER)


@pytest.mark.parametrize("module", ORDER)
def test_imports_point_down(module):
    siblings, parents = _imports(NORMS / f"{module}.py")
    below = set(ORDER[: ORDER.index(module)])
    assert siblings <= below, (module, sorted(siblings - below))
    assert not parents & set(ABOVE), (module, sorted(parents & set(ABOVE)))


@pytest.mark.parametrize("path", sorted((PKG / "io").glob("*.py")), ids=lambda p: p.name)
def test_io_is_below_reports_and_norms(path):
    _, parents = _imports(path)  # level 2 here means a scanplan module
    assert not parents & {"reports", "norms", *ABOVE}


def test_the_guard_sees_an_upward_import(tmp_path):
    """The check above fails when a lower module imports a higher one."""
    bad = tmp_path / "cells.py"
    bad.write_text("from .writer import write_norm_set\nfrom ..reports import ReportMeta\n",
                   encoding="utf-8")
    siblings, parents = _imports(bad)
    assert not siblings <= set(ORDER[: ORDER.index("cells")])
    assert parents & set(ABOVE) == {"reports"}
