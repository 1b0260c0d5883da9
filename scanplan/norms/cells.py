"""Problems of an input file, and turning a cell's raw value into a checked value
(numbers typed as text, scales, percents, header aliases)."""

from __future__ import annotations

import dataclasses
import datetime as _dt
import math
import re
import stat
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import InputError, NotFoundError
from ..io.files import file_kind
from . import limits as _limits
from .limits import META_TABLE
from .schema import PARAMETERS, TABLES, TableSpec, ValueSpec

_EXCEL_ERRORS = frozenset(
    (
        "#NULL!",
        "#DIV/0!",
        "#VALUE!",
        "#REF!",
        "#NAME?",
        "#NUM!",
        "#N/A",
        "#GETTING_DATA",
        "#SPILL!",
        "#CALC!",
        "#FIELD!",
        "#BLOCKED!",
        "#CONNECT!",
        "#UNKNOWN!",
        "#BUSY!",
    )
)
_DELETE_SPACES = dict.fromkeys(map(ord, " \t\u00a0\u202f\u2009\u2007\u200a\u2008\u2006"), None)
_NUMBER_RE = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?")


# =========================================================================================
# Problems
# =========================================================================================


@dataclass(frozen=True)
class ImportProblem:
    """One problem of an input file.

    Attributes
    ----------
    address : str
        Where: ``'Objects'!C7`` (paste into Excel's Name Box), or a file name for problems
        that have no cell.
    message : str
        What is wrong (without the address), e.g. ``must be a number > 0 [m]``.
    header : str
        The column's header as written in the file ("" when not about a column).
    value : str or None
        The offending value as written (None when not about a value).
    hint : str
        How to fix it.
    """

    address: str
    message: str
    header: str = ""
    value: str | None = None
    hint: str = ""

    def __post_init__(self) -> None:
        # text from the file is shown on a terminal: no control characters, no megabytes
        for name, limit in (("address", 300), ("message", 2000), ("header", 200)):
            object.__setattr__(self, name, _printable(getattr(self, name), limit))
        if self.value is not None:
            object.__setattr__(self, "value", _printable(self.value, 200))

    def __str__(self) -> str:
        parts = [self.address]
        if self.header:
            parts.append(f'column "{self.header}"')
        if self.value is not None:
            if self.value != "":
                parts.append(f'value "{self.value}"')
        text = ": ".join(parts) + ": " + self.message
        return text + (f"; hint: {self.hint}" if self.hint else "")

    def as_dict(self) -> dict[str, Any]:
        """The problem as JSON-ready data (``text`` is the one-line form)."""
        d = dataclasses.asdict(self)
        d["text"] = str(self)
        return d


_UNPRINTABLE = re.compile(r"[\x00-\x1f\x7f-\x9f\u202a-\u202e\u2066-\u2069]")


def _printable(text: str, limit: int) -> str:
    """``text`` safe to print: control (and bidi) characters escaped, cut at ``limit``."""
    text = _UNPRINTABLE.sub(lambda m: f"\\u{ord(m.group()):04x}", str(text))
    if len(text) > limit:
        text = text[:limit] + f"… ({len(text):,} characters)"
    return text


def format_problems(
    problems: Sequence[ImportProblem], total: int | None = None, limit: int | None = None
) -> list[str]:
    """One line per problem, capped at ``limit`` (default :data:`MAX_ERRORS_SHOWN`).

    Parameters
    ----------
    problems : sequence of ImportProblem
        Problems kept.
    total : int, optional
        How many there were in all (default ``len(problems)``).
    limit : int, optional
        Lines shown before a final ``+N more``.
    """
    limit = _limits.MAX_ERRORS_SHOWN if limit is None else limit
    total = len(problems) if total is None else total
    lines = [str(p) for p in problems[:limit]]
    if total > len(lines):
        lines.append(f"+{total - len(lines)} more")
    return lines


class NormImportError(InputError):
    """An input file that cannot become a norm set, with every problem found.

    Attributes
    ----------
    problems : tuple of ImportProblem
        The problems (at most :data:`MAX_ERRORS_KEPT`).
    total : int
        How many problems there were in all.
    """

    def __init__(
        self, source: str, problems: Sequence[ImportProblem], total: int | None = None
    ) -> None:
        self.problems = tuple(problems)
        self.total = len(self.problems) if total is None else total
        n = self.total
        head = f"{n} problem{'s' if n != 1 else ''} found; nothing was written"
        super().__init__(
            source, head + "\n  " + "\n  ".join(format_problems(self.problems, self.total))
        )


class Problems:
    """Collects problems (keeps the first _limits.MAX_ERRORS_KEPT, counts all)."""

    def __init__(self) -> None:
        self.items: list[ImportProblem] = []
        self.total = 0

    def add(self, problem: ImportProblem) -> None:
        self.total += 1
        if len(self.items) < _limits.MAX_ERRORS_KEPT:
            self.items.append(problem)

    def raise_if_any(self, source: str) -> None:
        if self.total:
            raise NormImportError(source, self.items, self.total)


def fail(source: str, message: str, hint: str = "", at: str | None = None) -> NormImportError:
    """One problem of file ``source``, at cell ``at`` (default: the file itself)."""
    return NormImportError(source, [ImportProblem(at or source, message, hint=hint)])


# =========================================================================================
# Values
# =========================================================================================


def parse_number(text: str, *, scale: bool = False, percent: bool = False) -> float:
    """A number from spreadsheet text, in any locale Excel users type.

    Accepts a decimal comma (``0,20``) or point, thousands separators made of spaces,
    NBSP, narrow NBSP or thin spaces (``2 000``), both separators (``1 000,5``,
    ``1,000.5``, ``1.000,5``), the minus sign U+2212, and with ``scale`` a ``1:``
    prefix (``1:2000``); with ``percent`` a trailing ``%``.

    Parameters
    ----------
    text : str
        The cell text.
    scale : bool
        Allow ``1:N``.
    percent : bool
        Allow a trailing ``%`` (the number is kept as written: ``60%`` → 60).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        When the text is not a finite number.
    """
    s = text.translate(_DELETE_SPACES).replace("\u2212", "-").replace("\u2012", "-")
    if scale and s.startswith("1:"):
        s = s[2:]
    if percent and s.endswith("%"):
        s = s[:-1]
    if "," in s and "." in s:
        if s.rfind(",") > s.rfind("."):  # 1.000,5
            s = s.replace(".", "").replace(",", ".")
        else:  # 1,000.5
            s = s.replace(",", "")
    elif s.count(",") == 1:  # decimal comma (a Russian-locale 0,20)
        s = s.replace(",", ".")
    elif s.count(",") > 1 and re.fullmatch(r"[+-]?\d{1,3}(,\d{3})+", s):
        s = s.replace(",", "")
    elif s.count(".") > 1 and re.fullmatch(r"[+-]?\d{1,3}(\.\d{3})+", s):
        s = s.replace(".", "")
    if not _NUMBER_RE.fullmatch(s):
        raise ValueError(text)
    v = float(s)
    if not math.isfinite(v):
        raise ValueError(text)
    return v


def num_text(v: float) -> str:
    """Shortest text that reads back as ``v`` (``2000`` not ``2000.0``)."""
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def _shown(raw: object) -> str:
    """A raw cell value as the user sees it."""
    if raw is None:
        return ""
    if isinstance(raw, bool):
        return "TRUE" if raw else "FALSE"
    if isinstance(raw, float):
        return num_text(raw)
    if isinstance(raw, _dt.datetime | _dt.date | _dt.time):
        return raw.isoformat()
    return str(raw)


class Bad(Exception):
    """A value breaks its rule (message, hint)."""

    def __init__(self, message: str, hint: str = "") -> None:
        super().__init__(message)
        self.message = message
        self.hint = hint


def _number_hint(spec: ValueSpec, scale: bool) -> str:
    if scale:
        return "type the scale denominator, e.g. 2000, 2 000 or 1:2000"
    if spec.kind == "int":
        return "type a whole number, e.g. 2000"
    return "type a decimal number, e.g. 0,20 or 0.20"


def _is_empty(raw: object) -> bool:
    return raw is None or (isinstance(raw, str) and raw.strip() == "")


def _convert(
    raw: object, spec: ValueSpec, *, scale: bool = False, percent_cell: bool = False
) -> str:
    """Check one raw cell value against its rule; return its canonical text, or raise Bad.

    ``percent_cell``: the cell has a percent number format (Excel stores 60 % as 0.6).
    """
    if _is_empty(raw):
        if spec.required:
            raise Bad(f"is empty; must be {spec.describe()}", "fill in the cell")
        return ""
    if isinstance(raw, str) and raw.strip() in _EXCEL_ERRORS:
        raise Bad(
            f"the cell shows an Excel error; must be {spec.describe()}",
            "fix the formula or type the value",
        )
    if isinstance(raw, _dt.datetime | _dt.date | _dt.time | _dt.timedelta):
        raise Bad(
            f"is a date or time; must be {spec.describe()}",
            "Excel turned the value into a date: format the column as Text or "
            "Number and type the value again",
        )
    if spec.kind in ("float", "int"):
        if isinstance(raw, bool):
            raise Bad(f"must be {spec.describe()}", "type a number, not TRUE/FALSE")
        if isinstance(raw, int | float):
            v = float(raw)
            if percent_cell and spec.unit == "%":
                v *= 100.0
            v = float(f"{v:.15g}")  # drop binary noise of Excel's doubles
        else:
            try:
                v = parse_number(str(raw), scale=scale, percent=spec.unit == "%")
            except ValueError:
                raise Bad(f"must be {spec.describe()}", _number_hint(spec, scale)) from None
        problem = spec.check(v)
        if problem:
            hint = (
                _number_hint(spec, scale)
                if spec.kind == "int" and v != int(v)
                else (
                    f"check the unit: {spec.unit}"
                    if spec.unit and spec.unit != "-"
                    else "check the value"
                )
            )
            raise Bad(problem, hint)
        return str(int(v)) if spec.kind == "int" else num_text(v)
    if isinstance(raw, bool):
        text = "TRUE" if raw else "FALSE"
    elif isinstance(raw, float):
        text = num_text(raw)
    else:
        text = str(raw).strip()
    if spec.kind == "text":
        check_text(text)
    if spec.kind == "choice":
        folded = {c.casefold(): c for c in spec.choices}
        text = folded.get(text.casefold(), text)
    elif spec.kind == "list":
        folded = {c.casefold(): c for c in spec.choices}
        items = [x.strip() for x in re.split(r"[,;]", text) if x.strip()]
        text = ",".join(folded.get(x.casefold(), x) for x in items)
    problem = spec.check(text)
    if problem:
        raise Bad(problem, "spelling matters" if spec.choices else "")
    return text


_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")
_FORMULA_START = "=+-@"


def check_text(text: str) -> None:
    """Refuse text a norm set must not store (raise Bad).

    A norm set is CSV files engineers open in Excel, and its text goes into workbooks:
    text starting with ``=``, ``+``, ``-`` or ``@`` would run as a formula there
    (``=HYPERLINK(...)``, ``+cmd|' /C calc'!A0``), so it is refused — numbers such as
    ``-2`` and a lone ``-`` are fine. Leading tabs and line breaks are trimmed before.
    Control characters (terminal escapes) and text longer than Excel's cell limit are
    refused too.
    """
    if len(text) > _limits.MAX_CELL_CHARS:
        raise Bad(
            f"the text is {len(text):,} characters long; the limit is {_limits.MAX_CELL_CHARS:,} "
            "(Excel's, for one cell)",
            "shorten it",
        )
    bad = _CONTROL.search(text)
    if bad:
        raise Bad(
            f"the text contains the control character U+{ord(bad.group()):04X}",
            "delete it (it comes with text copied from another program)",
        )
    if len(text) > 1 and text[0] in _FORMULA_START and not _NUMBER_RE.fullmatch(text):
        raise Bad(
            f'text may not start with "{text[0]}": it would run as a formula in Excel '
            "(the norm set is stored as CSV files)",
            f'delete the leading "{text[0]}", or start the text with a letter or digit',
        )


# =========================================================================================
# Headers
# =========================================================================================


def _norm(text: object) -> str:
    """Header text folded for matching: case, ё, punctuation, underscores, spaces."""
    s = str(text).casefold().replace("ё", "е").replace("_", " ")
    s = re.sub(r"[^\w]+", " ", s)
    return " ".join(s.split())


def _header_forms(text: str) -> list[str]:
    """Ways to read a header, most literal first ("Размер объекта L, м" → ... "размер")."""
    forms = [_norm(text)]
    no_paren = re.sub(r"\([^)]*\)|\[[^\]]*\]", " ", text)
    forms.append(_norm(no_paren))
    if "," in no_paren:
        forms.append(_norm(no_paren.rsplit(",", 1)[0]))
    last = forms[-1].split()
    if len(last) > 1 and len(last[-1]) <= 2:
        forms.append(" ".join(last[:-1]))
    seen: list[str] = []
    for f in forms:
        if f and f not in seen:
            seen.append(f)
    return seen


def _alias_index(items: Iterable[tuple[str, Iterable[str]]]) -> dict[str, str]:
    """normalised alias → canonical name (names themselves are aliases too)."""
    index: dict[str, str] = {}
    for name, aliases in items:
        for a in (name, *aliases):
            index.setdefault(_norm(a), name)
    return index


_COLUMN_INDEX: dict[str, dict[str, str]] = {
    t.name: _alias_index((c.name, c.aliases) for c in t.columns)
    for t in (*TABLES.values(), META_TABLE)
}
_PARAMETER_INDEX = _alias_index((p.name, p.aliases) for p in PARAMETERS.values())
_ALL_TABLES: dict[str, TableSpec] = {**TABLES, META_TABLE.name: META_TABLE}
_SHEET_INDEX = _alias_index((t.name, (t.title_ru, Path(t.file).stem)) for t in _ALL_TABLES.values())


def _match(index: Mapping[str, str], text: object) -> str | None:
    if _is_empty(text):
        return None
    for form in _header_forms(str(text)):
        if form in index:
            return index[form]
    return None




def _size(n: int) -> str:
    return f"{n / 2**20:.1f} MB" if n >= 2**20 else f"{n:,} bytes"


def check_file(path: Path) -> int:
    """The size [bytes] of the norm file at ``path``, checked before it is read: a
    regular file within :data:`~scanplan.norms.limits.MAX_FILE_BYTES` (else a
    :class:`~scanplan.errors.NotFoundError`, :class:`~scanplan.errors.InputError` or
    :class:`NormImportError` naming it)."""
    try:
        st = path.stat()
    except OSError as exc:
        raise NotFoundError(str(path), f"cannot be read: {exc.strerror or exc}") from None
    if not stat.S_ISREG(st.st_mode):
        raise InputError(
            str(path),
            f"is {file_kind(st.st_mode)}, not a regular file; give the workbook or CSV file",
        )
    size = st.st_size
    if size > _limits.MAX_FILE_BYTES:
        raise fail(
            path.name,
            f"the file is {_size(size)}; the limit is {_size(_limits.MAX_FILE_BYTES)}",
            "a norm workbook is small: delete unused sheets, images and rows",
        )
    return size

