"""Edge cases of what the commands write and say: a dangling ``--out`` link, the paper's
rounding at P > 0.99, ``init --force`` over a protected file, the files a huge block does
not get (and why), and a height no flight can have."""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

import pytest
from click.testing import CliRunner
from layouts import make_layout

import scanplan.reports.exports as exports_mod
from scanplan.cli.main import main

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FILM = EXAMPLES / "instruction-2000-film.toml"
SCAN = ("scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
        "--camera", "rc30-153")


def cli(*args: str):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.mark.parametrize("out", ["dang", "dang/sub/deeper"])
def test_out_naming_a_dangling_link_is_bad_input(tmp_path, monkeypatch, out):
    """Bug: ``--out`` naming a symbolic link to nothing exited 1 ("cannot create folder:
    File exists")."""
    monkeypatch.chdir(tmp_path)
    os.symlink(tmp_path / "missing" / "dir", "dang")
    r = cli("plan", FILM, "--out", out)
    assert r.exit_code == 2, r.output
    assert "error: --out: 'dang'" in r.stderr and "is a symbolic link to" in r.stderr
    assert "which does not exist" in r.stderr and "Traceback" not in r.output
    assert sorted(os.listdir(tmp_path)) == ["dang"]  # nothing created


@pytest.mark.parametrize("p", ["0.995", "0.9901", "0.999"])
def test_paper_rounding_above_its_range_is_refused(p):
    """Bug: --rounding paper with P > 0.99 printed a 0 µm scan pixel, "1:0" and "+inf %":
    the paper truncates −ln P to two decimals, 0 above P = 0.99004."""
    r = cli(*SCAN, "--rounding", "paper", "--probability", p)
    assert r.exit_code == 2, r.output
    assert "--probability" in r.stderr and "P ≤ 0.99004" in r.stderr
    assert "--rounding exact" in r.stderr


def test_paper_rounding_at_its_edge_and_exact_beyond_it_give_numbers():
    for args in (("--rounding", "paper", "--probability", "0.99"),
                 ("--rounding", "exact", "--probability", "0.995")):
        r = cli(*SCAN, *args)
        assert r.exit_code == 0, r.output
        assert "1:0 " not in r.stdout and "inf" not in r.stdout, r.stdout
        pd = next(line for line in r.stdout.splitlines() if line.startswith("PD "))
        assert float(pd.split()[-1].rstrip("*")) > 0


def test_init_force_never_replaces_a_write_protected_file(tmp_path):
    """Bug: ``init --force`` replaced a write-protected file (reports refuse to)."""
    p = tmp_path / "x.toml"
    p.write_text("mine\n", encoding="utf-8")
    p.chmod(0o444)
    r = cli("init", p, "--map-scale", "2000", "--relief", "1", "--force")
    assert r.exit_code == 2 and "write-protected" in r.stderr, r.output
    assert p.read_text(encoding="utf-8") == "mine\n"
    assert stat.S_IMODE(p.stat().st_mode) == 0o444
    link = tmp_path / "link.toml"
    link.symlink_to(p)
    r = cli("init", link, "--map-scale", "2000", "--relief", "1", "--force")
    assert r.exit_code == 2 and "symbolic link" in r.stderr
    assert set(os.listdir(tmp_path)) == {"x.toml", "link.toml"}  # no temporary left


@pytest.fixture()
def town(tmp_path, monkeypatch):
    text = (EXAMPLES / "uav-town-2000.toml").read_text(encoding="utf-8")
    (tmp_path / "proj.toml").write_text(
        text.replace('file = "areas/', f'file = "{EXAMPLES}/areas/'), encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    import scanplan.reports.excel as excel_mod
    import scanplan.reports.pdf as pdf_mod

    monkeypatch.setattr(excel_mod, "render_xlsx", lambda **kw: b"PK workbook")
    monkeypatch.setattr(pdf_mod, "render_pdf", lambda **kw: b"%PDF-1.7 document")
    return tmp_path


def test_a_block_too_big_to_fly_or_list_says_which_files_it_lacks(town, monkeypatch):
    """Bug: a 9,999 km² block wrote no mission and no photos.csv without saying why."""
    import dataclasses

    from scanplan.i18n.messages import Message

    base = make_layout()
    huge = dataclasses.replace(
        base, feasible=False, photos=type(base.photos)({}),
        reason=Message("layout.too_many_sorties", most=1000, limit=25.0),
        notes={**base.notes, "photos": 12_935_836})
    monkeypatch.setattr(exports_mod, "spec_layouts", lambda spec: [("uav", huge)])
    r = cli("plan", "proj.toml", "--out", "out", "--force")
    assert r.exit_code == 0, r.output
    assert sorted(n for n in os.listdir(town / "out") if not n.startswith(".")) == [
        "flight.geojson", "flight.gpkg", "flight.kml", "spec.pdf", "spec.xlsx"]
    assert ("note: no mission file written: the flight plan over the area is not feasible "
            "(more than 1,000 sorties of 25 min") in r.stderr
    assert ("note: no photos.csv written: the 12,935,836 photo centres are more than the "
            "2,000,000 scanplan lists") in r.stderr
    feasible_unlisted = dataclasses.replace(huge, feasible=True, reason=None)
    monkeypatch.setattr(exports_mod, "spec_layouts",
                        lambda spec: [("uav", feasible_unlisted)])
    r = cli("plan", "proj.toml", "--out", "out", "--force")
    assert "no mission file written: the 12,935,836 photo centres are more than" in r.stderr


def test_a_height_no_flight_can_have_is_not_feasible_not_0_m(tmp_path):
    """Bug: "planned height 100 m is above the maximum planned height 0 m"."""
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project

    text = (EXAMPLES / "uav-canon-2000.toml").read_text(encoding="utf-8")
    text = text.replace('camera = "canon-eos-5d-mark-ii-50"',
                        'pixel_um = 100\nfocal_mm = 1\nsensor_mm = "36x24"').replace(
        "max_height_m = 500", "max_height_m = 500\ngsd_cm = 0.01")
    (tmp_path / "p.toml").write_text(text, encoding="utf-8")
    result = plan_project(load_project(tmp_path / "p.toml"))
    texts = [w.text("en") for w in result.warnings if w.code == "height_above_max"]
    assert texts and not any(re.search(r"(?<![\d.,])0 m", t) for t in texts)
    assert "no flight height is feasible" in texts[0]
    assert "ни на какой высоте" in next(w.text("ru") for w in result.warnings
                                        if w.code == "height_above_max")
