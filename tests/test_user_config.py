"""The user's configuration file: defaults for [project], overridden by each project."""

from __future__ import annotations

import json

import platformdirs
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.project.userconfig import config_path

PROJECT = ('[map]\nscale = 2000\nrelief_interval_m = 0.5\n[uav]\n'
           'camera = "dji-zenmuse-p1-35"\nheight_m = 100\n')


def _meta(tmp_path, project_extra: str = "") -> dict:
    p = tmp_path / "p.toml"
    p.write_text(project_extra + PROJECT, encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(p), "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)["project"]


def test_configuration_gives_defaults_a_project_overrides(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    cfg.write_text('[project]\norganisation = "ООО «Аэрогеодезия»"\ncompiled_by = '
                   '"Иванов И. И."\nlocale = "ru"\n', encoding="utf-8")
    monkeypatch.setenv("SCANPLAN_CONFIG", str(cfg))
    meta = _meta(tmp_path)
    assert meta["organisation"] == "ООО «Аэрогеодезия»"
    assert meta["compiled_by"] == "Иванов И. И." and meta["locale"] == "ru"
    own = _meta(tmp_path, '[project]\norganisation = "АО «Другая»"\nlocale = "en"\n')
    assert own["organisation"] == "АО «Другая»" and own["locale"] == "en"
    assert own["compiled_by"] == "Иванов И. И."
    monkeypatch.setenv("SCANPLAN_CONFIG", str(tmp_path / "none.toml"))  # no file: no defaults
    assert _meta(tmp_path)["organisation"] == ""


def test_bad_configuration_names_file_key_and_line(tmp_path, monkeypatch):
    cfg = tmp_path / "config.toml"
    monkeypatch.setenv("SCANPLAN_CONFIG", str(cfg))
    p = tmp_path / "p.toml"
    p.write_text(PROJECT, encoding="utf-8")
    for text, words in (('[project]\n\norganisation = 5\n', ["project.organisation (line 3)",
                                                              "must be text"]),
                        ('[project]\nlocale = "de"\n', ["project.locale (line 2)", '"ru"']),
                        ('[project]\nboss = "x"\n', ["project.boss", "unknown key"]),
                        ('[project]\norganisaton = "x"\n',
                         ["project.organisaton (line 2)", "did you mean organisation?"]),
                        ('[project\norganisation = "x"\n', ["is not valid TOML", "line 1"]),
                        (b"[project]\norganisation = \"\xff\"\n".decode("latin-1"),
                         ["is not UTF-8 text"]),
                        ('[uav]\nheight_m = 5\n', ["[uav]", "one table"])):
        cfg.write_bytes(text.encode("latin-1" if "UTF-8" in words[0] else "utf-8"))
        r = CliRunner().invoke(main, ["plan", str(p)])
        assert r.exit_code == 2, r.output
        assert str(cfg) in r.output and all(w in r.output for w in words), r.output


def test_configuration_is_found_in_the_platforms_config_folder(tmp_path, monkeypatch):
    monkeypatch.delenv("SCANPLAN_CONFIG", raising=False)
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "cfg"))
    assert config_path() == platformdirs.user_config_path("scanplan", appauthor=False) / \
        "config.toml"
    assert config_path() == tmp_path / "cfg" / "scanplan" / "config.toml"
    config_path().parent.mkdir(parents=True)
    config_path().write_text('[project]\ncontractor = "ООО «Съёмка»"\n', encoding="utf-8")
    assert _meta(tmp_path)["contractor"] == "ООО «Съёмка»"
