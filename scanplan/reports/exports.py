"""The files ``scanplan plan --out`` writes beside spec.xlsx and spec.pdf (issue 11).

:func:`export_files` renders, for every flight layout of a specification, the mission
(UAV: a QGroundControl Plan per sortie and the same mission as a Mission Planner waypoint
file), the flight as KML and GeoJSON, and the photo
centres as CSV — in memory, named for the ``--out`` folder. The command line writes them
with the reports in one all-or-nothing transaction. A UAV flight writes ``mission.plan``
and ``mission.waypoints`` (``mission-01.plan``, ``mission-01.waypoints`` … for several
sorties), ``flight.kml``, ``flight.geojson`` and
``photos.csv``; the film survey's flight scheme ``film-flight.kml``,
``film-flight.geojson`` and ``film-frames.csv``. A batch puts the project's name before
each (``NAME-flight.kml``). An abstract block (width × length, not georeferenced) writes
none of them, and the reports say so.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from ..geo.layout import FlightLayout
from ..outpaths import SUFFIX, written_by_scanplan
from .labels import t

if TYPE_CHECKING:  # the writers (pandas, shapely) are imported when files are written
    from ..geo.export import ExportNames, MissionOptions

__all__ = ["KIND_OF_SUFFIX", "export_files", "spec_layouts", "stale_exports", "view_of"]

#: File-name ending → the kind :func:`scanplan.outpaths.check_target` checks it as.
KIND_OF_SUFFIX = {suffix: kind for kind, suffix in SUFFIX.items()}


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
class _JobsView:
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
        return _JobsView(_UavPart(uav, uav.layout))
    return None


def export_names(locale: str, title: str = "", film: bool = False) -> ExportNames:
    """The names inside the exported files, in the report's language."""
    from ..geo.export import ExportNames

    return ExportNames(
        title=title or t("geo_export_title", locale),
        area=t("geo_area", locale),
        strips=t("geo_strips", locale),
        photos=t("geo_frames" if film else "geo_photos", locale),
        strip=t("geo_strip_n", locale),
        sortie=t("geo_sortie_n", locale),
        sorties=t("geo_sorties", locale), takeoff=t("geo_takeoff", locale))


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
    project = getattr(spec, "project", None)
    get = getattr(project, "get", None)
    if get is not None and any(get("uav", key) is not None
                               for key in ("turn_radius_m", "bank_deg")):
        return "fixed_wing"
    return "multirotor"


def export_files(spec: Any, folder: str, *, prefix: str = "") -> dict[str, tuple[str, bytes]]:
    """Every exported file of ``spec``: path in ``folder`` → (kind, content).

    Parameters
    ----------
    spec : PlanResult
        The specification of one project.
    folder : str
        The ``--out`` folder.
    prefix : str
        Put before every name (a batch: ``"NAME-"``).

    Returns
    -------
    dict
        Path → (kind for :func:`scanplan.outpaths.check_target`, bytes); empty for a
        project without a georeferenced area.
    """
    locale = getattr(getattr(spec, "meta", None), "locale", "en")
    title = getattr(getattr(spec, "meta", None), "project", "")
    files: dict[str, tuple[str, bytes]] = {}
    for kind, layout in spec_layouts(spec):
        if not layout.area.georeferenced:  # an abstract block: no files (layout_files)
            continue
        from ..geo.export import layout_files

        film = kind == "film"
        rendered = layout_files(
            layout, names=export_names(locale, title, film),
            mission=None if film else mission_options(spec, layout),
            prefix=prefix + ("film-" if film else ""),
            photos_name="frames" if film else "photos")
        for name, data in rendered.items():
            suffix = os.path.splitext(name)[1].lower()
            files[os.path.join(folder, name)] = (KIND_OF_SUFFIX[suffix], data)
    return files


_EXPORT_NAME = re.compile(r"(?:film-)?(?:mission(?:-\d+)?\.(?:plan|waypoints)|flight\.kml|"
                          r"flight\.geojson|photos\.csv|frames\.csv)")


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
    keep = {os.path.normcase(os.path.abspath(p)) for p in written}
    out = []
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    for name in names:
        if not _EXPORT_NAME.fullmatch(name):
            continue
        path = os.path.join(folder, name)
        if os.path.normcase(os.path.abspath(path)) in keep or os.path.islink(path) \
                or not os.path.isfile(path):
            continue
        if written_by_scanplan(path, KIND_OF_SUFFIX[os.path.splitext(name)[1].lower()]):
            out.append(path)
    return out
