"""Hostile text in what scanplan writes: CSV cells a spreadsheet would run as formulas.

A project name is the user's text, and it lands in the batch's summary.csv; a spreadsheet
runs a cell that starts with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return
(OWASP, "CSV Injection"). Such text cells start with ``'``; numbers never change.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.io.files import csv_safe

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
FILM = EXAMPLES / "instruction-2000-film.toml"

HOSTILE = ["=cmd|' /C calc'!A0", "@SUM(1+1)*cmd|' /C calc'!A0", "+7+cmd", "-2+3+cmd",
           "\t=1+1", "\r=1+1"]


@pytest.mark.parametrize(("value", "expected"), [
    *[(h, "'" + h) for h in HOSTILE],
    ("-12.5", "-12.5"), ("+3", "+3"), ("-1e-3", "-1e-3"), (" =x", " =x"),
    ("Town plan", "Town plan"), ("", ""), (-5, -5), (2.5, 2.5), (None, None),
])
def test_csv_safe(value, expected):
    assert csv_safe(value) == expected


def test_summary_csv_neutralises_formula_project_names(tmp_path, monkeypatch):
    """Bug: summary.csv carried a project name like ``=cmd|…`` raw at the start of a
    cell. Read back with the csv module, every hostile name starts with ``'``, and the
    numeric columns are the plain numbers of the workbook."""
    import openpyxl

    monkeypatch.chdir(tmp_path)
    text = FILM.read_text(encoding="utf-8")
    names = []
    import scanplan.reports.excel as excel_mod
    import scanplan.reports.pdf as pdf_mod

    monkeypatch.setattr(excel_mod, "render_xlsx", lambda **kw: b"PK workbook")
    monkeypatch.setattr(pdf_mod, "render_pdf", lambda **kw: b"%PDF-1.7 document")
    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    # a carriage return is refused in a project name (a control character): not here
    for i, hostile in enumerate(h for h in HOSTILE if "\r" not in h):
        body = text.replace('name = "', 'name = "' + hostile.replace("\t", "\\t").replace(
            "\r", "\\r").replace('"', '\\"') + " ", 1)
        (tmp_path / f"p{i}.toml").write_text(body, encoding="utf-8")
        names.append(hostile)
    r = CliRunner().invoke(main, ["plan", *sorted(p.name for p in tmp_path.glob("*.toml")),
                                  "--out", "out", "--jobs", "1"])
    assert r.exit_code == 0, r.output
    raw = (tmp_path / "out" / "summary.csv").read_bytes().decode("utf-8-sig")
    rows = list(csv.DictReader(io.StringIO(raw, newline="")))
    assert len(rows) == len(names)
    for row, hostile in zip(rows, names, strict=True):
        assert row["project"].startswith("'" + hostile), row["project"]
        assert float(row["map_scale"]) == 2000  # numbers unchanged
    for line in raw.splitlines()[1:]:
        assert not line.startswith(("=", "+", "-", "@"))
    wb = openpyxl.load_workbook(tmp_path / "out" / "summary.xlsx")
    assert wb.active.cell(2, 1).value.startswith(names[0])  # the workbook keeps the text
    assert os.path.exists(tmp_path / "out" / "p0.xlsx")
