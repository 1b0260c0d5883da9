"""The presentation pipeline's shape, checked from the sources: a result → the locale-free
views (``reports/views/``) → one ``Formatter(locale)`` → thin layouts → ``reports/
documents.py``, the only path that renders and writes documents (docs/architecture.md,
"From a result to a printed word").

Each test is one acceptance check of that shape; the checks that read outputs render
the examples' documents (their HTML, which is the PDF's text) and the terminal.
"""

from __future__ import annotations

import ast
import re
from collections import defaultdict
from pathlib import Path

import pytest

import scanplan

PKG = Path(scanplan.__file__).parent
REPORTS = PKG / "reports"

#: The modules of ``reports/`` that are no layout: the views, the formatter, the one
#: document path, the JSON document (no words, no locale: the keys are the contract), the
#: exported files of ``plan --out`` (geo/ writes them), the bibliography and the names of
#: norm-set items the formatter words, and the speed-ups of WeasyPrint's import.
NOT_LAYOUTS = {"views", "formatter.py", "documents.py", "jsondoc.py", "exports.py",
               "references.py", "wording.py", "__init__.py", "_weasy.py", "view.py"}


#: A check the branch does not meet yet (strict: it fails until it passes, then this mark
#: must go).


def _layouts() -> list[Path]:
    """Every layout module: ``reports/`` but :data:`NOT_LAYOUTS`."""
    out = []
    for path in sorted(REPORTS.rglob("*.py")):
        first = path.relative_to(REPORTS).parts[0]
        if first not in NOT_LAYOUTS:
            out.append(path)
    return out


def _web() -> list[Path]:
    return sorted((PKG / "web").rglob("*.py"))


def _rel(path: Path) -> str:
    return path.relative_to(PKG).as_posix()


def _tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(encoding="utf-8"))


def _type_checking_nodes(tree: ast.Module) -> set[int]:
    """The ids of the nodes under ``if TYPE_CHECKING:`` (type hints only)."""
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            for child in node.body:
                out |= {id(n) for n in ast.walk(child)}
    return out


def _imports(path: Path) -> list[tuple[int, str]]:
    """(line, absolute module) of every import in ``path`` but the type hints'."""
    tree = _tree(path)
    hints = _type_checking_nodes(tree)
    parts = list(path.relative_to(PKG.parent).with_suffix("").parts)
    package = parts[:-1]  # a module's package; an __init__'s is its folder
    out = []
    for node in ast.walk(tree):
        if id(node) in hints:
            continue
        if isinstance(node, ast.ImportFrom):
            base = package[: len(package) - (node.level - 1)] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            out.append((node.lineno, target))
            out += [(node.lineno, f"{target}.{a.name}") for a in node.names]
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
    return out


def _calls(path: Path) -> list[tuple[int, str]]:
    """(line, called name) of every call in ``path`` (``f(…)`` and ``x.f(…)``)."""
    out = []
    for node in ast.walk(_tree(path)):
        if isinstance(node, ast.Call):
            func = node.func
            name = func.id if isinstance(func, ast.Name) else (
                func.attr if isinstance(func, ast.Attribute) else "")
            out.append((node.lineno, name))
    return out


# -- 1. one formatter ---------------------------------------------------------------------

FORMATTERS = {"Numbers", "Labels", "Formatter"}
"""The classes that word or format a number for a reader."""
ADAPTERS = {"_Words", "_Fmt", "_W", "_Terminal", "Labels"}
"""Former per-renderer adapters of the catalogue and the number format."""


def test_1_formatters_are_made_in_one_module():
    """``Numbers(``-style formatters are constructed in one module of ``reports/`` (and
    nowhere above it); no adapter class wraps them again; the API has no ``_fmt``."""
    found = []
    home = REPORTS / "formatter.py"
    above = [*REPORTS.rglob("*.py"), *_web(), *(PKG / "cli").rglob("*.py"), PKG / "api.py"]
    for path in above:
        if path == home:
            continue
        found += [f"{_rel(path)}:{line} constructs {name}" for line, name in _calls(path)
                  if name in FORMATTERS]
        for node in ast.walk(_tree(path)):
            if isinstance(node, ast.ClassDef) and node.name in ADAPTERS:
                found.append(f"{_rel(path)}:{node.lineno} defines the adapter {node.name}")
            if isinstance(node, ast.FunctionDef) and path.name == "api.py" \
                    and node.name == "_fmt":
                found.append(f"api.py:{node.lineno} formats numbers itself (_fmt)")
    assert home.is_file(), "reports/formatter.py holds the one Formatter"
    assert not found, "\n".join(found)


# -- 2. layouts and the page import no engine --------------------------------------------

ENGINE_FORMULAS = {"jpeg_volume_bytes", "height_at_photo_scale_m", "photo_scale_at_height",
                   "ground_sample_distance_m", "data_volume_bytes"}


PAGE_INPUTS = {
    "web/basemap.py": (("scanplan.geo.basemap", "scanplan.geo.tiles"),
                       "the page's own background: an uploaded orthophoto warped to the web "
                       "map's tiles in the worker, the tile sources and their cache — an "
                       "input of the page, not a figure of a result"),
}
"""A module of ``web/`` that reads an input of the page itself with the engine's reader:
the module, the engine modules it may import and why."""


def test_2_layouts_and_the_page_import_no_engine():
    """No layout and no module of ``web/`` imports ``scanplan.core`` or ``scanplan.geo``
    (type hints aside), and none calls the engines' formulas; nothing in ``reports/``
    computes the JPEG volume (the result carries it)."""
    found = []
    for path in [*_layouts(), *_web()]:
        allowed = PAGE_INPUTS.get(_rel(path), ((),))[0]
        found += [f"{_rel(path)}:{line} imports {target}" for line, target in _imports(path)
                  if re.match(r"scanplan\.(core|geo)(\.|$)", target)
                  and not target.startswith(tuple(allowed))]
        found += [f"{_rel(path)}:{line} calls {name}" for line, name in _calls(path)
                  if name in ENGINE_FORMULAS]
    for path in REPORTS.rglob("*.py"):
        found += [f"{_rel(path)}:{line} computes the JPEG volume" for line, name
                  in _calls(path) if name == "jpeg_volume_bytes"]
    assert not found, "\n".join(found)


# -- 3. layouts read views, not plans ----------------------------------------------------

PLAN_ATTRIBUTES = {"inputs", "plan", "heights_m"}


def test_3_layouts_read_no_plan_attribute():
    """A layout reads no plan attribute directly (``.inputs``, ``.plan``, ``.heights_m``):
    what it shows comes from the views."""
    found = []
    for path in [*_layouts(), *_web()]:
        for node in ast.walk(_tree(path)):
            if isinstance(node, ast.Attribute) and node.attr in PLAN_ATTRIBUTES:
                found.append(f"{_rel(path)}:{node.lineno} reads .{node.attr}")
    assert not found, f"{len(found)} reads:\n" + "\n".join(found)


# -- 4. one terminal renderer, no localized view beside views/ ---------------------------


def test_4_one_terminal_renderer_and_no_localized_view():
    """The terminal reports of ``plan``, ``scan`` and ``uav`` are laid out by one
    renderer (the package ``reports/text/``), and no module beside ``views/`` builds a
    view of its own (a class ``…View`` holding worded rows)."""
    defined: dict[str, list[str]] = defaultdict(list)
    views = []
    for path in REPORTS.rglob("*.py"):
        for node in ast.walk(_tree(path)):
            if isinstance(node, ast.FunctionDef) and node.name in (
                    "format_plan_result", "format_scan_plan", "format_uav_plan"):
                defined[node.name].append(_rel(path))
            if isinstance(node, ast.ClassDef) and node.name.endswith("View") \
                    and "views" not in path.relative_to(REPORTS).parts \
                    and node.name != "ReportView":
                views.append(f"{_rel(path)}:{node.lineno} {node.name}")
    homes = {p.rpartition("/")[0] for paths in defined.values() for p in paths}
    assert len(defined) == 3 and all(len(v) == 1 for v in defined.values()), dict(defined)
    assert homes == {"reports/text"}, dict(defined)
    assert not (REPORTS / "terminal.py").exists()
    assert not views, views


# -- 5. label keys name concepts ---------------------------------------------------------


def test_5_no_label_key_is_named_after_a_renderer():
    from scanplan.i18n.labels import AIRCRAFT_LABELS, LABELS

    keys = set(LABELS["en"]) | set(AIRCRAFT_LABELS["en"])
    bad = sorted(k for k in keys if k.startswith(("xlsx_", "pdf_", "term_", "design_")))
    assert not bad, f"{len(bad)} keys: {bad}"


# -- 6. every catalogue in i18n/ -----------------------------------------------------------


def _en_ru_dicts(path: Path) -> list[int]:
    lines = []
    for node in ast.walk(_tree(path)):
        keys: set[object] = set()
        if isinstance(node, ast.Dict):
            keys = {k.value for k in node.keys if isinstance(k, ast.Constant)}
        elif isinstance(node, ast.Call) and getattr(node.func, "id", "") == "dict":
            keys = {k.arg for k in node.keywords}
        if {"en", "ru"} <= keys:
            lines.append(node.lineno)
    return lines


def test_6_no_en_ru_catalogue_outside_i18n():
    found = [f"{_rel(p)}:{line}" for p in sorted(PKG.rglob("*.py"))
             if p.relative_to(PKG).parts[0] != "i18n" for line in _en_ru_dicts(p)]
    assert not found, f"{len(found)} dicts with 'en' and 'ru' keys:\n" + "\n".join(found)


# -- 7. one Russian word per concept -----------------------------------------------------

#: Concepts whose English word is shared by two things the Russian tells apart, with the
#: reason (the concept as compared: the English text's first phrase — up to a comma, a
#: bracket, a colon, a slash or a dash — in lower case).
TWO_WORDS = {
    "aerial survey": "a workbook sheet's name holds 31 characters: «Аэрофотосъёмка» names "
                     "the sheet of «Аэрофотосъёмка цифровой камерой»",
    "area": "«площадь» (a size, km²) and «участок» (the place surveyed)",
    "data volume": "«объём данных без сжатия» (uncompressed, alone) and «объём данных» "
                   "(given with its JPEG estimate beside it)",
    "easting": "a single coordinate («Y» in the geodetic convention) and a pair of them "
               "(«координаты X, Y»)",
    "film": "«плёнка» (the medium: the comparison's column), «плёночная» (a camera's kind) "
            "and «плёночная аэрофотосъёмка» (the film survey's section)",
    "frame": "«формат кадра» (a frame's size, mm) and «снимок» (one photo)",
    "frames": "«число снимков» (a count) and «кадры» (the sheet listing them)",
    "ground control points": "«опознаки» (the markers, counted) and «по опознакам» (the "
                             "control's mode: «привязка по опознакам»)",
    "highlighted": "two notes under two tables whose first words are the same",
    "id": "«обозначение» (a constraint's) and «камера» (the column of camera ids)",
    "name": "«Ф. И. О.» (a signer's) and «имя» (a norm set's)",
    "not resolvable": "a value («не разрешается») and a warning's heading that names its "
                      "subject («объект не разрешается»)",
    "photos": "«снимки» (a sheet, a layer) and «снимков» (the genitive after a count: "
              "«снимков / маршрутов: 120 / 4»)",
    "sorties": "«вылеты» (a list), «число вылетов» (a count) and «вылетов» (the genitive "
               "after a count)",
    "survey precision of the markers": "two figures, «в плане» and «по высоте» (the English "
                                       "names differ after the comma: horizontal, vertical)",
    "strips": "«маршруты» (a list) and «маршрутов» (the genitive after a count)",
    "unit": "«ед. изм.» in the documents' tables and «ед.» in a narrow terminal column",
}


def _normalized(text: str) -> str:
    """A text's first phrase in lower case: what it names before its unit, remark or
    value (``Flight length, km / time, min`` → ``flight length``)."""
    return re.split(r"[,(:/;]| — | – ", text.strip())[0].strip().lower()


def concept_words() -> dict[str, dict[str, list[str]]]:
    """English concept → {Russian word: [catalogue:key, …]} over every catalogue of
    ``i18n/`` and the constraint registry's names."""
    from scanplan.i18n import catalogues
    from scanplan.rules.registry import CONSTRAINTS

    seen: dict[str, dict[str, list[str]]] = defaultdict(lambda: defaultdict(list))
    for name, cat in catalogues().items():
        for key, en in cat["en"].items():
            ru = cat["ru"].get(key)
            if isinstance(en, str) and isinstance(ru, str) and _normalized(en) \
                    and "{" not in _normalized(en):
                seen[_normalized(en)][_normalized(ru)].append(f"{name}:{key}")
    for cid, rec in CONSTRAINTS.items():
        seen[_normalized(rec.title("en"))][_normalized(rec.title("ru"))].append(
            f"constraint:{cid}")
    return seen


def test_7_one_russian_word_per_concept():
    split = {en: dict(rus) for en, rus in concept_words().items()
             if len(rus) > 1 and en not in TWO_WORDS}
    report = "\n".join(f"{en!r}: {rus}" for en, rus in sorted(split.items()))
    assert not split, f"{len(split)} concepts with two Russian words:\n{report}"
    unused = set(TWO_WORDS) - {en for en, rus in concept_words().items() if len(rus) > 1}
    assert not unused, f"allowed but no longer split: {sorted(unused)}"


# -- 8. documents rendered by one path ---------------------------------------------------

RENDERERS = {"render_pdf", "render_xlsx", "write_pdf", "write_xlsx", "html_to_pdf",
             "render_html", "summary_xlsx"}
RENDERER_HOMES = {"reports/documents.py", "reports/pdf.py", "reports/pdfhtml.py",
                  "reports/pdfrender.py", "reports/pdfworker.py", "reports/excel/__init__.py",
                  "reports/summary.py"}


def test_8_documents_are_rendered_only_by_documents_py():
    found = []
    for path in sorted(PKG.rglob("*.py")):
        if _rel(path) in RENDERER_HOMES:
            continue
        found += [f"{_rel(path)}:{line} calls {name}" for line, name in _calls(path)
                  if name in RENDERERS]
        found += [f"{_rel(path)}:{line} imports {target}" for line, target in _imports(path)
                  if target.rpartition(".")[2] in RENDERERS]
    import scanplan.reports.excel as excel
    import scanplan.reports.pdf as pdf

    side_doors = [n for n, m in (("write_pdf", pdf), ("write_xlsx", excel)) if hasattr(m, n)]
    assert not found, "\n".join(found)
    assert not side_doors, f"public writers beside documents.py: {side_doors}"


# -- 9. what a reader sees: numbers, subscripts, the Russian words ------------------------

#: Examples whose documents the check reads (a UAV plan with heights over 1,000 m, a
#: UAV plan over a polygon with thousands of photos, film and UAV side by side, an archive).
READ = ("aerial-ultracam-5000", "uav-town-2000", "uav-canon-2000", "archive-12000-for-2000")
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"  # the repository's, not the package's
_UNIT = r"(?:m|м|km|км|MB|МБ|GB|ГБ|px|пикс|photos|снимк\w*|frames|min|мин)\b"


def _document_text(example: str, locale: str) -> dict[str, str]:
    """What a reader sees of an example: the PDF's text (its HTML, with the charts' SVG
    text), the workbook's text cells, the terminal summary."""
    import base64
    import dataclasses
    import html as html_mod
    import io

    import openpyxl

    from scanplan.project.file import load_project
    from scanplan.project.spec import plan_project
    from scanplan.reports import documents
    from scanplan.reports.pdfhtml import render_html
    from scanplan.reports.text import format_plan_result
    from scanplan.reports.view import build_view

    r = plan_project(load_project(EXAMPLES / f"{example}.toml"))
    r = dataclasses.replace(r, meta=dataclasses.replace(r.meta, locale=locale))
    jobs = {"scan": r.film.job if r.film else None, "uav": r.uav.job if r.uav else None,
            "meta": r.meta, "spec": r}
    page = render_html(view=build_view(**jobs))
    svgs = [base64.b64decode(m).decode("utf-8") for m in
            re.findall(r"data:image/svg\+xml;base64,([A-Za-z0-9+/=]+)", page)]
    texts = [page] + [" ".join(re.findall(r"<text[^>]*>([^<]*)</text>", s)) for s in svgs]
    pdf = html_mod.unescape(re.sub(r"<[^>]+>", " ", re.sub(r"<style.*?</style>", " ",
                                                          "\n".join(texts), flags=re.S)))
    book = openpyxl.load_workbook(io.BytesIO(documents.render(("xlsx",), **jobs)["xlsx"]))
    cells = [str(c.value) for ws in book.worksheets for row in ws.iter_rows() for c in row
             if isinstance(c.value, str)]
    return {"pdf": pdf, "xlsx": "\n".join(cells), "terminal": format_plan_result(r)}


@pytest.fixture(scope="module")
def read_texts() -> dict[tuple[str, str], dict[str, str]]:
    return {(ex, loc): _document_text(ex, loc) for ex in READ for loc in ("en", "ru")}


def test_9_numbers_are_grouped_alike_in_prose_and_tables():
    """A number of 1,000 or more reads the same in an engine sentence, a table's cell and
    the terminal, in both languages."""
    from scanplan.i18n.messages import Message
    from scanplan.reports.formatter import formatter

    for loc, grouped in (("en", "2,093"), ("ru", "2\u00a0093")):
        f = formatter(loc)
        assert f.num(2093.2, 0) == f.g(2093.0) == f.fixed(2093.2, 0) == grouped
        assert grouped in Message("spec.uav_within", max=2093.2).text(loc)
        assert f.short(12500.0) == f.num(12500, 0) and f.sig(2093.46) == grouped


def test_9_no_ungrouped_number_with_a_unit_in_any_document(read_texts):
    found = {(*key, part): re.findall(rf"(?<![\d.,:/\-\w])\d{{4,}}(?:[.,]\d+)?\s?{_UNIT}",
                                      text)
             for key, parts in read_texts.items() for part, text in parts.items()}
    assert not {k: v for k, v in found.items() if v}


def test_9_no_underscore_between_letters_in_a_pdf(read_texts):
    found = {key: sorted(set(re.findall(r"[A-Za-zА-Яа-яσΔ]+_[A-Za-zА-Яа-я0-9]+",
                                        parts["pdf"])))
             for key, parts in read_texts.items()}
    assert not {k: v for k, v in found.items() if v}


def test_9_no_latin_gsd_in_russian_documents_but_as_a_symbol(read_texts):
    """In Russian the ground sample distance is «размер пикселя на местности»; GSD is only
    a symbol of the formulas (``GSD = p·H/f``, ``GSD_max``), defined in the list of
    symbols of the document."""
    for (example, locale), parts in read_texts.items():
        for part in ("pdf", "xlsx") if locale == "ru" else ():
            text = parts[part]
            symbols = text.find("Условные обозначения")
            listed = text[symbols:symbols + 800] if symbols >= 0 else ""
            rest = text.replace(listed, " ")
            loose = [m.start() for m in re.finditer(r"GSD", rest)
                     if not re.match(r"GSD(?:_max|\s?max)?\s*[=≤(]", rest[m.start():])]
            assert not loose, (example, part, [rest[i - 40:i + 40] for i in loose[:5]])
            if "GSD" in rest:
                assert re.search(r"GSD\s+размер пикселя на местности", listed), (example, part)


# -- 10. the Python API as a type checker and a user see it ------------------------------

USER_SCRIPT = '''\
import scanplan

good = scanplan.uav(height_m=100, camera="dji-zenmuse-p1-35", map_scale=2000)
print(good.gsd_m, good.to_frame())
bad_keyword = scanplan.uav(hieght_m=100, camera="dji-zenmuse-p1-35")
bad_type = scanplan.uav(height_m=100, camera=5)
film = scanplan.scan(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000])
result: scanplan.ProjectResult = scanplan.plan("project.toml")
files = result.write("out", formats=["xlsx", "gis"])
'''


def test_10_a_type_checker_reads_the_api(tmp_path):
    """``python -m mypy`` on a user's script flags a misspelt keyword and a wrong type of
    ``scanplan.uav`` (the package is typed, py.typed; its signatures come from the input
    registry) and nothing of the rest."""
    import subprocess
    import sys

    from scanplan.project.signature import typed_block

    api = (PKG / "api.py").read_text(encoding="utf-8")
    assert typed_block() in api, "regenerate: python -m scanplan.project.signature " \
        "scanplan/api.py"
    assert (PKG / "py.typed").is_file()
    script = tmp_path / "user.py"
    script.write_text(USER_SCRIPT, encoding="utf-8")
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--follow-imports=silent", "--no-error-summary",
         "--cache-dir", str(tmp_path / "cache"), "--python-version", "3.11", str(script)],
        capture_output=True, text=True, check=False, cwd=tmp_path)
    lines = [line for line in done.stdout.splitlines() if ": error:" in line]
    assert any(":5:" in line and '"hieght_m"' in line for line in lines), done.stdout
    assert any(":6:" in line and '"camera"' in line and '"int"' in line for line in lines), \
        done.stdout
    assert len(lines) == 2, done.stdout


# -- a table every layout shows: the plans compared ---------------------------------------


def test_the_plans_compared_have_one_entry_in_each_registry_and_words_by_concept():
    """The plans compared are one table (``views/plans.py``), worded once
    (``planwords.py``, through the document's Formatter) and laid out by one entry of each
    layout's registry: a PDF section, a workbook sheet, a part of the terminal summary."""
    from scanplan.reports.excel import SHEETS
    from scanplan.reports.pdfhtml import PDF_SECTIONS
    from scanplan.reports.text.plan import PLAN_PARTS

    for names in ([s.name for s in PDF_SECTIONS], [s.name for s in SHEETS],
                  [p.name for p in PLAN_PARTS]):
        assert names.count("plans") == 1, names
    pdf = [s.name for s in PDF_SECTIONS]
    assert pdf.index("plans") == pdf.index("spec") + 1  # right after the specification
    words = (REPORTS / "planwords.py").read_text(encoding="utf-8")
    assert not re.search(r"""["'](?:term|xlsx|pdf|design)_""", words)
    assert not [name for _, name in _calls(REPORTS / "planwords.py")
                if name in FORMATTERS | {"t", "localize"}]


def test_the_plans_cells_are_formatted_by_the_documents_formatter():
    """A plan's cells read as every other figure of the document: counts grouped by the
    language's rule (a no-break space in Russian), the verdict and the marks in the
    catalogue's words; an estimate's counts with ≈."""
    from scanplan.i18n.messages import Message
    from scanplan.reports.formatter import formatter
    from scanplan.reports.planwords import plan_cells, plan_head
    from scanplan.reports.views import Row

    row = Row("auto", (Message("plan_choice.mode.follow"), 97.6, 115.0, 6217, 834.2, 167.4,
                       4, (1.44, 2.24), "HC", ()), flags=frozenset({"recommended"}),
              fields={"findings": ()})
    en, ru = plan_cells(row, formatter("en")), plan_cells(row, formatter("ru"))
    assert en[1:8] == ["97.6° (least length)", "115", "6,217", "834", "167", "4",
                       "1.44–2.24"]
    assert ru[1:8] == ["97,6° (мин. длина)", "115", "6\u00a0217", "834", "167", "4",
                       "1,44–2,24"]
    assert en[-1] == "meets every constraint (recommended)"
    assert ru[-1] == "все условия выполнены (рекомендуемый)"
    guess = Row("block", row.values, flags=frozenset({"estimate"}), fields={})
    assert plan_cells(guess, formatter("en"))[3] == "≈6,217"
    assert plan_head(formatter("ru"))[0] == "Режим"
    assert plan_head(formatter("en"), terminal=True)[2] == "m"
