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

from collections.abc import Callable, Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..i18n.labels import add_name_source

if TYPE_CHECKING:
    from .results import ScanInputs, ScanRules, UavInputs

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


@dataclass(frozen=True)
class FilmArgs:
    """The film scenario(s) a pixel function sees (arrays broadcast together)."""

    map_scale: ArrayLike
    photo_scale: ArrayLike
    relief_interval_m: ArrayLike
    focal_mm: ArrayLike
    frame_along_mm: ArrayLike
    forward_overlap_pct: ArrayLike
    resolving_power_lpmm: ArrayLike
    object_size_m: ArrayLike
    shape_coefficient: ArrayLike
    height_formula: str


@dataclass(frozen=True)
class DigitalLimit:
    """A constraint's limit for one UAV flight: the value, why, and details for reports."""

    limit_m: float
    reason: str
    details: dict[str, Any]
    equation: str | None = None
    """Overrides the record's equation (the normal-case form of P_Z)."""


FilmPixel = Callable[["ScanRules", FilmArgs], NDArray[np.float64]]
FilmReason = Callable[["ScanInputs", "ScanRules"], str]
FilmDetails = Callable[["ScanInputs", "ScanRules", dict[str, Any], int], dict[str, Any]]
GroundLimit = Callable[["UavInputs", "ScanRules | None"], "DigitalLimit | None"]


@dataclass(frozen=True)
class Constraint:
    """One constraint: what it protects, what it compares with, how each engine computes it.

    Attributes
    ----------
    id : str
        Short id shown in every table (``PS``, ``PZ``, …).
    name, name_ru : str
        The human name in English and Russian (the reports' label for the id).
    protects, equation : str
        :class:`~scanplan.i18n.messages.Message` s (or plain text): what the constraint protects;
        its equation and source citation.
    depends_on_photo_scale : bool
        Whether the film pixel is a ground limit divided by Mc (False for P_R).
    compares : {"GSD", "L", "H"}
        What the ground limit is compared with (see the module docstring).
    film_pixel_um : callable or None
        ``(rules, FilmArgs) -> pixel [µm]``, vectorised; None: not a film constraint.
    film_reason : callable or None
        ``(inputs, rules) -> Message``: why it is there, with the contract's numbers.
    film_details : callable or None
        ``(inputs, rules, context, j) -> dict``: extra numbers for ``--json`` and reports at
        scenario ``j`` (``context`` holds the engine's per-scale arrays).
    ground_limit : callable or None
        ``(uav inputs, rules) -> DigitalLimit | None`` (None: not applicable to this flight);
        None: not a digital constraint.
    norm_switch : bool
        True: the norm set enables it (its id in ``[parameters] constraints``); False: it
        applies whenever its inputs are given (the altitude ceiling, a target GSD).
    needs_map : bool
        The digital limit needs a map scale (and so the norm set's rules).
    """

    id: str
    name: str
    name_ru: str
    protects: str
    equation: str
    depends_on_photo_scale: bool
    compares: str = "GSD"
    film_pixel_um: FilmPixel | None = None
    film_reason: FilmReason | None = None
    film_details: FilmDetails | None = None
    ground_limit: GroundLimit | None = None
    norm_switch: bool = True
    needs_map: bool = True

    @property
    def workflows(self) -> tuple[str, ...]:
        """``"film"`` and/or ``"digital"``: the engines that know this constraint."""
        return tuple(w for w, fn in (("film", self.film_pixel_um),
                                     ("digital", self.ground_limit)) if fn is not None)

    def title(self, locale: str = "en") -> str:
        """The human name in ``locale``."""
        return self.name_ru if locale == "ru" else self.name


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


def _install_builtins() -> None:
    from . import constraints  # noqa: F401  (registers PS, PZ, PP, PR, PD, GL, GSD, HC)


_install_builtins()
