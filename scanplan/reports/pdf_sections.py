"""The PDF's sections as plain strings and flags the templates lay out.

Each ``_*_view`` turns one part of a :class:`scanplan.reports.view.ReportView` (the
specification, the film scan, the UAV flight, the comparison) into the dictionary its
template (``templates/_spec.html``, ``_scan.html``, ``_uav.html``, ``_comparison.html``)
shows; numbers and labels come from the view (one formatter and one catalogue per
locale), works are cited by this document's reference numbers (:class:`_Fmt`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..core.flight import MAX_BLUR_PX
from ..i18n.labels import LABELS
from ..i18n.messages import localize
from ..norms import NormSet
from ..norms.schema import DIGITAL_ONLY_PARAMETERS
from ..project.jobs import ScanJob, UavJob
from ..rules.film import CONSTRAINTS, ScanPlan
from ..rules.uav import UavPlan
from .plots import view_plot_uri
from .references import Bibliography
from .tablewords import row_label, row_unit, row_value
from .view import ReportView, warning_heading_key
from .views import Row, Table
from .wording import (
    camera_title,
    display_message,
    name_title,
    object_status,
    object_title,
    param_name,
    param_value,
    scanner_title,
    sentence,
    shape_title,
    with_status,
)

if TYPE_CHECKING:
    from ..project.spec import PlanResult

_MAX_COLUMNS = 6  # photo scales per result table on A4 portrait

_UAV_FORMULAS = (  # formula, meaning (label), source (label)
    ("GSD = p·H/f", "pdf_f_gsd", "pdf_src_gsd"),
    ("L = H/(2·R·f), K(R) = K_thr(R)", "pdf_f_l", "pdf_src_l"),
    ("P = exp(−(B·L/L_obj)²)", "pdf_f_p", "pdf_src_p"),
    ("L ≤ L_obj·sqrt(−ln P)/B", "pdf_f_pd", "pdf_src_pd"),
    ("H_max = H·(1 + Δ_H)", "pdf_f_tol", "pdf_src_tol"),
)


# ---------------------------------------------------------------------------------------
# Formatting
# ---------------------------------------------------------------------------------------


@dataclass(frozen=True)
class _Fmt:
    """The view's labels and numbers plus this document's bibliography (its reference
    numbers follow the order the PDF cites the works in)."""

    view: ReportView
    bib: Bibliography

    @property
    def locale(self) -> str:
        return self.view.locale

    @property
    def list_sep(self) -> str:
        """Between the items of a list of scales: ``"; "`` in Russian, where the comma is
        the decimal separator (as the messages join lists), ``", "`` in English."""
        return "; " if self.locale == "ru" else ", "

    def cite(self, text: str) -> str:
        """``text`` with the works it names replaced by reference numbers."""
        return self.bib.cite(text)

    def label(self, key: str, **kw: Any) -> str:
        return self.view.labels(key, **kw)

    def num(self, x: float | None, digits: int = 1) -> str:
        return self.view.numbers.num(x, digits)

    def g(self, x: float | None) -> str:
        """Shortest form (like ``:g``) with the locale's decimal separator."""
        return self.view.numbers.g(x)

    def scale(self, x: float) -> str:
        return self.view.numbers.scale(x)

    def floor_scale(self, x: float) -> str:
        return self.view.numbers.floor_scale(x)

    def cname(self, cid: str) -> str:
        return self.view.labels.constraint(cid)


def _object_name(ns: NormSet, name: str, size_m: float, map_scale: int | None,
                 locale: str) -> str:
    """A norm-table object's name in the report's language (unnamed: "object of the given
    size")."""
    from ..project.jobs import USER_OBJECT_NAME

    if map_scale is None and name == USER_OBJECT_NAME["en"]:  # a project's unnamed object
        return name_title("", "", locale)
    for o in ns.objects:
        if o.name == name and o.size_m == size_m and (map_scale is None
                                                      or o.map_scale == map_scale):
            return object_title(o, locale)
    return name_title(name, "", locale)


def _shape_name(ns: NormSet, shape: str, locale: str) -> str:
    """The shape in words in the report's language."""
    return shape_title(ns, shape, locale)


def _after_heading(message: str, heading: str) -> str:
    """A warning's sentence after its bold heading (``Motion blur.``) reads as a sentence:
    capitalised, with a full stop."""
    return sentence(message) if heading else message


def _warnings(ws: Table, f: _Fmt, ns: NormSet | None = None) -> list[dict[str, Any]]:
    """A section's warnings table as the templates show it: heading, scales, sentence."""
    out = []
    for r in ws.rows:
        message, scales = r.values
        key = warning_heading_key(r.key)
        heading = f.label(key) if key else ""
        scale_list = [f.scale(x) for x in scales]
        out.append({"code": r.key, "severity": r.fields["severity"], "heading": heading,
                    "scales": f.list_sep.join(scale_list), "scale_list": scale_list,
                    "message": _after_heading(f.cite(display_message(message, ns, f.locale)),
                                              heading)})
    return out


# ---------------------------------------------------------------------------------------
# View models: plain strings and flags the templates lay out
# ---------------------------------------------------------------------------------------


def _norm_view(ns: NormSet, f: _Fmt) -> dict[str, Any]:
    title = ns.title_ru if f.locale == "ru" and ns.title_ru else ns.title
    cited = f.cite(ns.source)
    numbers = re.findall(r"\[\d+\]", cited)
    # a source naming known works is shown by their numbers (its prose is the bibliography's)
    source = "; ".join(dict.fromkeys(numbers)) if numbers else ns.source
    return {"name": ns.name, "title": title, "source": source,
            "imported_from": ns.imported_from, "imported_at": ns.imported_at}


def _film_inputs(tbl: Table, ns: NormSet, f: _Fmt) -> list[tuple[str, str]]:
    """The film section's inputs (the ``film_inputs`` table), each number in its shortest
    form: scales, camera, frame, object, height formula, scanner, bands."""
    r = {row.key: row for row in tbl.rows}
    inputs: list[tuple[str, str]] = [
        (f.label("map_scale"), f.scale(r["map_scale"].value)),
        (f.label("relief_interval_m"), f.g(r["relief_interval_m"].value)),
        (f.label("photo_scale"), f.list_sep.join(f.scale(x) for x in r["photo_scales"].value)),
    ]
    camera = r["camera"]
    if camera.value or camera.fields["name"]:
        inputs.append((f.label("camera"), camera_title(ns, camera.value, f.locale,
                                                       camera.fields["name"])))
    width, along = r["frame_mm"].value
    inputs += [
        (f.label("focal_mm"), f.g(r["focal_mm"].value)),
        (f.label("frame_mm"), f"{f.g(width)} × {f.g(along)}"),
        (f.label("resolving_power_lpmm"), f.g(r["resolving_power_lpmm"].value)),
        (f.label("forward_overlap_pct"), f.g(r["forward_overlap_pct"].value)),
    ]
    obj = r["object"].value
    if obj is not None:
        inputs += [
            (f.label("object"), f"{object_title(obj, f.locale)}: "
                                f"{f.g(r['object_size_m'].value)} {f.label('m')}, "
                                f"{_shape_name(ns, r['shape'].value, f.locale)}, "
                                f"B = {f.g(r['shape_coefficient'].value)}"),
            (f.label("probability"), f.g(r["probability"].value)),
            (f.label("norm_rows"), with_status(f.cite(localize(r["object_source"].value,
                                                               f.locale)),
                                               object_status(ns, obj), f.locale)),
        ]
    formula = r["height_formula"]
    if formula.fields["used"]:
        key = f"pdf_hf_{formula.value}"
        inputs.append((f.label("height_formula"),
                       f.label(key) if key in LABELS["en"] else formula.value))
    if r["scanner"].value:
        steps = r["scanner_steps_um"].value if "scanner_steps_um" in r else ()
        inputs.append((f.label("scanner"), f"{scanner_title(ns, r['scanner'].value, f.locale)}"
                       " (" + f.list_sep.join(f.g(x) for x in steps) + f" {f.label('um')})"))
    inputs.append((f.label("pdf_bands"), f"{r['bands'].value} × {r['bits_per_band'].value}"))
    inputs.append((f.label("norm_set"), _norm_view(ns, f)["title"]))
    return inputs


def _scan_view(job: ScanJob, f: _Fmt) -> dict[str, Any]:
    plan: ScanPlan = job.plan
    inp, rules, ns = plan.inputs, plan.rules, job.norm_set
    inputs = _film_inputs(f.view.tables["film_inputs"], ns, f)
    obj = inp.object
    obj_name = object_title(obj, f.locale) if obj is not None else ""

    # at most _MAX_COLUMNS photo scales per table, so a wide plan stays inside A4
    scen = plan.scenarios
    n_tables = math.ceil(len(scen) / _MAX_COLUMNS)
    size = math.ceil(len(scen) / n_tables)
    tables = [_scan_table(f.view.tables["film_constraints"], slice(i, i + size), f)
              for i in range(0, len(scen), size)]

    explanations = [f.cite(display_message(s.explanation, ns, f.locale))
                    for s in plan.scenarios]

    limit = ""
    mci = plan.interpretation_limit_photo_scale
    if mci is not None and obj is not None:
        limit = f.label("pdf_interpretation_limit", object=obj_name, p=f.g(rules.probability),
                        scale=f.floor_scale(mci), ratio=f.num(mci / inp.map_scale, 1),
                        r=f.g(inp.resolving_power_lpmm))
    reach = [{"pixel": f.g(r.pixel_um),
              "scale": f.floor_scale(r.max_photo_scale) if r.max_photo_scale > 0
              else f.label("pdf_none"),
              "limit": f"{r.limit} — {f.cname(r.limit)}" if r.limit in CONSTRAINTS else r.limit,
              "interpretable": (f.floor_scale(r.max_photo_scale_interpretable)
                                if r.max_photo_scale_interpretable else f.label("pdf_none"))}
             for r in plan.max_photo_scales]
    formulas = [{"id": cid, "name": f.cname(cid),
                 "equation": f.cite(localize(CONSTRAINTS[cid].equation, f.locale)),
                 "protects": localize(CONSTRAINTS[cid].protects, f.locale)}
                for cid in plan.constraint_ids]
    params = [{"name": param_name(ns, k, f.locale),
               "value": param_value(ns, k, v, f.locale, f.g),
               "source": with_status(f.cite(ns.parameter_sources.get(k, "")),
                                     ns.parameter_status.get(k, ""), f.locale)}
              for k, v in ns.parameters.items() if k not in DIGITAL_ONLY_PARAMETERS]
    return {
        "inputs": inputs, "tables": tables,
        "explanations": explanations, "interpretation_limit": limit, "reach": reach,
        "reach_interpretable": obj is not None and mci is not None,
        "warnings": _warnings(f.view.tables["film_warnings"], f, ns), "formulas": formulas,
        "params": params, "norm": _norm_view(ns, f),
        "plot": view_plot_uri(f.view, "constraints"),
    }


def _scan_table(film: Table, part: slice, f: _Fmt) -> dict[str, Any]:
    """The film table (:func:`scanplan.reports.views.film_constraints`) for some of its
    photo scales: the constraints (binding flagged, others with their margin), then the
    summary rows."""
    header = [f.scale(c.value) for c in film.columns[part]]
    rows: list[dict[str, Any]] = []
    summary: list[dict[str, Any]] = []
    for r in film.rows:
        unit = row_unit(r.unit, f.view.labels)
        values = r.values[part]
        texts = [row_value(r, v, f.view.numbers) for v in values]
        label = row_label(r, f.view.labels, f.view.numbers)
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


def _uav_inputs(job: UavJob, f: _Fmt) -> list[tuple[str, str]]:
    """The UAV section's inputs: camera, heights, speed, overlaps, scene, map."""
    plan: UavPlan = job.plan
    inp, ns, h = plan.inputs, job.norm_set, plan.heights_m
    m = f.label("m")
    cam = camera_title(ns, inp.camera, f.locale, inp.camera_name)
    inputs: list[tuple[str, str]] = []
    if cam:
        inputs.append((f.label("camera"), cam))
    inputs += [
        (f.label("pixel_pitch_um"), f.view.numbers.sig(inp.pixel_um)),
        (f.label("focal_mm"), f.g(inp.focal_mm)),
        (f.label("pdf_f_number"), f.g(inp.f_number)),
        (f.label("pdf_sensor_mm"), f"{f.view.numbers.sig(inp.sensor_width_mm)} × "
                                   f"{f.view.numbers.sig(inp.sensor_height_mm)}"),
        (f.label("orientation"), f.label(f"orientation_{inp.orientation}")),
        (f.label("height_m"), f.g(h["planned"])),
    ]
    if h["max"] != h["min"] or h["min"] != h["planned"]:
        inputs.append((f.label("pdf_flown_heights"), f"{f.g(h['min'])} – {f.g(h['max'])}"))
    if inp.ceiling_m is not None:
        inputs.append((f.label("ceiling_m"), f.g(inp.ceiling_m)))
    if inp.gsd_target_m is not None:
        inputs.append((f.label("gsd_target_cm"), f.g(inp.gsd_target_m * 100.0)))
    inputs += [
        (f.label("ground_speed_ms"), f.g(inp.speed_ms)),
        (f.label("exposure_s"), f.g(inp.exposure_s)),
        (f.label("design_overlaps"),
         f"{f.g(inp.forward_overlap_pct)} / {f.g(inp.side_overlap_pct)}"),
        (f.label("pdf_scene"), f"{f.g(inp.r_max)} / {f.g(inp.r_min)}"),
        (f.label("threshold_k0"), f.g(inp.threshold_k0)),
    ]
    if inp.map_scale is not None:
        inputs += [(f.label("map_scale"), f.scale(inp.map_scale)),
                   (f.label("relief_interval_m"), f.g(inp.relief_interval_m))]
        obj = inp.map_object
        if obj is not None:
            name = object_title(obj, f.locale)
            inputs.append((f.label("object"), with_status(
                f"{name}: {f.g(obj.size_m)} {m}, {_shape_name(ns, obj.shape, f.locale)}, "
                f"B = {f.g(obj.shape_coefficient)}", obj.status, f.locale)))
    inputs.append((f.label("norm_set"), _norm_view(ns, f)["title"]))
    return inputs


def _uav_results(plan: UavPlan, f: _Fmt) -> tuple[list[str], list[dict[str, Any]], str]:
    """The result table's columns (the planned and the highest flown height), its rows
    and the motion-blur sentence."""
    table = f.view.tables["uav_results"]
    cols = [f.label("pdf_at_height", h=f.g(c.value)) for c in table.columns]
    results = [{"label": row_label(r, f.view.labels, f.view.numbers),
                "cells": [row_value(r, v, f.view.numbers) for v in r.values]
                + [""] * (len(cols) - len(r.values))}
               for r in table.rows]
    blur = f.label("pdf_blur_limit", blur=f.g(MAX_BLUR_PX),
                   exposure=f"1/{math.ceil(1 / plan.max_exposure_s):d}",
                   speed=f.num(plan.max_speed_ms, 1))
    return cols, results, blur


def _uav_flight(flight: Table, f: _Fmt) -> list[tuple[str, str]]:
    """The flight geometry at the planned height (the ``uav_flight`` table)."""
    v = {r.key: r.value for r in flight.rows}
    trigger, overlap = (next(r.fields for r in flight.rows if r.key == key)
                        for key in ("photo_interval", "overlap_range"))
    rows = [
        (f.label("pdf_footprint"), f"{f.num(v['footprint'][0], 0)} × "
                                   f"{f.num(v['footprint'][1], 0)}"),
        (f.label("base_m"), f.num(v["base"], 1)),
        (f.label("line_spacing_m"), f.num(v["line_spacing"], 1)),
        (f.label("photo_interval_s"), f.num(v["photo_interval"], 2)
         + (f" ({f.label('pdf_trigger_min')} {f.g(trigger['min_trigger'])})"
            if trigger else "")),
        (f.label("pdf_overlap_at", lo=f.g(overlap["lo"]), hi=f.g(overlap["hi"])),
         f"{f.num(v['overlap_range'][0], 1)} / {f.num(v['overlap_range'][1], 1)}"),
    ]
    if "strips" in v:  # counts grouped as page 1 and the flight-lines table give them
        rows.append((f.label("pdf_strips"), " × ".join(f.num(x, 0) for x in v["strips"][:2])
                     + f" = {f.num(v['strips'][2], 0)}"))
    elif "strips_photos" in v:  # a polygon: the strips differ in length
        rows.append((f.label("pdf_strips_photos"),
                     " / ".join(f.num(x, 0) for x in v["strips_photos"])))
    if "flight_length_km" in v:
        minutes = v["flight_time_min"]
        rows.append((f.label("pdf_flight_length"), f"{f.num(v['flight_length_km'], 1)} / "
                     + (f.num(minutes, 0) if minutes is not None else "—")))
    if "data_volume_gb" in v:
        rows.append((f.label("data_volume_gb"), f.num(v["data_volume_gb"], 1)))
        rows.append((f.label("data_volume_jpeg_gb"), f.num(v["data_volume_jpeg_gb"], 1)))
    return rows


def _uav_limits(plan: UavPlan, f: _Fmt) -> dict[str, Any]:
    """The constraints as maximum heights, the sentence on the binding one, the height
    accuracy forms and the formulas."""
    inp, h = plan.inputs, plan.heights_m
    limits = [{"id": r.key, "name": f.cname(r.key),
               "limit": f.num(limit, 3 if limit < 10 else 0),
               "compares": compares, "max_height": f.num(top, 0),
               "max_flown": f.num(flown, 0),
               "margin": "" if margin is None else _margin(f, margin),
               "binding": "binding" in r.flags}
              for r in f.view.tables["uav_limits"].rows
              for limit, compares, top, flown, margin in [r.values]]
    limits_title = ""
    max_sentence = ""
    if plan.limits and inp.map_scale is not None:
        tol = inp.height_tolerance_up_pct
        limits_title = f.label("pdf_limits", scale=f.scale(inp.map_scale),
                               hc=f.g(inp.relief_interval_m)) + (
            f.label("pdf_tol_note", tol=f.g(tol)) if tol else "")
        b = next(x for x in plan.limits if x.binding)
        max_sentence = f.label("pdf_max_height_sentence", h=f.num(plan.max_height_m, 0),
                               cid=b.id, name=f.cname(b.id),
                               reason=f.cite(localize(b.reason, f.locale)))
    height_forms = ""
    acc = plan.height_accuracy
    if acc:
        m = f.label("m")
        height_forms = f.label("pdf_height_forms", sigma=f.num(
            acc["sigma_z_at_highest_flown_height_m"], 3), h=f.g(h["max"]),
            vz=f.g(acc["height_accuracy_m"]), forms="; ".join(
                f"{f.label('hf_' + k)}: {f.num(acc['forms'][k]['max_planned_height_m'], 0)} {m}"
                + (f" ({f.label('hf_used')})" if k == acc.get("formula") else "")
                for k in ("normal_case", "instruction", "parallax")))
    formulas = [{"equation": eq, "meaning": f.label(key), "source": f.cite(f.label(src))}
                for eq, key, src in _UAV_FORMULAS
                if plan.limits or key not in ("pdf_f_pd", "pdf_f_tol")]
    limit_formulas = [{"id": lim.id, "name": f.cname(lim.id),
                       "equation": f.cite(localize(lim.equation, f.locale))}
                      for lim in plan.limits]
    return {"limits": limits, "limits_title": limits_title, "max_sentence": max_sentence,
            "height_forms": height_forms, "formulas": formulas,
            "limit_formulas": limit_formulas}


def _uav_view(job: UavJob, f: _Fmt) -> dict[str, Any]:
    plan: UavPlan = job.plan
    ns, h = job.norm_set, plan.heights_m
    cols, results, blur = _uav_results(plan, f)
    recognition = [{
        "object": _object_name(ns, r.fields["name"], size, scale, f.locale),
        "map": f.scale(scale) if scale else "—", "size": f.g(size),
        "shape": _shape_name(ns, shape, f.locale), "p": f.num(p, 2),
        "p_max": f.num(p_max, 2), "p_corner": f.num(p_corner, 2)}
        for r in f.view.tables["uav_recognition"].rows
        for scale, size, shape, p, p_max, p_corner in [r.values]]
    return {
        "inputs": _uav_inputs(job, f), "cols": cols, "results": results, "blur": blur,
        "flight": _uav_flight(f.view.tables["uav_flight"], f),
        "recognition": recognition, "recognition_cols": [
            f.label("pdf_at_height", h=f.g(h["planned"])),
            f.label("pdf_at_height", h=f.g(h["max"])),
            f.label("pdf_corner_at", h=f.g(h["max"]))],
        **_uav_limits(plan, f),
        "warnings": _warnings(f.view.tables["uav_warnings"], f, ns),
        "norm": _norm_view(ns, f),
        "plot_mtf": view_plot_uri(f.view, "mtf"),
        "plot_height": view_plot_uri(f.view, "height"),
        "not_resolvable": not plan.resolvable,
    }


def _comparison_view(scan: ScanJob, uav: UavJob, f: _Fmt) -> dict[str, Any]:
    sp, up = scan.plan, uav.plan
    um, m = f.label("um"), f.label("m")
    film_result = "; ".join(f"{f.scale(s.photo_scale)}: {f.num(s.scan_pixel_um, 1)} {um} "
                            f"({s.binding})" for s in sp.scenarios)
    uav_result = (f"{f.label('max_height_m').split(',')[0]}: {f.num(up.max_height_m, 0)} {m}"
                  f" ({up.binding}); " if up.max_height_m is not None else "") + (
        f"GSD {f.num(up.gsd_m, 3)} {m}, L {f.num(up.ground_resolution_m, 3)} {m} "
        f"({f.label('pdf_at_height', h=f.g(up.heights_m['planned']))})")
    film_binding = ", ".join(dict.fromkeys(f"{s.binding} — {f.cname(s.binding)}"
                                           for s in sp.scenarios))
    return {"rows": [
        (f.label("map_scale"), f.scale(sp.inputs.map_scale),
         f.scale(up.inputs.map_scale) if up.inputs.map_scale is not None else "—"),
        (f.label("binding"), film_binding,
         f"{up.binding} — {f.cname(up.binding)}" if up.binding else "—"),
        (f.label("pdf_result"), film_result, uav_result),
        (f.label("warnings"), str(len(sp.warnings)), str(len(up.warnings))),
    ]}


def _film_relief_rows(tbl: Table, f: _Fmt) -> list[tuple[str, str]]:
    """``[terrain]``: the frame the film specification holds at, and the flat-ground scan
    pixel beside it (issue 12)."""
    keys = tbl.keys()
    if "relief_mc_max" not in keys:
        return []
    mc = tbl.row("relief_mc_max")
    where = (f"{f.label('terrain_film_frame')}: {mc.fields['frame']} ({mc.fields['strip']})"
             if mc.fields["ground_known"] else f.label("terrain_film_frame_range",
                                                       low=f.g(mc.fields["ground_low_m"])))
    flat = tbl.row("relief_flat_pixel")
    rows = [(f.label("terrain_film_mc_max"), f"{f.scale(mc.value)}; {where}"),
            (f.label("terrain_film_flat_pixel"),
             f"{f.num(flat.value, flat.digits)} ({flat.fields['binding']})")]
    if "relief_rejected" in keys:
        rows.append((f.label("terrain_film_rejected"), "; ".join(
            f.label("terrain_film_rejected_value", scale=f.scale(scale), local=f.scale(local))
            for scale, local in tbl.row("relief_rejected").values)))
    return rows


def _reason_text(r: Row, f: _Fmt) -> str:
    return sentence(f.cite(display_message(r.value, r.details[0]["norm_set"], f.locale)))


def _spec_film_rows(tbl: Table, f: _Fmt) -> list[tuple[str, str]]:
    """The film's headline (the ``spec_film`` table): the scale, the scan pixel (and the
    scanner's step after an arrow), the binding constraint, the relief, the probability,
    the frames."""
    if tbl.keys() == ["reason"]:
        return []
    r = {row.key: row for row in tbl.rows}
    rows = [(f.label("spec_archive_photo_scale" if "archive" in r["photo_scale"].flags
                     else "spec_recommended_photo_scale"), f.scale(r["photo_scale"].value))]
    px, px_label = f.num(r["scan_pixel_um"].value, 1), "scan_pixel_um"
    if "scanner_pixel_um" in r:  # "12.5 → 7.0" says what the arrow means
        px += f" → {f.num(r['scanner_pixel_um'].value, 1)}"
        px_label = "spec_scan_pixel_to_step_um"
    rows.append((f.label(px_label), px))
    binding = r["binding"].value
    rows.append((f.label("binding"), f"{binding} — {f.cname(binding)}"))
    rows += _film_relief_rows(tbl, f)
    prob = r["probability"]
    rows.append((f.label("terrain_film_probability" if "over_relief" in prob.flags
                         else "probability"), f.num(prob.value, prob.digits)))
    if "frames" in r:
        rows.append((f.label("spec_frames"), f.g(r["frames"].value)))
        rows.append((f.label("spec_scanned_gb"), f.num(r["scanned_gb"].value, 1)))
    return rows


def _spec_uav_rows(tbl: Table, f: _Fmt) -> list[tuple[str, str]]:
    """The digital camera's headline (the ``spec_uav`` table): the heights, the binding
    constraint and the contract's deliverables (the GSD and the overlaps the crew flies,
    the photos, the data volume)."""
    r = {row.key: row for row in tbl.rows}
    rows: list[tuple[str, str]] = []
    if "planned_height_m" in r:
        rows.append((f.label("spec_planned_height_m"), f.num(r["planned_height_m"].value, 0)))
    rows.append((f.label("spec_recommended_height_m"),
                 f.num(r["recommended_height_m"].value, 0)))
    rows.append((f.label("spec_max_height_flat_m" if "flat" in r["max_height_m"].flags
                         else "max_height_m"), f.num(r["max_height_m"].value, 0)))
    if "max_height_relief_m" in r:
        rows.append((f.label("spec_max_height_relief_m"),
                     f.num(r["max_height_relief_m"].value, 0)))
    if "binding" in r:
        binding = r["binding"].value
        rows.append((f.label("binding"), f"{binding} — {f.cname(binding)}"))
    rows.append((f.label("design_gsd_planned"), f.num(r["gsd_cm"].value, 2)))
    rows.append((f.label("design_overlaps"), f.label(
        "design_overlaps_value", fwd=f.num(r["forward_overlap_pct"].value, 0),
        side=f.num(r["side_overlap_pct"].value, 0))))
    if "photos" in r:
        rows.append((f.label("spec_photos"), f.g(r["photos"].value)))
    for key in ("data_volume_gb", "data_volume_jpeg_gb"):
        if key in r:
            rows.append((f.label(key), f.num(r[key].value, 1)))
    return rows


def _spec_view(spec: PlanResult, f: _Fmt) -> dict[str, Any]:
    """The specification of ``scanplan plan``: what was chosen, with its reason (the
    ``spec_film`` and ``spec_uav`` tables), and the comparison."""
    rows: list[tuple[str, str]] = []
    reasons: list[str] = []
    for name, lay_out in (("spec_film", _spec_film_rows), ("spec_uav", _spec_uav_rows)):
        if f.view.tables.has(name):
            tbl = f.view.tables[name]
            rows += lay_out(tbl, f)
            reasons.append(_reason_text(tbl.row("reason"), f))
    comparison = [(row_label(r, f.view.labels, f.view.numbers),
                   *(row_value(r, x, f.view.numbers) for x in r.values),
                   row_unit(r.unit, f.view.labels))
                  for r in f.view.tables["comparison"].rows]
    return {"rows": rows, "reasons": reasons, "comparison": comparison}


def _margin(f: _Fmt, pct: float) -> str:
    """A constraint's margin to the binding one, signed with a real minus (``+7 %``,
    ``−21 %`` for a constraint set aside below the binding one; never ``+-21 %``)."""
    return f"{'+' if pct >= 0 else '−'}{f.num(abs(pct), 0)} %"

