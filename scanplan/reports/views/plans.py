"""The plans compared for a UAV block (``UavSpec.alternatives``, :mod:`scanplan.project.
alternatives`): one row per plan, side by side — the terminal, the PDF and the workbook lay
it out."""

from __future__ import annotations

from typing import Any

from ...i18n.messages import Message
from .table import Column, Row, Table

__all__ = ["PLAN_COLUMNS", "plans"]

#: The columns, in order: (label key, unit key, decimals).
PLAN_COLUMNS: tuple[tuple[str, str, int | None], ...] = (
    ("plans_mode", "", None), ("plans_lines", "deg", 1), ("plans_height", "m", 0),
    ("geo_n_photos", "", 0), ("plans_volume", "GB", 0), ("plans_time", "min", 0),
    ("sorties", "", 0), ("plans_gsd", "cm", 2), ("plans_binding", "", None),
    ("plans_verdict", "", None))

_MODE = {None: "plan_choice.mode.flat", "constant": "plan_choice.mode.constant",
         "strip": "plan_choice.mode.strip", "follow": "plan_choice.mode.follow"}


def plans(spec: Any) -> Table:
    """The plans compared, the recommended one first, then the others by flying time.

    Parameters
    ----------
    spec : PlanResult
        A specification with a UAV part.

    Returns
    -------
    Table
        Columns :data:`PLAN_COLUMNS`; one row per plan, key its line direction's kind
        (``auto``, ``long_axis``, ``relief``, ``project``, ``block``), values: how it is
        flown (a :class:`Message`), the lines' direction [°], the height [m], photos, the
        data volume [GB], the flying time [min], sorties, the GSD at the lowest and highest
        heights flown (a pair) [cm], the binding constraint, and what it misses (a tuple of
        Messages; empty when it meets every constraint). Fields ``findings``: what it holds
        only within an allowance (Messages). Flags ``"recommended"``,
        ``"feasible"``, ``"estimate"``, ``"not_allowed"`` (the project's choices rule it
        out). No rows without alternatives.
    """
    alts = list(getattr(spec.uav, "alternatives", ()) or ())
    alts.sort(key=lambda a: (not a.recommended, a.estimate, a.cost))
    rows = []
    for a in alts:
        mode = (Message("plan_choice.mode.parts", n=a.parts) if a.parts > 1
                else Message(_MODE[a.mode]))
        flags = {name for name, on in (("recommended", a.recommended), ("feasible", a.feasible),
                                       ("estimate", a.estimate),
                                       ("not_allowed", not a.allowed)) if on}
        gsd = ((a.gsd_min_m * 100.0, a.gsd_max_m * 100.0)
               if a.gsd_min_m is not None and a.gsd_max_m is not None else None)
        rows.append(Row(a.direction, (
            mode, a.direction_deg, a.height_m, a.n_photos,
            a.data_volume_bytes / 1e9 if a.data_volume_bytes is not None else None,
            a.flight_time_s / 60.0 if a.flight_time_s is not None else None,
            a.n_sorties, gsd, a.binding, tuple(a.rejected_because)),
            flags=frozenset(flags),
            fields={"mode": a.mode, "parts": a.parts, "findings": tuple(a.findings)}))
    columns = tuple(Column(key, unit=unit, digits=digits) for key, unit, digits in PLAN_COLUMNS)
    return Table("plans", "plans_title", columns, tuple(rows))
