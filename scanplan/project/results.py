"""The records of a planned project: what :func:`scanplan.project.spec.plan_project` returns.

:class:`PlanResult` (the specification of one project file: its :class:`ProjectModel`, the
film part :class:`FilmSpec`, the UAV part :class:`UavSpec`, the comparison, the warnings) and
the survey design's records (:class:`SurveyDesign`, :class:`GsdCompliance`,
:class:`SunPlan`, computed by :mod:`scanplan.project.design`). Records only: the modules that
compute them and the reports that render them both import from here.
"""

from __future__ import annotations

import datetime as dt
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core.blocks import BlockHeightCheck
from ..core.photoscale import height_at_photo_scale_m
from ..geo.layout import Area, FlightLayout
from ..geo.sun import FlyingDays, SunWindow
from ..rules.film import PlanWarning, ScanScenario
from .file import ReportMeta
from .jobs import ScanJob, UavJob
from .model import ProjectModel

if TYPE_CHECKING:  # the relief's modules are imported for a plan with [terrain] only
    from ..geo.terrain import TerrainResult
    from ..geo.terrain_film import FilmTerrain
    from .control import ControlSpec

__all__ = ["Alternative", "FilmSpec", "GsdCompliance", "PlanResult", "SunPlan", "SurveyDesign",
           "UavSpec"]


@dataclass(frozen=True)
class GsdCompliance:
    """The GSD of a workflow against the largest GSD of the plan scale (Table Б.1).

    Attributes
    ----------
    workflow : {"digital", "film"}
    map_scale : int
    area : str
        ``general`` or ``dense_urban``.
    limit_cm : float
        The table's largest GSD [cm].
    gsd_cm : float
        Digital: the GSD at the highest flown height of the recommended height; film: the
        scanned ground pixel, scan pixel × Mc [cm].
    complies : bool
    binding : bool
        Digital: GL is the binding constraint of the flight height.
    source : str
        The table row's source cell.
    status : str
        What the figure is (the row's status: a recommendation for Table Б.1).
    set_aside : str
        The project's reason for setting the recommendation aside (``""``: applied).
    """

    workflow: str
    map_scale: int
    area: str
    limit_cm: float
    gsd_cm: float
    complies: bool
    binding: bool
    source: str
    status: str = ""
    set_aside: str = ""


@dataclass(frozen=True)
class SunPlan:
    """The sun window at the site over the planned dates, and the flying days.

    Attributes
    ----------
    lat_deg, lon_deg : float
    utc_offset_h : float
        Local time = UTC + offset on the first date [h].
    min_elevation_deg : float
    elevation_source : str
        ``"project"`` or the norm set's parameter source.
    start_date, end_date : datetime.date
    windows : tuple of SunWindow
    sortie_time_s, turnaround_s : float
        The planned sortie (the one sortie length, :mod:`scanplan.project.sorties`; a
        layout's sorties are at most this long) and the ground time between sorties [s].
    flight_time_s : float or None
        Flight time of the whole survey [s] (None: no ``[area]``, or film).
    days : FlyingDays or None
    time_zone : str or None
        The site's IANA time zone the times are in (found from the coordinates); None
        when the project gives ``utc_offset_h``.
    """

    lat_deg: float
    lon_deg: float
    utc_offset_h: float
    min_elevation_deg: float
    elevation_source: str
    start_date: dt.date
    end_date: dt.date
    windows: tuple[SunWindow, ...]
    sortie_time_s: float
    turnaround_s: float
    flight_time_s: float | None
    days: FlyingDays | None
    time_zone: str | None = None

    @property
    def window_hours(self) -> tuple[float, float]:
        """Shortest and longest daily window over the dates [h]."""
        hours = [w.hours for w in self.windows]
        return min(hours), max(hours)


@dataclass(frozen=True)
class SurveyDesign:
    """What the survey design sheet shows beyond the specification."""

    gsd: tuple[GsdCompliance, ...]
    block: BlockHeightCheck | None
    block_source: str
    sun: SunPlan | None
    warnings: tuple[PlanWarning, ...]
    block_ground: str = ""  # "dem": the DEM's samples; "range": [terrain] ground_elevation_m
    block_waived: bool = False  # the flight follows the relief: the rule does not apply
    block_status: str = ""  # what the block relief numbers are (a draft's recommendation)
    block_set_aside: str = ""  # the project's reason for setting the rule aside
    sun_status: str = ""  # what the norm set's sun elevation is (practice); "" if the project's


@dataclass(frozen=True)
class FilmSpec:
    """The film part of a specification (``reason``: a :class:`~scanplan.i18n.messages.Message`,
    English text that renders in another locale with ``.text(locale)``)."""

    job: ScanJob
    recommended: ScanScenario | None
    reason: str
    frames: int | None
    strips: int | None
    scanned_gigabytes: float | None
    side_overlap_pct: float
    archive: bool = False  # existing photos at a given scale ([film] photo_scale)
    layout: FlightLayout | None = None  # the flight scheme at the recommended photo scale
    terrain: FilmTerrain | None = None  # [terrain]: the local photo scale of every frame
    flat: ScanScenario | None = None
    """[terrain]: the recommended photo scale as the engine gives it on flat ground (for
    comparison); ``recommended`` is then the engine's answer at the frame over the lowest
    ground (its ``local_photo_scale``), which the specification states."""
    rejected: tuple[tuple[ScanScenario, FilmTerrain], ...] = ()
    """[terrain]: the candidate scales with fewer frames (larger Mc) the relief ruled out,
    with their frames."""

    @property
    def flight_height_m(self) -> float | None:
        """The flight height above the ground of the recommended photo scale, H = Mc·f [m]
        (:func:`scanplan.core.photoscale.height_at_photo_scale_m`); None without a
        recommendation and for existing photos (no flight is planned)."""
        if self.recommended is None or self.archive:
            return None
        return float(height_at_photo_scale_m(self.recommended.photo_scale,
                                             self.job.plan.inputs.focal_mm))

    @property
    def flight_altitude_m(self) -> tuple[float, float] | None:
        """[terrain]: the lowest and the highest flight altitude of the frames over the
        relief [m] (the highest ground under a frame + Mc·f, in the ground's height system);
        None without frames over the relief."""
        ft = self.terrain
        if ft is None or not len(ft.altitude_m):
            return None
        return float(np.min(ft.altitude_m)), float(np.max(ft.altitude_m))


@dataclass(frozen=True)
class Alternative:
    """One plan a crew would consider for a UAV block, planned and costed
    (:mod:`scanplan.project.alternatives`, docs/plan-choice.md).

    Attributes
    ----------
    mode : str or None
        Altitude mode (``constant``, ``strip``, ``follow``; None on flat ground).
    direction : str
        Which line direction: ``auto`` (the least flight length), ``long_axis`` (the area's
        long axis), ``relief`` (strips spanning the least relief), ``project`` (the one the
        project gives), ``block`` (the ``width_m × length_m`` block, flown along its length).
    direction_deg : float or None
        The lines' direction as laid out, clockwise from grid north [°].
    parts : int
        Parts of the block flown at their own height (> 1: split by ground height).
    height_m : float or None
        The planned height above the reference ground [m].
    n_photos, n_strips, n_sorties : int or None
    flight_length_m, flight_time_s : float or None
        With the turns, the run-in and run-out and the sorties' transit [m], [s].
    data_volume_bytes : float or None
        Uncompressed.
    gsd_min_m, gsd_max_m : float or None
        GSD at the lowest and the highest heights above ground flown [m].
    binding : str or None
        The constraint that sets the height.
    feasible : bool
        Meets every constraint (``rejected_because`` is empty).
    rejected_because : tuple of Message
        What it misses.
    findings : tuple of Message
        What it holds only within an allowance (an overlap a few tenths short).
    heights_tried : tuple of (float, bool)
        Over relief, every height its layout was laid out at and checked, and whether its
        worst photo met every limit, in the order tried [m] (the fixed point).
    estimate : bool
        Costed but not laid out and checked photo by photo (what it needs is in
        ``rejected_because``).
    allowed : bool
        The project's choices (``[terrain] altitude_mode``, ``[area] direction_deg``)
        allow it.
    recommended : bool
        The plan of the specification.
    """

    mode: str | None
    direction: str
    direction_deg: float | None
    parts: int
    height_m: float | None
    n_photos: int | None
    n_strips: int | None
    n_sorties: int | None
    flight_length_m: float | None
    flight_time_s: float | None
    data_volume_bytes: float | None
    gsd_min_m: float | None
    gsd_max_m: float | None
    binding: str | None
    feasible: bool
    rejected_because: tuple[Any, ...] = ()
    estimate: bool = False
    allowed: bool = True
    recommended: bool = False
    findings: tuple[Any, ...] = ()
    heights_tried: tuple[tuple[float, bool], ...] = ()

    @property
    def cost(self) -> tuple[float, float]:
        """What the choice minimises: (flying time [s], photos); unknown ones last."""
        t = self.flight_time_s
        n = self.n_photos
        return (t if t is not None else math.inf, float(n) if n is not None else math.inf)


@dataclass(frozen=True)
class UavSpec:
    """The UAV part of a specification (the flight at the recommended height; ``reason``: a
    :class:`~scanplan.i18n.messages.Message`)."""

    job: UavJob
    planned_height_m: float | None
    recommended_height_m: float | None
    max_height_m: float | None  # the maximum PLANNED height (highest flown meets every limit)
    reason: str
    terrain: TerrainResult | None = None  # [terrain]: every photo over its own ground
    terrain_warnings: tuple[PlanWarning, ...] = ()
    alternatives: tuple[Alternative, ...] = ()
    """The plans compared (one marked ``recommended``); empty when there was no choice."""
    choice: str | None = None
    """Why this plan among the plans compared (a Message; None without a choice)."""

    @property
    def layout(self) -> FlightLayout | None:
        """Strips and photo centres at the recommended height (None without an area)."""
        return self.job.layout


@dataclass(frozen=True)
class PlanResult:
    """Everything ``scanplan plan`` reports for one project."""

    project: ProjectModel
    """The project file as parsed (:mod:`scanplan.project.model`)."""
    meta: ReportMeta
    film: FilmSpec | None
    uav: UavSpec | None
    comparison: list[dict[str, Any]] = field(default_factory=list)
    warnings: tuple[PlanWarning, ...] = ()
    design: SurveyDesign | None = None
    """The survey design checks: GSD against ГОСТ Р 59562-2021 Table Б.1, the one-height
    rule of a block, the sun window (:mod:`scanplan.project.design`)."""
    area: Area | None = None  # the contract area ([area]), in its planning CRS
    control: ControlSpec | None = None  # [control]: GCPs, checkpoints, the error budget
    exports_written: frozenset[str] | None = None
    """The exported formats (``csv``, ``plan`` … :data:`scanplan.geo.export.FORMATS` names)
    the run that renders the documents writes beside them; None: the documents alone
    (``--pdf FILE``, the API's ``write``), so they never say a file is beside them."""
    backgrounds: dict[str, Any] = field(default_factory=dict)
    """``[map] basemap`` as a tile URL: each map page's background by job (``"uav"``,
    ``"film"``), a :class:`scanplan.geo.basemap.Basemap` in its layout's planning CRS
    (:mod:`scanplan.project.background`)."""

    @property
    def layouts(self) -> dict[str, FlightLayout]:
        """The flight layouts by job, ``{"film": ..., "uav": ...}`` (those that exist)."""
        out = {}
        if self.film is not None and self.film.layout is not None:
            out["film"] = self.film.layout
        if self.uav is not None and self.uav.layout is not None:
            out["uav"] = self.uav.layout
        return out
