"""Flight-line directions a crew would consider over an area (docs/plan-choice.md).

Beside the direction of the least flight length (``"auto"``, :mod:`scanplan.geo.lines`),
a crew lays the lines along the area's long axis — fewer, longer strips, fewer turns — and,
over relief flown one altitude per strip, along the direction whose strips span the least
relief (:mod:`scanplan.geo.terrain_choice`). The long axis is the long side of the area's
minimum-area enclosing rectangle (shapely's ``oriented_envelope``, the rotating-calipers
rectangle of the convex hull: H. Freeman and R. Shapira, "Determining the minimum-area
encasing rectangle for an arbitrary closed curve", *Comm. ACM* 18(7), 409–413, 1975).
"""

from __future__ import annotations

import math

import numpy as np
import shapely

__all__ = ["long_axis_deg", "same_direction"]

SAME_DIRECTION_DEG = 1.0
"""Two directions closer than this are one candidate [°]."""


def long_axis_deg(geometry: object) -> float | None:
    """The direction of the long side of the area's minimum-area enclosing rectangle,
    clockwise from grid north [°, 0–180), as ``[area] direction_deg`` takes it.

    Parameters
    ----------
    geometry : shapely geometry
        The area in its planning CRS.

    Returns
    -------
    float or None
        None for an area without extent (a point, a line of zero length).

    Examples
    --------
    >>> from shapely.geometry import box
    >>> long_axis_deg(box(0, 0, 1000, 200)), long_axis_deg(box(0, 0, 200, 1000))
    (90.0, 0.0)
    """
    rect = shapely.oriented_envelope(geometry)
    if rect.geom_type != "Polygon" or rect.is_empty:
        return None
    xy = np.asarray(rect.exterior.coords, dtype=float)[:3]
    sides = np.diff(xy, axis=0)  # two adjacent sides
    lengths = np.hypot(sides[:, 0], sides[:, 1])
    if not lengths.max() > 0:
        return None
    dx, dy = sides[int(np.argmax(lengths))]
    bearing = math.degrees(math.atan2(dx, dy)) % 180.0  # clockwise from grid north
    return round(bearing, 6) % 180.0


def same_direction(a_deg: float, b_deg: float) -> bool:
    """Whether two line directions are one candidate (within :data:`SAME_DIRECTION_DEG`,
    modulo 180°).

    >>> same_direction(0.4, 179.8), same_direction(10.0, 12.0)
    (True, False)
    """
    d = abs((a_deg - b_deg + 90.0) % 180.0 - 90.0)
    return d < SAME_DIRECTION_DEG
