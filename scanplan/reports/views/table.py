"""The records of a report table: locale-free, unformatted, built once per result.

A :class:`Table` is what several renderers show alike (the terminal, the workbook, the PDF,
a notebook's ``_repr_html_``): a title (a label key), its columns and its rows. A row is a
label key, raw values (numbers, None, identifiers, :class:`~scanplan.messages.Message`
sentences), a unit key, the decimals the value is shown with, and flags (``"binding"``,
``"warning"``, ``"emph"`` …). Nothing here knows a language or a number format: a renderer
words the keys (:class:`scanplan.reports.view.Labels`) and prints the values
(:class:`scanplan.reports.view.Numbers`); a constraint is named by the rules registry
(:func:`constraint_title`), nowhere else.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ...rules.registry import CONSTRAINTS

__all__ = ["Cited", "Column", "Date", "Joined", "Msg", "Named", "Num", "Phrase", "Plural",
           "Row", "Scale", "Table", "constraint_title"]


# -- the values of a row: raw, typed, locale-free ------------------------------------------
# A row's value is a number, None, a text shown as it is, a Message (an engine sentence),
# or one of these records, which the formatter (scanplan.reports.formatter.Formatter.show)
# turns into the reader's words and numbers.


@dataclass(frozen=True)
class Num:
    """A number with the decimals it is shown with (None: its shortest form)."""

    value: float | None
    digits: int | None = None


@dataclass(frozen=True)
class Scale:
    """A scale ``1:value`` (a denominator)."""

    value: float


@dataclass(frozen=True)
class Date:
    """A date (a :class:`datetime.date` or ISO text), written as the document's
    convention writes it."""

    value: Any


@dataclass(frozen=True)
class Phrase:
    """Words of the label catalogue (``key``) whose ``{fields}`` are raw values (each shown
    as a row's value is)."""

    key: str
    fields: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Msg:
    """An engine sentence whose catalogue ids (camera, scanner) are named from
    ``norm_set`` (None: as the sentence has them)."""

    value: Any
    norm_set: Any = None


@dataclass(frozen=True)
class Cited:
    """A source the document cites by its reference number (a text or a sentence naming
    known works), with what the figure taken from it is (``status``: ``"estimate"`` …)."""

    text: Any
    status: str = ""


@dataclass(frozen=True)
class Named:
    """A thing named in the reader's language: ``kind`` ``"constraint"`` (its name),
    ``"cname"`` (``PZ — its name``), ``"camera"``, ``"scanner"``, ``"shape"`` (from
    ``norm_set``; ``default``: the name when the catalogue has none)."""

    kind: str
    id: str
    norm_set: Any = None
    default: str = ""


@dataclass(frozen=True)
class Plural:
    """A noun in the form a count ``n`` takes (one/few/many in Russian): the label
    ``forms`` holds the forms, ``|``-separated (``part|parts``)."""

    n: int
    forms: str


@dataclass(frozen=True)
class Joined:
    """Values shown one after the other, joined by ``sep``."""

    parts: tuple[Any, ...]
    sep: str = "; "


@dataclass(frozen=True)
class Column:
    """A column of a :class:`Table`.

    Attributes
    ----------
    key : str
        The label key of its heading ("" for none).
    value : object
        The raw value the heading shows, when it is one (a photo scale, a height [m]).
    unit : str
        The unit key of its values ("" for none).
    digits : int or None
        The decimals of its values (None: as the value is).
    """

    key: str = ""
    value: Any = None
    unit: str = ""
    digits: int | None = None


@dataclass(frozen=True)
class Row:
    """A row of a :class:`Table`.

    Attributes
    ----------
    key : str
        The label key of the quantity (a constraint's id for a constraint's row).
    values : tuple
        One raw value per column: a number, None (missing), an identifier, a pair of
        numbers (shown as ``a / b``), a :class:`~scanplan.messages.Message`.
    unit : str
        The unit key ("" for none).
    digits : int or None
        The decimals its numbers are shown with (None: as the value is).
    flags : frozenset of str
        The row's marks: ``"constraint"`` (a constraint's row, ``key`` its id),
        ``"binding"``, ``"emph"`` (a result the reader looks for), ``"summary"``,
        ``"warning"`` / ``"note"``.
    cells : tuple of frozenset
        Each value's marks (``"binding"``), as many as ``values`` or none.
    margins : tuple
        Each value's margin to the binding one [%] (a constraint's row), or none.
    fields : mapping
        The raw values its label's ``{fields}`` are filled with (``h``: a height …).
    details : tuple of mapping
        Each value's further raw data, for a renderer that shows more of it (a
        constraint's margin in µm and %, its reason and equation), or none.
    """

    key: str
    values: tuple[Any, ...] = ()
    unit: str = ""
    digits: int | None = None
    flags: frozenset[str] = frozenset()
    cells: tuple[frozenset[str], ...] = ()
    margins: tuple[float | None, ...] = ()
    fields: Mapping[str, Any] = field(default_factory=dict)
    details: tuple[Mapping[str, Any], ...] = ()

    def flagged(self, i: int, flag: str) -> bool:
        """Whether value ``i`` has ``flag`` (a cell's own mark)."""
        return i < len(self.cells) and flag in self.cells[i]

    @property
    def value(self) -> Any:
        """The first value (a one-column table's)."""
        return self.values[0] if self.values else None


@dataclass(frozen=True)
class Table:
    """A report table, built once per result by one of the builders of
    :mod:`scanplan.reports.views`.

    Attributes
    ----------
    name : str
        What the table is (``"film_constraints"``, ``"comparison"`` …).
    title : str
        The label key of its title.
    columns : tuple of Column
        Its value columns (a row's label and unit are not columns).
    rows : tuple of Row
    """

    name: str
    title: str
    columns: tuple[Column, ...]
    rows: tuple[Row, ...]

    def row(self, key: str) -> Row:
        """The row ``key``; KeyError when the table has none."""
        for r in self.rows:
            if r.key == key:
                return r
        raise KeyError(key)

    def keys(self) -> list[str]:
        """The rows' keys, in order."""
        return [r.key for r in self.rows]


def constraint_title(cid: str, locale: str = "en", default: str | None = None) -> str:
    """A constraint's name in ``locale``, from the rules registry (the one place that names
    a constraint).

    Parameters
    ----------
    cid : str
        The constraint's id (``"PZ"``).
    locale : {"en", "ru"}
    default : str, optional
        What an id the registry does not know reads as (default: the id).

    Returns
    -------
    str

    Examples
    --------
    >>> constraint_title("PZ"), constraint_title("PZ", "ru"), constraint_title("XX")
    ('height accuracy', 'точность по высоте', 'XX')
    """
    info = CONSTRAINTS.get(cid)
    if info is None:
        return cid if default is None else default
    return info.title(locale)
