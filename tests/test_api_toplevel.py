"""The top-level Python API (issue 15): results with to_dict (the --json document),
to_frame (pandas), write and a notebook summary; batches with typed errors; --jobs."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

import scanplan
from scanplan.api import SUMMARY_COLUMNS
from scanplan.cli.main import main
from scanplan.errors import InputError

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.name)
def test_to_dict_is_the_cli_json(example):
    cli = CliRunner().invoke(main, ["plan", str(example), "--json"])
    assert cli.exit_code == 0, cli.output
    assert scanplan.plan(example).to_dict() == json.loads(cli.output)


def test_scan_and_uav_to_dict_are_the_cli_json():
    runner = CliRunner()
    cli = runner.invoke(main, ["scan", "--map-scale", "2000", "--relief", "1",
                               "--photo-scale", "10000", "--camera", "afa-te-100", "--json"])
    assert scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[10000],
                         camera="afa-te-100").to_dict() == json.loads(cli.output)
    cli = runner.invoke(main, ["uav", "--camera", "dji-zenmuse-p1-35", "--height-m", "120",
                               "--map-scale", "1000", "--relief", "0.5", "--json"])
    assert scanplan.uav(camera="dji-zenmuse-p1-35", height_m=120, map_scale=1000,
                        relief_interval_m=0.5).to_dict() == json.loads(cli.output)


def test_plan_takes_a_path_a_toml_text_or_a_dict():
    path = ROOT / "examples" / "instruction-2000-film.toml"
    text = path.read_text(encoding="utf-8")
    by_path = scanplan.plan(str(path)).to_dict()["specification"]
    assert scanplan.plan(text).to_dict()["specification"] == by_path
    as_dict = {"map": {"scale": "1:2000", "relief_interval_m": 1.0},
               "film": {"camera": "afa-te-100", "photo_scales": [6000, 8000, 10000],
                        "resolving_power_lpmm": 40, "scanner": "photoscan-td"},
               "area": {"width_m": 3000, "length_m": 4000}}
    spec = scanplan.plan(as_dict).to_dict()["specification"]["film"]
    assert spec["recommended_photo_scale"] == 8000 and spec["binding"] == "PR"
    with pytest.raises(InputError) as err:
        scanplan.plan({"map": {"scale": 2000, "relief_interval_m": 1.0},
                       "uav": {"camera": "dji-zenmuse-p1-35", "speed_ms": -1}})
    assert "uav.speed_ms" in err.value.field


def test_scan_frame_one_row_per_photo_scale_units_in_names():
    frame = scanplan.scan(map_scale=2000, relief_interval_m=1.0,
                          photo_scales=[6000, 8000, 10000], camera="afa-te-100").to_frame()
    assert list(frame["photo_scale"]) == [6000, 8000, 10000]
    for col in ("binding", "scan_pixel_um", "scanner_pixel_um", "resolution_on_ground_mm",
                "recognition_probability", "frame_megabytes", "pixel_um_PS", "pixel_um_PR"):
        assert col in frame.columns
    row = frame.set_index("photo_scale").loc[10000]
    pixels = {c.removeprefix("pixel_um_"): row[c] for c in frame.columns
              if c.startswith("pixel_um_")}
    assert row["scan_pixel_um"] == min(pixels.values())
    assert pixels[row["binding"]] == row["scan_pixel_um"]


def test_uav_frame_one_row_per_constraint():
    r = scanplan.uav(camera="dji-zenmuse-p1-35", height_m=100, map_scale=500,
                     relief_interval_m=0.5)
    frame = r.to_frame()
    assert list(frame.columns) == ["constraint", "name", "compares", "limit_m",
                                   "max_planned_height_m", "max_flown_height_m",
                                   "margin_pct", "binding"]
    assert frame["binding"].sum() == 1
    binding = frame[frame["binding"]].iloc[0]
    assert binding["constraint"] == r.plan.binding
    assert binding["max_planned_height_m"] == pytest.approx(r.plan.max_height_m)
    assert "<table>" in r._repr_html_()


def test_height_sweep_as_a_frame():
    """The README's notebook example: a sweep of heights, GSD rising with height."""
    import pandas as pd

    rows = [{"height_m": h, "gsd_cm": scanplan.uav(camera="dji-zenmuse-p1-35",
                                                   height_m=h).plan.gsd_m * 100}
            for h in (60, 100, 140)]
    frame = pd.DataFrame(rows)
    assert frame["gsd_cm"].is_monotonic_increasing


def test_batch_keeps_the_good_results_and_a_typed_error(tmp_path):
    for p in EXAMPLES[:2]:
        (tmp_path / p.name).write_text(p.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "zz-bad.toml").write_text("[map]\nscale = 2000\nrelief_interval_m = -1\n"
                                          "[uav]\ncamera = 'dji-zenmuse-p1-35'\n",
                                          encoding="utf-8")
    b = scanplan.batch(tmp_path)
    assert len(b.results) == 2
    (bad, err), = b.errors.items()
    assert bad.endswith("zz-bad.toml") and isinstance(err, InputError)
    assert "map.relief_interval_m (line 3)" in err.field
    frame = b.to_frame()
    assert list(frame.columns) == list(SUMMARY_COLUMNS) and len(frame) == 2
    assert "<table" in b._repr_html_()


def test_write_is_atomic_and_as_the_cli(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    example = ROOT / "examples" / "uav-p1-500.toml"
    written = scanplan.plan(example).write(tmp_path / "api", formats=["xlsx"])
    assert [p.name for p in written] == ["spec.xlsx"]
    cli = CliRunner().invoke(main, ["plan", str(example), "--out", str(tmp_path / "cli")])
    assert cli.exit_code == 0
    assert (tmp_path / "api" / "spec.xlsx").read_bytes() == \
        (tmp_path / "cli" / "spec.xlsx").read_bytes()
    with pytest.raises(InputError):
        scanplan.plan(example).write(tmp_path / "api", formats=["docx"])


def test_batch_jobs_1_and_2_write_identical_files(tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    src = tmp_path / "in"
    src.mkdir()
    for p in EXAMPLES[:3]:
        (src / p.name).write_text(p.read_text(encoding="utf-8"), encoding="utf-8")
    (src / "zz-bad.toml").write_text("nonsense\n", encoding="utf-8")
    outs = {}
    for jobs in (1, 2):
        out = tmp_path / f"out{jobs}"
        r = subprocess.run([sys.executable, "-m", "scanplan", "plan", str(src), "--out",
                            str(out), "--jobs", str(jobs)], capture_output=True, text=True)
        assert r.returncode == 2, r.stderr  # the bad file is reported, the others planned
        assert "zz-bad.toml" in r.stderr and "Traceback" not in r.stderr
        assert "planning" not in r.stderr  # no progress line: stderr is not a terminal
        outs[jobs] = (r.stdout, {p.name: p.read_bytes() for p in sorted(out.iterdir())})
    assert outs[1] == outs[2]
    files = outs[1][1]
    assert {"summary.csv", "summary.xlsx"} <= set(files) and len(files) == 3 * 2 + 2
    csv = files["summary.csv"].decode("utf-8-sig").splitlines()
    assert csv[0].startswith("project,file,map_scale,") and len(csv) == 1 + 4
    assert "zz-bad.toml" in csv[-1]


def test_import_scanplan_and_help_do_not_import_numpy():
    code = ("import sys, scanplan; from scanplan.cli import main; "
            "from click.testing import CliRunner; "
            "assert 'Commands:' in CliRunner().invoke(main, ['--help']).output; "
            "print('numpy' in sys.modules)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.stdout.strip() == "False", r.stderr


def test_batch_to_dict_is_the_cli_json_of_a_batch(tmp_path):
    for p in EXAMPLES[:2]:
        (tmp_path / p.name).write_text(p.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "zz-bad.toml").write_text("[map]\nscale = 2000\n", encoding="utf-8")
    cli = CliRunner().invoke(main, ["plan", str(tmp_path), "--json", "--jobs", "1"])
    assert cli.exit_code == 2
    assert scanplan.batch(tmp_path).to_dict() == json.loads(cli.stdout)


def test_notebook_summaries_and_safe_writes(tmp_path):
    project = scanplan.plan(ROOT / "examples" / "instruction-2000-film.toml")
    shown = project._repr_html_()
    assert "Instruction example" in shown and "film_photo_scale" in shown and "8000" in shown
    assert "1:8000" in project.film._repr_html_()
    (tmp_path / "spec.xlsx").write_bytes(b"someone else's workbook")
    with pytest.raises(InputError, match="not written by scanplan"):
        project.write(tmp_path, formats=["xlsx"])
    assert (tmp_path / "spec.xlsx").read_bytes() == b"someone else's workbook"
    assert project.write(tmp_path, formats=["xlsx"], force=True)[0].name == "spec.xlsx"


def test_write_never_replaces_an_input_of_the_project(tmp_path):
    """The API's write protects what the command line's does: the project's area file too
    (here linked as the report's name), even with ``force``; a folder it created for
    nothing is removed again."""
    project = scanplan.plan(ROOT / "examples" / "uav-town-2000.toml")
    area = project.spec.project.area.file
    out = tmp_path / "out"
    out.mkdir()
    os.link(area, out / "spec.xlsx")
    with pytest.raises(InputError, match="is the input file"):
        project.write(out, formats=["xlsx"], force=True)
    assert (out / "spec.xlsx").read_bytes() == Path(area).read_bytes()
    (tmp_path / "a-file").write_text("x")
    with pytest.raises(InputError, match="is not a folder"):
        project.write(tmp_path / "a-file", formats=["xlsx"])
    with pytest.raises(InputError, match="the file system allows"):
        project.write(out / "new" / "deeper", formats=["xlsx"], name="x" * 300)
    assert not (out / "new").exists()
