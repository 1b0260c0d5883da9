"""The constraint registry: a new constraint is one record plus one function, and it flows
into both engines, ``scan --json``, ``uav --json``, the terminal tables, the workbook and
the PDF. Also runs the doctest examples of the rules engine's modules."""

from __future__ import annotations

import doctest
import io
import json

import numpy as np
import openpyxl
import pytest
from click.testing import CliRunner

from scanplan.cli.main import main
from scanplan.i18n.messages import MESSAGES, Message
from scanplan.project.jobs import scan_job, uav_job
from scanplan.reports import ReportMeta
from scanplan.reports.excel import render_xlsx
from scanplan.rules import constraints, film, registry, results, uav
from scanplan.rules.registry import CONSTRAINTS, Constraint, DigitalLimit, FilmArgs

DUMMY_GROUND_M = 0.01
"""The dummy's limit on the ground: 1 cm, finer than every real limit of the settings below,
so the dummy binds both the film plan (1 µm at 1:10000) and the UAV flight."""


def _dummy_pixel(rules: results.ScanRules, a: FilmArgs) -> np.ndarray:
    return DUMMY_GROUND_M * 1e6 / np.asarray(a.photo_scale, dtype=np.float64)


def _dummy_ground(inp: results.UavInputs, rules: results.ScanRules | None) -> DigitalLimit:
    return DigitalLimit(DUMMY_GROUND_M, Message("limit.QX", g=DUMMY_GROUND_M * 100), {})


@pytest.fixture()
def dummy(monkeypatch):
    """Register constraint QX (texts in the message catalogue, as a real one would have),
    then unregister it."""
    for key, en, ru in (
            ("protects.QX", "the dummy property", "пробное свойство"),
            ("equation.QX", "P_QX = g/Mc (test)", "P_QX = g/Mc (тест)"),
            ("reason.QX", "the dummy limit", "пробный предел"),
            ("limit.QX", "GSD ≤ {g:g} cm (dummy)", "GSD ≤ {g:g} см (пробный)")):
        monkeypatch.setitem(MESSAGES, key, {"en": en, "ru": ru})
    record = registry.register(Constraint(
        "QX", "dummy limit", "пробное условие", Message("protects.QX"),
        Message("equation.QX"), True, "GSD", film_pixel_um=_dummy_pixel,
        film_reason=lambda inp, rules: Message("reason.QX"), ground_limit=_dummy_ground,
        norm_switch=False, needs_map=False))
    yield record
    registry.unregister("QX")
    assert "QX" not in CONSTRAINTS


SCAN = ["scan", "--map-scale", "2000", "--relief", "0.5", "--photo-scale", "10000",
        "--camera", "rc30-153"]
UAV = ["uav", "--camera", "canon-eos-5d-mark-ii-50", "--f-number", "8", "--height-m", "300",
       "--map-scale", "2000", "--relief", "0.5"]


def test_dummy_constraint_flows_into_json_and_terminal(dummy):
    r = CliRunner().invoke(main, [*SCAN, "--json"])
    assert r.exit_code == 0, r.output
    scen = json.loads(r.stdout)["scenarios"][0]
    assert scen["binding"] == "QX"
    assert scen["constraints"]["QX"]["pixel_um"] == pytest.approx(1.0)
    assert scen["constraints"]["QX"]["name"] == "dummy limit"
    assert set(scen["constraints"]) == {"PS", "PZ", "PP", "PR", "PD", "QX"}
    r = CliRunner().invoke(main, SCAN)
    assert r.exit_code == 0, r.output
    assert "QX  dummy limit" in r.stdout

    r = CliRunner().invoke(main, [*UAV, "--json"])
    assert r.exit_code == 0, r.output
    doc = json.loads(r.stdout)
    assert doc["binding"] == "QX"
    # a 1 cm GSD with the camera's 6.41 µm pixel behind 50 mm: H = g·f/p = 78 m
    pixel_mm = doc["inputs"]["pixel_um"] / 1000
    assert doc["max_height_m"] == pytest.approx(DUMMY_GROUND_M * 50 / pixel_mm, rel=1e-9)
    assert doc["max_height_m"] == pytest.approx(78.0, abs=0.05)
    r = CliRunner().invoke(main, UAV)
    assert r.exit_code == 0, r.output
    assert "QX" in r.stdout


def test_dummy_constraint_flows_into_the_workbook_and_pdf(dummy):
    scan = scan_job(map_scale=2000, relief_interval_m=0.5, photo_scales=[10000, 15000],
                    camera="rc30-153")
    flight = uav_job(camera="canon-eos-5d-mark-ii-50", f_number=8, height_m=300,
                     map_scale=2000, relief_interval_m=0.5)
    assert flight.plan.binding == "QX"
    wb = openpyxl.load_workbook(io.BytesIO(render_xlsx(
        scan=scan, uav=flight, meta=ReportMeta(project="Dummy"))))
    cells = {str(c.value) for ws in wb.worksheets for row in ws.iter_rows() for c in row
             if c.value is not None}
    assert "QX" in cells and "dummy limit" in cells
    pypdf = pytest.importorskip("pypdf")
    pytest.importorskip("weasyprint")
    from scanplan.reports.pdf import render_pdf
    for locale, name in (("en", "dummy limit"), ("ru", "пробное условие")):
        data = render_pdf(scan=scan, uav=flight, meta=ReportMeta(project="Dummy", locale=locale))
        text = " ".join(p.extract_text() for p in pypdf.PdfReader(io.BytesIO(data)).pages)
        assert "QX" in text and name in " ".join(text.split())


def test_without_the_dummy_nothing_changed():
    """After unregistering, the real constraints alone (the registry is as shipped)."""
    assert list(CONSTRAINTS) == ["PS", "PZ", "PP", "PR", "PD", "GL", "GSD", "HC"]
    assert [c.id for c in CONSTRAINTS.values() if "film" in c.workflows] == [
        "PS", "PZ", "PP", "PR", "PD"]
    assert [c.id for c in CONSTRAINTS.values() if "digital" in c.workflows] == [
        "PS", "PZ", "PP", "PD", "GL", "GSD", "HC"]


def test_norm_schema_allows_exactly_the_norm_switched_constraints():
    """A norm file may list the ids of the records the norm set switches on, no other."""
    from scanplan.norms.schema import CONSTRAINT_IDS
    assert set(CONSTRAINT_IDS) == {c.id for c in CONSTRAINTS.values() if c.norm_switch}


def test_unknown_norm_id_is_refused():
    with pytest.raises(ValueError, match="unknown constraint 'XX'"):
        registry.film_ids(("PS", "XX"))


@pytest.mark.parametrize("module", [registry, constraints, film, uav, results])
def test_doctests(module):
    failures, _ = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
    assert failures == 0
