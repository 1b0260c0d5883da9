"""One sortie count everywhere (issue 14: one home per concept).

The flight layout splits the block into sorties and the survey design counts the flying
days from them: one sortie length (``[uav] max_flight_time_min`` or ``[schedule]
sortie_time_min``, scanplan/project/sorties.py) drives both, and the terminal, the JSON, the
workbook, the PDF and the mission files show the same number. Each document is read back
(JSON keys, openpyxl cells, pdftotext of the PDF, the files written).
"""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest
from click.testing import CliRunner

import scanplan
from scanplan.cli.main import main
from scanplan.errors import InputError
from scanplan.i18n.labels import t
from scanplan.i18n.messages import render
from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "examples").glob("*.toml"))


def _json_counts(doc: dict) -> dict[str, int]:
    """Every sortie count of the JSON document, by where it is."""
    spec = doc["specification"]
    out: dict[str, int] = {}
    uav = spec.get("uav") or {}
    if uav.get("layout"):
        out["specification.uav.layout.n_sorties"] = uav["layout"]["n_sorties"]
    if uav.get("sorties") is not None:
        out["specification.uav.sorties"] = uav["sorties"]
    flight = (doc.get("uav") or {}).get("flight") or {}
    if "sorties" in flight:
        out["uav.flight.sorties"] = flight["sorties"]
    sun = (doc.get("survey_design") or {}).get("sun") or {}
    if sun.get("sorties") is not None:
        out["survey_design.sun.sorties"] = sun["sorties"]
    return out


def _labels(key: str) -> tuple[str, ...]:
    return tuple(t(key, loc) for loc in ("en", "ru"))


def _text_counts(text: str, doc: dict | None = None) -> list[int]:
    """The sortie counts the terminal prints: the flight lines ("sorties: 6") and the survey
    design ("Sorties: 10 of up to 30 min") — of the plan flown, not the figures of the other
    plans compared that the choice's sentences name."""
    flat = re.sub(r"\s+", " ", text)
    alts = ((((doc or {}).get("specification") or {}).get("uav") or {}).get("layout")
            or {}).get("alternatives") or []
    for a in alts:
        if a["recommended"] or a.get("n_sorties") is None:
            continue
        for loc in ("en", "ru"):
            said = render("plan_choice.figures", {"photos": a["n_photos"],
                                                  "time": a["flight_time_s"] / 60.0,
                                                  "sorties": a["n_sorties"]}, loc)
            flat = flat.replace(re.sub(r"\s+", " ", said), "")
    words = "|".join(re.escape(w) for w in ("sorties", "вылетов", *_labels("sorties")))
    return [int(n) for n in re.findall(rf"(?:{words}): (\d+)", flat)]


def _xlsx_counts(path: Path) -> list[int]:
    openpyxl = pytest.importorskip("openpyxl")
    heads = set(_labels("sorties_count") + _labels("geo_n_sorties")
                + _labels("sorties"))
    out = []
    wb = openpyxl.load_workbook(path, read_only=True)
    for ws in wb.worksheets:
        for row in ws.iter_rows(values_only=True):
            if row and row[0] in heads and len(row) > 1 and row[1] is not None:
                value = row[1]
                out.append(int(value) if isinstance(value, int | float)
                           else int(re.match(r"\s*(\d+)", str(value)).group(1)))
    return out


def _pdf_counts(path: Path) -> list[int]:
    if shutil.which("pdftotext") is None:
        pytest.skip("pdftotext is not installed")
    text = subprocess.run(["pdftotext", "-layout", str(path), "-"], capture_output=True,
                          text=True, check=True).stdout
    heads = "|".join(re.escape(w) for w in _labels("geo_n_sorties") + _labels("sorties"))
    return [int(n) for n in re.findall(rf"^\s*(?:{heads})\s+(\d+)", text, flags=re.M)]


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_every_document_shows_the_same_sortie_count(tmp_path, example):
    doc = scanplan.plan(str(example)).to_dict()
    counts = _json_counts(doc)
    out = tmp_path / "out"
    res = CliRunner().invoke(main, ["plan", str(example), "--out", str(out)])
    assert res.exit_code == 0, res.output
    found = {"json": sorted(set(counts.values())), "text": _text_counts(res.stdout, doc),
             "xlsx": _xlsx_counts(out / "spec.xlsx"), "pdf": _pdf_counts(out / "spec.pdf")}
    missions = sorted(out.glob("mission*.plan"))
    if missions:
        found["mission files"] = [len(missions)]
    numbers = {n for values in found.values() for n in values}
    assert len(numbers) <= 1, (example.name, counts, found)
    layout = (doc["specification"].get("uav") or {}).get("layout")
    unknown = "sortie_time_unknown" in {w["code"] for w in doc["warnings"]}
    if layout is not None and unknown:  # no sortie time: no document counts sorties
        assert not (found["text"] or found["xlsx"] or found["pdf"]), found
    elif layout is not None and "sorties" in ((doc.get("uav") or {}).get("flight") or {}):
        assert numbers == {layout["n_sorties"]}, (example.name, found)  # every document
        assert found["xlsx"] and found["pdf"], found
    if "survey_design.sun.sorties" in counts and layout is not None:
        assert found["text"], res.stdout  # the design line of the terminal


def test_the_afs_example_counts_its_sorties_once():
    """The example that gives only ``[schedule] sortie_time_min = 30``: its layout is split
    at 30 min and the design counts the same sorties (before: 1 and 10)."""
    doc = scanplan.plan(str(ROOT / "examples" / "uav-town-2000-afs.toml")).to_dict()
    sun = doc["survey_design"]["sun"]
    layout = doc["specification"]["uav"]["layout"]
    assert sun["sortie_time_min"] == 30.0
    assert sun["sorties"] == layout["n_sorties"] == len(layout["sorties"]) > 1
    assert all(s["time_s"] <= 30 * 60 + 1e-6 for s in layout["sorties"])
    assert sum(s["time_s"] for s in layout["sorties"]) == pytest.approx(
        sun["flight_time_min"] * 60, rel=1e-9)


UAV = """[project]
name = "sorties"
[map]
scale = 2000
relief_interval_m = 0.5
[uav]
camera = "dji-zenmuse-p1-35"
speed_ms = 12
exposure_s = 0.0005
[area]
width_m = 1500
length_m = 2000
"""
SCHEDULE = """[site]
lat_deg = 56.3
lon_deg = 37.5
[schedule]
start_date = 2025-06-01
utc_offset_h = 3
"""


def _plan(tmp_path, text):
    path = tmp_path / "p.toml"
    path.write_text(text, encoding="utf-8")
    return plan_project(parse_project(text, path))


def _uav_with(key_lines: str) -> str:
    return UAV.replace("exposure_s = 0.0005\n", "exposure_s = 0.0005\n" + key_lines)


def test_either_key_gives_the_same_sorties(tmp_path):
    by_uav = _plan(tmp_path, _uav_with("max_flight_time_min = 20\n") + SCHEDULE)
    by_schedule = _plan(tmp_path, UAV + SCHEDULE + "sortie_time_min = 20\n")
    both = _plan(tmp_path, _uav_with("max_flight_time_min = 20\n") + SCHEDULE
                 + "sortie_time_min = 20\n")
    n = len(by_uav.uav.layout.sorties)
    assert n > 1
    for r in (by_uav, by_schedule, both):
        assert len(r.uav.layout.sorties) == n == r.design.sun.days.sorties
        assert r.design.sun.sortie_time_s == 20 * 60
        assert r.uav.job.plan.flight["sorties"] == n


def test_the_schedule_default_splits_the_layout_too(tmp_path):
    """No key, a schedule: the platform's default sortie (25 min for a UAV battery) splits
    the layout and counts the days; no schedule: one flight, as before."""
    r = _plan(tmp_path, UAV + SCHEDULE)
    assert r.design.sun.sortie_time_s == 25 * 60
    assert len(r.uav.layout.sorties) == r.design.sun.days.sorties > 1
    assert all(s.time_s <= 25 * 60 + 1e-6 for s in r.uav.layout.sorties)
    assert len(_plan(tmp_path, UAV).uav.layout.sorties) == 1


def test_two_different_sortie_lengths_are_an_error_naming_both_keys(tmp_path):
    text = _uav_with("max_flight_time_min = 25\n") + SCHEDULE + "sortie_time_min = 30\n"
    with pytest.raises(InputError) as err:
        _plan(tmp_path, text)
    msg = str(err.value)
    assert "schedule.sortie_time_min (line" in msg and "uav.max_flight_time_min (line" in msg
    path = tmp_path / "p.toml"
    res = CliRunner().invoke(main, ["plan", str(path)])
    assert res.exit_code == 2
    assert "sortie_time_min" in res.stderr and "max_flight_time_min" in res.stderr
    assert res.stderr.count(str(path)) == 1  # the file named once
    assert "Traceback" not in res.output


@pytest.mark.parametrize("value", ["0", "-5", "2000", '"half an hour"'])
@pytest.mark.parametrize("area", [True, False])
def test_a_sortie_time_out_of_range_names_its_key(tmp_path, value, area):
    text = UAV + SCHEDULE + f"sortie_time_min = {value}\n"
    if not area:
        text = text.replace("[area]\nwidth_m = 1500\nlength_m = 2000\n", "")
    with pytest.raises(InputError, match=r"schedule\.sortie_time_min") as err:
        _plan(tmp_path, text)
    assert str(err.value).count("p.toml") == 1


def test_examples_of_the_sortie_rules_run():
    import doctest

    import scanplan.project.sorties as module

    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert result.attempted and result.failed == 0
