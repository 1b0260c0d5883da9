"""The terminal summary of ``scanplan plan`` and of a batch, in the project's language."""

from __future__ import annotations

import math
import os
import textwrap
from collections.abc import Callable
from typing import Any, NamedTuple

from ..formatter import COMPARISON_LABELS, Formatter, formatter
from ..jsondoc import scale_value
from ..views import ResultTables, Row, Table
from ..views.design import TERMINAL_ROWS
from .area import format_area, format_layout, format_terrain
from .layout import WIDTH, code_tag, table, text_table, wrap
from .uav import volume_text

__all__ = ["PLAN_PARTS", "PlanPart", "batch_row", "batch_summary", "batch_table",
           "batch_warnings", "format_plan_result", "project_warnings", "warning_items"]


def format_plan_result(result: Any, locale: str | None = None,
                       tables: ResultTables | None = None) -> str:
    """The concise terminal summary of ``scanplan plan``, in the project's language
    (``[project] locale``) unless ``locale`` is given.

    Parameters
    ----------
    result : PlanResult
        The specification.
    locale : {"en", "ru"}, optional
        The language (default: the project's).
    tables : ResultTables, optional
        The result's tables when a view of it already holds them (``view.tables``): the
        summary lays out the same records as the documents; built here otherwise.

    Returns
    -------
    str
    """
    f = formatter(locale or result.meta.locale)
    if tables is None:
        tables = ResultTables.of_jobs(result.film.job if result.film else None,
                                      result.uav.job if result.uav else None, result)
    lines: list[str] = []
    for part in PLAN_PARTS:
        lines += part.lines(result, tables, f)
    return "\n".join(lines)


def _platform(tables: ResultTables) -> str:
    """The digital camera's carrier (``"uav"``, ``"aircraft"``): the UAV inputs'."""
    return str(tables["uav_inputs"].row("platform").value)


def _design_lines(tables: ResultTables, f: Formatter) -> list[str]:
    """The survey design's key figures (the ``design`` table's :data:`TERMINAL_ROWS`: the
    GSD against Table Б.1, the one-height rule, the sun window, the flying days)."""
    if not tables.has("design"):
        return []
    rows = [(f.row_label(r), f.show(r.values[0])) for r in tables["design"].rows
            if r.key in TERMINAL_ROWS]
    if not rows:
        return []
    return ["", f("survey_design") + ":", *(
        textwrap.fill(f"{label}: {value}", width=WIDTH, initial_indent="  ",
                      subsequent_indent="    ") for label, value in rows)]


def _control_lines(tables: ResultTables, f: Formatter) -> list[str]:
    """The ground control: counts, figures and the error budget at best, and the control's
    precision against the target (the ``control`` and ``control_checks`` tables)."""
    from ..controlwords import check_rows, summary_rows

    rows = summary_rows(tables, f)
    width = max(len(label) for label, _, _ in rows)
    lines = ["", f("control_points") + ":"]
    lines += [f"  {label:<{width}}  {value}" for label, value, _ in rows]
    lines.append(f"  {f('control_check')}:")
    for rule, axis, ratio, required, ok, _ in check_rows(tables, f):
        lines.append(f"    {rule} ({axis}): {ratio} / {required} — {ok}")
    return lines


def _plan_heading(result: Any, f: Formatter) -> list[str]:
    """The project, map scale and relief interval, the parties, the area and its flight
    lines."""
    meta = result.meta
    inp_map = result.project.map
    lines = [f"{meta.project} — {f.cli('map')} {f.scale(scale_value(inp_map.scale))}, "
             f"{f.cli('relief_interval')} {f.short(inp_map.relief_interval_m)} {f.cli('m')}"]
    if meta.customer or meta.contractor:
        lines.append(", ".join(x for x in (f"{f.cli('customer')} {meta.customer}"
                                           if meta.customer else "",
                                           f"{f.cli('contractor')} {meta.contractor}"
                                           if meta.contractor else "") if x))
    area = getattr(result, "area", None)
    if area is not None and area.georeferenced:
        lines.append(format_area(area, f.locale))
        for kind, lay in result.layouts.items():
            scale = (f.scale(result.film.recommended.photo_scale)
                     if kind == "film" and result.film.recommended else "")
            lines.append(format_layout(lay, scale, f.locale))
    return lines


def _film_summary(tbl: Table, f: Formatter) -> list[str]:
    """The film block (the ``spec_film`` table): photo scale, scan pixel, binding
    constraint, frames, the reason."""
    r = {row.key: row for row in tbl.rows}
    lines = ["", f.cli("summary_film")]
    reason = wrap(f.text(r["reason"].value), "  ")
    if "photo_scale" not in r:
        return [*lines, reason]
    um = f.cli("um")
    px = (f"{f.um(r['scan_pixel_um'].value)} {um}"
          + (f" → {f.cli('scanner_step')} {f.short(r['scanner_pixel_um'].value)} {um}"
             if r.get("scanner_pixel_um") and r["scanner_pixel_um"].value else ""))
    binding, scale = r["binding"].value, r["photo_scale"]
    which = "photo_scale_archive" if "archive" in scale.flags else "recommended_photo_scale"
    rows = [[f"  {f.cli(which)}", f.scale(scale.value)],
            [f"  {f.cli('scan_pixel')}", px],
            [f"  {f.cli('binding_constraint')}", f"{binding} ({f.constraint(binding)})"],
            [f"  {f.cli('recognition_map_object')}", f.fixed(r["probability"].value, 2)],
            [f"  {f.cli('frame_volume')}",
             f"{f.num(r['frame_megabytes'].value, 0)} {f.cli('mb')}"]]
    if "frames" in r:
        frames, strips = r["frames"].value, r["strips"].value
        gb = f.num(r["scanned_gb"].value, 1)
        rows.append([f"  {f.cli('frames_for_area')}",
                     f"{frames} ({strips} {f.cli('strips_count')}), {gb} {f.cli('gb')} "
                     f"{f.cli('scanned_uncompressed')}" if f.locale == "en" else
                     f"{frames} ({f.cli('strips_count')}: {strips}), "
                     f"{f.cli('scanned_uncompressed')} {gb} {f.cli('gb')}"])
    return [*lines, table(rows, align="ll"), reason]


def _comparison_lines(result: Any, f: Formatter, tables: ResultTables) -> list[str]:
    """Film and digital camera side by side (the ``comparison`` table; counts grouped as
    the documents group them)."""
    aircraft = bool(result.uav) and _platform(tables) == "aircraft"

    def quantity(r: Row) -> str:  # the documents' word
        key = COMPARISON_LABELS.get(r.key)
        return "  " + (f(key) if key else r.fields["quantity"])

    def cell(r: Row, i: int, x: Any) -> str:
        return "—" if x is None else f.num(x, r.digits if r.digits is not None else 3)

    def unit(r: Row) -> str:
        return {"m": f.cli("m"), "GB": f.cli("gb")}.get(r.unit, r.unit)

    words = formatter(f.locale, "aircraft" if aircraft else "uav")  # the documents' words
    head = [f"  {words('spec_quantity')}", words("spec_film"), words("spec_uav"),
            words("unit")]
    text = text_table(tables["comparison"], label=quantity, cell=cell, head=head,
                      align="lrrl", after=unit)
    return ["", words("spec_comparison") + ":", text]


def warning_items(result: Any, locale: str, tables: ResultTables | None = None
                  ) -> list[tuple[str, str, str]]:
    """The warnings of a specification (the ``spec_warnings`` table) as the terminal and
    the page word them: (code, severity, sentence in ``locale``; in Russian the catalogue
    ids by their names, as the Russian documents show them)."""
    f = formatter(locale)
    if tables is None:
        tables = ResultTables(spec=result)
    ns = (result.film or result.uav).job.norm_set if (result.film or result.uav) else None
    return [(r.key, r.fields["severity"],
             f.message(r.values[0], ns if f.locale == "ru" else None))
            for r in tables["spec_warnings"].rows]


def _warning_lines(result: Any, f: Formatter, tables: ResultTables) -> list[str]:
    """The warnings (``!``) and notes (``i``) with their codes."""
    lines = ["", f.cli("warnings")]
    for code, severity, text in warning_items(result, f.locale, tables):
        mark = "!" if severity == "warning" else "i"
        lines.append(wrap(text + code_tag(code, f.locale), f"  {mark} "))
    return lines


def _uav_summary(tbl: Table, platform: str, f: Formatter) -> list[str]:
    """The UAV part of :func:`format_plan_result` (the ``spec_uav`` table)."""
    r = {row.key: row for row in tbl.rows}
    lines = ["", f.cli("summary_aircraft" if platform == "aircraft" else "summary_uav")]
    reason = wrap(f.text(r["reason"].value), "  ")
    height = r["recommended_height_m"]
    if height.value is None:
        return [*lines, reason]
    rows = _uav_heights(r, f)
    rows += _uav_flight_rows(r, f)
    lines.append(table(rows, align="ll"))
    lines.append(reason)
    return lines


def _uav_heights(r: dict[str, Row], f: Formatter) -> list[list[str]]:
    """The heights, the binding constraint, the GSD, the height accuracy, the recognition."""
    height = r["recommended_height_m"]
    tol = height.fields["tolerance_pct"]
    m = f.cli("m")
    flown = r.get("max_flown_height_m")
    binding = r["binding"].value if "binding" in r else None
    if height.fields.get("over_relief"):  # the heights really flown above the ground
        flown_text = (f" ({f.cli('flown_relief')} {f.num(height.fields['lowest'], 0)}–"
                      f"{f.num(height.fields['flown'], 0)} {m})")
    else:
        flown_text = (f" ({f.cli('flown_up_to')} {f.short(height.fields['flown'])} {m}, "
                      f"+{f.short(tol)} %)" if tol else "")
    rows = [[f"  {f.cli('recommended_height')}", f"{f.short(height.value)} {m}" + flown_text],
            [f"  {f.cli('max_height')}", f"{f.fixed(r['max_height_m'].value, 0)} {m}"
             + (f" ({f.cli('flown_up_to')} {f.fixed(flown.value, 0)} {m})"
                if tol and flown is not None else "")
             + f" ({binding} {f.constraint(binding)})" if binding else "—"],
            [f"  {f.cli('gsd_and_l')}", f"{f.fixed(r['gsd_m'].value, 3)} {m} / "
             f"{f.fixed(r['ground_resolution_m'].value, 3)} {m} ({f.cli('l_gsd')} "
             f"{f.fixed(r['l_over_gsd'].value, 2)})" + _at_highest(r, f)]]
    if "constraints_max_height_m" in r:
        rows.append([f"  {f.cli('no_ceiling')}",
                     f"{f.fixed(r['constraints_max_height_m'].value, 0)} {m} "
                     f"{f.cli('no_ceiling_note')}"])
    if "sigma_z" in r:
        sz = r["sigma_z"]
        at = (f.num(sz.fields["at"], 0) if sz.fields.get("over_relief")
              else f.short(sz.fields["at"]))
        rows.append([f"  {f.cli('sigma_z')}",
                     f"{f.fixed(sz.value, 3)} {m} {f.cli('at_height_word')} "
                     f"{at} {m} ({f.cli('required')} "
                     f"{f.short(sz.fields['required'])} {m} {f.cli('rms')})"])
    if "recognition" in r:
        rec = r["recognition"]
        name = (rec.fields["name_ru"] or rec.fields["name"]) if f.locale == "ru" \
            else rec.fields["name"]
        rows.append([f"  {f.cli('recognition_map_object')}",
                     f"{f.fixed(rec.value, 2)} ({name}, {f.short(rec.fields['size_m'])} {m})"])
    return rows


def _at_highest(r: dict[str, Row], f: Formatter) -> str:
    """Over relief: the GSD and L at the highest height flown above the ground."""
    gsd, lr = r["gsd_m"].fields.get("at_max"), r["ground_resolution_m"].fields.get("at_max")
    if gsd is None:
        return ""
    m = f.cli("m")
    return (f"; {f.cli('at_highest')} {f.fixed(gsd, 3)} {m} / "
            f"{'—' if lr is None else f.fixed(lr, 3)} {m}")


def _plans_lines(tables: ResultTables, f: Formatter, choice: Any) -> list[str]:
    """The plans compared (the ``plans`` table, words of :mod:`..planwords`): why the plan
    was chosen, then one aligned row each, the recommended one marked ``>``, and under it
    whether it meets every constraint or what it misses."""
    if not tables.has("plans") or not tables["plans"].rows:
        return []
    from ..planwords import plan_cells, plan_head

    rows = tables["plans"].rows
    head = plan_head(f, terminal=True)[:-1]
    cells = [plan_cells(r, f) for r in rows]
    marks = [">" if "recommended" in r.flags else " " for r in rows]
    body = table([["", *head], *[[mk, *c[:-1]] for mk, c in zip(marks, cells, strict=True)]],
                 align="ll" + "r" * (len(head) - 1)).split("\n")
    out = ["", f("plans_intro")]
    if choice is not None:
        out.append(wrap(f.text(choice), "  "))
    out.append("  " + body[0])
    for line, c in zip(body[1:], cells, strict=True):
        out.append("  " + line)
        out.append(textwrap.fill(c[-1], width=96, initial_indent="      ",
                                 subsequent_indent="        "))
    return out


def _uav_flight_rows(r: dict[str, Row], f: Formatter) -> list[list[str]]:
    """The overlaps, the photo interval, the photos, the flight, the volume, the blur."""
    m, s = f.cli("m"), f.cli("s")
    interval = r["photo_interval"].value
    rows = [[f"  {f.cli('overlaps_base_spacing')}",
             f"{f.short(r['forward_overlap_pct'].value)} % / "
             f"{f.short(r['side_overlap_pct'].value)} % "
             f"— {f.fixed(r['base'].value, 1)} {m} / {f.fixed(r['line_spacing'].value, 1)} {m}"],
            [f"  {f.cli('interval')}",
             f"{f.fixed(interval, 2)} {s}" if math.isfinite(interval)
             else f.cli("interval_none")]]
    if "photos" in r:
        rows.append([f"  {f.cli('photos_strips')}",  # grouped as the flight-lines line
                     f"{f.num(r['photos'].value, 0)} / {f.num(r['strips'].value, 0)}"])
        minutes = r["flight_time_min"].value
        rows.append([f"  {f.cli('flight')}",
                     f"{f.fixed(r['flight_length_km'].value, 1)} {f.cli('km')}"
                     + (f", {f.fixed(minutes, 0)} {f.cli('min')}" if minutes else "")])
        if "data_volume_gb" in r:
            rows.append([f"  {f.cli('volume')}", volume_text(
                r["data_volume_gb"], r["data_volume_jpeg_gb"], f)])
    rows.append([f"  {f.cli('motion_blur_limit')}",
                 f"{f.cli('exposure')} ≤ 1/{math.ceil(1 / r['max_exposure_s'].value):d} "
                 f"{s} {f.cli('or_speed')} ≤ {f.fixed(r['max_speed_ms'].value, 1)} "
                 f"{f.cli('ms')}"])
    return rows


class PlanPart(NamedTuple):
    """One part of the terminal summary of ``scanplan plan``: ``lines(result, tables, f)``
    gives its lines (none: the result has not got it), from the result's tables and the
    terminal's formatter."""

    name: str
    lines: Callable[[Any, ResultTables, Formatter], list[str]]


#: The parts of the terminal summary, in order.
PLAN_PARTS: tuple[PlanPart, ...] = (
    PlanPart("heading", lambda r, t, f: _plan_heading(r, f)),
    PlanPart("terrain", lambda r, t, f: [wrap(x, "") for x in format_terrain(r, f.locale)]),
    PlanPart("film", lambda r, t, f: _film_summary(t["spec_film"], f) if r.film else []),
    PlanPart("uav", lambda r, t, f: _uav_summary(t["spec_uav"], _platform(t), f)
             if r.uav else []),
    PlanPart("plans", lambda r, t, f: _plans_lines(t, f, getattr(r.uav, "choice", None))
             if r.uav else []),
    PlanPart("comparison", lambda r, t, f: _comparison_lines(r, f, t) if r.comparison
             else []),
    PlanPart("control", lambda r, t, f: _control_lines(t, f)
             if getattr(r, "control", None) is not None else []),
    PlanPart("design", lambda r, t, f: _design_lines(t, f)),
    PlanPart("warnings", lambda r, t, f: _warning_lines(r, f, t) if r.warnings else []),
)


_BATCH_HEADER = ["project", "map", "film: photo scale", "scan µm", "digital camera: height m",
                 "max m", "binding"]


def batch_row(path: str, r: Any) -> list[str]:
    """The row of one project in :func:`batch_table` (text only: a batch keeps these, not
    the projects' results)."""
    f = formatter("en")
    fs, u = r.film, r.uav
    rec = fs.recommended if fs else None
    uav_binding = ""
    if u:
        head = {row.key: row.value for row in ResultTables(spec=r)["spec_uav"].rows}
        uav_binding = head.get("binding") or ""
    return [
        os.path.basename(path), f"1:{r.project.map.scale}",
        (f"1:{scale_value(rec.photo_scale)}" if rec else "none") if fs else "—",
        (f.um(rec.scanner_pixel_um or rec.scan_pixel_um) if rec else "—") if fs else "—",
        f.fixed(u.recommended_height_m, 0) if u else "—",
        f.fixed(u.max_height_m, 0) if u else "—",
        " / ".join(x for x in ((rec.binding if rec else "") if fs else "",
                               uav_binding) if x) or "—"]


def batch_table(rows: list[list[str]], failed: list[tuple[str, str]]) -> str:
    """One table for a batch of projects: the rows of :func:`batch_row`, then the
    failures."""
    out = table([_BATCH_HEADER, *rows], align="llrrrrl")
    if failed:
        out += f"\n{len(rows)} planned, {len(failed)} failed:"
        for path, msg in failed:
            out += "\n" + wrap(f"{os.path.basename(path)}: {msg}", "  ! ")
    return out


def batch_summary(done: list[tuple[str, Any]], failed: list[tuple[str, str]]) -> str:
    """One table for a batch of projects: the headline of each, then the failures."""
    return batch_table([batch_row(path, r) for path, r in done], failed)


def project_warnings(path: str, r: Any) -> str:
    """The warnings of one project of a batch under its file name ("" if none)."""
    if not r.warnings:
        return ""
    out = ["", f"Warnings — {os.path.basename(path)}:"]
    for w in r.warnings:
        mark = "!" if w.severity == "warning" else "i"
        out.append(wrap(w.text(r.meta.locale) + code_tag(w.code, r.meta.locale),
                        f"  {mark} "))
    return "\n".join(out)


def batch_warnings(done: list[tuple[str, Any]]) -> str:
    """The warnings of each project of a batch, under its file name ("" if none)."""
    return "\n".join(t for t in (project_warnings(p, r) for p, r in done) if t)
