"""Files a crew or a GIS opens: the mission (QGroundControl Plan), KML, GeoJSON, CSV.

:func:`layout_files` renders every file of one flight layout to memory (name → bytes);
the caller writes them in the same all-or-nothing transaction as the reports
(:func:`scanplan.io.atomic.write_atomic_many`). An abstract ``width × length`` block (not
georeferenced) gets none of them; a plan that is not feasible gets no mission.

| file | content | module |
|---|---|---|
| ``mission.plan`` (``mission-01.plan`` … per sortie) | the mission to fly (UAV) | :mod:`.qgc` |
| ``mission.waypoints`` (beside each ``.plan``) | the mission for Mission Planner | :mod:`.wpl` |
| ``flight.kml`` | area, strips, numbered photo centres for Google Earth | :mod:`.gis` |
| ``flight.geojson`` | the same as RFC 7946 GeoJSON | :mod:`.gis` |
| ``photos.csv`` | every photo centre with its figures | :mod:`.gis` |
| ``control.csv`` | GCPs and checkpoints (``[control]``) | :mod:`.gis` |
| ``flight.gpkg`` | area, strips, photo centres, sorties as one GeoPackage | :mod:`.gpkg` |
| ``mission-dji.kmz`` (``mission-dji-01.kmz`` …) | the mission for DJI Pilot 2 | :mod:`.wpml` |

Each kind of file is one record of :data:`.formats.FORMATS` (suffix, what it is, mark,
writer, one file per sortie or not); :func:`layout_files` writes them in its order.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable

from ...progress import stage
from ..control import ControlPoints
from ..layout import FlightLayout
from .common import GENERATOR
from .formats import FORMATS, ExportFormat, ExportJob, format_named
from .gis import ExportNames, render_control_csv, render_csv, render_geojson, render_kml
from .gpkg import render_gpkg
from .qgc import MissionOptions, plan_files, render_plan
from .wpl import render_waypoints, waypoint_files
from .wpml import wpml_files

__all__ = ["FORMATS", "GENERATOR", "ExportFormat", "ExportJob", "ExportNames", "MissionOptions",
           "format_named", "layout_files", "plan_files", "render_control_csv", "render_csv",
           "render_geojson",
           "render_gpkg", "render_kml", "render_plan", "render_waypoints", "waypoint_files",
           "wpml_files"]


def layout_files(layout: FlightLayout, *, names: ExportNames | None = None,
                 mission: MissionOptions | None = None, prefix: str = "",
                 photos_name: str = "photos", camera: str | None = None,
                 note: Callable[[str], None] | None = None,
                 control: ControlPoints | None = None) -> dict[str, bytes]:
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
    camera : str, optional
        With a mission, the camera's id: the same mission for DJI Pilot 2 (when DJI Pilot
        2 can fly the camera).
    prefix : str
        Put before every file name (``"film-"``; a batch's project name).
    photos_name : str
        Stem of the CSV (``"photos"``; ``"frames"`` for film).
    note : callable, optional
        Told why a file the user may expect is not written, one line each
        (``"no mission-dji.kmz: …"``).
    control : ControlPoints, optional
        GCPs and checkpoints: ``control.csv``, and their points in the KML, GeoJSON and
        GeoPackage.

    Returns
    -------
    dict of str to bytes
        Empty when the layout is not georeferenced.
    """
    if not layout.area.georeferenced:
        return {}
    job = ExportJob(layout, names, mission, photos_name, camera, control=control)
    # a format written per sortie shows its own progress by sortie; the others, one file
    # each, are one stage
    for per_sortie, run in itertools.groupby(FORMATS, key=lambda f: f.per_sortie):
        formats = list(run)
        if per_sortie:
            for fmt in formats:
                job.written.update(fmt.write(job, fmt))
            continue
        with stage("GIS files", len(formats), "files") as step:
            for fmt in formats:
                job.written.update(fmt.write(job, fmt))
                step()
    for line in job.notes if note is not None else ():
        note(f"no {prefix}{line}")
    return {prefix + name: data for name, data in job.written.items()}
