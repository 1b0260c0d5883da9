"""The files ``scanplan plan --out`` writes beside spec.xlsx and spec.pdf (issue 11).

:func:`export_files` renders, for every flight layout of a specification, the mission
(UAV: a QGroundControl Plan per sortie and the same mission as a Mission Planner waypoint
file), the flight as KML and GeoJSON, and the photo
centres as CSV — in memory, named for the ``--out`` folder. The command line writes them
with the reports in one all-or-nothing transaction. A UAV flight writes ``mission.plan``
and ``mission.waypoints`` (``mission-01.plan``, ``mission-01.waypoints`` … for several
sorties), for a DJI camera ``mission-dji.kmz`` (``mission-dji-01.kmz`` …: DJI Pilot 2),
``flight.kml``, ``flight.geojson``, ``flight.gpkg`` and ``photos.csv``; the film survey's
flight scheme ``film-flight.kml``, ``film-flight.geojson``, ``film-flight.gpkg`` and
``film-frames.csv``. A batch puts the project's name before
each (``NAME-flight.kml``). An abstract block (width × length, not georeferenced) writes
none of them, and the reports say so. The formats, their names and marks are the records of
:data:`scanplan.geo.export.formats.FORMATS`.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from ..geo.layout import FlightLayout
from ..i18n.labels import t
from ..io.targets import is_managed, written_by_scanplan

if TYPE_CHECKING:  # the writers (pandas, shapely) are imported when files are written
    from ..geo.export import ExportFormat, ExportNames, MissionOptions

__all__ = ["export_files", "export_notes", "files_beside", "spec_layouts", "stale_exports",
           "view_of", "with_exports"]


def spec_layouts(spec: Any) -> list[tuple[str, FlightLayout]]:
    """The flight layouts of a specification: ``[("uav", layout), ("film", layout)]``
    (those it has), the UAV flight first."""
    out = []
    for kind in ("uav", "film"):
        part = getattr(spec, kind, None)
        layout = getattr(part, "layout", None) if part is not None else None
        if isinstance(layout, FlightLayout):
            out.append((kind, layout))
    return out


@dataclass(frozen=True)
class _UavPart:
    job: Any
    layout: FlightLayout | None


@dataclass(frozen=True)
class _JobParts:
    """A UAV job without a specification (``scanplan uav --area-file … --pdf``), shaped
    like the specification's parts that :func:`spec_layouts` reads."""

    uav: _UavPart | None
    film: None = None
    writes_files: bool = False  # only a specification's run writes the exported files


def view_of(spec: Any, uav: Any = None) -> Any:
    """What the report pages read the flight layouts from: the specification, else a UAV
    job that carries a georeferenced layout (``uav --area-file``), else None."""
    if spec is not None:
        return spec
    layout = getattr(uav, "layout", None) if uav is not None else None
    if isinstance(layout, FlightLayout) and layout.area.georeferenced:
        return _JobParts(_UavPart(uav, uav.layout))
    return None


def files_beside(spec: Any, layout: FlightLayout) -> bool:
    """Whether the photo-centre table is written beside the report of ``spec``: only for
    an area on the map, and only when the run writing the report writes the table too
    (``plan --out`` with the ``gis`` output; not ``--formats pdf,xlsx``, ``--pdf FILE``
    or the documents alone: :attr:`scanplan.project.results.PlanResult.exports_written`)."""
    written = getattr(spec, "exports_written", None)
    return (layout.area.georeferenced and getattr(spec, "writes_files", True)
            and written is not None and "csv" in written)


def with_exports(spec: Any, kinds: Any) -> Any:
    """``spec`` as the documents of one run see it: the exported formats ``kinds`` (file
    kinds or their names) written beside them (a specification; anything else as it is)."""
    if spec is None or not hasattr(spec, "exports_written"):
        return spec
    from dataclasses import replace

    names = frozenset(getattr(k, "name", k) for k in kinds)
    if spec.exports_written == names:  # already so: the same result, not a copy
        return spec
    return replace(spec, exports_written=names)


def export_names(locale: str, title: str = "", film: bool = False) -> ExportNames:
    """The names inside the exported files, in the report's language."""
    from ..geo.export import ExportNames

    return ExportNames(
        title=title or t("geo_export_title", locale),
        area=t("area", locale),
        strips=t("strips", locale),
        photos=t("frame_centres" if film else "photo_centres", locale),
        strip=t("geo_strip_n", locale),
        sortie=t("geo_sortie_n", locale),
        sorties=t("sorties", locale), takeoff=t("takeoff_point", locale),
        control=t("control_points", locale))


def mission_options(spec: Any, layout: FlightLayout) -> MissionOptions | None:
    """How the UAV mission is flown, from the specification; None when no mission is
    written (a manned aircraft, a plan that cannot be flown, no speed)."""
    uav = getattr(spec, "uav", None)
    if uav is None or not layout.feasible:
        return None
    inputs = uav.job.plan.inputs
    if getattr(inputs, "platform", "uav") != "uav":
        return None
    speed = layout.speed_ms if layout.speed_ms else inputs.speed_ms
    if not speed or speed <= 0:
        return None
    # over a DEM or a ground range the photos' altitudes are above sea level (the DEM's
    # height system): the mission states them so, not relative to a home whose ground the
    # plan does not know (docs/exports.md)
    frame = "amsl" if layout.notes.get("altitude_frame") == "AMSL" else "relative"
    from ..geo.export import MissionOptions

    return MissionOptions(speed_ms=float(speed), vehicle=_vehicle(spec), frame=frame)


def _vehicle(spec: Any) -> Literal["multirotor", "fixed_wing"]:
    """The aircraft, from the turn keys the project gives: ``[uav] turn_radius_m`` or
    ``[uav] bank_deg`` (turns of a fixed wing) → a fixed wing; otherwise a multirotor."""
    flight = getattr(getattr(spec, "project", None), "flight", None)
    if flight is not None and (flight.turn_radius_m is not None
                               or flight.bank_deg is not None):
        return "fixed_wing"
    return "multirotor"


def camera_id(spec: Any) -> str:
    """The UAV camera's id (a DJI route is written for a camera DJI Pilot 2 can fly)."""
    camera = getattr(spec.uav.job.plan.inputs, "camera", None)
    return str(getattr(camera, "id", camera))


def export_files(spec: Any, folder: str, *, prefix: str = "",
                 note: Callable[[str], None] | None = None
                 ) -> dict[str, tuple[ExportFormat, bytes]]:
    """Every exported file of ``spec``: path in ``folder`` → (kind, content).

    Parameters
    ----------
    spec : PlanResult
        The specification of one project.
    folder : str
        The ``--out`` folder.
    prefix : str
        Put before every name (a batch: ``"NAME-"``).
    note : callable, optional
        Told why a file the user may expect is not written (no DJI route for a camera
        DJI Pilot 2 cannot fly; no EGM96 grid for a terrain plan), one line each, for the
        terminal.

    Returns
    -------
    dict
        Path → (its format, the kind :func:`scanplan.io.targets.check_target` checks;
        bytes); empty for a project without a georeferenced area.
    """
    locale = getattr(getattr(spec, "meta", None), "locale", "en")
    title = getattr(getattr(spec, "meta", None), "project", "")
    files: dict[str, tuple[ExportFormat, bytes]] = {}
    for kind, layout in spec_layouts(spec):
        if not layout.area.georeferenced:  # an abstract block: no files (layout_files)
            continue
        from ..geo.export import layout_files

        film = kind == "film"
        mission = None if film else mission_options(spec, layout)
        rendered = layout_files(
            layout, names=export_names(locale, title, film), mission=mission,
            prefix=prefix + ("film-" if film else ""),
            photos_name="frames" if film else "photos",
            camera=None if film else camera_id(spec), note=note,
            control=None if film else _control_points(spec))
        by_suffix = _formats_by_suffix()
        for name, data in rendered.items():
            suffix = os.path.splitext(name)[1].lower()
            files[os.path.join(folder, name)] = (by_suffix[suffix], data)
    return files


def _control_points(spec: Any) -> Any:
    """The specification's GCPs and checkpoints (``[control]``), or None."""
    control = getattr(spec, "control", None)
    return control.points if control is not None else None


def _formats_by_suffix() -> dict[str, ExportFormat]:
    from ..geo.export.formats import FORMATS

    return {fmt.suffix: fmt for fmt in FORMATS}


def export_notes(spec: Any) -> list[Any]:
    """Why ``plan --out`` writes no mission or no photo table for a georeferenced area
    (a plan that cannot be flown, too many photos to list, no speed, an aircraft), in the
    project's language; empty when every file is written.

    Parameters
    ----------
    spec : PlanResult
        The specification of one project.

    Returns
    -------
    list of Message
        One sentence per file not written (``.text(locale)`` in the project's language).
    """
    from ..geo.lines import MAX_PHOTO_CENTRES
    from ..i18n.messages import Message

    out = []
    for kind, layout in spec_layouts(spec):
        if not layout.area.georeferenced:  # the reports say an abstract block has none
            continue
        n = int(layout.notes.get("photos", len(layout.photos)) or 0)
        listed = len(layout.photos) > 0 or n == 0
        if kind == "uav":
            why = None
            inputs = spec.uav.job.plan.inputs
            if not layout.feasible:
                why = Message("export.why_not_feasible", why=layout.reason or "")
            elif getattr(inputs, "platform", "uav") != "uav":
                why = Message("export.why_aircraft")
            elif mission_options(spec, layout) is None:
                why = Message("export.why_no_speed")
            elif not listed:
                why = Message("export.why_not_listed", n=n, most=MAX_PHOTO_CENTRES)
            if why is not None:
                out.append(Message("export.no_mission", why=why))
        if not listed:
            name = "film-frames.csv" if kind == "film" else "photos.csv"
            out.append(Message("export.no_photos", name=name, n=n, most=MAX_PHOTO_CENTRES))
    return out


def stale_exports(folder: str, written: set[str]) -> list[str]:
    """Exported files of an earlier run in ``folder`` that this run did not write.

    A plan that now needs three sorties leaves ``mission-04.plan`` … of an earlier plan
    with six; an area that is no longer a polygon leaves the old KML. A crew must never
    fly a stale sortie, so ``plan --out`` removes them after its write. Only scanplan's
    own files (their mark) with the names of a single project's exports count; symbolic
    links and other files are left alone.

    Parameters
    ----------
    folder : str
        The ``--out`` folder.
    written : set of str
        The paths this run wrote.

    Returns
    -------
    list of str
        Paths to remove, sorted.
    """
    from ..geo.export.formats import FORMATS

    keep = {os.path.normcase(os.path.abspath(p)) for p in written}
    out = []
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    for name in names:
        # a single project's exports, the film survey's with "film-" before them
        fmt = next((f for f in FORMATS
                    if re.fullmatch(f"(?:film-)?{f.name_pattern()}", name)), None)
        if fmt is None:
            continue
        path = os.path.join(folder, name)
        if os.path.normcase(os.path.abspath(path)) in keep or (
                os.path.islink(path) and not is_managed(path)) or not os.path.isfile(path):
            continue
        if written_by_scanplan(path, fmt):
            out.append(path)
    return out
