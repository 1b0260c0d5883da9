"""Plain-text rendering of results for the terminal (aligned tables, wrapped notes)."""

from __future__ import annotations

import math
import textwrap
from collections.abc import Sequence

from .planner import CONSTRAINTS, ScanPlan
from .serialize import scale_value

__all__ = ["format_scan_plan", "table"]


def table(rows: Sequence[Sequence[str]], *, align: str = "", gap: int = 2) -> str:
    """Align rows of cells; ``align`` holds 'l'/'r' per column (default: first l, rest r)."""
    widths = [max(len(r[i]) for r in rows if i < len(r)) for i in range(max(map(len, rows)))]
    out = []
    for r in rows:
        cells = []
        for i, cell in enumerate(r):
            a = align[i] if i < len(align) else ("l" if i == 0 else "r")
            cells.append(cell.ljust(widths[i]) if a == "l" else cell.rjust(widths[i]))
        out.append((" " * gap).join(cells).rstrip())
    return "\n".join(out)


def _num(x: float | None, digits: int = 1) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "—"
    return f"{x:.{digits}f}"


def _wrap(text: str, indent: str) -> str:
    return textwrap.fill(text, width=96, initial_indent=indent,
                         subsequent_indent=" " * len(indent))


def format_scan_plan(plan: ScanPlan, norm_name: str = "", norm_title: str = "") -> str:
    """The terminal report of ``scanplan scan``: constraints × photo scales, like seed 001's
    Tables 6–9, with the binding constraint starred, then reasons and warnings."""
    inp = plan.inputs
    cam = (f"camera {inp.camera} (f {inp.focal_mm:g} mm, frame {inp.frame_width_mm:g}×"
           f"{inp.frame_along_mm:g} mm)" if inp.camera else
           f"f {inp.focal_mm:g} mm, frame {inp.frame_width_mm:g}×{inp.frame_along_mm:g} mm")
    lines = [
        f"Scan plan — map 1:{scale_value(inp.map_scale)}, relief interval "
        f"{inp.relief_interval_m:g} m",
        f"{cam}, R {inp.resolving_power_lpmm:g} lines/mm, forward overlap "
        f"{inp.forward_overlap_pct:g} %",
    ]
    if norm_name:
        lines.append(f"norm set {norm_name}" + (f" — {norm_title}" if norm_title else ""))
    obj = inp.object
    if obj:
        lines.append(f"object to interpret: {obj.name}, {obj.size_m:g} m, {obj.shape} "
                     f"(B {obj.shape_coefficient:g}), P {plan.rules.probability:g} — {obj.source}")
    lines.append("")
    header = ["", "", *(f"1:{scale_value(s.photo_scale)}" for s in plan.scenarios)]
    rows = [header, ["Mc/Mk", "", *(f"{s.photo_to_map_ratio:.1f}" for s in plan.scenarios)]]
    for cid in plan.rules.constraints:
        row = [f"{cid}  {CONSTRAINTS[cid].name}", "µm"]
        for s in plan.scenarios:
            c = s.constraint(cid)
            row.append(_num(c.pixel_um) + ("*" if c.binding else " "))
        rows.append(row)
    rows.append(["binding", "", *(s.binding + " " for s in plan.scenarios)])
    rows.append(["scan pixel", "µm", *(_num(s.scan_pixel_um) + " " for s in plan.scenarios)])
    if inp.scanner:
        rows.append([f"scanner {inp.scanner} step", "µm",
                     *(_num(s.scanner_pixel_um) + " " for s in plan.scenarios)])
    rows.append([f"scanned frame ({inp.bands} band, {inp.bits_per_band} bit)", "MB",
                 *(f"{s.frame_megabytes:,.0f} " for s in plan.scenarios)])
    rows.append(["photo resolution on the ground A", "mm",
                 *(_num(s.resolution_on_ground_mm) + " " for s in plan.scenarios)])
    if obj:
        rows.append(["R needed to interpret", "lines/mm",
                     *(_num(s.required_resolving_power_lpmm) + " " for s in plan.scenarios)])
        rows.append(["P(recognition) at the scan pixel", "",
                     *(_num(s.recognition_probability, 2) + " " for s in plan.scenarios)])
    lines.append(table(rows, align="ll" + "r" * len(plan.scenarios)))
    lines.append("* binding constraint (the smallest allowed pixel)")
    lines.append("")
    lines.append("Why:")
    for s in plan.scenarios:
        lines.append(_wrap(s.explanation, "  "))
    if plan.interpretation_limit_photo_scale is not None:
        mci = plan.interpretation_limit_photo_scale
        lines.append("")
        lines.append(_wrap(
            f"Interpretation limit: {obj.name if obj else 'the object'} can be recognised with "
            f"P ≥ {plan.rules.probability:g} on photos up to 1:{math.floor(mci):d} "
            f"(Mc/Mk ≤ {mci / inp.map_scale:.1f}) at R {inp.resolving_power_lpmm:g} lines/mm.",
            ""))
    if plan.max_photo_scales:
        lines.append("")
        who = " and ".join(x for x in (f"scanner {inp.scanner}" if inp.scanner else "",
                                       "--pixel-um" if inp.candidate_pixels_um else "") if x)
        lines.append(f"Largest photo scale each scan pixel supports ({who}):")
        rows = [["pixel µm", "photo scale", "limited by"]]
        for r in plan.max_photo_scales:
            if r.max_photo_scale > 0:
                rows.append([f"{r.pixel_um:g}", f"1:{math.floor(r.max_photo_scale):d}", r.limit])
            else:
                rows.append([f"{r.pixel_um:g}", "none", "PR (pixel coarser than P_R)"])
        lines.append(table(rows, align="rrl"))
    if plan.warnings:
        lines.append("")
        lines.append("Warnings:")
        for w in plan.warnings:
            mark = "!" if w.severity == "warning" else "i"
            lines.append(_wrap(f"{w.message} [{w.code}]", f"  {mark} "))
    return "\n".join(lines)
