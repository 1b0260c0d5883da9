"""The everyday jobs run out of the box: a 1:500 UAV plan, a 1:1000 film plan and an
archive-photo scan job (issue 13). Their headline numbers, in the terminal text and in
``--json``.

The UAV heights depend on the height model and the altitude ceiling; they live in
``UAV_500`` only, so a change of either is one edit here.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"

# --- the numbers, in one place ------------------------------------------------------------
UAV_500 = {
    "file": "uav-p1-500.toml",
    "planned_height_m": 100,
    # The altitude ceiling binds: 150 m highest flown (Russian airspace rules, para. 52(1))
    # / 1.1 = 136.4 m planned. Without it P_P would: GSD ≤ 0.07 mm × 500 = 35 mm at the
    # highest flown height 1.1·H, with the exact pitch 35.9 mm / 8192 px = 4.382 µm:
    # H = 0.035 m × 35 mm / 4.382 µm / 1.1 = 254.1 m
    "max_height_m": 150 / 1.1,
    "binding": "HC",
    "constraints_max_height_m": 254.1,
    "constraints_binding": "PP",
    "gsd_m": 0.012521,  # 4.382 µm × 100 m / 35 mm
    "object": "gas-valve covers, survey marks",
    "object_size_m": 0.15,
    "photos": 1240,
}
FILM_1000 = {
    "file": "film-1000.toml",
    "photo_scale": 8000,
    # P_P = 70 µm × Mk/Mc = 70 × 1000/8000 (the Instruction's graphic photo-plan pixel)
    "scan_pixel_um": 8.75,
    "binding": "PP",
    "scanner_pixel_um": 7.0,
    "frames": 12,
}
ARCHIVE = {
    "file": "archive-12000-for-2000.toml",
    "photo_scale": 12000,
    # P_P = 70 × 2000/12000 = 11.67 µm binds once P_D (9.2 µm < P_R 12.5 µm) is set aside
    "scan_pixel_um": 11.667,
    "binding": "PP",
    "pd_um": 9.21,
    # seed 001: 20 cm poles, circle, P 0.75, R 40: Mc_interp = 2·200·0.5364·40/0.97 = 8847
    "limit": 8847,
}


def _run(*args: str) -> str:
    r = CliRunner().invoke(main, list(args), prog_name="scanplan")
    assert r.exit_code == 0, (r.output, r.exception)
    return r.output


def _json(name: str) -> dict:
    return json.loads(_run("plan", str(EXAMPLES / name), "--json"))


# --- 1:500 UAV ----------------------------------------------------------------------------


def test_uav_500_json():
    d = _json(UAV_500["file"])
    u = d["specification"]["uav"]
    assert u["recommended_height_m"] == UAV_500["planned_height_m"]
    assert u["max_height_m"] == pytest.approx(UAV_500["max_height_m"], abs=0.05)
    assert u["binding"] == UAV_500["binding"]
    assert u["max_flown_height_m"] == pytest.approx(150.0)
    assert u["constraints_max_height_m"] == pytest.approx(UAV_500["constraints_max_height_m"],
                                                          abs=0.05)
    assert u["gsd_m"] == pytest.approx(UAV_500["gsd_m"], rel=1e-3)
    rec = d["uav"]["recognition"]
    assert [(r["object"], r["object_size_m"], r["map_scale"]) for r in rec] == [
        (UAV_500["object"], UAV_500["object_size_m"], 500)]
    fl = d["uav"]["flight"]
    assert fl["photos"] == UAV_500["photos"]
    assert fl["data_volume_jpeg_bytes"] == pytest.approx(fl["data_volume_bytes"] / 9.0)


def test_uav_500_text():
    out = _run("plan", str(EXAMPLES / UAV_500["file"]))
    assert (f"maximum planned height         {UAV_500['max_height_m']:.0f} m (flown up to 150 m)"
            f" ({UAV_500['binding']}") in out
    assert (f"without the ceiling            {UAV_500['constraints_max_height_m']:.0f} m"
            in out)
    assert f"({UAV_500['constraints_binding']} binds there)" in out
    assert f"{UAV_500['planned_height_m']} m (flown up to 110 m" in out
    assert UAV_500["object"] in out
    assert "uncompressed (JPEG ≈" in out


# --- 1:1000 film --------------------------------------------------------------------------


def test_film_1000_json():
    d = _json(FILM_1000["file"])
    f = d["specification"]["film"]
    assert f["recommended_photo_scale"] == FILM_1000["photo_scale"]
    assert f["archive"] is False
    assert f["scan_pixel_um"] == pytest.approx(FILM_1000["scan_pixel_um"])
    assert f["binding"] == FILM_1000["binding"]
    assert f["scanner_pixel_um"] == FILM_1000["scanner_pixel_um"]
    assert f["frames"] == FILM_1000["frames"]
    assert d["film"]["norms"]["object_row"]["map_scale"] == 1000
    assert "Недра, 1989" in d["film"]["inputs"]["object"]["source"]


def test_film_1000_text():
    out = _run("plan", str(EXAMPLES / FILM_1000["file"]))
    assert "map 1:1000, relief interval 0.5 m" in out
    assert "recommended photo scale        1:8000" in out
    assert "8.8 µm → scanner step 7 µm" in out


# --- archive photos -----------------------------------------------------------------------


def test_archive_json():
    d = _json(ARCHIVE["file"])
    f = d["specification"]["film"]
    assert f["archive"] is True
    assert f["recommended_photo_scale"] == ARCHIVE["photo_scale"]
    assert f["scan_pixel_um"] == pytest.approx(ARCHIVE["scan_pixel_um"], abs=1e-3)
    assert f["binding"] == ARCHIVE["binding"]
    pd = d["film"]["scenarios"][0]["constraints"]["PD"]["pixel_um"]
    assert pd == pytest.approx(ARCHIVE["pd_um"], abs=0.01)
    codes = [w["code"] for w in d["warnings"]]
    # and, for information, the scanned ground pixel against ГОСТ Р 59562-2021 Table Б.1
    assert codes == ["archive_not_interpretable", "gsd_limit_film"]
    w = d["warnings"][0]
    assert w["params"]["limit"] == ARCHIVE["limit"]
    # the photos exist: nothing advises another flight
    assert "fly" not in json.dumps(d["warnings"]) and "fly" not in f["reason"]
    assert "in the field" in w["message"] and "other sources" in w["message"]


def test_archive_text_and_scale_written_with_colon():
    out = _run("plan", str(EXAMPLES / ARCHIVE["file"]))
    # the file writes scale = "1:2000": shown once as 1:2000, never 1:1:2000
    assert "map 1:2000," in out and "1:1:" not in out
    assert "photo scale (existing photos, given)  1:12000" in out
    assert "11.7 µm" in out and "poles, hydrants" in out


def test_archive_russian_messages():
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    r = plan_project(load_project(EXAMPLES / ARCHIVE["file"]))
    ru = r.warnings[0].text("ru")
    assert "в поле" in ru and "других источников" in ru and "столбы, гидранты" in ru
    assert "аэрофотосъ" not in ru  # no "fly a larger scale" in Russian either
    assert "11,7" in r.film.reason.text("ru")


def test_archive_readable_photos_keep_the_engine_answer(tmp_path):
    """Archive photos at 1:8000 show the poles: the scan pixel is the engine's own."""
    text = (EXAMPLES / ARCHIVE["file"]).read_text(encoding="utf-8").replace(
        'photo_scale = "1:12000"', "photo_scale = 8000")
    p = tmp_path / "a.toml"
    p.write_text(text, encoding="utf-8")
    d = json.loads(_run("plan", str(p), "--json"))
    f = d["specification"]["film"]
    assert f["binding"] == "PR" and f["scan_pixel_um"] == pytest.approx(12.5)
    assert f["reason"].startswith("the photos exist at 1:8000")
    assert not [w for w in d["warnings"] if "interpret" in w["code"]]


def test_archive_and_candidates_are_exclusive(tmp_path):
    p = tmp_path / "a.toml"
    p.write_text("[map]\nscale = 2000\nrelief_interval_m = 1\n[film]\ncamera = 'rc30-153'\n"
                 "photo_scale = 12000\nphoto_scales = [8000]\n", encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p)], prog_name="scanplan")
    assert r.exit_code == 2
    assert "film.photo_scale (line 6)" in r.output and "not both" in r.output


def test_batch_shows_each_projects_warnings(tmp_path):
    out = _run("plan", str(EXAMPLES))
    assert "Warnings — archive-12000-for-2000.toml:" in out
    assert "[archive_not_interpretable]" in out
    assert "Warnings — instruction-2000-film.toml:" in out


def test_archive_scan_pixel_curve_passes_through_the_specified_pixel():
    """With P_D set aside for archive photos 1:12000, the plot's and the Sweep sheet's scan
    pixel curve is P_P's 11.7 µm there, as specified (it drew P_D's 9.2 µm below the marked
    point); where the object can be interpreted (up to 1:8847) the curve is unchanged."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    plan = plan_project(load_project(EXAMPLES / ARCHIVE["file"])).film.job.plan
    (s,) = plan.scenarios
    sw = plan.sweep
    i = min(range(len(sw["photo_scale"])), key=lambda k: abs(sw["photo_scale"][k] - 12000))
    assert sw["photo_scale"][i] == pytest.approx(12000)
    assert (sw["scan_pixel_um"][i], sw["binding"][i]) == (pytest.approx(s.scan_pixel_um), "PP")
    assert s.scan_pixel_um == pytest.approx(11.67, abs=0.01)
    limit = plan.interpretation_limit_photo_scale
    for k, mc in enumerate(sw["photo_scale"]):
        cids = [c for c in plan.constraint_ids if c in sw and (c != "PD" or mc <= limit)]
        assert sw["scan_pixel_um"][k] == pytest.approx(min(sw[c][k] for c in cids))
