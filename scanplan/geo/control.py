"""Ground control points (GCPs) and checkpoints laid out over the area (shapely, numpy).

Every rule is a number the caller passes (:class:`ControlLayoutRules`, from
``norms/catalogue/control-rules.csv`` — docs/control.md gives each rule's source and status):

* **inside** — every marker at least ``inset_m`` inside the boundary (the inner polygon
  ``area.buffer(-inset_m)``), so the outer strip's photos and its neighbour's see it;
* **GCPs, ``mode = "gcp"``** — per block (each polygon of the area): one at every corner of
  the inner polygon, more along its boundary so that no two neighbours are farther apart
  than the spacing ``s``, and a stratified interior: one per ``s × s`` cell, the cells'
  centres that lie at least ``s/2`` inside the inner polygon; ``s = 100 m / sqrt(GCP/ha)``;
* **GCPs, ``"rtk"`` / ``"ppk"``** — the camera positions control the block: the corner GCPs
  and the interior GCP nearest the block's centre (the pole of inaccessibility), a subset of
  the ``"gcp"`` layout; ``"direct"`` — none;
* **checkpoints** — their own layout, independent of the GCPs: cell centres of a grid offset
  by half a cell from the GCPs' (and, when these are too few, of a grid twice as fine), none
  nearer than ``separation_m`` to any GCP of the ``"gcp"`` layout, taken in farthest-point
  order from the area's centre until the count is reached — the same points in every mode;
* **steep ground** — with a ground function (a DEM), a marker whose slope exceeds the limit
  moves to the nearest flatter place within ``s/2`` that keeps the other rules.

Coordinates are in the planning CRS [m] (:mod:`scanplan.geo.layout`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely.ops import polylabel

from ..errors import InputError
from .layout import FlightLayout

__all__ = ["CONTROL_COLUMNS", "ControlLayoutRules", "ControlPoints", "layout_control",
           "photos_seeing", "slope_pct"]

#: The columns of control.csv and of the GeoPackage's ``control`` layer, with their units.
CONTROL_COLUMNS: dict[str, str] = {
    "id": "marker name: G1, G2 … for GCPs, C1, C2 … for checkpoints",
    "role": "gcp (ground control point) or check (independent checkpoint)",
    "block": "the block (polygon of the area) it controls, from 1",
    "x_m": "easting in the planning CRS [m]",
    "y_m": "northing in the planning CRS [m]",
    "lon_deg": "longitude, WGS 84 [°]",
    "lat_deg": "latitude, WGS 84 [°]",
    "ground_m": "ground height from the DEM [m] (empty without a DEM)",
    "photos": "photos whose footprint holds it",
}

Ground = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
"""Ground heights [m] at points of the planning CRS (NaN where unknown)."""


@dataclass(frozen=True)
class ControlLayoutRules:
    """The numbers of the layout (each a rule of ``control-rules.csv``, or the project's).

    Attributes
    ----------
    spacing_m : float
        ``s``: the GCPs' spacing along the boundary and of the interior grid [m].
    inset_m : float
        How far inside the boundary every marker stays [m].
    separation_m : float
        The least distance from a checkpoint to a GCP [m].
    checkpoints : int
        How many checkpoints.
    max_slope_pct : float
        The steepest ground a marker may stand on [%] (with a DEM).
    rtk_interior : int
        Interior GCPs per block kept in the RTK/PPK layout.
    corner_turn_deg : float
        A vertex of the inner polygon turning more than this is a corner [°].
    """

    spacing_m: float
    inset_m: float
    separation_m: float
    checkpoints: int
    max_slope_pct: float = 10.0
    rtk_interior: int = 1
    corner_turn_deg: float = 20.0


@dataclass(frozen=True)
class ControlPoints:
    """The markers: GCPs first, then checkpoints, as columns (:data:`CONTROL_COLUMNS`).

    Attributes
    ----------
    columns : dict of str to ndarray
        ``id``, ``role``, ``block`` (1-based), ``x_m``, ``y_m``, ``lon_deg``, ``lat_deg``,
        ``ground_m``, ``photos``.
    moved : int
        Markers moved off steep ground.
    steep : int
        Markers left on steep ground (no flatter place near).
    corners : int
        Corner GCPs (of the ``"gcp"`` layout; kept in every mode that sets GCPs).
    """

    columns: dict[str, np.ndarray]
    moved: int = 0
    steep: int = 0
    corners: int = 0

    def __len__(self) -> int:
        return len(self.columns["id"])

    def role(self, role: str) -> NDArray[np.bool_]:
        """Mask of the markers of ``role`` (``"gcp"``, ``"check"``)."""
        return np.asarray(self.columns["role"]) == role

    @property
    def n_gcp(self) -> int:
        """Number of GCPs."""
        return int(self.role("gcp").sum())

    @property
    def n_check(self) -> int:
        """Number of checkpoints."""
        return int(self.role("check").sum())


def _parts(geometry: shapely.Geometry) -> list[shapely.Polygon]:
    return list(getattr(geometry, "geoms", [geometry]))


def _corners(inner: shapely.Polygon, turn_deg: float) -> NDArray[np.float64]:
    """The vertices of the inner polygon's outer ring turning by more than ``turn_deg``."""
    ring = np.asarray(inner.exterior.coords)[:-1]
    if len(ring) < 3:
        return ring
    prev, nxt = np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0)
    a, b = ring - prev, nxt - ring
    ang = np.degrees(np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0],
                                       (a * b).sum(axis=1))))
    return ring[ang > turn_deg]


def _edge_points(inner: shapely.Polygon, corners: NDArray[np.float64],
                 spacing_m: float) -> NDArray[np.float64]:
    """Points along the inner ring between consecutive corners, no gap longer than the
    spacing (the corners themselves excluded)."""
    ring = shapely.LineString(inner.exterior.coords)
    if not len(corners):
        corners = np.asarray(ring.coords)[:1]
    at = np.sort(np.asarray(shapely.line_locate_point(ring, shapely.points(corners))))
    total = ring.length
    stops = np.append(at, at[0] + total)
    out = []
    for a, b in pairwise(stops):
        n = math.ceil((b - a) / spacing_m - 1e-9)
        for k in range(1, n):
            out.append(ring.interpolate((a + (b - a) * k / n) % total).coords[0])
    return np.asarray(out, float).reshape(-1, 2)


def _grid(poly: shapely.Geometry, step_m: float, offset_m: float,
          origin: tuple[float, float]) -> NDArray[np.float64]:
    """Nodes ``origin + offset + k·step`` that lie inside ``poly``."""
    if poly.is_empty:
        return np.empty((0, 2))
    x0, y0, x1, y1 = poly.bounds
    ox, oy = origin[0] + offset_m, origin[1] + offset_m
    xs = ox + step_m * np.arange(math.floor((x0 - ox) / step_m), math.ceil((x1 - ox) / step_m) + 1)
    ys = oy + step_m * np.arange(math.floor((y0 - oy) / step_m), math.ceil((y1 - oy) / step_m) + 1)
    if len(xs) * len(ys) > 4_000_000:  # the spacing is checked against the area before
        raise InputError("control.gcp_per_ha", "gives more than 4,000,000 grid cells "
                         "over this area: fewer GCPs per hectare")
    gx, gy = np.meshgrid(xs, ys)
    pts = np.column_stack([gx.ravel(), gy.ravel()])
    keep = shapely.contains_xy(poly, pts[:, 0], pts[:, 1])
    return pts[keep]


def slope_pct(ground: Ground, xy: NDArray[np.float64], step_m: float) -> NDArray[np.float64]:
    """The ground's slope at points [%], from central differences ``step_m`` apart (NaN
    where the ground is unknown)."""
    x, y = xy[:, 0], xy[:, 1]
    gx = (ground(x + step_m, y) - ground(x - step_m, y)) / (2 * step_m)
    gy = (ground(x, y + step_m) - ground(x, y - step_m)) / (2 * step_m)
    return 100.0 * np.hypot(gx, gy)


def _off_steep(xy: NDArray[np.float64], allowed: shapely.Geometry, ground: Ground | None,
               rules: ControlLayoutRules) -> tuple[NDArray[np.float64], int, int]:
    """Markers on steeper ground than allowed moved to the nearest flatter place within
    ``s/2`` that stays in ``allowed``; (points, moved, left on steep ground)."""
    if ground is None or not len(xy):
        return xy, 0, 0
    step = max(rules.inset_m / 10.0, 1.0)
    slope = slope_pct(ground, xy, step)
    out, moved, left = xy.copy(), 0, 0
    rings = [(r, k) for r in np.linspace(rules.spacing_m / 8, rules.spacing_m / 2, 4)
             for k in range(12)]
    offsets = np.array([(r * math.cos(k * math.pi / 6), r * math.sin(k * math.pi / 6))
                        for r, k in rings])
    for i in np.flatnonzero(~(slope <= rules.max_slope_pct)):
        if not np.isfinite(slope[i]):
            continue  # unknown ground: not judged
        cand = xy[i] + offsets
        cand = cand[shapely.contains_xy(allowed, cand[:, 0], cand[:, 1])]
        if len(cand):
            ok = cand[slope_pct(ground, cand, step) <= rules.max_slope_pct]
            if len(ok):
                out[i] = ok[np.argmin(np.hypot(*(ok - xy[i]).T))]
                moved += 1
                continue
        left += 1
    return out, moved, left


@dataclass
class _Block:
    corners: NDArray[np.float64]
    edge: NDArray[np.float64]
    interior: NDArray[np.float64]
    inner: shapely.Geometry


def _block(part: shapely.Polygon, rules: ControlLayoutRules) -> _Block | None:
    inner = part.buffer(-rules.inset_m, join_style="mitre")
    if inner.is_empty:
        return None
    # the largest piece of a pinched part carries the corners; every piece its grid
    pieces = sorted(_parts(inner), key=lambda p: p.area, reverse=True)
    corners, edge = [], []
    for piece in pieces:
        c = _corners(piece, rules.corner_turn_deg)
        corners.append(c)
        edge.append(_edge_points(piece, c, rules.spacing_m))
    interior = _grid(inner.buffer(-rules.spacing_m / 2), rules.spacing_m, rules.spacing_m / 2,
                     (part.bounds[0], part.bounds[1]))
    return _Block(np.vstack(corners), np.vstack(edge), interior, inner)


def _farthest(cand: NDArray[np.float64], n: int, start: tuple[float, float]
              ) -> NDArray[np.int64]:
    """``n`` indices of ``cand`` in farthest-point order from the candidate nearest
    ``start`` (an even spread, deterministic)."""
    if n <= 0 or not len(cand):
        return np.empty(0, np.int64)
    first = int(np.argmin(np.hypot(cand[:, 0] - start[0], cand[:, 1] - start[1])))
    chosen = [first]
    dist = np.hypot(*(cand - cand[first]).T)
    while len(chosen) < min(n, len(cand)):
        nxt = int(np.argmax(dist))
        chosen.append(nxt)
        dist = np.minimum(dist, np.hypot(*(cand - cand[nxt]).T))
    return np.asarray(chosen, np.int64)


def _checkpoints(blocks: list[tuple[int, _Block]], gcp_all: NDArray[np.float64],
                 rules: ControlLayoutRules, area: shapely.Geometry, field_name: str
                 ) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The checkpoints and their blocks (see the module)."""
    tree = shapely.STRtree(shapely.points(gcp_all)) if len(gcp_all) else None
    centre = area.centroid.coords[0]
    best = (np.empty((0, 2)), np.empty(0, np.int64))
    for step in (rules.spacing_m, rules.spacing_m / 2, rules.spacing_m / 4):
        cand, owner = [], []
        for number, b in blocks:
            pts = _grid(b.inner, step, step / 2 + rules.spacing_m / 2,
                        (area.bounds[0], area.bounds[1]))
            cand.append(pts)
            owner.append(np.full(len(pts), number))
        pts, own = np.vstack(cand), np.concatenate(owner)
        if tree is not None and len(pts):
            _, d = tree.query_nearest(shapely.points(pts), return_distance=True, all_matches=False)
            far = d >= rules.separation_m
            pts, own = pts[far], own[far]
        if len(pts) >= rules.checkpoints:
            idx = _farthest(pts, rules.checkpoints, centre)
            return pts[idx], own[idx]
        if len(pts) > len(best[0]):
            best = (pts, own)
    raise InputError(field_name, f"must be at most {len(best[0])} over this area: no more "
                     f"places lie {rules.inset_m:.0f} m inside the boundary and "
                     f"{rules.separation_m:.0f} m from every GCP (got {rules.checkpoints})")


def photos_seeing(layout: FlightLayout, xy: NDArray[np.float64], planned_agl_m: float
                  ) -> NDArray[np.int64]:
    """How many photos' footprints hold each point (each footprint at its own height above
    ground when the photos carry ``agl_m``, turned to the strips' direction)."""
    n = len(layout.photos)
    if not n or not len(xy):
        return np.zeros(len(xy), np.int64)
    px = np.asarray(layout.photos["x_m"], float)
    py = np.asarray(layout.photos["y_m"], float)
    agl = np.asarray(layout.photos["agl_m"], float) if "agl_m" in layout.photos.columns \
        else np.full(n, planned_agl_m)
    k = np.where(np.isfinite(agl) & (agl > 0), agl / planned_agl_m, 1.0)
    half_along = 0.5 * layout.footprint_along_m * k
    half_across = 0.5 * layout.footprint_across_m * k
    d = math.radians(layout.direction_deg)
    u = (math.sin(d), math.cos(d))  # along track, clockwise from grid north
    # the photos near each marker (an STRtree of the photo centres, boxes of the largest
    # footprint's half-diagonal), then the turned-footprint test on those pairs only
    reach = float(np.hypot(half_along, half_across).max())
    tree = shapely.STRtree(shapely.points(px, py))
    mi, pj = tree.query(shapely.box(xy[:, 0] - reach, xy[:, 1] - reach,
                                    xy[:, 0] + reach, xy[:, 1] + reach))
    dx, dy = px[pj] - xy[mi, 0], py[pj] - xy[mi, 1]
    along = dx * u[0] + dy * u[1]
    across = dx * u[1] - dy * u[0]
    seen = (np.abs(along) <= half_along[pj]) & (np.abs(across) <= half_across[pj])
    return np.bincount(mi[seen], minlength=len(xy)).astype(np.int64)


def layout_control(area: shapely.Geometry, mode: str, rules: ControlLayoutRules, *,
                   ground: Ground | None = None, area_field: str = "area",
                   checkpoints_field: str = "control.checkpoints") -> ControlPoints:
    """GCPs and checkpoints over ``area`` (see the module); lon/lat/photos left NaN/0.

    Parameters
    ----------
    area : shapely.Polygon or MultiPolygon
        The area in the planning CRS [m]; each polygon is a block.
    mode : {"gcp", "rtk", "ppk", "direct"}
        How the block is controlled.
    rules : ControlLayoutRules
        The layout's numbers.
    ground : callable, optional
        Ground heights at points (a DEM): markers avoid steep ground.
    area_field, checkpoints_field : str
        How an error names the area and the checkpoint count.

    Raises
    ------
    InputError
        The area has no place ``inset_m`` inside its boundary (smaller than a footprint),
        or fewer places for checkpoints than asked.
    """
    blocks = [(i, b) for i, part in enumerate(_parts(area), start=1)
              if (b := _block(part, rules)) is not None]
    if not blocks:
        raise InputError(area_field, "is too small for ground control: no place lies "
                         f"{rules.inset_m:.0f} m (half a photo footprint) inside its "
                         "boundary; the area must be larger than one photo footprint")
    allowed = shapely.union_all([b.inner for _, b in blocks])
    full, full_block, kinds = [], [], []
    for number, b in blocks:
        for kind, pts in (("corner", b.corners), ("edge", b.edge), ("interior", b.interior)):
            full.append(pts)
            full_block.append(np.full(len(pts), number))
            kinds += [kind] * len(pts)
    gcp_all = np.vstack(full)
    gcp_block = np.concatenate(full_block)
    kind_arr = np.asarray(kinds)
    gcp_all, moved, steep = _off_steep(gcp_all, allowed, ground, rules)
    keep = _mode_keep(mode, gcp_all, gcp_block, kind_arr, blocks, rules)
    gcp, gblock = gcp_all[keep], gcp_block[keep]
    chk, cblock = _checkpoints(blocks, gcp_all, rules, area, checkpoints_field)
    free = allowed.difference(shapely.union_all(shapely.buffer(shapely.points(gcp_all),
                                                               rules.separation_m))) \
        if len(gcp_all) and ground is not None else allowed
    chk, m2, s2 = _off_steep(chk, free, ground, rules)
    xy = np.vstack([gcp, chk]) if len(chk) else gcp
    n_g, n_c = len(gcp), len(chk)
    ids = np.array([f"G{i}" for i in range(1, n_g + 1)] + [f"C{i}" for i in range(1, n_c + 1)],
                   dtype=object)
    cols: dict[str, np.ndarray] = {
        "id": ids,
        "role": np.array(["gcp"] * n_g + ["check"] * n_c, dtype=object),
        "block": np.concatenate([gblock, cblock]).astype(np.int64),
        "x_m": xy[:, 0].astype(float) if len(xy) else np.empty(0),
        "y_m": xy[:, 1].astype(float) if len(xy) else np.empty(0),
        "lon_deg": np.full(len(xy), np.nan), "lat_deg": np.full(len(xy), np.nan),
        "ground_m": (np.asarray(ground(xy[:, 0], xy[:, 1]), float) if ground is not None
                     and len(xy) else np.full(len(xy), np.nan)),
        "photos": np.zeros(len(xy), np.int64),
    }
    corners = int((kind_arr[keep] == "corner").sum())
    return ControlPoints(cols, moved + m2, steep + s2, corners)


def _mode_keep(mode: str, gcp_all: NDArray[np.float64], gcp_block: NDArray[np.int64],
               kinds: NDArray[np.str_], blocks: list[tuple[int, _Block]],
               rules: ControlLayoutRules) -> NDArray[np.bool_]:
    """Which GCPs of the full (``"gcp"``) layout a mode keeps."""
    if mode == "gcp":
        return np.ones(len(gcp_all), bool)
    keep = np.zeros(len(gcp_all), bool)
    if mode == "direct":
        return keep
    keep |= kinds == "corner"
    for number, b in blocks:
        mine = np.flatnonzero((gcp_block == number) & (kinds != "corner"))
        if not len(mine):
            continue
        pole = polylabel(b.inner if b.inner.geom_type == "Polygon"
                                 else max(_parts(b.inner), key=lambda p: p.area), 1.0)
        d = np.hypot(gcp_all[mine, 0] - pole.x, gcp_all[mine, 1] - pole.y)
        keep[mine[np.argsort(d, kind="stable")[:rules.rtk_interior]]] = True
    return keep
