"""The film plan's table: every constraint's scan pixel at every photo scale (the binding
one flagged), then the scale's results — the terminal report of ``scanplan scan``, the
PDF's film section and a notebook's ``ScanResult`` lay it out."""

from __future__ import annotations

from typing import Any

from .table import Column, Row, Table

__all__ = ["film_constraints"]

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
