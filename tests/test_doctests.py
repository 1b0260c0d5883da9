"""The numpydoc Examples of the MTF package run as doctests (fast: no plan, no report)."""

from __future__ import annotations

import doctest
import importlib
import inspect
import pkgutil

import pytest

import scanplan.core.mtf

MODULES = sorted(m.name for m in pkgutil.iter_modules(scanplan.core.mtf.__path__,
                                                     "scanplan.core.mtf."))
#: Modules whose every public function is a formula a reader should see worked.
WITH_EXAMPLES = ("atmosphere", "lens", "sensor", "motion", "threshold", "chain")


@pytest.mark.parametrize("name", MODULES)
def test_examples_run(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS, verbose=False)
    assert result.failed == 0, f"{result.failed} doctest(s) of {name} failed (see stdout)"


@pytest.mark.parametrize("family", WITH_EXAMPLES)
def test_every_public_function_has_an_example(family):
    module = importlib.import_module(f"scanplan.core.mtf.{family}")
    public = [f for n, f in vars(module).items() if inspect.isfunction(f)
              and not n.startswith("_") and f.__module__ == module.__name__]
    assert public
    missing = [f.__name__ for f in public if "\n    Examples\n    --------\n" not in f.__doc__]
    assert not missing


@pytest.mark.parametrize("name", ["scanplan.project.inputs", "scanplan.project.jobs"])
def test_examples_of_the_project_layer_run(name):
    result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS)
    assert result.attempted and result.failed == 0, f"{result.failed} doctest(s) of {name}"


def test_examples_of_the_top_level_api_run():
    import scanplan.api

    result = doctest.testmod(scanplan.api, optionflags=doctest.ELLIPSIS)
    assert result.attempted >= 4 and result.failed == 0


@pytest.mark.parametrize("name", ["scanplan.core.formulas", "scanplan.core.stereo",
                                  "scanplan.core.flight", "scanplan.core.orientation",
                                  "scanplan.core.shown"])
def test_every_formula_of_the_core_has_an_example_that_runs(name):
    """The Instruction's formulas, the recognition model and the block geometry (issue 14,
    item 5): each public function shows a worked example, and the examples run."""
    module = importlib.import_module(name)
    public = [f for n, f in vars(module).items() if inspect.isfunction(f)
              and not n.startswith("_") and f.__module__ == module.__name__]
    assert public
    missing = [f.__name__ for f in public if "\n    Examples\n    --------\n" not in f.__doc__]
    assert not missing
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS, verbose=False)
    assert result.attempted >= len(public) and result.failed == 0


def test_every_example_in_the_package_runs():
    """Every module of scanplan whose docstrings hold an example (``>>>``) runs it: the
    examples are documentation that cannot go stale unnoticed."""
    from pathlib import Path

    root = Path(scanplan.__file__).resolve().parent.parent
    names = sorted(".".join(p.relative_to(root).with_suffix("").parts)
                   for p in (root / "scanplan").rglob("*.py")
                   if ">>>" in p.read_text(encoding="utf-8"))
    assert "scanplan.core.formulas" in names and "scanplan.rules.film" in names
    failed = {}
    for name in names:
        result = doctest.testmod(importlib.import_module(name), optionflags=doctest.ELLIPSIS,
                                 verbose=False)
        if result.failed or not result.attempted:
            failed[name] = result
    assert not failed
