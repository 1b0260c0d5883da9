"""The report view model (issue 14): one view per result, one number formatter per locale,
one label catalogue, plots drawn once, sheets as records (issue 15: fast reports)."""

from __future__ import annotations

import doctest
import io
import math

import openpyxl
import pytest

from scanplan.i18n import numbers
from scanplan.i18n.labels import LABELS
from scanplan.i18n.numbers import Numbers
from scanplan.project.jobs import scan_job, uav_job
from scanplan.reports import ReportMeta, plots
from scanplan.reports import excel as X
from scanplan.reports.formatter import formatter
from scanplan.reports.view import build_view, section_names


@pytest.fixture(scope="module")
def scan():
    return scan_job(map_scale=2000, relief_interval_m=0.5, photo_scales=[5000, 10000],
                    camera="rc30-153")


@pytest.fixture(scope="module")
def uav():
    return uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                   speed_ms=25, map_scale=2000, relief_interval_m=0.5)


def test_the_examples_of_the_formatter_module_run():
    from scanplan.reports import formatter as formatter_module

    result = doctest.testmod(formatter_module, verbose=False)
    assert result.attempted >= 2 and result.failed == 0
    result = doctest.testmod(numbers, verbose=False)  # the number formatter's, beside it
    assert result.attempted >= 2 and result.failed == 0


@pytest.mark.parametrize(("locale", "x", "digits", "grouped"), [
    ("en", 12345.678, 1, "12,345.7"),
    ("ru", 12345.678, 1, "12\u00a0345,7"),
    ("en", 0.25, 3, "0.250"),
    ("ru", 0.25, 3, "0,250"),
])
def test_one_number_formatter_per_locale(locale, x, digits, grouped):
    """A number of 1,000 and more is grouped the same way in prose (``fixed``, the
    terminal's and the documents' sentences) and in tables (``num``)."""
    n = Numbers(locale)
    assert n.num(x, digits) == grouped
    assert n.fixed(x, digits) == grouped


def test_numbers_never_print_a_non_finite_value():
    for n in (Numbers("en"), Numbers("ru")):
        for bad in (None, math.nan, math.inf, -math.inf):
            assert n.num(bad) == n.fixed(bad) == n.g(bad) == n.um(bad) == "—"


def test_scales_pixels_and_whole_numbers():
    en, ru = Numbers("en"), Numbers("ru")
    assert (en.scale(10000), ru.scale(10000)) == ("1:10000", "1:10\u00a0000")
    # one way in every document: four digits whole in both languages (Russian typesetting)
    assert (en.scale(2000), ru.scale(2000), ru.floor_scale(8847.9)) == ("1:2000", "1:2000",
                                                                        "1:8847")
    assert (en.plain_scale(10000), en.floor_scale(12345.9)) == ("1:10000", "1:12345")
    assert (en.whole(10000), ru.whole(10000)) == ("10,000", "10\u00a0000")
    # one grouping rule on every page: a count of four digits is grouped as num() groups it
    assert (en.g(4575.0), ru.g(1501.0), en.whole(4575), ru.whole(1501)) == (
        "4,575", "1\u00a0501", "4,575", "1\u00a0501")
    assert (en.g(4575.0), ru.g(1501.0)) == (en.num(4575, 0), ru.num(1501, 0))
    # a height in a chart's legend as the tables give it (148.5 is not rounded to 148)
    assert (en.height(148.5), ru.height(148.5), en.height(70.01)) == ("148.5", "148,5", "70")
    # a pixel under 1 µm keeps two significant digits, never "0.0"
    assert (en.um(0.42), ru.um(0.42), en.um(12.34)) == ("0.42", "0,42", "12.3")
    assert (en.g(2.5), ru.g(2.5), ru.g(25000.0)) == ("2.5", "2,5", "25\u00a0000")


def test_the_plot_module_formats_numbers_with_the_view():
    assert plots.number(1234.5, 1, "ru") == Numbers("ru").num(1234.5, 1) == "1\u00a0234,5"


def test_one_formatter_for_documents_and_terminal():
    assert formatter("ru")("map_scale") == LABELS["ru"]["map_scale"]
    # the terminal's words are the terminal catalogue's, keyed by concept in both languages
    assert formatter("ru").cli("map") == "карта" and formatter("en").cli("volume")
    assert formatter("en", "aircraft")("title_uav") != formatter("en", "uav")("title_uav")
    assert formatter("ru").constraint("PZ") == "точность по высоте"


def test_sections_in_document_order(scan, uav):
    assert section_names(scan, uav, None) == ("film", "uav", "comparison")
    assert section_names(None, uav, object()) == ("spec", "uav")
    with pytest.raises(ValueError):
        build_view()


def test_plots_are_drawn_once_per_view(scan, uav, monkeypatch):
    """The workbook and the PDF of one result share the view; each plot is drawn once
    however many documents (or renders) use it."""
    from scanplan.reports.pdf import render_html

    calls: list[str] = []
    for name in ("constraints_svg", "mtf_svg", "height_svg"):
        real = getattr(plots, name)
        monkeypatch.setattr(plots, name,
                            lambda *a, _real=real, _name=name, **k: (calls.append(_name),
                                                                     _real(*a, **k))[1])
    v = build_view(scan=scan, uav=uav, meta=ReportMeta(locale="ru"))
    X.render_xlsx(view=v)
    first = render_html(view=v)
    second = render_html(view=v)
    assert first == second
    assert sorted(calls) == ["constraints_svg", "height_svg", "mtf_svg"]
    assert plots.view_plot(v, "mtf").startswith("<?xml")
    assert "Scanplan Sans" in plots.view_plot(v, "mtf")


def test_a_view_renders_as_the_jobs_do(scan, uav, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    meta = ReportMeta(project="Lida", locale="ru")
    assert (X.render_xlsx(view=build_view(scan=scan, uav=uav, meta=meta))
            == X.render_xlsx(scan=scan, uav=uav, meta=meta))


def test_a_new_sheet_is_one_record(scan, uav, monkeypatch):
    """Extending the workbook (docs/architecture.md, "Adding a section or a sheet"): one
    writer and one record in SHEETS; a sheet of a section the result lacks is left out."""
    def strips(book, v):
        ws = book.sheet("flight_geometry", landscape=False, widths=(30, 12))
        X.put_text(ws, 1, 1, book.f("n_strips"))
        X.put_num(ws, 1, 2, v.uav.plan.flight.get("strips", 0), "0")

    monkeypatch.setattr(X, "SHEETS", (*X.SHEETS, X.Sheet("strips", strips, "uav")))
    wb = openpyxl.load_workbook(io.BytesIO(X.render_xlsx(scan=scan, uav=uav)))
    assert wb.sheetnames[-1] == LABELS["en"]["flight_geometry"]
    assert wb.worksheets[-1]["A1"].value == LABELS["en"]["n_strips"]
    film_only = openpyxl.load_workbook(io.BytesIO(X.render_xlsx(scan=scan)))
    assert LABELS["en"]["flight_geometry"] not in film_only.sheetnames
