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


def test_a_wrong_answer_is_said_and_asked_again(tmp_path, monkeypatch):
    """Bug: answering 0 to "Map scale" ended the whole interview with an error naming
    --map-scale (an option never typed), and a film camera id that was not one was found
    wrong only after every question. Each answer is checked as it is read: the reason is
    said and the question asked again."""
    monkeypatch.setattr(cli_init, "_interactive", lambda: True)
    p = tmp_path / "asked.toml"
    # kind; map scale 0, then 2000; relief -1, then 1; name; locale; film camera: an
    # unknown id, a digital camera, then a film one
    r = _cli("init", str(p), input="film\n0\n2000\n-1\n1\n\nen\nnope\n"
             "dji-zenmuse-p1-35\nrc30-153\nn\n\n")
    assert r.exit_code == 0, r.output
    said = r.output
    assert said.count("Map scale") == 2 and said.count("Relief") == 2, said
    assert said.count("Film camera id") == 3 and "is a digital camera" in said, said
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["map"]["scale"] == 2000 and doc["map"]["relief_interval_m"] == 1
    assert doc["film"]["camera"] == "rc30-153"


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
    assert r.exit_code == 2 and "error: --map-scale" in r.output and not p.exists()
    assert "1:500, 1:1000" in r.output and "size of the object to interpret" in r.output
    r = _cli("init", str(p), "--kind", "film", "--map-scale", "100000", "--relief", "20",
             "--object-size-m", "10", "--object-name", "bridges")
    assert r.exit_code == 0, r.output
    doc = tomllib.loads(p.read_text(encoding="utf-8"))
    assert doc["norms"]["object_name"] == "bridges" and doc["norms"]["object_size_m"] == 10
    assert _cli("plan", str(p)).exit_code == 0


def _catalogue():
    from scanplan.norms import load_norm_set

    return load_norm_set().cameras


@pytest.mark.parametrize("locale", ["en", "ru"])
def test_every_catalogue_camera_gives_a_file_that_plans(tmp_path, locale):
    """init plans the file before writing it, so exit 0 means `plan` runs it as written:
    every digital camera (its f-number given where the catalogue has none, the ground speed
    for a manned aircraft) and every film camera, in both languages of the comments."""
    for i, (cid, cam) in enumerate(sorted(_catalogue().items())):
        p = tmp_path / f"c{i}.toml"
        if cam.kind == "film":
            args = ["--kind", "film", "--film-camera", cid]
        else:
            args = ["--kind", "uav", "--uav-camera", cid]
            if cam.f_number is None:
                args += ["--f-number", "5.6"]
            if cam.carrier == "aircraft":
                args += ["--speed-ms", "70"]
        r = _cli("init", str(p), "--map-scale", "2000", "--relief", "0.5", "--locale", locale,
                 *args)
        assert r.exit_code == 0, (cid, r.output)
        assert tomllib.loads(p.read_text(encoding="utf-8"))["project"]["locale"] == locale


def test_a_camera_without_an_f_number_names_the_option_not_a_line(tmp_path):
    cid = next(c for c, cam in sorted(_catalogue().items())
               if cam.kind != "film" and cam.f_number is None and cam.carrier == "uav")
    p = tmp_path / "x.toml"
    r = _cli("init", str(p), "--kind", "uav", "--map-scale", "2000", "--relief", "0.5",
             "--uav-camera", cid)
    assert r.exit_code == 2 and "error: --f-number" in r.output and not p.exists()
    assert "line" not in r.output and "x.toml" not in r.output
    aircraft = next(c for c, cam in sorted(_catalogue().items()) if cam.carrier == "aircraft")
    r = _cli("init", str(p), "--kind", "uav", "--map-scale", "5000", "--relief", "1",
             "--uav-camera", aircraft, "--f-number", "5.6")
    assert r.exit_code == 2 and "error: --speed-ms" in r.output and not p.exists()


def test_prompts_for_the_f_number_at_a_terminal(tmp_path, monkeypatch):
    monkeypatch.setattr(cli_init, "_interactive", lambda: True)
    cid = next(c for c, cam in sorted(_catalogue().items())
               if cam.kind != "film" and cam.f_number is None and cam.carrier == "uav")
    p = tmp_path / "asked.toml"
    # kind, map scale, relief, name, locale, UAV camera, f-number
    r = _cli("init", str(p), input=f"uav\n2000\n0.5\n\nen\n{cid}\n4\n")
    assert r.exit_code == 0, r.output
    assert tomllib.loads(p.read_text(encoding="utf-8"))["uav"]["f_number"] == 4


def test_russian_comments_and_the_signing_keys(tmp_path):
    p = tmp_path / "ru.toml"
    r = _cli("init", str(p), "--kind", "uav", "--map-scale", "500", "--relief", "0.5",
             "--locale", "ru", "--organisation", "ООО «Аэросъёмка»", "--contract-number",
             "17/2027", "--compiled-by", "Иванов И. И.", "--checked-by", "Петров П. П.")
    assert r.exit_code == 0, r.output
    text = p.read_text(encoding="utf-8")
    doc = tomllib.loads(text)
    assert doc["project"]["name"] == "Топографический план 1:500"
    assert {k: doc["project"][k] for k in ("organisation", "contract_number", "compiled_by",
                                           "checked_by")} == {
        "organisation": "ООО «Аэросъёмка»", "contract_number": "17/2027",
        "compiled_by": "Иванов И. И.", "checked_by": "Петров П. П."}
    assert "# высота сечения рельефа h_c [м]" in text and "relief (contour)" not in text
    for commented in ("# [terrain]", "# [site]", "# [schedule]", "# approver_position"):
        assert commented in text
    en = tmp_path / "en.toml"
    assert _cli("init", str(en), "--kind", "uav", "--map-scale", "500", "--relief",
                "0.5").exit_code == 0
    assert "# organisation = \"\"" in en.read_text(encoding="utf-8")
