"""The background of the PDF's map pages when ``[map] basemap`` names an XYZ tile URL: the
tiles over each flight layout's map, fetched once with the plan (kept in the user's tile
cache, as the page's are) so that every document prints the same picture, and a warning
when the tile server did not give them all (offline, unreachable) — the plan and its PDF
are made all the same, the map without the missing tiles.

A background file (GeoTIFF, MBTiles) is read where the map is drawn
(:func:`scanplan.reports.mapview.map_basemap`): it is on the disk already.
"""

from __future__ import annotations

from ..geo.basemap import Basemap, layout_extent_lonlat, read_tiles
from ..geo.layout import FlightLayout
from ..i18n.messages import Message
from ..rules.results import PlanWarning
from .model import ProjectModel

__all__ = ["MAP_PX", "map_backgrounds"]

MAP_PX = 1600
"""Most pixels a side of a map page's background (as a background file is read)."""


def map_backgrounds(project: ProjectModel, layouts: dict[str, FlightLayout]
                    ) -> tuple[dict[str, Basemap], tuple[PlanWarning, ...]]:
    """The tile background of each georeferenced layout (``{"uav": …, "film": …}``) when
    ``[map] basemap`` is a URL template, and the warnings of tiles that did not come."""
    m = project.map
    url = getattr(m, "basemap_url", None) if m is not None else None
    if not url:
        return {}, ()
    out: dict[str, Basemap] = {}
    warnings: list[PlanWarning] = []
    for kind, layout in layouts.items():
        if not layout.area.georeferenced:
            continue
        got = read_tiles(url, str(layout.area.plan_crs), layout_extent_lonlat(layout),
                         max_px=MAP_PX, name=m.basemap_attribution)
        if got.image is None:
            warnings.append(PlanWarning("map_tiles_unreachable", Message(
                "map_tiles_unreachable", host=got.host)))
            continue
        out[kind] = got.image
        if got.missing:
            warnings.append(PlanWarning("map_tiles_missing", Message(
                "map_tiles_missing", host=got.host, missing=got.missing, asked=got.asked)))
    return out, tuple(warnings)
