"""The reports' bibliography (norms/references.toml) and the citation renderer."""

from __future__ import annotations

import re

import pytest

from scanplan.norms import list_norm_sets, load_norm_set
from scanplan.reports.references import Bibliography, references


def test_every_work_in_both_languages_with_unique_short_forms():
    refs = references()
    assert len(refs) >= 5
    seen: set[str] = set()
    for ref in refs:
        assert ref.en.strip() and ref.ru.strip(), ref.id
        if not re.search(r"[а-яё]", ref.ru, re.IGNORECASE):  # an English work, as published
            assert "(in Russian)" not in ref.en and ref.ru.split(".")[0] in ref.en, ref.id
        for alias in ref.aliases:
            assert alias.casefold() not in seen, alias
            seen.add(alias.casefold())


def test_the_papers_and_the_instruction_are_there():
    ids = {r.id: r for r in references()}
    assert "2002" in ids["gkinp-02-036-02"].ru and "ЦНИИГАиК" in ids["gkinp-02-036-02"].ru
    assert "№ 12" in ids["miheeva-medvedev-2010"].ru and "103–108" in ids[
        "miheeva-medvedev-2010"].ru
    assert "Михеева" in ids["miheeva-ilushenko-2015"].ru
    assert "Зверев" in ids["zverev-fisenko-2014"].ru


def test_short_forms_become_numbers_with_locators_in_the_reports_language():
    en, ru = Bibliography("en"), Bibliography("ru")
    assert en.cite("seed 001 Table 3") == "[1], Table 3"
    assert ru.cite("seed 001 Table 3") == "[1], табл. 3"
    assert en.cite("GKINP (GNTA)-02-036-02; seed 001 eq. 1 (V_s)") == "[2]; [1], eq. (1) (V_s)"
    assert ru.cite("seed 001 eqs. 5-6 and its ref. [2]") == "[1], ф. (5)–(6) и его источник № 2"
    # the numbers follow the order of first citation and are stable within a document
    assert [n for n, _ in en.entries()] == [1, 2]
    assert en.entries()[0][1].startswith("Miheeva A.A., Ilushenko A.")
    assert ru.entries()[0][1].startswith("Михеева А.А., Илюшенко А.")


def test_a_full_citation_passes_through():
    text = ("Условные знаки для топографических планов масштабов 1:5000, 1:2000, 1:1000, "
            "1:500. — М.: Недра, 1989, с. 12")
    assert Bibliography("ru").cite(text) == text


@pytest.mark.parametrize("name", [n for n, where in list_norm_sets() if where == "bundled"])
@pytest.mark.parametrize("locale", ["en", "ru"])
def test_every_bundled_source_cell_is_cited_without_seed(name, locale):
    ns = load_norm_set(name)
    bib = Bibliography(locale)
    # the set's own source is prose naming the works: the reports show their numbers only
    assert re.findall(r"\[\d+\]", bib.cite(ns.source))
    cells = [*ns.parameter_sources.values(), *(o.source for o in ns.objects),
             *(row.get("source", "") for row in ns.shape_rows.values())]
    for cell in cells:
        shown = bib.cite(cell)
        assert not re.search(r"seed\s*0", shown, re.IGNORECASE), (cell, shown)
        if locale == "ru" and shown != cell:  # a cited cell: its locator is Russian too
            assert not re.search(r"\b[a-z]{3,}\b", shown), (cell, shown)


def test_author_cite_names_the_work_for_output_without_a_reference_list():
    """The terminal has no reference list: a norm table's source reads as authors and year,
    in the output's language — never 'seed 001' (the Russian terminal said '(seed 001 Table
    3)')."""
    from scanplan.reports.references import author_cite

    assert author_cite("1:2000 (seed 001 Table 3)", "en") == \
        "1:2000 (Miheeva & Ilushenko 2015, Table 3)"
    assert author_cite("1:2000 (seed 001 Table 3)", "ru") == \
        "1:2000 (Михеева, Илюшенко, 2015, табл. 3)"
    assert author_cite("no work named", "ru") == "no work named"


def test_scan_terminal_names_no_seed():
    from click.testing import CliRunner

    from scanplan.cli.main import main

    for loc in ("en", "ru"):
        r = CliRunner().invoke(main, ["scan", "--map-scale", "2000", "--relief", "1",
                                      "--photo-scale", "10000", "--camera", "rc30-153",
                                      "--locale", loc])
        assert r.exit_code == 0, r.output
        assert "seed 0" not in r.output
        assert ("Михеева, Илюшенко, 2015, табл. 3" if loc == "ru"
                else "Miheeva & Ilushenko 2015, Table 3") in r.output


def test_the_pdf_and_the_workbook_of_one_run_number_a_work_alike():
    """One view renders both documents of a run: the works share their numbers, and each
    document lists the works it cites with those numbers (gaps allowed, never renumbered)."""
    import io
    import re
    from pathlib import Path

    import openpyxl

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.excel import render_xlsx
    from scanplan.reports.pdfhtml import render_html
    from scanplan.reports.view import build_view

    root = Path(__file__).resolve().parent.parent
    for name in ("archive-12000-for-2000", "uav-town-2000-afs", "instruction-2000-film"):
        r = plan_project(load_project(root / "examples" / f"{name}.toml"))
        for first in ("pdf", "xlsx"):
            view = build_view(scan=r.film.job if r.film else None,
                              uav=r.uav.job if r.uav else None, meta=r.meta, spec=r)
            if first == "xlsx":
                data = render_xlsx(view=view)
            html = render_html(view=view)
            if first == "pdf":
                data = render_xlsx(view=view)
            pdf = dict(re.findall(r'<li value="(\d+)">(.*?)</li>', html, re.S))
            wb = openpyxl.load_workbook(io.BytesIO(data))
            ws = wb.worksheets[-1]  # the references close the workbook
            book = {str(row[0]): row[1] for row in ws.iter_rows(min_row=2, values_only=True)}
            shared = set(pdf) & set(book)
            assert shared, name
            for n in shared:
                assert " ".join(pdf[n].split())[:40] == " ".join(book[n].split())[:40], (
                    name, first, n)


def test_the_workbook_and_the_pdf_of_one_view_render_its_html_once(monkeypatch):
    """The workbook numbers its works by the PDF's HTML; the PDF then uses that HTML, not a
    second render of it (workbook first is the order of the API's and the batch's writes)."""
    from pathlib import Path

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports import pdfhtml
    from scanplan.reports.excel import render_xlsx
    from scanplan.reports.view import build_view

    root = Path(__file__).resolve().parent.parent
    r = plan_project(load_project(root / "examples" / "instruction-2000-film.toml"))
    view = build_view(scan=r.film.job, meta=r.meta, spec=r)
    env = pdfhtml._environment()
    real = env.get_template
    calls = []
    monkeypatch.setattr(env, "get_template",
                        lambda name, *a, **k: calls.append(name) or real(name, *a, **k))
    render_xlsx(view=view)
    html = pdfhtml.render_html(view=view)
    assert calls.count("report.html") == 1 and pdfhtml.render_html(view=view) is html


@pytest.mark.parametrize("work", ["kraus-2007", "luhmann-2014", "aguera-vega-2017",
                                  "reda-andreas-2004", "meeus-1998"])
def test_the_russian_list_cites_an_english_work_by_its_original_title(work):
    """GOST R 7.0.100-2018: a work is described in the language it was published in."""
    ref = {r.id: r for r in references()}[work]
    title = re.split(r"\. (?:\d|Berlin|Measurement|Solar|Richmond)", ref.en.split(". ", 1)[1])[0]
    assert title in ref.ru, (work, title)
    assert "на англ. яз." not in ref.ru


def test_every_entry_is_a_citable_work():
    """No entry apologises for itself or points to a work by "e.g.": each names one work."""
    for ref in references():
        for text in (ref.en, ref.ru):
            for phrase in ("not preserved", "не сохранились", "e.g.", "напр.",
                           "textbook relations", "учебные соотношения"):
                assert phrase not in text, (ref.id, phrase)
    lobanov = {r.id: r for r in references()}["uav-geometry"]
    assert lobanov.ru == "Лобанов А.Н. Фотограмметрия. — М.: Недра, 1984. — 552 с."
    assert lobanov.en.startswith("Lobanov A.N. Photogrammetry. Moscow: Nedra, 1984.")


def test_a_paragraph_of_the_airspace_rules_has_one_form():
    """Para. 52(3), never 52.3 or 52.1, in every entry and every message."""
    from scanplan.i18n.messages import MESSAGES

    texts = [t for r in references() for t in (r.en, r.ru)]
    texts += [t for m in MESSAGES.values() for t in m.values()]
    for text in texts:
        assert not re.search(r"(?:para\.|paras\.|п\.|пп\.)\s*\d+[,\s\d]*52\.\d", text), text
        assert not re.search(r"\b52\.\d\b", text), text
