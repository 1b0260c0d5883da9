"""Where the area is: a polygon with latitude and longitude swapped is said (the site of
the sun window or the CRS's area of use shows it), a site far from the area is said with
the distance and the threshold, and without a site the sun window is the area's."""

from __future__ import annotations

import io
import json
import math
import re

import pytest
from click.testing import CliRunner
from openpyxl import load_workbook

from scanplan.cli.main import main
from scanplan.project.file import load_project
from scanplan.project.site import SITE_FAR_KM
from scanplan.project.spec import plan_project

MOSCOW = [[37.60, 55.75], [37.61, 55.75], [37.61, 55.76], [37.60, 55.76], [37.60, 55.75]]
SWAPPED = [[lat, lon] for lon, lat in MOSCOW]
_BASE = ('[project]\nname = "t"\nlocale = "{locale}"\n[map]\nscale = 2000\n'
         'relief_interval_m = 1\n[uav]\ncamera = "dji-zenmuse-p1-35"\nheight_m = 100\n')
_SUN = "[schedule]\nstart_date = 2025-06-01\nend_date = 2025-06-02\n"


def _write(tmp_path, area: str, extra: str = "", locale: str = "en"):
    path = tmp_path / "p.toml"
    path.write_text(_BASE.format(locale=locale) + area + extra, encoding="utf-8")
    return path


def _geojson(tmp_path, ring) -> str:
    (tmp_path / "area.geojson").write_text(json.dumps({
        "type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
                                                   "geometry": {"type": "Polygon",
                                                                "coordinates": [ring]}}]}))
    return '[area]\nfile = "area.geojson"\n'


def _codes(path) -> list[str]:
    return [w.code for w in plan_project(load_project(path)).warnings]


def test_a_geojson_given_lat_lon_is_said_swapped_by_its_site(tmp_path):
    path = _write(tmp_path, _geojson(tmp_path, SWAPPED),
                  _SUN + "[site]\nlat_deg = 55.755\nlon_deg = 37.605\n")
    result = plan_project(load_project(path))
    [w] = [w for w in result.warnings if w.code == "area_latlon_swapped"]
    assert "longitude 55.7550°, latitude 37.6050°" in w.message
    assert "longitude 37.6050°, latitude 55.7550°" in w.message
    assert "[lon, lat]" in w.message
    assert "site_far_from_area" not in _codes(path)  # the swap says the distance already
    ru = w.text("ru")
    assert "широта и долгота перепутаны" in ru and "55,7550°" in ru


def test_the_swap_is_in_the_terminal_the_json_and_the_workbook(tmp_path):
    path = _write(tmp_path, _geojson(tmp_path, SWAPPED),
                  _SUN + "[site]\nlat_deg = 55.755\nlon_deg = 37.605\n")
    term = CliRunner().invoke(main, ["plan", str(path)])
    assert term.exit_code == 0, term.output
    assert "latitude and longitude look swapped" in " ".join(term.output.split())
    doc = json.loads(CliRunner().invoke(main, ["plan", str(path), "--json"]).output)
    assert "area_latlon_swapped" in [w["code"] for w in doc["warnings"]]
    out = tmp_path / "out"
    done = CliRunner().invoke(main, ["plan", str(path), "--out", str(out), "--formats",
                                     "xlsx"])
    assert done.exit_code == 0, done.output
    book = load_workbook(io.BytesIO(next(out.glob("*.xlsx")).read_bytes()))
    cells = " ".join(str(c.value) for ws in book.worksheets for row in ws.iter_rows()
                     for c in row if c.value is not None)
    assert "latitude and longitude look swapped" in cells


def test_a_swap_is_said_when_only_the_swapped_place_is_in_the_plan_crs(tmp_path):
    area = "[area]\npolygon = " + json.dumps(SWAPPED) + '\nplan_crs = "EPSG:28407"\n'
    result = plan_project(load_project(_write(tmp_path, area)))
    [w] = [w for w in result.warnings if w.code == "area_latlon_swapped"]
    assert "EPSG:28407" in w.message


def test_a_correct_area_with_its_site_says_nothing_of_either(tmp_path):
    area = "[area]\npolygon = " + json.dumps(MOSCOW) + '\nplan_crs = "EPSG:28407"\n'
    codes = _codes(_write(tmp_path, area, _SUN + "[site]\nlat_deg = 55.8\nlon_deg = 37.7\n"))
    assert "area_latlon_swapped" not in codes and "site_far_from_area" not in codes


def test_a_site_far_from_the_area_is_said_with_distance_and_threshold(tmp_path):
    area = "[area]\npolygon = " + json.dumps(MOSCOW) + "\n"
    path = _write(tmp_path, area, _SUN + "[site]\nlat_deg = 59.94\nlon_deg = 30.31\n")
    [w] = [w for w in plan_project(load_project(path)).warnings
           if w.code == "site_far_from_area"]
    said = re.search(r"is ([\d,]+) km from the centre of the area", w.message)
    assert said, w.message
    # Moscow – St Petersburg by the haversine on the mean sphere: the ellipsoid's geodesic
    # differs from it by well under 0.5 %
    lat1, lon1, lat2, lon2 = map(math.radians, (55.755, 37.605, 59.94, 30.31))
    hav = (math.sin((lat2 - lat1) / 2) ** 2
           + math.cos(lat1) * math.cos(lat2) * math.sin((lon2 - lon1) / 2) ** 2)
    sphere_km = 2 * 6371.0 * math.asin(math.sqrt(hav))
    assert float(said.group(1).replace(",", "")) == pytest.approx(sphere_km, rel=0.005)
    assert f"farther than {SITE_FAR_KM:g} km" in w.message
    assert "[site] lat_deg, lon_deg" in w.message  # the key, in the terminal
    ru = w.text("ru")
    assert said.group(1) in ru and "дальше 50" in ru


@pytest.mark.parametrize(("lat", "lon", "said"), [(55.9, 37.6, False), (56.3, 37.6, True)])
def test_the_site_threshold_is_the_named_distance(tmp_path, lat, lon, said):
    area = "[area]\npolygon = " + json.dumps(MOSCOW) + "\n"
    codes = _codes(_write(tmp_path, area, _SUN + f"[site]\nlat_deg = {lat}\nlon_deg = {lon}\n"))
    assert ("site_far_from_area" in codes) is said


def test_without_a_site_the_sun_window_is_the_areas_centre(tmp_path):
    area = "[area]\npolygon = " + json.dumps(MOSCOW) + "\n"
    result = plan_project(load_project(_write(tmp_path, area, _SUN)))
    sun = result.design.sun
    assert sun is not None
    assert sun.lat_deg == pytest.approx(55.755, abs=1e-3)
    assert sun.lon_deg == pytest.approx(37.605, abs=1e-3)
    assert "site_far_from_area" not in [w.code for w in result.warnings]


def test_an_abstract_block_has_no_place_to_check(tmp_path):
    codes = _codes(_write(tmp_path, "[area]\nwidth_m = 500\nlength_m = 500\n",
                          _SUN + "[site]\nlat_deg = 55.8\nlon_deg = 37.7\n"))
    assert "site_far_from_area" not in codes and "area_latlon_swapped" not in codes


@pytest.mark.parametrize(("locale", "heading"), [
    ("en", "Latitude and longitude of the area look swapped"),
    ("ru", "Широта и долгота участка, похоже, перепутаны")])
def test_the_pdf_names_the_swap_in_its_language(tmp_path, locale, heading):
    from scanplan.reports.pdf import render_html

    path = _write(tmp_path, "[area]\npolygon = " + json.dumps(SWAPPED) + "\n",
                  _SUN + "[site]\nlat_deg = 55.755\nlon_deg = 37.605\n", locale=locale)
    result = plan_project(load_project(path))
    page = render_html(uav=result.uav.job, meta=result.meta, spec=result)
    assert heading in page
    assert ("[lon, lat]" if locale == "en" else "[долгота, широта]") in page
    assert "[site]" not in page  # no project-file syntax in a document
