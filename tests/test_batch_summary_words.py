"""A batch summary (summary.csv, summary.xlsx) says its warnings in words, in the
project's language; the warning codes are a column of their own for programs."""

from __future__ import annotations

import io
from pathlib import Path

import pandas as pd
from click.testing import CliRunner

from scanplan.api import SUMMARY_COLUMNS, summary_row
from scanplan.cli.main import main
from scanplan.i18n.messages import MESSAGES
from scanplan.project.file import load_project
from scanplan.project.spec import plan_project

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_summary_warnings_are_sentences_and_codes_are_a_column_of_their_own():
    result = plan_project(load_project(EXAMPLES / "archive-12000-for-2000.toml"))
    row = summary_row(result)
    codes = row["warning_codes"].split()
    assert codes and all(c in MESSAGES for c in codes)
    for code in codes:
        assert code not in row["warnings"]
    assert row["warnings"].startswith("On the 1:12000 photos")
    assert row["warnings"].endswith(".")
    assert list(SUMMARY_COLUMNS)[-2:] == ["warnings", "warning_codes"]


def test_a_russian_project_summary_speaks_russian(tmp_path):
    path = tmp_path / "ru.toml"
    path.write_text('[project]\nlocale = "ru"\n[map]\nscale = 2000\nrelief_interval_m = 1\n'
                    '[uav]\ncamera = "dji-zenmuse-p1-35"\nheight_m = 200\n', encoding="utf-8")
    row = summary_row(plan_project(load_project(path)))
    assert row["warning_codes"]
    assert any("а" <= ch <= "я" for ch in row["warnings"])
    assert "_" not in row["warnings"].replace("[uav] max_height_m", "")


def test_summary_csv_holds_words_and_codes(tmp_path):
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["plan", str(EXAMPLES / "archive-12000-for-2000.toml"),
                                       str(EXAMPLES / "film-1000.toml"), "--out", str(out),
                                       "--formats", "xlsx"])  # the summary is always written
    assert result.exit_code == 0, result.output
    frame = pd.read_csv(io.BytesIO((out / "summary.csv").read_bytes()), encoding="utf-8-sig")
    row = frame[frame["file"].str.endswith("archive-12000-for-2000.toml")].iloc[0]
    assert "archive_not_interpretable" in row["warning_codes"]
    assert "archive_not_interpretable" not in row["warnings"]
    assert "cannot be interpreted" in row["warnings"]
