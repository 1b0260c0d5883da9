"""``scanplan init``: a commented project file that ``scanplan plan`` runs as it is."""

from __future__ import annotations

import os
import tomllib

import pytest
from click.testing import CliRunner

from scanplan.cli import init as cli_init
from scanplan.cli.main import main


def _cli(*args: str, input: str | None = None):
    return CliRunner().invoke(main, list(args), input=input, prog_name="scanplan")


@pytest.mark.parametrize("kind, sections", [
    ("film", {"film"}), ("uav", {"uav"}), ("both", {"film", "uav"})])
def test_written_file_plans(tmp_path, kind, sections):
    p = tmp_path / f"{kind}.toml"
    r = _cli("init", str(p), "--kind", kind, "--map-scale", "1:1000", "--relief", "0.5",
             "--area-m", "1000x1500")
    assert r.exit_code == 0, r.output
    text = p.read_text(encoding="utf-8")
    doc = tomllib.loads(text)
    assert sections <= set(doc) and not ({"film", "uav"} - sections) & set(doc)
    assert doc["map"] == {"scale": 1000, "relief_interval_m": 0.5}
    assert text.count("#") > 20  # commented: every key explained
    plan = _cli("plan", str(p), "--json")
    assert plan.exit_code == 0, plan.output
    assert '"specification"' in plan.output


def test_archive_and_russian(tmp_path):
    p = tmp_path / "a.toml"
    r = _cli("init", str(p), "--kind", "film", "--map-scale", "2000", "--relief", "1",
             "--photo-scale", "1:12000", "--locale", "ru", "--name", 'План "Лида" #1',
             "--scanner", "photoscan-td")
    assert r.exit_code == 0, r.output
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["film"]["photo_scale"] == 12000 and "photo_scales" not in doc["film"]
    assert doc["project"] == {"name": 'План "Лида" #1', "customer": "", "contractor": "",
                              "locale": "ru"}
    out = _cli("plan", str(p))
    assert out.exit_code == 0 and "1:12\u00a0000" in out.output  # the Russian summary


def test_never_overwrites_without_force(tmp_path):
    p = tmp_path / "x.toml"
    p.write_text("mine\n", encoding="utf-8")
    r = _cli("init", str(p), "--map-scale", "2000", "--relief", "1")
    assert r.exit_code == 2 and "exists; give --force" in r.output
    assert p.read_text(encoding="utf-8") == "mine\n"
    r = _cli("init", str(p), "--map-scale", "2000", "--relief", "1", "--force")
    assert r.exit_code == 0
    assert "[map]" in p.read_text(encoding="utf-8")
    assert [f for f in os.listdir(tmp_path) if f != "x.toml"] == []  # no temporary left


def test_bad_answers_write_nothing_and_name_the_option(tmp_path):
    p = tmp_path / "x.toml"
    cases = [
        (["--map-scale", "2000", "--relief", "1", "--film-camera", "rc30"], "--film-camera",
         "did you mean rc30-153?"),
        (["--map-scale", "50", "--relief", "1"], "--map-scale", "≥ 100"),
        (["--map-scale", "2000", "--relief", "-1"], "--relief", "relief"),
        (["--map-scale", "2000"], "--relief", "is required"),
        (["--relief", "1"], "--map-scale", "is required"),
        (["--map-scale", "2000", "--relief", "1", "--photo-scale", "9000",
          "--photo-scales", "8000"], "--photo-scale", "not both"),
    ]
    for args, option, text in cases:
        r = _cli("init", str(p), *args)
        assert r.exit_code == 2, (args, r.output)
        assert f"error: {option}" in r.output and text in r.output, (args, r.output)
        assert not p.exists()


def test_missing_folder(tmp_path):
    r = _cli("init", str(tmp_path / "no" / "x.toml"), "--map-scale", "2000", "--relief", "1")
    assert r.exit_code == 2 and "does not exist" in r.output


def test_prompts_at_a_terminal(tmp_path, monkeypatch):
    monkeypatch.setattr(cli_init, "_interactive", lambda: True)
    p = tmp_path / "asked.toml"
    # kind, map scale, relief, name, locale, UAV camera
    r = _cli("init", str(p), input="uav\n1:500\n0.5\nTown plan\nen\n\n")
    assert r.exit_code == 0, r.output
    assert "Map scale" in r.output and "Relief" in r.output
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["map"]["scale"] == 500 and doc["uav"]["camera"] == "dji-zenmuse-p1-35"
    assert doc["project"]["name"] == "Town plan"
    assert _cli("plan", str(p)).exit_code == 0


def test_no_overwrite_race(tmp_path, monkeypatch):
    """A file that appears between the check and the write is not replaced."""
    p = tmp_path / "x.toml"
    real = os.link

    def racing_link(src, dst, *a, **kw):
        with open(dst, "w", encoding="utf-8") as fh:
            fh.write("theirs\n")
        return real(src, dst, *a, **kw)

    monkeypatch.setattr(os, "link", racing_link)
    r = _cli("init", str(p), "--map-scale", "2000", "--relief", "1")
    assert r.exit_code == 2 and "exists" in r.output
    assert p.read_text(encoding="utf-8") == "theirs\n"
    assert os.listdir(tmp_path) == ["x.toml"]


def test_prompts_for_archive_photos(tmp_path, monkeypatch):
    monkeypatch.setattr(cli_init, "_interactive", lambda: True)
    p = tmp_path / "archive.toml"
    # kind, map scale, relief, name, locale, film camera, archive?, its scale
    r = _cli("init", str(p), input="film\n2000\n1\n\nru\n\ny\n1:12000\n")
    assert r.exit_code == 0, r.output
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["film"]["photo_scale"] == 12000 and doc["project"]["locale"] == "ru"
    assert _cli("plan", str(p)).exit_code == 0
    p2 = tmp_path / "candidates.toml"
    r = _cli("init", str(p2), input="film\n1000\n0.5\n\nen\n\nn\n\n")
    assert r.exit_code == 0, r.output
    assert tomllib.loads(p2.read_text(encoding="utf-8"))["film"]["photo_scales"] == [
        3000, 4000, 5000, 6000]


def test_own_object_for_a_scale_without_a_norm_object(tmp_path):
    """1:100000 has no norm object: init says which option gives one, and with it plans."""
    p = tmp_path / "small.toml"
    r = _cli("init", str(p), "--kind", "film", "--map-scale", "100000", "--relief", "20")
    assert r.exit_code == 2 and "error: --object-size-m" in r.output and not p.exists()
    r = _cli("init", str(p), "--kind", "film", "--map-scale", "100000", "--relief", "20",
             "--object-size-m", "10", "--object-name", "bridges")
    assert r.exit_code == 0, r.output
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["norms"]["object_name"] == "bridges" and doc["norms"]["object_size_m"] == 10
    assert _cli("plan", str(p)).exit_code == 0
