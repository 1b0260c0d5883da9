"""The flight over the area as the map page and the Strips/Photos sheets show it: what they
need of a plan and of the engine, ready to draw and to write (no words, no number formats).

- :func:`map_terrain` — the photo centres' heights above ground and the photos that break
  a constraint (a :class:`MapTerrain`), or None without ``[terrain]``;
- :func:`ground_known` — whether the ground under each photo is known (a DEM);
- :func:`strip_ends_lonlat` — the strips' start and end as longitude/latitude;
- :func:`photo_columns` — the photo table's columns, in the GIS files' order;
- :func:`map_basemap` — ``[map] basemap`` warped under the map (a file, or the tiles the
  plan fetched); :func:`map_extent` the map's extent; :func:`tile_host` a tile URL's host.

The layouts (:mod:`scanplan.reports.mapview`, :mod:`scanplan.reports.geosheets`) read these
and the :class:`~scanplan.geo.layout.FlightLayout`'s own figures; they import no engine.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ...core.photoscale import height_at_photo_scale_m, photo_scale_at_height

if TYPE_CHECKING:
    from ...geo.layout import FlightLayout

__all__ = ["MapTerrain", "ground_known", "map_basemap", "map_extent", "map_terrain",
           "photo_columns", "strip_ends_lonlat", "tile_host"]


@dataclass(frozen=True)
class MapTerrain:
    """What the map shows of a ``[terrain]`` plan: the photo centres coloured by their height
    above ground, and the photos that break a constraint marked.

    Attributes
    ----------
    agl_m : ndarray
        Height above ground of every photo (the layout's order) [m].
    too_high : ndarray of bool
        Photos above the maximum planned height (resolution / interpretation fail).
    overlap_short : ndarray of bool
        Photos whose forward or side overlap falls below the planned one.
    limit_m : float or None
        The maximum planned height [m] and ``cid`` the constraint that sets it.
    highlight : int or None
        Running number of the photo to mark (the worst photo, the binding frame).
    highlight_key : str
        Its legend label.
    scale_of_height, height_of_scale : callable or None
        Film: the local photo scale denominator at a height above ground [m] and its
        inverse (the colour bar's second axis), from the camera's focal length.
    agl_range_m : (float, float) or None
        The colour bar's span [m]: the heights a range of ground elevations allows.
    """

    agl_m: np.ndarray
    too_high: np.ndarray
    overlap_short: np.ndarray
    limit_m: float | None = None
    cid: str = ""
    highlight: int | None = None
    highlight_key: str = "map_legend_worst_photo"
    scale_of_height: Callable[[Any], Any] | None = None
    height_of_scale: Callable[[Any], Any] | None = None
    agl_range_m: tuple[float, float] | None = None


def map_terrain(spec: Any, kind: str, layout: FlightLayout) -> MapTerrain | None:
    """The :class:`MapTerrain` of a layout of ``spec`` (None when its plan has no
    ``[terrain]``, i.e. the layout's notes name no altitude mode, or no known ground)."""
    ph = layout.photos
    if "altitude_mode" not in layout.notes or len(ph) == 0 or "agl_m" not in ph.columns:
        return None
    if not ground_known(spec, kind):
        return None  # one height above ground for every photo: no colours to tell apart
    agl = np.asarray(ph["agl_m"], dtype=float)
    none = np.zeros(agl.size, dtype=bool)
    if kind == "film":
        return _film_terrain(spec, agl, none)
    uav = getattr(spec, "uav", None)
    tr = getattr(uav, "terrain", None)
    if uav is None or tr is None:
        return MapTerrain(agl, none, none)
    plan = uav.job.plan
    limit = plan.max_height_m
    high = agl > limit + 1e-6 if limit is not None else none
    short = none
    cols = ph.columns
    if "forward_overlap_pct" in cols and "side_overlap_pct" in cols:
        with np.errstate(invalid="ignore"):
            short = ((np.asarray(cols["forward_overlap_pct"], float)
                      < plan.inputs.forward_overlap_pct - 0.05)
                     | (np.asarray(cols["side_overlap_pct"], float)
                        < plan.inputs.side_overlap_pct - 0.05))
    d = tr.summary()
    span = ((d["agl_min_m"], d["agl_max_m"]) if d.get("agl_min_m") is not None
            and d.get("agl_max_m") is not None else None)
    return MapTerrain(agl, high, short, limit_m=limit, cid=plan.binding or "",
                      highlight=tr.worst_resolution_photo or None, agl_range_m=span)


def _film_terrain(spec: Any, agl: np.ndarray, none: np.ndarray) -> MapTerrain:
    """A film layout's :class:`MapTerrain`: the binding frame marked, the local photo
    scales beside the colour bar, its span the heights the ground range allows."""
    film = getattr(spec, "film", None)
    ft = getattr(film, "terrain", None)
    inp = film.job.plan.inputs if film is not None else None
    span = None
    if ft is not None and inp is not None:  # a ground range: the heights it allows
        span = (float(height_at_photo_scale_m(ft.mc_min, inp.focal_mm)),
                float(height_at_photo_scale_m(ft.mc_max, inp.focal_mm)))
    f_mm = inp.focal_mm if inp is not None else None
    return MapTerrain(
        agl, none, none,
        highlight=ft.binding_frame if ft is not None and ft.ground_known else None,
        highlight_key="map_legend_binding_frame",
        scale_of_height=(lambda h: photo_scale_at_height(h, f_mm)) if f_mm else None,
        height_of_scale=(lambda m: height_at_photo_scale_m(m, f_mm)) if f_mm else None,
        agl_range_m=span)


def ground_known(spec: Any, kind: str) -> bool:
    """Whether the ground under each photo of a ``[terrain]`` plan is known (a DEM); with
    only a range of ground elevations every photo is planned over the same ground, and a
    map coloured by height above ground showed every frame in one colour."""
    if kind == "film":
        ft = getattr(getattr(spec, "film", None), "terrain", None)
        return ft is None or bool(getattr(ft, "ground_known", True))
    tr = getattr(getattr(spec, "uav", None), "terrain", None)
    return tr is None or tr.summary().get("source") == "dem"


def strip_ends_lonlat(layout: FlightLayout) -> np.ndarray | None:
    """The start and end of every strip as (longitude, latitude) [°], shape
    ``(strips, 2, 2)``; None for an area without a coordinate system (an abstract
    width × length block)."""
    if not layout.area.georeferenced:
        return None
    from ...geo.export.common import lonlat

    ends = np.array([[s.start_xy_m, s.end_xy_m] for s in layout.strips],
                    float).reshape(-1, 2)
    if not len(ends):
        return np.zeros((0, 2, 2))
    return np.asarray(lonlat(layout).points(ends), float).reshape(-1, 2, 2)


def map_basemap(spec: Any, layout: FlightLayout, kind: str = "uav") -> Any:
    """The background of a layout's map in its planning CRS, or None without one: the
    tiles the plan fetched for job ``kind`` (``[map] basemap`` as a tile URL,
    :mod:`scanplan.project.background`), else ``[map] basemap`` as a file, read here
    (:func:`scanplan.geo.basemap.read_basemap`)."""
    if not layout.area.georeferenced:
        return None
    fetched = (getattr(spec, "backgrounds", None) or {}).get(kind)
    if fetched is not None:
        return fetched
    project = getattr(spec, "project", None)
    path = getattr(getattr(project, "map", None), "basemap", None)
    if path is None:
        return None
    from ...geo.basemap import layout_extent_lonlat, read_basemap

    return read_basemap(path, str(layout.area.plan_crs), max_px=1600,
                        area_lonlat=layout_extent_lonlat(layout))


def map_extent(layout: FlightLayout) -> tuple[float, float, float, float]:
    """The map's extent in the planning CRS [m]: the area, its strips and the take-off
    point (:func:`scanplan.geo.basemap.layout_extent`)."""
    from ...geo.basemap import layout_extent

    return layout_extent(layout)


def tile_host(url: str) -> str:
    """The host of a tile URL template, as the map's note names it
    (:func:`scanplan.geo.tiles.template_host`)."""
    from ...geo.tiles import template_host

    return template_host(url)


def photo_columns(layout: FlightLayout) -> list[str]:
    """The columns of the layout's photo table that hold values, in the order of the GIS
    files (:func:`scanplan.geo.export.gis.photo_columns`)."""
    from ...geo.export.gis import photo_columns as columns

    return list(columns(layout.photos))
