"""The registry of exported formats: one record per kind of file ``plan --out`` exports.

Each :class:`ExportFormat` says what the file is (its suffix, a name for messages, the
output of ``--formats`` it belongs to), how scanplan recognises its own file of that kind
(the mark a target check and the stale-file cleanup look for), whether a flight gets one
file per sortie, and how it is written. Three things iterate :data:`FORMATS`, in its
order: :func:`scanplan.geo.export.layout_files` (the files of a flight layout),
:func:`scanplan.io.targets.check_target` (the record is the target's kind) and
:func:`scanplan.reports.exports.stale_exports` (the names and marks of an earlier run's
files). A new format is one record here and its writer.
"""

from __future__ import annotations

import io
import re
import zipfile
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal

from ...io.targets import OUR_MARK, FileKind
from ..control import ControlPoints
from ..layout import FlightLayout
from .common import LonLat, lonlat
from .gis import ExportNames, render_control_csv, render_csv, render_geojson, render_kml
from .gpkg import render_gpkg
from .qgc import MissionOptions, plan_files
from .wpl import waypoint_files
from .wpml import wpml_files

__all__ = ["FORMATS", "ExportFormat", "ExportJob", "format_named"]


@dataclass
class ExportJob:
    """What the writers of one flight layout share.

    Attributes
    ----------
    layout : FlightLayout
        The georeferenced flight lines and photo centres.
    names : ExportNames or None
        Names inside the files (the report's language).
    mission : MissionOptions or None
        How the mission is flown; None: no mission file is written.
    photos_name : str
        Stem of the photo table (``"photos"``; ``"frames"`` for film).
    camera : str or None
        The camera's id for a DJI route; None: no DJI route is written.
    written : dict of str to bytes
        The files written so far, by name (the waypoint files read the Plan files).
    notes : list of str
        Why a file the user may expect is not written (``"mission-dji.kmz: …"``).
    control : ControlPoints or None
        GCPs and checkpoints (``[control]``): control.csv, and in the GIS files.
    """

    layout: FlightLayout
    names: ExportNames | None = None
    mission: MissionOptions | None = None
    photos_name: str = "photos"
    camera: str | None = None
    written: dict[str, bytes] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    control: ControlPoints | None = None

    @cached_property
    def geo(self) -> LonLat:
        """The WGS 84 view of the layout, computed once for every writer."""
        return lonlat(self.layout)


@dataclass(frozen=True)
class ExportFormat(FileKind):
    """One exported format (also the kind :func:`scanplan.io.targets.check_target` checks).

    Attributes
    ----------
    stems : tuple of str
        The file names' stems it writes (before a sortie number and the suffix); the first
        is the one the writer uses unless the job names another (the photo table).
    output : {"missions", "gis"}
        The output of ``plan --formats`` that writes it.
    per_sortie : bool
        One file per sortie (``mission-01.plan`` …) when a flight has several.
    write : callable
        ``write(job: ExportJob, fmt: ExportFormat) -> dict[str, bytes]``: its files of one
        flight layout, file name → content; empty when the layout gives none (no mission,
        no photos).
    """

    stems: tuple[str, ...]
    output: Literal["missions", "gis"]
    per_sortie: bool
    write: Callable[[ExportJob, ExportFormat], dict[str, bytes]]

    def name_pattern(self) -> str:
        """A regular expression of the file names it writes (without a prefix)."""
        stems = "|".join(re.escape(stem) for stem in self.stems)
        sortie = r"(?:-\d+)?" if self.per_sortie else ""
        return f"(?:{stems}){sortie}{re.escape(self.suffix)}"


def _text_mark(pattern: bytes) -> Callable[[bytes], bool]:
    """A mark looked for in a text file's first 4 KiB."""
    compiled = re.compile(pattern)
    return lambda data: bool(compiled.search(data[:4096]))


def _zip_comment_is_ours(data: bytes) -> bool:
    """A ZIP whose comment names scanplan (the DJI route file)."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as zf:
            return zf.comment.startswith(OUR_MARK + b" ")
    except (zipfile.BadZipFile, OSError, ValueError, EOFError):
        return False


_GPKG_MARK = re.compile(rb'<MDI key="GENERATOR">scanplan ')


def _gpkg_is_ours(data: bytes) -> bool:
    """An SQLite file whose dataset metadata item GENERATOR names scanplan."""
    return data.startswith(b"SQLite format 3\x00") and bool(_GPKG_MARK.search(data))


def _plans(job: ExportJob, fmt: ExportFormat) -> dict[str, bytes]:
    if job.mission is None:
        return {}
    # terrain following: a waypoint at every altitude step (the other files keep the
    # strips as laid out)
    return plan_files(job.layout, job.mission, stem=fmt.stems[0], geo=job.geo)


def _waypoints(job: ExportJob, fmt: ExportFormat) -> dict[str, bytes]:
    plan = format_named("plan").suffix  # the same missions as the Plan files
    return waypoint_files({k: v for k, v in job.written.items() if k.endswith(plan)})


def _photos(job: ExportJob, fmt: ExportFormat) -> dict[str, bytes]:
    out = {}
    if len(job.layout.photos):
        out[f"{job.photos_name}{fmt.suffix}"] = render_csv(job.layout)
    if job.control is not None and len(job.control):  # the markers' table beside it
        out[f"control{fmt.suffix}"] = render_control_csv(job.control)
    return out


def _dji(job: ExportJob, fmt: ExportFormat) -> dict[str, bytes]:
    if job.mission is None or job.camera is None:
        return {}
    files, reason = wpml_files(job.layout, job.mission, job.camera, stem=fmt.stems[0],
                               geo=job.geo)
    if reason:
        job.notes.append(f"{fmt.stems[0]}{fmt.suffix}: {reason}")
    return files


def _one_file(render: Callable[[ExportJob], bytes]
              ) -> Callable[[ExportJob, ExportFormat], dict[str, bytes]]:
    """The writer of a format with one file per layout, named by its first stem."""
    return lambda job, fmt: {f"{fmt.stems[0]}{fmt.suffix}": render(job)}


FORMATS: list[ExportFormat] = [
    ExportFormat(name="plan", suffix=".plan", what="mission",
                 is_ours=_text_mark(rb'"groundStation"\s*:\s*"scanplan[ "]'),
                 stems=("mission",), output="missions", per_sortie=True, write=_plans),
    # the comment line after the header (Mission Planner skips it)
    ExportFormat(name="waypoints", suffix=".waypoints", what="waypoint file",
                 is_ours=_text_mark(rb"\AQGC WPL 110\r?\n# scanplan "),
                 stems=("mission",), output="missions", per_sortie=True, write=_waypoints),
    ExportFormat(name="kml", suffix=".kml", what="KML file",
                 is_ours=_text_mark(rb"\A<\?xml[^>]*\?>\s*<!-- scanplan "),
                 stems=("flight",), output="gis", per_sortie=False,
                 write=_one_file(lambda job: render_kml(job.layout, job.names, job.control))),
    ExportFormat(name="geojson", suffix=".geojson", what="GeoJSON file",
                 is_ours=_text_mark(rb'"generator"\s*:\s*"scanplan[ "]'),
                 stems=("flight",), output="gis", per_sortie=False,
                 write=_one_file(lambda job: render_geojson(job.layout, job.names,
                                                            job.control))),
    ExportFormat(name="gpkg", suffix=".gpkg", what="GeoPackage", is_ours=_gpkg_is_ours,
                 stems=("flight",), output="gis", per_sortie=False,
                 write=_one_file(lambda job: render_gpkg(job.layout, job.control))),
    # the photo table's and the control table's header: a CSV has no place for a comment
    ExportFormat(name="csv", suffix=".csv", what="table",
                 is_ours=_text_mark(rb"\A(?:photo,strip,index,sortie,x_m,y_m,lon_deg,lat_deg,"
                                    rb"|id,role,block,x_m,y_m,lon_deg,lat_deg,)"),
                 stems=("photos", "frames", "control"), output="gis", per_sortie=False,
                 write=_photos),
    ExportFormat(name="kmz", suffix=".kmz", what="DJI route file", is_ours=_zip_comment_is_ours,
                 stems=("mission-dji",), output="missions", per_sortie=True, write=_dji),
]
"""Every exported format, in the order its files are written."""


def format_named(name: str) -> ExportFormat:
    """The record of :data:`FORMATS` named ``name``.

    Parameters
    ----------
    name : str
        A format's name (``"plan"``, ``"kml"`` …).

    Returns
    -------
    ExportFormat
        Its record.

    Raises
    ------
    KeyError
        No format has that name.
    """
    for fmt in FORMATS:
        if fmt.name == name:
            return fmt
    raise KeyError(name)
