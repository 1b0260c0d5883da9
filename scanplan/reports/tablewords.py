"""The documents' words and numbers for the rows of the report tables
(:mod:`scanplan.reports.views`): the PDF, the workbook and a notebook's ``_repr_html_`` name
a row and print a value alike (the terminal has its shorter words, :mod:`.labels_cli`).

Each function takes the row and a language's :class:`~.view.Labels` and
:class:`~.view.Numbers`; none of them computes anything.
"""

from __future__ import annotations

from typing import Any

from ..i18n.numbers import Numbers
from .view import Labels
from .views import Row

__all__ = ["COMPARISON_LABELS", "UNITS", "row_label", "row_unit", "row_value"]

#: The label of a row whose table key is not the catalogue's (a quantity's unit after its
#: comma is dropped for the others: ``Scan pixel, µm`` → ``Scan pixel``).
_LABELS = {"photo_to_map": "photo_to_map", "binding": "binding",
           "resolution_on_ground": "pdf_resolution_on_ground", "required_r": "pdf_required_r",
           "recognition_probability": "pdf_recognition_at_scan", "l_corner": "pdf_l_corner",
           "tilted_gsd": "pdf_tilted_gsd"}
#: The label of each unit key.
UNITS = {"um": "um", "mb": "mb", "mm": "pdf_mm", "lpmm": "pdf_lpmm", "m": "m",
         "GB": "gb"}
#: The label of each row of the comparison, by its key (another: its English ``quantity``).
COMPARISON_LABELS = {"ground_pixel": "spec_cmp_ground_pixel",
                     "ground_resolution": "spec_cmp_ground_resolution",
                     "recognition": "spec_cmp_recognition", "frames": "spec_cmp_frames",
                     "data_volume": "spec_cmp_data_volume"}
_UNIT_AFTER_COMMA = {"scan_pixel_um", "scanner_pixel_um", "frame_megabytes"}


def row_label(r: Row, labels: Labels, numbers: Numbers) -> str:
    """A row's label as the documents give it.

    Parameters
    ----------
    r : Row
        A row of a report table.
    labels, numbers : Labels, Numbers
        The document's language.

    Returns
    -------
    str
        ``PZ — height accuracy`` for a constraint, the comparison's or the results'
        quantity, its ``{fields}`` filled (heights and angles in shortest form).
    """
    if "constraint" in r.flags:
        return f"{r.key} — {labels.constraint(r.key)}"
    if r.key == "resolving_power":
        return labels("resolving_power_system") + " " + labels("pdf_centre_corner")
    if r.key == "motion_blur_px":
        at = labels("pdf_at_height", h=numbers.g(r.fields["h"]))
        return f"{labels('motion_blur_px')} ({at})"
    if "quantity" in r.fields:  # a comparison's row: the documents' word, else English
        key = COMPARISON_LABELS.get(r.key)
        return labels(key) if key else str(r.fields["quantity"])
    if r.key in _UNIT_AFTER_COMMA:
        return labels(r.key).rsplit(",", 1)[0]
    return labels(_LABELS.get(r.key, r.key), **{k: numbers.g(v) for k, v in r.fields.items()})


def row_unit(unit: str, labels: Labels) -> str:
    """A unit key in words (``um`` …); an unknown one as it is."""
    return labels(UNITS[unit]) if unit in UNITS else unit


def row_value(r: Row, value: Any, numbers: Numbers, digits: int | None = None) -> str:
    """A value of a row as the documents print it: the row's decimals (``digits`` when it
    has none: its column's; else 3), thousands grouped, a pair as ``centre / corner``,
    ``—`` for a missing number, a text as it is."""
    if isinstance(value, str):
        return value
    if r.digits is not None:
        digits = r.digits
    elif digits is None:
        digits = 3
    if isinstance(value, tuple):
        return " / ".join(numbers.num(x, digits) for x in value)
    return numbers.num(value, digits)
