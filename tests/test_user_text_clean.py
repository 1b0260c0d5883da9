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
from scanplan.i18n.labels import AIRCRAFT_LABELS, LABELS
from scanplan.i18n.labels_cli import CLI
from scanplan.i18n.messages import MESSAGES

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


# --- the norm sets as `scanplan norms` shows them --------------------------------------

BUNDLED_SETS = [name for name, where in scanplan.norms.list_norm_sets() if where == "bundled"]
#: The ways ``scanplan norms`` prints a set's text (sources, notes, titles); the group has no
#: ``export`` command: ``show --json`` is the export.
SHOW_ARGS = [("--locale", "en"), ("--locale", "ru"), ("--json",)]


def _norms_show(name: str, *args: str) -> str:
    result = CliRunner().invoke(main, ["norms", "show", name, *args], terminal_width=200)
    assert result.exit_code == 0, result.output
    return result.output


def test_every_bundled_set_is_shown() -> None:
    listed = CliRunner().invoke(main, ["norms", "list", "--json"])
    assert listed.exit_code == 0, listed.output
    import json

    bundled = [s["name"] for s in json.loads(listed.output)["norm_sets"]
               if s["where"] == "bundled"]
    assert sorted(bundled) == sorted(BUNDLED_SETS) and len(BUNDLED_SETS) >= 2
    assert "export" not in main.commands["norms"].commands  # else check it below too


@pytest.mark.parametrize("args", SHOW_ARGS, ids=" ".join)
@pytest.mark.parametrize("name", BUNDLED_SETS)
def test_norms_show(name: str, args: tuple[str, ...]) -> None:
    out = _norms_show(name, *args)
    assert "Miheeva & Ilushenko 2015" in out  # the sources are there, by authors and year
    assert not _hits(out), _hits(out)


@pytest.mark.parametrize("lang", ["en", "ru"])
@pytest.mark.parametrize("name", BUNDLED_SETS)
def test_norms_template(name: str, lang: str, tmp_path: Path) -> None:
    """The workbook ``norms template`` pre-fills with a set: every cell and comment."""
    import openpyxl

    out = tmp_path / "t.xlsx"
    result = CliRunner().invoke(main, ["norms", "template", str(out), "--norms", name,
                                       "--locale", lang])
    assert result.exit_code == 0, result.output
    found = {}
    for ws in openpyxl.load_workbook(out).worksheets:
        for row in ws.iter_rows():
            for cell in row:
                for text in (cell.value, cell.comment.text if cell.comment else None):
                    if isinstance(text, str) and (hits := _hits(text)):
                        found[f"{ws.title}!{cell.coordinate}"] = hits
    assert not found


def test_bundled_norm_files() -> None:
    """The bundled tables and set files cite the papers by authors and year; only the
    ``old_aliases`` of ``references.toml`` keep the old names (read, never printed)."""
    import tomllib

    folder = ROOT / "norms"
    found = {str(p.relative_to(folder)): hits for p in sorted(folder.rglob("*"))
             if p.is_file() and (hits := _hits("\n".join(
                 line for line in p.read_text("utf-8").splitlines()
                 if not line.startswith("old_aliases = "))))}
    assert not found
    data = tomllib.loads((folder / "references.toml").read_text("utf-8"))
    olds = [old for ref in data["reference"] for old in ref.get("old_aliases", ())]
    assert olds and all(re.fullmatch(r"seed 00\d", old) for old in olds), olds


# --- old norm files (a template filled in, or a set imported, by an earlier version) ---

OLD_OBJECTS = ("map_scale,object,size_m,shape,source\n"
               "2000,poles,0.2,circle,seed 001 Table 3\n"
               '5000,wells,0.7,circle,"GKINP (GNTA)-02-036-02; seed 001 eq. 1 (V_s)"\n'
               "10000,pipes,1.0,rectangle,Seed 002 names no lens; seed 000 eq. 6\n")


@pytest.mark.parametrize(("old", "new"), [
    ("seed 001 Table 3", "Miheeva & Ilushenko 2015, Table 3"),
    ("GKINP (GNTA)-02-036-02; seed 001 eq. 1 (V_s)",
     "GKINP (GNTA)-02-036-02; Miheeva & Ilushenko 2015, eq. 1 (V_s)"),
    ("seed 001 after eq. 9, ref. [3]", "Miheeva & Ilushenko 2015, after eq. 9, ref. [3]"),
    ("quoted in seed 001 (18x18 cm)", "quoted in Miheeva & Ilushenko 2015 (18x18 cm)"),
    ("Seed 002 names no lens", "Zverev & Fisenko 2014 names no lens"),
    ("seed 000, eq. 6", "UAS-FP paper, eq. 6"),
    ("seeds 001", "seeds 001"),  # not a name of a work
    ("Miheeva & Ilushenko 2015, Table 3", "Miheeva & Ilushenko 2015, Table 3"),
    ("", ""),
])
def test_old_names_are_read_as_authors_and_year(old: str, new: str) -> None:
    from scanplan.norms.citations import modern_citation

    assert modern_citation(old) == new


def test_an_old_norm_file_imports_without_its_old_names(user_dir: Path, tmp_path: Path
                                                        ) -> None:
    old = tmp_path / "objects.csv"
    old.write_text(OLD_OBJECTS, encoding="utf-8")
    result = CliRunner().invoke(main, ["norms", "import", str(old), "--name", "old"])
    assert result.exit_code == 0, result.output
    written = (user_dir / "old" / "objects.csv").read_text("utf-8")
    assert not _hits(written) and "Miheeva & Ilushenko 2015, Table 3" in written
    for args in SHOW_ARGS:
        out = _norms_show("old", *args)
        assert not _hits(out), (args, _hits(out))


def test_a_set_imported_by_an_earlier_version_is_shown_without_its_old_names(
        user_dir: Path) -> None:
    """A user set on disk written with the old names: shown, exported to a template and
    cited in the reports by authors and year (the files themselves are left alone)."""
    import shutil

    from scanplan.norms import load_norm_set
    from scanplan.reports.references import Bibliography

    target = user_dir / "from-2025"
    shutil.copytree(ROOT / "norms" / "gkinp-02-036-02", target)
    for p in target.iterdir():
        text = p.read_text("utf-8").replace('"Miheeva & Ilushenko 2015, ', '"seed 001 ')
        p.write_text(text.replace("Miheeva & Ilushenko 2015", "seed 001"), encoding="utf-8")
    assert _hits((target / "parameters.csv").read_text("utf-8"))  # old names on disk
    for args in SHOW_ARGS:
        out = _norms_show("from-2025", *args)
        assert not _hits(out), (args, _hits(out))
        assert "Miheeva & Ilushenko 2015" in out
    ns = load_norm_set(str(target))
    cells = [ns.source, *ns.parameter_sources.values(), *(o.source for o in ns.objects)]
    assert not [c for c in cells if _hits(c)]
    poles = next(o for o in ns.objects if o.map_scale == 2000)
    assert poles.source == "Miheeva & Ilushenko 2015, Table 3"
    assert Bibliography("en").cite(poles.source) == "[1], Table 3"
