"""``scanplan norms``: list, show, validate, import and template norm sets.

Registered by :mod:`scanplan.cli.main` (``main.add_command(norms)``); it also runs on its own
(``norms.main(args)``). Every problem is an :class:`~scanplan.errors.InputError`: printed as
``error: ...`` on stderr (or as JSON with ``--json``) with exit code 2, never a traceback.
A failure to write (:class:`~scanplan.errors.WriteError`: disk full, permission, an
interrupted rename) is exit code 1 with ``error: cannot write PATH: REASON``. The commands
raise; the group applies the command line's error policy (:mod:`scanplan.cli.errors`).
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import textwrap
from pathlib import Path
from typing import Any

import click

from .. import norms as _norms
from ..errors import InputError
from ..norms.schema import PARAMETERS, TABLES
from .errors import PolicyGroup, json_errors
from .options import complete_norms

__all__ = ["norms"]


def _table(rows: list[list[str]], header: list[str]) -> str:
    widths = [max(len(str(x)) for x in col) for col in zip(header, *rows, strict=False)]
    lines = ["  ".join(str(h).ljust(w) for h, w in zip(header, widths, strict=False)).rstrip()]
    lines.append("  ".join("-" * w for w in widths))
    for r in rows:
        lines.append("  ".join(str(x).ljust(w) for x, w in zip(r, widths, strict=False)).rstrip())
    return "\n".join(lines)


def _txt(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, list | tuple):
        return ",".join(map(str, v))
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)


_JSON = click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")


@click.group("norms", cls=PolicyGroup)
def norms() -> None:
    """Norm sets: list, show, validate and import spreadsheets, write a template.

    A norm set holds the coefficients of a technical instruction, shape coefficients,
    the smallest map objects per map scale, and optionally cameras and scanners. Bundled
    sets ship with scanplan; imported ones live in $SCANPLAN_NORMS_DIR (else the user data
    folder: ~/.local/share/scanplan/norms on Linux,
    ~/Library/Application Support/scanplan/norms on macOS,
    %LOCALAPPDATA%\\scanplan\\norms on Windows). See docs/norms.md.

    \b
    Example:
      scanplan norms template my-norms.xlsx
      (edit it in Excel)
      scanplan norms validate my-norms.xlsx
      scanplan norms import my-norms.xlsx --name my-enterprise
      scanplan scan --norms my-enterprise --map-scale 2000 --relief 1 \\
                    --photo-scale 10000 --camera rc30-153
    """


_LOCALE = click.option(
    "--locale",
    type=click.Choice(["en", "ru"]),
    default="en",
    show_default=True,
    help="Language of the listing (headers, titles, numbers); sources are shown as the "
    "norm set stores them.",
)


def _w(key: str, locale: str, **fields: Any) -> str:
    from ..i18n.labels_cli import cli_text

    return cli_text(key, locale, **fields)


@norms.command("list")
@_JSON
@_LOCALE
@json_errors
def list_cmd(as_json: bool, locale: str = "en") -> None:
    """List the bundled and imported norm sets.

    \b
    Example:
      scanplan norms list
      scanplan norms list --json
    """
    # an import a crash interrupted: put the set it was replacing back, drop its leftovers
    with contextlib.suppress(OSError):
        for line in _norms.recover_norm_dir():
            click.echo(f"note: {line}", err=True)
    out = []
    for name, where in _norms.list_norm_sets():
        if name.startswith("."):
            continue  # a leftover of an interrupted import
        try:
            ns = _norms.load_norm_set(
                name if where == "bundled" else _norms.user_norms_dir() / name
            )
            item = {
                "name": name,
                "where": where,
                "title": ns.title_ru if locale == "ru" and ns.title_ru and not as_json
                else ns.title,
                "imported_from": ns.imported_from,
                "imported_at": ns.imported_at,
                "path": str(ns.path),
                "ok": True,
            }
        except InputError as exc:
            item = {
                "name": name,
                "where": where,
                "title": "",
                "imported_from": "",
                "imported_at": "",
                "path": "",
                "ok": False,
                "error": str(exc),
            }
        out.append(item)
    if as_json:
        click.echo(
            json.dumps(
                {"norm_sets": out, "user_dir": str(_norms.user_norms_dir())},
                ensure_ascii=False,
                indent=2,
            )
        )
        return
    where_word = {"bundled": _w("ns_bundled", locale), "user": _w("ns_user", locale)}
    rows = [
        [
            i["name"],
            where_word.get(i["where"], i["where"]) + ("" if i["ok"] else _w("ns_broken", locale)),
            i["imported_at"][:10],
            textwrap.shorten(i["title"] or i.get("error", ""), 70, placeholder=" …"),
        ]
        for i in out
    ]
    head = [_w(k, locale) for k in ("ns_name", "ns_where", "ns_imported", "ns_title")]
    click.echo(_table(rows, head))
    click.echo("\n" + _w("ns_user_dir", locale, path=_norms.user_norms_dir()))


@norms.command("show")
@click.argument("name", shell_complete=complete_norms)
@_JSON
@_LOCALE
@json_errors
def show_cmd(name: str, as_json: bool, locale: str = "en") -> None:
    """Show a norm set: meta, parameters (value, unit, source) and tables.

    NAME is a bundled or imported set name, or a norm-set folder.

    \b
    Example:
      scanplan norms show gkinp-02-036-02
      scanplan norms show my-enterprise --json
    """
    try:
        loaded = _norms.load_norm_set(name)
    except InputError as exc:  # named by the argument typed here, not by --norms
        if exc.field != "--norms":
            raise
        raise InputError("NAME", exc.message) from None
    data = _norms.norm_set_dict(loaded)
    if as_json:
        click.echo(json.dumps(data, ensure_ascii=False, indent=2))
        return
    if locale == "ru":
        click.echo(_show_ru(data, name))
        return
    out = [f"{data['name']} ({'bundled' if data['bundled'] else 'user'}: {data['path']})"]
    for key in ("title", "title_ru", "source", "imported_from", "imported_at"):
        if data[key]:
            out.append(f"  {key}: {data[key]}")
    out.append("\nparameters")
    out.append(
        _table(
            [[k, _txt(v["value"]), v["unit"], v["source"]] for k, v in data["parameters"].items()],
            ["name", "value", "unit", "source"],
        )
    )
    for tname in ("shapes", "objects", "gsd_limits", "cameras", "scanners"):
        rows = data.get(tname) or []
        if not rows:
            continue
        cols = [
            c.name
            for c in TABLES[tname].columns
            if c.name != "source" and any(r.get(c.name) not in (None, "") for r in rows)
        ]
        out.append(f"\n{tname}")
        out.append(_table([[_txt(r.get(c)) for c in cols] for r in rows], cols))
    click.echo("\n".join(out))


def _txt_ru(v: Any) -> str:
    """:func:`_txt` in Russian: a decimal comma, lists joined by "; "."""
    if isinstance(v, list | tuple):
        return "; ".join(_txt_ru(x) for x in v)
    if isinstance(v, float):
        return f"{v:g}".replace(".", ",")
    return _txt(v)


def _show_ru(data: dict[str, Any], name: str) -> str:
    """``norms show`` in Russian: the tables and columns as the Russian norm workbook
    names them (``norms template --locale ru``), parameters by their Russian names."""
    from ..reports.wording import param_name

    ns = _norms.load_norm_set(name)
    where = _w("ns_bundled" if data["bundled"] else "ns_user", "ru")
    out = [f"{data['name']} ({where}: {data['path']})"]
    if data["title_ru"] or data["title"]:
        out.append(f"  {_w('ns_title', 'ru')}: {data['title_ru'] or data['title']}")
    if data["source"]:
        out.append(f"  {_w('source', 'ru')}: {data['source']}")
    for key in ("imported_from", "imported_at"):
        if data[key]:
            out.append(f"  {_w('ns_imported', 'ru')}: {data[key]}")
    out.append("\n" + _w("ns_parameters", "ru"))
    out.append(
        _table(
            [[param_name(ns, k, "ru"), _param_ru(ns, k, v["value"]), v["source"]]
             for k, v in data["parameters"].items()],
            [_w("ns_parameter", "ru"), _w("ns_value", "ru"), _w("source", "ru")],
        )
    )
    for tname in ("shapes", "objects", "gsd_limits", "cameras", "scanners"):
        rows = data.get(tname) or []
        if not rows:
            continue
        cols = [
            c
            for c in TABLES[tname].columns
            if c.name != "source" and any(r.get(c.name) not in (None, "") for r in rows)
        ]
        out.append("\n" + (TABLES[tname].title_ru or tname))
        out.append(_table([[_txt_ru(r.get(c.name)) for c in cols] for r in rows],
                          [_ru_header(c) for c in cols]))
    return "\n".join(out)


def _ru_header(col: Any) -> str:
    """A column as the Russian norm workbook heads it (its first Russian alias)."""
    return next((a for a in col.aliases if re.search("[А-Яа-яЁё]", a)), col.name)


def _param_ru(ns: Any, key: str, value: Any) -> str:
    """A parameter's value in Russian words (a shape, a formula) or with a decimal comma."""
    from ..reports.formatter import formatter
    from ..reports.wording import param_value

    try:
        text = param_value(ns, key, value, "ru", number=formatter("ru").g)
    except (KeyError, ValueError, TypeError):
        text = ""
    return text or _txt_ru(value)


def _summary(parsed: _norms.ParsedNormSet) -> dict[str, Any]:
    return {
        "ok": True,
        "file": parsed.source_file,
        "tables": parsed.counts(),
        "from_file": list(parsed.from_file),
        "base": parsed.base,
        "warnings": list(parsed.warnings),
    }


_TABLE = click.option(
    "--table",
    type=click.Choice(list(TABLES)),
    default=None,
    help="Table a CSV holds (default: from its name or headers).",
)
_BASE = click.option(
    "--base",
    default=None,
    metavar="NAME|PATH",
    help="Set supplying what the file lacks (a CSV always has one: default "
    f"{_norms.DEFAULT_NORM_SET}).",
)


@norms.command("validate")
@click.argument("file", type=click.Path(dir_okay=False, path_type=Path))
@_TABLE
@_BASE
@_JSON
@json_errors
def validate_cmd(file: Path, table: str | None, base: str | None, as_json: bool) -> None:
    """Check a norm workbook (.xlsx) or CSV without writing anything.

    Every problem is listed with a cell address you can paste into Excel's Name Box,
    the header, the value, the rule and a hint. Exit code 2 when there are problems.

    \b
    Example:
      scanplan norms validate my-norms.xlsx
      scanplan norms validate objects.csv --json
    """
    parsed = _norms.read_norm_file(file, table=table, base=base)
    if as_json:
        click.echo(json.dumps(_summary(parsed), ensure_ascii=False, indent=2))
        return
    click.echo(
        f"{file.name}: OK — "
        + ", ".join(f"{n} {k}" for k, n in parsed.counts().items())
        + (
            f" (base {parsed.base}; from the file: {', '.join(parsed.from_file)})"
            if parsed.base
            else ""
        )
    )
    for w in parsed.warnings:
        click.echo(f"note: {w}", err=True)


@norms.command("import")
@click.argument("file", type=click.Path(dir_okay=False, path_type=Path))
@click.option("--name", required=True, help="Name of the new user set (a folder name).")
@click.option("--force", is_flag=True, help="Replace an existing user set of that name.")
@click.option("--title", default=None, help="Title of the set (default: from the file).")
@_TABLE
@_BASE
@_JSON
@json_errors
def import_cmd(
    file: Path,
    name: str,
    force: bool,
    title: str | None,
    table: str | None,
    base: str | None,
    as_json: bool,
) -> None:
    """Import a norm workbook (.xlsx) or CSV as a user norm set.

    Nothing is written unless the whole file is valid; an existing set is replaced only
    with --force, atomically. A .csv holds one table and is merged onto --base (default
    the bundled set): it replaces that table, or for parameters only the parameters it
    names.

    \b
    Example:
      scanplan norms import my-norms.xlsx --name my-enterprise
      scanplan norms import objects.csv --name my-objects --base gkinp-02-036-02
      scanplan norms import my-norms.xlsx --name my-enterprise --force --json
    """
    path, parsed = _norms.import_norm_file(
        file, name, force=force, table=table, base=base, title=title
    )
    if as_json:
        click.echo(
            json.dumps(
                {**_summary(parsed), "name": name, "path": str(path)}, ensure_ascii=False, indent=2
            )
        )
        return
    click.echo(
        f"imported {file.name} as norm set {name!r} ({path}): "
        + ", ".join(f"{n} {k}" for k, n in parsed.counts().items())
    )
    for w in parsed.warnings:
        click.echo(f"note: {w}", err=True)
    click.echo(f"use it with: scanplan scan --norms {name} ...")


@norms.command("template")
@click.argument("file", type=click.Path(dir_okay=False, path_type=Path))
@click.option(
    "--norms",
    "norm_set",
    default=_norms.DEFAULT_NORM_SET,
    metavar="NAME|PATH",
    show_default=True,
    help="Set to pre-fill the workbook with.",
)
@click.option(
    "--locale",
    "--lang",
    "lang",
    type=click.Choice(["en", "ru"]),
    default="en",
    show_default=True,
    help="Sheet names and headers in English or Russian (--lang: the same, the older "
    "spelling).",
)
@click.option("--no-catalogue", is_flag=True, help="Leave out the cameras and scanners.")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
@_JSON
@json_errors
def template_cmd(
    file: Path, norm_set: str, lang: str, no_catalogue: bool, force: bool, as_json: bool
) -> None:
    """Write a norm workbook pre-filled with a norm set, to edit and import back.

    One sheet per table, header comments with units and rules, data validation on
    numeric columns. Importing it unchanged gives the same set.

    \b
    Example:
      scanplan norms template my-norms.xlsx
      scanplan norms template my-norms-ru.xlsx --locale ru --norms gkinp-02-036-02-printed
    """
    out = _norms.write_template(
        file, norm_set, lang=lang, catalogue=not no_catalogue, force=force
    )
    if as_json:
        click.echo(
            json.dumps(
                {"ok": True, "file": str(out), "norms": norm_set, "lang": lang},
                ensure_ascii=False,
                indent=2,
            )
        )
        return
    click.echo(f"wrote {out} (pre-filled with {norm_set}; {len(PARAMETERS)} parameters)")
    click.echo(f"next: edit it, then scanplan norms import {os.fspath(file)} --name NAME")
