"""The words of the plans compared (the ``plans`` table, :mod:`scanplan.reports.views.plans`)
in one language: the terminal, the PDF and the workbook lay out the same cells. Nothing here
computes; numbers by :class:`~scanplan.i18n.numbers.Numbers`, words from the label catalogue.
"""

from __future__ import annotations

from typing import Any

from ..i18n.labels import t
from ..i18n.messages import localize
from ..i18n.numbers import Numbers
from .views import PLAN_COLUMNS, Row, Table

__all__ = ["plan_cells", "plan_head"]


#: The terminal's shorter headings, by column (a unit where the unit says it).
_TERMINAL = {"plans_mode": "term_plans_mode", "plans_lines": "term_plans_lines",
             "plans_height": "m", "geo_n_photos": "term_plans_photos", "plans_volume": "gb",
             "plans_time": "term_min", "sorties": "term_plans_sorties",
             "plans_gsd": "photo_gsd_cm", "plans_binding": "term_plans_binding"}


def plan_head(locale: str, terminal: bool = False) -> list[str]:
    """The columns' headings (the terminal's shorter ones)."""
    return [t(_TERMINAL.get(key, key) if terminal else key, locale)
            for key, _, _ in PLAN_COLUMNS]


def plan_cells(r: Row, locale: str) -> list[str]:
    """One plan's cells: how it is flown, its lines (direction and which), height, photos,
    data volume, flying time, sorties, the GSD flown, the binding constraint, and whether
    it meets every constraint (what it misses), recommended or not the project's choice.
    An estimate's counts carry ``≈``."""
    n = Numbers(locale)
    mode, deg, height, photos, gb, minutes, sorties, gsd, binding, why = r.values
    approx = "≈" if "estimate" in r.flags else ""

    def count(x: Any, digits: int = 0) -> str:
        return "—" if x is None else approx + n.num(x, digits)

    lines = "—" if deg is None else f"{n.fixed(deg, 1)}° ({t('plans_dir_' + r.key, locale)})"
    gsd_text = "—" if gsd is None else f"{n.fixed(gsd[0], 2)}–{n.fixed(gsd[1], 2)}"
    verdict = "; ".join(localize(m, locale) for m in why) if why else t("plans_ok", locale)
    findings = r.fields.get("findings") or ()
    if findings:
        verdict = "; ".join([verdict, *(localize(m, locale) for m in findings)])
    marks = [t(k, locale) for k, flag in (("xlsx_recommended", "recommended"),
                                          ("plans_not_allowed", "not_allowed"))
             if flag in r.flags]
    if marks:
        verdict = f"{verdict} ({', '.join(marks)})"
    return [localize(mode, locale), lines, "—" if height is None else n.short(height),
            count(photos), count(gb), count(minutes), count(sorties), gsd_text,
            binding or "—", verdict]


def plan_rows(tbl: Table, locale: str) -> list[list[str]]:
    """Every plan's cells, in the table's order (the recommended one first)."""
    return [plan_cells(r, locale) for r in tbl.rows]
