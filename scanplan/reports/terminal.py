"""The terminal reports of ``scanplan scan`` and ``scanplan uav``, in the language of
``--locale`` (English or Russian): words from :mod:`scanplan.i18n.labels_cli`, constraint
names from the label catalogue, messages from :mod:`scanplan.i18n.messages`, numbers in the
locale's convention (:class:`scanplan.i18n.numbers.Numbers`: a decimal comma in Russian).
"""

from __future__ import annotations

import math
from typing import Any

from ..i18n.labels_cli import cli_text
from ..i18n.messages import localize, scale_text
from ..i18n.numbers import Numbers
from ..rules.film import ScanPlan
from ..rules.uav import UavPlan
from .references import author_cite
from .text import _wrap, code_tag, table, text_table, volume_text
from .views import ResultTables, Row, Table, constraint_title

__all__ = ["format_scan_plan", "format_uav_plan"]


class _Words:
    """The words and numbers of one terminal report in one locale."""

    def __init__(self, locale: str, norm_set: Any = None) -> None:
        self.loc = locale if locale in ("en", "ru") else "en"
        self.n = Numbers(self.loc)
        self.ns = norm_set

    def __call__(self, key: str, **fields: object) -> str:
        return cli_text(key, self.loc, **fields)

    def g(self, x: float) -> str:
        """Shortest form (``:g``), the locale's decimal separator."""
        return self.n.short(float(x))

    def f(self, x: float | None, digits: int = 1) -> str:
        """Fixed decimals."""
        return self.n.fixed(x, digits)

    def scale(self, x: float) -> str:
        """``1:10000`` (English), ``1:10 000`` (Russian):
        :func:`scanplan.i18n.messages.scale_text`."""
        return scale_text(x, self.loc)

    def constraint(self, cid: str) -> str:
        """A constraint's name (the rules registry's)."""
        return constraint_title(cid, self.loc)

    def object(self, name: str, size_m: float | None = None) -> str:
        """A norm object's name in the locale (the norm set's Russian name)."""
        if self.loc == "ru" and self.ns is not None:
            from .wording import object_title

            for o in getattr(self.ns, "objects", ()):
                if o.name == name and (size_m is None or o.size_m == size_m):
                    return object_title(o, self.loc)
        return name

    def shape(self, shape: str) -> str:
        """A shape in words (the norm set's Russian name)."""
        if self.loc == "ru" and self.ns is not None:
            from .wording import shape_title

            return shape_title(self.ns, shape, self.loc)
        return shape


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
    w = _Words(locale, norm_set)
    inp = plan.inputs
    frame = dict(f=w.g(inp.focal_mm), w=w.g(inp.frame_width_mm), l=w.g(inp.frame_along_mm))
    cam = (w("scan_camera", camera=inp.camera, **frame) if inp.camera
           else w("scan_no_camera", **frame))
    lines = [
        w("scan_head", map=w.scale(inp.map_scale), hc=w.g(inp.relief_interval_m)),
        w("scan_camera_line", camera=cam, r=w.g(inp.resolving_power_lpmm),
          p=w.g(inp.forward_overlap_pct)),
    ]
    if norm_name:
        if w.loc == "ru" and getattr(norm_set, "title_ru", ""):
            norm_title = norm_set.title_ru
        lines.append(w("norm_set", name=norm_name) + (f" — {norm_title}" if norm_title else ""))
    obj = inp.object
    if obj:
        lines.append(w("scan_object", name=w.object(obj.name, obj.size_m), size=w.g(obj.size_m),
                       shape=w.shape(obj.shape), b=w.g(obj.shape_coefficient),
                       p=w.g(plan.rules.probability),
                       source=author_cite(localize(obj.source, w.loc), w.loc)))
    lines.append("")
    tables = ResultTables(scan=plan)  # built once for this report
    tbl = tables["film_constraints"]
    lines.append(text_table(tbl, label=lambda r: _film_label(r, w),
                            unit=lambda r: w(r.unit) if r.unit else "",
                            cell=lambda r, i, v: _film_cell(r, i, v, w),
                            head=["", "", *(w.scale(c.value) for c in tbl.columns)],
                            align="ll" + "r" * len(tbl.columns)))
    lines.append(w("binding_note"))
    lines.append("")
    lines.append(w("why"))
    for s in plan.scenarios:
        lines.append(_wrap(localize(s.explanation, w.loc), "  "))
    if plan.interpretation_limit_photo_scale is not None:
        mci = plan.interpretation_limit_photo_scale
        lines.append("")
        lines.append(_wrap(w(
            "interpretation_limit", obj=w.object(obj.name, obj.size_m) if obj else w("the_object"),
            p=w.g(plan.rules.probability), scale=w.scale(math.floor(mci)),
            ratio=w.f(mci / inp.map_scale, 1), r=w.g(inp.resolving_power_lpmm)), ""))
    lines += _reach_lines(plan, w)
    lines += _warning_lines(tables["film_warnings"], w, scan=True)
    return "\n".join(lines)


#: The terminal's word (:mod:`.labels_cli`) of each row of the film table.
_FILM_WORDS = {"binding": "binding", "scan_pixel_um": "scan_pixel",
               "scanner_pixel_um": "scanner_step", "frame_megabytes": "scanned_frame",
               "resolution_on_ground": "resolution_a", "required_r": "r_needed",
               "recognition_probability": "p_at_pixel"}


def _film_label(r: Row, w: _Words) -> str:
    """A row's label in the film table: ``PZ  height accuracy``, ``Mc/Mk``, a word."""
    if "constraint" in r.flags:
        return f"{r.key}  {w.constraint(r.key)}"
    if r.key == "photo_to_map":
        return "Mc/Mk"
    return w(_FILM_WORDS[r.key], **r.fields)


def _film_cell(r: Row, i: int, v: Any, w: _Words) -> str:
    """A value of the film table: pixels as µm (``*`` where a constraint binds; the other
    results keep its column), the frame grouped."""
    if r.key == "photo_to_map":
        return w.f(v, r.digits or 0)
    if isinstance(v, str):
        text = v
    elif "constraint" in r.flags or r.key == "scan_pixel_um":
        text = w.n.um(v)
    elif r.key == "frame_megabytes":
        text = w.n.num(v, r.digits or 0)
    else:
        text = w.f(v, r.digits if r.digits is not None else 1)
    return text + ("*" if r.flagged(i, "binding") else " ")


def _warning_lines(warnings: Table, w: _Words, scan: bool = False) -> list[str]:
    """The warnings table as lines: ``!`` before each (a film plan's notes: ``i``)."""
    if not warnings.rows:
        return []
    out = ["", w("warnings")]
    for r in warnings.rows:
        mark = "!" if (not scan or "warning" in r.flags) else "i"
        out.append(_wrap(localize(r.values[0], w.loc) + code_tag(r.key, w.loc), f"  {mark} "))
    return out


def _reach_lines(plan: ScanPlan, w: _Words) -> list[str]:
    """The smallest photo scale (largest Mc) each scan pixel supports (scanner steps,
    --pixel-um)."""
    inp = plan.inputs
    lines: list[str] = []
    if plan.max_photo_scales:
        lines.append("")
        who = w("reach_and").join(
            x for x in (w("reach_scanner", scanner=inp.scanner) if inp.scanner else "",
                        "--pixel-um" if inp.candidate_pixels_um else "") if x)
        lines.append(w("reach_head", who=who))
        both = plan.interpretation_limit_photo_scale is not None
        rows = [[w("pixel_um"), w("reach_scale"), w("reach_limit")]
                + ([w("reach_interpretable")] if both else [])]
        for r in plan.max_photo_scales:
            if r.max_photo_scale > 0:
                row = [w.g(r.pixel_um), w.scale(math.floor(r.max_photo_scale)), r.limit]
            else:
                row = [w.g(r.pixel_um), w("none"), w("reach_pr")]
            if both:
                mi = r.max_photo_scale_interpretable
                row.append(w.scale(math.floor(mi)) if mi else w("none"))
            rows.append(row)
        lines.append(table(rows, align="rrlr" if both else "rrl"))
    return lines


def format_uav_plan(plan: UavPlan, norm_name: str = "", locale: str = "en",
                    norm_set: Any = None) -> str:
    """The terminal report of ``scanplan uav``.

    Parameters
    ----------
    plan : UavPlan
    norm_name : str
        The norm set's name.
    locale : {"en", "ru"}
        The language (``--locale``).
    norm_set : NormSet, optional
        For the Russian names of objects and shapes.
    """
    w = _Words(locale, norm_set)
    inp = plan.inputs
    h = plan.heights_m
    carrier = w("carrier_aircraft" if inp.platform == "aircraft" else "carrier_uav")
    name = inp.camera_name
    if name and w.loc == "ru" and norm_set is not None:  # English remarks dropped, units
        from .wording import camera_title

        name = camera_title(norm_set, inp.camera, w.loc, name)
    lines = [
        w("uav_head", carrier=carrier, camera=inp.camera or name or w("camera"))
        + (f" ({name})" if name and inp.camera else ""),
        w("uav_line1", pixel=w.n.sig(inp.pixel_um), f=w.n.sig(inp.focal_mm),
          n=w.g(inp.f_number), w=w.n.sig(inp.sensor_width_mm),
          h=w.n.sig(inp.sensor_height_mm), height=w.g(h["planned"]))
        + (w("uav_flown", lo=w.g(h["min"]), hi=w.g(h["max"])) if h["max"] != h["min"] else "")
        + w("uav_line1_tail", v=w.g(inp.speed_ms), t=w.g(inp.exposure_s),
            fo=w.g(inp.forward_overlap_pct), so=w.g(inp.side_overlap_pct)),
        w("uav_line2", rmax=w.g(inp.r_max), rmin=w.g(inp.r_min), k0=w.g(inp.threshold_k0))
        + (w("uav_norm", name=norm_name) if norm_name else ""),
        "",
    ]
    tables = ResultTables(uav=plan)  # built once for this report
    results = tables["uav_results"]
    lines.append(text_table(
        results, label=lambda r: w(_UAV_WORDS[r.key], **{k: w.g(v) for k, v in r.fields.items()}),
        unit=lambda r: w(r.unit) if r.unit else "", cell=lambda r, i, v: _uav_cell(r, v, w),
        head=["", "", *(w("at_height", h=w.g(c.value)) for c in results.columns)],
        align="ll" + "r" * len(results.columns)))
    lines.append(w("blur_limit", denominator=math.ceil(1 / plan.max_exposure_s),
                   v=w.f(plan.max_speed_ms, 1)))
    lines += _flight_lines(tables["uav_flight"], w)
    lines += _recognition_lines(tables["uav_recognition"], w)
    lines += _limit_lines(plan, w, tables)
    lines += _warning_lines(tables["uav_warnings"], w)
    return "\n".join(lines)


#: The terminal's word (:mod:`.labels_cli`) of each row of the UAV results.
_UAV_WORDS = {"gsd_m": "gsd", "nyquist_lpmm": "nyquist", "resolving_power": "resolving_power",
              "ground_resolution_m": "l_centre", "l_corner": "l_corner",
              "l_over_gsd": "l_gsd", "motion_blur_px": "blur", "tilted_gsd": "tilted"}


def _uav_cell(r: Row, v: Any, w: _Words) -> str:
    """A UAV result: fixed decimals, a pair as ``centre / corner``, "" for none."""
    if isinstance(v, str):
        return v
    digits = r.digits if r.digits is not None else 1
    if isinstance(v, tuple):
        return " / ".join(w.f(x, digits) for x in v)
    return w.f(v, digits)


def _limit_cell(r: Row, i: int, v: Any, w: _Words) -> str:
    """A constraint as a maximum height: its limit (a height as given, a ground limit to
    mm), what it compares, the maximum planned (``*`` where it binds) and flown height."""
    m = w("m")
    if i == 0:
        return f"{w.g(v) if r.values[1] == 'H' else w.f(v, 3)} {m}"
    if i == 1:
        return str(v)
    return f"{w.f(v, 0)} {m}" + (("*" if "binding" in r.flags else " ") if i == 2 else "")


def _flight_lines(flight: Table, w: _Words) -> list[str]:
    """The flight geometry at the planned height (the ``uav_flight`` table), one line per
    pair of its rows where the terminal joins them."""
    v = {r.key: r.value for r in flight.rows}
    fields = {r.key: r.fields for r in flight.rows}
    m, s = w("m"), w("s")
    interval, trigger = v["photo_interval"], fields["photo_interval"]
    overlap = fields["overlap_range"]
    frows = [[w("footprint"), f"{w.f(v['footprint'][0], 0)} × {w.f(v['footprint'][1], 0)} {m}"],
             [w("base_spacing"), f"{w.f(v['base'], 1)} {m} / {w.f(v['line_spacing'], 1)} {m}"],
             [w("interval"), (f"{w.f(interval, 2)} {s}" if math.isfinite(interval)
                              else w("interval_none"))
              + (w("camera_min", t=w.g(trigger["min_trigger"])) if trigger else "")],
             [w("overlap_at", lo=w.g(overlap["lo"]), hi=w.g(overlap["hi"])),
              f"{w.f(v['overlap_range'][0], 1)} / {w.f(v['overlap_range'][1], 1)} %"]]
    if "strips" in v:
        strips, per, photos = v["strips"]
        frows.append([w("strips_photos"), w("strips_photos_value", strips=strips, per=per,
                                            photos=photos)])
    elif "strips_photos" in v:
        strips, photos = v["strips_photos"]
        frows.append([w("strips_photos"), w("strips_photos_total", strips=strips,
                                            photos=photos)])
    if "flight_length_km" in v:
        minutes = v["flight_time_min"]
        frows.append([w("length_time"), f"{w.f(v['flight_length_km'], 1)} {w('km')} / "
                      + (f"{w.f(minutes, 0)} {w('min')}" if minutes is not None else "—")])
    if "data_volume_gb" in v:
        frows.append([w("volume"), volume_text(v["data_volume_gb"], v["data_volume_jpeg_gb"],
                                               w.loc)])
    return ["", w("flight_head"), table([[f"  {a}", b] for a, b in frows], align="ll")]


def _recognition_lines(recognition: Table, w: _Words) -> list[str]:
    """The recognition probability of the norm objects (the ``uav_recognition`` table)."""
    if not recognition.rows:
        return []
    cols = recognition.columns
    head = [f"  {w('rec_object')}", w("rec_map"), w("rec_size"), w("rec_shape"),
            f"{w.g(cols[3].value)} {w('m')}", f"{w.g(cols[4].value)} {w('m')}",
            w("rec_corner")]

    def cell(r: Row, i: int, v: Any) -> str:
        if i == 0:
            return w.scale(v) if v else "—"
        if i == 1:
            return w.g(v)
        return w.shape(v) if i == 2 else w.f(v, cols[i].digits or 0)

    text = text_table(recognition, head=head, align="llrlrrr", cell=cell,
                      label=lambda r: f"  {w.object(r.fields['name'], r.fields['size_m'])}")
    return ["", w("recognition_head"), text]


def _limit_lines(plan: UavPlan, w: _Words, tables: ResultTables) -> list[str]:
    """The constraints as maximum planned heights, the binding one, height accuracy."""
    inp, h = plan.inputs, plan.heights_m
    if not plan.limits:
        return []
    tol = inp.height_tolerance_up_pct
    head = (w("limits_head_map", map=w.scale(inp.map_scale), hc=w.g(inp.relief_interval_m))
            if inp.map_scale is not None else w("limits_head"))
    lines = ["", head + (w("limits_flown", tol=w.g(tol)) if tol else "") + ":"]
    lines.append(text_table(
        tables["uav_limits"], label=lambda r: f"  {r.key}  {w.constraint(r.key)}",
        cell=lambda r, i, v: _limit_cell(r, i, v, w), columns=(0, 1, 2, 3),
        head=[f"  {w('lim_constraint')}", w("lim_limit"), w("lim_compares"), w("lim_max"),
              w("lim_flown")], align="lrlrr"))
    b = next(x for x in plan.limits if x.binding)
    lines.append(_wrap(w("lim_sentence", max=w.f(plan.max_height_m, 0),
                         flown=w.f(plan.max_flown_height_m or plan.max_height_m, 0),
                         cid=b.id, name=w.constraint(b.id),
                         reason=localize(b.reason, w.loc)), ""))
    acc = plan.height_accuracy
    if acc:
        forms = acc["forms"]
        lines.append(_wrap(w(
            "accuracy", sz=w.f(acc["sigma_z_at_highest_flown_height_m"], 3), h=w.g(h["max"]),
            req=w.g(acc["height_accuracy_m"]), gsd=w.f(acc["sigma_z_in_gsd"], 2),
            normal=w.f(forms["normal_case"]["max_planned_height_m"], 0),
            instruction=w.f(forms["instruction"]["max_planned_height_m"], 0),
            parallax=w.f(forms["parallax"]["max_planned_height_m"], 0),
            used=w(f"form_{acc['formula']}")), ""))
    return lines
