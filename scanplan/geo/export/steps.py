"""Terrain following in the mission: a waypoint wherever the altitude steps (issue 12).

In ``[terrain] altitude_mode = "follow"`` the altitude of a strip steps with the ground
(:func:`scanplan.geo.terrain.altitudes_m`): consecutive photos whose ground spans at most
the tolerance share one altitude. A mission that had waypoints only at the ends of the
photographed parts of a strip would fly a straight line between two altitudes and miss
every step between them (too high over a valley, too low over a hill). Here every
photographed part is cut where the altitude steps: the last photo of a run and the first
photo of the next become waypoints at their own altitudes (the mission climbs or descends
over one photo base between them), so the mission holds every altitude the checks assumed.

The layout for the mission only: the KML, GeoJSON and CSV keep the strips as laid out.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..layout import FlightLayout, Strip
from .common import StripPhotos, photos_by_strip

__all__ = ["mission_layout"]

_STEP_M = 1e-6  # an altitude change smaller than this is no step [m]


def mission_layout(layout: FlightLayout) -> FlightLayout:
    """``layout`` with each strip's photographed parts cut at the altitude steps (follow
    mode); any other layout unchanged."""
    if layout.notes.get("altitude_mode") != "follow" or not len(layout.photos):
        return layout
    by_strip = photos_by_strip(layout)
    strips = tuple(_cut(layout, s, by_strip.get(s.number)) for s in layout.strips)
    return replace(layout, strips=strips)


def _cut(layout: FlightLayout, strip: Strip, sp: StripPhotos | None) -> Strip:
    """The strip with its parts (given, or its runs of photos) cut at the altitude steps."""
    if sp is None or not len(sp.order):
        return strip
    ph = layout.photos
    x = np.asarray(ph["x_m"], float)
    y = np.asarray(ph["y_m"], float)
    alt = np.asarray(ph["altitude_m"], float)
    start, end = np.asarray(strip.start_xy_m, float), np.asarray(strip.end_xy_m, float)
    axis = end - start
    length = float(np.hypot(*axis))
    if length <= 0:
        return strip
    axis /= length

    def along_m(px: Any, py: Any) -> Any:  # distance along the strip from its start [m]
        return (px - start[0]) * axis[0] + (py - start[1]) * axis[1]

    along = along_m(x[sp.order], y[sp.order])
    if strip.parts:
        parts = [(tuple(map(float, a)), tuple(map(float, b))) for a, b in strip.parts]
    else:
        parts = [((float(x[sp.order[a]]), float(y[sp.order[a]])),
                  (float(x[sp.order[b]]), float(y[sp.order[b]]))) for a, b in sp.runs]
    out: list[tuple[tuple[float, float], tuple[float, float]]] = []
    for a, b in parts:
        lo, hi = along_m(*a), along_m(*b)
        inside = sp.order[(along >= min(lo, hi) - 0.5) & (along <= max(lo, hi) + 0.5)]
        steps = np.flatnonzero(np.abs(np.diff(alt[inside])) > _STEP_M)
        if not steps.size:
            out.append((a, b))
            continue
        ends = [(float(x[inside[k]]), float(y[inside[k]])) for k in steps]
        starts = [(float(x[inside[k + 1]]), float(y[inside[k + 1]])) for k in steps]
        out += list(zip([a, *starts], [*ends, b], strict=True))
    return replace(strip, parts=tuple(out))
