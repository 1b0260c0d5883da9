"""The PDF's sections as plain strings and flags the templates lay out.

Each ``_*_view`` turns one part of a :class:`scanplan.reports.view.ReportView` (the
specification, the film scan, the UAV flight, the comparison) into the dictionary its
template (``templates/_spec.html``, ``_scan.html``, ``_uav.html``, ``_comparison.html``)
shows; words and numbers come from the document's formatter
(:class:`~.formatter.Formatter`: one per locale, works cited by this document's reference
numbers).
"""

from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any

from ..i18n.labels import LABELS
from ..i18n.messages import localize
from ..norms import NormSet
from ..norms.schema import DIGITAL_ONLY_PARAMETERS
from ..project.jobs import ScanJob, UavJob
from .formatter import Formatter
from .plots import view_plot_uri
from .view import ReportView, warning_heading_key
from .views import ResultTables, Row, Table
from .wording import (
    object_status,
    param_name,
    param_value,
    sentence,
    with_status,
)

if TYPE_CHECKING:
    from ..project.spec import PlanResult

_MAX_COLUMNS = 6  # photo scales per result table on A4 portrait

_UAV_FORMULAS = (  # formula, meaning (label), source (label)
    ("GSD = p·H/f", "formula_gsd", "source_gsd"),
    ("L = H/(2·R·f), K(R) = K_thr(R)", "formula_l", "source_l"),
    ("P = exp(−(B·L/L_obj)²)", "formula_p", "source_p"),
    ("L ≤ L_obj·sqrt(−ln P)/B", "formula_pd", "source_pd"),
    ("H_max = H·(1 + Δ_H)", "formula_tol", "source_tol"),
)


# ---------------------------------------------------------------------------------------
# Formatting
# ---------------------------------------------------------------------------------------


def _after_heading(message: str, heading: str) -> str:
    """A warning's sentence after its bold heading (``Motion blur.``) reads as a sentence:
    capitalised, with a full stop."""
    return sentence(message) if heading else message


def _warnings(ws: Table, f: Formatter, ns: NormSet | None = None) -> list[dict[str, Any]]:
    """A section's warnings table as the templates show it: heading, scales, sentence."""
    out = []
    for r in ws.rows:
        message, scales = r.values
        key = warning_heading_key(r.key)
        heading = f(key) if key else ""
        scale_list = [f.scale(x) for x in scales]
        out.append({"code": r.key, "severity": r.fields["severity"], "heading": heading,
                    "scales": f.list_sep.join(scale_list), "scale_list": scale_list,
                    "message": _after_heading(f.message(message, ns),
                                              heading)})
    return out


# ---------------------------------------------------------------------------------------
# View models: plain strings and flags the templates lay out
# ---------------------------------------------------------------------------------------


def _norm_view(ns: NormSet, f: Formatter) -> dict[str, Any]:
    title = ns.title_ru if f.locale == "ru" and ns.title_ru else ns.title
    cited = f.cite(ns.source)
    numbers = re.findall(r"\[\d+\]", cited)
    # a source naming known works is shown by their numbers (its prose is the bibliography's)
    source = "; ".join(dict.fromkeys(numbers)) if numbers else ns.source
    return {"name": ns.name, "title": title, "source": source,
            "imported_from": ns.imported_from, "imported_at": ns.imported_at}


def _film_inputs(tbl: Table, ns: NormSet, f: Formatter) -> list[tuple[str, str]]:
    """The film section's inputs (the ``film_inputs`` table), each number in its shortest
    form: scales, camera, frame, object, height formula, scanner, bands."""
    r = {row.key: row for row in tbl.rows}
    inputs: list[tuple[str, str]] = [
        (f("map_scale"), f.scale(r["map_scale"].value)),
        (f("relief_interval_m"), f.g(r["relief_interval_m"].value)),
        (f("photo_scale"), f.list_sep.join(f.scale(x) for x in r["photo_scales"].value)),
    ]
    camera = r["camera"]
    if camera.value or camera.fields["name"]:
        inputs.append((f("camera"), f.camera(ns, camera.value, camera.fields["name"])))
    width, along = r["frame_mm"].value
    inputs += [
        (f("focal_mm"), f.g(r["focal_mm"].value)),
        (f("frame_mm"), f"{f.g(width)} × {f.g(along)}"),
        (f("resolving_power_lpmm"), f.g(r["resolving_power_lpmm"].value)),
        (f("forward_overlap_pct"), f.g(r["forward_overlap_pct"].value)),
    ]
    obj = r["object"].value
    if obj is not None:
        inputs += [
            (f("object"), f"{f.object(obj)}: "
                                f"{f.g(r['object_size_m'].value)} {f('m')}, "
                                f"{f.shape(ns, r['shape'].value)}, "
                                f"B = {f.g(r['shape_coefficient'].value)}"),
            (f("probability"), f.g(r["probability"].value)),
            (f("norm_rows"), with_status(f.cite(localize(r["object_source"].value,
                                                               f.locale)),
                                               object_status(ns, obj), f.locale)),
        ]
    formula = r["height_formula"]
    if formula.fields["used"]:
        key = f"film_height_formula_{formula.value}"
        inputs.append((f("height_formula"),
                       f(key) if key in LABELS["en"] else formula.value))
    if r["scanner"].value:
        steps = r["scanner_steps_um"].value if "scanner_steps_um" in r else ()
        inputs.append((f("scanner"), f"{f.scanner(ns, r['scanner'].value)}"
                       " (" + f.list_sep.join(f.g(x) for x in steps) + f" {f('um')})"))
    inputs.append((f("bands_bits"), f"{r['bands'].value} × {r['bits_per_band'].value}"))
    inputs.append((f("norm_set"), _norm_view(ns, f)["title"]))
    return inputs


def _scan_view(job: ScanJob, view: ReportView, f: Formatter) -> dict[str, Any]:
    """The film section: its inputs, the constraints × photo scales tables, why each scale's
    constraint binds, the interpretation limit, the smallest photo scale each scan pixel
    supports, the formulas, the norm set's parameters, the warnings, the chart."""
    ns = job.norm_set
    inputs = _film_inputs(view.tables["film_inputs"], ns, f)
    obj = view.tables["film_inputs"].row("object").value
    obj_name = f.object(obj) if obj is not None else ""

    # at most _MAX_COLUMNS photo scales per table, so a wide plan stays inside A4
    film = view.tables["film_constraints"]
    n_tables = math.ceil(len(film.columns) / _MAX_COLUMNS)
    size = math.ceil(len(film.columns) / n_tables)
    tables = [_scan_table(film, slice(i, i + size), f)
              for i in range(0, len(film.columns), size)]

    explanations = [f.message(r.value, ns) for r in view.tables["film_explanations"].rows]

    reach_table = view.tables["film_reach"]
    lim = reach_table.row("interpretation_limit")
    mci = lim.value
    limit = ""
    if mci is not None and obj is not None:
        limit = f("interpretation_limit_sentence", object=obj_name,
                  p=f.g(lim.fields["probability"]), scale=f.floor_scale(mci),
                  ratio=f.num(lim.fields["ratio"], 1), r=f.g(lim.fields["resolving_power"]))
    reach = [{"pixel": f.g(pixel),
              "scale": f.floor_scale(largest) if largest is not None else f("none"),
              "limit": f.cname(limiting),
              "interpretable": f.floor_scale(interpretable) if interpretable
              else f("none")}
             for r in reach_table.rows if r.key == "reach"
             for pixel, largest, limiting, interpretable in [r.values]]
    formulas = [{"id": r.key, "name": f.constraint(r.key),
                 "equation": f.cite(f.text(r.values[0])), "protects": f.text(r.values[1])}
                for r in view.tables["film_formulas"].rows]
    params = [{"name": param_name(ns, k, f.locale),
               "value": param_value(ns, k, v, f.locale, f.g),
               "source": with_status(f.cite(ns.parameter_sources.get(k, "")),
                                     ns.parameter_status.get(k, ""), f.locale)}
              for k, v in ns.parameters.items() if k not in DIGITAL_ONLY_PARAMETERS]
    return {
        "inputs": inputs, "tables": tables,
        "explanations": explanations, "interpretation_limit": limit, "reach": reach,
        "reach_interpretable": obj is not None and mci is not None,
        "warnings": _warnings(view.tables["film_warnings"], f, ns), "formulas": formulas,
        "params": params, "norm": _norm_view(ns, f),
        "plot": view_plot_uri(view, "constraints"),
    }


def _scan_table(film: Table, part: slice, f: Formatter) -> dict[str, Any]:
    """The film table (:func:`scanplan.reports.views.film_constraints`) for some of its
    photo scales: the constraints (binding flagged, others with their margin), then the
    summary rows."""
    header = [f.scale(c.value) for c in film.columns[part]]
    rows: list[dict[str, Any]] = []
    summary: list[dict[str, Any]] = []
    for r in film.rows:
        unit = f.unit(r.unit)
        values = r.values[part]
        texts = [f.value(r, v) for v in values]
        label = f.row_label(r)
        if "summary" in r.flags:
            summary.append({"label": label, "unit": unit, "cells": texts,
                            "strong": "emph" in r.flags})
            continue
        first = part.start or 0
        binding = [r.flagged(first + i, "binding") for i in range(len(values))]
        margins = r.margins[part] if r.margins else (None,) * len(values)
        rows.append({"label": label, "unit": unit,
                     "kind": "constraint" if "constraint" in r.flags else "ratio",
                     "cells": [{"text": text, "binding": b,
                                "margin": "" if b or m is None else _margin(f, m)}
                               for text, b, m in zip(texts, binding, margins, strict=True)]})
    return {"header": header, "rows": rows, "summary": summary}


def _uav_inputs(tables: ResultTables, ns: NormSet, f: Formatter) -> list[tuple[str, str]]:
    """The UAV section's inputs (the ``uav_inputs`` table), each number in its shortest
    form, a measured size to 4 significant digits: camera, heights, speed, overlaps,
    scene, map."""
    r = {row.key: row for row in tables["uav_inputs"].rows}
    v = {key: row.value for key, row in r.items()}
    m = f("m")
    inputs: list[tuple[str, str]] = []
    if v["camera"] is not None:
        inputs.append((f("camera"), f.show(v["camera"])))
    low, high = v["heights"]
    planned = r["heights"].fields["planned"]
    inputs += [
        (f("pixel_pitch_um"), f.sig(v["pixel_um"])),
        (f("focal_mm"), f.g(v["focal_mm"])),
        (f("f_number"), f.g(v["f_number"])),
        (f("sensor_mm"), " × ".join(f.value(r[k], r[k].value)  # the sides alike
                                    for k in ("sensor_width_mm", "sensor_height_mm"))),
        (f("orientation"), f(f"orientation_{v['orientation']}")),
        (f("height_m"), f.g(planned)),
    ]
    if high != low or low != planned:
        relief = r["heights"].fields.get("over_relief")
        hf = f.height if relief else f.g  # over relief: the heights as flown
        inputs.append((f("flown_heights_relief" if relief else "flown_heights"),
                       f"{hf(low)} – {hf(high)}"))
    if v["ceiling_m"] is not None:
        inputs.append((f("ceiling_m"), f.g(v["ceiling_m"])))
    if v["gsd_target_cm"] is not None:
        inputs.append((f("gsd_target_cm"), f.g(v["gsd_target_cm"])))
    inputs += [
        (f("ground_speed_ms"), f.g(v["speed_ms"])),
        (f("exposure_s"), f.g(v["exposure_s"])),
        (f("overlaps"), f"{f.g(v['forward_overlap_pct'])} / {f.g(v['side_overlap_pct'])}"),
        (f("scene"), f"{f.g(v['r_max'])} / {f.g(v['r_min'])}"),
        (f("threshold_k0"), f.g(v["threshold_k0"])),
    ]
    if v["map_scale"] is not None:
        inputs += [(f("map_scale"), f.scale(v["map_scale"])),
                   (f("relief_interval_m"), f.g(v["relief_interval_m"]))]
        if v["object"] is not None:
            text = (f"{f.object(v['object'])}: {f.g(v['object_size_m'])} {m}, "
                    f"{f.show(v['shape'])}, B = {f.g(v['shape_coefficient'])}")
            inputs.append((f("object"), with_status(text, v["object_status"], f.locale)))
    inputs.append((f("norm_set"), _norm_view(ns, f)["title"]))
    return inputs


def _uav_results(view: ReportView, f: Formatter
                 ) -> tuple[list[str], list[dict[str, Any]], str]:
    """The result table's columns (the planned and the highest flown height), its rows
    and the motion-blur sentence."""
    table = view.tables["uav_results"]
    cols = [f("at_height", h=f.g(c.value)) for c in table.columns]
    results = [{"label": f.row_label(r),
                "cells": [f.value(r, v) for v in r.values]
                + [""] * (len(cols) - len(r.values))}
               for r in table.rows]
    exposure = view.tables["uav_figures"].row("max_exposure_s")
    speed = view.tables["uav_figures"].row("max_speed_ms").value
    blur = f("blur_limit", blur=f.g(exposure.fields["blur_px"]),
             exposure=f"1/{math.ceil(1 / exposure.value):d}", speed=f.num(speed, 1))
    return cols, results, blur


def _uav_flight(flight: Table, f: Formatter) -> list[tuple[str, str]]:
    """The flight geometry at the planned height (the ``uav_flight`` table)."""
    v = {r.key: r.value for r in flight.rows}
    trigger, overlap = (next(r.fields for r in flight.rows if r.key == key)
                        for key in ("photo_interval", "overlap_range"))
    rows = [
        (f("footprint"), f"{f.num(v['footprint'][0], 0)} × "
                         f"{f.num(v['footprint'][1], 0)}"),
        (f("base_m"), f.num(v["base"], 1)),
        (f("line_spacing_m"), f.num(v["line_spacing"], 1)),
        (f("photo_interval_s"), f.num(v["photo_interval"], 2)
         + (f" ({f('trigger_min')} {f.g(trigger['min_trigger'])})"
            if trigger else "")),
        (f("overlap_at", lo=f.g(overlap["lo"]), hi=f.g(overlap["hi"])),
         f"{f.num(v['overlap_range'][0], 1)} / {f.num(v['overlap_range'][1], 1)}"),
    ]
    if "strips" in v:  # counts grouped as page 1 and the flight-lines table give them
        rows.append((f("strips_times_photos"), " × ".join(f.num(x, 0) for x in v["strips"][:2])
                     + f" = {f.num(v['strips'][2], 0)}"))
    elif "strips_photos" in v:  # a polygon: the strips differ in length
        rows.append((f("strips_photos"),
                     " / ".join(f.num(x, 0) for x in v["strips_photos"])))
    if "flight_length_km" in v:
        minutes = v["flight_time_min"]
        rows.append((f("flight_length"), f"{f.num(v['flight_length_km'], 1)} / "
                     + (f.num(minutes, 0) if minutes is not None else "—")))
    if "data_volume_gb" in v:
        rows.append((f("data_volume_gb"), f.num(v["data_volume_gb"], 1)))
        rows.append((f("data_volume_jpeg_gb"), f.num(v["data_volume_jpeg_gb"], 1)))
    return rows


def _uav_limits(view: ReportView, f: Formatter) -> dict[str, Any]:
    """The constraints as maximum heights (the ``uav_limits`` table), the sentence on the
    binding one, the height accuracy forms (``uav_accuracy``) and the formulas."""
    limit_rows = view.tables["uav_limits"].rows
    limits = [{"id": r.key, "name": f.constraint(r.key),
               "limit": f.num(limit, 3 if limit < 10 else 0),
               "compares": f.compared(compares), "max_height": f.num(top, 0),
               "max_flown": f.num(flown, 0),
               "margin": "" if margin is None else _margin(f, margin),
               "binding": "binding" in r.flags}
              for r in limit_rows
              for limit, compares, top, flown, margin in [r.values]]
    v = {row.key: row.value for row in view.tables["uav_inputs"].rows}
    fig = {row.key: row.value for row in view.tables["uav_figures"].rows}
    limits_title = ""
    max_sentence = ""
    if limit_rows and v["map_scale"] is not None:
        tol = v["height_tolerance_up_pct"]
        limits_title = f("limits_title", scale=f.scale(v["map_scale"]),
                         hc=f.g(v["relief_interval_m"])) + (
            f("tol_note", tol=f.g(tol)) if tol else "")
        b = next(r for r in limit_rows if "binding" in r.flags)
        max_sentence = f("max_height_sentence", h=f.num(fig.get("max_height_m"), 0),
                         cid=b.key, name=f.constraint(b.key),
                         reason=f.cite(f.text(b.fields["reason"])))
    height_forms = ""
    acc = {row.key: row for row in view.tables["uav_accuracy"].rows}
    if acc:
        m = f("m")
        sz = acc["sigma_z_m"]
        at = sz.fields["at"]
        height_forms = f("height_forms_sentence", sigma=f.num(sz.value, 3),
                         h=f.height(at) if sz.fields.get("over_relief") else f.g(at),
                         vz=f.g(acc["height_accuracy_m"].value),
                         forms="; ".join(
            f"{f('hf_' + k)}: {f.num(acc['form_' + k].value, 0)} {m}"
            + (f" ({f('hf_used')})" if "used" in acc["form_" + k].flags else "")
            for k in ("normal_case", "instruction", "parallax")))
    formulas = [{"equation": eq, "meaning": f(key), "source": f.cite(f(src))}
                for eq, key, src in _UAV_FORMULAS
                if limit_rows or key not in ("formula_pd", "formula_tol")]
    limit_formulas = [{"id": r.key, "name": f.constraint(r.key),
                       "equation": f.cite(f.text(r.fields["equation"]))}
                      for r in sorted(limit_rows, key=lambda r: r.fields["rank"])]
    return {"limits": limits, "limits_title": limits_title, "max_sentence": max_sentence,
            "height_forms": height_forms, "formulas": formulas,
            "limit_formulas": limit_formulas}


def _uav_view(job: UavJob, view: ReportView, f: Formatter) -> dict[str, Any]:
    """The digital-camera section: inputs, results, flight, recognition, the constraints
    as heights, warnings, the charts."""
    ns = job.norm_set
    cols, results, blur = _uav_results(view, f)
    recognition_table = view.tables["uav_recognition"]
    recognition = [{
        "object": f.object_named(ns, r.fields["name"], size, scale),
        "map": f.scale(scale) if scale else "—", "size": f.g(size),
        "shape": f.shape(ns, shape), "p": f.num(p, 2),
        "p_max": f.num(p_max, 2), "p_corner": f.num(p_corner, 2)}
        for r in recognition_table.rows
        for scale, size, shape, p, p_max, p_corner in [r.values]]
    planned, highest = (c.value for c in recognition_table.columns[3:5])
    return {
        "inputs": _uav_inputs(view.tables, ns, f), "cols": cols, "results": results,
        "blur": blur, "flight": _uav_flight(view.tables["uav_flight"], f),
        "recognition": recognition, "recognition_cols": [
            f("at_height", h=f.g(planned)), f("at_height", h=f.g(highest)),
            f("corner_at", h=f.g(highest))],
        **_uav_limits(view, f),
        "warnings": _warnings(view.tables["uav_warnings"], f, ns),
        "norm": _norm_view(ns, f),
        "plot_mtf": view_plot_uri(view, "mtf"),
        "plot_height": view_plot_uri(view, "height"),
        "not_resolvable": not view.tables["uav_figures"].row("resolvable").value,
    }


def _comparison_view(view: ReportView, f: Formatter) -> dict[str, Any]:
    """Film and digital camera side by side, without a specification (``scan`` and
    ``uav`` in one report): the map scales, the binding constraints, the results, the
    warnings."""
    t = view.tables
    film = t["film_constraints"]
    scales = [c.value for c in film.columns]
    pixels, bindings = film.row("scan_pixel_um").values, film.row("binding").values
    fig = {row.key: row.value for row in t["uav_figures"].rows}
    uav_scale = t["uav_inputs"].row("map_scale").value
    um, m = f("um"), f("m")
    film_result = "; ".join(f"{f.scale(sc)}: {f.num(px, 1)} {um} ({b})"
                            for sc, px, b in zip(scales, pixels, bindings, strict=True))
    binding = fig.get("binding")
    uav_result = (f"{f('max_height_m').split(',')[0]}: {f.num(fig['max_height_m'], 0)} {m}"
                  f" ({binding}); " if fig.get("max_height_m") is not None else "") + (
        f"GSD {f.num(fig['gsd_m'], 3)} {m}, L {f.num(fig['ground_resolution_m'], 3)} {m} "
        f"({f('at_height', h=f.g(fig['height_m']))})")
    film_binding = ", ".join(dict.fromkeys(f"{b} — {f.constraint(b)}" for b in bindings))
    return {"rows": [
        (f("map_scale"), f.scale(t["film_inputs"].row("map_scale").value),
         f.scale(uav_scale) if uav_scale is not None else "—"),
        (f("binding"), film_binding, f"{binding} — {f.constraint(binding)}" if binding
         else "—"),
        (f("result"), film_result, uav_result),
        (f("warnings"), str(len(t["film_warnings"].rows)), str(len(t["uav_warnings"].rows))),
    ]}


def _film_relief_rows(tbl: Table, f: Formatter) -> list[tuple[str, str]]:
    """``[terrain]``: the frame the film specification holds at, and the flat-ground scan
    pixel beside it (issue 12)."""
    keys = tbl.keys()
    if "relief_mc_max" not in keys:
        return []
    mc = tbl.row("relief_mc_max")
    where = (f"{f('terrain_film_frame')}: {mc.fields['frame']} ({mc.fields['strip']})"
             if mc.fields["ground_known"] else f("terrain_film_frame_range",
                                                       low=f.g(mc.fields["ground_low_m"])))
    flat = tbl.row("relief_flat_pixel")
    rows = [(f("terrain_film_mc_max"), f"{f.scale(mc.value)}; {where}"),
            (f("terrain_film_flat_pixel"),
             f"{f.num(flat.value, flat.digits)} ({flat.fields['binding']})")]
    if "relief_rejected" in keys:
        rows.append((f("terrain_film_rejected"), "; ".join(
            f("terrain_film_rejected_value", scale=f.scale(scale), local=f.scale(local))
            for scale, local in tbl.row("relief_rejected").values)))
    return rows


def _reason_text(r: Row, f: Formatter) -> str:
    return sentence(f.message(r.value, r.details[0]["norm_set"]))


def _spec_film_rows(tbl: Table, f: Formatter) -> list[tuple[str, str]]:
    """The film's headline (the ``spec_film`` table): the scale, the scan pixel (and the
    scanner's step after an arrow), the binding constraint, the relief, the probability,
    the frames."""
    if tbl.keys() == ["reason"]:
        return []
    r = {row.key: row for row in tbl.rows}
    rows = [(f("spec_archive_photo_scale" if "archive" in r["photo_scale"].flags
                     else "spec_recommended_photo_scale"), f.scale(r["photo_scale"].value))]
    px, px_label = f.num(r["scan_pixel_um"].value, 1), "scan_pixel_um"
    if "scanner_pixel_um" in r:  # "12.5 → 7.0" says what the arrow means
        px += f" → {f.num(r['scanner_pixel_um'].value, 1)}"
        px_label = "spec_scan_pixel_to_step_um"
    rows.append((f(px_label), px))
    binding = r["binding"].value
    rows.append((f("binding"), f"{binding} — {f.constraint(binding)}"))
    rows += _film_relief_rows(tbl, f)
    prob = r["probability"]
    rows.append((f("terrain_film_probability" if "over_relief" in prob.flags
                         else "probability"), f.num(prob.value, prob.digits)))
    if "frames" in r:
        rows.append((f("spec_frames"), f.g(r["frames"].value)))
        rows.append((f("spec_scanned_gb"), f.num(r["scanned_gb"].value, 1)))
    return rows


def _spec_uav_rows(tbl: Table, f: Formatter) -> list[tuple[str, str]]:
    """The digital camera's headline (the ``spec_uav`` table): the heights, the binding
    constraint and the contract's deliverables (the GSD and the overlaps the crew flies,
    the photos, the data volume)."""
    r = {row.key: row for row in tbl.rows}
    rows: list[tuple[str, str]] = []
    if "planned_height_m" in r:
        rows.append((f("spec_planned_height_m"), f.num(r["planned_height_m"].value, 0)))
    rows.append((f("spec_recommended_height_m"),
                 f.num(r["recommended_height_m"].value, 0)))
    rows.append((f("spec_max_height_flat_m" if "flat" in r["max_height_m"].flags
                         else "max_height_m"), f.num(r["max_height_m"].value, 0)))
    if "max_height_relief_m" in r:
        rows.append((f("spec_max_height_relief_m"),
                     f.num(r["max_height_relief_m"].value, 0)))
    if "binding" in r:
        binding = r["binding"].value
        rows.append((f("binding"), f"{binding} — {f.constraint(binding)}"))
    rows.append((f("gsd_recommended_cm"), f.num(r["gsd_cm"].value, 2)))
    rows.append((f("overlaps"), f(
        "overlaps_value", fwd=f.num(r["forward_overlap_pct"].value, 0),
        side=f.num(r["side_overlap_pct"].value, 0))))
    if "photos" in r:
        rows.append((f("spec_photos"), f.g(r["photos"].value)))
    for key in ("data_volume_gb", "data_volume_jpeg_gb"):
        if key in r:
            rows.append((f(key), f.num(r[key].value, 1)))
    return rows


def _spec_view(spec: PlanResult, view: ReportView, f: Formatter) -> dict[str, Any]:
    """The specification of ``scanplan plan``: what was chosen, with its reason (the
    ``spec_film`` and ``spec_uav`` tables), and the comparison."""
    rows: list[tuple[str, str]] = []
    reasons: list[str] = []
    for name, lay_out in (("spec_film", _spec_film_rows), ("spec_uav", _spec_uav_rows)):
        if view.tables.has(name):
            tbl = view.tables[name]
            rows += lay_out(tbl, f)
            reasons.append(_reason_text(tbl.row("reason"), f))
    comparison = [(f.row_label(r),
                   *(f.value(r, x) for x in r.values),
                   f.unit(r.unit))
                  for r in view.tables["comparison"].rows]
    return {"rows": rows, "reasons": reasons, "comparison": comparison}


def _design_view(view: ReportView, f: Formatter) -> dict[str, Any] | None:
    """The survey design (the ``design`` and ``design_notes`` tables): each quantity, its
    value and the norm it meets (cited); the design's notes in full."""
    if not view.tables.has("design"):
        return None
    rows = [(f.row_label(r), f.show(r.values[0]), f.show(r.values[1]) if r.values[1] else "")
            for r in view.tables["design"].rows]
    notes = [sentence(f.show(r.value)) for r in view.tables["design_notes"].rows]
    return {"rows": rows, "notes": notes}


def _margin(f: Formatter, pct: float) -> str:
    """A constraint's margin to the binding one, signed with a real minus (``+7 %``,
    ``−21 %`` for a constraint set aside below the binding one; never ``+-21 %``)."""
    return f"{'+' if pct >= 0 else '−'}{f.num(abs(pct), 0)} %"

