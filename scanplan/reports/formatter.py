"""The one formatter of every document: words by concept, numbers by the row's digits.

A :class:`Formatter` is what a layout (the terminal, the PDF, the workbook, a notebook's
HTML, the page, the charts) asks for every word and every number it prints, in one
language:

- words by concept from the one label catalogue of :mod:`scanplan.i18n`
  (:meth:`Formatter.__call__`, the digital camera's words by its platform: a UAV or a
  manned aircraft), a constraint by the rules registry's name, an engine sentence
  (:class:`~scanplan.i18n.messages.Message`) in the language with the works it names
  cited as the document numbers them, a norm-set item (camera, scanner, object, shape) by
  its name;
- numbers by one rule (:class:`~scanplan.i18n.numbers.Numbers`: the decimal comma and a
  no-break space grouping thousands in Russian), a table row's values with the digits the
  row declares (:meth:`Formatter.value`), never a renderer's own choice.

A layout never constructs a number format or a catalogue lookup of its own: it takes
``view.fmt`` (:func:`scanplan.reports.view.build_view`), and a document that cites works
takes :meth:`Formatter.document` (its own reference list, numbered as the other
documents of the same result number it). This module is the only place in the reports
that constructs one.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from ..i18n.labels import LABELS, t
from ..i18n.labels_cli import CLI, cli_text
from ..i18n.messages import localize, plural
from ..i18n.numbers import MISSING, Numbers
from .references import Bibliography
from .views import Row, constraint_title
from .views.table import Cited, Date, Joined, Msg, Named, Num, Phrase, Plural, Scale
from .wording import (
    camera_title,
    display_message,
    document_date,
    name_title,
    object_title,
    scanner_title,
    shape_title,
    with_status,
)

__all__ = ["LOCALES", "MISSING", "Formatter", "formatter"]

LOCALES = ("en", "ru")

#: The label of a row whose table key is not the catalogue's (a quantity's unit after its
#: comma is dropped for the others: ``Scan pixel, µm`` → ``Scan pixel``).
_ROW_LABELS = {"photo_to_map": "photo_to_map", "binding": "binding",
               "resolution_on_ground": "resolution_on_ground",
               "required_r": "required_r",
               "recognition_probability": "recognition_at_scan",
               "l_corner": "l_corner", "tilted_gsd": "tilted_gsd"}
#: The label of each unit key.
UNITS = {"um": "um", "mb": "mb", "mm": "mm", "lpmm": "lpmm", "m": "m", "GB": "gb"}
#: The label of each row of the comparison, by its key (another: its English ``quantity``).
COMPARISON_LABELS = {"ground_pixel": "spec_cmp_ground_pixel",
                     "ground_resolution": "spec_cmp_ground_resolution",
                     "recognition": "spec_cmp_recognition", "frames": "spec_cmp_frames",
                     "data_volume": "spec_cmp_data_volume"}
_UNIT_AFTER_COMMA = {"scan_pixel_um", "scanner_pixel_um", "frame_megabytes"}


@dataclass(frozen=True)
class Formatter:
    """Every word and number of one document, in one language.

    Parameters
    ----------
    locale : {"en", "ru"}
        The language (another reads as English).
    platform : {"uav", "aircraft"}
        The wording of a digital camera's sections.
    bibliography : Bibliography or None
        The document's reference list: a work an engine sentence or a source names is
        cited by its number (:meth:`cite`); None: no citation (the terminal).

    Examples
    --------
    >>> ru = formatter("ru")
    >>> ru("map_scale"), ru.num(12345.678, 1), ru.scale(25000)
    ('Масштаб карты (плана)', '12\\xa0345,7', '1:25\\xa0000')
    >>> formatter("en").has("no such key")
    False
    """

    locale: str = "en"
    platform: str = "uav"
    bibliography: Bibliography | None = field(default=None, compare=False)
    numbers: Numbers = field(init=False, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.locale not in LOCALES:
            object.__setattr__(self, "locale", "en")
        object.__setattr__(self, "numbers", Numbers(self.locale))

    # -- documents ---------------------------------------------------------------------

    def document(self, cited: list[Any] | None = None) -> Formatter:
        """This formatter for one document that cites works: its own reference list over
        ``cited`` (the works of the result in order of first citation, shared by the
        documents of one result, so a work has one number in all of them)."""
        return replace(self, bibliography=Bibliography(
            self.locale, cited if cited is not None else []))

    def cite(self, text: str) -> str:
        """``text`` with the works it names replaced by this document's reference numbers
        (as it is without a reference list)."""
        return self.bibliography.cite(text) if self.bibliography is not None else text

    def references(self) -> list[tuple[int, str]]:
        """(number, entry) of every work this document cites."""
        return self.bibliography.entries() if self.bibliography is not None else []

    # -- words -------------------------------------------------------------------------

    def __call__(self, key: str, **fields: Any) -> str:
        """The label ``key``, its ``{fields}`` filled from ``fields``; KeyError if unknown."""
        text = t(key, self.locale, self.platform)
        return text.format(**fields) if fields else text

    def has(self, key: str) -> bool:
        """Whether the catalogue has ``key``."""
        return key in LABELS["en"]

    def get(self, key: str, default: str) -> str:
        """The label ``key``, or ``default`` when the catalogue has none."""
        return self(key) if self.has(key) else default

    def cli(self, key: str, **fields: Any) -> str:
        """A template of the terminal reports and the catalogue listings, filled."""
        return cli_text(key, self.locale, **fields)

    def cli_get(self, key: str, default: str) -> str:
        """The terminal's word ``key``, or ``default`` when the catalogue has none."""
        return self.cli(key) if key in CLI["en"] else default

    def constraint(self, cid: str, default: str | None = None) -> str:
        """A constraint's name (the rules registry's record) in this language."""
        return constraint_title(cid, self.locale, default)

    def cname(self, cid: str) -> str:
        """A constraint by its id and name: ``PZ — height accuracy`` (an id the registry
        does not know, as it is)."""
        name = constraint_title(cid, self.locale, "")
        return f"{cid} — {name}" if name else cid

    def compared(self, symbol: str) -> str:
        """What a constraint compares (``GSD``, ``L``, ``H``) as a document writes it: the
        ground sample distance by its words in Russian (GSD is a symbol of the formulas,
        listed with them), the others as their symbols."""
        return self("gsd_symbol") if symbol == "GSD" else symbol

    def yes_no(self, value: bool) -> str:
        """Yes / Да."""
        return self("yes" if value else "no")

    @property
    def list_sep(self) -> str:
        """Between the items of a list of numbers or scales: ``"; "`` in Russian, where the
        comma is the decimal separator (as the messages join lists), ``", "`` in
        English."""
        return "; " if self.locale == "ru" else ", "

    def message(self, value: Any, norm_set: Any = None) -> str:
        """An engine sentence in this language — catalogue ids by their names when the
        norm set is given — with the works it names cited."""
        if norm_set is None:
            return self.cite(localize(value, self.locale))
        return self.cite(display_message(value, norm_set, self.locale))

    def text(self, value: Any) -> str:
        """An engine sentence or a text in this language, uncited (``""`` for None)."""
        return localize(value, self.locale)

    def date(self, day: Any) -> str:
        """A date as the document's convention writes it (23.11.2026, 2026-11-23)."""
        return document_date(day, self.locale)

    def camera(self, norm_set: Any, camera_id: str, name: str = "") -> str:
        """A camera by its model name (the catalogue's, in this language)."""
        return camera_title(norm_set, camera_id, self.locale, name)

    def scanner(self, norm_set: Any, scanner_id: str) -> str:
        """A scanner by its model name."""
        return scanner_title(norm_set, scanner_id, self.locale)

    def shape(self, norm_set: Any, shape: str) -> str:
        """A shape in words (the norm set's Russian name)."""
        return shape_title(norm_set, shape, self.locale)

    def object(self, obj: Any) -> str:
        """An object to interpret (with ``name`` and ``name_ru``) by its name."""
        return object_title(obj, self.locale)

    def object_named(self, norm_set: Any, name: str, size_m: float | None = None,
                     map_scale: int | None = None) -> str:
        """A norm-table object given by its English name (and, when given, its size and
        map scale) by its name in this language; a project's unnamed object as "the
        object of the given size"."""
        from ..project.jobs import USER_OBJECT_NAME

        if map_scale is None and name == USER_OBJECT_NAME["en"]:
            return name_title("", "", self.locale)
        for o in getattr(norm_set, "objects", ()):
            if o.name == name and (size_m is None or o.size_m == size_m) and (
                    map_scale is None or o.map_scale == map_scale):
                return object_title(o, self.locale)
        return name_title(name, "", self.locale)

    # -- numbers -----------------------------------------------------------------------

    def num(self, x: float | None, digits: int = 1) -> str:
        """``x`` with ``digits`` decimals, thousands grouped (``—`` for none)."""
        return self.numbers.num(x, digits)

    def fixed(self, x: float | None, digits: int = 1) -> str:
        """``x`` with ``digits`` decimals, thousands not grouped."""
        return self.numbers.fixed(x, digits)

    def whole(self, x: float) -> str:
        """``x`` rounded to a whole number, grouped."""
        return self.numbers.whole(x)

    def height(self, x: float) -> str:
        """A height [m]: whole metres when whole to 5 cm, else one decimal."""
        return self.numbers.height(x)

    def g(self, x: float | None) -> str:
        """Shortest form; whole numbers from 1,000 up grouped."""
        return self.numbers.g(x)

    def short(self, x: float) -> str:
        """Shortest form, never grouped."""
        return self.numbers.short(x)

    def sig(self, x: float | None, digits: int = 4) -> str:
        """A measured size to ``digits`` significant digits."""
        return self.numbers.sig(x, digits)

    def tick(self, x: float) -> str:
        """A plot's tick label."""
        return self.numbers.tick(x)

    def um(self, x: float | None) -> str:
        """A pixel [µm]: one decimal, two significant digits below 1 µm."""
        return self.numbers.um(x)

    def scale(self, x: float) -> str:
        """A scale as every document writes it (``1:10000`` / ``1:10 000``)."""
        return self.numbers.scale(x)

    def floor_scale(self, x: float) -> str:
        """The largest whole scale not above ``x``."""
        return self.numbers.floor_scale(x)

    def plain_scale(self, x: float) -> str:
        """A scale without grouping: ``1:10000``."""
        return self.numbers.plain_scale(x)

    # -- the values of the views -------------------------------------------------------

    def show(self, value: Any) -> str:
        """A view's value in this language (:mod:`scanplan.reports.views.table`): ``—``
        for None, a number in its shortest form, a :class:`~.views.table.Num` with its
        decimals, a scale, a date, a phrase of the catalogue with its fields shown alike,
        an engine sentence, a cited source, a thing by its name, joined parts; a text as
        it is."""
        if value is None:
            return MISSING
        if isinstance(value, Num):
            if value.value is None:
                return MISSING
            return self.g(value.value) if value.digits is None else \
                self.num(value.value, value.digits)
        if isinstance(value, Scale):
            return self.scale(value.value)
        if isinstance(value, Phrase):
            return self(value.key, **{k: self.show(v) for k, v in value.fields.items()})
        if isinstance(value, Msg):
            return self.message(value.value, value.norm_set)
        if isinstance(value, Cited):
            return with_status(self.cite(self.text(value.text)), value.status, self.locale)
        if isinstance(value, Named):
            return self._named(value)
        if isinstance(value, Joined):
            return value.sep.join(self.show(v) for v in value.parts)
        if isinstance(value, Date):
            return self.date(value.value)
        if isinstance(value, Plural):
            return plural(value.n, self(value.forms).split("|"), self.locale)
        if isinstance(value, bool):
            return self.yes_no(value)
        if isinstance(value, int | float):
            return self.g(value)
        if isinstance(value, Mapping):  # a name in both languages (i18n.messages.Names)
            return str(value.get(self.locale) or value.get("en", ""))
        return self.message(value) if not isinstance(value, str) or hasattr(
            value, "code") else value

    def _named(self, n: Named) -> str:
        if n.kind == "constraint":
            return self.constraint(n.id)
        if n.kind == "cname":
            return self.cname(n.id)
        if n.kind == "camera":
            return self.camera(n.norm_set, n.id, n.default)
        if n.kind == "scanner":
            return self.scanner(n.norm_set, n.id)
        if n.kind == "shape":
            return self.shape(n.norm_set, n.id)
        raise ValueError(f"no name of a {n.kind!r}")

    # -- the rows of the views ---------------------------------------------------------

    def row_label(self, r: Row) -> str:
        """A row's label as the documents give it: ``PZ — height accuracy`` for a
        constraint, the comparison's or the results' quantity, its ``{fields}`` filled
        (heights and angles in shortest form)."""
        if "constraint" in r.flags:
            return f"{r.key} — {self.constraint(r.key)}"
        if r.key == "resolving_power":
            return self("resolving_power_system") + " " + self("centre_corner")
        if r.key == "motion_blur_px":
            at = self("at_height", h=self.g(r.fields["h"]))
            return f"{self('motion_blur_px')} ({at})"
        if "quantity" in r.fields:  # a comparison's row: the documents' word, else English
            key = COMPARISON_LABELS.get(r.key)
            return self(key) if key else str(r.fields["quantity"])
        if r.key in _UNIT_AFTER_COMMA and r.unit:  # its unit in a column of its own
            return self(r.key).rsplit(",", 1)[0]
        return self(_ROW_LABELS.get(r.key, r.key),
                    **{k: self.show(v) for k, v in r.fields.items()})

    def unit(self, unit: str) -> str:
        """A unit key in words (``um`` …); an unknown one as it is."""
        return self(UNITS[unit]) if unit in UNITS else unit

    def value(self, r: Row, value: Any, digits: int | None = None) -> str:
        """A value of a row as the documents print it: the row's decimals (``digits`` when
        it has none: its column's; else 3), thousands grouped, a pair as ``a / b``, ``—``
        for a missing number, a text as it is."""
        if isinstance(value, str):
            return value
        if r.digits is not None:
            digits = r.digits
        elif digits is None:
            digits = 3
        if isinstance(value, tuple):
            return " / ".join(self.num(x, digits) for x in value)
        return self.num(value, digits)


@functools.lru_cache(maxsize=8)
def formatter(locale: str = "en", platform: str = "uav") -> Formatter:
    """The formatter of ``locale`` and ``platform`` (one per process; a formatter without a
    reference list holds no state).

    Parameters
    ----------
    locale : {"en", "ru"}
    platform : {"uav", "aircraft"}

    Returns
    -------
    Formatter
    """
    return Formatter(locale, platform)

