"""The survey design sheet («Технический проект АФС») as a table: *quantity | value | norm*,
locale-free — the workbook's sheet, the PDF's section and the terminal's key figures lay it
out (:func:`design`, :func:`design_notes`).

Each row's key is the label of its quantity (its ``fields`` fill that label), its values
the figure of the plan (a :class:`~.table.Num`, a :class:`~.table.Phrase` of the catalogue
with raw fields …) and the norm it meets (a :class:`~.table.Cited` source, cited by the
document's reference number). Nothing is computed here that the specification
(:class:`scanplan.project.spec.PlanResult`) and its survey design
(:mod:`scanplan.project.design`) do not hold.
"""

from __future__ import annotations

from typing import Any

from ...geo.sun import zone_country
from ...i18n.messages import Message
from ...rules.registry import CONSTRAINTS
from .headline import relief_max_height_m
from .table import (
    Cited,
    Column,
    Date,
    Joined,
    Msg,
    Named,
    Num,
    Phrase,
    Plural,
    Row,
    Scale,
    Table,
)

__all__ = ["GSD_TABLE", "MSK_UTC_OFFSET_H", "SUN_POSITION", "TERMINAL_ROWS", "design",
           "design_notes"]

GSD_TABLE = "GOST R 59562-2021, Appendix B, Table B.1"
SUN_POSITION = "Meeus 1998"
MSK_UTC_OFFSET_H = 3.0
"""Moscow time, from which Russia's time zones are counted (МСК+N), is UTC+3 [h]
(Federal Law No. 107-FZ "On the calculation of time", art. 5)."""
TERMINAL_ROWS = ("gsd_digital_vs_table", "gsd_film_vs_table", "block_range", "sun_window",
                 "sorties", "flying_days")
"""The survey design rows the terminal summary shows."""

_CONTRACT = Phrase("norm_contract")
_PROJECT = Phrase("norm_project")
_COLUMNS = (Column("proposed_value"), Column("norm_met"))


def _row(key: str, value: Any, norm: Any = "", **fields: Any) -> Row:
    return Row(key, (value, norm), fields=fields)


def _equation(cid: str, limits: Any = ()) -> Any:
    """The equation of constraint ``cid`` as the plan used it, cited: a UAV height limit
    carries its own (the digital normal-case σ_Z of P_Z, not the film formula of the
    registry)."""
    lim = next((x for x in limits if x.id == cid), None)
    if lim is not None and getattr(lim, "equation", None):
        return Cited(lim.equation)
    rec = CONSTRAINTS.get(cid)
    return Cited(rec.equation) if rec is not None else ""


def _project_rows(spec: Any) -> list[Row]:
    p = spec.project  # the parsed project file (scanplan.project.model)
    rows = [_row("purpose", p.signing.purpose or p.name, _CONTRACT),
            _row("plan_scale_relief", Phrase("plan_scale_relief_value", {
                "scale": Scale(p.map.scale), "hc": Num(p.map.relief_interval_m, 2)}),
                _CONTRACT)]
    from ...project.design import layout_of

    layout = layout_of(spec.uav) or layout_of(spec.film)
    width, length = p.area.width_m, p.area.length_m
    if layout is not None:  # the contract polygon, once the geography lays it out
        rows.append(_row("area_km2", Num(layout.area.area_km2, 2)))
    elif width and length:
        rows.append(_row("area_km2", Num(width * length / 1e6, 2)))
    for key, label in (("coordinate_system", "coordinate_system"),
                       ("height_system", "height_system")):
        rows.append(_row(label, getattr(p.signing, key) or None, _CONTRACT))
    return rows


def _gsd_row(design: Any, workflow: str) -> Row | None:
    for g in design.gsd if design is not None else ():
        if g.workflow == workflow:
            value = Phrase("gsd_vs_table_value", {
                "gsd": Num(g.gsd_cm, 1), "limit": Num(g.limit_cm, 0),
                "verdict": Phrase("complies" if g.complies else "exceeds"),
                "sign": "≤" if g.complies else ">"})
            norm: list[Any] = [Cited(GSD_TABLE, getattr(g, "status", ""))]
            if g.area == "dense_urban":
                norm.append(Phrase("dense_urban"))
            if getattr(g, "set_aside", ""):
                norm.append(Phrase("set_aside", {"reason": g.set_aside}))
            if workflow == "film":
                norm.append(Phrase("for_information"))
            label = "gsd_digital_vs_table" if workflow == "digital" else "gsd_film_vs_table"
            return _row(label, value, Joined(tuple(norm)))
    return None


def _uav_rows(spec: Any) -> list[Row]:
    u = spec.uav
    p = u.job.plan
    inp = p.inputs
    ns = u.job.norm_set
    rows = [_row("camera", Named("camera", inp.camera, ns, inp.camera_name) if inp.camera
                 else Phrase("camera_value", {"pixel": Num(inp.pixel_um, 2),
                                              "focal": Num(inp.focal_mm, 1)}))]
    rows.append(_row("gsd_recommended_cm", Num(p.gsd_m * 100, 2)))
    row = _gsd_row(spec.design, "digital")
    if row:
        rows.append(row)
    rows.append(_row("overlaps", Phrase("overlaps_value", {
        "fwd": Num(inp.forward_overlap_pct, 0), "side": Num(inp.side_overlap_pct, 0)}),
        _PROJECT))
    rows.append(_row("spec_recommended_height_m", Num(u.recommended_height_m, 0),
                     _equation(p.binding, p.limits) if p.binding else ""))
    relief = relief_max_height_m(u)
    rows.append(_row("max_height_m" if relief is None else "spec_max_height_flat_m",
                     Num(u.max_height_m, 0)))
    if relief is not None:
        rows.append(_row("spec_max_height_relief_m", Num(relief, 0)))
    fl = p.flight
    if "strips" in fl:
        rows.append(_row("strips_and_photos", Phrase("strips_and_photos_value", {
            "strips": Num(fl["strips"], 0), "photos": Num(fl["photos"], 0)})))
    if "data_volume_bytes" in fl:
        rows.append(_row("volume", Phrase("volume_value", {
            "raw": Num(fl["data_volume_bytes"] / 1e9, 1),
            "jpeg": Num(fl["data_volume_jpeg_bytes"] / 1e9, 1)})))
    return rows


def _film_rows(spec: Any) -> list[Row]:
    f = spec.film
    inp = f.job.plan.inputs
    ns = f.job.norm_set
    rec = f.recommended
    rows = [_row("camera", Named("camera", inp.camera, ns, inp.camera_name)
                 if inp.camera or inp.camera_name
                 else Phrase("film_camera_value", {"focal": Num(inp.focal_mm, 1)}))]
    if rec is None:
        return rows
    rows.append(_row("spec_archive_photo_scale" if f.archive else
                     "spec_recommended_photo_scale", Scale(rec.photo_scale),
                     _equation(rec.binding)))
    if not f.archive:  # existing photos: no flight is planned, only their scan
        rows.append(_row("film_height", Num(f.flight_height_m, 0)))
        alt = f.flight_altitude_m
        if alt is not None:  # over the relief: the altitude flown
            lo, hi = alt
            rows.append(_row("film_altitude", Num(hi, 0) if hi - lo <= 0.5
                             else Joined((Num(lo, 0), Num(hi, 0)), "–")))
    rows.append(_row("scan_pixel_um", Num(rec.scanner_pixel_um or rec.scan_pixel_um, 1)))
    row = _gsd_row(spec.design, "film")
    if row:
        rows.append(row)
    if f.archive:
        if f.frames is not None:
            rows.append(_row("frames_to_scan", Num(f.frames, 0)))
            rows.append(_row("spec_scanned_gb", Num(f.scanned_gigabytes, 1)))
        return rows
    rows.append(_row("overlaps", Phrase("overlaps_value", {
        "fwd": Num(inp.forward_overlap_pct, 0), "side": Num(f.side_overlap_pct, 0)}),
        Cited(ns.parameter_sources.get("standard_forward_overlap_pct", ""))))
    if f.frames is not None:
        rows.append(_row("strips_and_photos", Phrase("strips_and_photos_value", {
            "strips": Num(f.strips, 0), "photos": Num(f.frames, 0)})))
        rows.append(_row("spec_scanned_gb", Num(f.scanned_gigabytes, 1)))
    return rows


def _block_rows(design: Any) -> list[Row]:
    b = design.block
    if b is None:
        return []
    parts: list[Any] = [Phrase("block_value", {
        "lo": Num(b.ground_min_m, 0), "hi": Num(b.ground_max_m, 0), "pct": Num(b.range_pct, 1),
        "limit": Num(b.limit_pct, 0), "relief": Message(f"relief.{b.relief_class}")})]
    if getattr(design, "block_ground", "") == "dem":
        parts += [" ", Phrase("block_dem", {"n": Num(b.samples, 0)})]
    if getattr(design, "block_set_aside", ""):
        verdict: Any = Phrase("set_aside", {"reason": design.block_set_aside})
    elif getattr(design, "block_waived", False):
        verdict = Phrase("block_waived")
    else:
        verdict = (Phrase("block_split", {"n": b.blocks, "parts": Plural(b.blocks,
                                                                         "part_forms")})
                   if b.split_needed else Phrase("block_one"))
    parts += [" — ", verdict]
    return [_row("block_range", Joined(tuple(parts), ""),
                 Cited(design.block_source, getattr(design, "block_status", "")))]


def _zone(s: Any) -> Phrase:
    """The time zone the window's times are in: the site's named zone, or the project's
    offset from UTC."""
    utc = f"{s.utc_offset_h:+g}"
    if s.time_zone and zone_country(s.time_zone) == "RU":  # Russia's zones: MSK−1 … MSK+9
        msk = s.utc_offset_h - MSK_UTC_OFFSET_H
        return Phrase("zone_msk", {"name": s.time_zone, "utc": utc,
                                   "msk": f"{msk:+g}".replace("-", "−") if msk else ""})
    if s.time_zone:
        return Phrase("zone_named", {"name": s.time_zone, "utc": utc})
    return Phrase("zone_offset", {"utc": utc})


def _sun_rows(design: Any) -> list[Row]:
    s = design.sun
    if s is None:
        return []
    lo, hi = s.window_hours
    first = s.windows[0]
    span = (f"{first.start_local:%H:%M}–{first.end_local:%H:%M}" if first.start_local
            else "—")
    source = _PROJECT if s.elevation_source == "project" else \
        Cited(s.elevation_source, getattr(design, "sun_status", ""))
    rows = [_row("site", Phrase("site_value", {"lat": Num(s.lat_deg, 4),
                                               "lon": Num(s.lon_deg, 4)})),
            _row("flying_dates", Joined((Date(s.start_date), Date(s.end_date)), " … "),
                 _CONTRACT),
            _row("sun_window", Phrase("sun_value", {
                "date": Date(first.date), "span": span, "lo": Num(lo, 1), "hi": Num(hi, 1),
                "zone": _zone(s)}), Joined((source, Cited(SUN_POSITION))),
                elev=Num(s.min_elevation_deg, 0))]
    if s.days is not None:
        rows.append(_row("sorties", Phrase("sorties_value", {
            "n": Num(s.days.sorties, 0), "sortie": Num(s.sortie_time_s / 60, 0),
            "turn": Num(s.turnaround_s / 60, 0)}), _PROJECT))
        days = (Phrase("days_value", {"n": Num(s.days.days, 0),
                                      "last": Date(s.days.last_date)})
                if s.days.days is not None and s.days.last_date is not None
                else Phrase("days_none"))
        rows.append(_row("flying_days", days, Phrase("sun_only_weather")))
    return rows


def _binding_rows(spec: Any) -> list[Row]:
    rows = []
    if spec.uav is not None and spec.uav.job.plan.binding:
        p = spec.uav.job.plan
        lim = next((x for x in p.limits if x.binding), None)
        text: Any = Named("cname", p.binding)
        if lim is not None:
            text = Joined((text, Msg(lim.reason, spec.uav.job.norm_set)), ": ")
        rows.append(_row("binding_height", text, _equation(p.binding, p.limits)))
    if spec.film is not None and spec.film.recommended is not None:
        rec = spec.film.recommended
        rows.append(_row("binding_scan_pixel", Named("cname", rec.binding),
                         _equation(rec.binding)))
    return rows


def design(spec: Any) -> Table:
    """The survey design of a specification (``PlanResult.design``), row by row.

    Parameters
    ----------
    spec : PlanResult
        A specification with a survey design.

    Returns
    -------
    Table
        Columns ``proposed_value`` and ``norm_met``; one row per quantity (key: its label;
        ``fields``: that label's), in the sheet's order: the purpose, the plan's scale,
        the area, the coordinate and height systems; the digital camera's (camera, GSD,
        the GSD against Table Б.1, overlaps, the recommended and maximum heights, strips
        and photos, the data volume); the film's (camera, photo scale, flight height and
        altitude, scan pixel, the scanned ground pixel against Table Б.1, overlaps, frames,
        volume); the block's height range; the site, the dates, the sun window, the
        sorties and flying days; the binding constraints.
    """
    dsg = spec.design
    rows = _project_rows(spec)
    if spec.uav is not None:
        rows += _uav_rows(spec)
    if spec.film is not None:
        rows += _film_rows(spec)
    rows += _block_rows(dsg) + _sun_rows(dsg) + _binding_rows(spec)
    return Table("design", "survey_design", _COLUMNS, tuple(rows))


def design_notes(spec: Any) -> Table:
    """The survey design's warnings in full (one row each: key its code, value its
    sentence)."""
    return Table("design_notes", "survey_design_notes", (Column("message"),),
                 tuple(Row(w.code, (Msg(w.message),)) for w in spec.design.warnings))
