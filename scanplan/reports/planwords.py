"""The words of the plans compared (the ``plans`` table, :mod:`scanplan.reports.views.plans`)
in one language: the terminal, the PDF and the workbook lay out the same cells. Nothing here
computes and nothing is formatted here but through the document's
:class:`~scanplan.reports.formatter.Formatter` (words by concept, numbers by its rule).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .views import PLAN_COLUMNS, Row, Table

if TYPE_CHECKING:
    from .formatter import Formatter

__all__ = ["plan_cells", "plan_head", "plan_rows"]


#: The terminal's shorter headings, by column (a unit where the unit says it).
_TERMINAL = {"plans_mode": "how_flown", "plans_lines": "plan_lines", "plans_height": "m",
             "geo_n_photos": "photos_counted", "plans_volume": "gb", "plans_time": "min",
             "sorties": "sorties_counted", "plans_gsd": "cm", "plans_binding": "binds"}


def plan_head(f: Formatter, terminal: bool = False) -> list[str]:
    """The columns' headings in ``f``'s language (the terminal's shorter ones)."""
    return [f(_TERMINAL.get(key, key) if terminal else key) for key, _, _ in PLAN_COLUMNS]


def plan_cells(r: Row, f: Formatter) -> list[str]:
    """One plan's cells: how it is flown, its lines (direction and which), height, photos,
    data volume, flying time, sorties, the GSD flown, the binding constraint, and whether
    it meets every constraint (what it misses), recommended or not the project's choice.
    An estimate's counts carry ``≈``."""
    mode, deg, height, photos, gb, minutes, sorties, gsd, binding, why = r.values
    approx = "≈" if "estimate" in r.flags else ""

    def count(x: Any, digits: int = 0) -> str:
        return "—" if x is None else approx + f.num(x, digits)

    lines = "—" if deg is None else f"{f.fixed(deg, 1)}° ({f('plans_dir_' + r.key)})"
    gsd_text = "—" if gsd is None else f"{f.fixed(gsd[0], 2)}–{f.fixed(gsd[1], 2)}"
    verdict = "; ".join(f.text(m) for m in why) if why else f("plans_ok")
    findings = r.fields.get("findings") or ()
    if findings:
        verdict = "; ".join([verdict, *(f.text(m) for m in findings)])
    marks = [f(k) for k, flag in (("recommended", "recommended"),
                                  ("plans_not_allowed", "not_allowed")) if flag in r.flags]
    if marks:
        verdict = f"{verdict} ({', '.join(marks)})"
    return [f.text(mode), lines, "—" if height is None else f.num(height, 0),
            count(photos), count(gb), count(minutes), count(sorties), gsd_text,
            binding or "—", verdict]


def plan_rows(tbl: Table, f: Formatter) -> list[list[str]]:
    """Every plan's cells, in the table's order (the recommended one first)."""
    return [plan_cells(r, f) for r in tbl.rows]
