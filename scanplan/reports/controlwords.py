"""The control tables (:mod:`scanplan.reports.views.control`) worded for one locale: the
rows every layout prints — the terminal, the workbook's Control sheet and the PDF's control
section — from the same records, with the words of ``i18n/labels_control.py``."""

from __future__ import annotations

from typing import Any

from ..i18n.labels import t
from ..i18n.numbers import Numbers
from .views import ResultTables

__all__ = ["check_rows", "rule_rows", "summary_rows"]


def summary_rows(tables: ResultTables, loc: str) -> list[tuple[str, str, bool]]:
    """(label, value, emphasised) per row of the ``control`` table; the budget's rows end
    with "at best"."""
    n = Numbers(loc)
    out = []
    for r in tables["control"].rows:
        if r.key == "control_mode":
            value = t(r.fields["mode"], loc)
        else:
            value = n.num(r.value, r.digits if r.digits is not None else 3)
            if "rule" in r.fields:
                value = f"{value} ({t(r.fields['rule'], loc)})"
            if r.key in ("control_budget_z", "control_budget_h"):
                value = f"{value} ({t('control_at_best', loc)})"
        out.append((t(r.key, loc), value, "emph" in r.flags))
    return out


def check_rows(tables: ResultTables, loc: str) -> list[tuple[str, str, str, str, str, str]]:
    """(rule, axis, target / precision, required, met, status and source) per check."""
    n = Numbers(loc)
    out = []
    for r in tables["control_checks"].rows:
        ratio, required, ok = r.values
        out.append((t(r.key, loc), t(r.fields["axis"], loc), n.num(ratio, 1),
                    n.num(required, 0), t("control_ok" if ok else "control_not_ok", loc),
                    f"{t(r.fields['status'], loc)}: {r.fields['source']}"))
    return out


def rule_rows(tables: ResultTables, loc: str) -> list[tuple[str, str, str, str]]:
    """(rule, value, status, source) per layout rule."""
    n = Numbers(loc)
    out = []
    for r in tables["control_rules"].rows:
        v: Any = r.value
        source = r.fields["source"]
        if source in ("scanplan", "practice"):  # the planner's own rule, or common practice
            source = t(f"control_source_{source}", loc)
        out.append((t(r.key, loc), n.num(v, 0 if float(v).is_integer() else 2),
                     t(r.fields["status"], loc), source))
    return out
