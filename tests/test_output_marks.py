"""scanplan recognises its own workbook however openpyxl serialises the creator property:
``<dc:creator>scanplan …`` (the standard library's XML writer) or ``<dc:creator
xmlns:dc="…">scanplan …`` (lxml installed — pymavlink, a test extra, brings it). A rerun of
``plan --out`` must replace its own workbook without ``--force`` either way."""

from __future__ import annotations

import zipfile

import pytest

from scanplan.io.targets import written_by_scanplan

DC = "http://purl.org/dc/elements/1.1/"
CORE = ('<cp:coreProperties xmlns:cp="http://schemas.openxmlformats.org/package/2006/metadata/'
        'core-properties" xmlns:dc="{dc}">{creator}</cp:coreProperties>')


@pytest.mark.parametrize(("creator", "ours"), [
    ("<dc:creator>scanplan 0.1.0</dc:creator>", True),
    (f'<dc:creator xmlns:dc="{DC}">scanplan 0.1.0</dc:creator>', True),
    (f'<dc:creator xmlns:dc="{DC}">openpyxl</dc:creator>', False),
    ("<dc:creator>scanplanner 2</dc:creator>", False),
    (f'<dc:creatorX xmlns:dc="{DC}">scanplan 1</dc:creatorX>', False),
])
def test_workbook_creator_is_recognised_with_and_without_lxml(tmp_path, creator, ours):
    path = tmp_path / "spec.xlsx"
    with zipfile.ZipFile(path, "w") as zf:
        zf.writestr("docProps/core.xml", CORE.format(dc=DC, creator=creator))
    assert written_by_scanplan(path, "xlsx") is ours
