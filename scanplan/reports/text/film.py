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
    tables = ResultTables(scan=plan, scan_norms=norm_set)  # built once for this report
    r = {row.key: row for row in tables["film_inputs"].rows}
    width, along = r["frame_mm"].value
    frame = dict(f=f.short(r["focal_mm"].value), w=f.short(width), l=f.short(along))
    camera = r["camera"].value
    cam = (f.cli("scan_camera", camera=camera, **frame) if camera
           else f.cli("scan_no_camera", **frame))
    lines = [
        f.cli("scan_head", map=f.scale(r["map_scale"].value),
              hc=f.short(r["relief_interval_m"].value)),
        f.cli("scan_camera_line", camera=cam, r=f.short(r["resolving_power_lpmm"].value),
              p=f.short(r["forward_overlap_pct"].value)),
    ]
    if norm_name:
        if f.locale == "ru" and getattr(norm_set, "title_ru", ""):
            norm_title = norm_set.title_ru
        lines.append(f.cli("norm_set", name=norm_name)
                     + (f" — {norm_title}" if norm_title else ""))
    obj = r["object"].value
    if obj:
        lines.append(f.cli("scan_object", name=norm_object(f, norm_set, obj.name, obj.size_m),
                           size=f.short(r["object_size_m"].value),
                           shape=norm_shape(f, norm_set, r["shape"].value),
                           b=f.short(r["shape_coefficient"].value),
                           p=f.short(r["probability"].value),
                           source=author_cite(f.text(r["object_source"].value), f.locale)))
    lines.append("")
    tbl = tables["film_constraints"]
    lines.append(text_table(tbl, label=lambda r: _film_label(r, f),
                            unit=lambda r: f.cli(r.unit) if r.unit else "",
                            cell=lambda r, i, v: _film_cell(r, i, v, f),
                            head=["", "", *(f.scale(c.value) for c in tbl.columns)],
                            align="ll" + "r" * len(tbl.columns)))
    lines.append(f.cli("binding_note"))
    lines.append("")
    lines.append(f.cli("why"))
    for row in tables["film_explanations"].rows:
        lines.append(wrap(f.text(row.value), "  "))
    reach = tables["film_reach"]
    limit = reach.row("interpretation_limit")
    if limit.value is not None:
        lines.append("")
        lines.append(wrap(f.cli(
            "interpretation_limit",
            obj=norm_object(f, norm_set, obj.name, obj.size_m) if obj else f.cli("the_object"),
            p=f.short(limit.fields["probability"]), scale=f.scale(math.floor(limit.value)),
            ratio=f.fixed(limit.fields["ratio"], 1),
            r=f.short(limit.fields["resolving_power"])), ""))
    lines += _reach_lines(reach, r, f)
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


def _reach_lines(reach: Table, inputs: dict[str, Row], f: Formatter) -> list[str]:
    """The smallest photo scale (largest Mc) each scan pixel supports (the ``film_reach``
    table: the scanner's steps, --pixel-um)."""
    rows = [r for r in reach.rows if r.key == "reach"]
    if not rows:
        return []
    scanner = inputs["scanner"].value
    who = f.cli("reach_and").join(
        x for x in (f.cli("reach_scanner", scanner=scanner) if scanner else "",
                    "--pixel-um" if "candidate_pixels_um" in inputs else "") if x)
    both = reach.row("interpretation_limit").value is not None
    out = [[f.cli("pixel_um"), f.cli("reach_scale"), f.cli("reach_limit")]
           + ([f.cli("reach_interpretable")] if both else [])]
    for r in rows:
        pixel, largest, limit, interpretable = r.values
        if largest is not None:
            row = [f.short(pixel), f.scale(math.floor(largest)), limit]
        else:
            row = [f.short(pixel), f.cli("none"), f.cli("reach_pr")]
        if both:
            row.append(f.scale(math.floor(interpretable)) if interpretable else f.cli("none"))
        out.append(row)
    return ["", f.cli("reach_head", who=who), table(out, align="rrlr" if both else "rrl")]
