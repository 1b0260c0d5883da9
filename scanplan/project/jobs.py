"""The Python API: plan a film scan from names and numbers a surveyor knows.

>>> from scanplan import scan
>>> plan = scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
...             camera="afa-te-100")
>>> plan.scenarios[0].binding, round(plan.scenarios[0].scan_pixel_um, 1)
('PD', 11.1)

Errors are :class:`scanplan.errors.InputError` whose ``field`` is the argument name.
"""

from __future__ import annotations

import functools
import math
import numbers
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from ..core.domains import DOMAINS, MAX_LIST_ITEMS, check_domain
from ..core.mtf import DEFAULT_HAZE_CONTRAST, DEFAULT_K0
from ..errors import InputError
from ..geo.area import rectangle_area
from ..geo.layout import Area, FlightLayout
from ..i18n.messages import Message, Names
from ..norms import DEFAULT_NORM_SET, MapObject, NormSet, load_norm_set, parse_scale
from ..norms.schema import GSD_AREAS, ORIENTATIONS, PARAMETERS
from ..norms.store import GsdLimit
from ..rules.film import ObjectSpec, ScanInputs, ScanPlan, ScanRules, plan_scan
from ..rules.uav import UavInputs, UavPlan, plan_uav, with_curves
from .flightplan import LayoutOptions, uav_layout, with_layout
from .inputs import by_key, defaults, get, records

_FILM = defaults("film")  # the input registry's defaults (scanplan.project.inputs)
_UAV = defaults("uav")

HEIGHT_STEP_M = 5.0
"""Recommended flight heights are rounded down to this step [m]."""
PROVISIONAL_HEIGHT_M = 100.0
"""Height of the first pass when the planned height is to be derived [m]."""


def height_step_m(max_height_m: float) -> float:
    """The step a recommended height is rounded down to: 5 m, or 1 m below 5 m [m]."""
    return HEIGHT_STEP_M if max_height_m >= HEIGHT_STEP_M else 1.0


def recommended_height_m(max_height_m: float | None) -> float | None:
    """The maximum planned height rounded down to :func:`height_step_m`; None below 1 m."""
    if max_height_m is None or max_height_m < 1.0:
        return None
    step = height_step_m(max_height_m)
    return math.floor(max_height_m / step) * step

__all__ = ["USER_OBJECT_NAME", "ScanJob", "UavJob", "object_display_name", "parse_area_m",
           "parse_frame_mm", "resolve_object", "scan", "scan_job", "uav_job"]


@dataclass(frozen=True)
class ScanJob:
    """A computed scan plan together with the norm set it used."""

    plan: ScanPlan
    norm_set: NormSet


def parse_frame_mm(text: object, field: str = "frame_mm") -> tuple[float, float]:
    """``"230x230"`` (across × along track, mm) → (230.0, 230.0)."""
    return _parse_sides(text, field, "WIDTHxHEIGHT", "mm", "230x230")


def parse_area_m(text: object, field: str = "area_m") -> tuple[float, float]:
    """``"2000x3000"`` (block width across × length along the flight lines, m) →
    (2000.0, 3000.0); an error names the sides in metres, as the block is given."""
    return _parse_sides(text, field, "WIDTHxLENGTH", "m", "2000x3000")


def _parse_sides(text: object, field: str, form: str, unit: str,
                 example: str) -> tuple[float, float]:
    """Two sides written ``AxB`` (or a pair) → floats > 0, in ``unit``."""
    if isinstance(text, tuple | list) and len(text) == 2:
        parts = [str(x) for x in text]
    else:
        parts = str(text).lower().replace("×", "x").replace("*", "x").split("x")
    try:
        w, h = (float(p.strip().replace(",", ".")) for p in parts)
    except ValueError:
        raise InputError(
            field, f"must be {form} in {unit}, e.g. {example} (got {text!r})") from None
    if not (w > 0 and h > 0 and w < float("inf") and h < float("inf")):
        raise InputError(field, f"sides must be finite numbers > 0 {unit} (got {text!r})")
    return w, h


def _scale(value: object, field: str) -> float:
    """A scale denominator (``2000`` or ``"1:2000"``) within its domain; ``field`` is
    ``map_scale`` or ``photo_scale``."""
    denominator = parse_scale(value, field)
    check_domain(field, denominator)
    return denominator


USER_OBJECT_NAME = Names("object of the given size", "объект заданного размера")
"""The name of a project's own object when the project does not name it (the reports'
label ``obj_unnamed``)."""


def object_display_name(ns: NormSet, name: str, size_m: float, map_scale: int | None,
                        locale: str) -> str:
    """An object's name in a report's language.

    A norm-table row gives its Russian name; a project's own object keeps the name the
    project gave it (in its writer's language); an unnamed one is
    :data:`USER_OBJECT_NAME` in ``locale``.

    Parameters
    ----------
    ns : NormSet
        The norm set whose ``objects`` table names the rows.
    name, size_m, map_scale
        The object's (English) name, size [m] and, for a norm row, its map scale.
    locale : str
        ``"en"`` or ``"ru"``.
    """
    if map_scale is None and name == USER_OBJECT_NAME["en"]:
        return USER_OBJECT_NAME.get(locale, name)
    if locale != "ru":
        return name
    for o in ns.objects:
        if o.name == name and o.size_m == size_m and (map_scale is None
                                                      or o.map_scale == map_scale):
            return o.name_ru or name
    return name


def resolve_object(
    ns: NormSet,
    map_scale: float,
    *,
    object_size_m: float | None = None,
    shape: str | None = None,
    object_name: str | None = None,
) -> ObjectSpec | None:
    """The object the interpretation constraint protects.

    The user's size wins (named ``object_name``, else :data:`USER_OBJECT_NAME`);
    otherwise the norm set's smallest object for exactly this map scale (seed 001
    Table 3; the conventional signs for 1:1000 and 1:500). With neither, None (the engine
    then asks for a size if P_D is enabled — never a guess).
    """
    norm_obj = ns.object_for(map_scale)
    if object_name is not None and object_size_m is None:
        raise InputError("object_size_m", "give the size of the named object in m (> 0) "
                         "with its name")
    if object_size_m is not None:
        check_domain("object_size_m", object_size_m)
        shape_id = shape if shape is not None else (
            norm_obj.shape if norm_obj else ns.parameters["shape"])
        coef = ns.shape_coefficient(shape_id, "shape")
        name = (object_name or "").strip()
        en, ru = (name, name) if name else (USER_OBJECT_NAME["en"], USER_OBJECT_NAME["ru"])
        return ObjectSpec(en, float(object_size_m), shape_id, coef,
                          Message("object_source.user"),
                          name_ru=ru,
                          shape_ru=ns.shape_rows.get(shape_id, {}).get("name_ru", ""))
    if norm_obj is None:
        return None
    return norm_object_spec(ns, norm_obj, shape)


def norm_object_spec(ns: NormSet, obj: MapObject, shape: str | None = None) -> ObjectSpec:
    """An :class:`ObjectSpec` for a row of the norm set's ``objects`` table."""
    shape_id = shape if shape is not None else obj.shape
    return ObjectSpec(obj.name, obj.size_m, shape_id, ns.shape_coefficient(shape_id, "shape"),
                      Message("object_source.norm", name=ns.name, map=obj.map_scale,
                              source=obj.source),
                      map_scale=obj.map_scale, name_ru=obj.name_ru,
                      shape_ru=ns.shape_rows.get(shape_id, {}).get("name_ru", ""),
                      status=obj.status)


def recognition_rows(ns: NormSet, map_scale: float | None) -> list[MapObject]:
    """The norm objects a UAV recognition table lists: those of the map scale; without a
    map scale, every object once (the same name and size at two map scales is one row).

    Parameters
    ----------
    ns : NormSet
        The norm set.
    map_scale : float or None
        Mk of the plan [-].
    """
    if map_scale is not None:
        return [o for o in ns.objects if o.map_scale == map_scale]
    seen: set[tuple[str, float, str]] = set()
    rows = []
    for o in ns.objects:
        key = (o.name, o.size_m, o.shape)
        if key not in seen:
            seen.add(key)
            rows.append(o)
    return rows


def in_domains(plan: str, values: dict[str, Any]) -> None:
    """Every number of ``values`` (keyword → value of a job of ``plan``) within the domain
    of its input record (:class:`~scanplan.errors.InputError` naming the keyword and the
    range): an input's range is checked from its record, whichever engine reads it."""
    for name, value in values.items():
        if (value is None or isinstance(value, bool) or not isinstance(value, numbers.Real)
                or name not in _NUMERIC[plan]):
            continue
        check_domain(name, value, _NUMERIC[plan][name])


def _numeric_domains(plan: str) -> dict[str, str]:
    """The Python name → domain key of every numeric input of ``plan`` (the record
    :func:`~scanplan.project.inputs.get` gives: the plan's own section over a shared one)."""
    own = (get(name, plan) for name in dict.fromkeys(r.name for r in records(plan)))
    return {r.name: r.domain for r in own if r.kind in ("number", "int") and r.domain in DOMAINS}


_NUMERIC = {plan: _numeric_domains(plan) for plan in ("film", "uav")}
"""Per plan: the Python name → domain key of every numeric input (:func:`in_domains`)."""


def scan_job(
    *,
    map_scale: object,
    relief_interval_m: float,
    photo_scales: Iterable[object],
    camera: str | None = None,
    camera_name: str | None = None,
    focal_mm: float | None = None,
    frame_mm: object | None = None,
    resolving_power_lpmm: float | None = None,
    forward_overlap_pct: float | None = None,
    norms: str | os.PathLike[str] = DEFAULT_NORM_SET,
    object_size_m: float | None = None,
    shape: str | None = None,
    object_name: str | None = None,
    probability: float | None = None,
    height_formula: str | None = None,
    pr_coefficient: float | None = None,
    recognition_rounding: str | None = None,
    scanner: str | None = None,
    bands: int = _FILM["bands"],
    bits_per_band: int = _FILM["bits_per_band"],
    pixel_um: Iterable[float] = (),
) -> ScanJob:
    """Like :func:`scan`, returning the norm set too (for reports)."""
    in_domains("film", locals())
    ns = load_norm_set(norms)
    mk = _scale(map_scale, "map_scale")
    if isinstance(photo_scales, str | bytes) or not isinstance(photo_scales, Iterable):
        raise InputError("photo_scale", f"must be a list of scales (got {photo_scales!r})")
    scales = tuple(_scale(s, "photo_scale") for _, s in zip(range(MAX_LIST_ITEMS + 1),
                                                            photo_scales, strict=False))
    if len(scales) > MAX_LIST_ITEMS:
        raise InputError("photo_scale", f"more than {MAX_LIST_ITEMS} photo scales; give at "
                         f"most {MAX_LIST_ITEMS} candidates")
    if camera is not None:
        cam = ns.camera(camera, "camera")
        if cam.kind != "film":
            raise InputError("camera", f"{camera!r} is a digital camera, not a film one: "
                             "give a film camera (scanplan cameras list), or plan it as a "
                             "digital camera (a project's [uav] camera, scanplan uav --camera, "
                             "scanplan init --kind uav --uav-camera)")
        f = focal_mm if focal_mm is not None else cam.focal_mm
        w, h = (parse_frame_mm(frame_mm) if frame_mm is not None
                else (cam.sensor_width_mm, cam.sensor_height_mm))
        r = resolving_power_lpmm if resolving_power_lpmm is not None else cam.resolving_power_lpmm
    else:
        if focal_mm is None or frame_mm is None:
            raise InputError("camera", "give a catalogue camera id, or both the focal length "
                             "and the frame size (scanplan cameras list)")
        f = focal_mm
        w, h = parse_frame_mm(frame_mm)
        r = resolving_power_lpmm
    if r is None:
        raise InputError("resolving_power_lpmm", "the photo's resolving power R is needed "
                         "(lines/mm > 0, typically 25–60 for aerial film)")
    overrides = {"probability": probability, "height_formula": height_formula,
                 "pr_coefficient": pr_coefficient, "recognition_rounding": recognition_rounding}
    _check_overrides(overrides)
    rules = ns.rules(**overrides)
    obj = resolve_object(ns, mk, object_size_m=object_size_m, shape=shape,
                         object_name=object_name)
    if obj is None and "PD" in rules.constraints:
        raise _no_norm_object(ns, mk)
    steps = ns.scanner_steps(scanner, "scanner") if scanner is not None else ()
    overlap = (forward_overlap_pct if forward_overlap_pct is not None
               else rules.standard_forward_overlap_pct)
    inputs = ScanInputs(
        map_scale=mk, relief_interval_m=relief_interval_m, photo_scales=scales, focal_mm=f,
        frame_width_mm=w, frame_along_mm=h, resolving_power_lpmm=r,
        forward_overlap_pct=overlap, object=obj, camera=camera or "", scanner=scanner or "",
        camera_name=_camera_name(camera_name, None if camera is None else cam),
        scanner_steps_um=steps, bands=bands, bits_per_band=bits_per_band,
        candidate_pixels_um=_at_most(pixel_um, "pixel_um", "scan pixels"))
    return ScanJob(plan_scan(inputs, rules), ns)


def scan(**kwargs: object) -> ScanPlan:
    """Plan the scanning of film photos for a map: every constraint at each photo scale.

    Parameters
    ----------
    map_scale : int, float or str
        Map scale denominator Mk (``2000`` or ``"1:2000"``).
    relief_interval_m : float
        Relief (contour) interval h_c [m].
    photo_scales : iterable
        Photo scale denominators Mc to evaluate.
    camera : str, optional
        Catalogue camera id (``scanplan cameras list``); or give ``focal_mm`` and
        ``frame_mm`` (``"230x230"``, across × along track).
    resolving_power_lpmm : float, optional
        R of the photos [lines/mm] (default: the camera's catalogue value).
    forward_overlap_pct : float, optional
        Forward overlap [%] (default: the norm set's standard, 60 %).
    norms : str or path
        Norm set name or folder (default ``gkinp-02-036-02``).
    object_size_m, shape, probability : optional
        The object to interpret (default: the norm set's smallest object for the map scale).
    height_formula, pr_coefficient, recognition_rounding : optional
        Norm parameter overrides.
    scanner : str, optional
        Scanner id: round the scan pixel down to its steps.
    bands, bits_per_band : int
        For the data volume of a scanned frame.
    pixel_um : iterable of float
        Scan pixels [µm] to answer "what is the smallest photo scale this pixel supports"
        (the scanner's steps are always answered).

    Returns
    -------
    ScanPlan
    """
    return scan_job(**kwargs).plan  # type: ignore[arg-type]


UAV_DEFAULTS = {r.name: r.default for r in records("uav") if r.by_carrier}
"""Flight defaults for a camera on a UAV (the input registry's; docs/project-file.md)."""
AIRCRAFT_SIDE_OVERLAP_PCT: float = by_key("film", "side_overlap_pct").default
"""Side overlap for a camera on a manned aircraft, as for film (the specification's film
default)."""


@dataclass(frozen=True)
class UavJob:
    """A computed UAV plan together with the norm set it used, and its flight layout over
    the area (None without an area)."""

    plan: UavPlan
    norm_set: NormSet
    layout: FlightLayout | None = None
    limits: UavPlan | None = field(default=None, repr=False, compare=False)
    """The plan before the layout (``plan`` without an area): the limits, the same for
    every direction and layout at this height (:func:`uav_job`'s ``limits``)."""


def _airspace(ceiling_m: float | None) -> dict[str, Any]:
    """The conditions of flights without an airspace-use permission, from the data of
    :mod:`scanplan.norms.airspace` (none for a project's own ceiling or an aircraft)."""
    if ceiling_m is None:
        return {}
    return dict(_airspace_worded(ceiling_m))


@functools.lru_cache(maxsize=16)
def _airspace_worded(ceiling_m: float) -> dict[str, Any]:
    """:func:`_airspace` at a ceiling, worded once (the bundled conditions do not change
    while scanplan runs)."""
    from ..norms.airspace import airspace_conditions

    conds = airspace_conditions()
    ceiling = f"{ceiling_m:g}"
    return {"airspace_conditions": Names(
        "; ".join(c.text_en.replace("{ceiling}", ceiling) for c in conds),
        "; ".join(re.sub(r"(\d) (км|м|кг)\b", "\\1\u00a0\\2",
                         c.text_ru.replace("{ceiling}", ceiling)) for c in conds)),
        "airspace_wording": max(c.wording_date for c in conds)}


def uav_job(
    *,
    height_m: float | None = None,
    camera: str | None = None,
    camera_name: str | None = None,
    pixel_um: float | None = None,
    focal_mm: float | None = None,
    sensor_mm: object | None = None,
    f_number: float | None = None,
    speed_ms: float | None = None,
    exposure_s: float = _UAV["exposure_s"],
    forward_overlap_pct: float | None = None,
    side_overlap_pct: float | None = None,
    height_tolerance_pct: float = _UAV["height_tolerance_pct"],
    map_scale: object | None = None,
    relief_interval_m: float | None = None,
    norms: str | os.PathLike[str] = DEFAULT_NORM_SET,
    object_size_m: float | None = None,
    shape: str | None = None,
    object_name: str | None = None,
    probability: float | None = None,
    height_formula: str | None = None,
    r_max: float = _UAV["r_max"],
    r_min: float = _UAV["r_min"],
    threshold_k0: float | None = _UAV["threshold_k0"],
    haze_contrast: float | None = _UAV["haze_contrast"],
    shift_factor: float = _UAV["shift_factor"],
    random_speed_ms: float = _UAV["random_speed_ms"],
    roll_rate_rad_s: float = _UAV["roll_rate_rad_s"],
    pitch_rate_rad_s: float = _UAV["pitch_rate_rad_s"],
    yaw_rate_rad_s: float = _UAV["yaw_rate_rad_s"],
    area_m: object | None = None,
    roll_deg: float = _UAV["roll_deg"],
    pitch_deg: float = _UAV["pitch_deg"],
    orientation: str | None = None,
    max_height_m: float | None = None,
    gsd_cm: float | None = None,
    gsd_area: str = _UAV["gsd_area"],
    parallax_error_px: float | None = None,
    gsd_limit_reason: str | None = None,
    area: Area | None = None,
    layout_options: LayoutOptions | None = None,
    flown_band_m: tuple[float, float] | None = None,
    laid_out: FlightLayout | None = None,
    limits: UavPlan | None = None,
    curves: bool = True,
) -> UavJob:
    """Plan a UAV flight (see :func:`scanplan.rules.uav.plan_uav`); names as the CLI options.

    A catalogue ``camera`` gives pixel, focal length, sensor, image size, f-number and
    minimum trigger interval; explicit values override it. ``map_scale`` with
    ``relief_interval_m`` adds the norm set's constraints and the maximum flight height.
    Defaults (the input registry's, :mod:`scanplan.project.inputs`) for a UAV camera:
    :data:`UAV_DEFAULTS`. A camera carried by an
    aircraft (catalogue ``platform = aircraft``) needs the ground speed, and its overlaps
    default to the norm set's standard forward overlap (the Instruction's 60 %) and 30 %
    side overlap, as for film.
    ``orientation`` (``"landscape"``: sensor width across track, or ``"portrait"``;
    default the catalogue's, else landscape) turns the frame for footprint, base and
    spacing; the pitch of a catalogue camera is sensor width / image width.
    ``max_height_m`` is the altitude ceiling for the highest flown height (default for a
    UAV: the norm set's ``uav_max_height_m``; none for a camera on a manned aircraft, which
    flies 1,000–5,000 m under its own clearance); ``gsd_cm`` a target GSD the flight must
    deliver. ``gsd_area`` (``"general"``, the default, or ``"dense_urban"``) picks the row
    of the norm set's GSD limits per plan scale (constraint GL, ГОСТ Р 59562-2021 Table Б.1).
    ``area`` (a polygon, :mod:`scanplan.geo.area`) or ``area_m`` (the ``WxL`` block) lays
    the strips and photo centres out (``layout_options``: direction, turns, sorties); the
    flight figures (strips, photos, length, time, data volume) come from that layout.
    Without ``height_m`` the flight is planned at the maximum planned height, rounded
    down to :data:`HEIGHT_STEP_M` (needs a map scale or a target GSD). ``flown_band_m``:
    over relief, the lowest and highest heights above the ground really flown [m]
    (:func:`scanplan.rules.uav.plan_uav`); ``laid_out``: the layout of this very plan
    already laid out over ``area`` (the plan restated at those heights keeps it);
    ``limits``: the plan of these very inputs solved before (:attr:`UavJob.limits` of a job
    at this height along another direction), used instead of solving it again;
    ``curves=False``: the plan without its curves for plots (a plan whose limits or figures
    alone are asked; :func:`scanplan.rules.uav.with_curves` adds them).

    Long because: its keyword arguments (one per input of the registry) and this
    docstring; the work is in named steps: :func:`_carrier_defaults`,
    :func:`_digital_frame`, :func:`_map_constraints`, then the engine.
    """
    in_domains("uav", locals())
    if height_m is None:
        if map_scale is None and gsd_cm is None:
            raise InputError("height_m", "give the planned flight height (m ≥ 1), a target "
                             "GSD, or a map scale to derive it from")
        kw = dict(locals())
        if area_m is not None:
            parse_area_m(area_m, "area_m")  # refused before the heights, as it was
        # the limits do not depend on the area: the strips are laid out at the height chosen
        first = uav_job(**{**kw, "height_m": PROVISIONAL_HEIGHT_M, "area": None,
                           "area_m": None})
        rec = recommended_height_m(first.plan.max_height_m)
        if rec is None:
            raise InputError("height_m", "no flight height of 1 m or more meets every limit "
                             f"(maximum {first.plan.max_height_m or 0:.2f} m); give the "
                             "planned height to see the plan")
        if rec == PROVISIONAL_HEIGHT_M and area is None and area_m is None:
            return first
        return uav_job(**{**kw, "height_m": rec})
    ns = load_norm_set(norms)
    cam = ns.camera(camera, "camera") if camera is not None else None
    if cam is not None and cam.kind != "digital":
        raise InputError("camera", f"{camera!r} is a film camera; use `scanplan scan` for "
                         "film, or a digital camera (scanplan cameras list)")
    aircraft = cam is not None and cam.carrier == "aircraft"
    speed_ms, forward_overlap_pct, side_overlap_pct = _carrier_defaults(
        ns, camera, aircraft, speed_ms, forward_overlap_pct, side_overlap_pct)
    frame = _digital_frame(cam, pixel_um, focal_mm, sensor_mm, f_number, orientation)
    mk, rules, map_obj, objects = _map_constraints(
        ns, map_scale, relief_interval_m, probability, height_formula, object_size_m, shape,
        object_name, parallax_error_px)
    if gsd_limit_reason is not None and (not isinstance(gsd_limit_reason, str)
                                         or not gsd_limit_reason.strip()):
        raise InputError("gsd_limit_reason", "must be the reason, as text, for setting the "
                         "recommendation aside")
    gsd_row = None if gsd_limit_reason else _gsd_limit_row(ns, rules, mk, gsd_area)
    area_w = area_l = None
    if area_m is not None:
        area_w, area_l = parse_area_m(area_m, "area_m")
    inputs = UavInputs(
        **frame, height_m=height_m, speed_ms=speed_ms, exposure_s=exposure_s,
        forward_overlap_pct=forward_overlap_pct, side_overlap_pct=side_overlap_pct,
        height_tolerance_up_pct=height_tolerance_pct, camera=camera or "",
        camera_name=_camera_name(camera_name, cam), platform=cam.carrier if cam else "uav",
        lens_table_centre=_lens(ns, camera, "centre"), lens_table_corner=_lens(ns, camera,
                                                                              "corner"),
        min_trigger_interval_s=cam.min_trigger_interval_s if cam else None,
        r_max=r_max, r_min=r_min,
        threshold_k0=threshold_k0 if threshold_k0 is not None else DEFAULT_K0,
        haze_contrast=haze_contrast if haze_contrast is not None else DEFAULT_HAZE_CONTRAST,
        shift_factor=shift_factor, random_speed_ms=random_speed_ms,
        roll_rate_rad_s=roll_rate_rad_s, pitch_rate_rad_s=pitch_rate_rad_s,
        yaw_rate_rad_s=yaw_rate_rad_s, roll_deg=roll_deg, pitch_deg=pitch_deg, map_scale=mk,
        relief_interval_m=relief_interval_m, map_object=map_obj, objects=objects,
        area_width_m=area_w, area_length_m=area_l,
        ceiling_m=float(max_height_m) if max_height_m is not None
        else None if aircraft else float(ns.parameters["uav_max_height_m"]),
        ceiling_from_project=max_height_m is not None,
        aerodrome_distance_km=None if aircraft or max_height_m is not None
        else float(ns.parameters["uav_uncontrolled_aerodrome_km"]),
        **_airspace(None if aircraft or max_height_m is not None
                    else float(ns.parameters["uav_max_height_m"])),
        gsd_target_m=gsd_cm / 100.0 if gsd_cm is not None else None,
        gsd_limit_m=gsd_row.max_gsd_cm / 100.0 if gsd_row else None,
        gsd_limit_area=gsd_row.area if gsd_row else "general",
        gsd_limit_source=gsd_row.source if gsd_row else "")
    if limits is not None and (limits.inputs != inputs
                               or limits.over_relief != (flown_band_m is not None)):
        raise ValueError("uav_job: limits solved for other inputs")  # a caller's mistake
    plan = plan_uav(inputs, rules, flown_band_m, curves=curves) if limits is None \
        else with_curves(limits) if curves else limits
    if area is None and area_w is not None and area_l is not None:
        area = rectangle_area(area_w, area_l)
    if area is None:
        return UavJob(plan, ns, limits=plan)
    layout = laid_out if laid_out is not None else uav_layout(plan, area, layout_options,
                                                              manned=aircraft)
    return UavJob(with_layout(plan, layout), ns, layout, limits=plan)


def _carrier_defaults(ns: NormSet, camera: str | None, aircraft: bool,
                      speed_ms: float | None, forward_overlap_pct: float | None,
                      side_overlap_pct: float | None) -> tuple[float, float, float]:
    """Speed [m/s] and overlaps [%] the caller left out, by carrier: a UAV's
    (:data:`UAV_DEFAULTS`), or for a camera on a manned aircraft the norm set's standard
    forward overlap and :data:`AIRCRAFT_SIDE_OVERLAP_PCT` (its speed is required)."""
    if speed_ms is None:
        if aircraft:
            raise InputError("speed_ms", f"give the aircraft's ground speed in m/s (> 0): "
                             f"{camera!r} is flown on a manned aircraft, and the UAV default "
                             f"{UAV_DEFAULTS['speed_ms']:g} m/s does not apply")
        speed_ms = UAV_DEFAULTS["speed_ms"]
    if forward_overlap_pct is None:
        forward_overlap_pct = (float(ns.parameters["standard_forward_overlap_pct"]) if aircraft
                               else UAV_DEFAULTS["forward_overlap_pct"])
    if side_overlap_pct is None:
        side_overlap_pct = (AIRCRAFT_SIDE_OVERLAP_PCT if aircraft
                            else UAV_DEFAULTS["side_overlap_pct"])
    return speed_ms, forward_overlap_pct, side_overlap_pct


def _digital_frame(cam: Any, pixel_um: float | None, focal_mm: float | None,
                   sensor_mm: object | None, f_number: float | None,
                   orientation: str | None) -> dict[str, Any]:
    """The camera's pixel, focal length, f-number and frame as mounted (``UavInputs``
    fields): the catalogue camera's, each overridden by the value given."""
    if orientation is not None and orientation not in ORIENTATIONS:
        raise InputError("orientation", f"must be one of {', '.join(ORIENTATIONS)} "
                         f"(got {orientation!r})")
    mount = orientation or (cam.orientation if cam else "") or "landscape"
    p = pixel_um if pixel_um is not None else (cam.pixel_um if cam else None)
    f = focal_mm if focal_mm is not None else (cam.focal_mm if cam else None)
    w_px = h_px = None
    if cam is not None:
        _, _, w_px, h_px = cam.frame(mount)
    if sensor_mm is not None:
        w, h = parse_frame_mm(sensor_mm, "sensor_mm")
        if mount == "portrait":
            w, h = h, w
    elif cam is not None:
        w, h, _, _ = cam.frame(mount)
    else:
        w = h = None
    n0 = f_number if f_number is not None else (cam.f_number if cam else None)
    if cam is None and (p is None or f is None or w is None):
        raise InputError("camera", "give a catalogue camera id, or the pixel pitch, focal "
                         "length and sensor size (scanplan cameras list)")
    if n0 is None:
        raise InputError("f_number", f"the camera {cam.id!r} has no f-number in the "
                         "catalogue; give the working f-number (> 0)" if cam is not None
                         else "a camera given by its pixel pitch, focal length and sensor "
                         "size needs its working f-number (> 0)")
    if cam is None or pixel_um is not None or sensor_mm is not None:
        w_px, h_px = _image_px(w, h, p)
    return {"pixel_um": p, "focal_mm": f, "f_number": n0, "sensor_width_mm": w,
            "sensor_height_mm": h, "image_width_px": w_px, "image_height_px": h_px,
            "orientation": mount}


def _camera_name(name: object | None, cam: Any) -> str:
    """The camera's name in the reports: the one given (a camera given by its data), else
    the catalogue's model name."""
    if name is None:
        return cam.name if cam else ""
    if not isinstance(name, str) or not name.strip():
        raise InputError("camera_name", f"must be the camera's name as text (got {name!r})")
    return " ".join(name.split())


def _image_px(width_mm: float | None, height_mm: float | None, pixel_um: float | None
              ) -> tuple[int | None, int | None]:
    """The image size [px] of a sensor ``width_mm × height_mm`` with pixel pitch
    ``pixel_um``: side / pitch, to the nearest whole pixel (the pitch is the distance
    between pixel centres, so a side holds side/pitch pixels — the definition the catalogue
    follows in reverse: pitch = sensor width / image width). None when a value is missing."""
    if width_mm is None or height_mm is None or not pixel_um or pixel_um <= 0:
        return None, None
    return (max(1, round(float(width_mm) * 1000.0 / float(pixel_um))),
            max(1, round(float(height_mm) * 1000.0 / float(pixel_um))))


def _map_constraints(ns: NormSet, map_scale: object | None, relief_interval_m: float | None,
                     probability: float | None, height_formula: str | None,
                     object_size_m: float | None, shape: str | None, object_name: str | None,
                     parallax_error_px: float | None = None
                     ) -> tuple[float | None, ScanRules | None, ObjectSpec | None,
                                tuple[ObjectSpec, ...]]:
    """With a map scale: Mk, the norm set's rules, the map's object; and the objects the
    recognition table lists (those of the map scale; the project's own object first)."""
    rules = None
    mk = None
    map_obj = None
    if map_scale is None and relief_interval_m is not None:  # never silently unused
        raise InputError("relief_interval_m", "goes with the map scale (the map's accuracy "
                         "constraints); give the map scale too")
    if map_scale is not None:
        mk = _scale(map_scale, "map_scale")
        if relief_interval_m is None:
            raise InputError("relief_interval_m", "give the relief interval h_c (m > 0) with "
                             "the map scale")
        _check_overrides({"probability": probability})
        if height_formula is not None:
            spec = PARAMETERS["digital_height_formula"].value
            if not isinstance(height_formula, str) or spec.check(height_formula):
                raise InputError("height_formula", f"must be {spec.describe()} for a digital "
                                 f"camera (got {height_formula!r})")
        if parallax_error_px is not None:
            check_domain("parallax_error_px", parallax_error_px)
        rules = ns.rules(probability=probability, digital_height_formula=height_formula,
                         image_measurement_px=parallax_error_px)
        map_obj = resolve_object(ns, mk, object_size_m=object_size_m, shape=shape,
                                 object_name=object_name)
        if map_obj is None and "PD" in rules.constraints:
            raise _no_norm_object(ns, mk)
    objects = [norm_object_spec(ns, o, shape) for o in recognition_rows(ns, mk)]
    if map_obj is not None and map_obj.map_scale is None:
        objects.insert(0, map_obj)
    return mk, rules, map_obj, tuple(objects)


def _gsd_limit_row(ns: NormSet, rules: object, map_scale: float | None,
                   area: str | None) -> GsdLimit | None:
    """The norm set's GSD limit row for the map scale when the set switches GL on."""
    if area is not None and area not in GSD_AREAS:
        raise InputError("gsd_area", f"must be one of {', '.join(GSD_AREAS)} (got {area!r})")
    if rules is None or map_scale is None or "GL" not in getattr(rules, "constraints", ()):
        return None
    return ns.gsd_limit(map_scale, area or "general")


def _lens(ns: NormSet, camera: str | None, position: str
          ) -> tuple[tuple[float, ...], tuple[float, ...]] | None:
    """The catalogue's lens MTF table of ``camera`` at ``position``, if one is published."""
    curve = ns.lens_mtf.get(camera or "", {}).get(position)
    return (curve.freq_lpmm, curve.mtf) if curve else None


def _at_most(values: Iterable[float], field: str, what: str) -> tuple[float, ...]:
    """The values as a tuple; :class:`InputError` beyond :data:`MAX_LIST_ITEMS` of them."""
    out = tuple(v for _, v in zip(range(MAX_LIST_ITEMS + 1), values, strict=False))
    if len(out) > MAX_LIST_ITEMS:
        raise InputError(field, f"more than {MAX_LIST_ITEMS} {what}; give at most "
                         f"{MAX_LIST_ITEMS}")
    return out


def _check_overrides(overrides: dict[str, object]) -> None:
    for key, value in overrides.items():
        if value is not None:
            try:
                problem = (f"must be {PARAMETERS[key].value.describe()}"
                           if isinstance(value, bool) else PARAMETERS[key].value.check(value))
            except (TypeError, ValueError):
                problem = f"must be {PARAMETERS[key].value.describe()}"
            if problem:
                raise InputError(key, f"{problem} (got {value!r})")


def _no_norm_object(ns: NormSet, mk: float) -> InputError:
    """The map scale has no smallest object in the norm set. Outside the scales the set
    covers the usual mistake is the scale (1:50000 for a set of 1:500 … 1:25000), so the
    error names the map scale and that range; between them (1:3000) the object's size is
    what is missing. Either way it says how to plan it anyway: an object size of one's own."""
    covered = sorted({o.map_scale for o in ns.objects if o.map_scale})
    listing = ", ".join(f"1:{x:g}" for x in covered) or "none"
    inside = bool(covered) and covered[0] <= mk <= covered[-1]
    return InputError("object_size_m" if inside else "map_scale",
                      f"the norm set's smallest objects are for the map scales {listing}, "
                      f"not 1:{mk:g}: plan one of those scales, or give the size of the "
                      "object to interpret in m (> 0)")
