"""The output comparison script (tools/compare_outputs.py) on two tiny folders: it finds a
difference a reader would see, and ignores what only the run's folder or the bytes of a
zip change."""

from __future__ import annotations

import importlib
import json
import zipfile
from pathlib import Path

import pytest
from helpers import script_module

TOOLS = Path(__file__).resolve().parents[1] / "tools"


@pytest.fixture(scope="module")
def compare():
    with script_module(TOOLS, "compare_outputs") as module:
        yield module


def _run(folder: Path, work: str, waypoints: str, csv_row: str) -> Path:
    files = folder / "en" / "demo" / "files"
    files.mkdir(parents=True)
    (folder / "manifest.json").write_text(json.dumps({"work": work}))
    (files / "mission.waypoints").write_text(f"QGC WPL 110\n{waypoints}\n")
    (files / "photos.csv").write_text(f"id,file\n{csv_row.format(work=work)}\n")
    with zipfile.ZipFile(files / "route.kmz", "w") as z:
        z.writestr("wpmz/template.kml", "<kml/>")
    return folder


def test_one_difference_is_found_and_the_run_folder_is_not_one(compare, tmp_path):
    a = _run(tmp_path / "a", "/tmp/scanplan-compare-aaaa", "0\t1\t0\t16", "1,{work}/x.kml")
    b = _run(tmp_path / "b", "/tmp/scanplan-compare-bbbb", "0\t1\t0\t22", "1,{work}/x.kml")
    problems = compare.compare_folders(a, b)
    assert len(problems) == 1, problems
    assert problems[0].startswith("differs: en/demo/files/mission.waypoints")
    assert "-0\t1\t0\t16" in problems[0] and "+0\t1\t0\t22" in problems[0]
    assert compare.main(["compare", str(a), str(b)]) == 1


def test_the_same_runs_match_and_a_missing_file_is_reported(compare, tmp_path, capsys):
    a = _run(tmp_path / "a", "/tmp/p1", "0\t1", "1,{work}/x.kml")
    b = _run(tmp_path / "b", "/tmp/p2", "0\t1", "1,{work}/x.kml")
    assert compare.compare_folders(a, b) == []
    assert compare.main(["compare", str(a), str(b)]) == 0
    assert "all 3 files match" in capsys.readouterr().out
    (b / "en" / "demo" / "files" / "photos.csv").unlink()
    assert compare.compare_folders(a, b) == [f"only in {a}: en/demo/files/photos.csv"]


def test_the_locale_line_is_set_or_added(compare):
    assert compare.with_locale('[project]\nname = "x"\nlocale = "en"\n', "ru") == (
        '[project]\nname = "x"\nlocale = "ru"\n')
    assert compare.with_locale('[project]\nname = "x"\n', "ru") == (
        '[project]\nlocale = "ru"\nname = "x"\n')


def test_the_page_gets_the_project_as_flat_tables(compare):
    """A project file's sub-tables become the page's dotted sections, dates its text."""
    import datetime as dt

    faces = importlib.import_module("compare_faces")
    doc = {"map": {"scale": 2000}, "uav": {"camera": "x", "target": {"r_max": 0.3}},
           "schedule": {"start": dt.date(2024, 5, 1)}}
    assert faces.page_tables(doc) == {"map": {"scale": 2000}, "uav": {"camera": "x"},
                                      "uav.target": {"r_max": 0.3},
                                      "schedule": {"start": "2024-05-01"}}


def test_every_terminal_run_names_a_command(compare):
    """The other commands compared are real commands of the command line."""
    from scanplan.cli.main import main

    for name, args in compare.TERMINALS.items():
        assert args[0] in main.list_commands(None), name  # type: ignore[arg-type]
