"""The tables of a specification (``scanplan plan``) and of any plan: the film/digital
comparison and the warnings — the terminal, the workbook and the PDF lay them out."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from .table import Column, Row, Table

__all__ = ["FILM_SYMBOLS", "UAV_SYMBOLS", "all_warnings", "comparison", "symbols", "warnings"]


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
        ``"warning"`` or ``"note"`` (an ``info``), fields ``severity`` and ``section``.
    """
    return Table("warnings", "warnings", (Column("message"), Column("photo_scale")),
                 tuple(_warning_row(w, section) for w in found))


def _warning_row(w: Any, section: str) -> Row:
    return Row(w.code, (w.message, tuple(getattr(w, "photo_scales", ()) or ())),
               flags=frozenset({"warning" if w.severity == "warning" else "note"}),
               fields={"severity": w.severity, "section": section})


def all_warnings(scan: Any = None, uav: Any = None, spec: Any = None) -> Table:
    """Every warning of a result once: the film plan's, the UAV plan's, then those of the
    specification that neither section states (by code).

    Parameters
    ----------
    scan, uav : plan or None
        The film and the UAV plan.
    spec : PlanResult or None
        The specification.

    Returns
    -------
    Table
        As :func:`warnings`, each row's ``section`` field ``"film"``, ``"uav"`` or
        ``"spec"``.
    """
    rows = [_warning_row(w, "film") for w in (scan.warnings if scan is not None else ())]
    rows += [_warning_row(w, "uav") for w in (uav.warnings if uav is not None else ())]
    seen = {r.key for r in rows}
    rows += [_warning_row(w, "spec") for w in (spec.warnings if spec is not None else ())
             if w.code not in seen]
    return Table("warnings", "warnings", (Column("message"), Column("photo_scale")),
                 tuple(rows))


#: The symbols of the digital camera's formulas and of the film's, as the formulas write
#: them (the label ``symbol_<key>`` says what each means).
UAV_SYMBOLS = (("GSD", "GSD"), ("L", "L"), ("H", "H"), ("f", "f"), ("p", "p"), ("R", "R"),
               ("K", "K"), ("B", "B"), ("P", "P"), ("L_obj", "L_obj"), ("σ_Z", "sigma_Z"),
               ("V_z", "V_z"))
FILM_SYMBOLS = (("Mc", "Mc"), ("Mk", "Mk"), ("f", "f"), ("b", "b"), ("R", "R"),
                ("V_s", "V_s"), ("V_z", "V_z"), ("k", "k"), ("k_R", "k_R"), ("B", "B"),
                ("P", "P"), ("L_obj", "L_obj"))


def symbols(tables: Any) -> Table:
    """The list of symbols of a document's formulas: the digital camera's (with a UAV
    plan), then the film's (with a film plan), each once.

    Returns
    -------
    Table
        One row per symbol (key ``symbol``; value: the symbol as the formulas write it;
        field ``meaning``: the label of what it means).
    """
    seen: dict[str, str] = {}
    for present, group in ((tables.uav is not None, UAV_SYMBOLS),
                           (tables.scan is not None, FILM_SYMBOLS)):
        for symbol, key in group if present else ():
            seen.setdefault(symbol, f"symbol_{key}")
    return Table("symbols", "symbols", (Column("symbol"),),
                 tuple(Row("symbol", (s,), fields={"meaning": m}) for s, m in seen.items()))
