"""No development bookkeeping in the text a user reads.

Issue numbers and the internal names of the source papers ("seed 001") belong in code
comments, not in the README, the manuals, the example projects, the report templates, the
``--help`` texts, the public API's docstrings, the engine's messages or the report labels:
there a paper is cited by its authors and year.
"""

from __future__ import annotations

import inspect
import re
from collections.abc import Iterator
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

import scanplan
from scanplan.cli.main import main
from scanplan.messages import MESSAGES
from scanplan.reports.labels import AIRCRAFT_LABELS, LABELS
from scanplan.reports.labels_cli import CLI

ROOT = Path(__file__).resolve().parent.parent

# "issue 11", "issues 12", "issue #3", "seed 001", "seeds 0 and 1", "Seed 002" — also when
# a line break (a wrapped --help text or paragraph) falls between the word and the number
BOOKKEEPING = re.compile(r"\b(?:issues?\s+#?\d+|seeds?\s+\d)", re.IGNORECASE)


def _hits(text: str) -> list[str]:
    """The bookkeeping phrases in ``text``, each with a little context."""
    return [" ".join(text[max(m.start() - 30, 0):m.end() + 20].split())
            for m in BOOKKEEPING.finditer(text)]


def _files() -> Iterator[Path]:
    yield ROOT / "README.md"
    yield from sorted((ROOT / "docs").rglob("*.md"))
    yield from sorted((ROOT / "examples").rglob("*.toml"))
    yield from sorted(p for p in (ROOT / "templates").rglob("*") if p.is_file())


def _text(path: Path) -> str | None:
    data = path.read_bytes()
    if b"\0" in data:  # a font: no text of ours
        return None
    return data.decode("utf-8", errors="replace")


@pytest.mark.parametrize("path", list(_files()), ids=lambda p: str(p.relative_to(ROOT)))
def test_files(path: Path) -> None:
    text = _text(path)
    assert text is None or not _hits(text), _hits(text or "")


def _commands(group: click.Group, path: tuple[str, ...] = ()
              ) -> Iterator[tuple[str, ...]]:
    yield path
    ctx = click.Context(group)
    for name in group.list_commands(ctx):
        cmd = group.get_command(ctx, name)
        if isinstance(cmd, click.Group):
            yield from _commands(cmd, (*path, name))
        elif cmd is not None:
            yield (*path, name)


def test_help_texts() -> None:
    runner = CliRunner()
    found = {}
    paths = list(_commands(main))
    assert len(paths) > 5  # the walk reached the subcommands
    for path in paths:
        result = runner.invoke(main, [*path, "--help"], terminal_width=100)
        assert result.exit_code == 0, (path, result.output)
        if hits := _hits(result.output):
            found[" ".join(("scanplan", *path))] = hits
    assert not found


def _docstrings() -> Iterator[tuple[str, str]]:
    """What ``help()`` shows of the package and of each name it exports."""
    yield "scanplan", scanplan.__doc__ or ""
    for name in scanplan.__all__:
        obj = getattr(scanplan, name)
        if isinstance(obj, str):  # __version__
            continue
        yield name, inspect.getdoc(obj) or ""
        if inspect.isclass(obj):
            for attr, member in vars(obj).items():
                if attr.startswith("_") and attr != "__init__":
                    continue
                doc = inspect.getdoc(member) if not isinstance(member, str) else None
                if doc and doc != inspect.getdoc(type(member)):
                    yield f"{name}.{attr}", doc


def test_api_docstrings() -> None:
    found = {name: hits for name, doc in _docstrings() if (hits := _hits(doc))}
    assert not found


def test_messages() -> None:
    found = {f"{code} [{loc}]": hits for code, per_locale in MESSAGES.items()
             for loc, text in per_locale.items() if (hits := _hits(text))}
    assert not found


@pytest.mark.parametrize("table", ["LABELS", "AIRCRAFT_LABELS", "CLI"])
def test_report_labels(table: str) -> None:
    labels = {"LABELS": LABELS, "AIRCRAFT_LABELS": AIRCRAFT_LABELS, "CLI": CLI}[table]
    if all(isinstance(v, dict) and set(v) <= {"en", "ru"} for v in labels.values()):
        items = ((f"{key} [{loc}]", text) for key, per in labels.items()
                 for loc, text in per.items())  # key → locale → text
    else:
        items = ((f"{key} [{loc}]", text) for loc, per in labels.items()
                 for key, text in per.items())  # locale → key → text
    found = {key: hits for key, text in items if (hits := _hits(str(text)))}
    assert not found
