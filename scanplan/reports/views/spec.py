"""The tables of a specification (``scanplan plan``) and of any plan: the film/digital
comparison and the warnings — the terminal, the workbook and the PDF lay them out."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from .table import Column, Row, Table

__all__ = ["comparison", "warnings"]


def comparison(spec: Any) -> Table:
    """The film and the digital camera side by side (``PlanResult.comparison``).

    Parameters
    ----------
    spec : PlanResult

    Returns
    -------
    Table
        Columns ``film`` and ``uav``; one row per quantity (key: the comparison's key,
        e.g. ``ground_pixel``; ``unit``: ``"m"``, ``"GB"`` or ""), a count (an int) with
        0 decimals, any other number with 3; the row's English wording in ``fields``
        (``quantity``) for a quantity the labels do not know. No rows without both plans.
    """
    rows = []
    for c in spec.comparison:
        counts = isinstance(c["film"], int) or isinstance(c["uav"], int)
        rows.append(Row(c.get("key", ""), (c["film"], c["uav"]), unit=c["unit"],
                        digits=0 if counts else 3, fields={"quantity": c["quantity"]}))
    return Table("comparison", "spec_comparison", (Column("film"), Column("uav")),
                 tuple(rows))


def warnings(found: Iterable[Any], section: str = "") -> Table:
    """Warnings and notes of a plan, in order.

    Parameters
    ----------
    found : iterable of PlanWarning
    section : str
        The section they belong to (``"film"``, ``"uav"``, ``"spec"``; "" for one plan).

    Returns
    -------
    Table
        One row per warning: key its code, values ``(message, photo_scales)`` (the
        :class:`~scanplan.messages.Message` and the photo scales it concerns), flags
        ``"warning"`` or ``"note"`` (an ``info``) and the ``section``.
    """
    rows = tuple(Row(w.code, (w.message, tuple(getattr(w, "photo_scales", ()) or ())),
                     flags=frozenset({"warning" if w.severity == "warning" else "note",
                                      *([f"section:{section}"] if section else [])}),
                     fields={"severity": w.severity})
                 for w in found)
    return Table("warnings", "warnings", (Column("message"), Column("photo_scale")), rows)
