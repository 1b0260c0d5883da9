"""The constraint registry: one record per constraint id, iterated by both engines.

A constraint is a limit on the ground the contract tolerates (docs/architecture.md). The
film engine (:mod:`scanplan.rules.film`) turns it into the largest scan pixel at each photo
scale, the UAV engine (:mod:`scanplan.rules.uav`) into the largest flight height. A record
says what the limit compares with (``"GSD"``: the geometry, scan pixel × Mc or the GSD;
``"L"``: the resolution, A or the MTF ground resolution L; ``"H"``: the flown height
itself), names the constraint, cites its equation, explains it, and carries the small
functions that compute it for each workflow. A workflow whose function is None does not
know the constraint (P_R has no digital counterpart; the altitude ceiling has no film one).

To add a constraint, write its function(s) and one :class:`Constraint` record in
:mod:`scanplan.rules.constraints` (and its texts in :mod:`scanplan.i18n.messages`): the engines,
``--json``, the terminal, the workbook and the PDF pick it up from here.

>>> sorted(CONSTRAINTS)[:3]
['GL', 'GSD', 'HC']
>>> CONSTRAINTS["PS"].workflows
('film', 'digital')
>>> film_ids(("PS", "PR"))
('PS', 'PR')
"""

from __future__ import annotations

from collections.abc import Iterable

from ..i18n.labels import add_name_source
from .constraints import BUILTIN
from .record import Constraint, DigitalLimit, FilmArgs

__all__ = [
    "CONSTRAINTS",
    "Constraint",
    "ConstraintInfo",
    "DigitalLimit",
    "FilmArgs",
    "digital_ids",
    "film_ids",
    "register",
    "unregister",
]
ConstraintInfo = Constraint
"""The former name of :class:`Constraint` (kept for importers)."""

CONSTRAINTS: dict[str, Constraint] = {}
"""The registry: id → record, in the Instruction's order, then the UAV-only limits."""


def _title(key: str, locale: str) -> str | None:
    """A registered constraint's name, for the report labels (``t(cid, locale)``)."""
    record = CONSTRAINTS.get(key)
    return record.title(locale) if record is not None else None


add_name_source(_title)


def register(record: Constraint) -> Constraint:
    """Add ``record`` to the registry (replacing a record of the same id); returns it."""
    CONSTRAINTS[record.id] = record
    return record


def unregister(cid: str) -> None:
    """Remove constraint ``cid`` from the registry (no error if it is not there)."""
    CONSTRAINTS.pop(cid, None)


def film_ids(enabled: Iterable[str]) -> tuple[str, ...]:
    """The film engine's constraints: the norm set's ``enabled`` ids that are film
    constraints, then every film record that needs no norm switch.

    Raises
    ------
    ValueError
        For an id the registry does not know (the norm schema only lets known ids through).
    """
    out = []
    for cid in enabled:
        rec = CONSTRAINTS.get(cid)
        if rec is None:
            raise ValueError(f"unknown constraint {cid!r}")
        if rec.film_pixel_um is not None:
            out.append(cid)
    out += [r.id for r in CONSTRAINTS.values()
            if not r.norm_switch and r.film_pixel_um is not None and r.id not in out]
    return tuple(out)


def digital_ids(enabled: Iterable[str], *, with_map: bool) -> tuple[str, ...]:
    """The UAV engine's constraints, in registry order: the digital records the norm set
    enables (only ``with_map``), and those that need no norm switch (with a map, or not
    needing one)."""
    on = set(enabled)
    return tuple(r.id for r in CONSTRAINTS.values() if r.ground_limit is not None and (
        (r.norm_switch and with_map and r.id in on)
        or (not r.norm_switch and (with_map or not r.needs_map))))


for _record in BUILTIN:  # P_S, P_Z, P_P, P_R, P_D, then the UAV-only limits
    register(_record)
