"""Plain-text rendering of results for the terminal (aligned tables, wrapped notes)."""

from __future__ import annotations

import math
import os
import textwrap
from collections.abc import Sequence
from typing import Any

from .planner import CONSTRAINTS, ScanPlan
from .serialize import scale_value
from .uav import UavPlan

__all__ = ["format_plan_result", "format_scan_plan", "format_uav_plan", "table"]


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


def _um(x: float | None) -> str:
    """A pixel [µm]: one decimal, or two significant digits below 1 µm (never ``0.0``)."""
    if x is None or not math.isfinite(x) or x >= 0.95:
        return _num(x)
    return f"{x:.2g}"


def _interval(seconds: float) -> str:
    """The photo interval; none at ground speed 0 (a hovering UAV), never ``inf``."""
    return f"{seconds:.2f} s" if math.isfinite(seconds) else "— (ground speed ≈ 0)"


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
            row.append(_um(c.pixel_um) + ("*" if c.binding else " "))
        rows.append(row)
    rows.append(["binding", "", *(s.binding + " " for s in plan.scenarios)])
    rows.append(["scan pixel", "µm", *(_um(s.scan_pixel_um) + " " for s in plan.scenarios)])
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
        both = plan.interpretation_limit_photo_scale is not None
        rows = [["pixel µm", "largest photo scale", "limited by"]
                + (["with the object interpretable"] if both else [])]
        for r in plan.max_photo_scales:
            if r.max_photo_scale > 0:
                row = [f"{r.pixel_um:g}", f"1:{math.floor(r.max_photo_scale):d}", r.limit]
            else:
                row = [f"{r.pixel_um:g}", "none", "PR (pixel coarser than P_R)"]
            if both:
                mi = r.max_photo_scale_interpretable
                row.append(f"1:{math.floor(mi):d}" if mi else "none")
            rows.append(row)
        lines.append(table(rows, align="rrlr" if both else "rrl"))
    if plan.warnings:
        lines.append("")
        lines.append("Warnings:")
        for w in plan.warnings:
            mark = "!" if w.severity == "warning" else "i"
            lines.append(_wrap(f"{w.message} [{w.code}]", f"  {mark} "))
    return "\n".join(lines)


def _carrier(platform: str) -> str:
    """How the terminal names the digital-camera flight: a UAV, or a manned aerial survey
    (a large-format camera, catalogue ``platform = aircraft``)."""
    return "Aerial survey (digital camera)" if platform == "aircraft" else "UAV"


def format_uav_plan(plan: UavPlan, norm_name: str = "") -> str:
    """The terminal report of ``scanplan uav``."""
    inp = plan.inputs
    h = plan.heights_m
    cam = inp.camera or "camera"
    lines = [
        f"{_carrier(inp.platform)} plan — {cam}"
        + (f" ({inp.camera_name})" if inp.camera_name else ""),
        f"pixel {inp.pixel_um:g} µm, f {inp.focal_mm:g} mm, f/{inp.f_number:g}, sensor "
        f"{inp.sensor_width_mm:g}×{inp.sensor_height_mm:g} mm; height {h['planned']:g} m"
        + (f" (flown {h['min']:g}–{h['max']:g} m)" if h["max"] != h["min"] else "")
        + f", speed {inp.speed_ms:g} m/s, exposure {inp.exposure_s:g} s, overlaps "
        f"{inp.forward_overlap_pct:g}/{inp.side_overlap_pct:g} %",
        f"scene contrast r {inp.r_max:g}/{inp.r_min:g}, threshold contrast K0 {inp.threshold_k0:g}"
        + (f"; norm set {norm_name}" if norm_name else ""),
        "",
    ]
    rows = [["", "", f"at {h['planned']:g} m"]]
    if h["max"] != h["planned"]:
        rows[0].append(f"at {h['max']:g} m")
    two = len(rows[0]) == 4
    rows.append(["GSD", "m", _num(plan.gsd_m, 3),
                 *([_num(plan.gsd_at_max_height_m, 3)] if two else [])])
    rows.append(["sensor limit (Nyquist)", "lines/mm", f"{plan.nyquist_lpmm:.1f}",
                 *([""] if two else [])])
    rows.append(["resolving power R, centre / corner", "lines/mm",
                 f"{_num(plan.resolving_power_lpmm)} / {_num(plan.resolving_power_corner_lpmm)}",
                 *([""] if two else [])])
    rows.append(["ground resolution L (centre)", "m", _num(plan.ground_resolution_m, 3),
                 *([_num(plan.ground_resolution_at_max_height_m, 3)] if two else [])])
    rows.append(["L at the frame corner", "m", _num(plan.ground_resolution_corner_m, 3),
                 *([""] if two else [])])
    rows.append(["L / GSD", "", _num(plan.ground_resolution_to_gsd, 2), *([""] if two else [])])
    rows.append([f"motion blur (at {h['min']:g} m)", "px", f"{plan.motion_blur_px:.2f}",
                 *([""] if two else [])])
    if plan.tilted_corner_gsd_m is not None:
        rows.append([f"worst corner GSD, roll {inp.roll_deg:g}° pitch {inp.pitch_deg:g}°", "m",
                     "", *([_num(plan.tilted_corner_gsd_m, 3)] if two else [])])
    lines.append(table(rows, align="ll" + "r" * (len(rows[0]) - 2)))
    lines.append(f"blur ≤ 0.5 px needs exposure ≤ 1/{math.ceil(1 / plan.max_exposure_s):d} s "
                 f"or speed ≤ {plan.max_speed_ms:.1f} m/s")
    fl = plan.flight
    lines += ["", "Flight geometry (at the planned height):"]
    frows = [["footprint", f"{fl['footprint_across_m']:.0f} × {fl['footprint_along_m']:.0f} m"],
             ["base / line spacing", f"{fl['base_m']:.1f} m / {fl['line_spacing_m']:.1f} m"],
             ["photo interval", _interval(fl['photo_interval_s'])
              + (f" (camera minimum {fl['min_trigger_interval_s']:g} s)"
                 if "min_trigger_interval_s" in fl else "")],
             [f"forward overlap at {h['min']:g} / {h['max']:g} m",
              f"{fl['forward_overlap_at_min_height_pct']:.1f} / "
              f"{fl['forward_overlap_at_max_height_pct']:.1f} %"]]
    if "strips" in fl:
        frows += [["strips × photos", f"{fl['strips']} × {fl['photos_per_strip']} = "
                   f"{fl['photos']} photos"],
                  ["flight length / time", f"{fl['flight_length_m'] / 1000:.1f} km / "
                   + (f"{fl['flight_time_s'] / 60:.0f} min" if fl.get("flight_time_s") else "—")]]
        if "data_volume_bytes" in fl:
            frows.append(["data volume", _volume(fl["data_volume_bytes"])])
    lines.append(table([[f"  {a}", b] for a, b in frows], align="ll"))
    if plan.recognition:
        lines += ["", "Recognition probability of the norm objects (P = exp(−(B·L/L_obj)²)):"]
        rrows = [["  object", "map", "size m", "shape", f"{h['planned']:g} m",
                  f"{h['max']:g} m", "corner"]]
        for r in plan.recognition:
            rrows.append([f"  {r.object}", f"1:{r.map_scale}" if r.map_scale else "—",
                          f"{r.object_size_m:g}", r.shape, _num(r.probability, 2),
                          _num(r.probability_at_max_height, 2),
                          _num(r.probability_corner_at_max_height, 2)])
        lines.append(table(rrows, align="llrlrrr"))
    if plan.limits:
        tol = inp.height_tolerance_up_pct
        lines += ["", f"Maximum flight height for map 1:{scale_value(inp.map_scale or 0)}, relief "
                  f"interval {inp.relief_interval_m:g} m"
                  + (f" (checked at +{tol:g} % height)" if tol else "") + ":"]
        lrows = [["  constraint", "limit on the ground", "compared with", "max height"]]
        for lim in sorted(plan.limits, key=lambda x: x.max_height_m):
            lrows.append([f"  {lim.id}  {lim.name}", f"{lim.limit_m:.3f} m", lim.compares,
                          f"{lim.max_height_m:.0f} m" + ("*" if lim.binding else " ")])
        lines.append(table(lrows, align="lrlr"))
        b = next(x for x in plan.limits if x.binding)
        lines.append(_wrap(f"Maximum height {plan.max_height_m:.0f} m: {b.id} ({b.name}) binds — "
                           f"{b.reason}.", ""))
    if plan.warnings:
        lines += ["", "Warnings:"]
        for w in plan.warnings:
            lines.append(_wrap(f"{w.message} [{w.code}]", "  ! "))
    return "\n".join(lines)


def format_plan_result(result: Any) -> str:
    """The concise terminal summary of ``scanplan plan``."""
    meta = result.meta
    inp_map = result.project.values["map"]
    lines = [f"{meta.project} — map 1:{inp_map['scale']}, relief interval "
             f"{inp_map['relief_interval_m']:g} m"]
    if meta.customer or meta.contractor:
        lines.append(", ".join(x for x in (f"customer {meta.customer}" if meta.customer else "",
                                           f"contractor {meta.contractor}"
                                           if meta.contractor else "") if x))
    if result.film:
        f = result.film
        s = f.recommended
        lines += ["", "Film:"]
        if s is None:
            lines.append(_wrap(f.reason, "  "))
        else:
            px = (f"{_um(s.scan_pixel_um)} µm"
                  + (f" → scanner step {s.scanner_pixel_um:g} µm" if s.scanner_pixel_um else ""))
            rows = [["  photo scale (existing photos, given)" if f.archive
                     else "  recommended photo scale", f"1:{scale_value(s.photo_scale)}"],
                    ["  scan pixel", px],
                    ["  binding constraint", f"{s.binding} ({CONSTRAINTS[s.binding].name})"],
                    ["  recognition of the map object", _num(s.recognition_probability, 2)],
                    ["  scanned frame", f"{s.frame_megabytes:,.0f} MB"]]
            if f.frames is not None:
                rows.append(["  frames for the area", f"{f.frames} ({f.strips} strips), "
                             f"{f.scanned_gigabytes:,.1f} GB scanned, uncompressed"])
            lines.append(table(rows, align="ll"))
            lines.append(_wrap(f.reason, "  "))
    if result.uav:
        u = result.uav
        p = u.job.plan
        lines += ["", f"{_carrier(p.inputs.platform)}:"]
        if u.recommended_height_m is None:
            lines.append(_wrap(u.reason, "  "))
        else:
            tol = p.inputs.height_tolerance_up_pct
            rows = [["  recommended flight height", f"{u.recommended_height_m:g} m"
                     + (f" (flown up to {p.heights_m['max']:g} m, +{tol:g} %)" if tol else "")],
                    ["  maximum flight height", f"{u.max_height_m:.0f} m ({p.binding} "
                     f"{CONSTRAINTS[p.binding].name})" if p.binding else "—"],
                    ["  GSD / ground resolution L", f"{p.gsd_m:.3f} m / "
                     f"{_num(p.ground_resolution_m, 3)} m (L/GSD "
                     f"{_num(p.ground_resolution_to_gsd, 2)})"]]
            obj = p.inputs.map_object
            if obj is not None:
                rec = next((r for r in p.recognition if r.object == obj.name
                            and r.object_size_m == obj.size_m), None)
                if rec:
                    rows.append(["  recognition of the map object",
                                 f"{_num(rec.probability, 2)} ({obj.name}, {obj.size_m:g} m)"])
            fl = p.flight
            rows.append(["  overlaps / base / spacing",
                         f"{p.inputs.forward_overlap_pct:g} % / {p.inputs.side_overlap_pct:g} % "
                         f"— {fl['base_m']:.1f} m / {fl['line_spacing_m']:.1f} m"])
            rows.append(["  photo interval", _interval(fl['photo_interval_s'])])
            if "photos" in fl:
                rows.append(["  photos / strips", f"{fl['photos']} / {fl['strips']}"])
                rows.append(["  flight", f"{fl['flight_length_m'] / 1000:.1f} km"
                             + (f", {fl['flight_time_s'] / 60:.0f} min"
                                if fl.get("flight_time_s") else "")])
                if "data_volume_bytes" in fl:
                    rows.append(["  data volume", _volume(fl["data_volume_bytes"])])
            rows.append(["  blur limit", f"exposure ≤ 1/{math.ceil(1 / p.max_exposure_s):d} s "
                         f"or speed ≤ {p.max_speed_ms:.1f} m/s"])
            lines.append(table(rows, align="ll"))
            lines.append(_wrap(u.reason, "  "))
    if result.comparison:
        word = _carrier(result.uav.job.plan.inputs.platform) if result.uav else "UAV"
        lines += ["", f"Film and {word if word == 'UAV' else 'digital camera'} side by side:"]
        rows = [["  quantity", "film", word if word == "UAV" else "digital", "unit"]]
        for c in result.comparison:
            def v(x: Any) -> str:
                if x is None:
                    return "—"
                return f"{x:,.3f}" if isinstance(x, float) else str(x)
            rows.append([f"  {c['quantity']}", v(c["film"]), v(c["uav"]), c["unit"]])
        lines.append(table(rows, align="lrrl"))
    if result.warnings:
        lines += ["", "Warnings:"]
        for w in result.warnings:
            mark = "!" if w.severity == "warning" else "i"
            lines.append(_wrap(f"{w.message} [{w.code}]", f"  {mark} "))
    return "\n".join(lines)


def batch_summary(done: list[tuple[str, Any]], failed: list[tuple[str, str]]) -> str:
    """One table for a batch of projects: the headline of each, then the failures."""
    rows = [["project", "map", "film: photo scale", "scan µm", "digital camera: height m", "max m",
             "binding"]]
    for path, r in done:
        f, u = r.film, r.uav
        rec = f.recommended if f else None
        rows.append([
            os.path.basename(path), f"1:{r.project.values['map']['scale']}",
            (f"1:{scale_value(rec.photo_scale)}" if rec else "none") if f else "—",
            (_um(rec.scanner_pixel_um or rec.scan_pixel_um) if rec else "—") if f else "—",
            _num(u.recommended_height_m, 0) if u else "—",
            _num(u.max_height_m, 0) if u else "—",
            " / ".join(x for x in ((rec.binding if rec else "") if f else "",
                                   (u.job.plan.binding or "") if u else "") if x) or "—"])
    out = table(rows, align="llrrrrl")
    if failed:
        out += f"\n{len(done)} planned, {len(failed)} failed:"
        for path, msg in failed:
            out += "\n" + _wrap(f"{os.path.basename(path)}: {msg}", "  ! ")
    return out


def _volume(uncompressed_bytes: float) -> str:
    """``163.5 GB uncompressed (JPEG ≈ 18.2 GB)``: the JPEG estimate of
    :func:`scanplan.flight.jpeg_volume_bytes`."""
    from .flight import JPEG_COMPRESSION_RATIO, jpeg_volume_bytes

    jpeg = float(jpeg_volume_bytes(uncompressed_bytes)) / 1e9
    return (f"{uncompressed_bytes / 1e9:.1f} GB uncompressed "
            f"(JPEG ≈ {jpeg:.1f} GB at {JPEG_COMPRESSION_RATIO:g}:1)")


def batch_warnings(done: list[tuple[str, Any]]) -> str:
    """The warnings of each project of a batch, under its file name ("" if none)."""
    out: list[str] = []
    for path, r in done:
        if not r.warnings:
            continue
        out += ["", f"Warnings — {os.path.basename(path)}:"]
        for w in r.warnings:
            mark = "!" if w.severity == "warning" else "i"
            out.append(_wrap(f"{w.message} [{w.code}]", f"  {mark} "))
    return "\n".join(out)
