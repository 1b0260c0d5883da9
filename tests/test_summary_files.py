"""The batch summary files show measured values as the specification prints them."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import openpyxl

import scanplan
from scanplan.reports.summary import DIGITS, summary_csv, summary_xlsx

ROOT = Path(__file__).resolve().parent.parent


def _frame():
    return scanplan.batch([ROOT / "examples" / "uav-canon-2000.toml",
                           ROOT / "examples" / "instruction-2000-film.toml"]).to_frame()


def test_summary_csv_and_workbook_round_the_measured_columns():
    frame = _frame()
    raw = frame["uav_max_planned_height_m"].dropna().iloc[0]
    assert round(raw, 1) != raw  # the planned maximum is not a round number: a real check
    rows = list(csv.DictReader(io.StringIO(summary_csv(frame).decode("utf-8-sig"))))
    for row in rows:
        for col, digits in DIGITS.items():
            if row[col]:
                decimals = row[col].partition(".")[2]
                assert len(decimals) <= digits, (col, row[col])
    uav = next(r for r in rows if r["uav_max_planned_height_m"])
    assert float(uav["uav_max_planned_height_m"]) == round(raw, 1)
    ws = openpyxl.load_workbook(io.BytesIO(summary_xlsx(frame))).active
    head = [c.value for c in ws[1]]
    col = head.index("uav_max_planned_height_m") + 1
    values = [ws.cell(row=r, column=col).value for r in range(2, ws.max_row + 1)]
    assert round(raw, 1) in values
