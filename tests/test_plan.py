"""`scanplan plan PROJECT.toml`: the example contracts, invalid project files, batches."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.project.file import KEYS, load_project
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
if not EXAMPLES.is_dir():  # running against an installed package from elsewhere
    pytest.skip("examples/ not found beside the tests", allow_module_level=True)


def plan_json(*args: str) -> dict:
    r = CliRunner().invoke(main, ["plan", *args, "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_instruction_example():
    """1:2000 plan, 1 m relief, 18×18 cm f 100 mm R 40: at 1:10000 (the Instruction's
    choice) the 20 cm poles are not interpretable (Mc_interp ≈ 8850), so the largest
    candidate that meets every constraint is 1:8000; P_R = 12.5 µm binds there, and the
    PhotoScan TD's nearest finer step is 7 µm."""
    doc = plan_json(str(EXAMPLES / "instruction-2000-film.toml"))
    spec = doc["specification"]["film"]
    assert spec["recommended_photo_scale"] == 8000
    assert spec["binding"] == "PR"
    assert spec["scan_pixel_um"] == pytest.approx(12.5)
    assert spec["scanner_pixel_um"] == 7.0
    # the Instruction's own numbers at 1:10000 (with the corrected 0.5 coefficient)
    at10000 = next(s for s in doc["film"]["scenarios"] if s["photo_scale"] == 10000)
    c = at10000["constraints"]
    assert (c["PS"]["pixel_um"], round(c["PZ"]["pixel_um"], 1), c["PP"]["pixel_um"],
            c["PR"]["pixel_um"]) == (20.0, 13.9, 14.0, 12.5)
    assert "not_interpretable" in {w["code"] for w in doc["warnings"]}
    assert spec["frames"] == 30 and spec["strips"] == 3


def test_table_9_setting():
    """1:10000 map, 1 m relief (seed 001 Table 9): P_Z binds; 1:20000 is the smallest photo
    scale the 7 µm scanner still reaches (P_Z 8.3 µm; 6.7 µm at 1:25000 is too fine)."""
    doc = plan_json(str(EXAMPLES / "map-10000-relief-1m.toml"))
    spec = doc["specification"]["film"]
    assert spec["recommended_photo_scale"] == 20000
    assert spec["binding"] == "PZ"
    assert spec["scan_pixel_um"] == pytest.approx(8.315, abs=0.001)
    assert spec["recognition_probability"] > 0.75
    assert doc["project"]["locale"] == "ru"


def test_uav_seed_002_flight():
    """Canon 5D Mark II planned at 300 m, flown +40 %, for a 1:2000 plan with 0.5 m relief:
    the digital height accuracy (σ_Z = (H/B)·(H/c)·σ_px ≤ 0.1 m RMS, B/H 0.192, 0.5 px)
    allows at most 214 m planned (flown up to 300 m), so the 300 m plan is lowered to
    210 m (flown up to 294 m, under the project's 500 m ceiling): GSD 2.69 cm, L 4.48 cm,
    recognition of 20 cm poles 0.954. (At 300 m the seed's L, P stand: tests/test_uav.py.)"""
    doc = plan_json(str(EXAMPLES / "uav-canon-2000.toml"))
    u = doc["specification"]["uav"]
    assert u["recommended_height_m"] == 210 and u["binding"] == "PZ"
    assert u["max_height_m"] == u["max_planned_height_m"] == pytest.approx(213.95, abs=0.05)
    assert u["max_flown_height_m"] == pytest.approx(299.53, abs=0.05)
    assert u["recommended_flown_height_m"] == pytest.approx(294)
    assert u["ceiling_m"] == 500 and u["constraints_max_height_m"] is None
    assert u["sigma_z_m"] == pytest.approx(0.0982, abs=1e-4)
    assert u["gsd_m"] == pytest.approx(doc["uav"]["inputs"]["pixel_um"] / 1000 * 210 / 50)
    assert u["ground_resolution_m"] == pytest.approx(0.0448, abs=5e-5)
    assert u["recognition"][0]["probability"] == pytest.approx(0.954, abs=5e-4)
    assert u["photos"] == 5168 and u["strips"] == 34


def test_text_summary_shows_the_same_numbers():
    r = CliRunner().invoke(main, ["plan", str(EXAMPLES / "uav-canon-2000.toml")])
    assert r.exit_code == 0
    assert "210 m (flown up to 294 m, +40 %)" in r.output
    assert "214 m (flown up to 300 m) (PZ height accuracy)" in r.output
    assert "0.027 m / 0.045 m" in r.output
    r = CliRunner().invoke(main, ["plan", str(EXAMPLES / "instruction-2000-film.toml")])
    assert "recommended photo scale        1:8000" in r.output


def test_height_lowered_when_above_the_maximum(tmp_path):
    text = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8").replace(
        "height_m = 300", "height_m = 500")
    p = tmp_path / "high.toml"
    p.write_text(text, encoding="utf-8")
    result = plan_project(load_project(p))
    assert result.uav.recommended_height_m == 210 and result.uav.planned_height_m == 500
    assert "height_lowered" in {w.code for w in result.warnings}
    assert result.uav.job.plan.heights_m["planned"] == 210


def test_film_and_uav_side_by_side(tmp_path):
    film = (EXAMPLES / "instruction-2000-film.toml").read_text(encoding="utf-8")
    uav = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    uav_part = uav[uav.index("[uav]"):uav.index("[area]")]
    p = tmp_path / "both.toml"
    p.write_text(film.replace("[area]", uav_part + "[area]"), encoding="utf-8")
    doc = plan_json(str(p))
    rows = {r["quantity"]: r for r in doc["specification"]["comparison"]}
    assert rows["pixel on the ground"]["film"] == pytest.approx(7e-6 * 8000)
    assert rows["pixel on the ground"]["uav"] == pytest.approx(36 / 5616 * 300 / 50)


BAD = {
    "unknown key": ("[map]\nscale = 2000\nrelief_interval_m = 1\nscael = 3\n[film]\n"
                    "camera = 'rc30-153'\nphoto_scales = [10000]\n", "map.scael (line 4)"),
    "wrong type": ("[map]\nscale = 2000\nrelief_interval_m = 'one'\n[film]\n"
                   "camera = 'rc30-153'\nphoto_scales = [10000]\n",
                   "map.relief_interval_m (line 3)"),
    "negative scale": ("[map]\nscale = -2000\nrelief_interval_m = 1\n[film]\n"
                       "camera = 'rc30-153'\nphoto_scales = [10000]\n", "map.scale (line 2)"),
    "overlap 100": ("[map]\nscale = 2000\nrelief_interval_m = 1\n[film]\n"
                    "camera = 'rc30-153'\nphoto_scales = [10000]\nforward_overlap_pct = 100\n",
                    "film.forward_overlap_pct (line 7)"),
    "uav overlap 100": ("[map]\nscale = 2000\nrelief_interval_m = 1\n[uav]\n"
                        "camera = 'dji-zenmuse-p1-35'\nforward_overlap_pct = 100\n",
                        "uav.forward_overlap_pct (line 6)"),
    "missing camera": ("[map]\nscale = 2000\nrelief_interval_m = 1\n[uav]\nheight_m = 100\n",
                       "uav.camera (line 4)"),
    "unknown camera": ("[map]\nscale = 2000\nrelief_interval_m = 1\n[film]\n"
                       "camera = 'nope'\nphoto_scales = [10000]\n", "film.camera (line 5)"),
    "unknown section": ("[map]\nscale = 2000\nrelief_interval_m = 1\n[drone]\nx = 1\n",
                        "[drone] (line 4)"),
    "not TOML": ("[map\nscale = 2000\n", "is not valid TOML"),
    "no film or uav": ("[map]\nscale = 2000\nrelief_interval_m = 1\n", "[film] or a [uav]"),
}


@pytest.mark.parametrize("case", list(BAD), ids=list(BAD))
def test_invalid_project_exits_2_naming_key_and_line(tmp_path, case):
    text, expected = BAD[case]
    p = tmp_path / "bad.toml"
    p.write_text(text, encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p)])
    assert r.exit_code == 2, r.output
    assert expected in r.stderr and "Traceback" not in r.output


def test_unreadable_file(tmp_path):
    r = CliRunner().invoke(main, ["plan", str(tmp_path / "missing.toml")])
    assert r.exit_code == 2 and "cannot be read" in r.stderr
    p = tmp_path / "binary.toml"
    p.write_bytes(b"\xff\xfe\x00bad")
    r = CliRunner().invoke(main, ["plan", str(p)])
    assert r.exit_code == 2 and "UTF-8" in r.stderr


def test_batch_continues_past_bad_files(tmp_path):
    for name in ("instruction-2000-film.toml", "uav-canon-2000.toml"):
        (tmp_path / name).write_text((EXAMPLES / name).read_text(encoding="utf-8"),
                                     encoding="utf-8")
    (tmp_path / "broken.toml").write_text(BAD["overlap 100"][0], encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(tmp_path)])
    assert r.exit_code == 2
    assert "instruction-2000-film.toml" in r.stdout and "uav-canon-2000.toml" in r.stdout
    assert "2 planned, 1 failed" in r.stdout
    assert "film.forward_overlap_pct (line 7)" in r.stderr
    r = CliRunner().invoke(main, ["plan", str(tmp_path), "--json"])
    doc = json.loads(r.stdout)
    assert len(doc["projects"]) == 2 and len(doc["errors"]) == 1


def test_every_documented_key_is_in_the_project_docs():
    docs = (Path(__file__).resolve().parent.parent / "docs" / "project-file.md").read_text(
        encoding="utf-8")
    for section, keys in KEYS.items():
        assert f"[{section}]" in docs
        for key in keys:
            assert f"`{key}`" in docs, (section, key)


def test_plan_writes_both_reports_with_the_specification(tmp_path):
    """`--out DIR` writes spec.xlsx (and spec.pdf when the PDF writer is present); the
    workbook's Summary carries the same recommended photo scale as --json."""
    openpyxl = pytest.importorskip("openpyxl")
    r = CliRunner().invoke(main, ["plan", str(EXAMPLES / "instruction-2000-film.toml"),
                                  "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "spec.xlsx").exists() and (tmp_path / "spec.pdf").exists()
    wb = openpyxl.load_workbook(tmp_path / "spec.xlsx")
    ws = wb.worksheets[0]
    cells = {ws.cell(row, 1).value: ws.cell(row, 2).value for row in range(1, ws.max_row + 1)}
    assert cells["Recommended photo scale"] == 8000
    assert cells["Scan pixel, µm"] == pytest.approx(12.5)
    pypdf = pytest.importorskip("pypdf")
    text = "\n".join(page.extract_text() for page in pypdf.PdfReader(tmp_path / "spec.pdf").pages)
    assert "Recommended photo scale" in text and "1:8000" in text
    assert "12.5 → 7.0" in text
