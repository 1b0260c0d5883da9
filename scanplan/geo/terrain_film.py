"""Film frames over the relief: the local photo scale of every frame (issue 12, item 3).

The aircraft flies the planned photo scale Mc over the reference ground of the altitude
mode (the highest, see :mod:`scanplan.geo.terrain`): A = g_ref + f·Mc. A frame over ground g
then has the local photo scale Mc = (A − g)/f — the photo scale of a vertical photo,
Mc = H/f with H the height above *that* ground (formulas.md §2 and §4, "A = Mc/(2R) with
Mc = H/f"; the Instruction's photo scale is the scale at the ground, which relief changes
across a block). Every film constraint but P_R
needs a finer pixel at a larger Mc (P_S, P_Z, P_P and P_D all fall as Mc grows; P_R does
not depend on Mc), so the frame over the lowest ground — the smallest local photo scale,
the largest Mc — binds: the scan pixel of the whole block is the engine's
(:func:`scanplan.rules.film.evaluate`) at that Mc.

:func:`film_terrain` gives every frame its altitude and local Mc, the binding frame and the
scan pixel there; :func:`frames_over_terrain` writes the per-frame ground, altitude, height
above ground and scanned ground pixel into the flight scheme (the exports and the map read
them from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..core.photoscale import (
    height_at_photo_scale_m,
    photo_scale_at_height,
    scanned_ground_pixel_m,
)
from ..messages import Message
from ..rules.results import PlanWarning, ScanRules
from .layout import FlightLayout, Photos
from .terrain import ALTITUDE_FRAME, DEFAULT_FOLLOW_TOLERANCE_M, Ground, _order, worst_ground

__all__ = ["FilmTerrain", "film_terrain", "frames_over_terrain"]


@dataclass(frozen=True)
class FilmTerrain:
    """Film frames under the terrain: the local photo scale of every frame.

    Attributes
    ----------
    photo_scale : float
        The planned Mc, over the reference (highest) ground.
    altitude_m : ndarray
        Per frame [m] (the DEM's height system), in the layout's photo order.
    ground_m : ndarray
        Ground under each frame's centre [m] (NaN where unknown), in the layout's order.
    mc : ndarray
        Local photo scale denominator of every frame, Mc = (A − g)/f (at the lowest
        possible ground where the ground is unknown).
    mc_min, mc_max : float
        The largest and the smallest local photo scale of the block (Mc denominators).
    binding_frame, binding_strip : int
        Running number and strip of the frame with the largest Mc.
    scan_pixel_um : float
        The scan pixel at ``mc_max`` (the enabled constraints' minimum) [µm].
    scan_pixel_planned_um : float
        At the planned Mc, i.e. on flat ground [µm].
    binding : str
        The constraint binding at ``mc_max``.
    binding_planned : str
        The constraint binding at the planned Mc (flat ground).
    ground_known : bool
        True when the ground under the frames came from a DEM (False: only a range).
    ground_low_m : float
        The lowest ground under the frames [m].
    """

    photo_scale: float
    altitude_m: NDArray[np.float64]
    mc: NDArray[np.float64]
    mc_min: float
    mc_max: float
    binding_frame: int
    binding_strip: int
    scan_pixel_um: float
    scan_pixel_planned_um: float
    binding: str
    warnings: tuple[PlanWarning, ...]
    ground_m: NDArray[np.float64] | None = None
    binding_planned: str = ""
    ground_known: bool = True
    ground_low_m: float = math.nan


def local_forward_overlap_pct(rules: ScanRules, forward_overlap_pct: float,
                              photo_scale: float, local_scale: float) -> float:
    """The forward overlap the height constraint sees at a frame of local scale Mc_l [%].

    The exposures are spaced for the planned Mc, so the base on the ground is fixed,
    B = b·Mc, and the image base of a frame at Mc_l is b_l = b·Mc/Mc_l — the overlap
    1 − (1 − p)·Mc/Mc_l (:func:`scanplan.core.flight.actual_overlap_pct` with heights ∝ Mc).
    The parallax form P_Z = V_z·b/(k·Mc·f) takes that local base. The Instruction's form
    P_Z = V_z·f/(k·Mc·b) keeps the planned base, as it is checked as printed: with the
    local one its value would not depend on the local scale at all (Mc_l·b_l = Mc·b).

    Parameters
    ----------
    rules : ScanRules
        ``height_formula`` picks the form.
    forward_overlap_pct : float
        Planned forward overlap p [%].
    photo_scale, local_scale : float
        Planned and local photo scale denominators Mc, Mc_l.

    Returns
    -------
    float
        The overlap for the height constraint at that frame [%].

    Examples
    --------
    >>> from scanplan.norms import load_norm_set
    >>> from dataclasses import replace
    >>> r = replace(load_norm_set().rules(), height_formula="parallax")
    >>> round(local_forward_overlap_pct(r, 60.0, 10000.0, 12000.0), 3)
    66.667
    """
    if rules.height_formula != "parallax":
        return float(forward_overlap_pct)
    from ..core.flight import actual_overlap_pct

    return float(actual_overlap_pct(forward_overlap_pct, photo_scale, local_scale))


def film_terrain(layout: FlightLayout, ground: Ground, rules: ScanRules, *, map_scale: float,
                 photo_scale: float, relief_interval_m: float, focal_mm: float,
                 frame_along_mm: float, forward_overlap_pct: float,
                 resolving_power_lpmm: float, object_size_m: float = math.nan,
                 shape_coefficient: float = math.nan, mode: str = "constant",
                 follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M) -> FilmTerrain:
    """The local photo scale of every frame and the scan pixel at the smallest of them.

    The aircraft flies the planned Mc over the reference ground (the highest, by the
    altitude mode): A = g_ref + f·Mc. A frame over ground g has Mc = (A − g)/f; the frame
    over the lowest ground binds, and the engine (:func:`scanplan.rules.film.evaluate`) is
    run there and at the planned Mc (flat ground, for comparison).
    """
    from ..rules.film import evaluate

    ph = layout.photos
    n = len(ph)
    order = _order(ph)
    strip = np.asarray(ph["strip"])[order].astype(np.int64)
    g = ground.centre_m[order] if ground.centre_m.size == n else np.full(n, np.nan)
    h_m = float(height_at_photo_scale_m(photo_scale, focal_mm))
    cols = {k: np.asarray(ph[k])[order] for k in ("photo", "strip", "x_m", "y_m")}
    wg = worst_ground(layout, ground, cols, g, mode, h_m, follow_tolerance_m,
                      _per_m(layout.footprint_across_m, h_m),
                      _per_m(layout.footprint_along_m, h_m))
    g_res, g_alt, alt = wg.footprint_low_m, wg.path_high_m, wg.altitude_m
    mc = photo_scale_at_height(alt - g_res, focal_mm)
    mc_lo = float(photo_scale_at_height(alt - g_alt, focal_mm).min()) if n else photo_scale
    inverse = np.empty(n, dtype=np.int64)
    inverse[order] = np.arange(n)
    i = int(np.argmax(mc)) if n else 0
    mc_hi = float(mc[i]) if n else photo_scale
    overlap = np.array([forward_overlap_pct, local_forward_overlap_pct(
        rules, forward_overlap_pct, photo_scale, mc_hi)])  # the parallax form's local base
    ev = evaluate(rules, map_scale=map_scale, photo_scale=np.array([photo_scale, mc_hi]),
                  relief_interval_m=relief_interval_m, focal_mm=focal_mm,
                  frame_along_mm=frame_along_mm, forward_overlap_pct=overlap,
                  resolving_power_lpmm=resolving_power_lpmm, object_size_m=object_size_m,
                  shape_coefficient=shape_coefficient)
    pix = np.asarray(ev.scan_pixel_um, dtype=float)
    binds = np.asarray(ev.binding)
    frame = int(np.asarray(ph["photo"])[order][i]) if n else 0
    strip_i = int(strip[i]) if n else 0
    warnings = list(ground.warnings)
    known = ground.dem is not None
    if pix[1] < pix[0] * (1 - 1e-9):
        where = (Message("terrain_film_where.dem", frame=frame, strip=strip_i) if known
                 else Message("terrain_film_where.range", low=ground.low_m))
        warnings.append(PlanWarning("terrain_film_scale", Message(
            "terrain_film_scale", lo=float(round(mc_lo)), hi=float(round(mc_hi)), where=where,
            pixel=float(pix[1]), planned=float(pix[0]), cid=str(binds[1])),
            severity="info"))
    return FilmTerrain(photo_scale=photo_scale, altitude_m=alt[inverse], mc=mc[inverse],
                       mc_min=mc_lo, mc_max=mc_hi, binding_frame=frame,
                       binding_strip=strip_i, scan_pixel_um=float(pix[1]),
                       scan_pixel_planned_um=float(pix[0]), binding=str(binds[1]),
                       warnings=tuple(warnings), ground_m=g[inverse],
                       binding_planned=str(binds[0]), ground_known=known,
                       ground_low_m=float(ground.low_m))


def _per_m(footprint_m: float, height_m: float) -> float:
    """Footprint side per metre of height above ground (the frame side over f); 0 when the
    layout does not state its footprint (then only the path and centre are looked at)."""
    v = footprint_m / height_m if height_m > 0 else math.nan
    return v if math.isfinite(v) else 0.0


def frames_over_terrain(layout: FlightLayout, ft: FilmTerrain, pixel_um: float,
                        focal_mm: float, mode: str,
                        recognition_p: NDArray[np.float64] | None = None) -> FlightLayout:
    """The flight scheme with every frame's ground, altitude, height above ground and
    scanned ground pixel (``pixel_um`` × local Mc) filled in — and its recognition
    probability at its local scale when given — its notes stating the altitude mode and
    frame (as a UAV terrain layout's)."""
    ph = layout.photos
    if len(ph) == 0 or ft.mc.size != len(ph):
        return layout
    cols = dict(ph.columns)
    agl = height_at_photo_scale_m(ft.mc, focal_mm)
    cols.update(ground_m=(ft.ground_m if ft.ground_m is not None
                          else np.full(len(ph), np.nan)),
                altitude_m=np.asarray(ft.altitude_m, dtype=float), agl_m=agl,
                gsd_cm=scanned_ground_pixel_m(pixel_um, ft.mc) * 100.0)
    if recognition_p is not None:
        cols["recognition_p"] = np.asarray(recognition_p, dtype=float)
    notes = dict(layout.notes)
    notes.update(altitude_mode=mode, altitude_frame=ALTITUDE_FRAME)
    strips = layout.strips
    if mode != "follow":
        alt = np.asarray(ft.altitude_m, dtype=float)
        by = {int(k): float(alt[np.asarray(ph["strip"]) == k].max())
              for k in np.unique(ph["strip"])}
        strips = tuple(replace(s, altitude_m=by.get(s.number)) for s in strips)
    return replace(layout, photos=Photos(cols), strips=strips, notes=notes)
