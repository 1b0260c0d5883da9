"""The control tables (:mod:`scanplan.reports.views.control`) worded for one locale: the
rows every layout prints — the terminal, the workbook's Control sheet and the PDF's control
section — from the same records, with the words of ``i18n/labels_control.py`` and the numbers
of the document's :class:`~scanplan.reports.formatter.Formatter`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from .views import ResultTables

if TYPE_CHECKING:
    from .formatter import Formatter

__all__ = ["check_rows", "rule_rows", "summary_rows"]


def summary_rows(tables: ResultTables, f: Formatter) -> list[tuple[str, str, bool]]:
    """(label, value, emphasised) per row of the ``control`` table; the budget's rows end
    with "at best"."""
    out = []
    for r in tables["control"].rows:
        if r.key == "control_mode":
            value = f(r.fields["mode"])
        else:
            value = f.num(r.value, r.digits if r.digits is not None else 3)
            if "rule" in r.fields:
                value = f"{value} ({f(r.fields['rule'])})"
            if r.key in ("control_budget_z", "control_budget_h"):
                value = f"{value} ({f('control_at_best')})"
        out.append((f(r.key), value, "emph" in r.flags))
    return out


def check_rows(tables: ResultTables, f: Formatter) -> list[tuple[str, str, str, str, str, str]]:
    """(rule, axis, target / precision, required, met, status and source) per check."""
    out = []
    for r in tables["control_checks"].rows:
        ratio, required, ok = r.values
        out.append((f(r.key), f(r.fields["axis"]), f.num(ratio, 1),
                    f.num(required, 0), f("control_ok" if ok else "control_not_ok"),
                    f"{f(r.fields['status'])}: {r.fields['source']}"))
    return out


def rule_rows(tables: ResultTables, f: Formatter) -> list[tuple[str, str, str, str]]:
    """(rule, value, status, source) per layout rule."""
    out = []
    for r in tables["control_rules"].rows:
        v: Any = r.value
        source = r.fields["source"]
        if source in ("scanplan", "practice"):  # the planner's own rule, or common practice
            source = f(f"control_source_{source}")
        out.append((f(r.key), f.num(v, 0 if float(v).is_integer() else 2),
                     f(r.fields["status"]), source))
    return out
