"""The tables of one result, each built on first use and kept (:class:`ResultTables`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, NamedTuple

from .control import control_checks, control_rules_table, control_summary
from .design import design, design_notes
from .film import film_constraints, film_explanations, film_formulas, film_reach, film_sweep
from .headline import spec_film, spec_uav
from .inputs import film_inputs, uav_inputs
from .plans import plans
from .spec import all_warnings, comparison, symbols, warnings
from .table import Table
from .uav import uav_flight, uav_limits, uav_recognition, uav_results
from .uav_data import (
    uav_accuracy,
    uav_figures,
    uav_flight_figures,
    uav_height_curve,
    uav_mtf,
)

__all__ = ["TABLES", "ResultTables"]

#: Each table: the result it is built from (``"scan"`` / ``"uav"``: that plan;
#: ``"scan.job"`` / ``"uav.job"``: that plan with its norm set, as ``job.plan`` and
#: ``job.norm_set``; ``"spec"``: the specification; ``"spec.film"`` / ``"spec.uav"`` /
#: ``"spec.design"``: the specification, when it has that part; ``"all"``: the
#: :class:`ResultTables`, whichever it has) and its builder.
TABLES: dict[str, tuple[str, Callable[[Any], Table]]] = {
    "film_constraints": ("scan", film_constraints),
    "film_inputs": ("scan", film_inputs),
    "film_explanations": ("scan", film_explanations),
    "film_reach": ("scan", film_reach),
    "film_formulas": ("scan", film_formulas),
    "film_sweep": ("scan", film_sweep),
    "uav_inputs": ("uav.job", uav_inputs),
    "uav_figures": ("uav", uav_figures),
    "uav_accuracy": ("uav", uav_accuracy),
    "uav_flight_figures": ("uav", uav_flight_figures),
    "uav_height_curve": ("uav", uav_height_curve),
    "uav_mtf": ("uav", uav_mtf),
    "uav_results": ("uav", uav_results),
    "uav_limits": ("uav", uav_limits),
    "uav_flight": ("uav", uav_flight),
    "uav_recognition": ("uav", uav_recognition),
    "spec_film": ("spec.film", spec_film),
    "spec_uav": ("spec.uav", spec_uav),
    "comparison": ("spec", comparison),
    "design": ("spec.design", design),
    "design_notes": ("spec.design", design_notes),
    "plans": ("spec.uav", plans),
    "control": ("spec.control", control_summary),
    "control_checks": ("spec.control", control_checks),
    "control_rules": ("spec.control", control_rules_table),
    "film_warnings": ("scan", lambda plan: warnings(plan.warnings, "film")),
    "uav_warnings": ("uav", lambda plan: warnings(plan.warnings, "uav")),
    "spec_warnings": ("spec", lambda spec: warnings(spec.warnings, "spec")),
    "warnings": ("all", lambda tables: all_warnings(tables.scan, tables.uav, tables.spec)),
    "symbols": ("all", symbols),
}


@dataclass
class ResultTables:
    """The tables of one result, each built on first use and kept.

    Parameters
    ----------
    scan, uav : plan or None
        The film plan (``ScanPlan``) and the UAV plan (``UavPlan``).
    spec : PlanResult or None
        The specification of ``scanplan plan``.
    scan_norms, uav_norms : NormSet or None
        The norm set of each plan (the names of its cameras, objects and shapes).

    Attributes
    ----------
    built : list of str
        The tables built so far, in order (each once).

    Examples
    --------
    >>> import scanplan
    >>> r = scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[8000],
    ...                   camera="rc30-153")
    >>> tables = ResultTables(scan=r.job.plan)
    >>> tables["film_constraints"] is tables["film_constraints"], tables.built
    (True, ['film_constraints'])
    """

    scan: Any = None
    uav: Any = None
    spec: Any = None
    scan_norms: Any = None
    uav_norms: Any = None
    built: list[str] = field(default_factory=list)
    _tables: dict[str, Table] = field(default_factory=dict, repr=False)

    def __getitem__(self, name: str) -> Table:
        if name not in self._tables:
            source, build = TABLES[name]
            result = self._source(source)
            if result is None:
                raise KeyError(f"this result has no {source} plan for the table {name}")
            self._tables[name] = build(result)
            self.built.append(name)
        return self._tables[name]

    def has(self, name: str) -> bool:
        """Whether the result has what table ``name`` is built from."""
        return name in TABLES and self._source(TABLES[name][0]) is not None

    def _source(self, source: str) -> Any:
        """What a table is built from (None when the result has not got it)."""
        if source == "all":
            return self
        if source in ("scan.job", "uav.job"):
            plan = getattr(self, source[:-4])
            return None if plan is None else _Job(plan, getattr(self, source[:-4] + "_norms"))
        head, _, part = source.partition(".")
        found = getattr(self, head)
        return None if found is None or (part and getattr(found, part) is None) else found

    @classmethod
    def of_jobs(cls, scan: Any = None, uav: Any = None, spec: Any = None) -> ResultTables:
        """The tables of a film and/or UAV job (their plans) and a specification."""
        return cls(scan=scan.plan if scan is not None else None,
                   uav=uav.plan if uav is not None else None, spec=spec,
                   scan_norms=scan.norm_set if scan is not None else None,
                   uav_norms=uav.norm_set if uav is not None else None)


class _Job(NamedTuple):
    """A plan with its norm set (what a ``"scan.job"`` / ``"uav.job"`` table reads)."""

    plan: Any
    norm_set: Any
