"""The film plan's tables: every constraint's scan pixel at every photo scale (the binding
one flagged), then the scale's results — the terminal report of ``scanplan scan``, the
PDF's film section and a notebook's ``ScanResult`` lay it out (:func:`film_constraints`) —,
why each scale's constraint binds, the smallest photo scale each scan pixel supports, the
constraints' formulas and the dense sweep of the chart."""

from __future__ import annotations

from typing import Any

from .table import Column, Row, Table

__all__ = ["film_constraints", "film_explanations", "film_formulas", "film_reach",
           "film_sweep"]

_SUMMARY = frozenset({"summary"})
_EMPH = frozenset({"summary", "emph"})


def film_constraints(plan: Any) -> Table:
    """The constraints × photo scales table of a film scan plan.

    Parameters
    ----------
    plan : ScanPlan
        The film plan (:func:`scanplan.rules.film.plan_scan`).

    Returns
    -------
    Table
        One column per candidate photo scale (``value``: its denominator); rows
        ``photo_to_map``, one per constraint (key: its id; flags ``"constraint"``; each
        cell flagged ``"binding"`` where it binds, with its margin to the binding one and,
        in ``details``, its name, margins in µm and %, reason and equation),
        ``binding`` (the binding ids), ``scan_pixel_um``, ``scanner_pixel_um`` (with a
        scanner), ``frame_megabytes`` (fields ``bands``, ``bits``),
        ``resolution_on_ground``, and with a map object ``required_r`` and
        ``recognition_probability``.
    """
    scen = plan.scenarios
    inp = plan.inputs

    def values(attr: str) -> tuple[Any, ...]:
        return tuple(getattr(s, attr) for s in scen)

    rows = [Row("photo_to_map", values("photo_to_map_ratio"), digits=1,
                flags=frozenset({"ratio"}))]
    for cid in plan.constraint_ids:
        found = [s.constraint(cid) for s in scen]
        rows.append(Row(cid, tuple(c.pixel_um for c in found), unit="um", digits=1,
                        flags=frozenset({"constraint"}),
                        cells=tuple(frozenset({"binding"}) if c.binding else frozenset()
                                    for c in found),
                        margins=tuple(None if c.binding else c.margin_pct for c in found),
                        details=tuple({"name": c.name, "margin_um": c.margin_um,
                                       "margin_pct": c.margin_pct, "reason": c.reason,
                                       "equation": c.equation} for c in found)))
    rows.append(Row("binding", values("binding"), flags=_SUMMARY))
    rows.append(Row("scan_pixel_um", values("scan_pixel_um"), unit="um", digits=1,
                    flags=_EMPH))
    if inp.scanner:
        rows.append(Row("scanner_pixel_um", values("scanner_pixel_um"), unit="um", digits=1,
                        flags=_EMPH, fields={"scanner": inp.scanner}))
    rows.append(Row("frame_megabytes", values("frame_megabytes"), unit="mb", digits=0,
                    flags=_SUMMARY, fields={"bands": inp.bands, "bits": inp.bits_per_band}))
    rows.append(Row("resolution_on_ground", values("resolution_on_ground_mm"), unit="mm",
                    digits=1, flags=_SUMMARY))
    if inp.object is not None:
        rows.append(Row("required_r", values("required_resolving_power_lpmm"), unit="lpmm",
                        digits=1, flags=_SUMMARY))
        rows.append(Row("recognition_probability", values("recognition_probability"),
                        digits=2, flags=_SUMMARY))
    columns = tuple(Column(value=s.photo_scale, unit="scale") for s in scen)
    return Table("film_constraints", "film_constraints", columns, tuple(rows))


def film_explanations(plan: Any) -> Table:
    """Why each photo scale's binding constraint binds (the engine's sentence): one row per
    candidate photo scale (key ``explanation``; field ``photo_scale``)."""
    return Table("film_explanations", "film_constraints", (Column("message"),),
                 tuple(Row("explanation", (s.explanation,), fields={
                     "photo_scale": s.photo_scale}) for s in plan.scenarios))


def film_reach(plan: Any) -> Table:
    """The smallest photo scale (largest Mc) each scan pixel supports — the scanner's
    steps, the pixels asked about — and the interpretation limit.

    Returns
    -------
    Table
        Columns ``pixel_um``, ``max_photo_scale`` (None: no photo scale; its limit is
        then P_R), ``limit`` (the limiting constraint's id) and ``interpretable`` (the
        smallest with the map object interpretable, None: none); one row per pixel (key
        ``reach``), after a row ``interpretation_limit`` (values: the largest Mc at which
        the object is recognised, or None; fields ``ratio`` Mc/Mk, ``probability``,
        ``resolving_power``).
    """
    inp = plan.inputs
    mci = plan.interpretation_limit_photo_scale
    rows = [Row("interpretation_limit", (mci, None, None, None), unit="scale", fields={
        "ratio": mci / inp.map_scale if mci is not None else None,
        "probability": plan.rules.probability, "resolving_power": inp.resolving_power_lpmm})]
    rows += [Row("reach", (r.pixel_um, r.max_photo_scale if r.max_photo_scale > 0 else None,
                           r.limit, r.max_photo_scale_interpretable or None), unit="um")
             for r in plan.max_photo_scales]
    columns = (Column("pixel_um", unit="um"), Column("max_photo_scale", unit="scale"),
               Column("limit"), Column("interpretable", unit="scale"))
    return Table("film_reach", "max_photo_scales", columns, tuple(rows))


def film_formulas(plan: Any) -> Table:
    """The formula of each constraint the film plan evaluated: one row per constraint
    (key: its id; flag ``"constraint"``), values its equation with its source and what it
    protects (sentences of the rules registry)."""
    from ...rules.registry import CONSTRAINTS

    return Table("film_formulas", "formulas", (Column("equation"), Column("protects")),
                 tuple(Row(cid, (CONSTRAINTS[cid].equation, CONSTRAINTS[cid].protects),
                           flags=frozenset({"constraint"})) for cid in plan.constraint_ids))


def film_sweep(plan: Any) -> Table:
    """The dense photo-scale sweep (the chart's curves): rows ``photo_scale``, one per
    constraint swept (key: its id; flag ``"constraint"``), ``scan_pixel_um`` and
    ``binding``, each all the sweep's values."""
    sweep = plan.sweep
    rows = [Row("photo_scale", tuple(sweep.get("photo_scale", [])), unit="scale")]
    rows += [Row(cid, tuple(sweep[cid]), unit="um", digits=2, flags=frozenset({"constraint"}))
             for cid in plan.constraint_ids if cid in sweep]
    rows += [Row("scan_pixel_um", tuple(sweep.get("scan_pixel_um", [])), unit="um", digits=2),
             Row("binding", tuple(sweep.get("binding", [])))]
    return Table("film_sweep", "plot_constraints", (), tuple(rows))
