"""The records the geography layer produces: an area, the strips over it, the photo centres.

These are plain data (numpy arrays and numbers): the project layer puts them in the one
result object that text, JSON, Excel, PDF and the exported files all render. Every photo
centre carries its ground elevation and its height above ground (flat ground: the same
elevation everywhere, AGL = the planned height) so that terrain only fills in two columns.

Coordinates: ``x_m``/``y_m`` in the planning CRS (metric, projected: ``plan_epsg`` or a
WKT for a local system), ``lon_deg``/``lat_deg`` in WGS 84 (EPSG:4326, lon first as in
RFC 7946). An abstract ``width_m × length_m`` block has no georeference: its area is a
rectangle in a local metric frame, ``georeferenced`` is False and the lon/lat are NaN.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["PHOTO_COLUMNS", "Area", "FlightLayout", "LonLatColumns", "Photos", "Sortie", "Strip"]

#: The per-photo columns of :class:`Photos`, with their units (the CSV/GeoJSON/sheet header).
PHOTO_COLUMNS: dict[str, str] = {
    "photo": "running number of the photo in flight order, from 1",
    "strip": "strip number, from 1, in flight order",
    "index": "photo number within its strip, from 1",
    "sortie": "sortie (battery / flight) number, from 1",
    "x_m": "easting in the planning CRS [m]",
    "y_m": "northing in the planning CRS [m]",
    "lon_deg": "longitude, WGS 84 [°]",
    "lat_deg": "latitude, WGS 84 [°]",
    "ground_m": "ground elevation under the photo centre [m]",
    "altitude_m": "flight altitude of the exposure, same height system as ground_m [m]",
    "agl_m": "height above ground at the photo centre [m]",
    "gsd_cm": "ground sampling distance at agl_m [cm]",
    "resolution_cm": "ground resolution L (MTF) at agl_m [cm] (NaN for film)",
    "recognition_p": "probability of recognising the map objects at agl_m [–] (NaN if none)",
}


@dataclass(frozen=True)
class Area:
    """The contract area in the planning CRS.

    Attributes
    ----------
    geometry : shapely.Polygon or shapely.MultiPolygon
        The area in the planning CRS [m] (holes kept).
    plan_crs : str
        The planning CRS as given to pyproj (``"EPSG:32637"``; ``"LOCAL"`` for an abstract
        rectangle).
    source : str
        Where the area came from (file name and feature, ``inline polygon`` or
        ``rectangle W × L m``).
    georeferenced : bool
        False for the abstract ``width_m × length_m`` rectangle.
    area_km2, perimeter_km : float
        Size of the area [km²] and its boundary length [km] in the planning CRS.
    centroid_lonlat : tuple of float or None
        Centroid (lon, lat) in WGS 84 [°]; None when not georeferenced.
    plan_crs_name : str
        The planning CRS's name for reports (``"WGS 84 / UTM zone 37N"``; ``""`` local).
    input_crs : str or None
        The CRS the coordinates were given in (``"EPSG:4326"``); None for a rectangle.
    scale_error_pct : float or None
        The planning projection's largest scale error over the area's vertices,
        ``max |k − 1|`` [%] (pyproj's projection factors; inf where it cannot be
        evaluated); None for a rectangle.
    lon_range_deg : tuple of float or None
        The area's westmost and eastmost longitude [°]; None for a rectangle.
    source_file, source_feature, source_layer : str or None
        The parts of ``source`` for reports in another language: the file, the feature's
        name and its layer (None for an inline polygon or the rectangle).
    """

    geometry: Any
    plan_crs: str
    source: str
    georeferenced: bool
    area_km2: float
    perimeter_km: float
    centroid_lonlat: tuple[float, float] | None = None
    plan_crs_name: str = ""
    input_crs: str | None = None
    source_file: str | None = None
    source_feature: str | None = None
    source_layer: str | None = None
    scale_error_pct: float | None = None
    lon_range_deg: tuple[float, float] | None = None


@dataclass(frozen=True)
class Strip:
    """One flight line: flown from ``start`` to ``end`` (planning CRS [m]).

    ``segments`` > 1 when the line crosses a concave area or a hole several times: the
    strip is flown as one line and the camera is off over the gaps (see
    :mod:`scanplan.geo.lines`, split versus bridge). ``parts`` holds each photographed part
    as (start_xy_m, end_xy_m) in flight order, first to last exposure of the part (the
    trigger-on and trigger-off points); one part when the strip has no gap.
    """

    number: int
    start_xy_m: tuple[float, float]
    end_xy_m: tuple[float, float]
    length_m: float
    photos: int
    first_photo: int  # running number of its first photo
    sortie: int
    segments: int = 1
    altitude_m: float | None = None  # strip altitude (terrain 'strip' mode), else None
    parts: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = ()
    continued: tuple[tuple[int, int], ...] = ()  # (sortie, its first photo) of each later
    # sortie that continues the strip after a battery change mid-strip; () when one
    # sortie flies it all

    @property
    def last_sortie(self) -> int:
        """The sortie that flies the strip's end (:attr:`sortie` unless a later one
        continues it)."""
        return self.continued[-1][0] if self.continued else self.sortie

    @property
    def sorties_text(self) -> str:
        """The sortie, or the sorties ``1–2`` when a battery change falls mid-strip, that
        fly the strip (the strips table, the Strips sheet, the KML)."""
        last = self.last_sortie
        return str(self.sortie) if last == self.sortie else f"{self.sortie}–{last}"


@dataclass(frozen=True)
class Sortie:
    """One flight on one battery: its strips (whole or in part), length and time.

    ``length_m`` includes the run-in and run-out and ``transit_m``, the flight from the
    take-off point to the block and back [m]; ``time_s`` is the time as flown: climb,
    acceleration, the path with its corners, braking and descent
    (:mod:`scanplan.geo.sorties`); ``takeoff_xy_m`` the take-off and landing point in the
    planning CRS (the given one, else the area's boundary point nearest the sortie's
    start; None for an area with no place on the map).
    """

    number: int
    strips: tuple[int, ...]
    length_m: float
    time_s: float | None
    transit_m: float = 0.0
    takeoff_xy_m: tuple[float, float] | None = None


class LonLatColumns(Mapping[str, np.ndarray]):
    """Photo columns whose WGS 84 ``lon_deg``/``lat_deg`` are projected from ``x_m``/``y_m``
    when first read: a compared layout that is not chosen, or a plan nobody exports, never
    pays for them. The values are those an eager projection gives (the same transformer on
    the same numbers); a copy or a pickle holds them computed.

    Parameters
    ----------
    columns : dict of str to ndarray
        The columns of :data:`PHOTO_COLUMNS`; ``lon_deg``/``lat_deg`` left out or None are
        projected when first read.
    plan_crs : str
        The planning CRS of ``x_m``/``y_m``.
    """

    __slots__ = ("_columns", "_plan_crs")
    _LAZY = ("lon_deg", "lat_deg")

    def __init__(self, columns: Mapping[str, np.ndarray], plan_crs: str) -> None:
        self._columns: dict[str, np.ndarray | None] = {
            k: columns.get(k) for k in PHOTO_COLUMNS if k in columns or k in self._LAZY}
        self._plan_crs = plan_crs

    def __getitem__(self, name: str) -> np.ndarray:
        value = self._columns[name]
        if value is None:
            from .crs import transformer

            lon, lat = transformer(self._plan_crs, 4326).transform(
                self._columns["x_m"], self._columns["y_m"])
            # both at once (a reader in another thread computes the same values)
            self._columns.update(lon_deg=np.asarray(lon, dtype=float),
                                 lat_deg=np.asarray(lat, dtype=float))
            value = self._columns[name]
        return value  # type: ignore[return-value]

    def __contains__(self, name: object) -> bool:
        return name in self._columns

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    def __reduce__(self) -> tuple[Any, ...]:
        return dict, (dict(self.items()),)


@dataclass(frozen=True)
class Photos:
    """Photo centres as columns (numpy arrays of one length); see :data:`PHOTO_COLUMNS`."""

    columns: Mapping[str, np.ndarray]

    def __len__(self) -> int:
        first = next(iter(self.columns.values()), None)
        return 0 if first is None else int(first.shape[0])

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]


@dataclass(frozen=True)
class FlightLayout:
    """Flight lines and photo centres over an area (film: the aerial survey's flight scheme).

    Attributes
    ----------
    area : Area
    direction_deg : float
        Flight-line direction, clockwise from grid north of the planning CRS [°], 0 … 180.
    spacing_m, base_m : float
        Line spacing and photo base (trigger distance) [m].
    strips, sorties : tuple
        :class:`Strip` and :class:`Sortie` records in flight order.
    photos : Photos
        Every photo centre.
    flight_length_m : float
        Every sortie's flight: strips, turns, the run-in and run-out at each end and the
        transit from and to the take-off point when one is given [m] (the mission's path,
        :mod:`scanplan.geo.mission`).
    turn_length_m : float
        The turns' share of ``flight_length_m`` [m].
    flight_time_s : float or None
        At the ground speed (None for film or a zero speed).
    extension_bases : float
        How far strips run past the area, in photo bases, at each end.
    feasible : bool
        False when the plan cannot be flown; ``reason`` says why.
    kind : str
        ``"uav"`` or ``"film"`` (the aerial survey's flight scheme; no flight time).
    footprint_across_m, footprint_along_m : float
        Ground footprint of one photo across and along the strip at the planned height [m].
    speed_ms : float or None
        Ground speed the times are computed at [m/s].
    turn : str
        How the turns were counted (``"semicircle"``, ``"turnaround 20 m"``,
        ``"radius 150 m"``), for reports.
    notes : dict
        Extra figures (``bridged_m``: gap length flown with the camera off [m];
        ``candidates``: directions tried by "auto"; a crosshatch's ``pass_transit_m``: the
        flight from the first pass's last photo to the second pass's first).
    cross_direction_deg : float or None
        A crosshatch (double grid): the second pass's line direction, ``direction_deg`` +
        90° [°], 0 … 180; None for one pass.
    first_pass_strips : int or None
        A crosshatch: how many strips the first pass has (strips 1 … n at
        ``direction_deg``, the rest at ``cross_direction_deg``); None for one pass.
    """

    area: Area
    direction_deg: float
    spacing_m: float
    base_m: float
    strips: tuple[Strip, ...]
    sorties: tuple[Sortie, ...]
    photos: Photos
    flight_length_m: float
    turn_length_m: float
    flight_time_s: float | None
    extension_bases: float = 1.0
    feasible: bool = True
    reason: str | None = None
    notes: dict[str, Any] = field(default_factory=dict)
    kind: str = "uav"
    footprint_across_m: float = float("nan")
    footprint_along_m: float = float("nan")
    speed_ms: float | None = None
    turn: str = "semicircle"

    cross_direction_deg: float | None = None
    first_pass_strips: int | None = None

    @property
    def n_photos(self) -> int:
        """Number of photo centres."""
        return len(self.photos)

    @property
    def crosshatch(self) -> bool:
        """Whether the area is flown twice, the second pass at ``direction_deg`` + 90°."""
        return self.cross_direction_deg is not None

    def strip_pass(self, number: int) -> int:
        """The pass (1, or 2 for a crosshatch's second) that flies strip ``number``
        (from 1)."""
        n = self.first_pass_strips
        return 2 if n is not None and number > n else 1

    def strip_direction_deg(self, number: int) -> float:
        """The line direction of strip ``number`` (from 1) [°], 0 … 180."""
        if self.cross_direction_deg is not None and self.strip_pass(number) == 2:
            return self.cross_direction_deg
        return self.direction_deg

    def directions_deg(self, strip: np.ndarray) -> float | np.ndarray:
        """The line direction of each photo of the strips ``strip`` (from 1) [°]: the one
        ``direction_deg`` for a single pass, else one value per photo."""
        if self.cross_direction_deg is None or self.first_pass_strips is None:
            return self.direction_deg
        return np.where(np.asarray(strip) > self.first_pass_strips,
                        self.cross_direction_deg, self.direction_deg)


def line_axes(direction_deg: float | np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The unit vectors along and across the flight lines (x, y) of a line direction
    [° clockwise from grid north]; one per photo (2 × n) for one direction per photo (a
    crosshatch's two passes: :meth:`FlightLayout.directions_deg`)."""
    if np.ndim(direction_deg):
        t = np.radians(np.asarray(direction_deg, dtype=float))
        return np.array([np.sin(t), np.cos(t)]), np.array([np.cos(t), -np.sin(t)])
    t = math.radians(direction_deg)
    return np.array([math.sin(t), math.cos(t)]), np.array([math.cos(t), -math.sin(t)])
