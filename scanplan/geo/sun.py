"""The sun window of a survey: when the sun stands high enough, and how many flying days.

Aerial photographs are taken only while the sun is above a required elevation (norm
parameter ``min_sun_elevation_deg``): lower sun lengthens shadows that hide the ground
and darkens the image. This module finds, for a site and a range of dates, the hours each
day when the sun is at or above that elevation, and how many days the sorties of a flight
need when each day offers only its window.

The solar position is astral's implementation of the NOAA solar calculator, after Meeus,
*Astronomical Algorithms* (``astral.sun.elevation``): the apparent elevation, with
atmospheric refraction, is used. Against the NREL SPA (Reda & Andreas 2004) it differs by
less than 0.01° over the years of a survey, far inside the 2-minute search step. The
window's times are the site's legal time: its IANA time zone is found offline from the
coordinates (tzfpy's time-zone boundaries) and its rules read by :mod:`zoneinfo`. No
astronomy and no time-zone rule is written here.

>>> import datetime as dt
>>> w = sun_windows([dt.date(2025, 6, 21)], 55.75, 37.62, 30.0, utc_offset_h=3)[0]
>>> round(w.hours, 1), w.start_local.strftime("%H:%M")
(9.4, '07:50')
>>> time_zone_at(55.75, 37.62)
'Europe/Moscow'
"""

from __future__ import annotations

import datetime as dt
import functools
import math
import zoneinfo
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["FlyingDays", "SunWindow", "equal_sorties_s", "flying_days", "sun_elevation_deg",
           "sun_windows", "time_zone_at", "utc_offset_h_on", "zone_country"]

STEP_MIN = 2.0
"""Time step of the daily search [min]: windows are accurate to about this step."""


def sun_elevation_deg(times_utc: ArrayLike, lat_deg: float, lon_deg: float,
                      altitude_m: float = 0.0) -> NDArray[np.float64]:
    """Apparent sun elevation above the horizon (refraction included) [°].

    Parameters
    ----------
    times_utc : array_like of datetime64 or datetime
        Instants in UTC (naive values are read as UTC).
    lat_deg, lon_deg : float
        Site latitude (north positive) and longitude (east positive), WGS 84 [°].
    altitude_m : float
        Site height above sea level [m] (default 0); astral's observer elevation, which
        changes the apparent elevation by less than 0.01° at survey sites.

    Returns
    -------
    ndarray
        Elevation [°], one per instant.

    Notes
    -----
    astral's NOAA solar calculator (Meeus 1998, chapters 22–25), with its refraction
    correction for the standard atmosphere.
    """
    from astral import Observer
    from astral.sun import elevation

    times = np.atleast_1d(np.asarray(times_utc, dtype="datetime64[us]"))
    observer = Observer(float(lat_deg), float(lon_deg), float(altitude_m))
    utc = dt.UTC
    return np.fromiter(
        (elevation(observer, t.replace(tzinfo=utc)) for t in times.astype(dt.datetime)),
        dtype=np.float64, count=times.size)


def time_zone_at(lat_deg: float, lon_deg: float) -> str:
    """The IANA time zone of a point (e.g. ``"Asia/Novosibirsk"``), found offline.

    Parameters
    ----------
    lat_deg, lon_deg : float
        The point, WGS 84 [°].

    Returns
    -------
    str
        The zone's name; over the open sea the nautical zone (``"Etc/GMT-5"``).

    Notes
    -----
    tzfpy's time-zone boundary data (built from the timezone-boundary-builder polygons of
    OpenStreetMap); no network.
    """
    import tzfpy

    return str(tzfpy.get_tz(float(lon_deg), float(lat_deg)))


def zone_country(time_zone: str) -> str | None:
    """The ISO 3166 country code of an IANA zone (``"RU"`` for ``"Asia/Novosibirsk"``), from
    the time-zone database's ``zone.tab`` (tzdata's, else the system's); None when the zone
    is no country's (``"Etc/GMT-5"``) or the table is missing.

    >>> zone_country("Asia/Novosibirsk"), zone_country("Etc/GMT-5")
    ('RU', None)
    """
    return _zone_countries().get(time_zone)


def _zone_countries() -> dict[str, str]:
    if _ZONE_COUNTRIES:
        return _ZONE_COUNTRIES
    text = ""
    try:
        from importlib.resources import files

        text = files("tzdata.zoneinfo").joinpath("zone.tab").read_text(encoding="utf-8")
    except (ImportError, OSError):
        for folder in ("/usr/share/zoneinfo", "/usr/lib/zoneinfo"):
            try:
                with open(f"{folder}/zone.tab", encoding="utf-8") as f:
                    text = f.read()
                break
            except OSError:
                continue
    for line in text.splitlines():
        parts = line.split("\t")
        if len(parts) >= 3 and not line.startswith("#"):
            _ZONE_COUNTRIES[parts[2]] = parts[0]
    return _ZONE_COUNTRIES


_ZONE_COUNTRIES: dict[str, str] = {}


def utc_offset_h_on(time_zone: str, date: dt.date) -> float:
    """The legal offset from UTC of a zone at local noon of a date [h] (summer time included).

    >>> utc_offset_h_on("Europe/Berlin", dt.date(2025, 7, 1))
    2.0
    """
    noon = dt.datetime.combine(date, dt.time(12), tzinfo=zoneinfo.ZoneInfo(time_zone))
    offset = noon.utcoffset()
    assert offset is not None
    return offset.total_seconds() / 3600.0


@dataclass(frozen=True)
class SunWindow:
    """One day's window: the sun at or above the required elevation.

    Attributes
    ----------
    date : datetime.date
        The local calendar date.
    start_local, end_local : datetime.datetime or None
        First and last instant of the window, in local time (the zone's, or
        ``utc_offset_h``'s), naive; None when the sun never reaches the elevation that day.
    hours : float
        Length of the window [h].
    max_elevation_deg : float
        Highest sun elevation of the day [°].
    """

    date: dt.date
    start_local: dt.datetime | None
    end_local: dt.datetime | None
    hours: float
    max_elevation_deg: float
    utc_offset_h: float = 0.0
    """The day's offset of local time from UTC [h]."""


def sun_windows(dates: Sequence[dt.date], lat_deg: float, lon_deg: float,
                min_elevation_deg: float, *, utc_offset_h: float | None = None,
                time_zone: str | None = None,
                step_min: float = STEP_MIN) -> tuple[SunWindow, ...]:
    """The sun window of each date at a site.

    Parameters
    ----------
    dates : sequence of datetime.date
        Local calendar dates.
    lat_deg, lon_deg : float
        The site, WGS 84 [°].
    min_elevation_deg : float
        Required sun elevation [°].
    utc_offset_h : float, optional
        Local time = UTC + offset [h], the same on every date.
    time_zone : str, optional
        IANA zone whose legal time (summer time included) the dates and times are in;
        default the site's (:func:`time_zone_at`). Ignored when ``utc_offset_h`` is given.
    step_min : float
        Search step [min].

    Returns
    -------
    tuple of SunWindow
        One per date. The window is taken as the span between the first and last instant
        at or above the elevation (the sun's elevation has one maximum a day outside the
        polar regions).
    """
    if not dates:
        return ()
    return _sun_windows(tuple(dates), float(lat_deg), float(lon_deg), float(min_elevation_deg),
                        None if utc_offset_h is None else float(utc_offset_h), time_zone,
                        float(step_min))


@functools.lru_cache(maxsize=32)
def _sun_windows(dates: tuple[dt.date, ...], lat_deg: float, lon_deg: float,
                 min_elevation_deg: float, utc_offset_h: float | None, time_zone: str | None,
                 step_min: float) -> tuple[SunWindow, ...]:
    """:func:`sun_windows`, each site's and dates' windows computed once per process (a
    re-plan that moves no date and not the site asks them again; the windows are
    immutable)."""
    if utc_offset_h is not None:
        offsets = [float(utc_offset_h)] * len(dates)
    else:
        zone = time_zone or time_zone_at(lat_deg, lon_deg)
        offsets = [utc_offset_h_on(zone, d) for d in dates]
    n = round(24 * 60 / step_min)
    seconds = np.round(np.arange(n) * step_min * 60.0).astype(np.int64)
    day0 = np.array([np.datetime64(d.isoformat(), "s") for d in dates])
    local = day0[:, None] + seconds.astype("timedelta64[s]")[None, :]
    # the day's offset at local noon: a summer-time change falls at night, outside a window
    shift = np.array([round(o * 3600) for o in offsets], dtype=np.int64)
    utc = local - shift.astype("timedelta64[s]")[:, None]
    elev = sun_elevation_deg(utc.ravel(), lat_deg, lon_deg).reshape(local.shape)
    out = []
    for i, d in enumerate(dates):
        up = np.flatnonzero(elev[i] >= min_elevation_deg)
        if up.size == 0:
            out.append(SunWindow(d, None, None, 0.0, float(elev[i].max()), offsets[i]))
            continue
        first, last = int(up[0]), int(up[-1])
        start = local[i, first].astype(dt.datetime)
        end = local[i, last].astype(dt.datetime)
        out.append(SunWindow(d, start, end, (last - first) * step_min / 60.0,
                             float(elev[i].max()), offsets[i]))
    return tuple(out)


@dataclass(frozen=True)
class FlyingDays:
    """How many days the sorties need inside the daily sun windows.

    Attributes
    ----------
    days : int or None
        Flying days needed (days with a window, counted from the first date); None when
        the dates end first.
    sorties : int
        Sorties to fly.
    sorties_per_day : tuple of int
        Sorties flown on each date until the work is done.
    last_date : datetime.date or None
        The date the last sortie is flown.
    """

    days: int | None
    sorties: int
    sorties_per_day: tuple[int, ...]
    last_date: dt.date | None


def flying_days(windows: Sequence[SunWindow], sortie_times_s: Sequence[float],
                turnaround_s: float = 0.0) -> FlyingDays:
    """Fit the sorties, in order, into the days' sun windows (weather not counted).

    Parameters
    ----------
    windows : sequence of SunWindow
        The dates' windows (:func:`sun_windows`), in date order.
    sortie_times_s : sequence of float
        Flight time of each sortie [s] (from the flight layout, or the flight time cut into
        equal sorties of the endurance).
    turnaround_s : float
        Ground time between two sorties (landing, battery change, checks) [s].

    Returns
    -------
    FlyingDays

    Notes
    -----
    A sortie must fit whole into a window; each day takes sorties while
    Σ (sortie + turnaround) − turnaround ≤ the window. A sortie longer than every window is
    never flown (``days`` None).

    >>> import datetime as dt
    >>> w = [SunWindow(dt.date(2025, 6, d), None, None, 2.0, 50.0) for d in (1, 2, 3)]
    >>> flying_days(w, [1800.0] * 5, 600.0).sorties_per_day
    (3, 2)
    """
    queue = [float(t) for t in sortie_times_s]
    done_per_day: list[int] = []
    i = 0
    for w in windows:
        if i >= len(queue):
            break
        budget = w.hours * 3600.0
        used = 0.0
        flown = 0
        while i < len(queue):
            need = queue[i] + (turnaround_s if flown else 0.0)
            if used + need > budget + 1e-9:
                break
            used += need
            flown += 1
            i += 1
        done_per_day.append(flown)
    finished = i >= len(queue)
    days = sum(1 for k in done_per_day if k) if finished else None
    last = windows[len(done_per_day) - 1].date if finished and done_per_day else None
    return FlyingDays(days, len(queue), tuple(done_per_day), last)


def equal_sorties_s(flight_time_s: float, endurance_s: float) -> list[float]:
    """The flight time cut into the fewest equal sorties of at most ``endurance_s`` [s].

    >>> equal_sorties_s(5400.0, 1500.0)
    [1350.0, 1350.0, 1350.0, 1350.0]
    """
    if flight_time_s <= 0:
        return []
    n = max(1, math.ceil(flight_time_s / endurance_s - 1e-12))
    return [flight_time_s / n] * n
