"""The specification's headline (``scanplan plan``): what was chosen for the film and for
the digital camera, and why — the terminal summary, the PDF's specification section and
the workbook's Summary sheet lay it out, each the rows it shows (:func:`spec_film`,
:func:`spec_uav`)."""

from __future__ import annotations

import math
from typing import Any

from .table import Column, Row, Table

__all__ = ["relief_max_height_m", "spec_film", "spec_uav"]

_COLUMNS = (Column("value"),)


def relief_max_height_m(uav: Any) -> float | None:
    """The maximum planned height over the relief (``[terrain]``: the worst photo meets
    its binding constraint up to it, above the reference ground) [m], when it is lower than
    the flat-ground maximum the tables show beside it; None otherwise."""
    terrain = getattr(uav, "terrain", None)
    limit = getattr(terrain, "max_height_m", None)
    if limit is None or uav.max_height_m is None or limit >= uav.max_height_m - 0.5:
        return None
    return float(limit)


def _reason(spec_part: Any) -> Row:
    return Row("reason", (spec_part.reason,), details=({"norm_set": spec_part.job.norm_set},))


def spec_film(spec: Any) -> Table:
    """The film's headline of a specification (``PlanResult.film``).

    Parameters
    ----------
    spec : PlanResult
        A specification with a film part.

    Returns
    -------
    Table
        One column; with a recommended scale the rows ``photo_scale`` (unit ``scale``;
        flag ``"archive"`` for an archive's scale), ``scan_pixel_um``,
        ``scanner_pixel_um`` (with a scanner), ``binding`` (the constraint's id), over the
        relief ``relief_mc_max`` (the highest local photo scale, rounded; fields
        ``ground_known``, ``frame``, ``strip``, ``ground_low_m``), ``relief_flat_pixel``
        (the flat-ground scan pixel; field ``binding``) and ``relief_rejected`` (pairs:
        a rejected photo scale, its highest local one), ``probability`` (flag
        ``"over_relief"`` when it is the lowest ground's frame's), ``frame_megabytes``,
        with a frame count ``frames``, ``strips`` and ``scanned_gb``; always ``reason``
        (the :class:`~scanplan.messages.Message`; ``details``: its norm set).
    """
    fs = spec.film
    rec = fs.recommended
    if rec is None:
        return Table("spec_film", "spec_title", _COLUMNS, (_reason(fs),))
    rows = [Row("photo_scale", (rec.photo_scale,), unit="scale",
                flags=frozenset({"archive"}) if fs.archive else frozenset()),
            Row("scan_pixel_um", (rec.scan_pixel_um,), unit="um", digits=1)]
    if rec.scanner_pixel_um is not None:
        rows.append(Row("scanner_pixel_um", (rec.scanner_pixel_um,), unit="um", digits=1))
    rows.append(Row("binding", (rec.binding,), flags=frozenset({"constraint"})))
    ft, flat = getattr(fs, "terrain", None), getattr(fs, "flat", None)
    over_relief = ft is not None and flat is not None  # the lowest ground's frame
    if over_relief:
        rows.append(Row("relief_mc_max", (round(ft.mc_max),), unit="scale",
                        fields={"ground_known": ft.ground_known, "frame": ft.binding_frame,
                                "strip": ft.binding_strip, "ground_low_m": ft.ground_low_m}))
        rows.append(Row("relief_flat_pixel", (flat.scan_pixel_um,), unit="um", digits=1,
                        fields={"binding": flat.binding}))
        if fs.rejected:
            rows.append(Row("relief_rejected", tuple((r.photo_scale, round(t.mc_max))
                                                     for r, t in fs.rejected), unit="scale"))
    rows.append(Row("probability", (rec.recognition_probability,), digits=2,
                    flags=frozenset({"over_relief"}) if over_relief else frozenset()))
    rows.append(Row("frame_megabytes", (rec.frame_megabytes,), unit="mb", digits=0))
    if fs.frames is not None:
        rows += [Row("frames", (fs.frames,), digits=0), Row("strips", (fs.strips,), digits=0),
                 Row("scanned_gb", (fs.scanned_gigabytes,), unit="GB", digits=1)]
    rows.append(_reason(fs))
    return Table("spec_film", "spec_title", _COLUMNS, tuple(rows))


def spec_uav(spec: Any) -> Table:
    """The digital camera's headline of a specification (``PlanResult.uav``).

    Parameters
    ----------
    spec : PlanResult
        A specification with a UAV part.

    Returns
    -------
    Table
        One column; the rows ``planned_height_m`` (when given), ``recommended_height_m``
        (None when no height is; fields ``flown``: the highest flown height,
        ``tolerance_pct``, ``lowest``: the lowest flown height, ``over_relief``: both are
        the heights really flown above the ground over relief), ``max_height_m`` (flag
        ``"flat"`` when ``max_height_relief_m`` follows), ``max_flown_height_m`` (when
        known), ``binding`` (with one), ``gsd_m``, ``gsd_cm``, ``ground_resolution_m``
        (over relief ``gsd_m`` and ``ground_resolution_m`` with field ``at_max``: at the
        highest height flown above the ground),
        ``l_over_gsd``, ``constraints_max_height_m`` (the constraints' maximum above a
        ceiling), ``sigma_z`` (with a height accuracy; fields ``at``, ``required``),
        ``recognition`` (the map object's; fields ``name``, ``name_ru``, ``size_m``),
        ``forward_overlap_pct``, ``side_overlap_pct``, ``base``, ``line_spacing``,
        ``photo_interval`` (inf when hovering), with an area ``photos``, ``strips``,
        ``flight_length_km``, ``flight_time_min`` (None without a speed), with a data
        volume ``data_volume_gb``, ``data_volume_jpeg_gb``; then ``max_exposure_s``,
        ``max_speed_ms`` and ``reason`` (as :func:`spec_film`'s).
    """
    u = spec.uav
    p = u.job.plan
    h, inp, fl = p.heights_m, p.inputs, p.flight
    rows = [] if u.planned_height_m is None else [
        Row("planned_height_m", (u.planned_height_m,), unit="m", digits=0)]
    rows.append(Row("recommended_height_m", (u.recommended_height_m,), unit="m", digits=0,
                    fields={"flown": h["max"], "tolerance_pct": inp.height_tolerance_up_pct,
                            "lowest": h["min"], "over_relief": p.over_relief}))
    relief = relief_max_height_m(u)
    rows.append(Row("max_height_m", (u.max_height_m,), unit="m", digits=0,
                    flags=frozenset() if relief is None else frozenset({"flat"})))
    if relief is not None:
        rows.append(Row("max_height_relief_m", (relief,), unit="m", digits=0))
    if p.max_flown_height_m is not None:
        rows.append(Row("max_flown_height_m", (p.max_flown_height_m,), unit="m", digits=0))
    if p.binding:
        rows.append(Row("binding", (p.binding,), flags=frozenset({"constraint"})))
    # over relief: also at the highest height really flown above the ground
    top = ({"at_max": p.gsd_at_max_height_m} if p.over_relief else {},
           {"at_max": p.ground_resolution_at_max_height_m} if p.over_relief else {})
    rows += [Row("gsd_m", (p.gsd_m,), unit="m", digits=3, fields=top[0]),
             Row("gsd_cm", (p.gsd_m * 100.0,), unit="cm", digits=2),
             Row("ground_resolution_m", (p.ground_resolution_m,), unit="m", digits=3,
                 fields=top[1]),
             Row("l_over_gsd", (p.ground_resolution_to_gsd,), digits=2)]
    if p.constraints_max_height_m is not None:
        rows.append(Row("constraints_max_height_m", (p.constraints_max_height_m,), unit="m",
                        digits=0))
    if p.height_accuracy:
        acc = p.height_accuracy
        rows.append(Row("sigma_z", (acc["sigma_z_at_highest_flown_height_m"],), unit="m",
                        digits=3, fields={"at": h["max"], "required": acc["height_accuracy_m"],
                                          "over_relief": p.over_relief}))
    rows += _uav_recognition(p)
    rows += _uav_flight(p, fl)
    rows += [Row("max_exposure_s", (p.max_exposure_s,), unit="s"),
             Row("max_speed_ms", (p.max_speed_ms,), unit="ms", digits=1), _reason(u)]
    return Table("spec_uav", "spec_title", _COLUMNS, tuple(rows))


def _uav_recognition(p: Any) -> list[Row]:
    obj = p.inputs.map_object
    if obj is None:
        return []
    rec = next((r for r in p.recognition if r.object == obj.name
                and r.object_size_m == obj.size_m), None)
    if rec is None:
        return []
    return [Row("recognition", (rec.probability,), digits=2,
                fields={"name": obj.name, "name_ru": obj.name_ru, "size_m": obj.size_m})]


def _uav_flight(p: Any, fl: Any) -> list[Row]:
    inp = p.inputs
    rows = [Row("forward_overlap_pct", (inp.forward_overlap_pct,), unit="pct", digits=0),
            Row("side_overlap_pct", (inp.side_overlap_pct,), unit="pct", digits=0)]
    if "base_m" in fl:
        rows += [Row("base", (fl["base_m"],), unit="m", digits=1),
                 Row("line_spacing", (fl["line_spacing_m"],), unit="m", digits=1),
                 Row("photo_interval", (fl["photo_interval_s"],), unit="s",
                     digits=2 if math.isfinite(fl["photo_interval_s"]) else None)]
    if "photos" in fl:
        rows += [Row("photos", (fl["photos"],), digits=0),
                 Row("strips", (fl["strips"],), digits=0),
                 Row("flight_length_km", (fl["flight_length_m"] / 1000,), unit="km", digits=1),
                 Row("flight_time_min", (fl["flight_time_s"] / 60 if fl.get("flight_time_s")
                                         else None,), unit="min", digits=0)]
    if "data_volume_bytes" in fl:
        rows += [Row("data_volume_gb", (fl["data_volume_bytes"] / 1e9,), unit="GB", digits=1),
                 Row("data_volume_jpeg_gb", (fl["data_volume_jpeg_bytes"] / 1e9,), unit="GB",
                     digits=1, fields={"ratio": fl["jpeg_compression_ratio"]})]
    return rows
