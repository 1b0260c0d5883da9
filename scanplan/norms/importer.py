"""Assembling a norm set from a read file: every table checked, cross-table rules,
all problems collected (:func:`read_norm_file`)."""

from __future__ import annotations

import csv
import os
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError
from . import store as _norms
from .cells import (
    _ALL_TABLES,
    _SHEET_INDEX,
    ImportProblem,
    NormImportError,
    Problems,
    _is_empty,
    _match,
    _norm,
    _printable,
    check_file,
    fail,
)
from .csvfile import _read_csv_grid
from .grid import _data_rows, _find_header, _Grid, _Located, _Row, _Table
from .limits import CSV_SUFFIXES, META_KEYS, META_TABLE, XLSX_SUFFIXES
from .schema import PARAMETERS, TABLES
from .xlsx import _read_xlsx

# =========================================================================================
# Assembling a set
# =========================================================================================


@dataclass(frozen=True)
class ParsedNormSet:
    """A checked norm set, ready to write.

    Attributes
    ----------
    source_file : str
        Name of the file it came from.
    tables : dict
        Table name → rows (dicts of schema column → canonical text), ready for CSV.
    meta : dict
        ``title``, ``title_ru``, ``source`` (from the workbook's ``set`` sheet or the base).
    base : str or None
        The base set the file was merged onto.
    from_file : tuple of str
        Tables the file supplied (the rest came from ``base``).
    warnings : tuple of str
        Notes (ignored sheets and columns).
    """

    source_file: str
    tables: dict[str, list[dict[str, str]]]
    meta: dict[str, str]
    base: str | None = None
    from_file: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()

    def counts(self) -> dict[str, int]:
        """Rows per table."""
        return {k: len(v) for k, v in self.tables.items()}


def _base_tables(base: str) -> tuple[dict[str, _Table], dict[str, str], str]:
    """The tables of a base norm set (as grids read from its CSV files)."""
    ns = _norms.load_norm_set(base)  # checks it and resolves name or path
    tables: dict[str, _Table] = {}
    scratch = Problems()
    for spec in TABLES.values():
        p = ns.path / spec.file
        if not p.is_file():
            continue
        with p.open(encoding="utf-8", newline="") as fh:
            rows = [tuple(r) for r in csv.reader(fh)]
        grid = _Grid(p.stem, rows, file_label=f"{ns.name}/{spec.file}")
        loc = _find_header(grid, spec, scratch)
        if loc is not None:
            tables[spec.name] = _data_rows(loc, scratch)
    if scratch.total:  # the loader accepted it, so this would be a bug
        raise NormImportError(f"base set {base}", scratch.items, scratch.total)
    meta = {"title": ns.title, "title_ru": ns.title_ru, "source": ns.source}
    return tables, meta, ns.name


def _locate_csv_table(grid: _Grid, table: str | None, name: str,
                      candidates: tuple[str, ...] | None = None) -> _Located:
    problems = Problems()
    if table:
        spec = _ALL_TABLES.get(table) or _ALL_TABLES.get(_match(_SHEET_INDEX, table) or "")
        if spec is None or spec is META_TABLE:
            raise InputError("--table", f"unknown table {table!r}; one of {', '.join(TABLES)}")
        loc = _find_header(grid, spec, problems)
        problems.raise_if_any(name)
        assert loc is not None
        return loc
    names = candidates or tuple(TABLES)
    by_name = _match(_SHEET_INDEX, grid.label)
    if by_name in names:
        loc = _find_header(grid, TABLES[by_name], problems)
        problems.raise_if_any(name)
        assert loc is not None
        return loc
    scored = []
    for spec in (TABLES[n] for n in names):
        loc = _find_header(grid, spec, None)
        if loc is not None:
            scored.append((len(loc.columns) / len(spec.columns), len(loc.columns), loc))
    scored.sort(key=lambda t: (t[0], t[1]), reverse=True)
    if not scored:
        raise fail(
            name,
            "its header row matches no norm table",
            f"name the file after the table ({names[0]}.csv, ...) or give --table "
            + "|".join(names),
        )
    if len(scored) > 1 and scored[0][:2] == scored[1][:2]:
        raise fail(
            name,
            "its header row fits tables "
            f"{scored[0][2].spec.name!r} and {scored[1][2].spec.name!r} equally",
            "give --table",
        )
    return scored[0][2]


def _duplicate_keys(tables: dict[str, _Table], problems: Problems) -> None:
    """A second row with the key of an earlier one (in every table)."""
    for t in tables.values():
        seen: dict[tuple[str, ...], _Row] = {}
        for row in t.rows:
            if any(k not in row.values for k in t.spec.key):
                continue
            key = tuple(row.values[k] for k in t.spec.key)
            if key in seen:
                first = seen[key]
                problems.add(
                    row.problem(
                        t.spec.key[-1] if t.spec.name == "scanners" else t.spec.key[0],
                        f"duplicate {'/'.join(t.spec.key)}: the same as "
                        f"{first.grid.address(first.number, first.cols.get(t.spec.key[0], 1))}",
                        "keep one row per " + "/".join(t.spec.key),
                    )
                )
            else:
                seen[key] = row


class _ShapeResolver:
    """Resolves a shape cell to a shape id of the shapes table (its Russian name or id,
    any case), reporting one it does not name."""

    def __init__(self, shapes: _Table | None, problems: Problems) -> None:
        self.shapes = shapes
        self.problems = problems
        self.ids = [r.values["shape"] for r in shapes.rows if "shape" in r.values] if shapes else []
        self.by_name: dict[str, str] = {}
        for r in shapes.rows if shapes else ():
            for alt in (r.values.get("name_ru", ""), r.values.get("shape", "")):
                if alt:
                    self.by_name.setdefault(alt.casefold(), r.values["shape"])

    def __call__(self, row: _Row, column: str, what: str) -> None:
        if column not in row.values:
            return  # already reported
        given = row.values[column]
        if given in self.ids or not self.shapes:
            return
        if given.casefold() in self.by_name:
            row.values[column] = self.by_name[given.casefold()]
            return
        self.problems.add(
            row.problem(
                column,
                f"{what} must be a shape of the shapes table ({', '.join(self.ids) or 'none'})",
                "add it to the shapes sheet or fix the spelling",
            )
        )


def _check_parameters(params: _Table, resolve: _ShapeResolver, problems: Problems) -> None:
    """The default shape names a shape; every parameter is defined."""
    for row in params.rows:
        if row.values.get("name") == "shape":
            resolve(row, "value", "the default shape")
    defined = {r.values.get("name") for r in params.rows}
    missing = [p for p in PARAMETERS if p not in defined]
    if not missing:
        return
    g = params.grid
    last = max((r.number for r in params.rows), default=params.header_row) + 1
    for p in missing:
        spec = PARAMETERS[p]
        problems.add(
            ImportProblem(
                g.address(last, params.cols.get("name", 1), "name"),
                f"missing parameter {p!r} ({spec.description}); must be "
                f"{spec.value.describe()}",
                hint=f'add a row "{p}"' + (f' (or "{spec.aliases[-1]}")' if spec.aliases else ""),
            )
        )


def _cross_checks(
    tables: dict[str, _Table], problems: Problems, label: str, present: set[str]
) -> None:
    """The rules the loader checks across rows and tables, all collected."""
    _duplicate_keys(tables, problems)
    resolve = _ShapeResolver(tables.get("shapes"), problems)
    params = tables.get("parameters")
    if params is not None:
        _check_parameters(params, resolve, problems)
    objects = tables.get("objects")
    if objects is not None:
        for row in objects.rows:
            resolve(row, "shape", f"the shape of {row.values.get('object', '')!r}")
    for name in ("parameters", "shapes", "objects"):
        if name not in tables and name not in present:  # a broken sheet is reported already
            spec = TABLES[name]
            problems.add(
                ImportProblem(
                    label,
                    f"no sheet for table {name!r} ({spec.description})",
                    hint=f'add a sheet named "{spec.name}" or "{spec.title_ru}", or import '
                    "with --base NAME to take it from another set",
                )
            )


@dataclass
class _Found:
    """The tables located in a file: data tables, the ``set`` sheet, the sheets present."""

    located: list[_Located]
    meta: _Located | None
    present: set[str]


def _locate_sheets(
    grids: list[_Grid], label: str, problems: Problems, warnings: list[str]
) -> _Found:
    """Each workbook sheet named after a table, its header row found; other sheets noted."""
    found = _Found([], None, set())
    seen: dict[str, str] = {}
    for g in grids:
        name = _match(_SHEET_INDEX, g.label)
        if name is None:
            warnings.append(
                f"sheet {g.label!r} ignored (not a norm table: {', '.join(_ALL_TABLES)})"
            )
            continue
        if name in seen:
            problems.add(
                ImportProblem(
                    g.address(1, 1),
                    f"a second sheet for table {name!r} (the first is {seen[name]!r})",
                    hint="delete or rename one of them",
                )
            )
            continue
        seen[name] = g.label
        found.present.add(name)
        loc = _find_header(g, _ALL_TABLES[name], problems)
        if loc is None:
            continue
        if name == META_TABLE.name:
            found.meta = loc
        else:
            found.located.append(loc)
    if not found.present:  # an import that takes nothing from the file is an error
        sheets = ", ".join(repr(_printable(g.label, 60)) for g in grids) or "none"
        raise fail(
            label,
            f"no sheet is a norm table (sheets: {sheets}); nothing would be imported",
            "name each sheet after its table: " + ", ".join(_ALL_TABLES)
            + " (Excel names a new sheet after the file or 'Sheet1'; rename it)",
        )
    return found


def _locate_file(
    p: Path, table: str | None, problems: Problems, warnings: list[str],
    candidates: tuple[str, ...] | None = None,
) -> _Found:
    """The tables of a workbook or of a CSV (by the file's suffix); other files refused."""
    suffix = p.suffix.lower()
    if suffix in XLSX_SUFFIXES:
        return _locate_sheets(_read_xlsx(p), p.name, problems, warnings)
    if suffix in CSV_SUFFIXES:
        return _Found([_locate_csv_table(_read_csv_grid(p), table, p.name, candidates)], None,
                      set())
    if suffix == ".xls":
        raise fail(
            p.name,
            "is an old binary Excel file (.xls)",
            'save it from Excel as "Excel Workbook (*.xlsx)"',
        )
    raise fail(p.name, f"unknown file type {suffix or '(none)'}; give .xlsx or .csv")


def _note_ignored_columns(located: list[_Located], warnings: list[str]) -> None:
    """A note for each header cell that is no column of its table."""
    for loc in located:
        known = {c for c, _ in loc.columns.values()}
        for c in range(1, loc.grid.width(loc.header_row) + 1):
            h = loc.grid.value(loc.header_row, c)
            if c not in known and not _is_empty(h):
                warnings.append(
                    f'{loc.grid.address(loc.header_row, c)}: column "{_printable(h, 200)}" '
                    "ignored (not a column of table "
                    f"{loc.spec.name!r})"
                )


def _read_meta(
    meta_loc: _Located, meta: dict[str, str], problems: Problems, warnings: list[str]
) -> None:
    """The ``set`` sheet's title, title_ru and source into ``meta``; other keys noted."""
    for row in _data_rows(meta_loc, problems).rows:
        key = _norm(row.values.get("key", "")).replace(" ", "_")
        if key in META_KEYS:
            meta[key] = row.values.get("value", "")
        else:
            warnings.append(
                f"{row.grid.address(row.number, row.cols['key'])}: "
                f"key {row.values.get('key')!r} ignored ({', '.join(META_KEYS)})"
            )


def _merge_tables(tables: dict[str, _Table], file_tables: dict[str, _Table]) -> None:
    """The file's tables over the base's: whole tables replaced, parameters by name."""
    for name, t in file_tables.items():
        if name == "parameters" and name in tables:  # merge by parameter name
            given = {r.values.get("name") for r in t.rows}
            kept = [r for r in tables[name].rows if r.values["name"] not in given]
            t.rows = kept + t.rows
        tables[name] = t


def read_norm_file(
    path: str | os.PathLike[str], *, table: str | None = None, base: str | None = None,
    candidates: tuple[str, ...] | None = None,
) -> ParsedNormSet:
    """Read and check a norm workbook (.xlsx) or a single-table CSV.

    Parameters
    ----------
    path : str or path
        The file. ``.xlsx``/``.xlsm``: one sheet per table (sheet names are table names
        or their Russian titles). ``.csv``/``.txt``/``.tsv``: one table.
    table : str, optional
        The table a CSV holds (default: from the file name, else from its headers).
    candidates : tuple of str, optional
        The tables a CSV may hold when ``table`` is not given (default: every table);
        ``scanplan cameras import`` takes cameras, scanners and lens MTF only.
    base : str, optional
        A norm set (name or folder) supplying what the file lacks. A CSV is always merged
        onto a base (default the bundled set); a workbook only when ``base`` is given.
        Merging replaces whole tables, except ``parameters``, which merge by name.

    Returns
    -------
    ParsedNormSet

    Raises
    ------
    NormImportError
        Listing every problem (cell address, header, value, rule, hint).
    InputError
        For an unreadable file, or one over the size limits.
    """
    p = Path(path)
    check_file(p)
    problems = Problems()
    warnings: list[str] = []
    found = _locate_file(p, table, problems, warnings, candidates)
    if p.suffix.lower() in CSV_SUFFIXES:
        base = base or _norms.DEFAULT_NORM_SET
    _note_ignored_columns(found.located, warnings)
    file_tables = {loc.spec.name: _data_rows(loc, problems) for loc in found.located}
    if p.suffix.lower() in CSV_SUFFIXES and candidates is None:  # cameras: their own word
        for name, t in file_tables.items():
            if not t.rows:  # merged onto the base, a header alone would import nothing
                raise fail(p.name, f"holds the header of the {name} table and no rows; give "
                           "at least one row (a norm set's own values)")

    meta = {k: "" for k in META_KEYS}
    base_name = None
    tables: dict[str, _Table] = {}
    if base:
        tables, base_meta, base_name = _base_tables(base)
        meta["source"] = f"base set {base_name}" + (
            f": {base_meta['source']}" if base_meta["source"] else ""
        )
    if found.meta is not None:
        _read_meta(found.meta, meta, problems, warnings)
    _merge_tables(tables, file_tables)
    _cross_checks(tables, problems, p.name, found.present)
    problems.raise_if_any(p.name)
    order = [n for n in TABLES if n in tables]
    canonical = {
        n: [{c.name: r.values.get(c.name, "") for c in TABLES[n].columns} for r in tables[n].rows]
        for n in order
    }
    return ParsedNormSet(p.name, canonical, meta, base_name, tuple(file_tables), tuple(warnings))
