"""What a constraint is: the :class:`Constraint` record and what its functions see and give.

A record names a limit on the ground the contract tolerates, says what it compares with,
cites its equation and carries the small functions that compute it for each workflow
(docs/architecture.md). The built-in records are in :mod:`scanplan.rules.constraints`; the
registry that the engines iterate is :mod:`scanplan.rules.registry`. Both read the record
from here, so neither imports the other to know what a record is.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

if TYPE_CHECKING:
    from .results import ScanInputs, ScanRules, UavInputs

__all__ = ["Constraint", "DigitalLimit", "FilmArgs"]


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
        What the ground limit is compared with: ``"GSD"`` the geometry (scan pixel × Mc
        or the GSD), ``"L"`` the resolution (A or the MTF ground resolution L), ``"H"``
        the flown height itself.
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
