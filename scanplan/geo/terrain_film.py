"""Film frames over the relief: the local photo scale of every frame (issue 12, item 3).

The aircraft flies the planned photo scale Mc over the reference ground of the altitude
mode (the highest, see :mod:`scanplan.geo.terrain`): A = g_ref + f·Mc. A frame over ground g
then has the local photo scale Mc = (A − g)/f — the photo scale of a vertical photo,
Mc = H/f with H the height above *that* ground (formulas.md §2 and §4, "A = Mc/(2R) with
Mc = H/f"; the Instruction's photo scale is the scale at the ground, which relief changes
across a block). Every film constraint but P_R
needs a finer pixel at a larger Mc (P_S, P_Z, P_P and P_D all fall as Mc grows; P_R does
not depend on Mc), so the frame over the lowest ground — the smallest local photo scale,
the largest Mc — binds: the scan pixel of the whole block is the engine's at that Mc
(:func:`scanplan.rules.terrain.film_at_worst_frame`).

:func:`frame_scales` gives every frame its altitude and local Mc and finds the frame with
the largest; :func:`scanplan.project.terraincheck.film_terrain` makes the
:class:`FilmTerrain` of them; :func:`frames_over_terrain` writes the per-frame ground,
altitude, height above ground and scanned ground pixel into the flight scheme (the exports
and the map read them from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray

from ..core.photoscale import (
    height_at_photo_scale_m,
    photo_scale_at_height,
    scanned_ground_pixel_cm,
)
from ..i18n.messages import PlanWarning
from .layout import FlightLayout, Photos
from .terrain import ALTITUDE_FRAME, DEFAULT_FOLLOW_TOLERANCE_M, Ground, strip_order, worst_ground

__all__ = ["FilmTerrain", "FrameScales", "frame_scales", "frames_over_terrain"]


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


@dataclass(frozen=True)
class FrameScales:
    """Every frame's altitude and local photo scale, in strip order (:func:`frame_scales`).

    Attributes
    ----------
    order : ndarray
        The layout's photo indices in strip order.
    ground_m : ndarray
        Ground under each frame's centre [m] (NaN where unknown).
    altitude_m : ndarray
        The altitude of the mode [m].
    mc : ndarray
        Local photo scale denominators, Mc = (A − g)/f over the lowest ground under each
        footprint.
    mc_min : float
        The largest local photo scale (over the highest ground under the path).
    worst : int
        Index (strip order) of the frame with the largest Mc.
    """

    order: NDArray[np.int64]
    ground_m: NDArray[np.float64]
    altitude_m: NDArray[np.float64]
    mc: NDArray[np.float64]
    mc_min: float
    worst: int


def frame_scales(layout: FlightLayout, ground: Ground, *, photo_scale: float, focal_mm: float,
                 mode: str = "constant",
                 follow_tolerance_m: float = DEFAULT_FOLLOW_TOLERANCE_M) -> FrameScales:
    """The altitude and local photo scale of every frame.

    The aircraft flies the planned Mc over the reference ground (the highest, by the
    altitude mode): A = g_ref + f·Mc (:func:`scanplan.core.photoscale.height_at_photo_scale_m`).
    A frame over ground g has Mc = (A − g)/f
    (:func:`scanplan.core.photoscale.photo_scale_at_height`), g the lowest ground under its
    footprint (:func:`scanplan.geo.terrain.worst_ground`).
    """
    ph = layout.photos
    n = len(ph)
    order = strip_order(ph)
    g = ground.centre_m[order] if ground.centre_m.size == n else np.full(n, np.nan)
    h_m = float(height_at_photo_scale_m(photo_scale, focal_mm))
    cols = {k: np.asarray(ph[k])[order] for k in ("photo", "strip", "x_m", "y_m")}
    wg = worst_ground(layout, ground, cols, g, mode, h_m, follow_tolerance_m,
                      _per_m(layout.footprint_across_m, h_m),
                      _per_m(layout.footprint_along_m, h_m))
    g_res, g_alt, alt = wg.footprint_low_m, wg.path_high_m, wg.altitude_m
    mc = photo_scale_at_height(alt - g_res, focal_mm)
    mc_lo = float(photo_scale_at_height(alt - g_alt, focal_mm).min()) if n else photo_scale
    i = int(np.argmax(mc)) if n else 0
    return FrameScales(order, g, alt, mc, mc_lo, i)


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
                gsd_cm=scanned_ground_pixel_cm(pixel_um, ft.mc))
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
