"""The terminal report of ``scanplan uav``: the results at the planned and the highest flown
height, the flight geometry, the recognition of the norm objects, the constraints as
maximum heights and the warnings, in the language of ``--locale``."""

from __future__ import annotations

import math
from typing import Any

from ...rules.uav import UavPlan
from ..formatter import Formatter, formatter
from ..views import ResultTables, Row, Table
from .film import norm_object, norm_shape, warning_lines
from .layout import table, text_table, wrap

__all__ = ["format_uav_plan", "volume_text"]


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
    f = formatter(locale)
    tables = ResultTables(uav=plan, uav_norms=norm_set)  # built once for this report
    r = {row.key: row for row in tables["uav_inputs"].rows}
    v = {key: row.value for key, row in r.items()}
    camera_id, name = r["camera"].fields["id"], r["camera"].fields["name"]
    carrier = f.cli("carrier_aircraft" if v["platform"] == "aircraft" else "carrier_uav")
    if name and f.locale == "ru" and norm_set is not None:  # English remarks dropped, units
        name = f.camera(norm_set, camera_id, name)
    low, high = v["heights"]
    planned = r["heights"].fields["planned"]
    lines = [
        f.cli("uav_head", carrier=carrier, camera=camera_id or name or f.cli("camera"))
        + (f" ({name})" if name and camera_id else ""),
        f.cli("uav_line1", pixel=f.sig(v["pixel_um"]), f=f.sig(v["focal_mm"]),
              n=f.short(v["f_number"]), w=f.value(r["sensor_width_mm"], v["sensor_width_mm"]),
              h=f.value(r["sensor_height_mm"], v["sensor_height_mm"]),
              height=f.short(planned))
        + (f.cli("uav_flown", lo=f.short(low), hi=f.short(high)) if high != low else "")
        + f.cli("uav_line1_tail", v=f.short(v["speed_ms"]), t=f.short(v["exposure_s"]),
                fo=f.short(v["forward_overlap_pct"]), so=f.short(v["side_overlap_pct"])),
        f.cli("uav_line2", rmax=f.short(v["r_max"]), rmin=f.short(v["r_min"]),
              k0=f.short(v["threshold_k0"]))
        + (f.cli("uav_norm", name=norm_name) if norm_name else ""),
        "",
    ]
    results = tables["uav_results"]
    lines.append(text_table(
        results, label=lambda r: f.cli(_UAV_WORDS[r.key],
                                       **{k: f.short(v) for k, v in r.fields.items()}),
        unit=lambda r: f.cli(r.unit) if r.unit else "", cell=lambda r, i, v: _uav_cell(r, v, f),
        head=["", "", *(f.cli("at_height", h=f.short(c.value)) for c in results.columns)],
        align="ll" + "r" * len(results.columns)))
    fig = {row.key: row for row in tables["uav_figures"].rows}
    lines.append(f.cli("blur_limit", denominator=math.ceil(1 / fig["max_exposure_s"].value),
                       v=f.fixed(fig["max_speed_ms"].value, 1)))
    lines += _flight_lines(tables["uav_flight"], f)
    lines += _recognition_lines(tables["uav_recognition"], f, norm_set)
    lines += _limit_lines(tables, f)
    lines += warning_lines(tables["uav_warnings"], f)
    return "\n".join(lines)


#: The terminal's word of each row of the UAV results.
_UAV_WORDS = {"gsd_m": "gsd", "nyquist_lpmm": "nyquist", "resolving_power": "resolving_power",
              "ground_resolution_m": "l_centre", "l_corner": "l_corner",
              "l_over_gsd": "l_gsd", "motion_blur_px": "blur", "tilted_gsd": "tilted"}


def _uav_cell(r: Row, v: Any, f: Formatter) -> str:
    """A UAV result: fixed decimals, a pair as ``centre / corner``, "" for none."""
    if isinstance(v, str):
        return v
    digits = r.digits if r.digits is not None else 1
    if isinstance(v, tuple):
        return " / ".join(f.fixed(x, digits) for x in v)
    return f.fixed(v, digits)


def _limit_cell(r: Row, i: int, v: Any, f: Formatter) -> str:
    """A constraint as a maximum height: its limit (a height as given, a ground limit to
    mm), what it compares, the maximum planned (``*`` where it binds) and flown height."""
    m = f.cli("m")
    if i == 0:
        return f"{f.short(v) if r.values[1] == 'H' else f.fixed(v, 3)} {m}"
    if i == 1:
        return f.cli("gsd") if v == "GSD" else str(v)
    return f"{f.fixed(v, 0)} {m}" + (("*" if "binding" in r.flags else " ") if i == 2 else "")


def volume_text(full: Row, jpeg: Row, f: Formatter) -> str:
    """``163.5 GB uncompressed (JPEG ≈ 18.2 GB at 9:1)``: the rows ``data_volume_gb`` and
    ``data_volume_jpeg_gb`` (its field ``ratio``: the compression assumed) in words."""
    return f.cli("volume_value", full=f.num(full.value, 1), jpeg=f.num(jpeg.value, 1),
                 ratio=f.short(jpeg.fields["ratio"]))


def _flight_lines(flight: Table, f: Formatter) -> list[str]:
    """The flight geometry at the planned height (the ``uav_flight`` table), one line per
    pair of its rows where the terminal joins them."""
    v = {r.key: r.value for r in flight.rows}
    fields = {r.key: r.fields for r in flight.rows}
    rows = {r.key: r for r in flight.rows}
    m, s = f.cli("m"), f.cli("s")
    interval, trigger = v["photo_interval"], fields["photo_interval"]
    overlap = fields["overlap_range"]
    frows = [[f.cli("footprint"),
              f"{f.fixed(v['footprint'][0], 0)} × {f.fixed(v['footprint'][1], 0)} {m}"],
             [f.cli("base_spacing"),
              f"{f.fixed(v['base'], 1)} {m} / {f.fixed(v['line_spacing'], 1)} {m}"],
             [f.cli("interval"), (f"{f.fixed(interval, 2)} {s}" if math.isfinite(interval)
                                  else f.cli("interval_none"))
              + (f.cli("camera_min", t=f.short(trigger["min_trigger"])) if trigger else "")],
             [f.cli("overlap_at", lo=f.short(overlap["lo"]), hi=f.short(overlap["hi"])),
              f"{f.fixed(v['overlap_range'][0], 1)} / {f.fixed(v['overlap_range'][1], 1)} %"]]
    if "strips" in v:
        strips, per, photos = v["strips"]
        frows.append([f.cli("strips_photos"), f.cli("strips_photos_value", strips=strips,
                                                    per=per, photos=photos)])
    elif "strips_photos" in v:
        strips, photos = v["strips_photos"]
        frows.append([f.cli("strips_photos"), f.cli("strips_photos_total", strips=strips,
                                                    photos=photos)])
    if "flight_length_km" in v:
        minutes = v["flight_time_min"]
        frows.append([f.cli("length_time"),
                      f"{f.fixed(v['flight_length_km'], 1)} {f.cli('km')} / "
                      + (f"{f.fixed(minutes, 0)} {f.cli('min')}" if minutes is not None
                         else "—")])
    if "data_volume_gb" in v:
        frows.append([f.cli("volume"), volume_text(rows["data_volume_gb"],
                                                   rows["data_volume_jpeg_gb"], f)])
    return ["", f.cli("flight_head"), table([[f"  {a}", b] for a, b in frows], align="ll")]


def _recognition_lines(recognition: Table, f: Formatter, norm_set: Any) -> list[str]:
    """The recognition probability of the norm objects (the ``uav_recognition`` table)."""
    if not recognition.rows:
        return []
    cols = recognition.columns
    m = f.cli("m")
    head = [f"  {f.cli('rec_object')}", f.cli("map"), f.cli("rec_size"), f.cli("rec_shape"),
            f"{f.short(cols[3].value)} {m}", f"{f.short(cols[4].value)} {m}",
            f.cli("rec_corner")]

    def cell(r: Row, i: int, v: Any) -> str:
        if i == 0:
            return f.scale(v) if v else "—"
        if i == 1:
            return f.short(v)
        return norm_shape(f, norm_set, v) if i == 2 else f.fixed(v, cols[i].digits or 0)

    text = text_table(recognition, head=head, align="llrlrrr", cell=cell,
                      label=lambda r: "  " + norm_object(f, norm_set, r.fields["name"],
                                                         r.fields["size_m"]))
    return ["", f.cli("recognition_head"), text]


def _limit_lines(tables: ResultTables, f: Formatter) -> list[str]:
    """The constraints as maximum planned heights (the ``uav_limits`` table), the binding
    one, the height accuracy (``uav_accuracy``)."""
    limits = tables["uav_limits"]
    if not limits.rows:
        return []
    v = {row.key: row.value for row in tables["uav_inputs"].rows}
    fig = {row.key: row for row in tables["uav_figures"].rows}
    tol = v["height_tolerance_up_pct"]
    head = (f.cli("limits_head_map", map=f.scale(v["map_scale"]),
                  hc=f.short(v["relief_interval_m"]))
            if v["map_scale"] is not None else f.cli("limits_head"))
    lines = ["", head + (f.cli("limits_flown", tol=f.short(tol)) if tol else "") + ":"]
    lines.append(text_table(
        limits, label=lambda r: f"  {r.key}  {f.constraint(r.key)}",
        cell=lambda r, i, v: _limit_cell(r, i, v, f), columns=(0, 1, 2, 3),
        head=[f"  {f.cli('lim_constraint')}", f.cli("lim_limit"), f.cli("lim_compares"),
              f.cli("lim_max"), f.cli("lim_flown")], align="lrlrr"))
    b = next(r for r in limits.rows if "binding" in r.flags)
    top = fig["max_height_m"].value if "max_height_m" in fig else None
    flown = fig["max_flown_height_m"].value if "max_flown_height_m" in fig else None
    lines.append(wrap(f.cli("lim_sentence", max=f.fixed(top, 0), flown=f.fixed(flown or top, 0),
                            cid=b.key, name=f.constraint(b.key),
                            reason=f.text(b.fields["reason"])), ""))
    acc = {row.key: row for row in tables["uav_accuracy"].rows}
    if acc:
        used = next((row.fields["form"] for row in acc.values() if "used" in row.flags), None)
        sz = acc["sigma_z_m"]
        lines.append(wrap(f.cli(
            "accuracy", sz=f.fixed(sz.value, 3), h=f.short(sz.fields["at"]),
            req=f.short(acc["height_accuracy_m"].value), gsd=f.fixed(sz.fields["in_gsd"], 2),
            normal=f.fixed(acc["form_normal_case"].value, 0),
            instruction=f.fixed(acc["form_instruction"].value, 0),
            parallax=f.fixed(acc["form_parallax"].value, 0),
            used=f.cli(f"form_{used}")), ""))
    return lines
