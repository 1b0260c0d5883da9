"""The terminal report of ``scanplan scan``: constraints × photo scales, the reasons, the
smallest photo scale each scan pixel supports and the warnings, in the language of
``--locale``."""

from __future__ import annotations

import math
from typing import Any

from ...rules.film import ScanPlan
from ..formatter import Formatter, formatter
from ..references import author_cite
from ..views import ResultTables, Row, Table
from .layout import code_tag, table, text_table, wrap

__all__ = ["format_scan_plan", "norm_object", "norm_shape", "warning_lines"]


def norm_object(f: Formatter, norm_set: Any, name: str, size_m: float | None = None) -> str:
    """A norm object's name in the terminal's language (the norm set's Russian name; the
    English terminal names it as the norm table does)."""
    if f.locale != "ru" or norm_set is None:
        return name
    return f.object_named(norm_set, name, size_m)


def norm_shape(f: Formatter, norm_set: Any, shape: str) -> str:
    """A shape in words (the norm set's Russian name)."""
    return f.shape(norm_set, shape) if f.locale == "ru" and norm_set is not None else shape


def format_scan_plan(plan: ScanPlan, norm_name: str = "", norm_title: str = "",
                     locale: str = "en", norm_set: Any = None) -> str:
    """The terminal report of ``scanplan scan``: constraints × photo scales, like seed 001's
    Tables 6–9, with the binding constraint starred, then reasons and warnings.

    Parameters
    ----------
    plan : ScanPlan
    norm_name, norm_title : str
        The norm set's name and title.
    locale : {"en", "ru"}
        The language (``--locale``).
    norm_set : NormSet, optional
        For the Russian names of objects and shapes.
    """
    f = formatter(locale)
    inp = plan.inputs
    frame = dict(f=f.short(inp.focal_mm), w=f.short(inp.frame_width_mm),
                 l=f.short(inp.frame_along_mm))
    cam = (f.cli("scan_camera", camera=inp.camera, **frame) if inp.camera
           else f.cli("scan_no_camera", **frame))
    lines = [
        f.cli("scan_head", map=f.scale(inp.map_scale), hc=f.short(inp.relief_interval_m)),
        f.cli("scan_camera_line", camera=cam, r=f.short(inp.resolving_power_lpmm),
              p=f.short(inp.forward_overlap_pct)),
    ]
    if norm_name:
        if f.locale == "ru" and getattr(norm_set, "title_ru", ""):
            norm_title = norm_set.title_ru
        lines.append(f.cli("norm_set", name=norm_name)
                     + (f" — {norm_title}" if norm_title else ""))
    obj = inp.object
    if obj:
        lines.append(f.cli("scan_object", name=norm_object(f, norm_set, obj.name, obj.size_m),
                           size=f.short(obj.size_m), shape=norm_shape(f, norm_set, obj.shape),
                           b=f.short(obj.shape_coefficient), p=f.short(plan.rules.probability),
                           source=author_cite(f.text(obj.source), f.locale)))
    lines.append("")
    tables = ResultTables(scan=plan)  # built once for this report
    tbl = tables["film_constraints"]
    lines.append(text_table(tbl, label=lambda r: _film_label(r, f),
                            unit=lambda r: f.cli(r.unit) if r.unit else "",
                            cell=lambda r, i, v: _film_cell(r, i, v, f),
                            head=["", "", *(f.scale(c.value) for c in tbl.columns)],
                            align="ll" + "r" * len(tbl.columns)))
    lines.append(f.cli("binding_note"))
    lines.append("")
    lines.append(f.cli("why"))
    for s in plan.scenarios:
        lines.append(wrap(f.text(s.explanation), "  "))
    if plan.interpretation_limit_photo_scale is not None:
        mci = plan.interpretation_limit_photo_scale
        lines.append("")
        lines.append(wrap(f.cli(
            "interpretation_limit",
            obj=norm_object(f, norm_set, obj.name, obj.size_m) if obj else f.cli("the_object"),
            p=f.short(plan.rules.probability), scale=f.scale(math.floor(mci)),
            ratio=f.fixed(mci / inp.map_scale, 1), r=f.short(inp.resolving_power_lpmm)), ""))
    lines += _reach_lines(plan, f)
    lines += warning_lines(tables["film_warnings"], f, scan=True)
    return "\n".join(lines)


#: The terminal's word of each row of the film table.
_FILM_WORDS = {"binding": "binding", "scan_pixel_um": "scan_pixel",
               "scanner_pixel_um": "scanner_step_of", "frame_megabytes": "scanned_frame",
               "resolution_on_ground": "resolution_a", "required_r": "r_needed",
               "recognition_probability": "p_at_pixel"}


def _film_label(r: Row, f: Formatter) -> str:
    """A row's label in the film table: ``PZ  height accuracy``, ``Mc/Mk``, a word."""
    if "constraint" in r.flags:
        return f"{r.key}  {f.constraint(r.key)}"
    if r.key == "photo_to_map":
        return "Mc/Mk"
    return f.cli(_FILM_WORDS[r.key], **r.fields)


def _film_cell(r: Row, i: int, v: Any, f: Formatter) -> str:
    """A value of the film table: pixels as µm (``*`` where a constraint binds; the other
    results keep its column), the frame grouped."""
    if r.key == "photo_to_map":
        return f.fixed(v, r.digits or 0)
    if isinstance(v, str):
        text = v
    elif "constraint" in r.flags or r.key == "scan_pixel_um":
        text = f.um(v)
    elif r.key == "frame_megabytes":
        text = f.num(v, r.digits or 0)
    else:
        text = f.fixed(v, r.digits if r.digits is not None else 1)
    return text + ("*" if r.flagged(i, "binding") else " ")


def warning_lines(warnings: Table, f: Formatter, scan: bool = False) -> list[str]:
    """A warnings table as lines: ``!`` before each (a film plan's notes: ``i``)."""
    if not warnings.rows:
        return []
    out = ["", f.cli("warnings")]
    for r in warnings.rows:
        mark = "!" if (not scan or "warning" in r.flags) else "i"
        out.append(wrap(f.text(r.values[0]) + code_tag(r.key, f.locale), f"  {mark} "))
    return out


def _reach_lines(plan: ScanPlan, f: Formatter) -> list[str]:
    """The smallest photo scale (largest Mc) each scan pixel supports (scanner steps,
    --pixel-um)."""
    inp = plan.inputs
    lines: list[str] = []
    if plan.max_photo_scales:
        lines.append("")
        who = f.cli("reach_and").join(
            x for x in (f.cli("reach_scanner", scanner=inp.scanner) if inp.scanner else "",
                        "--pixel-um" if inp.candidate_pixels_um else "") if x)
        lines.append(f.cli("reach_head", who=who))
        both = plan.interpretation_limit_photo_scale is not None
        rows = [[f.cli("pixel_um"), f.cli("reach_scale"), f.cli("reach_limit")]
                + ([f.cli("reach_interpretable")] if both else [])]
        for r in plan.max_photo_scales:
            if r.max_photo_scale > 0:
                row = [f.short(r.pixel_um), f.scale(math.floor(r.max_photo_scale)), r.limit]
            else:
                row = [f.short(r.pixel_um), f.cli("none"), f.cli("reach_pr")]
            if both:
                mi = r.max_photo_scale_interpretable
                row.append(f.scale(math.floor(mi)) if mi else f.cli("none"))
            rows.append(row)
        lines.append(table(rows, align="rrlr" if both else "rrl"))
    return lines
