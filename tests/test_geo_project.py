"""Areas in projects and on the command line (issue 11): `[area]` keys, the flight figures
from the layout (the rectangle unchanged), --json's area/strips/sorties, --area-file on
`uav` and `scan`, bad areas → exit 2 with the key and line, nothing written."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.core import flight as FL
from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
if not EXAMPLES.is_dir():
    pytest.skip("examples/ not found beside the tests", allow_module_level=True)
UAV_TOML = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
TOWN_KML = EXAMPLES / "areas" / "town-uav.kml"


def _plan(text: str, folder: Path, name: str = "p.toml"):
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return plan_project(parse_project(text, path))


def _cli(*args: str) -> tuple[int, str, str]:
    r = CliRunner().invoke(main, list(args))
    return r.exit_code, r.stdout, r.stderr


def test_rectangle_polygon_project_equals_width_by_length(tmp_path):
    """The acceptance test: a rectangular polygon (UTM 37N, lines along its length) gives
    the same strips, photos, length, time and data volume as `width_m × length_m` of its
    size on the ground (the grid is k = 0.9996 times the ground on the central meridian,
    so the polygon's sides are 2000·k × 3000·k grid metres), and those are today's numbers
    (core/flight.py's block formulas)."""
    from pyproj import Proj

    x0, y0 = 500_000, 6_200_000
    k = min(Proj("EPSG:32637").get_factors(39.0, lat).meridional_scale
            for lat in (55.93, 55.96, 55.99))  # the central meridian: k grows off it
    w, h = 2000 * k, 3000 * k
    poly = (f"[area]\npolygon = [[{x0}, {y0}], [{x0 + w}, {y0}], [{x0 + w}, {y0 + h}], "
            f"[{x0}, {y0 + h}]]\ncrs = \"EPSG:32637\"\ndirection_deg = 0\n")
    rect_spec = _plan(UAV_TOML, tmp_path, "rect.toml").uav
    rect = rect_spec.job.plan.flight
    polyf = _plan(UAV_TOML.split("[area]")[0] + poly, tmp_path, "poly.toml").uav.job.plan.flight
    for key in ("strips", "photos_per_strip", "photos", "data_volume_bytes"):
        assert rect[key] == polyf[key], key
    assert ("sorties" in rect) == ("sorties" in polyf)  # no sortie time: neither counts
    # the polygon's in the grid (the way back from the block's edge too)
    assert rect["flight_length_m"] * k == pytest.approx(polyf["flight_length_m"], rel=1e-9)
    # the time as flown: the climb and the corners do not scale with k
    assert rect["flight_time_s"] == pytest.approx(polyf["flight_time_s"], rel=1e-3)
    n = int(FL.strip_count(2000, rect["line_spacing_m"]))
    k = int(FL.photos_per_strip(3000, rect["base_m"]))
    assert (rect["strips"], rect["photos_per_strip"]) == (n, k) == (34, 152)
    # and the run-out of half a base where the camera trigger is disarmed (geo/mission.py)
    transit = rect_spec.job.layout.notes["transit_m"]  # from the block's edge and back
    assert rect["flight_length_m"] - transit == pytest.approx(float(FL.flight_length_m(
        n, (k - 1) * rect["base_m"], rect["line_spacing_m"])) + rect["base_m"] / 2, rel=1e-12)


def test_town_example_json_has_area_strips_sorties_but_no_photo_centres():
    code, out, err = _cli("plan", str(EXAMPLES / "uav-town-2000.toml"), "--json")
    assert code == 0, err
    doc = json.loads(out)
    area = doc["area"]
    assert area["crs"] == "EPSG:32637" and area["crs_name"] == "WGS 84 / UTM zone 37N"
    assert 3.0 < area["area_km2"] < 3.5 and 8 < area["perimeter_km"] < 8.5
    lay = doc["specification"]["uav"]["layout"]
    assert lay["n_strips"] == len(lay["strips"]) == doc["specification"]["uav"]["strips"]
    assert lay["n_photos"] == doc["specification"]["uav"]["photos"]
    assert sum(s["photos"] for s in lay["strips"]) == lay["n_photos"]
    assert lay["n_sorties"] == len(lay["sorties"]) > 1
    assert all(k["time_s"] <= 44 * 60 for k in lay["sorties"])  # the M350 RTK's battery
    assert lay["turn"] == "turnaround 20 m" and lay["feasible"]
    s0 = lay["strips"][0]
    assert 38.7 < s0["start_lonlat"][0] < 38.9 and 55.0 < s0["start_lonlat"][1] < 55.2
    assert "\"lon_deg\"" not in out and "\"x_m\"" not in out  # photo centres: the files


def test_town_example_layout_photos_carry_the_plan_figures(tmp_path):
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    r = plan_project(parse_project(text, EXAMPLES / "uav-town-2000.toml"))
    lay = r.uav.layout
    assert r.layouts == {"uav": lay} and r.area is lay.area
    p = lay.photos
    plan = r.uav.job.plan
    assert np.allclose(p["gsd_cm"], plan.gsd_m * 100)
    assert np.allclose(p["resolution_cm"], plan.ground_resolution_m * 100)
    assert np.all((p["recognition_p"] > 0.9) & (p["recognition_p"] <= 1))
    assert np.all(p["ground_m"] == 0) and np.all(p["agl_m"] == plan.heights_m["planned"])
    assert np.allclose(p["altitude_m"], plan.heights_m["planned"])
    assert lay.notes["bridged_m"] > 0  # the river bay


def test_film_town_example_flight_scheme():
    code, out, err = _cli("plan", str(EXAMPLES / "film-town-10000.toml"), "--json")
    assert code == 0, err
    spec = json.loads(out)["specification"]["film"]
    lay = spec["layout"]
    assert spec["frames"] == lay["n_photos"] and spec["strips"] == lay["n_strips"]
    assert lay["kind"] == "film" and lay["flight_time_s"] is None
    assert spec["scanned_gigabytes"] == pytest.approx(spec["frames"] * spec["frame_megabytes"]
                                                      / 1000)
    # 18 cm frame at 1:8000: 1440 m footprint, 30 % side overlap → 1008 m spacing
    assert lay["line_spacing_m"] == pytest.approx(1008.0)


def test_area_file_is_relative_to_the_project(tmp_path):
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    os.chdir(tmp_path)
    code, out, err = _cli("plan", str(EXAMPLES / "uav-town-2000.toml"))
    assert code == 0, err
    assert "Area: " in out and "UTM zone 37N" in out and "sorties: " in out
    del text


@pytest.mark.parametrize("area,key,words", [
    ('file = "missing.kml"', "area.file (line", "No such file"),
    ("polygon = [[55.75, 37.6], [55.75, 137.63], [55.77, 37.63]]", "area.polygon (line",
     "swapped"),
    ("polygon = [[37.6, 55.7], [37.7, 55.8], [37.7, 55.7], [37.6, 55.8]]", "area.polygon",
     "crosses itself at lon 37.650000, lat 55.750000"),
    ('polygon = [[37.6, 55.75], [37.63, 55.75], [37.63, 55.77]]\ncrs = "EPSG:999999"',
     "area.crs (line", "EPSG"),
    ('polygon = [[37.6, 55.75], [37.63, 55.75], [37.63, 55.77]]\ndirection_deg = "north"',
     "area.direction_deg (line", '"auto"'),
    ("width_m = 2000\nlength_m = 3000\ndirection_deg = 30", "area.direction_deg",
     "polygon area"),
    ('polygon = [[37.6, 55.75], [37.63, 55.75], [37.63, 55.77]]\nextension_bases = 99',
     "area.extension_bases", "0 … 10"),
    ("polygon = [[37.6, 55.75]]", "area.polygon (line", "at least 3"),
])
def test_bad_areas_exit_2_naming_the_key_and_write_nothing(tmp_path, area, key, words):
    text = UAV_TOML.split("[area]")[0] + "[area]\n" + area + "\n"
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    out_dir = tmp_path / "out"
    code, out, err = _cli("plan", str(path), "--out", str(out_dir))
    assert code == 2, (out, err)
    assert key in err and words in err, err
    assert "Traceback" not in err
    assert not out_dir.exists() or not any(out_dir.iterdir())


def test_bad_area_in_a_file_names_the_file_and_the_key(tmp_path):
    (tmp_path / "lines.kml").write_text(
        '<?xml version="1.0"?><kml xmlns="http://www.opengis.net/kml/2.2"><Document>'
        "<Placemark><name>Road</name><LineString><coordinates>37.6,55.7 37.7,55.8"
        "</coordinates></LineString></Placemark></Document></kml>", encoding="utf-8")
    text = UAV_TOML.split("[area]")[0] + '[area]\nfile = "lines.kml"\n'
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    code, _, err = _cli("plan", str(path))
    assert code == 2 and "area.file (line" in err and "lines.kml" in err
    assert "holds no polygon" in err


def test_turn_keys_and_sorties_in_a_project(tmp_path):
    base = UAV_TOML.replace("[uav]\n", "[uav]\nmax_flight_time_min = 20\nbank_deg = 25\n")
    r = _plan(base, tmp_path)
    lay = r.uav.layout
    assert lay.turn.startswith("radius ") and len(lay.sorties) > 1
    both = UAV_TOML.replace("[uav]\n", "[uav]\nturnaround_m = 10\nbank_deg = 25\n")
    path = tmp_path / "both.toml"
    path.write_text(both, encoding="utf-8")
    code, _, err = _cli("plan", str(path))
    assert code == 2 and "uav.bank_deg (line" in err and "one turn" in err


def test_uav_command_area_file():
    code, out, err = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                          "--area-file", str(TOWN_KML), "--max-flight-time-min", "25",
                          "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["area"]["crs"] == "EPSG:32637"
    assert doc["layout"]["n_photos"] == doc["flight"]["photos"]
    assert doc["layout"]["n_sorties"] == doc["flight"]["sorties"] > 1
    code, out, err = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                          "--area-file", str(TOWN_KML), "--direction-deg", "45")
    assert code == 0 and "direction 45.0°" in out
    code, _, err = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                        "--area-file", str(TOWN_KML), "--area-m", "100x100")
    assert code == 2 and "--area-file" in err
    code, _, err = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                        "--area-file", str(TOWN_KML), "--area-feature", "Lake")
    assert code == 2 and "--area-feature" in err and "Town boundary" in err
    code, _, err = _cli("uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                        "--direction-deg", "45")
    assert code == 2 and "--direction-deg" in err


def test_scan_command_area_file():
    code, out, err = _cli("scan", "--map-scale", "2000", "--relief", "1", "--camera",
                          "afa-te-100", "--photo-scale", "8000", "--photo-scale", "10000",
                          "--area-file", str(EXAMPLES / "areas" / "town-film.kml"), "--json")
    assert code == 0, err
    doc = json.loads(out)
    schemes = doc["flight_schemes"]
    assert [s["photo_scale"] for s in schemes] == [8000, 10000]
    assert schemes[0]["n_photos"] > schemes[1]["n_photos"]
    code, out, err = _cli("scan", "--map-scale", "2000", "--relief", "1", "--camera",
                          "afa-te-100", "--photo-scale", "8000",
                          "--area-file", str(EXAMPLES / "areas" / "town-film.kml"))
    assert code == 0 and "Flight lines at scale 1:8000" in out
