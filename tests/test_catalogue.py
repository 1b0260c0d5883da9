"""The camera and scanner catalogue (issue 16): sources, exact geometry, QGroundControl's
CameraCalc formulas, portrait mounting, large-format cameras on aircraft, scanners.

QGroundControl's formulas (mavlink/qgroundcontrol src/MissionManager/CameraCalc.cc,
``_recalcTriggerDistance``), restated here independently of scanplan's code:

    imageDensity [cm/px]     = H·sensorWidth·100 / (imageWidth·focalLength)
    landscape: iWidth = imageWidth, iHeight = imageHeight; portrait: swapped
    imageFootprintSide [m]    = imageDensity·iWidth / 100
    imageFootprintFrontal [m] = imageDensity·iHeight / 100
    adjustedFootprintFrontal  = imageFootprintFrontal·(100 − frontOverlap)/100  (trigger distance)
    adjustedFootprintSide     = imageFootprintSide·(100 − sideOverlap)/100      (transect spacing)
"""

from __future__ import annotations

import csv
import json
import math
import shutil

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.norms import (
    PITCH_TOLERANCE,
    bundled_norms_dir,
    load_norm_set,
    read_norm_set_folder,
)
from scanplan.project.jobs import uav_job

CATALOGUE = bundled_norms_dir() / "catalogue"
NS = load_norm_set()
DIGITAL = sorted(c.id for c in NS.cameras.values()
                 if c.kind == "digital" and c.image_width_px and c.image_height_px)


def _rows(name: str) -> list[dict[str, str]]:
    with open(CATALOGUE / name, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


def qgc(camera, height_m: float, front_pct: float, side_pct: float, landscape: bool):
    """QGroundControl's CameraCalc on the catalogue's facts."""
    density_cm = height_m * camera.sensor_width_mm * 100 / (camera.image_width_px
                                                            * camera.focal_mm)
    i_width = camera.image_width_px if landscape else camera.image_height_px
    i_height = camera.image_height_px if landscape else camera.image_width_px
    side = density_cm * i_width / 100
    frontal = density_cm * i_height / 100
    return {"gsd_m": density_cm / 100, "footprint_across_m": side,
            "footprint_along_m": frontal, "base_m": frontal * (100 - front_pct) / 100,
            "line_spacing_m": side * (100 - side_pct) / 100}


# --- the catalogue itself ------------------------------------------------------------------

def test_catalogue_size_and_every_row_has_a_source():
    cams, scanners = _rows("cameras.csv"), _rows("scanners.csv")
    assert len(cams) >= 55
    assert all(r["source"].strip() for r in cams), [r["id"] for r in cams if not r["source"]]
    assert all(r["source"].strip() for r in scanners)
    ids = [r["id"] for r in cams]
    assert len(ids) == len(set(ids))
    # every fact row of the shared camera lists is a camera: 43 survey cameras and 12
    # large-format aerial cameras
    qgc_mp = [r for r in cams if r["source"].startswith(("QGroundControl camera list",
                                                          "Mission Planner camera list"))]
    aerial = [r for r in cams if r["source"].startswith("flight_planner")]
    assert (len(qgc_mp), len(aerial)) == (43, 12)
    assert all(r["platform"] == "aircraft" for r in aerial)


def test_every_pitch_is_sensor_width_over_image_width():
    for cid in DIGITAL:
        c = NS.cameras[cid]
        assert c.pixel_um == c.sensor_width_mm * 1000 / c.image_width_px, cid
        if c.published_pixel_um is not None:
            assert abs(c.published_pixel_um / c.pixel_um - 1) <= PITCH_TOLERANCE, cid


def test_the_two_rounded_pitches_the_cross_check_found_are_gone():
    """Mavic 3E: 3.3 µm published, 17.3/5280 = 3.2765 µm (+0.72 %); P1: 4.4 µm published,
    35.9/8192 = 4.3823 µm (+0.40 %). The GSD now uses the exact pitch."""
    m3e, p1 = NS.cameras["dji-mavic-3e"], NS.cameras["dji-zenmuse-p1-35"]
    assert m3e.published_pixel_um / m3e.pixel_um - 1 == pytest.approx(0.0072, abs=5e-5)
    assert p1.published_pixel_um / p1.pixel_um - 1 == pytest.approx(0.0040, abs=5e-5)
    for cam in (m3e, p1):
        plan = uav_job(camera=cam.id, height_m=100.0).plan
        assert plan.gsd_m == pytest.approx(qgc(cam, 100.0, 80, 60, True)["gsd_m"], rel=1e-14)


def test_conflicting_sources_are_kept_apart_with_a_note():
    for a, b in (("parrot-sequoia-rgb-qgc", "parrot-sequoia-rgb-mp"),
                 ("gopro-hero-4-qgc", "gopro-hero-4-black-wide-mp"),
                 ("sony-dsc-rx1r-ii-35mm-qgc", "sony-rx1r-ii-wingtra")):
        assert "conflict" in NS.cameras[a].note
        assert b in NS.cameras[a].note or a in NS.cameras[b].note
    assert NS.cameras["parrot-sequoia-rgb-qgc"].focal_mm == 4.9
    assert NS.cameras["parrot-sequoia-rgb-mp"].focal_mm == 4.88


def test_no_working_f_number_is_guessed():
    """The planners' lists give no f-number: those rows leave it empty, and planning with
    one of them asks for it (exit 2 naming --f-number)."""
    listed = [r for r in _rows("cameras.csv")
              if r["source"].startswith(("QGroundControl", "Mission Planner", "flight_planner"))]
    assert listed and all(r["f_number"] == "" for r in listed)
    r = CliRunner().invoke(main, ["uav", "--camera", "sony-a7r-iv-35mm", "--height-m", "100"])
    assert r.exit_code == 2 and "--f-number" in r.stderr


def test_trigger_interval_only_where_a_source_gives_it():
    assert NS.cameras["sentera-65r-sensor"].min_trigger_interval_s == 0.3
    assert NS.cameras["canon-s100-powershot"].min_trigger_interval_s is None


# --- QGroundControl's formulas, every camera, both mountings --------------------------------

@pytest.mark.parametrize("orientation", ["landscape", "portrait"])
@pytest.mark.parametrize("camera_id", DIGITAL)
def test_geometry_equals_qgroundcontrol(camera_id, orientation):
    cam = NS.cameras[camera_id]
    height = 3000.0 if cam.carrier == "aircraft" else 120.0
    plan = uav_job(camera=camera_id, f_number=8.0, height_m=height, speed_ms=60.0,
                   forward_overlap_pct=75.0, side_overlap_pct=65.0,
                   orientation=orientation).plan
    want = qgc(cam, height, 75.0, 65.0, orientation == "landscape")
    assert plan.gsd_m == pytest.approx(want["gsd_m"], rel=1e-13)
    for key in ("footprint_across_m", "footprint_along_m", "base_m", "line_spacing_m"):
        assert plan.flight[key] == pytest.approx(want[key], rel=1e-13), key


def test_portrait_swaps_footprint_spacing_and_base():
    land = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0).plan
    port = uav_job(camera="dji-zenmuse-p1-35", height_m=100.0, orientation="portrait").plan
    assert port.gsd_m == land.gsd_m
    assert port.flight["footprint_across_m"] == land.flight["footprint_along_m"]
    assert port.flight["footprint_along_m"] == land.flight["footprint_across_m"]
    assert port.flight["base_m"] > land.flight["base_m"]
    assert port.flight["line_spacing_m"] < land.flight["line_spacing_m"]
    assert port.inputs.orientation == "portrait"
    assert (port.inputs.image_width_px, port.inputs.image_height_px) == (5460, 8192)


def test_orientation_from_the_project_file_and_a_wrong_value(tmp_path):
    base = ('[project]\nname = "p"\n[map]\nscale = 2000\nrelief_interval_m = 0.5\n'
            '[uav]\ncamera = "dji-zenmuse-p1-35"\nheight_m = 100\n')
    p = tmp_path / "p.toml"
    p.write_text(base + 'orientation = "portrait"\n', encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p), "--json"])
    assert r.exit_code == 0, r.output
    u = json.loads(r.stdout)["specification"]["uav"]
    land = uav_job(camera="dji-zenmuse-p1-35", height_m=u["recommended_height_m"]).plan
    assert u["line_spacing_m"] == pytest.approx(
        land.flight["footprint_along_m"] * 0.4)
    p.write_text(base + 'orientation = "sideways"\n', encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p)])
    assert r.exit_code == 2 and "uav.orientation" in r.stderr and "portrait" in r.stderr


# --- large-format cameras on aircraft ---------------------------------------------------------

def test_large_format_camera_plans_at_manned_heights():
    """UltraCam Eagle 80 mm (5.2 µm) at 1,000–5,000 m: GSD = p·H/f, L > GSD, the flight at
    the Instruction's 60 % / 30 % overlaps, and the haze default flagged above 500 m."""
    for h in (1000.0, 3000.0, 5000.0):
        plan = uav_job(camera="ultracam-eagle-80", f_number=5.6, height_m=h, speed_ms=70.0,
                       map_scale=10000, relief_interval_m=2.0).plan
        assert plan.gsd_m == pytest.approx(5.2e-3 * h / 80, rel=1e-12)
        assert plan.ground_resolution_m is not None and plan.ground_resolution_m > plan.gsd_m
        assert plan.inputs.forward_overlap_pct == 60.0 and plan.inputs.side_overlap_pct == 30.0
        assert plan.inputs.platform == "aircraft"
        assert "haze_default_height" in {w.code for w in plan.warnings}
        assert plan.max_height_m is not None and plan.max_height_m > 1000
    clear = uav_job(camera="ultracam-eagle-80", f_number=5.6, height_m=3000.0, speed_ms=70.0,
                    haze_contrast=0.7).plan
    assert "haze_default_height" not in {w.code for w in clear.warnings}
    low = uav_job(camera="dji-mavic-3e", height_m=120.0).plan
    assert "haze_default_height" not in {w.code for w in low.warnings}


def test_aircraft_needs_its_speed():
    with pytest.raises(InputError) as e:
        uav_job(camera="dmc-iii", f_number=5.6, height_m=2000.0)
    assert e.value.field == "speed_ms" and "aircraft" in e.value.message
    r = CliRunner().invoke(main, ["uav", "--camera", "dmc-iii", "--f-number", "5.6",
                                  "--height-m", "2000"])
    assert r.exit_code == 2 and "--speed-ms" in r.stderr


def test_aerial_survey_wording_not_uav(tmp_path):
    """A large-format camera's plan says "aerial survey"/"digital camera", never "UAV",
    in the terminal, the workbook and the PDF, in English and Russian."""
    from openpyxl import load_workbook
    from pypdf import PdfReader

    from scanplan.i18n.labels import t

    for locale, banned, wanted in (("en", "UAV", "Aerial survey"),
                                   ("ru", "БПЛА", "цифровой камерой")):
        p = tmp_path / f"aerial-{locale}.toml"
        p.write_text(
            f'[project]\nname = "Block 7"\nlocale = "{locale}"\n[map]\nscale = 5000\n'
            'relief_interval_m = 1\n[uav]\ncamera = "ultracam-eagle-80"\nf_number = 5.6\n'
            'height_m = 2000\nspeed_ms = 70\n[area]\nwidth_m = 5000\nlength_m = 8000\n',
            encoding="utf-8")
        out = tmp_path / f"out-{locale}"
        r = CliRunner().invoke(main, ["plan", str(p), "--out", str(out)])
        assert r.exit_code == 0, r.output
        if locale == "en":
            assert "UAV" not in r.output and "Aerial survey (digital camera):" in r.output
        wb = load_workbook(out / "spec.xlsx")
        cells = " ".join(str(c.value) for ws in wb for row in ws.iter_rows() for c in row
                         if c.value is not None)
        text = " ".join(" ".join(page.extract_text() for page in
                                 PdfReader(out / "spec.pdf").pages).split())
        # the one exception: the title of the cited paper on the MTF model of UAV cameras
        text = text.replace(" ".join(t("pdf_src_l", locale).split()), "")
        for doc in (cells, text, " ".join(wb.sheetnames)):
            assert banned not in doc
        assert wanted in cells and wanted in text


# --- the cross-check's faults -----------------------------------------------------------------

def test_flight_length_covers_the_photographed_span_of_each_strip():
    """Regression: the flight length used the block length (2.5–6.8 % short); each strip is
    flown over (photos per strip − 1)·B, the photos past the block ends included."""
    job = uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8.0, height_m=300.0,
                  speed_ms=25.0, area_m="2000x3000")
    fl = job.plan.flight
    transit = job.layout.notes["transit_m"]  # from the block's edge and back
    span = (fl["photos_per_strip"] - 1) * fl["base_m"]
    assert span > 3000
    turn = math.pi * fl["line_spacing_m"] / 2
    # one sortie: no run-in for semicircle turns, and a run-out of half a base past the
    # last photo (where the camera trigger stops, so the last photo is surely fired)
    run_out = fl["base_m"] / 2
    assert fl["flight_length_m"] - transit == pytest.approx(fl["strips"] * span
                                                            + (fl["strips"] - 1) * turn
                                                            + run_out)
    # the time as flown: more than the length at the speed (climb, corners, the way back)
    assert fl["flight_time_s"] > fl["flight_length_m"] / 25.0
    # the block-length figure it replaces was 2.6 % short here
    old = fl["strips"] * 3000 + (fl["strips"] - 1) * turn
    assert 1 - old / (fl["flight_length_m"] - transit) == pytest.approx(0.026, abs=0.001)


def test_image_count_convention_is_documented_beside_qgroundcontrol():
    from scanplan.core import flight

    doc = flight.photos_per_strip.__doc__
    assert "QGroundControl" in doc and "ceil(L/B) + 3" in doc
    assert int(flight.photos_per_strip(3000.0, 28.8)) == math.ceil(3000 / 28.8) + 3


# --- scanners ---------------------------------------------------------------------------------

def test_scanner_steps_and_sources():
    assert NS.scanner_steps("photoscan-td") == (7.0, 14.0, 21.0, 28.0, 56.0, 112.0, 224.0)
    ps2000 = NS.scanner_details["photoscan-2000"]
    assert tuple(s.pixel_um for s in ps2000) == (7.0, 14.0, 21.0, 28.0, 56.0, 112.0, 224.0)
    assert all(s.bit_depth == "10 internal; 8 or 12 output" and "Baltsavias" in s.source
               for s in ps2000)
    # binary multiples of 7 µm, plus 21 µm
    assert {s.pixel_um for s in ps2000} - {21.0} == {7.0 * 2 ** k for k in range(6)}
    # the two test papers' scanners: only the pixels they tested, and they say so
    assert NS.scanner_steps("zeiss-scai") == (7.0, 14.0)
    assert NS.scanner_steps("lh-dsw300") == (12.5, 25.0)
    for sid in ("zeiss-scai", "lh-dsw300"):
        assert all("only the scan pixels the test used" in s.note and "ISPRS" in s.source
                   for s in NS.scanner_details[sid])
    assert len(NS.scanners) >= 4


def test_unknown_ids_suggest_the_close_ones():
    r = CliRunner().invoke(main, ["cameras", "show", "mavic-3e"])
    assert r.exit_code == 2 and "did you mean dji-mavic-3e" in r.stderr
    with pytest.raises(Exception, match="did you mean photoscan-td"):
        NS.scanner_steps("photoscan-tdd")


def test_cameras_list_kinds_and_json():
    runner = CliRunner()
    r = runner.invoke(main, ["cameras", "list"])
    assert r.exit_code == 0 and "68 cameras" in r.output and "4 scanners" in r.output
    r = runner.invoke(main, ["cameras", "list", "--kind", "aircraft", "--json"])
    rows = json.loads(r.stdout)
    assert {c["platform"] or "aircraft" for c in rows} == {"aircraft"}
    assert len([c for c in rows if c["kind"] == "digital"]) == 12
    r = runner.invoke(main, ["cameras", "list", "--kind", "scanner", "--json"])
    assert {s["scanner"] for s in json.loads(r.stdout)} == {
        "photoscan-td", "photoscan-2000", "zeiss-scai", "lh-dsw300"}
    r = runner.invoke(main, ["cameras", "show", "photoscan-2000", "--json"])
    assert r.exit_code == 0 and len(json.loads(r.stdout)) == 7


# --- the loader refuses a broken catalogue ----------------------------------------------------

def _set_with(tmp_path, cameras: str | None = None, scanners: str | None = None):
    folder = tmp_path / "set"
    shutil.copytree(bundled_norms_dir() / "gkinp-02-036-02", folder)
    if cameras is not None:
        (folder / "cameras.csv").write_text(cameras, encoding="utf-8")
    if scanners is not None:
        (folder / "scanners.csv").write_text(scanners, encoding="utf-8")
    return folder


HEAD = "id,kind,name,sensor_width_mm,sensor_height_mm,focal_mm,pixel_um,image_width_px," \
       "image_height_px,source\n"


def test_duplicate_camera_id_is_refused(tmp_path):
    row = "cam-a,digital,A,36,24,35,,6000,4000,x\n"
    with pytest.raises(InputError, match=r"cameras.csv:3 \(id\).*twice"):
        read_norm_set_folder(_set_with(tmp_path, HEAD + row + row))


def test_published_pitch_far_from_width_over_pixels_is_refused(tmp_path):
    ok = HEAD + "cam-a,digital,A,36,24,35,6.1,6000,4000,x\n"   # 6.0 exact, +1.7 %
    assert read_norm_set_folder(_set_with(tmp_path, ok)).cameras["cam-a"].pixel_um == 6.0
    bad = HEAD + "cam-b,digital,B,36,24,35,6.5,6000,4000,x\n"  # +8 %
    with pytest.raises(InputError, match=r"cameras.csv:2 \(pixel_um\).*sensor width / image"):
        read_norm_set_folder(_set_with(tmp_path / "b", bad))


def test_scanner_step_listed_twice_is_refused(tmp_path):
    text = "scanner,name,pixel_um,source\ns1,S,7,x\ns1,S,7,x\n"
    with pytest.raises(InputError, match=r"scanners.csv:3 \(pixel_um\).*twice"):
        read_norm_set_folder(_set_with(tmp_path, scanners=text))


def test_bundled_aerial_example():
    """examples/aerial-ultracam-5000.toml: a 1:5000 map, UltraCam Eagle 80 at manned
    heights — maximum 2093 m bound by the digital height accuracy P_Z (normal case:
    GSD ≤ V_z·(B/H)/σ_px with V_z = 0.2·1 m, B/H = 0.4·13080·5.2 µm / 80 mm, σ_px 0.5 px),
    GSD 0.136 m, 6 strips × 23 photos at the Instruction's 60/30 % overlaps, no altitude
    ceiling for a manned aircraft, the haze note. (The Instruction's printed P_Z would allow
    4524 m; it is reported beside it.)"""
    from pathlib import Path

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    path = Path(__file__).resolve().parent.parent / "examples" / "aerial-ultracam-5000.toml"
    if not path.is_file():
        pytest.skip("examples/ not beside the tests")
    res = plan_project(load_project(path))
    u, p = res.uav, res.uav.job.plan
    assert p.inputs.platform == "aircraft" and p.binding == "PZ"
    assert p.ceiling_m is None and all(x.id != "HC" for x in p.limits)
    bh = 0.4 * 13080 * 5.2e-3 / 80
    assert u.max_height_m == pytest.approx(0.2 * bh / 0.5 * 80 / 5.2e-3, rel=1e-9)
    assert u.recommended_height_m == 2090
    assert p.gsd_m == pytest.approx(5.2e-6 * 2090 / 0.080, rel=1e-12)
    assert (p.flight["strips"], p.flight["photos_per_strip"]) == (6, 23)
    # the Instruction's printed form, for comparison: V_z·f/(k·b) on the ground
    b_mm = 0.4 * 13080 * 5.2e-3
    assert p.height_accuracy["forms"]["instruction"]["max_planned_height_m"] == pytest.approx(
        0.2 * 80 / (2 * b_mm) * 80 / 5.2e-3, rel=1e-9)
    assert "haze_default_height" in {w.code for w in p.warnings}


def test_portrait_turns_an_explicit_sensor_too():
    land = uav_job(pixel_um=4.0, focal_mm=35.0, sensor_mm="36x24", f_number=4.0,
                   height_m=100.0).plan
    port = uav_job(pixel_um=4.0, focal_mm=35.0, sensor_mm="36x24", f_number=4.0,
                   height_m=100.0, orientation="portrait").plan
    assert land.flight["footprint_across_m"] == pytest.approx(36 * 100 / 35)
    assert port.flight["footprint_across_m"] == pytest.approx(24 * 100 / 35)
    assert port.flight["footprint_along_m"] == pytest.approx(36 * 100 / 35)
    with pytest.raises(InputError, match="orientation"):
        uav_job(pixel_um=4.0, focal_mm=35.0, sensor_mm="36x24", f_number=4.0,
                height_m=100.0, orientation="sideways")
