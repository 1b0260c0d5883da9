"""The survey design sheet («Технический проект АФС»): one view for the workbook and the PDF.

Each row is ``(quantity, value, norm)``: the figure of the plan in the report's language and
the norm it meets, cited by reference number through the document's bibliography. Nothing is
computed here that the specification (:class:`scanplan.project.spec.PlanResult`) and its
survey design (:mod:`scanplan.project.design`) do not already hold; this module only words
and formats them. The workbook (:mod:`scanplan.reports.excel`) and the PDF
(:mod:`scanplan.reports.pdf`, template ``_design.html``) call :func:`design_view`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import flight as FL
from ..core.photoscale import height_at_photo_scale_m
from ..geo.sun import zone_country
from ..i18n.labels import t
from ..i18n.messages import Message, localize, plural, scale_text
from ..i18n.numbers import Numbers
from ..rules.registry import CONSTRAINTS
from .views import constraint_title, relief_max_height_m
from .wording import camera_title, display_message, document_date, sentence, with_status

_PARTS = {"en": ("part", "parts"), "ru": ("часть", "части", "частей")}

__all__ = ["DesignView", "Figure", "design_text_lines", "design_view", "relief_max_height_m"]

GSD_TABLE = "GOST R 59562-2021, Appendix B, Table B.1"
SUN_POSITION = "Meeus 1998"
MSK_UTC_OFFSET_H = 3.0
"""Moscow time, from which Russia's time zones are counted (МСК+N), is UTC+3 [h]
(Federal Law No. 107-FZ "On the calculation of time", art. 5)."""


@dataclass(frozen=True)
class DesignView:
    """The survey design sheet in one language.

    Attributes
    ----------
    rows : list of (str, str, str)
        (quantity, value, norm) — the norm already cited (``[n], …``).
    notes : list of str
        The design's warnings in full, in the report's language.
    """

    rows: list[tuple[str, str, str]]
    notes: list[str]
    keys: list[str]
    """The label key of each row (``design_gsd_digital``, ``design_sun_window`` …)."""


class Figure(str):
    """A design value that is one number: its text in the report's language, and the number
    and its decimals, so the workbook writes a number cell (not the text ``"6,00"``)."""

    value: float
    digits: int

    def __new__(cls, text: str, value: float, digits: int) -> Figure:
        obj = super().__new__(cls, text)
        obj.value, obj.digits = float(value), digits
        return obj

    @property
    def number_format(self) -> str:
        """The workbook's number format: thousands grouped, ``digits`` decimals."""
        return "#,##0" + ("." + "0" * self.digits if self.digits > 0 else "")


class _W:
    """Formatting in one locale."""

    def __init__(self, locale: str, cite: Callable[[str], str], platform: str) -> None:
        self.loc, self.cite, self.platform = locale, cite, platform
        self._keys: dict[str, str] = {}

    def t(self, key: str, **kw: Any) -> str:
        text = t(key, self.loc, self.platform)
        text = text.format(**kw) if kw else text
        self._keys.setdefault(text, key)
        return text

    def key_of(self, label: str) -> str:
        """The label key a row's quantity was worded from."""
        return self._keys.get(label, "")

    def n(self, x: float | None, digits: int = 1) -> str:
        if x is None or not math.isfinite(float(x)):
            return "—"
        return Numbers(self.loc).num(float(x), digits)  # the report's one formatter

    def fig(self, x: float | None, digits: int = 1) -> str:
        """A value that is one number: :meth:`n`'s text carrying the number (:class:`Figure`)."""
        text = self.n(x, digits)
        if x is None or text == "—":
            return text
        return Figure(text, round(float(x), digits), digits)

    def scale(self, x: float) -> str:
        return scale_text(x, self.loc)

    def msg(self, m: Any, ns: Any = None) -> str:
        return self.cite(display_message(m, ns, self.loc))

    def date(self, day: Any) -> str:
        return document_date(day, self.loc)

    def cname(self, cid: str) -> str:
        return constraint_title(cid, self.loc)


def _equation(cid: str, w: _W, limits: Any = ()) -> str:
    """The equation of constraint ``cid`` as the plan used it: a UAV height limit carries
    its own (the digital normal-case σ_Z of P_Z, not the film formula of the registry)."""
    lim = next((x for x in limits if x.id == cid), None)
    if lim is not None and getattr(lim, "equation", None):
        return w.cite(localize(lim.equation, w.loc))
    rec = CONSTRAINTS.get(cid)
    return w.cite(localize(rec.equation, w.loc)) if rec is not None else ""


def _project_rows(spec: Any, w: _W) -> list[tuple[str, str, str]]:
    p = spec.project  # the parsed project file (scanplan.project.model)
    rows = []
    purpose = p.signing.purpose or p.name
    rows.append((w.t("design_purpose"), purpose, w.t("design_norm_contract")))
    rows.append((w.t("design_map"), w.t("design_map_value", scale=w.scale(p.map.scale),
                                        hc=w.n(p.map.relief_interval_m, 2)),
                 w.t("design_norm_contract")))
    from ..project.design import layout_of

    layout = layout_of(spec.uav) or layout_of(spec.film)
    width, length = p.area.width_m, p.area.length_m
    if layout is not None:  # the contract polygon, once the geography lays it out
        rows.append((w.t("area_km2"), w.fig(layout.area.area_km2, 2), ""))
    elif width and length:
        rows.append((w.t("area_km2"), w.fig(width * length / 1e6, 2), ""))
    for key, label in (("coordinate_system", "coordinate_system"),
                       ("height_system", "design_height_system")):
        rows.append((w.t(label), getattr(p.signing, key) or "—", w.t("design_norm_contract")))
    return rows


def _gsd_row(design: Any, workflow: str, w: _W) -> tuple[str, str, str] | None:
    for g in design.gsd if design is not None else ():
        if g.workflow == workflow:
            verdict = w.t("design_complies" if g.complies else "design_exceeds")
            value = w.t("design_gsd_value", gsd=w.n(g.gsd_cm, 1), limit=w.n(g.limit_cm, 0),
                        verdict=verdict, sign="≤" if g.complies else ">")
            norm = with_status(w.cite(GSD_TABLE), getattr(g, "status", ""), w.loc) + (
                "; " + w.t("design_dense_urban") if g.area == "dense_urban" else "")
            if getattr(g, "set_aside", ""):
                norm += "; " + w.t("design_set_aside", reason=g.set_aside)
            if workflow == "film":
                norm += "; " + w.t("design_information")
            label = "design_gsd_digital" if workflow == "digital" else "design_gsd_film"
            return (w.t(label), value, norm)
    return None


def _uav_rows(spec: Any, w: _W) -> list[tuple[str, str, str]]:
    u = spec.uav
    p = u.job.plan
    inp = p.inputs
    ns = u.job.norm_set
    rows = [(w.t("camera"), camera_title(ns, inp.camera, w.loc, inp.camera_name)
             if inp.camera else w.t("design_camera_value", pixel=w.n(inp.pixel_um, 2),
                                    focal=w.n(inp.focal_mm, 1)), "")]
    rows.append((w.t("design_gsd_planned"), w.fig(p.gsd_m * 100, 2), ""))
    row = _gsd_row(spec.design, "digital", w)
    if row:
        rows.append(row)
    rows.append((w.t("design_overlaps"), w.t("design_overlaps_value",
                                               fwd=w.n(inp.forward_overlap_pct, 0),
                                               side=w.n(inp.side_overlap_pct, 0)),
                 w.t("design_norm_project")))
    rows.append((w.t("spec_recommended_height_m"), w.fig(u.recommended_height_m, 0),
                 _equation(p.binding, w, p.limits) if p.binding else ""))
    relief = relief_max_height_m(u)
    rows.append((w.t("max_height_m" if relief is None else "spec_max_height_flat_m"),
                 w.fig(u.max_height_m, 0), ""))
    if relief is not None:
        rows.append((w.t("spec_max_height_relief_m"), w.fig(relief, 0), ""))
    fl = p.flight
    if "strips" in fl:
        rows.append((w.t("design_strips_photos"), w.t("design_strips_photos_value",
                                                         strips=w.n(fl["strips"], 0),
                                                         photos=w.n(fl["photos"], 0)), ""))
    if "data_volume_bytes" in fl:
        rows.append((w.t("design_volume"), w.t(
            "design_volume_value", raw=w.n(fl["data_volume_bytes"] / 1e9, 1),
            jpeg=w.n(float(FL.jpeg_volume_bytes(fl["data_volume_bytes"])) / 1e9, 1)), ""))
    return rows


def _film_rows(spec: Any, w: _W) -> list[tuple[str, str, str]]:
    f = spec.film
    inp = f.job.plan.inputs
    ns = f.job.norm_set
    rec = f.recommended
    rows = [(w.t("camera"), camera_title(ns, inp.camera, w.loc, inp.camera_name)
             if inp.camera or inp.camera_name
             else w.t("design_film_camera_value", focal=w.n(inp.focal_mm, 1)), "")]
    if rec is None:
        return rows
    rows.append((w.t("spec_archive_photo_scale" if f.archive else "spec_recommended_photo_scale"),
                 w.scale(rec.photo_scale), _equation(rec.binding, w)))
    if not f.archive:  # existing photos: no flight is planned, only their scan
        rows.append((w.t("design_film_height"), w.fig(float(height_at_photo_scale_m(
            rec.photo_scale, inp.focal_mm)), 0), ""))
        ft = getattr(f, "terrain", None)
        if ft is not None and len(ft.altitude_m):  # over the relief: the altitude flown
            lo, hi = float(np.min(ft.altitude_m)), float(np.max(ft.altitude_m))
            rows.append((w.t("design_film_altitude"), w.fig(hi, 0) if hi - lo <= 0.5
                         else f"{w.n(lo, 0)}–{w.n(hi, 0)}", ""))
    px = rec.scanner_pixel_um or rec.scan_pixel_um
    rows.append((w.t("scan_pixel_um"), w.fig(px, 1), ""))
    row = _gsd_row(spec.design, "film", w)
    if row:
        rows.append(row)
    if f.archive:
        if f.frames is not None:
            rows.append((w.t("design_frames_to_scan"), w.fig(f.frames, 0), ""))
            rows.append((w.t("spec_scanned_gb"), w.fig(f.scanned_gigabytes, 1), ""))
        return rows
    rows.append((w.t("design_overlaps"), w.t(
        "design_overlaps_value", fwd=w.n(inp.forward_overlap_pct, 0),
        side=w.n(f.side_overlap_pct, 0)),
        w.cite(ns.parameter_sources.get("standard_forward_overlap_pct", ""))))
    if f.frames is not None:
        rows.append((w.t("design_strips_photos"), w.t(
            "design_strips_photos_value", strips=w.n(f.strips, 0), photos=w.n(f.frames, 0)), ""))
        rows.append((w.t("spec_scanned_gb"), w.fig(f.scanned_gigabytes, 1), ""))
    return rows


def _block_rows(design: Any, w: _W) -> list[tuple[str, str, str]]:
    b = design.block
    if b is None:
        return []
    relief = localize(Message(f"relief.{b.relief_class}"), w.loc)
    value = w.t("design_block_value", lo=w.n(b.ground_min_m, 0), hi=w.n(b.ground_max_m, 0),
                pct=w.n(b.range_pct, 1), limit=w.n(b.limit_pct, 0), relief=relief)
    if getattr(design, "block_ground", "") == "dem":
        value += " " + w.t("design_block_dem", n=w.n(b.samples, 0))
    if getattr(design, "block_set_aside", ""):
        value += " — " + w.t("design_set_aside", reason=design.block_set_aside)
    elif getattr(design, "block_waived", False):
        value += " — " + w.t("design_block_waived")
    else:
        value += " — " + (w.t("design_block_split", n=b.blocks, parts=plural(
                              b.blocks, _PARTS[w.loc], w.loc)) if b.split_needed
                          else w.t("design_block_one"))
    return [(w.t("design_block"), value,
             with_status(w.cite(design.block_source), getattr(design, "block_status", ""),
                         w.loc))]


def _zone(s: Any, w: _W) -> str:
    """The time zone the window's times are in: the site's named zone, or the project's
    offset from UTC."""
    utc = f"{s.utc_offset_h:+g}"
    if s.time_zone and zone_country(s.time_zone) == "RU":  # Russia's zones: MSK−1 … MSK+9
        msk = s.utc_offset_h - MSK_UTC_OFFSET_H
        return w.t("design_zone_msk", name=s.time_zone, utc=utc,
                   msk=f"{msk:+g}".replace("-", "−") if msk else "")
    if s.time_zone:
        return w.t("design_zone_named", name=s.time_zone, utc=utc)
    return w.t("design_zone_offset", utc=utc)


def _sun_rows(design: Any, w: _W) -> list[tuple[str, str, str]]:
    s = design.sun
    if s is None:
        return []
    lo, hi = s.window_hours
    first = s.windows[0]
    span = (f"{first.start_local:%H:%M}–{first.end_local:%H:%M}" if first.start_local
            else "—")
    source = w.t("design_norm_project") if s.elevation_source == "project" else \
        with_status(w.cite(s.elevation_source), getattr(design, "sun_status", ""), w.loc)
    rows = [(w.t("design_site"), w.t("design_site_value", lat=w.n(s.lat_deg, 4),
                                     lon=w.n(s.lon_deg, 4)), ""),
            (w.t("design_dates"), f"{w.date(s.start_date)} … {w.date(s.end_date)}",
             w.t("design_norm_contract")),
            (w.t("design_sun_window", elev=w.n(s.min_elevation_deg, 0)), w.t(
                "design_sun_value", date=w.date(first.date), span=span,
                lo=w.n(lo, 1), hi=w.n(hi, 1), zone=_zone(s, w)),
             f"{source}; {w.cite(SUN_POSITION)}")]
    if s.days is not None:
        rows.append((w.t("sorties"), w.t(
            "design_sorties_value", n=w.n(s.days.sorties, 0),
            sortie=w.n(s.sortie_time_s / 60, 0), turn=w.n(s.turnaround_s / 60, 0)),
            w.t("design_norm_project")))
        days = (w.t("design_days_value", n=w.n(s.days.days, 0),
                    last=w.date(s.days.last_date))
                if s.days.days is not None and s.days.last_date is not None
                else w.t("design_days_none"))
        rows.append((w.t("design_flying_days"), days, w.t("design_weather")))
    return rows


def _binding_rows(spec: Any, w: _W) -> list[tuple[str, str, str]]:
    rows = []
    if spec.uav is not None and spec.uav.job.plan.binding:
        p = spec.uav.job.plan
        lim = next((x for x in p.limits if x.binding), None)
        text = f"{p.binding} — {w.cname(p.binding)}"
        if lim is not None:
            text += f": {w.msg(lim.reason, spec.uav.job.norm_set)}"
        rows.append((w.t("design_binding"), text, _equation(p.binding, w, p.limits)))
    if spec.film is not None and spec.film.recommended is not None:
        rec = spec.film.recommended
        rows.append((w.t("design_binding_film"), f"{rec.binding} — {w.cname(rec.binding)}",
                     _equation(rec.binding, w)))
    return rows


def design_view(spec: Any, locale: str, cite: Callable[[str], str]) -> DesignView | None:
    """The survey design sheet of a specification, in ``locale``.

    Parameters
    ----------
    spec : PlanResult
        The specification of ``scanplan plan`` (with its ``design``).
    locale : {"en", "ru"}
    cite : callable
        The document's citation function (``Bibliography.cite``): norms are numbered in
        the order the document first cites them.

    Returns
    -------
    DesignView or None
        None without a specification or a survey design.
    """
    design = getattr(spec, "design", None)
    if spec is None or design is None:
        return None
    platform = spec.uav.job.plan.inputs.platform if spec.uav is not None else "uav"
    w = _W(locale, cite, platform)
    rows = _project_rows(spec, w)
    if spec.uav is not None:
        rows += _uav_rows(spec, w)
    if spec.film is not None:
        rows += _film_rows(spec, w)
    rows += _block_rows(design, w) + _sun_rows(design, w) + _binding_rows(spec, w)
    notes = [sentence(w.msg(x.message)) for x in design.warnings]
    return DesignView(rows, notes, [w.key_of(label) for label, _, _ in rows])


TERMINAL_ROWS = ("design_gsd_digital", "design_gsd_film", "design_block", "design_sun_window",
                 "sorties", "design_flying_days")
"""The survey design rows the terminal summary shows."""


def design_text_lines(spec: Any, locale: str) -> list[str]:
    """The survey design's key figures for the terminal summary of ``scanplan plan``
    (the GSD against Table Б.1, the one-height rule, the sun window, the flying days)."""
    view = design_view(spec, locale, lambda text: text)
    if view is None:
        return []
    rows = [(label, value) for (label, value, _), key in zip(view.rows, view.keys, strict=True)
            if key in TERMINAL_ROWS]
    if not rows:
        return []
    out = ["", t("design_title", locale) + ":"]
    out += [f"  {label}: {value}" for label, value in rows]
    return out
