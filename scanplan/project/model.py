"""The project file parsed once: frozen, typed sections every consumer reads.

:func:`build_model` turns a loaded :class:`~scanplan.project.file.Project` (the TOML's keys,
their types checked by the loader) into a :class:`ProjectModel`: ``map``, ``film``, ``uav``,
``area``, ``flight``, ``terrain`` (with the DEM resolved beside the project file), ``site``,
``schedule``, ``norms`` and the signing blocks (``meta``, ``signing``). Each key is read
through the input registry (:mod:`scanplan.project.inputs`): its default, its choices and its
domain (lo, hi, unit — :func:`field_meta`, as QGroundControl's ``FactMetaData`` describes a
parameter), and a value outside them is refused here, once, naming the key and its line
(:meth:`ProjectModel.where`) and the range. Nothing above :mod:`scanplan.project` reads the
TOML; the specification, the survey design and the reports read this model.
"""

from __future__ import annotations

import datetime as dt
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ..core.domains import Domain, check_domain
from ..errors import InputError
from .file import Project, ReportMeta
from .inputs import by_key, domain_of, project_key, records

if TYPE_CHECKING:
    from ..geo.terrain import TerrainConfig

__all__ = ["AUTO_MODE", "AreaSection", "ControlSection", "FieldMeta", "FilmSection",
           "FlightSection", "FrozenMap", "MapSection", "NormsSection", "ProjectModel",
           "ScheduleSection", "Signing", "SiteSection", "TerrainSection", "UavSection",
           "build_model", "field_meta"]


AUTO_MODE = "auto"
"""``[terrain] altitude_mode`` that leaves the mode to the specification (the default)."""


class FrozenMap(dict):  # type: ignore[type-arg]
    """A read-only dict (a section's keys and values): it pickles and compares as a dict.

    >>> m = FrozenMap(a=1)
    >>> m["a"] = 2
    Traceback (most recent call last):
    TypeError: a parsed project file is read-only
    """

    def _read_only(self, *args: Any, **kwargs: Any) -> None:
        raise TypeError("a parsed project file is read-only")

    __setitem__ = __delitem__ = clear = pop = popitem = setdefault = update = _read_only
    __ior__ = _read_only  # type: ignore[assignment]

    def __reduce__(self) -> tuple[Any, ...]:
        return (FrozenMap, (dict(self),))


@dataclass(frozen=True)
class FieldMeta:
    """What the registry says about one project-file key.

    Attributes
    ----------
    section, key : str
        Where the file holds it.
    name : str
        The Python name (the API's keyword).
    unit : str
        Its unit (``""``: a pure number or text).
    default : object
        The registry's default (None: none, or it depends on other keys).
    domain : Domain or None
        Its range (None: no numeric domain).
    choices : tuple of str
        The allowed texts (empty: any).
    digits : int or None
        The decimals a value is shown with (None: not a number shown with decimals).
    """

    section: str
    key: str
    name: str
    unit: str
    default: Any
    domain: Domain | None
    choices: tuple[str, ...]
    digits: int | None = None


def field_meta(section: str, key: str) -> FieldMeta:
    """The registry's record of ``section.key`` as :class:`FieldMeta`.

    >>> m = field_meta("site", "lat_deg")
    >>> m.unit, m.domain.lo, m.domain.hi, m.digits
    ('°', -90, 90, 4)
    """
    r = by_key(section, key)
    return FieldMeta(section, key, r.name, r.unit, r.default, domain_of(r), r.choices,
                     r.digits)


@dataclass(frozen=True)
class MapSection:
    """``[map]``: the map scale denominator Mk and the relief interval h_c [m]; the
    background of the PDF's map page — a GeoTIFF or MBTiles file beside the project file
    (header checked, ``basemap``) or an XYZ tile URL template (``basemap_url``) — and its
    attribution."""

    scale: float
    relief_interval_m: float
    basemap: Path | None = None
    basemap_attribution: str = ""
    basemap_url: str | None = None


@dataclass(frozen=True)
class Signing:
    """``[project]`` texts of the survey design sheet beyond the title and signature blocks
    (those are :attr:`ProjectModel.meta`); ``""`` when not given."""

    purpose: str = ""
    coordinate_system: str = ""
    height_system: str = ""


@dataclass(frozen=True)
class NormsSection:
    """``[norms]`` keys the specification reads itself (the rest go to the jobs).

    ``gsd_area`` is None when the file does not say (the set's ``general`` row applies);
    the reasons are ``""`` when the recommendation is applied."""

    gsd_area: str | None = None
    gsd_limit_reason: str = ""
    block_relief_reason: str = ""


@dataclass(frozen=True)
class FilmSection:
    """``[film]``.

    Attributes
    ----------
    given : Mapping
        Python name → value of every registry input of the film plan the file gives (a key
        of ``[film]`` winning over a shared one of the same name): the job's keywords.
    photo_scale : float or None
        The scale of existing (archive) photos; None: candidates are chosen from.
    side_overlap_pct : float
        Side overlap of the flight scheme [%] (the registry's default when not given).
    """

    given: FrozenMap
    photo_scale: float | None
    side_overlap_pct: float

    @property
    def archive(self) -> bool:
        """Whether the photos exist at a given scale (``[film] photo_scale``)."""
        return self.photo_scale is not None


@dataclass(frozen=True)
class UavSection:
    """``[uav]``: ``given`` as :attr:`FilmSection.given`; the planned height [m] (None: the
    specification recommends one) and the ground speed [m/s] (the registry's default)."""

    given: FrozenMap
    height_m: float | None
    speed_ms: float


@dataclass(frozen=True)
class AreaSection:
    """``[area]`` (every key None when not given)."""

    file: str | None = None
    layer: str | None = None
    feature: str | int | None = None
    polygon: list[Any] | None = None
    crs: str | int | None = None
    plan_crs: str | int | None = None
    width_m: float | None = None
    length_m: float | None = None
    direction_deg: float | str | None = None
    extension_bases: int | None = None

    @property
    def rectangle(self) -> tuple[float, float] | None:
        """``(width_m, length_m)`` of the block [m], or None."""
        if self.width_m is None or self.length_m is None:
            return None
        return self.width_m, self.length_m


@dataclass(frozen=True)
class FlightSection:
    """The flight layout's keys: turns (``[uav]``, None when not given) and the take-off
    point ``[flight] takeoff`` ([lon, lat], WGS 84)."""

    turnaround_m: float | None = None
    turn_radius_m: float | None = None
    bank_deg: float | None = None
    takeoff: list[float] | None = None
    max_flight_time_min: float | None = None
    aircraft: str | None = None
    max_flying_days: int | None = None
    crosshatch: bool = False


@dataclass(frozen=True)
class TerrainSection:
    """``[terrain]``: its configuration (the DEM resolved beside the project file, every
    value checked) and the keys of the one-height rule."""

    config: TerrainConfig
    ground_elevation_m: list[float] | None
    relief_class: str
    altitude_mode: str
    """``[terrain] altitude_mode`` as given: a mode the plan keeps, or ``"auto"`` (the
    default: the specification compares the modes, :mod:`scanplan.project.alternatives`);
    ``config.altitude_mode`` is then ``"constant"``, the mode a film plan flies."""


@dataclass(frozen=True)
class SiteSection:
    """``[site]``: latitude and longitude [°] (None when not given)."""

    lat_deg: float | None = None
    lon_deg: float | None = None


@dataclass(frozen=True)
class ScheduleSection:
    """``[schedule]`` (each None when not given): the dates, the UTC offset [h], the sortie
    and ground times [min], the lowest sun elevation [°]."""

    start_date: dt.date | None = None
    end_date: dt.date | None = None
    utc_offset_h: float | None = None
    sortie_time_min: float | None = None
    turnaround_min: float | None = None
    min_sun_elevation_deg: float | None = None


@dataclass(frozen=True)
class ControlSection:
    """``[control]``: how the block is controlled (``mode``), the survey's precision of the
    GCPs and checkpoints [m], the checkpoints (None: the ASPRS count for the area) and the
    GCP density [GCP/ha] (None: the rule's)."""

    mode: str
    gcp_sigma_xy_m: float
    gcp_sigma_z_m: float
    checkpoints: int | None
    gcp_per_ha: float | None = None


@dataclass(frozen=True)
class ProjectModel:
    """A project file parsed once (see the module).

    ``film``/``uav``/``terrain`` are None when the file has no such section; ``site`` and
    ``schedule`` are None likewise (their keys are then all absent).
    """

    path: Path
    name: str
    meta: ReportMeta
    signing: Signing
    map: MapSection
    norms: NormsSection
    area: AreaSection
    flight: FlightSection
    film: FilmSection | None
    uav: UavSection | None
    terrain: TerrainSection | None
    site: SiteSection | None
    schedule: ScheduleSection | None
    lines: FrozenMap = field(default_factory=lambda: FrozenMap())
    control: ControlSection | None = None

    def where(self, section: str, key: str | None = None) -> str:
        """``section.key (line N)`` — how errors name a key; ``where("site.lat_deg")`` too.

        >>> m = build_model(Project(Path("p.toml"), "p", {"map": {"scale": 2000,
        ...     "relief_interval_m": 1}, "uav": {}}, {"map.scale": 2}))
        >>> m.where("map", "scale"), m.where("map.relief_interval_m")
        ('map.scale (line 2)', 'map.relief_interval_m')
        """
        if key is None:
            section, _, key = section.rpartition(".")
        dotted = f"{section}.{key}"
        line = self.lines.get(dotted) or self.lines.get(section)
        return f"{dotted} (line {line})" if line else dotted

    def at(self, section: str, key: str | None = None) -> str:
        """``FILE: section.key (line N)``: an error's field."""
        return f"{self.path}: {self.where(section, key)}"

    def named(self, exc: InputError, plan: str, *, archive: bool = False) -> InputError:
        """An engine's error (its ``field`` a Python name, :mod:`scanplan.project.inputs`)
        naming the project key of ``plan`` and its line instead.

        >>> m = build_model(Project(Path("p.toml"), "p", {"map": {"scale": 2000,
        ...     "relief_interval_m": 1}, "uav": {"speed_ms": 900}}, {"uav.speed_ms": 5}))
        >>> m.named(InputError("speed_ms", "must be ≤ 500 m/s"), "uav").field
        'p.toml: uav.speed_ms (line 5)'
        """
        found = project_key(exc.field, plan)
        if found is None:
            return InputError(f"{self.path}: {exc.field}", exc.message)
        section, key = found
        if archive and (section, key) == ("film", "photo_scales"):
            key = "photo_scale"  # existing photos: the one scale the file gave
        where = self.where(section, key) if section else key
        return InputError(f"{self.path}: {where}", exc.message)


class _Reader:
    """The loaded file's values read key by key, each checked against its registry record."""

    def __init__(self, project: Project) -> None:
        self.p = project

    def where(self, section: str, key: str) -> str:
        return f"{self.p.path}: {self.p.where(section, key)}"

    def raw(self, section: str, key: str, default: Any = None) -> Any:
        return self.p.get(section, key, default)

    def text(self, section: str, key: str) -> str:
        return self.p.get(section, key) or ""

    def ranged(self, section: str, key: str) -> float | None:
        """The value (None when absent) within its registry domain, or :class:`InputError`
        naming the key, e.g. ``schedule.turnaround_min (line 12): must be ≥ 0 and ≤ 1440
        min (got 2000)``."""
        value = self.p.get(section, key)
        if value is None:
            return None
        d = domain_of(by_key(section, key))
        assert d is not None, f"{section}.{key} has no domain in the input registry"
        v = float(value)
        if v < d.lo or v > d.hi or (d.lo_open and v == d.lo) or (d.hi_open and v == d.hi):
            low = f"> {d.lo:g}" if d.lo_open else f"≥ {d.lo:g}"
            high = f"< {d.hi:g}" if d.hi_open else f"≤ {d.hi:g}"
            raise InputError(self.where(section, key),
                             f"must be {d.meaning + ' ' if d.meaning else ''}{low} and "
                             f"{high}{' ' + d.unit if d.unit else ''} (got {value!r})")
        return v

    def choice(self, section: str, key: str, allowed: tuple[str, ...]) -> str | None:
        """The text (None when absent) among ``allowed`` (the registry's choices)."""
        value = self.p.get(section, key)
        if value is not None and value not in allowed:
            raise InputError(self.where(section, key),
                             f"must be one of {', '.join(allowed)} (got {value!r})")
        return value

    def date(self, section: str, key: str) -> dt.date | None:
        value = self.p.get(section, key)
        if value is None or isinstance(value, dt.date):
            return value
        return dt.date.fromisoformat(value)

    def given(self, plan: str) -> FrozenMap:
        """Python name → value of every input of ``plan`` the file gives; a key of the
        plan's own section wins over a shared one (``[uav] height_formula`` over ``[norms]
        height_formula``)."""
        own = {r.name for r in records(plan) if r.section.split(".")[0] == plan}
        out: dict[str, Any] = {}
        for r in records(plan):
            shared = r.section.split(".")[0] != plan
            if not r.key or (shared and r.name in own):
                continue
            value = self.p.get(r.section, r.key)
            if value is not None:
                out[r.name] = value
        return FrozenMap(out)


def _meta(r: _Reader) -> ReportMeta:
    keys = ("customer", "contractor", "approver_position", "approver_name", "organisation",
            "contract_number", "compiled_by", "checked_by", "agreed_position", "agreed_name",
            "agreed_organisation")
    return ReportMeta(project=r.p.name, locale=r.raw("project", "locale", "en"),
                      **{k: r.raw("project", k, "") for k in keys})


def _area(r: _Reader) -> AreaSection:
    """``[area]``; width and length both or neither, each in its domain."""
    width, length = r.raw("area", "width_m"), r.raw("area", "length_m")
    if width is not None or length is not None:
        for key, value in (("width_m", width), ("length_m", length)):
            if value is None:
                raise InputError(r.where("area", key), "is required with the other side of "
                                 "[area]: give both width_m and length_m")
            try:
                check_domain(f"area_{key}", value)
            except InputError as exc:
                raise InputError(r.where("area", key), exc.message) from None
    g = r.raw
    return AreaSection(
        file=g("area", "file"), layer=g("area", "layer"), feature=g("area", "feature"),
        polygon=g("area", "polygon"), crs=g("area", "crs"), plan_crs=g("area", "plan_crs"),
        width_m=None if width is None else float(width),
        length_m=None if length is None else float(length),
        direction_deg=g("area", "direction_deg"), extension_bases=g("area", "extension_bases"))


def _sortie(r: _Reader) -> tuple[float | None, float | None]:
    """``[uav] max_flight_time_min`` and ``[schedule] sortie_time_min`` [min]: each in
    range, and the same number when both are given (one sortie length,
    :mod:`scanplan.project.sorties`)."""
    uav = r.ranged("uav", "max_flight_time_min")
    schedule = r.ranged("schedule", "sortie_time_min")
    if uav is not None and schedule is not None and not math.isclose(uav, schedule,
                                                                     rel_tol=1e-9):
        raise InputError(
            r.where("schedule", "sortie_time_min"),
            f"is {schedule:g} min but {r.p.where('uav', 'max_flight_time_min')} is "
            f"{uav:g} min: both are the flight time of one sortie, which splits the flight "
            "layout and counts the flying days; give one of them (or the same number)")
    return uav, schedule


def _flying_days(r: _Reader) -> int | None:
    """``[flight] max_flying_days`` in range (None when not given)."""
    days = r.ranged("flight", "max_flying_days")
    return None if days is None else int(days)


def _aircraft(r: _Reader) -> str | None:
    """``[uav] aircraft``: a catalogue id (else exit 2 naming the key and the ids)."""
    value = r.raw("uav", "aircraft")
    if value is None:
        return None
    from ..norms.aircraft import aircraft

    try:
        return aircraft(str(value)).id
    except InputError as exc:
        raise InputError(r.where("uav", "aircraft"), exc.message) from None


def _basemap(r: _Reader) -> tuple[Path | None, str | None, str]:
    """``[map] basemap`` and its attribution: (file, URL template, attribution).

    A file — a GeoTIFF (its header checked as a DEM's) or an MBTiles file beside the project
    file (:func:`scanplan.geo.basemap.check_basemap`) —, or ``"osm"`` (OpenStreetMap's
    tiles) or an XYZ URL template (:func:`scanplan.geo.tiles.check_template`), whose
    tiles are printed only with their attribution (``[map] basemap_attribution``,
    OpenStreetMap's own for ``"osm"``)."""
    name = r.text("map", "basemap").strip()
    attribution = r.text("map", "basemap_attribution").strip()
    if not name:
        return None, None, attribution
    from ..geo.tiles import OSM_ATTRIBUTION, OSM_URL, check_template

    if name == "osm":
        return None, OSM_URL, attribution or OSM_ATTRIBUTION
    if "://" in name or any(k in name for k in ("{z}", "{x}", "{y}")):
        try:
            check_template(name, allowed='a GeoTIFF or MBTiles file, "osm" or ')
        except InputError as exc:
            raise InputError(r.where("map", "basemap"), exc.message) from None
        if not attribution:
            raise InputError(r.where("map", "basemap_attribution"), "is needed with a tile "
                             "URL: the tiles' source as their provider asks it printed, e.g. "
                             '"© OpenStreetMap contributors"')
        return None, name, attribution
    from ..geo.basemap import check_basemap

    path = Path(name) if Path(name).is_absolute() else r.p.path.parent / name
    try:
        check_basemap(path, "basemap")
    except InputError as exc:
        raise InputError(r.where("map", "basemap"), exc.message) from None
    return path, None, attribution


def _map_section(r: _Reader) -> MapSection:
    """``[map]``: the scale, the relief interval and the background."""
    path, url, attribution = _basemap(r)
    return MapSection(r.raw("map", "scale"), r.raw("map", "relief_interval_m"), path,
                      attribution, url)


def _terrain(r: _Reader) -> TerrainSection | None:
    """``[terrain]`` as a checked configuration (the DEM beside the project file)."""
    if not r.p.has("terrain"):
        return None
    from ..geo.dem_grid import DEFAULT_VOID_MARGIN_M, DEFAULT_VOID_RADIUS_M
    from ..geo.terrain import TerrainConfig

    g = r.raw
    dem = g("terrain", "dem")
    rng = g("terrain", "ground_elevation_m")
    mode = g("terrain", "altitude_mode", field_meta("terrain", "altitude_mode").default)
    relief = _relief_class(r)  # each key's own value first (named), then the section's keys
    try:
        cfg = TerrainConfig(
            dem=(Path(dem) if Path(dem).is_absolute() else r.p.path.parent / dem)
            if dem is not None and dem.strip() else (Path("") if dem is not None else None),
            ground_range_m=(float(rng[0]), float(rng[1])) if rng is not None else None,
            altitude_mode="constant" if mode == AUTO_MODE else mode,  # auto: chosen later
            follow_tolerance_m=float(g("terrain", "follow_tolerance_m",
                                       field_meta("terrain", "follow_tolerance_m").default)),
            vertical_unit=g("terrain", "vertical_unit"),
            void_fill_radius_m=float(g("terrain", "void_fill_radius_m", DEFAULT_VOID_RADIUS_M)),
            void_fill_margin_m=float(g("terrain", "void_fill_margin_m", DEFAULT_VOID_MARGIN_M)))
    except InputError as exc:
        if exc.field.startswith("terrain.") or exc.field == "terrain":
            section, _, key = exc.field.partition(".")
            where = r.p.where(section, key) if key else f"[{section}]"
            raise InputError(f"{r.p.path}: {where}", exc.message) from None
        raise
    return TerrainSection(cfg, rng, relief, mode)


def _relief_class(r: _Reader) -> str:
    meta = field_meta("terrain", "relief_class")
    return r.choice("terrain", "relief_class", meta.choices) or meta.default


def _film(r: _Reader) -> FilmSection | None:
    if not r.p.has("film"):
        return None
    side = r.raw("film", "side_overlap_pct", field_meta("film", "side_overlap_pct").default)
    try:
        check_domain("side_overlap_pct", side)
    except InputError as exc:
        raise InputError(r.where("film", "side_overlap_pct"), exc.message) from None
    return FilmSection(r.given("film"), r.raw("film", "photo_scale"), side)


def _uav(r: _Reader) -> UavSection | None:
    if not r.p.has("uav"):
        return None
    return UavSection(r.given("uav"), r.raw("uav", "height_m"),
                      r.raw("uav", "speed_ms", field_meta("uav", "speed_ms").default))


def _schedule(r: _Reader, sortie_min: float | None) -> ScheduleSection | None:
    """``[schedule]``: the offset, sun elevation and ground time in range (the order the
    survey design reads them)."""
    offset = r.ranged("schedule", "utc_offset_h")
    elev = r.ranged("schedule", "min_sun_elevation_deg")
    turn = r.ranged("schedule", "turnaround_min")
    if not r.p.has("schedule"):
        return None
    return ScheduleSection(r.date("schedule", "start_date"), r.date("schedule", "end_date"),
                           offset, sortie_min, turn, elev)


def _control(r: _Reader) -> ControlSection | None:
    """``[control]``: every key in its domain (a count of 10⁷ checkpoints or a negative
    precision is refused naming the key and the range)."""
    if not r.p.has("control"):
        return None
    mode = r.choice("control", "mode", field_meta("control", "mode").choices) \
        or field_meta("control", "mode").default
    checkpoints = r.raw("control", "checkpoints", "asprs")
    count = None if checkpoints == "asprs" else r.ranged("control", "checkpoints")

    def sigma(key: str) -> float:
        v = r.ranged("control", key)
        return float(field_meta("control", key).default) if v is None else v

    return ControlSection(mode, sigma("gcp_sigma_xy_m"), sigma("gcp_sigma_z_m"),
                          None if count is None else int(count),
                          r.ranged("control", "gcp_per_ha"))


def build_model(project: Project) -> ProjectModel:
    """The project file as a :class:`ProjectModel`, every key checked against the registry.

    Parameters
    ----------
    project : Project
        A loaded project file (:func:`scanplan.project.file.load_project`).

    Raises
    ------
    InputError
        Naming the file, the key and its line, and the allowed range or values, for a
        value outside its domain or choices, an ``[area]`` side without the other, two
        different sortie lengths, or a ``[terrain]`` that does not hold together.
    """
    r = _Reader(project)
    area = _area(r)
    uav_sortie, schedule_sortie = _sortie(r)
    terrain = _terrain(r)
    film = _film(r)
    uav = _uav(r)
    gsd_area = r.choice("norms", "gsd_area", field_meta("norms", "gsd_area").choices)
    site = SiteSection(r.ranged("site", "lat_deg"), r.ranged("site", "lon_deg"))
    schedule = _schedule(r, schedule_sortie)
    control = _control(r)
    g = r.raw
    return ProjectModel(
        path=project.path, name=project.name, meta=_meta(r),
        signing=Signing(r.text("project", "purpose"), r.text("project", "coordinate_system"),
                        r.text("project", "height_system")),
        map=_map_section(r),
        norms=NormsSection(gsd_area, r.text("norms.gsd_limits", "reason"),
                           r.text("norms.block_relief", "reason")),
        area=area,
        flight=FlightSection(g("uav", "turnaround_m"), g("uav", "turn_radius_m"),
                             g("uav", "bank_deg"), g("flight", "takeoff"), uav_sortie,
                             _aircraft(r), _flying_days(r), bool(g("uav", "crosshatch", False))),
        film=film, uav=uav, terrain=terrain,
        site=site if project.has("site") else None, schedule=schedule,
        lines=FrozenMap(project.lines), control=control)
