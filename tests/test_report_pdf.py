"""The PDF report: text in both locales, approval block, page numbers, the binding
constraint, HTML injection shown as text with nothing fetched, atomic writing, and
byte-identical output with SOURCE_DATE_EPOCH.

WeasyPrint is slowish: each document is rendered once per module (fixtures) and the tests
read the result.
"""

from __future__ import annotations

import io
import re
import socket
from pathlib import Path

import pytest

from scanplan.i18n.labels import LABELS

pypdf = pytest.importorskip("pypdf")
weasyprint = pytest.importorskip("weasyprint")

from scanplan.project.jobs import scan_job, uav_job  # noqa: E402
from scanplan.reports import ReportMeta, templates_dir  # noqa: E402
from scanplan.reports import pdf as P  # noqa: E402
from scanplan.reports.plots import constraints_svg, number  # noqa: E402
from scanplan.reports.views import ResultTables  # noqa: E402

EPOCH = "1700000000"  # 2023-11-14T22:13:20Z
INJECTION = 'Site <img src="file:///etc/passwd"> & <b>bold</b>'


@pytest.fixture(scope="module")
def scan():
    return scan_job(map_scale=2000, relief_interval_m=0.5,
                    photo_scales=[5000, 10000, 15000, 20000], camera="rc30-153")


@pytest.fixture(scope="module")
def uav():
    # the Instruction's height form and a raised ceiling: interpretation (PD) binds
    return uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                   height_tolerance_pct=40, speed_ms=25, map_scale=2000, max_height_m=1000,
                   height_formula="instruction", relief_interval_m=0.5)


def _meta(locale: str, project: str) -> ReportMeta:
    ru = locale == "ru"
    return ReportMeta(project=project, customer="ООО «Заказчик»" if ru else "Customer Ltd",
                      contractor="АО «Аэрогеодезия»" if ru else "Aerogeo Inc.",
                      locale=locale,
                      approver_position="Главный инженер" if ru else "Chief engineer",
                      approver_name="И. И. Иванов" if ru else "I. I. Ivanov")


class _Render:
    """One rendered document: its bytes, its text, what the fetcher was asked for."""

    def __init__(self, data: bytes, fetcher: P.BundledAssetFetcher, connects: list) -> None:
        self.data = data
        self.fetcher = fetcher
        self.connects = connects
        self.reader = pypdf.PdfReader(io.BytesIO(data))
        self.pages = [p.extract_text() for p in self.reader.pages]
        self.text = " ".join(" ".join(self.pages).split())


def _render(scan, uav, meta: ReportMeta) -> _Render:
    """Render with SOURCE_DATE_EPOCH, a recording fetcher, and the network cut off."""
    connects: list = []

    def no_connect(self, address, *a, **k):  # any socket connection is a failure
        connects.append(address)
        raise OSError("network access during report rendering")

    fetcher = P.BundledAssetFetcher()
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv("SOURCE_DATE_EPOCH", EPOCH)
        mp.setattr(socket.socket, "connect", no_connect)
        data = P.render_pdf(scan=scan, uav=uav, meta=meta, url_fetcher=fetcher)
    return _Render(data, fetcher, connects)


@pytest.fixture(scope="module")
def doc_en(scan, uav):
    return _render(scan, uav, _meta("en", INJECTION))


@pytest.fixture(scope="module")
def doc_ru(scan, uav):
    return _render(scan, uav, _meta("ru", "г. Ивановка, топографический план 1:2000"))


# --- text in both locales -------------------------------------------------------------


def test_english_title_approval_and_binding(doc_en):
    text = doc_en.text
    assert doc_en.data.startswith(b"%PDF-")
    assert "Aerial survey and scan specification" in text
    for s in ("APPROVED", "Chief engineer", "I. I. Ivanov", "Position", "Signature", "Name",
              "Customer Ltd", "Aerogeo Inc.", "Contractor"):
        assert s in text, s
    # the binding constraint named and explained in one sentence per photo scale
    assert "PZ (height accuracy) binds at 1:10000: 8.3 µm" in text
    assert "PR (resolving power of the photo) binds at 1:5000: 12.5 µm" in text
    assert "Binding constraint" in text
    # UAV: maximum height and its binding constraint
    assert "Maximum planned flight height 386 m: PD (interpretation) binds" in text
    assert "Maximum planned height by height formula — normal-case stereo" in text
    # warnings, formulas with sources
    assert "Not interpretable." in text and "[not_interpretable]" not in text
    assert "Motion blur." in text
    # formulas cite numbered references, listed at the end in full (issue 13)
    assert re.search(r"PS = Vs·Mk/\(k·Mc\) — \[\d\]; \[\d\], eq\. \(1\)", text)  # subscripts set
    assert "L = H/(2·R·f)" in text and "seed 0" not in text
    assert "References" in text and "Miheeva A.A., Ilushenko A. Resolution calculation" in text
    assert "GKINP (GNTA)-02-036-02. Instruction for photogrammetric works" in text
    assert "Comparison" in text


def test_russian_title_approval_and_binding(doc_ru):
    text = doc_ru.text
    assert "Техническое задание на аэрофотосъёмку и сканирование" in text
    for s in ("УТВЕРЖДАЮ", "Главный инженер", "И. И. Иванов", "Должность", "Подпись",
              "Ф. И. О.", "ООО «Заказчик»", "Исполнитель"):
        assert s in text, s
    assert ("При масштабе 1:10 000 размер пикселя сканирования 8,3 мкм определяет условие "
            "PZ (точность по высоте)") in text
    assert "Определяющее условие" in text
    assert ("Максимальную плановую высоту полёта 386 м определяет условие PD (дешифрирование)"
            in text)
    assert "Формулы и источники" in text and "Предупреждения" in text
    assert "Дешифрирование невозможно." in text
    assert "столбы, гидранты: 0,2 м, круг" in text  # norm object and shape in Russian
    assert re.search(r"\b12,5\b", text) and "1:20 000" in text  # decimal comma, grouping


@pytest.mark.parametrize("which, word, of", [("doc_en", "Sheet", "of"),
                                             ("doc_ru", "Лист", "/ Листов")])
def test_every_page_is_numbered_x_of_y(request, which, word, of):
    doc = request.getfixturevalue(which)
    n = len(doc.pages)
    assert n >= 3
    for i, page in enumerate(doc.pages, 1):
        assert f"{word} {i} {of} {n}" in " ".join(page.split()), (i, page[-80:])


def test_pdf_metadata_uses_source_date_epoch(doc_en):
    created = doc_en.reader.metadata.creation_date
    assert created is not None and created.year == 2023 and created.month == 11
    assert "scanplan" in (doc_en.reader.metadata.creator or "")


def test_bundled_font_is_embedded(doc_ru):
    fonts = set()
    for page in doc_ru.reader.pages:
        for f in (page["/Resources"].get("/Font") or {}).values():
            fonts.add(str(f.get_object()["/BaseFont"]))
    assert fonts and all("Scanplan-Sans" in f for f in fonts), fonts  # @font-face family


# --- safety: injection shown as text, nothing fetched -----------------------------------


def test_html_in_project_name_is_text_and_nothing_is_fetched(doc_en):
    assert INJECTION in doc_en.text  # the literal text, tags and all
    root = templates_dir().resolve().as_uri() + "/"
    for url in doc_en.fetcher.requested:
        assert url.startswith("data:") or url.startswith(root), url
    assert not any("passwd" in u or u.startswith(("http:", "https:"))
                   for u in doc_en.fetcher.requested)
    assert doc_en.fetcher.refused == [] and doc_en.connects == []
    # the fonts and the stylesheet did come from the bundled folder
    assert any(u.endswith("fonts/DejaVuSans.ttf") for u in doc_en.fetcher.requested)


def test_html_is_escaped(scan):
    html = P.render_html(scan=scan, meta=_meta("en", INJECTION))
    assert '<img src="file:///etc/passwd">' not in html
    assert "&lt;img src=&#34;file:///etc/passwd&#34;&gt; &amp; &lt;b&gt;bold&lt;/b&gt;" in html


def test_fetcher_refuses_everything_but_data_and_bundled_assets(tmp_path):
    root = tmp_path / "templates"
    (root / "fonts").mkdir(parents=True)
    (root / "fonts" / "a.ttf").write_bytes(b"font")
    secret = tmp_path / "secret.txt"
    secret.write_text("secret")
    (root / "link.txt").symlink_to(secret)
    f = P.BundledAssetFetcher(root)
    assert f.fetch((root / "fonts" / "a.ttf").as_uri()).read() == b"font"
    assert f.fetch("data:text/plain;base64,aGk=").read() == b"hi"
    for url in (secret.as_uri(), (root / "link.txt").as_uri(), "file:///etc/passwd",
                (root / "fonts" / ".." / ".." / "secret.txt").as_uri(), root.as_uri(),
                "http://example.com/x.png", "https://example.com/x.css",
                "ftp://example.com/x", "file://otherhost/etc/passwd", "javascript:alert(1)"):
        with pytest.raises(ValueError):
            f.fetch(url)
    assert len(f.refused) == 10


# --- writing: atomic and reproducible ---------------------------------------------------


def test_same_input_gives_byte_identical_pdf(scan, uav, doc_en):
    again = _render(scan, uav, _meta("en", INJECTION))
    assert again.data == doc_en.data



def _write(path, kind, **jobs):
    """One document written through the one document path (as ``--xlsx``/``--pdf`` with
    ``--force``): the target checked, rendered to memory, written atomically."""
    from scanplan.reports.documents import Target, write_documents

    write_documents([Target(str(path), kind, "--" + kind)], force=True, **jobs)
    return Path(path)


def test_write_pdf_writes_atomically(uav, tmp_path, monkeypatch):
    monkeypatch.setenv("SOURCE_DATE_EPOCH", EPOCH)
    target = tmp_path / "uav.pdf"
    target.write_bytes(b"previous")
    out = _write(target, "pdf", uav=uav, meta=ReportMeta(locale="ru"))
    assert out == target and target.read_bytes().startswith(b"%PDF-")
    text = " ".join(pypdf.PdfReader(target).pages[0].extract_text().split())
    assert "Техническое задание на аэрофотосъёмку с БПЛА" in text
    assert sorted(p.name for p in tmp_path.iterdir()) == ["uav.pdf"]


def test_render_failure_leaves_the_old_report(scan, tmp_path, monkeypatch):
    target = tmp_path / "report.pdf"
    target.write_bytes(b"previous report")

    def broken(self, *a, **k):
        raise RuntimeError("renderer crashed")

    monkeypatch.setattr(weasyprint.HTML, "write_pdf", broken)
    with pytest.raises(RuntimeError, match="renderer crashed"):
        _write(target, "pdf", scan=scan)
    assert target.read_bytes() == b"previous report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["report.pdf"]


# --- smaller pieces ---------------------------------------------------------------------


def test_render_needs_a_plan_and_a_known_locale(scan):
    with pytest.raises(ValueError):
        P.render_html()
    with pytest.raises(ValueError):
        P.render_html(scan=scan, meta=ReportMeta(locale="de"))


def test_scan_only_html_has_the_binding_cells_highlighted(scan):
    html = P.render_html(scan=scan, meta=ReportMeta(locale="ru"))
    # one highlighted cell per photo scale, in the binding constraint's row
    assert html.count('class="num binding"') == len(scan.plan.scenarios)
    assert 'lang="ru"' in html and "Лист" in html and "УТВЕРЖДАЮ" in html


def test_many_photo_scales_split_into_tables_that_fit_a4():
    wide = scan_job(map_scale=2000, relief_interval_m=0.5, camera="rc30-153",
                    photo_scales=[3000, 5000, 7000, 8000, 10000, 12000, 15000, 20000, 25000])
    html = P.render_html(scan=wide, meta=ReportMeta(locale="en"))
    assert html.count('<table class="results">') == 2  # 5 + 4 photo scales
    assert html.count('class="num binding"') == 9


def test_plots_are_deterministic_svg(scan):
    tables = ResultTables.of_jobs(scan)
    a, b = constraints_svg(tables, "ru"), constraints_svg(ResultTables.of_jobs(scan), "ru")
    assert a == b and a.lstrip().startswith("<?xml") and "<svg" in a
    assert "dc:date" not in a


def test_number_format_per_locale():
    assert number(12.5, 1, "en") == "12.5" and number(12.5, 1, "ru") == "12,5"
    assert number(10000, 0, "en") == "10,000" and number(10000, 0, "ru") == "10\u00a0000"
    assert number(float("nan"), 1, "ru") == "—"


def test_templates_are_bundled():
    for name in ("report.html", "report.css", "_scan.html", "_uav.html", "_comparison.html",
                 "_macros.html"):
        assert (templates_dir() / name).is_file(), name
    assert Path(P.__file__).name == "pdf.py"


def test_plan_with_both_sections_has_one_comparison_table(tmp_path):
    """With a specification, the PDF shows the specification's side-by-side table only."""
    from pathlib import Path

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.pdf import render_html

    examples = Path(__file__).resolve().parent.parent / "examples"
    if not examples.is_dir():
        pytest.skip("examples/ not found beside the tests")
    film = (examples / "instruction-2000-film.toml").read_text(encoding="utf-8")
    uav = (examples / "uav-canon-2000.toml").read_text(encoding="utf-8")
    p = tmp_path / "both.toml"
    p.write_text(film.replace("[area]", uav[uav.index("[uav]"):uav.index("[area]")] + "[area]"),
                 encoding="utf-8")
    r = plan_project(load_project(p))
    old_heading = f">{LABELS['en']['comparison']}<"
    html = render_html(scan=r.film.job, uav=r.uav.job, meta=r.meta, spec=r)
    assert html.count("Film and UAV side by side") == 1
    assert "pixel on the ground" in html
    assert old_heading not in html
    without_spec = render_html(scan=r.film.job, uav=r.uav.job, meta=r.meta)
    assert old_heading in without_spec


def test_bundled_fonts_cover_every_character_the_documents_print():
    """The bundled fonts are cut down to the scripts the documents use (templates/fonts/
    README.md): every character of the label and message catalogues, the templates, the
    examples and the bundled norm sets must have a glyph in both of them."""
    from fontTools.ttLib import TTFont

    root = Path(__file__).resolve().parent.parent
    sources = [*(root / "scanplan").rglob("*.py"), *(root / "templates").glob("*.*"),
               *(root / "norms").rglob("*.csv"), *(root / "examples").glob("*.toml")]
    sources = [p for p in sources if p.suffix not in (".ttf", ".md", ".txt")]
    chars = set()
    for path in sources:
        chars |= {ch for ch in path.read_text(encoding="utf-8") if ch.isprintable()}
    assert {"№", "≤", "σ", "ё", "«", "µ", "×", "−", "…"} <= chars  # the sample is real
    for name in ("DejaVuSans.ttf", "DejaVuSans-Bold.ttf"):
        cmap = TTFont(templates_dir() / "fonts" / name).getBestCmap()
        missing = sorted(ch for ch in chars if ord(ch) not in cmap and ch != " ")
        assert not missing, (name, missing)


def test_fonts_kept_across_reports_give_the_same_pdf(scan, uav, monkeypatch):
    """The process keeps one font configuration for every report (a batch renders many);
    a second render, and one with fresh fonts, are byte-identical."""
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "1700000000")
    first = P.render_pdf(scan=scan, uav=uav)
    assert P._font_config.cache_info().currsize >= 1
    second = P.render_pdf(scan=scan, uav=uav)
    fresh = P.render_pdf(scan=scan, uav=uav, url_fetcher=P.BundledAssetFetcher())
    assert first == second == fresh


def test_the_formulas_heading_is_not_left_alone_at_a_page_foot():
    """The Russian valley report put «Формулы и источники» and its norm-set sentence at the
    foot of sheet 5 and the formula table on sheet 6: the heading and its lead paragraph
    now go with the table."""
    import documents  # the valley's Russian PDF, rendered once per run

    pages = documents.pdf_pages(str(documents.EXAMPLES / "uav-town-valley-2000.toml"), "ru")
    (page,) = [p for p in pages if "Формулы и источники" in p]
    assert "Нормативы:" in page and "Смысл" in page  # the formula table's head


def test_a_film_specification_lists_no_parameter_of_a_digital_camera():
    """The film section's norm parameters leave out what only a UAV plan uses (σ_px, the
    multi-ray model, the altitude ceiling, the aerodrome distance)."""
    from scanplan.norms.schema import DIGITAL_ONLY_PARAMETERS
    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports.wording import param_name

    root = Path(__file__).resolve().parent.parent
    r = plan_project(load_project(root / "examples" / "instruction-2000-film.toml"))
    ns = r.film.job.norm_set
    html = P.render_html(scan=r.film.job, meta=r.meta, spec=r)
    from scanplan.reports.pdfhtml import typeset

    names = {k: str(typeset(param_name(ns, k, "en")))
             for k in DIGITAL_ONLY_PARAMETERS if k in ns.parameters}
    assert names and not [k for k, n in names.items() if n in html]
    assert str(typeset(param_name(ns, "planimetric_accuracy_mm", "en"))) in html  # film's stay
