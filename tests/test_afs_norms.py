"""Today's Russian norms of digital aerial survey (issue 18).

- ГОСТ Р 59562-2021, Appendix Б, Table Б.1: the largest GSD per plan scale (norm table
  ``gsd_limits``; the constraint GL of digital cameras, information for film);
- ГОСТ Р 59328-2021 §6.2.1 (second draft): one photographing height per block only while
  the ground height range stays within 7 / 15 / 25 % of the flight height;
- the sun window from astral's NOAA solar position, checked against published references.
"""

from __future__ import annotations

import datetime as dt
import json

import numpy as np
import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.core.blocks import block_bands, block_height_check
from scanplan.errors import InputError
from scanplan.geo.sun import SunWindow, flying_days, sun_elevation_deg, sun_windows
from scanplan.norms import load_norm_set
from scanplan.project.file import parse_project
from scanplan.project.jobs import uav_job
from scanplan.project.spec import plan_project

# --- ГОСТ Р 59562-2021 Table Б.1 ---------------------------------------------------------

TABLE_B1 = [  # plan scale, area, largest GSD [cm] as printed in Table Б.1
    (500, "general", 6.0),
    (1000, "general", 9.0),
    (2000, "general", 20.0),
    (2000, "dense_urban", 14.0),  # footnote: towns with dense multi-storey buildings
    (5000, "general", 30.0),
    (10000, "general", 50.0),
    (25000, "general", 70.0),
]


@pytest.mark.parametrize(("scale", "area", "gsd_cm"), TABLE_B1)
def test_table_b1_rows_are_the_bundled_gsd_limits(scale, area, gsd_cm):
    row = load_norm_set().gsd_limit(scale, area)
    assert row is not None and (row.map_scale, row.area) == (scale, area)
    assert row.max_gsd_cm == gsd_cm
    assert "GOST R 59562-2021" in row.source and "Table B.1" in row.source


def test_table_b1_has_exactly_these_rows_and_dense_urban_falls_back():
    ns = load_norm_set()
    assert [(g.map_scale, g.area, g.max_gsd_cm) for g in ns.gsd_limits] == sorted(TABLE_B1)
    assert ns.gsd_limit(10000, "dense_urban").max_gsd_cm == 50.0  # no footnote row: general
    assert ns.gsd_limit(3000) is None
    assert "GL" not in load_norm_set("gkinp-02-036-02-printed").parameters["constraints"]


P1 = dict(camera="dji-zenmuse-p1-35", relief_interval_m=10.0, max_height_m=10000.0)


def test_uav_plan_at_10000_binds_on_the_50_cm_gsd_limit():
    """The Instruction allows P_P 70 cm and P_S 1 m on the ground at 1:10000; Table Б.1
    allows 50 cm: GL binds and the highest flown GSD is 50 cm."""
    plan = uav_job(map_scale=10000, height_m=100.0, **P1).plan
    limits = {lim.id: lim for lim in plan.limits}
    assert limits["PP"].limit_m == pytest.approx(0.70)
    assert limits["PS"].limit_m == pytest.approx(1.00)
    assert limits["GL"].limit_m == pytest.approx(0.50)
    assert min(lim.limit_m for lim in plan.limits if lim.compares == "GSD") == \
        pytest.approx(0.50)
    assert plan.binding == "GL"
    # GSD = p·H/c: the maximum height gives exactly 50 cm
    pixel_m = plan.inputs.pixel_um / 1e6
    assert plan.max_height_m * pixel_m / (plan.inputs.focal_mm / 1000) == pytest.approx(0.50)
    assert "50 cm for 1:10000" in limits["GL"].reason
    assert "Table B.1" in limits["GL"].equation and "59562-2021" in limits["GL"].equation
    assert "табл. Б.1" in limits["GL"].equation.text("ru")
    # without the layer (a set whose constraints omit GL) P_P binds at 70 cm
    plain = uav_job(map_scale=10000, height_m=100.0, norms="gkinp-02-036-02-printed", **P1)
    assert "GL" not in {lim.id for lim in plain.plan.limits}
    assert plain.plan.max_height_m == pytest.approx(plan.max_height_m * 0.70 / 0.50)


def test_dense_urban_row_at_2000_is_a_project_key():
    general = uav_job(map_scale=2000, height_m=100.0, **P1).plan
    dense = uav_job(map_scale=2000, height_m=100.0, gsd_area="dense_urban", **P1).plan
    assert {lim.id: lim.limit_m for lim in general.limits}["GL"] == pytest.approx(0.20)
    gl = {lim.id: lim for lim in dense.limits}["GL"]
    assert gl.limit_m == pytest.approx(0.14)
    assert "dense multi-storey" in gl.reason
    with pytest.raises(InputError, match="gsd_area"):
        uav_job(map_scale=2000, height_m=100.0, gsd_area="downtown", **P1)


FILM = """
[map]
scale = {scale}
relief_interval_m = 1.0
[film]
camera = "rc30-153"
photo_scales = [{photo}]
"""


@pytest.mark.parametrize(("scale", "photo", "within"), [(2000, 8000, True),
                                                         (10000, 30000, True)])
def test_film_scanned_ground_pixel_is_compared_with_table_b1_as_information(
        tmp_path, scale, photo, within):
    r = plan_project(parse_project(FILM.format(scale=scale, photo=photo), tmp_path / "f.toml"))
    (g,) = r.design.gsd
    s = r.film.recommended
    pixel = s.scanner_pixel_um or s.scan_pixel_um
    assert g.workflow == "film" and g.gsd_cm == pytest.approx(pixel * s.photo_scale / 1e4)
    assert g.limit_cm == load_norm_set().gsd_limit(scale).max_gsd_cm
    assert g.complies is within and g.complies == (g.gsd_cm <= g.limit_cm)
    info = [w for w in r.warnings if w.code == "gsd_limit_film"]
    assert len(info) == 1 and info[0].severity == "info"
    assert "for information" in info[0].message
    # information only: the film engine's constraints are the Instruction's
    assert "GL" not in r.film.job.plan.constraint_ids


# --- ГОСТ Р 59328-2021 §6.2.1: one height per block -------------------------------------

def _dem(relief_pct: float, height_m: float = 200.0, base_m: float = 150.0) -> np.ndarray:
    """A synthetic DEM: a tilted plane with a hill, range = relief_pct % of the height."""
    y, x = np.mgrid[0:101, 0:101] / 100.0
    z = 0.6 * x + 0.4 * np.exp(-((x - 0.5) ** 2 + (y - 0.5) ** 2) / 0.02) * y
    z = (z - z.min()) / (z.max() - z.min())
    return base_m + z * relief_pct / 100.0 * height_m


def test_block_rule_triggers_at_8_pct_and_not_at_6_pct_on_flat_terrain():
    limit = load_norm_set().parameters["block_relief_flat_pct"]
    assert limit == 7.0
    at6 = block_height_check(_dem(6.0), 200.0, "flat", limit)
    at8 = block_height_check(_dem(8.0), 200.0, "flat", limit)
    assert at6.range_pct == pytest.approx(6.0) and not at6.split_needed and at6.blocks == 1
    assert at8.range_pct == pytest.approx(8.0) and at8.split_needed and at8.blocks == 2
    assert at8.samples == 101 * 101
    # each band can be flown at one height
    for lo, hi in at8.bands_m:
        assert (hi - lo) <= at8.allowed_range_m + 1e-9
    assert at8.bands_m[0][0] == pytest.approx(150.0) and at8.bands_m[-1][1] == pytest.approx(166.0)
    # the same 8 % is within the hilly and mountainous limits
    ns = load_norm_set()
    assert not block_height_check(_dem(8.0), 200.0, "hilly",
                                  ns.parameters["block_relief_hilly_pct"]).split_needed
    assert block_height_check(_dem(30.0), 200.0, "mountainous",
                              ns.parameters["block_relief_mountain_pct"]).blocks == 2


def test_block_bands_say_where_a_dem_is_split():
    dem = _dem(20.0)  # 40 m range at 200 m: flat limit 14 m → 3 sub-blocks
    check = block_height_check(dem, 200.0, "flat", 7.0)
    bands = block_bands(dem, check)
    assert bands.shape == dem.shape and check.blocks == 3
    assert set(np.unique(bands)) == {0, 1, 2}
    for i in range(3):  # every sub-block can be flown at one height
        z = dem[bands == i]
        assert z.max() - z.min() <= check.allowed_range_m + 1e-9


def test_block_rule_edges():
    assert not block_height_check([100.0, 107.0], 100.0, "flat", 7.0).split_needed  # at limit
    assert block_height_check([100.0, np.nan, 130.0], 100.0, "flat", 7.0).blocks == 5
    for bad in ({"relief_class": "swamp"}, {"flight_height_m": 0.0}, {"limit_pct": -1.0}):
        args = {"ground_elevations_m": [1.0, 2.0], "flight_height_m": 100.0,
                "relief_class": "flat", "limit_pct": 7.0, **bad}
        with pytest.raises(ValueError):
            block_height_check(**args)
    with pytest.raises(ValueError, match="no finite"):
        block_height_check([np.nan], 100.0, "flat", 7.0)


UAV = """
[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
height_m = 100
[area]
width_m = 1000
length_m = 1500
"""


def test_block_rule_on_the_project_ground_elevations(tmp_path):
    text = UAV + '[terrain]\nground_elevation_m = [150, 158]\nrelief_class = "flat"\n'
    r = plan_project(parse_project(text, tmp_path / "p.toml"))
    assert r.design.block.split_needed and r.design.block.range_pct == pytest.approx(8.0)
    (w,) = [w for w in r.warnings if w.code == "block_split"]
    assert "2 parts" in w.message and "150–154 m" in w.message
    assert "2\u00a0части" in w.text("ru")
    ok = plan_project(parse_project(UAV + "[terrain]\nground_elevation_m = [150, 156]\n",
                                    tmp_path / "q.toml"))
    assert not ok.design.block.split_needed
    assert not [w for w in ok.warnings if w.code == "block_split"]
    for bad, key in (("[terrain]\nground_elevation_m = [160, 150]\n", "ground_elevation_m"),
                     ('[terrain]\nground_elevation_m = [150, 156]\nrelief_class = "swamp"\n',
                      "relief_class")):
        with pytest.raises(InputError, match=key):
            plan_project(parse_project(UAV + bad, tmp_path / "b.toml"))


# --- the sun window ----------------------------------------------------------------------

def test_sun_elevation_reproduces_the_spa_worked_example():
    """Reda & Andreas 2004 (NREL/TP-560-34302), Table A5.1: 17 October 2003 12:30:30 local
    time (UTC−7) at Golden, Colorado (39.742476 N, 105.1786 W, 1830.14 m): topocentric zenith
    angle 50.11162° (refraction at 820 mbar, 11 °C), i.e. elevation 39.88838°."""
    elev = sun_elevation_deg([np.datetime64("2003-10-17T19:30:30")], 39.742476, -105.1786,
                             1830.14)[0]
    assert elev == pytest.approx(90.0 - 50.11162, abs=0.01)  # acceptance: 0.1°


# USNO "Earth's Seasons and Apsides" 2024: June solstice 20 June 20:51 UT, March equinox
# 20 March 03:06 UT. At the solstice the sun's declination equals the obliquity of the
# ecliptic, 23.4361° in 2024 (IAU 2006: 23°26'21.406" − 46.837"·T, T = 0.2447 century), at
# the equinox 0°. At a longitude where local noon falls at that instant the day's highest
# elevation is 90° − |φ − δ| plus refraction (Bennett: 0.012° at 53°, 0.006° at 68°,
# 0.011° at 55°, 0.022° at 37°).
SOLAR_NOON = [  # date, longitude where noon falls at the instant, latitude, top elevation
    (dt.date(2024, 6, 20), -132.3, 60.0, 90.0 - 60.0 + 23.4361 + 0.012),
    (dt.date(2024, 6, 20), -132.3, 45.0, 90.0 - 45.0 + 23.4361 + 0.006),
    (dt.date(2024, 6, 20), -132.3, -30.0, 90.0 - 30.0 - 23.4361 + 0.022),
    (dt.date(2024, 3, 20), 135.3, 35.0, 90.0 - 35.0 + 0.011),
]


@pytest.mark.parametrize(("date", "lon", "lat", "top"), SOLAR_NOON)
def test_noon_elevation_at_solstice_and_equinox(date, lon, lat, top):
    (w,) = sun_windows([date], lat, lon, 0.0, step_min=1.0)
    assert w.max_elevation_deg == pytest.approx(top, abs=0.01)  # acceptance: 0.1°


def test_sun_window_is_symmetric_about_noon_and_grows_toward_summer():
    days = [dt.date(2025, 4, 1), dt.date(2025, 6, 21)]
    april, june = sun_windows(days, 55.75, 37.62, 30.0, utc_offset_h=3)
    assert 0 < april.hours < june.hours < 12
    # Moscow: solar noon about 12:30 MSK in June (lon 37.62° → 2 h 30 min, minus UTC+3)
    mid = april.start_local + (april.end_local - april.start_local) / 2
    assert abs((mid - dt.datetime(2025, 4, 1, 12, 34)).total_seconds()) < 15 * 60
    (dec,) = sun_windows([dt.date(2025, 12, 21)], 55.75, 37.62, 30.0)
    assert dec.hours == 0 and dec.start_local is None and dec.max_elevation_deg < 12


def test_flying_days_fits_whole_sorties_into_each_window():
    w = [SunWindow(dt.date(2025, 6, d), None, None, h, 40.0) for d, h in
         ((1, 1.0), (2, 0.0), (3, 2.0), (4, 2.0))]
    fd = flying_days(w, [1800.0] * 5, 900.0)
    # day 1: 30 + 15 + 30 = 75 min > 60 → 1 sortie; day 2: none; day 3: 3 (120 min); day 4: 1
    assert fd.sorties_per_day == (1, 0, 3, 1) and fd.days == 3
    assert fd.last_date == dt.date(2025, 6, 4)
    assert flying_days(w[:1], [1800.0] * 5).days is None


def test_plan_reports_the_sun_window_and_flying_days(tmp_path):
    text = UAV + ("[site]\nlat_deg = 55.75\nlon_deg = 37.62\n[schedule]\n"
                  "start_date = 2025-06-01\nend_date = \"2025-06-05\"\nutc_offset_h = 3\n"
                  "sortie_time_min = 20\nturnaround_min = 10\n")
    path = tmp_path / "sun.toml"
    path.write_text(text, encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(path), "--json"])
    assert res.exit_code == 0, res.output
    sun = json.loads(res.stdout)["survey_design"]["sun"]
    assert sun["first_window"]["start"] < "08:30" < "16:30" < sun["first_window"]["end"]
    flight_min = sun["flight_time_min"]
    assert sun["sorties"] == int(np.ceil(flight_min / 20 - 1e-9))
    per_day = int((sun["window_hours_min"] * 60 + 10) // 30)
    assert sun["flying_days"] == int(np.ceil(sun["sorties"] / per_day))
    # winter: no window at 30°
    winter = text.replace("2025-06-01", "2025-12-10").replace("2025-06-05", "2025-12-12")
    r = plan_project(parse_project(winter, tmp_path / "w.toml"))
    assert [w.code for w in r.warnings if w.code.startswith("sun_")] == ["sun_no_window"]
    short = text.replace('end_date = "2025-06-05"', 'end_date = "2025-06-01"').replace(
        "turnaround_min = 10", "turnaround_min = 300")
    r = plan_project(parse_project(short, tmp_path / "s.toml"))
    assert [w.code for w in r.warnings if w.code.startswith("sun_")] == ["sun_dates_short"]
    for bad, key in (("lat_deg = 55.75", "lat_deg = 95"), ("utc_offset_h = 3", "utc_offset_h = 20"),
                     ('end_date = "2025-06-05"', 'end_date = "2025-05-05"'),
                     ("start_date = 2025-06-01", 'start_date = "June"')):
        with pytest.raises(InputError, match=key.split(" ")[0]):
            plan_project(parse_project(text.replace(bad, key), tmp_path / "bad.toml"))


# --- the survey design sheet («Технический проект АФС») ---------------------------------

EXAMPLE = "uav-town-2000-afs.toml"


@pytest.mark.parametrize("locale", ["ru", "en"])
def test_survey_design_sheet_in_workbook_and_pdf(tmp_path, locale):
    openpyxl = pytest.importorskip("openpyxl")
    from pathlib import Path

    src = Path(__file__).resolve().parent.parent / "examples" / EXAMPLE
    path = tmp_path / "p.toml"
    path.write_text(src.read_text(encoding="utf-8").replace('locale = "ru"',
                                                             f'locale = "{locale}"'),
                    encoding="utf-8")
    res = CliRunner().invoke(main, ["plan", str(path), "--out", str(tmp_path)])
    assert res.exit_code == 0, res.output
    wb = openpyxl.load_workbook(tmp_path / "spec.xlsx")
    name = "Технический проект АФС" if locale == "ru" else "Design"
    assert wb.sheetnames[1] == name
    ws = wb[name]
    rows = {r[0]: (r[1], r[2]) for r in ws.iter_rows(min_row=2, values_only=True) if r[0]}
    gsd_label = ("Размер пикселя на местности на наибольшей фактической высоте и предельный "
                 "для масштаба плана" if locale == "ru" else
                 "GSD at the highest flown height against the largest GSD of the plan scale")
    value, norm = rows[gsd_label]
    assert "14" in value and ("соответствует" if locale == "ru" else "complies") in value
    # the norm is cited by its number in the list of references, with its table
    assert ("табл. Б.1" if locale == "ru" else "Table B.1") in norm and norm.startswith("[")
    refs = {r[0]: r[1] for r in wb["Список литературы" if locale == "ru" else "References"]
            .iter_rows(min_row=2, values_only=True)}  # numbered as the PDF numbers them
    n = int(norm[1:norm.index("]")])
    assert ("ГОСТ Р 59562-2021" if locale == "ru" else "GOST R 59562-2021") in refs[n]
    coords = "Система координат" if locale == "ru" else "Coordinate system"
    assert rows[coords][0] == "МСК-50, зона 2"
    days = "Лётные дни" if locale == "ru" else "Flying days needed"
    assert rows[days][0].startswith("1 ")
    # the PDF carries the same sheet, on its own page after the specification
    pypdf = pytest.importorskip("pypdf")
    pages = [" ".join(p.extract_text().split())
             for p in pypdf.PdfReader(tmp_path / "spec.pdf").pages]
    title = "Технический проект аэрофотосъёмки" if locale == "ru" else "Survey design"
    (page,) = [p for p in pages if p.startswith(title) or f" {title} " in p[:200]]
    assert ("МСК-50, зона 2" in page and "Балтийская" in page
            and ("прил. Б, табл. Б.1" if locale == "ru" else "Appendix B, Table B.1") in page)
    # the ground range 150–205 m also drives the terrain plan: one altitude over the highest
    # ground, strictly below the 150 m ceiling over the lowest, gives 90 m above the
    # reference ground (95 m would be flown at exactly 150 m), so the 55 m range is 61 % of
    # it, over the 15 % hilly limit → 5 bands of ≤ 15 %·90 m
    assert ("разделить на 5 частей" if locale == "ru" else "split into 5 parts") in page


@pytest.mark.parametrize("name", ["scanplan.core.blocks", "scanplan.geo.sun",
                                  "scanplan.project.design", "scanplan.norms.store"])
def test_doctests_of_the_new_modules(name):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(name), verbose=False)
    assert result.failed == 0 and result.attempted > 0


def test_layout_gives_the_site_and_the_sorties_once_the_geography_lands():
    """With a laid-out flight (geo.layout records) the sun window takes the area's centroid
    and the layout's own sorties."""
    import shapely

    from scanplan.geo.layout import Area, FlightLayout, Photos, Sortie
    from scanplan.project.design import layout_site, layout_sorties_s

    area = Area(shapely.box(0, 0, 1000, 1000), "EPSG:32637", "inline polygon", True, 1.0, 4.0,
                (37.62, 55.75))
    layout = FlightLayout(area, 0.0, 50.0, 20.0, (), (Sortie(1, (1,), 9000.0, 1500.0),
                                                     Sortie(2, (2,), 3000.0, 600.0)),
                          Photos({}), 12000.0, 500.0, 2100.0)
    assert layout_site(layout) == (55.75, 37.62)
    assert layout_sorties_s(layout) == [1500.0, 600.0]
    abstract = FlightLayout(Area(shapely.box(0, 0, 1, 1), "LOCAL", "rectangle", False, 1.0,
                                 4.0), 0.0, 1.0, 1.0, (), (), Photos({}), 0.0, 0.0, None)
    assert layout_site(abstract) is None and layout_sorties_s(abstract) is None


@pytest.mark.parametrize(("scale", "photo", "en", "ru"), [
    (2000, 8000, "1:8000 photos, 7 µm × 8000 = 5.6 cm",
     "снимков 1:8000: 7\u00a0мкм × 8000 = 5,6\u00a0см"),
    (10000, 30000, "1:30000 photos, 5.54348 µm × 30000 = 16.6 cm",
     "снимков 1:30\u00a0000: 5,54348\u00a0мкм × 30\u00a0000 = 16,6\u00a0см"),
])
def test_film_ground_pixel_writes_the_scale_number_as_the_scale(tmp_path, scale, photo, en, ru):
    """The product pixel × Mc writes Mc as its scale 1:Mc is written (English 8000, never
    8,000; Russian 8000 and 30 000, never 8 000) — it said '1:8000 photos, 7 µm × 8,000'."""
    toml = FILM.format(scale=scale, photo=photo)
    if photo == 8000:
        toml = toml.replace('camera = "rc30-153"', 'camera = "rc30-153"\nscanner = "photoscan-td"')
    r = plan_project(parse_project(toml, tmp_path / "f.toml"))
    (info,) = [w for w in r.warnings if w.code == "gsd_limit_film"]
    assert en in info.text("en")
    assert ru in info.text("ru")
