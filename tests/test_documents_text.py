"""Documents fit to sign (issue 13): the text of every page of every example's PDF and of
every workbook cell and chart, in English and in Russian, holds no internal jargon.

Every project file in ``examples/`` (globbed, so new examples are covered) is planned in
both locales and rendered to spec.pdf and spec.xlsx. The extracted text must not contain

- "seed 0…" (the papers are cited by their references, never by our file names),
- repository paths (``docs/…``, ``….md``, ``….py``, ``norms/…``),
- code identifiers: snake_case names (norm-schema parameters such as
  ``planimetric_accuracy_mm``, message codes such as ``not_interpretable``), and the
  raw values ``instruction`` / ``exact`` / ``paper`` of the norm set,
- project-file syntax: a ``[section]``, a ``[section] key`` or a ``key = value`` (the
  documents say what to do in words; the key belongs in the terminal and the docs),
- command-line flags (``--height-formula``);

and the Russian documents hold no English: no Latin word of 3+ letters outside a short
list of names, units and symbols (camera and lens model names from the catalogue,
"scanplan", GSD/MTF, formula symbols) and outside the user's own text (project name,
customer, ... — shown as typed).
"""

from __future__ import annotations

import io
import re
import zipfile
from functools import cache
from pathlib import Path

import pytest

pypdf = pytest.importorskip("pypdf")
pytest.importorskip("weasyprint")

import documents  # noqa: E402

from scanplan.norms import store as norms_mod  # noqa: E402
from scanplan.project.file import KEYS, load_project  # noqa: E402

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "examples").glob("*.toml"))
LOCALES = ("en", "ru")

_SEED = re.compile(r"seed\s*0", re.IGNORECASE)
_PATH = re.compile(r"\b(?:docs|norms|scanplan|templates|tests|examples|benchmarks)/"
                   r"|\b[\w-]+\.(?:md|py|toml|csv)\b")
_FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]+")
_SNAKE = re.compile(r"\b[a-z][a-z0-9]+(?:_[a-z0-9]+)+\b")
_RAW_VALUES = re.compile(r"\b(?:instruction|exact|paper)\b")  # norm-set values as stored
_PROJECT_KEY = re.compile(r'\[([a-z][a-z.]*)\]\s+([a-z][a-z0-9_]*)(?:\s*=\s*"[^"]*")?')
_SECTION = re.compile(r"\[[a-z][a-z._]*\]")
# a key set to a value; formula symbols (h_c = 0.5 m, k = 2) and words of a sentence
# ("per strip = photos") are not keys: a key is a project-file key or a snake_case name
_KEY_VALUE = re.compile(r"\b(?:[a-z][a-z0-9]+(?:_[a-z0-9]+)+|set|scale|camera|locale|file|"
                        r"polygon|dem|scanner)\s*=\s*[\"«'\w]")
_LATIN_WORD = re.compile(r"[A-Za-z][A-Za-z'’-]*[A-Za-z]")

# Latin words a Russian document may hold: units, symbols and abbreviations of formulas,
# the program's name. Camera/lens/scanner names come from the catalogue (below).
_RU_ALLOWED = {
    "scanplan", "gsd", "mtf", "ln", "sqrt", "exp", "max", "min", "obj", "thr", "mc", "mk",
    "px", "rgb", "jpeg", "tiff", "dpi", "uas-fp",
    "gsdmax",  # GSD with its subscript "max", as a PDF's text joins them
    "epsg", "wgs", "utm",  # coordinate systems are named by their codes (issue 11)
}


def _project_keys() -> set[tuple[str, str]]:
    return {(sec, key) for sec, keys in KEYS.items() for key in keys}


@cache
def _catalogue_words() -> frozenset[str]:
    """Words of the catalogues' model names (the part before any parenthesis)."""
    ns = norms_mod.load_norm_set()
    from scanplan.norms.aircraft import all_aircraft

    names = ([c.name for c in ns.cameras.values()] + list(ns.scanner_names.values())
             + [a.name for a in all_aircraft().values()])  # and the aircraft's models
    words: set[str] = set()
    for name in names:
        model = re.sub(r"\([^)]*\)", " ", name)
        words.update(w.lower() for w in _LATIN_WORD.findall(model))
    return frozenset(words - {"with", "and", "lens", "assumed"})


# Each example is planned once per locale and each document rendered once (the plan, the
# workbook, the PDF's text, page 1's HTML: tests/documents.py): the tests below read them
# many ways.
_planned, _workbook, _page_html = documents.planned, documents.workbook, documents.page_html


@cache
def _documents(example: str, locale: str) -> dict[str, str]:
    """{'pdf page N' / 'xlsx SHEET' / 'xlsx chart N': text} for one example in one locale."""
    out: dict[str, str] = {}
    for i, text in enumerate(documents.pdf_pages(example, locale), 1):
        out[f"pdf page {i}"] = text
    data = _workbook(example, locale)
    wb = documents.loaded_workbook(example, locale)
    for ws in wb.worksheets:
        cells = [ws.title]
        for row in ws.iter_rows():
            cells += [c.value for c in row if isinstance(c.value, str)]
        for hf in (ws.oddHeader, ws.oddFooter):
            cells += [part.text for part in (hf.left, hf.center, hf.right) if part.text]
        out[f"xlsx sheet {ws.title!r}"] = "\n".join(cells)
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        for name in sorted(n for n in z.namelist() if n.startswith("xl/charts/chart")):
            xml = z.read(name).decode("utf-8")
            out[f"xlsx {name}"] = "\n".join(re.findall(r"<(?:a:t|c:v)>([^<]*)</", xml))
    return out


def _user_text(example: str) -> list[str]:
    """The user's own text in the project file (shown as typed, any language)."""
    project = load_project(example)
    texts = [project.name]
    for sec in ("project",):
        for key, value in project.values.get(sec, {}).items():
            if isinstance(value, str) and key != "locale":
                texts.append(value)
    for sec, key in (("terrain", "dem"), ("area", "file")):  # file names, as the user gave
        value = project.values.get(sec, {}).get(key)
        if isinstance(value, str):
            texts.append(Path(value).name)
    return [" ".join(t.split()) for t in texts if t and t.strip()]


def _without_user_text(text: str, example: str) -> str:
    flat = " ".join(text.split())
    for t in sorted(_user_text(example), key=len, reverse=True):
        flat = flat.replace(t, " ")
        if len(t) > 40:  # the running header shortens the project name with an ellipsis
            for n in range(20, len(t)):
                flat = flat.replace(t[:n] + "…", " ")
    return flat


def jargon(text: str) -> list[str]:
    """What in ``text`` is internal jargon (any locale); [] when it is clean."""
    found = []
    found += [f"seed reference {m.group()!r}" for m in _SEED.finditer(text)]
    found += [f"repository path {m.group()!r}" for m in _PATH.finditer(text)]
    found += [f"command-line flag {m.group()!r}" for m in _FLAG.finditer(text)]
    found += [f"project-file section {m.group()!r}" for m in _SECTION.finditer(text)]
    found += [f"project-file setting {m.group()!r}" for m in _KEY_VALUE.finditer(text)]
    found += [f"code identifier {m.group()!r}" for m in _SNAKE.finditer(text)]
    found += [f"raw norm value {m.group()!r}" for m in _RAW_VALUES.finditer(text)]
    return found


def _cited_originals(text: str) -> set[str]:
    """Latin words of the works the text lists in their original language: a Russian
    reference list cites an English work by its English title (GOST R 7.0.100-2018)."""
    from scanplan.reports.references import references

    flat = " ".join(text.split())
    words: set[str] = set()
    for ref in references():
        head = ref.ru.split(".")[0]  # the authors (or the title of a work without them)
        if _LATIN_WORD.search(head) and head in flat:
            words.update(w.lower() for w in _LATIN_WORD.findall(ref.ru))
    return words


def english_in_russian(text: str) -> list[str]:
    """Latin words (3+ letters) in a Russian text that are not names, units or symbols."""
    allowed = _RU_ALLOWED | _catalogue_words() | _cited_originals(text)
    text = _PROJECT_KEY.sub(" ", text)  # a project-file key is typed as it is
    def symbol(w: str) -> bool:  # a formula symbol with its subscript set: H_max → Hmax,
        return w[1:].lower() in allowed  # r_max → rmax (one letter, then a known subscript)
    return sorted({w for w in _LATIN_WORD.findall(text)
                   if len(w) >= 3 and w.lower() not in allowed and not symbol(w)})


CASES = [pytest.param(str(e), loc, id=f"{e.stem}-{loc}") for e in EXAMPLES for loc in LOCALES]


def test_examples_exist():
    assert len(EXAMPLES) >= 3


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_documents_have_no_internal_jargon(example, locale):
    problems = []
    for where, text in _documents(example, locale).items():
        problems += [f"{where}: {p}" for p in jargon(_without_user_text(text, example))]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("example", [str(e) for e in EXAMPLES], ids=[e.stem for e in EXAMPLES])
def test_russian_documents_have_no_english(example):
    problems = []
    for where, text in _documents(example, "ru").items():
        words = english_in_russian(_without_user_text(text, example))
        if words:
            problems.append(f"{where}: {', '.join(words)}")
    assert not problems, "\n".join(problems)


_UNDERSCORE_SYMBOL = re.compile(r"(?<![\w])[A-Za-zσΔ]_[A-Za-z0-9]{1,5}(?![\w])")


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_pdf_sets_the_subscripts_of_its_symbols(example, locale):
    """Bug: the PDF's sentences printed "P_R", "σ_Z", "h_c", "r_max / r_min" with the
    underscore of plain text, where its formula tables set the subscripts as a printed
    instruction does; every text of the PDF now sets them (P<sub>R</sub>)."""
    problems = []
    for where, text in _documents(example, locale).items():
        if where.startswith("pdf"):
            found = _UNDERSCORE_SYMBOL.findall(_without_user_text(text, example))
            if found:
                problems.append(f"{where}: {', '.join(sorted(set(found)))}")
    assert not problems, "\n".join(problems)


# --- the detectors themselves catch what they are for -------------------------------


@pytest.mark.parametrize("text", [
    "Source: seed 001 Table 3", "docs/uav-models.md §1", "planimetric_accuracy_mm 0.2",
    "(--height-formula parallax to use the parallax form.)", "[not_interpretable]",
    "height formula instruction", "rounding exact",
    'set [norms] height_formula = "parallax" in the project file', "raise [uav] max_height_m",
    "([terrain] altitude_mode)", 'Chosen by set = "gkinp-02-036-02"', "a polygon ([area])"])
def test_jargon_detector_catches(text):
    assert jargon(text)


@pytest.mark.parametrize("text", [
    "use the parallax height formula of the norm set", "P_S = V_s·Mk/(k·Mc)",
    "r_max / r_min 0.3 / 0.1", "Instruction GKINP (GNTA)-02-036-02, 2002", "circle, B = 0.97",
    "references [1]; [2]", "h_c = 0.5 m"])
def test_jargon_detector_passes(text):
    assert not jargon(text)


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_no_claim_of_files_that_are_not_written(example, locale):
    """A block with no place on the map (an abstract rectangle) writes no mission, GIS or
    photo-centre files, so its documents never say something is "written beside" them."""
    project = load_project(example)
    if project.values.get("area", {}).get("file") or project.values.get("area", {}).get(
            "polygon"):
        return
    claims = ("written beside", "записанной рядом", "записываются рядом")
    for where, text in _documents(example, locale).items():
        flat = " ".join(text.split())
        assert not [c for c in claims if c in flat], (where, flat[:400])


def test_english_detector():
    assert english_in_russian("Объект: object, круг") == ["object"]
    assert english_in_russian("Источник: Instruction for photogrammetric works") != []
    assert english_in_russian("GSD 0,038 м; P = exp(−(B·L/L_obj)²); scanplan 0.1.0") == []
    assert english_in_russian("[norms] height_formula = «parallax»") == ["parallax"]


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_no_near_empty_last_page(example, locale):
    """The last page carries real content (not a lone signature block or a footer note):
    at least a quarter of the text of an average earlier page."""
    pages = [text for where, text in _documents(example, locale).items()
             if where.startswith("pdf page")]
    if len(pages) < 2:
        return
    mean = sum(len(p) for p in pages[:-1]) / (len(pages) - 1)
    assert len(pages[-1]) >= 0.25 * mean, (len(pages[-1]), mean, pages[-1][:300])


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_signing_blocks_and_sheet_numbers(example, locale):
    """Approval block, compiled/checked lines, references and «Лист N / Листов M»."""
    docs = _documents(example, locale)
    pages = [text for where, text in docs.items() if where.startswith("pdf page")]
    first, last = " ".join(pages[0].split()), " ".join(pages[-1].split())
    n = len(pages)
    if locale == "ru":
        assert "УТВЕРЖДАЮ" in first
        assert "Составил" in last and "Проверил" in last and "Список литературы" in " ".join(
            pages)
        assert all(f"Лист {i} / Листов {n}" in " ".join(p.split())
                   for i, p in enumerate(pages, 1))
        assert re.search(r"Дата \d\d\.\d\d\.\d{4}", first)
    else:
        assert "APPROVED" in first
        assert "Compiled by" in last and "Checked by" in last and "References" in " ".join(
            pages)
        assert all(f"Sheet {i} of {n}" in " ".join(p.split()) for i, p in enumerate(pages, 1))
        assert re.search(r"Date \d{4}-\d\d-\d\d", first)


_TERMINAL_PROJECT = """
[project]
name = "Карта"
locale = "{locale}"
[map]
scale = 10000
relief_interval_m = 1.0
[film]
camera = "rc30-153"
photo_scales = [15000, 20000, 25000, 30000]
scanner = "photoscan-td"
[uav]
camera = "canon-eos-5d-mark-ii-50"
f_number = 8
height_m = 300
"""


@pytest.mark.parametrize("locale", LOCALES)
def test_terminal_summary_speaks_the_projects_language(tmp_path, locale):
    from click.testing import CliRunner

    from scanplan.cli.main import main

    path = tmp_path / "p.toml"
    path.write_text(_TERMINAL_PROJECT.format(locale=locale), encoding="utf-8")
    out = CliRunner().invoke(main, ["plan", str(path)])
    assert out.exit_code == 0, out.output
    text = out.stdout
    if locale == "ru":
        for phrase in ("рекомендуемый масштаб снимков", "размер пикселя сканирования",
                       "рекомендуемая высота полёта", "Предупреждения:", "8,3 мкм"):
            assert phrase in text, phrase
        # no English sentence: the words left are symbols, ids in brackets, names
        body = re.sub(r"\[[a-z]+_[a-z_]+\]", " ", text)  # the codes, not "[norms]"
        assert english_in_russian(body) == [], english_in_russian(body)
    else:
        assert "recommended photo scale" in text and "8.3 µm" in text


@pytest.mark.parametrize("locale", LOCALES)
@pytest.mark.parametrize("example", [str(e) for e in EXAMPLES], ids=[e.stem for e in EXAMPLES])
def test_wrapped_cells_have_room(example, locale):
    """A wrapped cell longer than its column gets a row tall enough for its lines, so it
    does not run over the next row where the row height is taken from the file
    (LibreOffice). In both locales (the example's own is one of them)."""
    import math

    from openpyxl.utils import get_column_letter

    wb = documents.loaded_workbook(example, locale)
    def col_width(c: int) -> float:
        return ws.column_dimensions[get_column_letter(c)].width or 8.43

    for ws in wb.worksheets:
        merged = {(r.min_row, r.min_col): sum(col_width(c) for c in range(r.min_col,
                                                                          r.max_col + 1))
                  for r in ws.merged_cells.ranges}
        for row in ws.iter_rows():
            for cell in row:
                if not (isinstance(cell.value, str) and cell.alignment.wrap_text):
                    continue
                width = merged.get((cell.row, cell.column), col_width(cell.column))
                lines = math.ceil(len(cell.value) / max(width * 1.1 - 1, 4))
                if lines > 1:
                    height = ws.row_dimensions[cell.row].height
                    assert height is not None and height >= 14 * lines, (
                        ws.title, cell.coordinate, lines, height)


@pytest.mark.parametrize("locale", LOCALES)
def test_film_and_uav_document_is_clean_and_ends_on_a_full_page(tmp_path, locale):
    """Film and UAV side by side (the longest document): no jargon, no English in Russian,
    and the references travel with the signatures to the last page."""
    path = tmp_path / "both.toml"
    path.write_text(_TERMINAL_PROJECT.format(locale=locale)
                    + "[area]\nwidth_m = 5000\nlength_m = 6000\n", encoding="utf-8")
    docs = _documents(str(path), locale)
    pages = [t for w, t in docs.items() if w.startswith("pdf page")]
    mean = sum(len(p) for p in pages[:-1]) / (len(pages) - 1)
    assert len(pages[-1]) >= 0.25 * mean
    problems = []
    for where, text in docs.items():
        clean = _without_user_text(text, str(path))
        problems += [f"{where}: {p}" for p in jargon(clean)]
        if locale == "ru":
            problems += [f"{where}: {w}" for w in english_in_russian(clean)]
    assert not problems, "\n".join(problems)


def test_every_warning_has_a_heading_in_both_languages():
    """The page-1 warnings box names each warning by a short heading: every warning code
    the engine can emit has one (``warn_<code>``) in English and Russian."""
    import pathlib

    from scanplan.i18n.labels import LABELS

    src = "".join(p.read_text(encoding="utf-8")
                  for p in pathlib.Path(norms_mod.__file__).parent.parent.rglob("*.py"))
    codes = set(re.findall(r'PlanWarning\(\s*"([a-z_]+)"', src))
    # a warning built from a message: msg = Message("code", ...) … PlanWarning(msg.code, …)
    codes |= set(re.findall(r'msg = Message\(\s*"([a-z_]+)"', src))
    codes |= {"not_interpretable", "above_interpretation_limit"}  # built from a variable
    assert len(codes) >= 10
    for loc in LOCALES:
        missing = sorted(c for c in codes if f"warn_{c}" not in LABELS[loc])
        assert not missing, (loc, missing)


def test_height_limits_print_heights_as_heights():
    """The altitude ceiling's limit is a height (500 m), not a ground size: printed without
    three decimals, so the Russian decimal comma never reads it as 500 000."""
    docs = _documents(str(EXAMPLES[0].parent / "uav-canon-2000.toml"), "ru")
    pdf = "\n".join(v for k, v in docs.items() if k.startswith("pdf"))
    assert re.search(r"HC — предельная\s+высота полёта\s+500\s", pdf), pdf
    assert "500,000" not in pdf


# --- sentences a reader signs (the audit of issue 14) ---------------------------------


def _warning_headings(locale: str) -> list[str]:
    from scanplan.i18n.labels import LABELS

    return [v for k, v in LABELS[locale].items() if k.startswith("warn_")]


@pytest.mark.parametrize("example", [str(e) for e in EXAMPLES], ids=[e.stem for e in EXAMPLES])
def test_english_documents_read_as_sentences(example):
    """A warning after its bold heading, the specification's reason and the survey
    design's notes are sentences in print (the terminal's lower-case ``! motion blur …``
    is not): no "Motion blur. motion blur …", no "strip(s)", no "flown high"."""
    problems = []
    headings = _warning_headings("en")
    for where, text in _documents(example, "en").items():
        flat = " ".join(text.split())
        for h in headings:
            problems += [f"{where}: {m.group()!r}" for m in
                         re.finditer(re.escape(h) + r"\. [a-z]\w*", flat)]
        problems += [f"{where}: {m.group()!r}" for m in
                     re.finditer(r"\w+\(s\)|flown high\b|by m:", flat)]
    assert not problems, "\n".join(problems)


def test_height_error_names_the_highest_flown_height_as_the_tables_do():
    """σ_Z is stated at the highest flown height as the results table heads it (148.5 m
    for 135 m + 10 %), not rounded half-to-even to 148 m."""
    docs = _documents(str(EXAMPLES[0].parent / "uav-town-2000.toml"), "en")
    pdf = " ".join(" ".join(v.split()) for k, v in docs.items() if k.startswith("pdf"))
    assert "at 148.5 m" in pdf
    assert "at the highest flown height 148.5 m" in pdf, pdf[:2000]
    assert "highest flown height 148 m" not in pdf


@pytest.mark.parametrize(("locale", "label"), [("en", "Forward / side overlap, %"),
                                               ("ru", "Продольное / поперечное перекрытие, %")])
def test_inputs_name_both_overlaps_with_one_unit(locale, label):
    """The inputs table's overlaps row: "Forward / side overlap, %", not
    "Forward overlap, % / Side overlap"."""
    docs = _documents(str(EXAMPLES[0].parent / "uav-canon-2000.toml"), locale)
    pdf = " ".join(" ".join(v.split()) for k, v in docs.items() if k.startswith("pdf"))
    assert "% / Side overlap" not in pdf and "% / Поперечное" not in pdf
    assert label in pdf


@pytest.mark.parametrize("locale", LOCALES)
def test_relief_film_probability_says_which_frame(locale):
    """Over the relief page 1's recognition probability is the one at the frame over the
    lowest ground (0.83 at 1:7200), not the results table's 0.88 at 1:6000: it says so."""
    docs = _documents(str(EXAMPLES[0].parent / "film-town-relief-10000.toml"), locale)
    first = " ".join(docs["pdf page 1"].split())
    label = ("Recognition probability at the frame over the lowest ground" if locale == "en"
             else "Вероятность распознавания на снимке над наинизшей точкой")
    assert label in first
    summary = next(v for k, v in docs.items() if k.startswith("xlsx sheet"))
    assert label in " ".join(summary.split())


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_citations_read_cleanly(example, locale):
    """A cited work's locator follows its number directly: "[3], Table B.1", never
    "[3], (Table B.1)" (a parenthesis after the comma the citation adds)."""
    problems = []
    for where, text in _documents(example, locale).items():
        flat = " ".join(text.split())
        problems += [f"{where}: {flat[max(0, m.start() - 40):m.end() + 20]!r}"
                     for m in re.finditer(r"\], \(", flat)]
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("locale", LOCALES)
def test_scan_pixel_arrow_is_explained(locale):
    """Page 1's "12.5 → 7.0" names what the arrow joins (the required pixel and the
    scanner's step)."""
    docs = _documents(str(EXAMPLES[0].parent / "instruction-2000-film.toml"), locale)
    first = " ".join(docs["pdf page 1"].split())
    label = ("Scan pixel, µm (required → the scanner's step) 12.5 → 7.0" if locale == "en"
             else "Размер пикселя сканирования, мкм (расчётный → шаг сканера) 12,5 → 7,0")
    assert label in first, first[:1500]


@pytest.mark.parametrize(("example", "locale"), [
    pytest.param(str(e), loc, id=f"{e.stem}-{loc}") for e in EXAMPLES for loc in LOCALES])
def test_no_page_holds_only_a_heading(example, locale):
    """Every page carries content: none holds only its running head, a section heading
    and the sheet number (a long table pushed whole to the next page)."""
    pages = [" ".join(v.split()) for k, v in _documents(example, locale).items()
             if k.startswith("pdf page")]
    short = [(i, p) for i, p in enumerate(pages, 1) if len(p) < 160]
    assert not short, short


@pytest.fixture(scope="module")
def valley_constant(tmp_path_factory):
    """The valley at one altitude (the example leaves the mode to scanplan)."""
    from terrain_helpers import valley_pinned

    return str(valley_pinned(tmp_path_factory.mktemp("valley")))


@pytest.mark.parametrize("locale", LOCALES)
def test_relief_maximum_height_stands_beside_the_flat_one(locale, valley_constant):
    """Over a DEM the plan is lowered to 70 m because the worst photo meets HC only up to
    72 m at one altitude: page 1, the survey design and the summary sheet show that 72 m
    beside the flat-ground 136 m (not a bare "maximum 136 m" above a recommended 70 m)."""
    docs = _documents(valley_constant, locale)
    flat_label, relief_label = (
        ("Maximum planned flight height on flat ground, m 136",
         "Maximum planned flight height over the relief (above the reference ground), m 72")
        if locale == "en" else
        ("Максимальная плановая высота полёта для плоской местности, м 136",
         "Максимальная плановая высота полёта с учётом рельефа (над опорной отметкой), м 72"))
    first = " ".join(docs["pdf page 1"].split())
    assert flat_label in first and relief_label in first, first[:1500]
    pdf = " ".join(" ".join(v.split()) for k, v in docs.items() if k.startswith("pdf"))
    assert pdf.count(relief_label.rsplit(" ", 1)[0]) >= 2  # page 1 and the survey design
    sheets = " ".join(" ".join(v.split()) for k, v in docs.items() if k.startswith("xlsx"))
    assert relief_label.rsplit(" ", 1)[0] in sheets


def test_flat_ground_documents_keep_one_maximum_height():
    docs = _documents(str(EXAMPLES[0].parent / "uav-town-2000.toml"), "en")
    pdf = " ".join(" ".join(v.split()) for k, v in docs.items() if k.startswith("pdf"))
    assert "over the relief (above" not in pdf and "on flat ground" not in pdf
    assert "Maximum planned flight height, m 136" in pdf


def test_summary_box_lists_a_warning_once_with_its_scales():
    """The workbook's warnings box names each kind of warning once, with every photo scale
    it concerns ("P_R drives the data volume: 1:6000, 1:8000"), and the Warnings sheet
    heads that column "Warning"."""
    docs = _documents(str(EXAMPLES[0].parent / "instruction-2000-film.toml"), "en")
    summary = docs["xlsx sheet 'Summary'"]
    lines = [x for x in summary.splitlines() if x.startswith("i P_R drives the data volume")]
    assert lines == ["i P_R drives the data volume: 1:6000, 1:8000"], lines  # information
    assert docs["xlsx sheet 'Warnings'"].splitlines()[1:4] == ["Section", "Severity", "Warning"]


def _page_one_warnings(example: str, locale: str, box: str = "warnbox") -> list[str]:
    """The items of page 1's warnings box (``box="warnbox notebox"``: its box of information
    and conditions checked), from the HTML the PDF is made of."""
    import html as html_mod

    page = _page_html(example, locale)
    box = re.search(rf'<div class="{box}">.*?<ul>(.*?)</ul>', page, re.S)
    items = re.findall(r"<li>(.*?)</li>", box[1], re.S) if box else []
    # a subscript as the source writes it: P<sub>R</sub> → P_R
    return [html_mod.unescape(re.sub(r"<sub>(.*?)</sub>", r"_\1", x)).strip() for x in items]


@pytest.mark.parametrize("locale", LOCALES)
@pytest.mark.parametrize("example", [str(e) for e in EXAMPLES], ids=[e.stem for e in EXAMPLES])
def test_page_one_lists_each_kind_of_warning_once(example, locale):
    """Page 1's warnings: one item per kind of warning with all its photo scales ("P_R
    drives the data volume: 1:6000, 1:8000"), as the workbook's box, not one per scale."""
    for box in ("warnbox", "warnbox notebox"):
        heads = [item.split(": 1:")[0] for item in _page_one_warnings(example, locale, box)]
        assert len(heads) == len(set(heads)), heads


def test_page_one_groups_the_photo_scales_of_a_warning():
    items = _page_one_warnings(str(EXAMPLES[0].parent / "instruction-2000-film.toml"), "en",
                               "warnbox notebox")  # information: nothing to act on
    assert "P_R drives the data volume: 1:6000, 1:8000" in items, items


@pytest.mark.parametrize("locale", LOCALES)
def test_page_one_says_why_the_valley_plan_was_lowered(locale, valley_constant):
    """Over the valley the plan is lowered from 135 m to 70 m: page 1 lists the lowering once
    (its why is in the warning's text), not the finding at 135 m as a fault of the plan
    that is flown."""
    from scanplan.i18n.labels import LABELS

    items = _page_one_warnings(valley_constant, locale)
    heads = [x.split(" — ")[0] for x in items]  # "… — see “Specification”"
    assert LABELS[locale]["warn_terrain_resolution"] not in heads, items
    assert heads.count(LABELS[locale]["warn_height_lowered"]) == 1, items


def test_russian_page_one_lists_scales_as_the_messages_do():
    """Russian lists are joined by '; ' (the comma is the decimal separator), as the
    messages and the workbook's box list them; page 1 said '1:6000, 1:8000'."""
    items = _page_one_warnings(str(EXAMPLES[0].parent / "instruction-2000-film.toml"), "ru",
                               "warnbox notebox")
    assert "Объём данных определяет P_R: 1:6000; 1:8000" in items, items


@pytest.mark.parametrize(("locale", "sep"), [("en", ","), ("ru", "\u00a0")])
def test_the_photo_count_is_written_one_way_in_the_pdf(locale, sep, valley_constant):
    """The valley's 16,000-odd photos at one altitude: page 1, the flight geometry ('strips /
    photos') and the flight-lines table group the count alike (the geometry said 88 /
    16432)."""
    example = valley_constant
    result = _planned(example, locale)
    assert result.film is None  # page 1 is the UAV plan's alone
    page = _page_html(example, locale)
    n = int(result.uav.job.plan.flight["photos"])
    assert n > 10000
    photos = f"{n // 1000}{sep}{n % 1000:03d}"
    assert f"{result.uav.job.plan.flight['strips']} / {photos}" in page
    assert str(n) not in page


@pytest.mark.parametrize("locale", LOCALES)
@pytest.mark.parametrize(("example", "source"), [
    ("uav-town-valley-2000", {"en": "digital elevation model town-valley.tif, EPSG:32637",
                              "ru": "цифровая модель рельефа town-valley.tif, EPSG:32637"}),
    ("uav-town-2000-afs", {"en": "the range of ground elevations given for the area",
                           "ru": "диапазон отметок, заданный для участка"})])
def test_terrain_pdfs_state_the_dem_the_ground_and_the_altitude(example, source, locale):
    """The crew and the approver read on paper what the terminal prints: where the ground
    heights come from, the ground under the photos, the flight altitude above sea level."""
    path = next(e for e in EXAMPLES if e.stem == example)
    result = _planned(str(path), locale)  # the ground does not depend on the locale
    tr = result.uav.terrain
    d = tr.summary()
    pages = [t for w, t in _documents(str(path), locale).items() if w.startswith("pdf")]
    flat = " ".join(" ".join(pages).split()).replace("\u00a0", " ")
    words = {"en": ("Ground heights from", "Ground under the photos",
                    "Flight altitude above sea level"),
             "ru": ("Отметки рельефа", "Отметки под снимками", "Высота полёта над уровнем моря")}
    for w in words[locale]:
        assert w in flat, w
    assert source[locale].replace(" ", "") in flat.replace(" ", "")  # lines wrap anywhere
    sep = "." if locale == "en" else ","
    lo = f"{d['ground_min_m']:.1f}".replace(".", sep)
    hi = f"{d['ground_max_m']:.1f}".replace(".", sep)
    assert f"{lo}–{hi}" in flat
    alt = tr.layout.photos["altitude_m"]
    assert f"{float(alt.max()):,.0f}".replace(",", " ") in flat


@pytest.mark.parametrize(("example", "locale"), CASES)
def test_signed_numbers_have_one_sign(example, locale):
    """A margin below the binding constraint is −21 %, never +-21 %."""
    for where, text in _documents(example, locale).items():
        assert not re.search(r"\+\s*[-−]|[-−]\s*\+", text), where


_DECIMAL_POINT = re.compile(r"(?<![\d.])\d+\.\d+(?![\d.])")
# where a point between digits is not a decimal sign: standards' and clauses' numbers,
# tables, dates, versions, the reference list's imprints, coordinate system names
_NOT_DECIMAL = re.compile(r"ГОСТ|GOST|ГКИНП|EPSG|[Тт]абл|п\. |пп\. |§|scanplan|\d\.\d+\.\d|"
                          r"UTM|[БB]\.\d|Vol\.|p\. |С\. |ed\.|изд\.")


@cache
def _model_names() -> tuple[str, ...]:
    """Catalogue model names as the maker writes them (``f/1.4``, ``F2.8`` stay)."""
    ns = norms_mod.load_norm_set()
    return tuple(c.name for c in ns.cameras.values())


@pytest.mark.parametrize("example", [str(e) for e in EXAMPLES], ids=[e.stem for e in EXAMPLES])
def test_russian_documents_use_the_decimal_comma(example):
    """«B = 0,97», never «B = 0.97»: every number of a Russian document has the decimal
    comma (the maker's model names such as «F2.8» are quoted as written)."""
    problems = []
    for where, text in _documents(example, "ru").items():
        flat = " ".join(text.split())
        for m in _DECIMAL_POINT.finditer(flat):
            around = flat[max(0, m.start() - 50):m.end() + 30]
            if _NOT_DECIMAL.search(flat[max(0, m.start() - 14):m.end()]):
                continue
            if any(m.group() in name and name.split()[0] in around
                   for name in _model_names()):
                continue
            problems.append(f"{where}: …{around}…")
    assert not problems, "\n".join(problems)
