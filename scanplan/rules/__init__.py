"""The rules engine: constraints as a registry, and the film and UAV engines that iterate it.

- :mod:`~scanplan.rules.results` — the input and result records (one place);
- :mod:`~scanplan.rules.record` — the :class:`Constraint` record (what a constraint is);
- :mod:`~scanplan.rules.registry` — the registry the engines iterate;
- :mod:`~scanplan.rules.constraints` — the built-in constraints (seed 001's P_S … P_D, the
  digital height model, a target GSD, the altitude ceiling);
- :mod:`~scanplan.rules.film` — the film/scan engine (:func:`~scanplan.rules.film.plan_scan`);
- :mod:`~scanplan.rules.uav` — the UAV engine (:func:`~scanplan.rules.uav.plan_uav`).
"""

from .registry import CONSTRAINTS, Constraint, DigitalLimit, FilmArgs, register, unregister
from .results import (
    ConstraintResult,
    HeightLimit,
    ObjectSpec,
    PlanWarning,
    ScanInputs,
    ScanPlan,
    ScanRules,
    UavInputs,
    UavPlan,
)

__all__ = [
    "CONSTRAINTS",
    "Constraint",
    "ConstraintResult",
    "DigitalLimit",
    "FilmArgs",
    "HeightLimit",
    "ObjectSpec",
    "PlanWarning",
    "ScanInputs",
    "ScanPlan",
    "ScanRules",
    "UavInputs",
    "UavPlan",
    "register",
    "unregister",
]
