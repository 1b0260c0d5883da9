"""`scanplan cameras import`: QGroundControl's camera list and spreadsheets (English or
Russian headers) into the user catalogue, with the norm importer's refusals (issue 16)."""

from __future__ import annotations

import json
import os

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.norms import NormImportError, load_norm_set, write_template
from scanplan.project.cameras import import_camera_file, read_camera_file, user_catalogue_dir
from scanplan.project.jobs import uav_job

# two entries in QGroundControl's own format (src/Camera/CameraMetaData.json)
QGC = [
    {"canonicalName": "Sony a7r IV 35mm", "brand": "Sony", "model": "a7r IV 35mm",
     "sensorWidth": 35.7, "sensorHeight": 23.8, "imageWidth": 9504, "imageHeight": 6336,
     "focalLength": 35, "landscape": True, "fixedOrientation": False,
     "minTriggerInterval": 1.0, "deprecatedTranslatedName": ""},
    {"canonicalName": "Sony DSC-RX0", "brand": "Sony", "model": "DSC-RX0",
     "sensorWidth": 13.2, "sensorHeight": 8.8, "imageWidth": 4800, "imageHeight": 3200,
     "focalLength": 7.7, "landscape": False, "fixedOrientation": False,
     "minTriggerInterval": 0, "deprecatedTranslatedName": "Sony DSC-RX0"},
]


def _cli(*args):
    return CliRunner().invoke(main, list(args))


def test_qgroundcontrol_list_round_trips(tmp_path, user_dir):
    f = tmp_path / "CameraMetaData.json"
    f.write_text(json.dumps(QGC), encoding="utf-8")
    r = _cli("cameras", "import", str(f), "--source", "QGroundControl 4.4", "--json")
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["cameras"] == ["sony-a7r-iv-35mm", "sony-dsc-rx0"]
    ns = load_norm_set()
    a7, rx0 = ns.cameras["sony-a7r-iv-35mm"], ns.cameras["sony-dsc-rx0"]
    for cam, entry in ((a7, QGC[0]), (rx0, QGC[1])):
        assert (cam.sensor_width_mm, cam.sensor_height_mm, cam.image_width_px,
                cam.image_height_px, cam.focal_mm) == (
            entry["sensorWidth"], entry["sensorHeight"], entry["imageWidth"],
            entry["imageHeight"], entry["focalLength"])
        assert "QGroundControl camera list CameraMetaData.json" in cam.source
        assert "QGroundControl 4.4" in cam.source
        assert cam.f_number is None  # never guessed
    assert a7.min_trigger_interval_s == 1.0 and rx0.min_trigger_interval_s is None  # 0 = unset
    assert (a7.orientation, rx0.orientation) == ("landscape", "portrait")
    # the imported camera plans with QGroundControl's GSD and, mounted portrait, its footprint
    plan = uav_job(camera="sony-dsc-rx0", f_number=4.0, height_m=100.0).plan
    density_cm = 100 * 13.2 * 100 / (4800 * 7.7)
    assert plan.gsd_m == pytest.approx(density_cm / 100, rel=1e-14)
    assert plan.flight["footprint_across_m"] == pytest.approx(density_cm * 3200 / 100)
    # a second import of the same ids needs --force
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 2 and "--force" in r.stderr
    assert _cli("cameras", "import", str(f), "--force").exit_code == 0


def test_russian_header_workbook_round_trips(tmp_path, user_dir):
    """The Russian template (sheets «Камеры», «Сканеры», Russian headers) imports back into
    the same 68 cameras and the scanners' steps."""
    book = write_template(tmp_path / "шаблон.xlsx", lang="ru")
    folder, parsed = import_camera_file(book)
    assert folder == user_catalogue_dir() and len(parsed.cameras) == 68
    bundled = {c.id: c for c in load_norm_set("gkinp-02-036-02-printed").cameras.values()}
    ns = load_norm_set()
    for cid, cam in bundled.items():
        got = ns.cameras[cid]
        for field in ("kind", "name", "sensor_width_mm", "sensor_height_mm", "focal_mm",
                      "pixel_um", "published_pixel_um", "image_width_px", "image_height_px",
                      "f_number", "min_trigger_interval_s", "platform", "note"):
            assert getattr(got, field) == getattr(cam, field), (cid, field)
        assert got.source.startswith(cam.source) and "imported from шаблон.xlsx" in got.source
    assert ns.scanner_steps("photoscan-2000") == (7.0, 14.0, 21.0, 28.0, 56.0, 112.0, 224.0)


def test_russian_headers_written_by_hand(tmp_path, user_dir):
    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.title = "Камеры"
    ws.append(["Камера", "Тип", "Модель", "Ширина кадра", "Высота кадра",
               "Фокусное расстояние", "Ширина изображения", "Высота изображения",
               "Диафрагма", "Источник"])
    ws.append(["our-cam", "digital", "Наша камера", 23.5, 15.6, 20, 6000, 4000, 5.6,
               "паспорт камеры"])
    path = tmp_path / "камеры.xlsx"
    wb.save(path)
    import_camera_file(path)
    cam = load_norm_set().cameras["our-cam"]
    assert cam.name == "Наша камера" and cam.pixel_um == 23.5 * 1000 / 6000
    assert cam.f_number == 5.6 and cam.source.startswith("паспорт камеры")


@pytest.mark.parametrize(("text", "expect"), [
    ('{"a": 1}', "top level must be a JSON list"),
    ("[1, 2]", "entry 1: must be a JSON object"),
    ('[{"canonicalName": "x", "sensorWidth": NaN, "sensorHeight": 1, "imageWidth": 1,'
     ' "imageHeight": 1, "focalLength": 1}]', "NaN is not a number JSON allows"),
    ('[{"canonicalName": "x", "sensorWidth": "7", "sensorHeight": 1, "imageWidth": 1,'
     ' "imageHeight": 1, "focalLength": 1}]',
     'entry 1 (sensorWidth): value "7": must be a number'),
    ('[{"canonicalName": "x", "sensorWidth": 7, "sensorHeight": 1, "imageWidth": 10.5,'
     ' "imageHeight": 1, "focalLength": 1}]', "whole number of pixels"),
    ('[{"canonicalName": "x", "sensorWidth": 7, "sensorHeight": 1, "imageWidth": 10,'
     ' "imageHeight": 1, "focalLength": -1}]', "entry 1 (focalLength)"),
    ('[{"canonicalName": "=HYPERLINK(1)", "sensorWidth": 7, "sensorHeight": 1,'
     ' "imageWidth": 10, "imageHeight": 1, "focalLength": 1}]', "formula"),
    ('[{"canonicalName": "a\\u001b[31m", "sensorWidth": 7, "sensorHeight": 1,'
     ' "imageWidth": 10, "imageHeight": 1, "focalLength": 1}]', "control character"),
    ("[" * 100000, "camera list"),
    ("[{", "not valid JSON"),
])
def test_hostile_json_is_refused_and_nothing_written(tmp_path, user_dir, text, expect):
    f = tmp_path / "cams.json"
    f.write_text(text, encoding="utf-8")
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 2, r.output
    assert expect in r.stderr and "Traceback" not in r.output
    assert not (user_catalogue_dir() / "cameras.csv").exists()


def test_duplicate_names_and_oversized_files(tmp_path, user_dir):
    f = tmp_path / "dup.json"
    f.write_text(json.dumps([QGC[0], QGC[0]]), encoding="utf-8")
    with pytest.raises(NormImportError, match=r"entry 2.*same id 'sony-a7r-iv-35mm' as entry 1"):
        read_camera_file(f)
    big = tmp_path / "big.json"
    with big.open("wb") as fh:
        fh.truncate(30 * 1024 * 1024)
    r = _cli("cameras", "import", str(big))
    assert r.exit_code == 2 and "limit" in r.stderr


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_a_fifo_is_refused_without_reading(tmp_path, user_dir):
    fifo = tmp_path / "cams.json"
    os.mkfifo(fifo)
    r = _cli("cameras", "import", str(fifo))
    assert r.exit_code == 2 and "FIFO" in r.stderr


def test_bad_spreadsheet_cells_are_addressed(tmp_path, user_dir):
    f = tmp_path / "cameras.csv"
    f.write_text("id,kind,name,sensor_width_mm,sensor_height_mm,focal_mm,image_width_px,"
                 "image_height_px,pixel_um,source\n"
                 "c1,digital,C1,36,24,-35,6000,4000,,x\n"
                 "c2,digital,C2,36,24,35,6000,4000,9,x\n", encoding="utf-8")
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 2 and "'cameras'!F2" in r.stderr and "focal_mm" in r.stderr
    f.write_text(f.read_text(encoding="utf-8").replace(",-35,", ",35,"), encoding="utf-8")
    r = _cli("cameras", "import", str(f))  # the 9 µm pitch disagrees with 36 mm/6000 px
    assert r.exit_code == 2 and "row 2 (pixel_um)" in r.stderr and "sensor width" in r.stderr
    assert not (user_catalogue_dir() / "cameras.csv").exists()


def test_a_file_without_camera_tables_is_refused(tmp_path, user_dir):
    book = write_template(tmp_path / "t.xlsx", lang="en", catalogue=False)
    with pytest.raises(InputError, match="no cameras or scanners table"):
        read_camera_file(book)


def test_a_lens_mtf_table_replaces_the_diffraction_formula(tmp_path, user_dir):
    """A user lens table (frequency → MTF, centre and corner) is used by the MTF chain:
    R and L equal the chain evaluated with that table, and a poorer lens gives a larger L."""
    from scanplan.core import mtf

    f = tmp_path / "lens-mtf.csv"
    rows = ["camera,position,freq_lpmm,mtf,source"]
    for pos, drop in (("centre", 0.006), ("corner", 0.008)):
        for n in (0, 20, 40, 80, 120, 160, 200):
            rows.append(f"dji-zenmuse-p1-35,{pos},{n},{max(0.0, 1 - drop * n):.3f},test chart")
    f.write_text("\n".join(rows) + "\n", encoding="utf-8")
    before = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0).plan
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 0, r.output
    ns = load_norm_set()
    curve = ns.lens_mtf["dji-zenmuse-p1-35"]["centre"]
    assert curve.freq_lpmm[:3] == (0.0, 20.0, 40.0) and curve.source == (
        "test chart (imported from lens-mtf.csv)")
    after = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0).plan
    cam = ns.cameras["dji-zenmuse-p1-35"]
    direct = mtf.uav_resolution(
        mtf.Camera(cam.pixel_um, 35.0, 2.8, 35.9, cam.frame()[1],
                   lens_table_centre=(curve.freq_lpmm, curve.mtf),
                   lens_table_corner=(ns.lens_mtf["dji-zenmuse-p1-35"]["corner"].freq_lpmm,
                                      ns.lens_mtf["dji-zenmuse-p1-35"]["corner"].mtf)),
        mtf.Flight(100.0, 15.0, 0.001), threshold=mtf.Threshold(params={"k0": 0.03}))
    assert after.resolving_power_lpmm == pytest.approx(float(direct.centre.r_lpmm), rel=1e-9)
    assert after.ground_resolution_m > before.ground_resolution_m
    r = _cli("cameras", "show", "dji-zenmuse-p1-35")
    assert "centre: 7 points to 200 lines/mm (test chart" in r.output


def test_a_lens_table_for_an_unknown_camera_is_refused(tmp_path, user_dir):
    f = tmp_path / "lens-mtf.csv"
    f.write_text("camera,position,freq_lpmm,mtf\nno-such,centre,0,1\nno-such,centre,50,0.5\n",
                 encoding="utf-8")
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 2 and "no-such" in r.stderr and "not a digital camera" in r.stderr
    f.write_text("camera,position,freq_lpmm,mtf\ndji-mavic-3e,centre,0,1\n", encoding="utf-8")
    r = _cli("cameras", "import", str(f))
    assert r.exit_code == 2 and "at least two frequencies" in r.stderr


def test_a_workbook_with_an_external_entity_is_refused(tmp_path, user_dir):
    """The norm importer's XML defences apply: a DTD in the cameras sheet is refused before
    any parsing, /etc/passwd is never read, nothing is written."""
    import re
    import zipfile

    from openpyxl import Workbook

    wb = Workbook()
    ws = wb.active
    ws.title = "cameras"
    ws.append(["id", "kind", "name", "sensor_width_mm", "sensor_height_mm", "focal_mm"])
    ws.append(["c1", "digital", "C1", 36, 24, 35])
    clean = tmp_path / "clean.xlsx"
    wb.save(clean)
    bad = tmp_path / "evil.xlsx"
    with zipfile.ZipFile(clean) as zin, zipfile.ZipFile(bad, "w") as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "xl/worksheets/sheet1.xml":
                data = (b'<?xml version="1.0" encoding="UTF-8"?>\n<!DOCTYPE worksheet '
                        b'[<!ENTITY xxe SYSTEM "file:///etc/passwd">]>\n'
                        + re.sub(rb"^<\?xml[^>]*\?>\s*", b"", data))
            zout.writestr(item, data)
    r = _cli("cameras", "import", str(bad))
    assert r.exit_code == 2 and "DTD or XML entities" in r.stderr and "root:" not in r.output
    assert not user_catalogue_dir().exists() or not any(user_catalogue_dir().iterdir())


def test_the_refusals_name_what_cameras_import_takes(tmp_path, user_dir):
    """Bug: a project file given to ``cameras import`` was told "give .xlsx or .csv" (the
    QGroundControl list, .json, is taken too), and a CSV of no camera table was told
    "give --table parameters|shapes|objects|…", tables ``cameras import`` refuses."""
    toml = tmp_path / "project.toml"
    toml.write_text("[map]\nscale = 2000\n")
    r = _cli("cameras", "import", str(toml))
    assert r.exit_code == 2 and ".json" in r.stderr and ".xlsx" in r.stderr, r.output
    other = tmp_path / "mine.csv"
    other.write_text("colour,weight\nred,1\n")
    r = _cli("cameras", "import", str(other))
    assert r.exit_code == 2 and "--table cameras|scanners|lens_mtf" in r.stderr, r.output
    assert "objects" not in r.stderr
