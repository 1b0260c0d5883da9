"""The sun window from astral's solar position, in the site's legal time zone.

The reference windows below were computed on 26 November 2026 with the code this module
replaced: pvlib 0.16.1, ``pvlib.solarposition.get_solarposition(method="nrel_numpy")``
(NREL SPA, Reda & Andreas 2004), apparent elevation, the same 2-minute grid and the same
fixed UTC offsets. astral must give the same window to the step.
"""

from __future__ import annotations

import datetime as dt
import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.geo.sun import STEP_MIN, sun_windows, time_zone_at, utc_offset_h_on

PVLIB_REFERENCE = [  # date, lat, lon, min elevation, UTC offset, start, end, top elevation
    ((2025, 6, 21), 55.75, 37.62, 30.0, 3, "07:50", "17:14", 57.697),
    ((2025, 4, 15), 55.03, 82.92, 30.0, 7, "10:08", "16:50", 44.860),
    ((2025, 6, 21), 62.03, 129.73, 20.0, 9, "06:18", "18:28", 51.420),
    ((2025, 9, 1), 43.6, 39.73, 30.0, 3, "08:38", "16:04", 54.528),
    ((2025, 1, 15), -33.87, 151.21, 30.0, 11, "08:36", "17:32", 77.233),
    ((2025, 6, 21), 69.0, 33.1, 0.0, 3, "00:00", "23:58", 44.453),  # polar day
    ((2025, 3, 10), 51.5, -0.13, 30.0, 0, "10:24", "13:58", 34.628),
]


def _minutes(hhmm: str) -> int:
    h, m = hhmm.split(":")
    return int(h) * 60 + int(m)


@pytest.mark.parametrize(("date", "lat", "lon", "elev", "utc", "start", "end", "top"),
                         PVLIB_REFERENCE)
def test_window_matches_the_former_spa_results_to_the_step(date, lat, lon, elev, utc,
                                                          start, end, top):
    (w,) = sun_windows([dt.date(*date)], lat, lon, elev, utc_offset_h=utc)
    assert abs(_minutes(f"{w.start_local:%H:%M}") - _minutes(start)) <= STEP_MIN
    assert abs(_minutes(f"{w.end_local:%H:%M}") - _minutes(end)) <= STEP_MIN
    assert w.max_elevation_deg == pytest.approx(top, abs=0.01)


def test_polar_night_has_no_window():
    (w,) = sun_windows([dt.date(2025, 12, 21)], 69.0, 33.1, 0.0, utc_offset_h=3)
    assert w.start_local is None and w.hours == 0.0  # pvlib: top −2.44° (no window)


@pytest.mark.parametrize(("lat", "lon", "zone", "offset_h"), [
    (55.75, 37.62, "Europe/Moscow", 3.0),        # round(lon/15) = 3
    (55.03, 82.92, "Asia/Novosibirsk", 7.0),     # round(lon/15) = 6: an hour behind
    (56.84, 60.61, "Asia/Yekaterinburg", 5.0),   # round(lon/15) = 4
    (43.12, 131.89, "Asia/Vladivostok", 10.0),   # round(lon/15) = 9
    (54.71, 20.51, "Europe/Kaliningrad", 2.0),   # round(lon/15) = 1
])
def test_the_legal_zone_is_found_offline(lat, lon, zone, offset_h):
    assert time_zone_at(lat, lon) == zone
    assert utc_offset_h_on(zone, dt.date(2025, 6, 1)) == offset_h


def test_summer_time_moves_the_window():
    """Berlin: CET (UTC+1) in March, CEST (UTC+2) from 30 March 2025."""
    before, after = sun_windows([dt.date(2025, 3, 29), dt.date(2025, 3, 31)], 52.52, 13.40,
                                20.0)
    assert (before.utc_offset_h, after.utc_offset_h) == (1.0, 2.0)
    shift = (_minutes(f"{after.start_local:%H:%M}") - _minutes(f"{before.start_local:%H:%M}"))
    assert 45 <= shift <= 60  # one hour later, less the two days' earlier sunrise


def _project(tmp_path, extra: str, locale: str = "en") -> str:
    text = (f'[project]\nlocale = "{locale}"\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n[uav]\n'
            'camera = "dji-zenmuse-p1-35"\nheight_m = 100\n'
            '[site]\nlat_deg = 55.03\nlon_deg = 82.92\n[schedule]\n'
            'start_date = 2025-06-01\nend_date = "2025-06-02"\n' + extra)
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_plan_names_the_zone_and_prints_legal_time(tmp_path):
    res = CliRunner().invoke(main, ["plan", _project(tmp_path, ""), "--json"])
    assert res.exit_code == 0, res.output
    sun = json.loads(res.stdout)["survey_design"]["sun"]
    assert sun["time_zone"] == "Asia/Novosibirsk" and sun["utc_offset_h"] == 7.0
    fixed = CliRunner().invoke(main, ["plan", _project(tmp_path, "utc_offset_h = 6\n"),
                                      "--json"])
    sun6 = json.loads(fixed.stdout)["survey_design"]["sun"]
    assert sun6["time_zone"] is None
    # the legal time is an hour ahead of the solar zone's
    assert (_minutes(sun["first_window"]["start"]) - _minutes(sun6["first_window"]["start"])
            == 60)
    for locale, word in (("en", "time zone Asia/Novosibirsk (MSK+4), UTC+7"),
                         ("ru", "время МСК+4, всемирное время +7 ч")):
        res = CliRunner().invoke(main, ["plan", _project(tmp_path, "", locale)])
        assert res.exit_code == 0, res.output
        assert word in " ".join(res.stdout.split())  # the terminal wraps lines


def test_zones_outside_russia_are_named_by_their_iana_name(tmp_path):
    path = Path(_project(tmp_path, ""))
    path.write_text(path.read_text(encoding="utf-8").replace("lat_deg = 55.03", "lat_deg = "
                    "52.52").replace("lon_deg = 82.92", "lon_deg = 13.40"), encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(path)])
    assert res.exit_code == 0, res.output
    assert "time zone Europe/Berlin, UTC+2" in " ".join(res.stdout.split())
