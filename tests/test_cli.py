"""The command line as a user meets it: output, --json keys, exit codes, messages."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from scanplan import __version__
from scanplan.cli.main import main

BASE = ["scan", "--map-scale", "2000", "--relief", "0.5", "--camera", "rc30-153"]


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def test_version():
    r = run("--version")
    assert r.exit_code == 0 and __version__ in r.output


@pytest.mark.parametrize("cmd", [[], ["scan"], ["cameras"], ["cameras", "list"]])
def test_help_has_an_example(cmd):
    r = run(*cmd, "--help")
    assert r.exit_code == 0
    assert "scanplan" in r.output and ("Example" in r.output or "--json" in r.output)


def test_instruction_example_text():
    r = run("scan", "--map-scale", "1:2000", "--relief", "1.0", "--photo-scale", "1:10000",
            "--camera", "afa-te-100", "--norms", "gkinp-02-036-02-printed")
    assert r.exit_code == 0, r.output
    assert "1:10000" in r.output
    row = next(line for line in r.output.splitlines() if line.startswith("PR "))
    assert row.split()[-1] == "10.0*"
    assert "binding" in r.output


def test_sweep_json_contract():
    """Several --photo-scale values give one scenario each, with the documented keys."""
    r = run(*BASE, "--photo-scale", "5000", "--photo-scale", "10000", "--photo-scale",
            "15000", "--photo-scale", "20000", "--json")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert [s["photo_scale"] for s in doc["scenarios"]] == [5000, 10000, 15000, 20000]
    s = doc["scenarios"][1]
    assert set(s["constraints"]) == {"PS", "PZ", "PP", "PR", "PD"}
    assert s["constraints"]["PZ"]["pixel_um"] == pytest.approx(8.3152, abs=0.0001)
    assert s["binding"] == "PZ"
    assert s["scan_pixel_um"] == s["constraints"]["PZ"]["pixel_um"]
    pd = s["constraints"]["PD"]
    assert pd["object_size_m"] == 0.2 and pd["probability"] == 0.75 and pd["shape"] == "circle"
    assert {"code", "message"} <= set(doc["warnings"][0])
    assert doc["norms"]["name"] == "gkinp-02-036-02"
    assert doc["norms"]["object_row"]["map_scale"] == 2000


def test_disabled_constraint_is_absent():
    r = run(*BASE, "--photo-scale", "10000", "--norms", "gkinp-02-036-02-printed", "--json")
    assert r.exit_code == 0
    assert "PD" not in json.loads(r.stdout)["scenarios"][0]["constraints"]


def test_focal_and_frame_instead_of_camera():
    r = run("scan", "--map-scale", "5000", "--relief", "2", "--photo-scale", "8000",
            "--focal-mm", "153", "--frame-mm", "230x230", "--resolving-power", "40", "--json")
    assert r.exit_code == 0, r.output
    c = json.loads(r.stdout)["scenarios"][0]["constraints"]
    assert c["PS"]["pixel_um"] == pytest.approx(62.5)


def test_options_change_the_result():
    def pd(*extra):
        r = run(*BASE, "--photo-scale", "10000", "--json", *extra)
        assert r.exit_code == 0, r.output
        return json.loads(r.stdout)["scenarios"][0]["constraints"]
    base = pd()
    assert pd("--object-size-m", "0.4")["PD"]["pixel_um"] == pytest.approx(
        2 * base["PD"]["pixel_um"])
    assert pd("--shape", "square")["PD"]["pixel_um"] < base["PD"]["pixel_um"]
    assert pd("--probability", "0.9")["PD"]["pixel_um"] < base["PD"]["pixel_um"]
    assert pd("--pr-coefficient", "0.4")["PR"]["pixel_um"] == pytest.approx(10.0)
    par = pd("--height-formula", "parallax")["PZ"]
    assert par["formula"] == "parallax" and par["pixel_um"] < base["PZ"]["pixel_um"]


def test_scanner_steps_and_overlap_warning():
    r = run(*BASE, "--photo-scale", "5000", "--scanner", "photoscan-td", "--overlap-pct", "80",
            "--json")
    doc = json.loads(r.stdout)
    assert doc["scenarios"][0]["scanner_pixel_um"] == 7.0
    assert "overlap_not_standard" in {w["code"] for w in doc["warnings"]}


def test_no_norm_object_and_no_size():
    r = run("scan", "--map-scale", "3000", "--relief", "1", "--photo-scale", "10000",
            "--camera", "rc30-153")
    assert r.exit_code == 2
    assert "--object-size-m" in r.stderr and "1:3000" in r.stderr
    r = run("scan", "--map-scale", "3000", "--relief", "1", "--photo-scale", "10000",
            "--camera", "rc30-153", "--object-size-m", "0.5")
    assert r.exit_code == 0, r.output


BAD = [
    (["--photo-scale", "0"], "--photo-scale"),
    (["--photo-scale", "-5000"], "--photo-scale"),
    (["--photo-scale", "nan"], "--photo-scale"),
    (["--photo-scale", "abc"], "--photo-scale"),
    (["--photo-scale", "1:0"], "--photo-scale"),
    (["--photo-scale", "10000", "--map-scale", "0"], "--map-scale"),
    (["--photo-scale", "10000", "--map-scale", "inf"], "--map-scale"),
    (["--photo-scale", "10000", "--overlap-pct", "100"], "--overlap-pct"),
    (["--photo-scale", "10000", "--overlap-pct", "-1"], "--overlap-pct"),
    (["--photo-scale", "10000", "--resolving-power", "0"], "--resolving-power"),
    (["--photo-scale", "10000", "--resolving-power", "-40"], "--resolving-power"),
    (["--photo-scale", "10000", "--resolving-power", "nan"], "--resolving-power"),
    (["--photo-scale", "10000", "--probability", "0"], "--probability"),
    (["--photo-scale", "10000", "--probability", "1"], "--probability"),
    (["--photo-scale", "10000", "--probability", "1.5"], "--probability"),
    (["--photo-scale", "10000", "--shape", "hexagon"], "--shape"),
    (["--photo-scale", "10000", "--object-size-m", "-0.2"], "--object-size-m"),
    (["--photo-scale", "10000", "--pr-coefficient", "0"], "--pr-coefficient"),
    (["--photo-scale", "10000", "--scanner", "nope"], "--scanner"),
    (["--photo-scale", "10000", "--norms", "no-such-set"], "--norms"),
    (["--photo-scale", "10000", "--relief", "0"], "--relief"),
]


@pytest.mark.parametrize(("extra", "option"), BAD, ids=[" ".join(b[0]) for b in BAD])
def test_bad_input_exits_2_naming_the_option(extra, option):
    r = run(*BASE, *extra)
    assert r.exit_code == 2, r.output
    assert option in r.stderr
    assert "Traceback" not in r.output
    assert any(w in r.stderr for w in ("must be", "unknown", "no norm set", "invalid", "Invalid"))


def test_unknown_camera_lists_known():
    r = run("scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000",
            "--camera", "nikon")
    assert r.exit_code == 2 and "--camera" in r.stderr and "rc30-153" in r.stderr


def test_camera_missing_and_no_focal():
    r = run("scan", "--map-scale", "2000", "--relief", "1", "--photo-scale", "10000")
    assert r.exit_code == 2 and "--camera" in r.stderr


def test_cameras_list_and_show():
    r = run("cameras", "list")
    assert r.exit_code == 0 and "rc30-153" in r.output and "afa-te-100" in r.output
    r = run("cameras", "show", "rc30-153", "--json")
    assert json.loads(r.stdout)["focal_mm"] == 153.0
    r = run("cameras", "show", "nope")
    assert r.exit_code == 2


def test_internal_error_is_exit_1_without_traceback(monkeypatch):
    import scanplan.project.jobs

    def boom(**kw):
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(scanplan.project.jobs, "scan_job", boom)
    r = run(*BASE, "--photo-scale", "10000")
    assert r.exit_code == 1
    assert "disk on fire" in r.stderr and "Traceback" not in r.output


def test_largest_photo_scale_per_pixel():
    """Inverse answer: 10 µm supports 1:8315 for Table 8's setting (P_Z limits); a pixel
    coarser than P_R = 12.5 µm supports no photo scale."""
    r = run(*BASE, "--photo-scale", "5000", "--pixel-um", "10", "--pixel-um", "14", "--json")
    assert r.exit_code == 0, r.output
    reach = {x["pixel_um"]: x for x in json.loads(r.stdout)["max_photo_scales"]}
    assert reach[10.0]["max_photo_scale"] == pytest.approx(8315.2, abs=0.1)
    assert reach[10.0]["limit"] == "PZ"
    assert reach[14.0]["max_photo_scale"] == 0 and reach[14.0]["limit"] == "PR"
    r = run(*BASE, "--photo-scale", "5000", "--pixel-um", "-3")
    assert r.exit_code == 2 and "--pixel-um" in r.stderr


@pytest.mark.parametrize("cmd", [
    ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "100", "--area-m", "20x"],
    ["init", "/nonexistent-dir/x.toml", "--kind", "uav", "--map-scale", "2000",
     "--relief", "0.5", "--area-m", "2000by3000"],
])
def test_bad_area_m_names_metres_and_a_block_example(cmd):
    """A block is WIDTHxLENGTH in metres: the error must not ask for millimetres and a
    230x230 frame (it did — the frame parser's message)."""
    r = run(*cmd)
    assert r.exit_code == 2, r.output
    assert "--area-m" in r.stderr and "WIDTHxLENGTH in m, e.g. 2000x3000" in r.stderr
    assert "mm" not in r.stderr and "230x230" not in r.stderr
