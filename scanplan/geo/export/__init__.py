"""Files a crew or a GIS opens: the mission (QGroundControl Plan), KML, GeoJSON, CSV.

:func:`layout_files` renders every file of one flight layout to memory (name → bytes);
the caller writes them in the same all-or-nothing transaction as the reports
(:func:`scanplan.safeio.write_atomic_many`). An abstract ``width × length`` block (not
georeferenced) gets none of them; a plan that is not feasible gets no mission.

| file | content | module |
|---|---|---|
| ``mission.plan`` (``mission-01.plan`` … per sortie) | the mission to fly (UAV) | :mod:`.qgc` |
| ``mission.waypoints`` (beside each ``.plan``) | the mission for Mission Planner | :mod:`.wpl` |
| ``flight.kml`` | area, strips, numbered photo centres for Google Earth | :mod:`.gis` |
| ``flight.geojson`` | the same as RFC 7946 GeoJSON | :mod:`.gis` |
| ``photos.csv`` | every photo centre with its figures | :mod:`.gis` |
| ``flight.gpkg`` | area, strips, photo centres, sorties as one GeoPackage | :mod:`.gpkg` |
| ``mission-dji.kmz`` (``mission-dji-01.kmz`` …) | the mission for DJI Pilot 2 | :mod:`.wpml` |
"""

from __future__ import annotations

from ...progress import stage
from ..layout import FlightLayout
from .common import GENERATOR, lonlat
from .gis import ExportNames, render_csv, render_geojson, render_kml
from .gpkg import render_gpkg
from .qgc import MissionOptions, plan_files, render_plan
from .wpl import render_waypoints, waypoint_files
from .wpml import wpml_files

__all__ = ["GENERATOR", "ExportNames", "MissionOptions", "layout_files", "plan_files",
           "render_csv", "render_geojson", "render_gpkg", "render_kml", "render_plan",
           "render_waypoints", "waypoint_files", "wpml_files"]


def layout_files(layout: FlightLayout, *, names: ExportNames | None = None,
                 mission: MissionOptions | None = None, prefix: str = "",
                 photos_name: str = "photos") -> dict[str, bytes]:
    """Every exported file of ``layout``: file name → content.

    Parameters
    ----------
    layout : FlightLayout
        The flight lines and photo centres.
    names : ExportNames, optional
        Names inside the files (the report's language).
    mission : MissionOptions, optional
        With it (a UAV flight), the mission of every sortie as well: the QGroundControl
        Plan file and the same mission as Mission Planner's waypoint file.
    prefix : str
        Put before every file name (``"film-"``; a batch's project name).
    photos_name : str
        Stem of the CSV (``"photos"``; ``"frames"`` for film).

    Returns
    -------
    dict of str to bytes
        Empty when the layout is not georeferenced.
    """
    if not layout.area.georeferenced:
        return {}
    geo = lonlat(layout)
    files: dict[str, bytes] = {}
    if mission is not None:
        # terrain following: a waypoint at every altitude step (the other files keep the
        # strips as laid out)
        plans = plan_files(layout, mission, geo=geo)
        plans.update(waypoint_files(plans))  # the same missions for Mission Planner
        files.update({prefix + k: v for k, v in plans.items()})
    gis = {"flight.kml": lambda: render_kml(layout, names),
           "flight.geojson": lambda: render_geojson(layout, names),
           "flight.gpkg": lambda: render_gpkg(layout)}
    if len(layout.photos):
        gis[f"{photos_name}.csv"] = lambda: render_csv(layout)
    with stage("GIS files", len(gis), "files") as step:
        for name, render in gis.items():
            files[prefix + name] = render()
            step()
    return files
