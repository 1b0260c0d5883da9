"""How the PDF and the workbook look: numbers stored as numbers, one grouping rule, the
formula the plan used cited, page 1's warnings apart from its information, no near-empty
page, each heading once."""

from __future__ import annotations

import io
import re
from pathlib import Path

import openpyxl
import pytest

from scanplan.project.file import parse_project
from scanplan.project.spec import plan_project
from scanplan.reports.view import build_view

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _plan(name: str, locale: str):
    path = EXAMPLES / name
    text = re.sub(r'(?m)^locale = "\w+"', f'locale = "{locale}"', path.read_text("utf-8"))
    return plan_project(parse_project(text, path))


def _view(result):
    film = result.film.job if result.film else None
    uav = result.uav.job if result.uav else None
    return build_view(scan=film, uav=uav, meta=result.meta, spec=result)


def _render(result, kind: str, view=None) -> bytes:
    view = view or _view(result)
    if kind == "xlsx":
        from scanplan.reports.excel import render_xlsx as render
    elif kind == "html":
        from scanplan.reports.pdfhtml import render_html as render
    else:
        from scanplan.reports.pdf import render_pdf as render
    film = result.film.job if result.film else None
    uav = result.uav.job if result.uav else None
    return render(scan=film, uav=uav, meta=result.meta, spec=result, view=view)


_NUMBER_TEXT = re.compile(r"[−-]?\d[\d\u00a0 ,.]*")


@pytest.mark.parametrize("name,locale", [("uav-canon-2000.toml", "ru"),
                                         ("film-1000.toml", "en"),
                                         ("archive-12000-for-2000.toml", "ru")])
def test_design_sheet_numbers_are_number_cells(name, locale):
    """A figure of the survey design sheet is a number cell with a number format (it was
    the text "6,00", which a spreadsheet neither sums nor sorts)."""
    wb = openpyxl.load_workbook(io.BytesIO(_render(_plan(name, locale), "xlsx")))
    ws = wb.worksheets[1]
    assert ws.title in ("Design", "Технический проект АФС")
    numbers = 0
    for row in ws.iter_rows(min_row=2, max_col=2):
        cell = row[1]
        if isinstance(cell.value, str):
            assert not _NUMBER_TEXT.fullmatch(cell.value.strip()), (cell.coordinate, cell.value)
        elif isinstance(cell.value, (int, float)):
            numbers += 1
            assert cell.number_format.startswith("#,##0"), cell.number_format
    assert numbers >= 3


def test_uav_design_sheet_cites_the_digital_height_formula():
    """The UAV plan's P_Z is the digital normal case σ_Z (the one its table binds on); the
    design sheet cited the film formula P_Z = V_z·f/(k·Mc·b) beside it."""
    from scanplan.reports.formatter import formatter
    from scanplan.reports.views import ResultTables

    result = _plan("uav-canon-2000.toml", "en")
    assert result.uav.job.plan.binding == "PZ"
    f = formatter("en")
    norms = " ".join(f.show(r.values[1]) for r in ResultTables(spec=result)["design"].rows)
    assert "σ_Z = (H/B)·(H/f)·σ_px" in norms
    assert "V_z·f/(k·Mc·b)" not in norms


def _box(html: str, cls: str) -> str:
    """The text of page 1's box of class ``cls`` ("" when the page has none)."""
    m = re.search(rf'<div class="{cls}">(.*?)</div>\s*</div>', html, re.S)
    if not m:
        return ""
    text = re.sub(r"<sub>(.*?)</sub>", r"_\1", m.group(1))  # P<sub>R</sub> → P_R
    return re.sub(r"<[^>]+>", " ", text)


def test_page_one_keeps_warnings_apart_from_information():
    """Page 1's red box holds what to act on; information and conditions checked (P_R
    driving the volume, the design's compliant GSD) have a box of their own. The haze
    assumption asks for the flight's own value, so it is in the red box, not in the box
    whose items need no action. A warning only the specification gives names the section
    that explains it."""
    html = _render(_plan("aerial-ultracam-5000.toml", "en"), "html")
    assert "Haze contrast assumed" in _box(html, "warnbox")
    assert "Haze contrast assumed" not in _box(html, "warnbox notebox")
    html = _render(_plan("uav-canon-2000.toml", "en"), "html")
    warn = _box(html, "warnbox")
    assert "Motion blur" in warn
    assert "Flight height lowered — see “Specification”" in warn
    html = _render(_plan("film-1000.toml", "ru"), "html")
    assert "P_R" not in _box(html, "warnbox")
    assert "Объём данных определяет P_R" in _box(html, "warnbox notebox")
    assert "см. «Технический проект аэрофотосъёмки»" in _box(html, "warnbox notebox")


def test_uav_specification_on_page_one_gives_gsd_and_overlaps():
    """The contract's deliverables on page 1 of a UAV specification: the GSD and the
    overlaps, beside the heights."""
    html = _render(_plan("uav-canon-2000.toml", "en"), "html")
    spec = html[html.index('<h2 class="spec">'):html.index("</table>",
                                                          html.index('<h2 class="spec">'))]
    assert "GSD at the recommended height, cm</th><td>2.69" in spec.replace("\n", "")
    assert "Forward / side overlap, %</th><td>80 / 60" in spec.replace("\n", "")


def _page_fill(pdf: bytes) -> list[float]:
    """How far down each page its content reaches (0–1 of the body, header and footer
    left out), from the pages rasterised at 20 dpi."""
    import shutil
    import subprocess
    import tempfile

    import numpy as np
    from PIL import Image

    if shutil.which("pdftoppm") is None:
        pytest.skip("pdftoppm (poppler) is not installed")
    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "d.pdf").write_bytes(pdf)
        subprocess.run(["pdftoppm", "-gray", "-r", "20", "d.pdf", "p"], cwd=tmp, check=True)
        fills = []
        for page in sorted(Path(tmp).glob("p*.pgm")):
            a = np.asarray(Image.open(page))
            body = a[int(a.shape[0] * 0.05):int(a.shape[0] * 0.93)]
            rows = np.flatnonzero((body < 200).any(axis=1))
            fills.append((rows.max() + 1) / body.shape[0] if rows.size else 0.0)
    return fills


@pytest.mark.parametrize("name,locale", [("film-1000.toml", "ru"),
                                         ("aerial-ultracam-5000.toml", "en")])
def test_no_near_empty_page_but_the_last(name, locale):
    """A few spilled rows then a forced break (a section on a new page, the references moved
    whole) left pages filled to a sixth; every page but the last is now at least half full."""
    fills = _page_fill(_render(_plan(name, locale), "pdf"))
    assert all(f >= 0.5 for f in fills[:-1]), fills


def test_an_abstract_area_prints_its_flight_lines_heading_once():
    html = _render(_plan("film-1000.toml", "en"), "html")
    assert html.count(">Flight lines over the area<") == 1


def test_short_tables_are_kept_whole():
    """A table of a few rows is not split over two pages (a six-row table split 3/3)."""
    html = _render(_plan("film-1000.toml", "en"), "html")
    assert '<table class="results strips short">' in html
    assert '<table class="kv short">' in html
    css = (Path(__file__).resolve().parent.parent / "templates" / "report.css").read_text()
    assert re.search(r"table\.kv\.short[^{]*\{\s*break-inside: avoid", css)


def test_a_ground_range_draws_no_flat_heights_chart_and_says_why():
    """With a range of ground elevations and no DEM every photo is planned over the same
    ground: the heights chart showed flat ground and the map one colour; neither is drawn
    coloured, and the documents say why."""
    from scanplan.reports.exports import spec_layouts
    from scanplan.reports.mapview import geo_views, map_terrain

    result = _plan("uav-town-2000-afs.toml", "en")
    html = _render(result, "html")
    assert "Heights above ground along the strips" not in html
    assert "no chart of the heights along the strips is drawn" in html
    film = _plan("film-town-relief-10000.toml", "en")
    (layout,) = [lay for _kind, lay in spec_layouts(film)]
    assert map_terrain(film, "film", layout) is None
    (view,) = geo_views(film, "en")
    assert any("not coloured by their height above ground" in n for n in view["notes"])


def test_film_chart_draws_coinciding_constraints_apart_and_ticks_a_lone_scale():
    """P_Z lies within 1 % of P_P for the Instruction's example: it is dashed and drawn
    over the solid P_P; an archive's single photo scale gets round scales beside it."""
    from scanplan.reports import plots
    from scanplan.reports.views import ResultTables

    film = _plan("instruction-2000-film.toml", "en").film.job
    svg = plots.constraints_svg(ResultTables.of_jobs(film))
    red = re.findall(r'<(?:path|polyline)[^>]*stroke="#d62728"[^>]*>', svg)
    assert red and all("stroke-dasharray" in x for x in red), red[:2]
    assert svg.index('stroke="#2ca02c"') < svg.index('stroke="#d62728"')
    assert plots._scale_ticks([12000.0], 6000.0, 24000.0) == [
        6000.0, 8000.0, 10000.0, 12000.0, 15000.0, 20000.0]


def test_workbook_chart_legend_gives_a_height_as_the_pdf_does():
    """The highest flown height 148.5 m: the workbook's chart legend said 148 m beside the
    PDF's 148.5 m (one rounding rule, Numbers.height)."""
    import documents  # the town's English workbook, rendered once per run

    town = str(documents.EXAMPLES / "uav-town-2000.toml")
    result = documents.planned(town, "en")
    assert result.uav.job.plan.heights_m["max"] == pytest.approx(148.5)
    wb = documents.loaded_workbook(town, "en")
    cells = {c.value for ws in wb.worksheets for row in ws.iter_rows() for c in row
             if isinstance(c.value, str)}
    assert "highest flown: 148.5 m" in cells
    assert "highest flown: 148 m" not in cells
    from scanplan.reports import plots
    from scanplan.reports.views import ResultTables

    assert "148.5 m" in plots.height_svg(ResultTables.of_jobs(None, result.uav.job), "en")
