"""The conditions of UAV flights without an airspace-use permission, as data:
``norms/catalogue/airspace-conditions.csv`` — each condition in English and Russian with its
source, the date of the wording it follows and its status (``secondary``: as secondary
sources describe the wording in force; ``norm``: read in the text itself). An update of the
rules is an edit of that file; the plan prints the conditions with their wording date.

>>> c = airspace_conditions()
>>> [x.id for x in c][:2], c[0].wording_date
(['vlos', 'below_150'], '2024-03-01')
"""

from __future__ import annotations

import csv
import datetime as dt
import io
from dataclasses import dataclass
from functools import lru_cache

from .paths import CATALOGUE, bundled_norms_dir

__all__ = ["AIRSPACE_STATUSES", "AirspaceCondition", "airspace_conditions"]

AIRSPACE_STATUSES = ("norm", "secondary")
"""``norm``: the wording read in the rules themselves; ``secondary``: as secondary sources
describe it (the amended text itself not read)."""


@dataclass(frozen=True)
class AirspaceCondition:
    """One condition: ``text_en``/``text_ru`` (``{ceiling}`` is the norm set's ceiling [m]),
    its source, the wording's date (ISO), its status and a note."""

    id: str
    text_en: str
    text_ru: str
    source: str
    wording_date: str
    status: str
    note: str


@lru_cache(maxsize=1)
def airspace_conditions() -> tuple[AirspaceCondition, ...]:
    """The bundled conditions, in order.

    Raises
    ------
    RuntimeError
        The bundled file is broken (a broken installation, not a user error).
    """
    path = bundled_norms_dir() / CATALOGUE / "airspace-conditions.csv"
    out = []
    for i, row in enumerate(csv.DictReader(io.StringIO(path.read_text(encoding="utf-8"),
                                                        newline="")), start=2):
        cond = AirspaceCondition(**{k: (row.get(k) or "").strip()
                                    for k in AirspaceCondition.__dataclass_fields__})
        try:
            dt.date.fromisoformat(cond.wording_date)
        except ValueError:
            raise RuntimeError(f"{path}:{i}: wording_date must be a date YYYY-MM-DD") from None
        if not (cond.id and cond.text_en and cond.text_ru) or \
                cond.status not in AIRSPACE_STATUSES:
            raise RuntimeError(f"{path}:{i}: a condition needs an id, both texts and a status "
                               f"of {', '.join(AIRSPACE_STATUSES)}")
        out.append(cond)
    return tuple(out)
