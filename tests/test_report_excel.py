"""The Excel report: sheets, values read from the plans, highlighting, page setup, charts,
text that stays text, reproducible bytes and atomic writing."""

from __future__ import annotations

import dataclasses
import io
import re
import zipfile
from pathlib import Path

import openpyxl
import pytest

from scanplan.project.jobs import scan_job, uav_job
from scanplan.reports import ReportMeta
from scanplan.reports import excel as X
from scanplan.reports.excel import render_xlsx

INJECTION = '=HYPERLINK("http://x","y")'
EN_SHEETS = ["Summary", "Inputs", "Constraints", "Sweep", "UAV", "MTF", "Norms", "Warnings",
             "References"]
RU_SHEETS = ["Сводка", "Исходные данные", "Условия", "Ряд масштабов", "БПЛА", "ФПМ",
             "Нормативы", "Предупреждения", "Список литературы"]


@pytest.fixture(scope="module")
def scan():
    """Seed 001's Table 8 setting."""
    return scan_job(map_scale=2000, relief_interval_m=0.5,
                    photo_scales=[5000, 10000, 15000, 20000], camera="rc30-153",
                    scanner="photoscan-td")


@pytest.fixture(scope="module")
def uav():
    """Seed 002's flight."""
    # the Instruction's height form and a raised ceiling: interpretation (PD) binds
    return uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                   height_tolerance_pct=40, speed_ms=25, map_scale=2000, max_height_m=1000,
                   height_formula="instruction", relief_interval_m=0.5, area_m="2000x3000")


def load(data: bytes) -> openpyxl.Workbook:
    return openpyxl.load_workbook(io.BytesIO(data))


@pytest.fixture(scope="module")
def both_en_bytes(scan, uav):
    meta = ReportMeta(project=INJECTION, customer="+cmd|' /C calc'!A0", contractor="@SUM(1)",
                      approver_position="Chief engineer", approver_name="I. I. Ivanov",
                      date="2024-05-01")
    return render_xlsx(scan=scan, uav=uav, meta=meta)


@pytest.fixture(scope="module")
def both_en(both_en_bytes):
    return load(both_en_bytes)


@pytest.fixture(scope="module")
def both_ru(scan, uav):
    return load(render_xlsx(scan=scan, uav=uav, meta=ReportMeta(locale="ru")))


def find_row(ws, **cols):
    """First row whose cells (column letter → value) all match."""
    for row in range(1, ws.max_row + 1):
        if all(ws[f"{c}{row}"].value == v for c, v in cols.items()):
            return row
    raise AssertionError(f"no row with {cols} in {ws.title}")


def exact(x):
    """Equal as stored: openpyxl writes 16 significant digits (Excel shows 15)."""
    return pytest.approx(x, rel=1e-15, abs=0)


def is_marked(cell) -> bool:
    return bool(cell.font.bold) and cell.fill.fgColor.rgb == X._BINDING_FILL.fgColor.rgb


# --- sheets ---------------------------------------------------------------------------


def test_sheet_names_in_both_locales(both_en, both_ru):
    assert both_en.sheetnames == EN_SHEETS
    assert both_ru.sheetnames == RU_SHEETS


def test_only_sheets_with_content(scan, uav):
    assert load(render_xlsx(scan=scan)).sheetnames == [
        "Summary", "Inputs", "Constraints", "Sweep", "Norms", "Warnings", "References"]
    assert load(render_xlsx(uav=uav, meta=ReportMeta(locale="ru"))).sheetnames == [
        "Сводка", "Исходные данные", "БПЛА", "ФПМ", "Нормативы", "Предупреждения",
        "Список литературы"]


def test_nothing_to_report_is_an_error():
    with pytest.raises(ValueError):
        render_xlsx()


# --- values -----------------------------------------------------------------------------


def test_table8_pz_at_10000_in_constraints_with_binding_highlight(both_en, scan):
    ws = both_en["Constraints"]
    assert "µm" in ws["E1"].value and "µm" in ws["F1"].value and "%" in ws["G1"].value
    row = find_row(ws, A=10000, C="PZ")
    assert ws[f"A{row}"].data_type == "n" and ws[f"A{row}"].number_format == '"1:"0'
    assert ws[f"E{row}"].value == pytest.approx(8.315, abs=5e-4)
    assert ws[f"E{row}"].value == exact(scan.plan.scenarios[1].constraint("PZ").pixel_um)
    assert is_marked(ws[f"E{row}"])
    other = find_row(ws, A=10000, C="PD")
    assert not is_marked(ws[f"E{other}"])
    # at 1:5000 the binding one is PR
    assert is_marked(ws[f"E{find_row(ws, A=5000, C='PR')}"])
    assert not is_marked(ws[f"E{find_row(ws, A=5000, C='PZ')}"])
    n = sum(len(s.constraints) for s in scan.plan.scenarios)
    assert ws.max_row == n + 1


def test_units_in_russian_headers(both_ru):
    assert "мкм" in both_ru["Условия"]["E1"].value
    assert all("мкм" in c.value for c in both_ru["Ряд масштабов"][1][1:7])


def test_summary_headline_is_read_from_the_plan(both_en, scan, uav):
    ws = both_en["Summary"]
    row = find_row(ws, A=10000)
    s = scan.plan.scenarios[1]
    assert ws[f"C{row}"].value.startswith("PZ")
    assert ws[f"D{row}"].value == exact(s.scan_pixel_um) and is_marked(ws[f"D{row}"])
    assert ws[f"E{row}"].value == exact(s.scanner_pixel_um)
    assert ws[f"F{row}"].value == exact(s.frame_megabytes)
    assert ws[f"J{row}"].value == s.explanation
    row15 = find_row(ws, A=15000)
    assert ws[f"E{row15}"].value == "—"  # no scanner step is fine enough
    labels = {ws[f"A{r}"].value: ws[f"B{r}"].value for r in range(1, ws.max_row + 1)}
    assert labels["GSD, m"] == exact(uav.plan.gsd_m)
    assert labels["Ground resolution L, m"] == exact(uav.plan.ground_resolution_m)
    assert labels["L/GSD"] == exact(uav.plan.ground_resolution_to_gsd)
    assert labels["Maximum planned flight height, m"] == exact(uav.plan.max_height_m)
    assert labels["Binding constraint"].startswith("PD")
    assert labels["APPROVED"] is None and labels["Position"] == "Chief engineer"
    assert (ws["A6"].value, ws["B6"].value) == ("Date", "2024-05-01")


def test_uav_sheet_height_limits_and_recognition(both_en, uav):
    ws = both_en["UAV"]
    row = find_row(ws, A="PD")
    assert ws[f"E{row}"].value == exact(uav.plan.max_height_m) and is_marked(ws[f"E{row}"])
    assert not is_marked(ws[f"E{find_row(ws, A='PS')}"])
    rec = find_row(ws, A="poles, hydrants")
    assert ws[f"E{rec}"].value == exact(uav.plan.recognition[0].probability)
    assert ws[f"D{rec}"].value == 2000 and ws[f"D{rec}"].number_format == '"1:"0'


def test_uav_limits_are_listed_lowest_first_as_on_the_pdf(both_en, uav):
    """The workbook lays out the same constraints table as the PDF and the terminal
    (lowest maximum height first); it listed them in the rules' order, so the two
    documents of one plan read in different orders."""
    ws = both_en["UAV"]
    head = find_row(ws, A="ID")
    ids, heights = [], []
    row = head + 1
    while ws[f"A{row}"].value:
        ids.append(ws[f"A{row}"].value)
        heights.append(ws[f"E{row}"].value)
        row += 1
    by_height = sorted(uav.plan.limits, key=lambda lim: lim.max_height_m)
    assert ids == [lim.id for lim in by_height] and len(ids) >= 3
    assert heights == sorted(heights) and heights == exact([lim.max_height_m for lim in by_height])
    assert ids != [lim.id for lim in uav.plan.limits]  # the rules' order differs here


def test_mtf_sheet_has_every_component_contrast_threshold_and_r(both_en, uav):
    ws = both_en["MTF"]
    mc = uav.plan.mtf_centre
    heads = [c.value for c in ws[1]]
    assert heads[0] == "Spatial frequency, lines/mm"
    n_curves = len(mc) - 1
    assert len([h for h in heads[1:] if h]) == n_curves + 2  # + the R marker's two columns
    assert "Image contrast K(N)" in heads and "Threshold contrast" in heads
    col = heads.index("Image contrast K(N)") + 1
    column = [ws.cell(r, col).value for r in range(2, len(mc["freq_lpmm"]) + 2)]
    assert column == exact(mc["image_contrast"])
    rcol = heads.index("Resolving power R") + 1
    assert ws.cell(2, rcol).value == ws.cell(3, rcol).value == exact(uav.plan.resolving_power_lpmm)


def test_sweep_sheet_and_norms_used_rows(both_en, scan):
    ws = both_en["Sweep"]
    sweep = scan.plan.sweep
    n = len(sweep["photo_scale"])
    # the sweep, then (below a blank row) the candidate photo scales the chart labels
    assert ws.cell(n + 2, 1).value is None
    assert [ws.cell(n + 4 + i, 1).value for i in range(len(scan.plan.scenarios))] == [
        s.photo_scale for s in scan.plan.scenarios]
    assert ws["B2"].value == exact(sweep["PS"][0])
    assert ws["G2"].value == exact(sweep["scan_pixel_um"][0])
    assert is_marked(ws.cell(2, 2 + scan.plan.rules.constraints.index(sweep["binding"][0])))
    norms = both_en["Norms"]
    row = find_row(norms, A=2000, B="poles, hydrants")
    assert is_marked(norms[f"A{row}"])
    assert not is_marked(norms[f"A{find_row(norms, A=1000, B='poles, hydrants')}"])
    assert not is_marked(norms[f"A{find_row(norms, B='communal wells')}"])


def test_numbers_are_numbers(both_en, both_ru):
    number = re.compile(r"^\s*[-+]?\d+([.,]\d+)?\s*$")
    for wb in (both_en, both_ru):
        for ws in wb:
            for row in ws.iter_rows():
                for cell in row:
                    if isinstance(cell.value, str):
                        assert not number.match(cell.value), (ws.title, cell.coordinate)
                    if isinstance(cell.value, float):
                        assert cell.number_format != "General", (ws.title, cell.coordinate)


def test_warnings_sheet(both_en, scan, uav):
    ws = both_en["Warnings"]
    headings = [ws.cell(r, 3).value for r in range(2, ws.max_row + 1)]
    # each warning by its heading, never by its code (issue 13)
    assert headings == [X.t(f"warn_{w.code}", "en")
                        for w in scan.plan.warnings + uav.plan.warnings]
    quiet = dataclasses.replace(scan, plan=dataclasses.replace(scan.plan, warnings=()))
    ws = load(render_xlsx(scan=quiet))["Warnings"]
    assert ws["A2"].value == "No warnings."


# --- layout -----------------------------------------------------------------------------


def test_charts_present(both_en, both_en_bytes, scan):
    assert len(both_en["Sweep"]._charts) == 1
    assert len(both_en["MTF"]._charts) == 1
    assert len(both_en["UAV"]._charts) == 1  # GSD and L against height
    with zipfile.ZipFile(io.BytesIO(both_en_bytes)) as z:
        names = z.namelist()
        charts = [n for n in names if n.startswith("xl/charts/chart")]
        assert len(charts) == 3
        sweep_xml = z.read(charts[0]).decode()
    # one series per constraint, the scan pixel, one labelled point per candidate photo
    # scale (issue 13: every candidate scale named on the chart); log pixel axis with the
    # photo-scale ticks on the candidates
    assert sweep_xml.count("<ser>") == 6 + len(scan.plan.scenarios) and "logBase" in sweep_xml
    assert sweep_xml.count("<showSerName val=\"1\"") == len(scan.plan.scenarios)
    assert "<majorUnit" in sweep_xml
    # charts start a printed page (never split), below their data
    for name in ("Sweep", "UAV", "MTF"):
        ws = both_en[name]
        anchor_row = ws._charts[0].anchor._from.row + 1
        assert anchor_row - 1 in [b.id for b in ws.row_breaks.brk], name


def test_page_setup_frozen_headers_print_titles(both_en):
    for ws in both_en:
        assert ws.freeze_panes == "A2", ws.title
        assert int(ws.page_setup.paperSize) == int(ws.PAPERSIZE_A4) == 9
        assert ws.page_setup.orientation in ("portrait", "landscape")
        assert ws.page_setup.fitToWidth == 1 and ws.sheet_properties.pageSetUpPr.fitToPage
        assert ws.print_title_rows == "$1:$1"
        assert all((ws.column_dimensions[c].width or 0) >= 8 for c in "ABC")
    assert both_en["Constraints"].page_setup.orientation == "landscape"


# --- text stays text ----------------------------------------------------------------------



def _write(path, kind, **jobs):
    """One document written through the one document path (as ``--xlsx``/``--pdf`` with
    ``--force``): the target checked, rendered to memory, written atomically."""
    from scanplan.reports.documents import Target, write_documents

    write_documents([Target(str(path), kind, "--" + kind)], force=True, **jobs)
    return Path(path)


def test_user_text_is_never_a_formula(both_en, tmp_path, scan):
    ws = both_en["Summary"]
    for coord, text in (("B3", INJECTION), ("B4", "+cmd|' /C calc'!A0"), ("B5", "@SUM(1)")):
        assert ws[coord].data_type == "s" and ws[coord].value == text
        assert ws[coord].quotePrefix  # Excel keeps it text when the cell is edited
    path = _write(tmp_path / "r.xlsx", "xlsx", scan=scan, meta=ReportMeta(project=INJECTION))
    with zipfile.ZipFile(path) as z:
        for name in z.namelist():
            if name.startswith("xl/worksheets/"):
                assert "<f>" not in z.read(name).decode(), name
    assert load(path.read_bytes())["Summary"]["B3"].value == INJECTION


def test_control_characters_in_user_text_are_dropped(scan):
    wb = load(render_xlsx(scan=scan, meta=ReportMeta(project="Lida\x00\x07 plan")))
    assert wb["Summary"]["B3"].value == "Lida plan"


# --- reproducible and atomic -----------------------------------------------------------------


def test_byte_identical_with_source_date_epoch(monkeypatch, scan, uav):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    meta = ReportMeta(project="Lida", locale="ru")
    one = render_xlsx(scan=scan, uav=uav, meta=meta)
    two = render_xlsx(scan=scan, uav=uav, meta=meta)
    assert one == two
    with zipfile.ZipFile(io.BytesIO(one)) as z:
        assert {i.date_time for i in z.infolist()} == {(2023, 11, 14, 22, 13, 20)}
        core = z.read("docProps/core.xml").decode()
    assert core.count("2023-11-14T22:13:20Z") == 2  # created and modified
    assert load(one)["Сводка"]["B6"].value == "14.11.2023"  # the Russian date convention
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000060")
    assert render_xlsx(scan=scan, uav=uav, meta=meta) != one


def test_epoch_before_1980_still_renders(monkeypatch, scan):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "0")
    with zipfile.ZipFile(io.BytesIO(render_xlsx(scan=scan))) as z:
        assert {i.date_time for i in z.infolist()} == {(1980, 1, 1, 0, 0, 0)}


def test_failure_while_rendering_keeps_the_old_file(tmp_path, monkeypatch, scan, uav):
    target = tmp_path / "report.xlsx"
    target.write_bytes(b"previous")

    def broken(book, view):
        raise RuntimeError("boom")

    # the MTF sheet's writer fails (a sheet is a record of the registry X.SHEETS)
    sheets = tuple(X.Sheet(s.name, broken, s.section) if s.name == "mtf" else s
                   for s in X.SHEETS)
    assert sheets != X.SHEETS
    monkeypatch.setattr(X, "SHEETS", sheets)
    with pytest.raises(RuntimeError, match="boom"):
        _write(target, "xlsx", scan=scan, uav=uav)
    assert target.read_bytes() == b"previous"
    assert [p.name for p in tmp_path.iterdir()] == ["report.xlsx"]
    monkeypatch.undo()
    assert _write(target, "xlsx", scan=scan, uav=uav) == target
    assert load(target.read_bytes()).sheetnames == EN_SHEETS
    assert [p.name for p in tmp_path.iterdir()] == ["report.xlsx"]


def test_minimal_plans_render(scan):
    """A UAV flight without a map (no limits, no map object) and the printed Instruction."""
    bare = uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300)
    wb = load(render_xlsx(uav=bare))
    assert wb["UAV"]["A1"].value == "Parameter" and len(wb["MTF"]._charts) == 1
    printed = scan_job(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000],
                       camera="rc30-153", norms="gkinp-02-036-02-printed")
    ws = load(render_xlsx(scan=printed))["Constraints"]
    assert {ws.cell(r, 3).value for r in range(2, ws.max_row + 1)} == {"PS", "PZ", "PP", "PR"}


def test_russian_report_uses_the_norm_tables_russian_names(both_ru):
    ws = both_ru["Исходные данные"]
    values = {ws[f"A{r}"].value: ws[f"B{r}"].value for r in range(1, ws.max_row + 1)}
    assert values["Объект дешифрирования"] == "столбы, гидранты"
    assert values["Форма"] == "круг"
    assert both_ru["Сводка"]["A1"].value.startswith("Техническое задание")


def test_scales_read_as_the_documents_write_them(both_en, both_ru):
    """A scale cell reads as the PDF and the terminal write the scale: English 1:20000,
    Russian 1:20 000 from five digits and 1:5000 whole (it showed 1:20000 in Russian)."""
    ru_formats = {c.number_format for ws in both_ru.worksheets for row in ws.iter_rows()
                  for c in row if isinstance(c.value, int | float) and "1:" in c.number_format}
    en_formats = {c.number_format for ws in both_en.worksheets for row in ws.iter_rows()
                  for c in row if isinstance(c.value, int | float) and "1:" in c.number_format}
    assert en_formats == {'"1:"0'}
    assert ru_formats == {'[>=10000]"1:"#,##0;"1:"0'}
    ws = both_ru["Ряд масштабов"]
    assert any(c.value == 20000 and c.number_format == '[>=10000]"1:"#,##0;"1:"0'
               for row in ws.iter_rows() for c in row)


def test_warnings_list_their_scales_as_the_text_writes_them(both_en, both_ru):
    """The Warnings sheet's photo scales and the Summary's '!' lines: Russian 1:10 000 and
    1:5000 joined by '; ' (as the messages list them), English 1:10000 by ', ' (the Russian
    sheet said 1:10000, 1:15000)."""
    en = [r[3] for r in both_en["Warnings"].iter_rows(min_row=2, values_only=True)]
    ru = [r[3] for r in both_ru["Предупреждения"].iter_rows(min_row=2, values_only=True)]
    assert "1:10000, 1:15000, 1:20000" in en and "1:5000" in en
    assert "1:10\u00a0000; 1:15\u00a0000; 1:20\u00a0000" in ru and "1:5000" in ru
    lines = [r[0] for r in both_ru["Сводка"].iter_rows(values_only=True)
             if isinstance(r[0], str) and r[0].startswith("! ")]
    assert any(line.endswith(": 1:15\u00a0000; 1:20\u00a0000") for line in lines), lines
    assert not any("1:15000" in line for line in lines)
