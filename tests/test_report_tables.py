"""The report tables (scanplan/reports/views/): built once per result from the plan objects,
locale-free, and laid out alike by the terminal, the workbook, the PDF and the notebook."""

from __future__ import annotations

import ast
import io
import math
from pathlib import Path

import openpyxl
import pytest

import scanplan
from scanplan.i18n.numbers import Numbers
from scanplan.reports.excel import render_xlsx
from scanplan.reports.pdfhtml import render_html
from scanplan.reports.text import format_plan_result
from scanplan.reports.view import build_view
from scanplan.reports.views import ResultTables, constraint_title
from scanplan.rules.registry import CONSTRAINTS

ROOT = Path(__file__).resolve().parent.parent
VIEWS = ROOT / "scanplan" / "reports" / "views"

BOTH = {"project": {"name": "Film or UAV", "locale": "en"},
        "map": {"scale": 1000, "relief_interval_m": 0.5},
        "film": {"camera": "rc30-153", "photo_scales": [3000, 4000, 5000]},
        "uav": {"camera": "dji-zenmuse-p1-35"},
        "area": {"width_m": 800, "length_m": 1200}}


@pytest.fixture(scope="module")
def both():
    return scanplan.plan(BOTH).spec


@pytest.fixture(scope="module")
def film():
    return scanplan.plan(ROOT / "examples" / "instruction-2000-film.toml").spec


@pytest.fixture(scope="module")
def uav():
    return scanplan.plan(ROOT / "examples" / "uav-town-2000.toml").spec


def test_the_film_table_holds_the_plan_numbers(film):
    """instruction-2000-film: one column per candidate photo scale, one row per constraint
    with its scan pixel, the binding one flagged in each column, then the results."""
    plan = film.film.job.plan
    t = ResultTables(scan=plan)["film_constraints"]
    assert [c.value for c in t.columns] == [s.photo_scale for s in plan.scenarios]
    assert t.keys()[0] == "photo_to_map"
    assert t.keys()[1:1 + len(plan.constraint_ids)] == list(plan.constraint_ids)
    assert {"binding", "scan_pixel_um", "frame_megabytes",
            "resolution_on_ground"} <= set(t.keys())
    for i, s in enumerate(plan.scenarios):
        binding = [r.key for r in t.rows if r.flagged(i, "binding")]
        assert binding == [s.binding]
        assert t.row("binding").values[i] == s.binding
        assert t.row("scan_pixel_um").values[i] == s.scan_pixel_um
        for cid in plan.constraint_ids:
            assert t.row(cid).values[i] == s.constraint(cid).pixel_um
            assert (t.row(cid).margins[i] is None) == s.constraint(cid).binding
    assert "emph" in t.row("scan_pixel_um").flags and t.row("scan_pixel_um").digits == 1


def test_the_uav_tables_hold_the_plan_numbers(uav):
    """uav-town-2000 (height tolerance 10 %): results at the planned and the highest
    flown height; the limits lowest first, exactly one binding."""
    plan = uav.uav.job.plan
    tables = ResultTables(uav=plan)
    results = tables["uav_results"]
    assert [c.value for c in results.columns] == [plan.heights_m["planned"],
                                                  plan.heights_m["max"]]
    assert results.row("gsd_m").values == (plan.gsd_m, plan.gsd_at_max_height_m)
    assert results.row("resolving_power").value == (plan.resolving_power_lpmm,
                                                    plan.resolving_power_corner_lpmm)
    limits = tables["uav_limits"]
    heights = [r.values[2] for r in limits.rows]
    assert heights == sorted(heights) and len(heights) == len(plan.limits)
    assert [r.key for r in limits.rows if "binding" in r.flags] == [plan.binding]


def test_the_comparison_and_the_warnings_tables(both):
    t = ResultTables(spec=both)["comparison"]
    assert [r.key for r in t.rows] == [c["key"] for c in both.comparison]
    assert [r.values for r in t.rows] == [(c["film"], c["uav"]) for c in both.comparison]
    assert t.row("frames").digits == 0 and t.row("ground_pixel").digits == 3
    tables = ResultTables.of_jobs(both.film.job, both.uav.job, both)
    every = tables["warnings"]
    sections = [r.fields["section"] for r in every.rows]
    assert sections == sorted(sections, key=["film", "uav", "spec"].index)
    stated = {r.key for r in every.rows if r.fields["section"] != "spec"}
    assert not stated & {r.key for r in every.rows if r.fields["section"] == "spec"}
    assert {r.key for r in every.rows} == {w.code for w in both.warnings} | stated


def test_the_same_table_reads_alike_in_the_terminal_the_workbook_and_the_pdf(both):
    """One view: its tables are built once, however many documents lay them out; the
    comparison's values are the same numbers in the workbook's cells, the PDF and the
    terminal summary."""
    view = build_view(scan=both.film.job, uav=both.uav.job, meta=both.meta, spec=both)
    book = openpyxl.load_workbook(io.BytesIO(render_xlsx(view=view)))
    html = render_html(view=view)
    text = format_plan_result(both, tables=view.tables)
    built = view.tables.built
    assert len(built) == len(set(built))
    assert {"comparison", "film_constraints", "uav_results", "uav_limits",
            "warnings"} <= set(built)
    numbers = Numbers("en")
    summary = {row[0]: row[1:3] for row in book["Summary"].iter_rows(values_only=True)}
    for r in view.tables["comparison"].rows:
        label = view.fmt.row_label(r)
        assert summary[label] == pytest.approx(tuple("—" if v is None else v
                                                     for v in r.values)), r.key
        for v in (v for v in r.values if v is not None):
            shown = numbers.num(v, r.digits)
            assert shown in html and shown in text, (r.key, shown)
    film = view.tables["film_constraints"]
    sheet = {(row[0], row[2]): row[4] for row in book["Constraints"].iter_rows(
        min_row=2, values_only=True)}
    for r in film.rows:
        if "constraint" in r.flags:  # every scan pixel of the film table: PDF and workbook
            assert all(numbers.num(v, 1) in html for v in r.values if math.isfinite(v))
            assert [sheet[(c.value, r.key)] for c in film.columns] == pytest.approx(r.values)


def test_the_notebook_lays_out_the_tables():
    r = scanplan.scan(map_scale=2000, relief_interval_m=1.0, photo_scales=[8000, 10000],
                      camera="rc30-153")
    shown = r._repr_html_()
    assert "1:8000" in shown and "PR — resolving power of the photo" in shown
    assert "<b>12.5</b>" in shown  # the binding constraint's scan pixel


def test_constraint_names_come_from_the_registry():
    for cid, rec in CONSTRAINTS.items():
        assert constraint_title(cid, "en") == rec.name
        assert constraint_title(cid, "ru") == rec.name_ru
    assert constraint_title("XX", "ru", "custom") == "custom"


def test_the_views_import_no_renderer_and_no_labels():
    """The tables know no language and no layout: scanplan/reports/views/ imports nothing
    of reports/ outside itself (labels, view, text, excel, pdf …)."""
    for path in VIEWS.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom) and node.level:
                assert node.level == 1 or (node.level == 3 and node.module
                                           and not node.module.startswith("reports")), \
                    f"{path.name}:{node.lineno} imports {'.' * node.level}{node.module}"


def test_the_headline_tables_hold_the_specification(both):
    """``spec_film`` / ``spec_uav``: what the specification chose, built from the
    ``PlanResult`` once, laid out by the terminal summary, the PDF and the workbook."""
    tables = ResultTables.of_jobs(both.film.job, both.uav.job, both)
    assert tables.has("spec_film") and tables.has("spec_uav")
    film, rec = tables["spec_film"], both.film.recommended
    assert film.row("photo_scale").value == rec.photo_scale
    assert film.row("scan_pixel_um").value == rec.scan_pixel_um
    assert film.row("binding").value == rec.binding and "constraint" in film.row(
        "binding").flags
    assert film.row("frames").value == both.film.frames
    assert film.row("reason").value is both.film.reason
    uav, p = tables["spec_uav"], both.uav.job.plan
    assert uav.row("recommended_height_m").value == both.uav.recommended_height_m
    assert uav.row("gsd_cm").value == pytest.approx(p.gsd_m * 100)
    assert uav.row("photos").value == p.flight["photos"]
    assert uav.keys()[-1] == "reason"
    assert not ResultTables(scan=both.film.job.plan).has("spec_film")
    view = build_view(scan=both.film.job, uav=both.uav.job, meta=both.meta, spec=both,
                      tables=tables)
    assert view.tables is tables
    html = render_html(view=view)
    book = openpyxl.load_workbook(io.BytesIO(render_xlsx(view=view)))
    text = format_plan_result(both, tables=tables)
    assert tables.built.count("spec_film") == 1 and tables.built.count("spec_uav") == 1
    summary = {row[0]: row[1] for row in book["Summary"].iter_rows(values_only=True)}
    assert summary[view.fmt("spec_recommended_height_m")] == uav.row(
        "recommended_height_m").value
    numbers = Numbers("en")
    for shown in (numbers.num(film.row("scan_pixel_um").value, 1),
                  numbers.num(uav.row("recommended_height_m").value, 0)):
        assert shown in html and shown in text


def test_a_views_tables_are_its_results_only(both, film):
    """Tables handed to a view must be of that result."""
    other = ResultTables.of_jobs(film.film.job, None, film)
    with pytest.raises(ValueError, match="not this result"):
        build_view(scan=both.film.job, uav=both.uav.job, spec=both, tables=other)


def test_plan_lays_out_one_view_in_the_terminal_and_the_documents(tmp_path, monkeypatch):
    """``scanplan plan --out``: the terminal summary and the documents lay out one
    ``ResultTables``, each table built once."""
    from click.testing import CliRunner

    import scanplan.reports.text as text_mod
    import scanplan.reports.view as view_mod
    from scanplan.cli.main import main

    monkeypatch.setenv("SCANPLAN_NO_FORK", "1")
    seen: dict[str, object] = {}
    real_view, real_text = view_mod.build_view, text_mod.format_plan_result

    def build_view_spy(**kw):
        view = real_view(**kw)
        seen["view"] = view.tables
        return view

    def format_spy(result, locale=None, tables=None):
        seen["text"] = tables
        return real_text(result, locale, tables)

    monkeypatch.setattr(view_mod, "build_view", build_view_spy)
    monkeypatch.setattr(text_mod, "format_plan_result", format_spy)
    project = tmp_path / "p.toml"
    project.write_text(_toml(BOTH), encoding="utf-8")
    r = CliRunner().invoke(main, ["plan", str(project), "--xlsx", str(tmp_path / "p.xlsx")])
    assert r.exit_code == 0, r.output
    tables = seen["text"]
    assert tables is seen["view"] and tables is not None
    assert {"spec_film", "spec_uav", "comparison", "spec_warnings"} <= set(tables.built)
    assert len(tables.built) == len(set(tables.built))


def _toml(data: dict) -> str:
    out = []
    for section, values in data.items():
        out.append(f"[{section}]")
        for k, v in values.items():
            out.append(f"{k} = {v!r}".replace("'", '"'))
    return "\n".join(out) + "\n"


def test_the_film_inputs_carry_the_registry_units_and_decimals(film):
    """``film_inputs``: each number with its input record's unit and decimals; the
    workbook's Inputs sheet formats its cells by them."""
    from scanplan.project.inputs import get

    plan = film.film.job.plan
    view = build_view(scan=film.film.job, meta=film.meta, spec=film)
    t = view.tables["film_inputs"]
    for key in ("relief_interval_m", "focal_mm", "probability", "pr_coefficient", "bands"):
        assert t.row(key).digits == get(key, "film").digits
        assert t.row(key).unit == get(key, "film").unit
    assert t.row("map_scale").unit == "scale" and t.row("map_scale").value == \
        plan.inputs.map_scale
    assert t.row("photo_scales").value == tuple(plan.inputs.photo_scales)
    sheet = openpyxl.load_workbook(io.BytesIO(render_xlsx(view=view)))["Inputs"]
    cells = {row[0].value: row[1] for row in sheet.iter_rows() if row[0].value}
    relief = cells[view.fmt("relief_interval_m")]
    # the decimals the row declares, thousands grouped (one rule with the documents' text)
    assert relief.value == plan.inputs.relief_interval_m and relief.number_format == "#,##0.00"
    assert cells[view.fmt("bands")].number_format == "#,##0"
    assert view.tables.built.count("film_inputs") == 1
